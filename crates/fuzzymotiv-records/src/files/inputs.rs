//! Reading user input: config files with `--set` overrides, and room files.

use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::experiment::RawConfig;
use fuzzymotiv::experiment::{
    RoomFile, RoomFiles, Setup, SetupError, UnreadableFile, blame_set, parse_room_file,
};
use fuzzymotiv::simulation::{BUILTIN_ROBOTS, RobotSpec};
use fuzzymotiv::simulation::{BUILTIN_ROOMS, Room};

use crate::files::bounded::{InputKind, read_input};
use crate::files::error::CliError;

/// A config file, read whole (at most [`crate::files::bounded::TEXT_LIMIT`] bytes).
pub const CONFIG: InputKind = InputKind::text("config file");

/// A room file, read whole (at most [`crate::files::bounded::TEXT_LIMIT`] bytes).
pub const ROOM_FILE: InputKind = InputKind::text("room file");

/// A sensor table file (`trial.sensor_table`), read whole (at most
/// [`crate::files::bounded::TEXT_LIMIT`] bytes).
pub const SENSOR_TABLE: InputKind = InputKind::text("sensor table file");

/// A robot file (`robot.file`, `--robot`).
pub const ROBOT_FILE: InputKind = InputKind::text("robot file");

/// Reads and validates a room file.
pub fn load_room_file(path: &Path) -> Result<Room, CliError> {
    let text = read_input(path, ROOM_FILE)?;
    Ok(parse_room_file(&text, &path.display().to_string())?)
}

/// The robot `entry` names (a command-line option `option`): a built-in robot, or a robot
/// file read and checked (errors name the file and its field).
pub fn load_robot(entry: &str, option: &str) -> Result<&'static RobotSpec, CliError> {
    if let Some(robot) = RobotSpec::builtin(entry) {
        return Ok(robot);
    }
    let path = Path::new(entry);
    if !path.is_file() {
        return Err(CliError::input(format!(
            "{option} {entry}: neither a built-in robot ({}) nor a robot file",
            BUILTIN_ROBOTS.join(", ")
        )));
    }
    let text = read_input(path, ROBOT_FILE)?;
    let robot = RobotSpec::from_toml_str(&text, &path.display().to_string())
        .map_err(|e| CliError::Setup(fuzzymotiv::experiment::SetupError::Field(e)))?;
    Ok(robot.intern())
}

/// A config ready to run: the raw document (room paths made absolute) and the experiment.
pub struct Loaded {
    /// The resolved document, as written to `config.resolved.toml`.
    pub raw: RawConfig,
    /// The validated experiment.
    pub experiment: Experiment,
    /// What the front should tell its user (e.g. that the motivations were normalised): the
    /// library's [`Setup::notes`], shown by each front its own way.
    pub notes: Vec<String>,
}

/// Room files of a config (and its robot file and sensor table): paths relative to the config
/// file's folder, recorded absolute; a file that cannot be read is the [`CliError`] of reading
/// it (in [`UnreadableFile::cause`]). The CLI's, Python's and the lab's.
#[derive(Debug, Clone, Copy)]
pub struct RoomDir<'a>(pub &'a Path);

impl RoomDir<'_> {
    /// The file `entry` names (relative to the folder), read as a file of `kind`.
    fn find_as(&self, entry: &str, kind: InputKind) -> Result<Option<RoomFile>, UnreadableFile> {
        let path = self.0.join(entry);
        if !path.is_file() {
            return Ok(None);
        }
        let text = read_input(&path, kind).map_err(UnreadableFile::new)?;
        let source_name = path.display().to_string();
        let abs: PathBuf = path.canonicalize().unwrap_or(path);
        Ok(Some(RoomFile {
            text,
            source_name,
            entry: abs.display().to_string(),
        }))
    }
}

impl RoomFiles for RoomDir<'_> {
    fn find(&self, entry: &str) -> Result<Option<RoomFile>, UnreadableFile> {
        self.find_as(entry, ROOM_FILE)
    }

    fn find_sensor_table(&self, entry: &str) -> Result<Option<RoomFile>, UnreadableFile> {
        self.find_as(entry, SENSOR_TABLE)
    }

    fn find_robot(&self, entry: &str) -> Result<Option<RoomFile>, UnreadableFile> {
        self.find_as(entry, ROBOT_FILE)
    }

    fn looked_for(&self, entry: &str) -> String {
        self.0.join(entry).display().to_string()
    }
}

/// Loads rooms named in `raw.rooms` (built-in names, or room files relative to `base_dir`) and
/// validates the config: the library's [`Setup::resolve`], its notes in [`Loaded::notes`].
pub fn resolve(raw: RawConfig, base_dir: &Path, source: &str) -> Result<Loaded, CliError> {
    let setup = Setup::resolve(raw, source, &RoomDir(base_dir))?;
    Ok(Loaded {
        raw: setup.raw,
        experiment: setup.experiment,
        notes: setup.notes,
    })
}

/// Reads a config file (or the built-in defaults for `None`) with overrides.
pub fn load_config(
    path: Option<&Path>,
    sets: &[String],
    seed: Option<u64>,
) -> Result<Loaded, CliError> {
    let mut sets = sets.to_vec();
    if let Some(s) = seed {
        sets.push(format!("seed={s}"));
    }
    let (text, source, base) = match path {
        Some(p) => {
            let text = read_input(p, CONFIG)?;
            let base = p.parent().map(Path::to_path_buf).unwrap_or_default();
            (text, p.display().to_string(), base)
        }
        None => (
            String::new(),
            "(built-in defaults)".to_string(),
            PathBuf::from("."),
        ),
    };
    let raw = RawConfig::parse(&text, &source, &sets)?;
    // A value of a --set is named as such, not as the file's.
    resolve(raw, &base, &source).map_err(|e| match e {
        CliError::Setup(SetupError::Field(f)) => SetupError::Field(blame_set(f, &sets)).into(),
        e => e,
    })
}

/// The largest number of worker threads (`--threads` of every command, the lab's runs,
/// Python's `threads=`). Results never depend on the number of threads, so threads beyond the
/// machine's cores only cost memory (a stack each) and switching; 256 is at least the hardware
/// threads of the machines this program is meant for (a two-socket server has up to 256),
/// while the thousands a slip of the finger asks for would make the machine unusable. A fixed
/// bound (not a multiple of this machine's cores) keeps the accepted values, and so a command
/// line, the same on every machine.
pub const MAX_THREADS: usize = 256;

/// A value of `--threads` or `--seed` that is not one: what the option takes and what it got,
/// worded as the end of a sentence whose start names the option (`--threads must be a whole
/// number from 1 to 256, got 0`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OptionValueError {
    /// Not a number of worker threads from 1 to [`MAX_THREADS`].
    #[error("must be a whole number from 1 to {MAX_THREADS}, got {got}")]
    Threads {
        /// The value given.
        got: Given,
    },
    /// Not a seed from 0 to [`MAX_SEED`].
    #[error("`{got}` is not a seed; a seed is a whole number from 0 to {MAX_SEED} (2^53 − 1)")]
    Seed {
        /// The text given.
        got: String,
    },
}

/// A value as given: a whole number, or text that is not one (shown in backticks).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Given {
    /// A whole number.
    Number(i128),
    /// Text that is not a whole number.
    Text(String),
}

impl std::fmt::Display for Given {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Given::Number(n) => write!(f, "{n}"),
            Given::Text(t) => write!(f, "`{t}`"),
        }
    }
}

/// `n` as a number of worker threads: from 1 to [`MAX_THREADS`].
pub fn check_threads(n: i128) -> Result<usize, OptionValueError> {
    match usize::try_from(n) {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        _ => Err(OptionValueError::Threads {
            got: Given::Number(n),
        }),
    }
}

/// `--threads N` (a clap value parser): a whole number from 1 to [`MAX_THREADS`], with a
/// message stating the range otherwise.
pub fn parse_threads(text: &str) -> Result<usize, OptionValueError> {
    match text.trim().parse::<i128>() {
        Ok(n) => check_threads(n),
        Err(_) => Err(OptionValueError::Threads {
            got: Given::Text(text.to_string()),
        }),
    }
}

/// The largest seed: 2^53 − 1, so every seed is exact in JSON for tools that read numbers as
/// doubles (JavaScript, jq).
pub const MAX_SEED: u64 = fuzzymotiv::experiment::MAX_SEED;

/// Parses `--seed`: a whole number from 0 to 2^53 − 1, with a plain message otherwise.
pub fn parse_seed(text: &str) -> Result<u64, OptionValueError> {
    text.trim()
        .parse::<u64>()
        .ok()
        .filter(|&s| s <= MAX_SEED)
        .ok_or_else(|| OptionValueError::Seed {
            got: text.to_string(),
        })
}

/// The contents of `config.resolved.toml`: the resolved config with the program and model
/// versions on top (so a build of another model makes another run),
/// and a line per room file with a digest of its contents ([`room_file_lines`]), so that a run
/// made after a room file changed is another run (its identity differs).
pub fn resolved_toml(raw: &RawConfig) -> String {
    format!(
        "# Resolved configuration written by fuzzymotiv {}, model {} (all keys, with the seed).\n# Re-run: fuzzymotiv run config.resolved.toml\n{}{}",
        fuzzymotiv::VERSION,
        fuzzymotiv::MODEL_VERSION,
        room_file_lines(raw).concat(),
        raw.to_toml()
    )
}

/// The comment lines `# Room file PATH: FNV-1a HEX` of the config's room files and
/// `# Robot file PATH: FNV-1a HEX` of its robot file (resolved entries are absolute paths;
/// built-in rooms and robots have none), each ending in a newline.
pub fn room_file_lines(raw: &RawConfig) -> Vec<String> {
    let rooms = (raw.rooms.iter()).map(|entry| ("Room file", entry, ROOM_FILE));
    let robot = (raw.robot.file.iter()).map(|entry| ("Robot file", entry, ROBOT_FILE));
    (rooms.chain(robot))
        .filter(|(_, entry, _)| Path::new(entry).is_absolute())
        .map(
            |(what, entry, kind)| match read_input(Path::new(entry), kind) {
                Ok(text) => format!("# {what} {entry}: FNV-1a {:016x}\n", fnv1a(text.as_bytes())),
                Err(_) => format!("# {what} {entry}: unreadable\n"),
            },
        )
        .collect()
}

/// The room and robot files of the run whose `config.resolved.toml` is `config` still hold
/// what the run used (its `# Room file` and `# Robot file` lines; a run written before they were recorded has none, and is
/// taken as it is); else an error ending in `remedy`.
pub fn rooms_unchanged(config: &Path, loaded: &Loaded, remedy: &str) -> Result<(), CliError> {
    let text = read_input(config, CONFIG)?;
    let saved = saved_room_file_lines(&text);
    let now = room_file_lines(&loaded.raw);
    match saved.iter().find(|l| !now.contains(l)) {
        Some(line) => Err(CliError::input(format!(
            "{}: a {} file changed since the run ({}); {remedy}",
            config.display(),
            if line.starts_with("# Robot") {
                "robot"
            } else {
                "room"
            },
            line.trim_start_matches("# ").trim_end()
        ))),
        None => Ok(()),
    }
}

/// The room-file lines of a saved `config.resolved.toml` text.
fn saved_room_file_lines(text: &str) -> Vec<String> {
    (text.lines())
        .filter(|l| l.starts_with("# Room file ") || l.starts_with("# Robot file "))
        .map(|l| format!("{l}\n"))
        .collect()
}

/// 64-bit FNV-1a of `bytes` (a fingerprint, not a cryptographic hash).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// What makes an output directory "the same run": its `config.resolved.toml` holds exactly
/// [`resolved_toml`] of the config (the identity [`crate::files::guard::check_out`] compares).
pub fn run_identity(raw: &RawConfig) -> Vec<(String, String)> {
    vec![("config.resolved.toml".to_string(), resolved_toml(raw))]
}

/// A room to replay in `loaded`'s setting, as a config entry: a room of the config, a built-in
/// room, or a room file (made absolute). `option` names the choice in the error (`--room`).
pub fn room_entry(option: &str, want: &str, loaded: &Loaded) -> Result<String, CliError> {
    let names = loaded.experiment.room_names();
    if let Some(i) = names.iter().position(|n| n == want) {
        Ok(loaded.raw.rooms[i].clone())
    } else if Room::builtin(want).is_some() {
        Ok(want.to_string())
    } else if Path::new(want).is_file() {
        let path = Path::new(want);
        load_room_file(path)?;
        let abs = path
            .canonicalize()
            .map_err(|e| crate::files::guard::io_err(path, e))?;
        Ok(abs.display().to_string())
    } else {
        Err(CliError::input(format!(
            "{option} {want}: not a room of the config ({}), a built-in room ({}) or a room file",
            names.join(", "),
            BUILTIN_ROOMS.join(", ")
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue #56: a room file the front cannot read reaches the front as its own error, kept
    /// whole through the library ([`UnreadableFile::cause`]), not as a message; bad input.
    #[test]
    fn an_unreadable_room_file_comes_back_as_the_fronts_own_error() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("r.toml"), b"name = \"r\xff\"\n").unwrap();
        let config = dir.path().join("c.toml");
        std::fs::write(&config, "rooms = [\"r.toml\"]\n").unwrap();
        let Err(e) = load_config(Some(&config), &[], None) else {
            panic!("a room file that is not UTF-8 is refused");
        };
        assert!(e.is_input(), "{e:?}");
        let CliError::Setup(SetupError::Unreadable(u)) = &e else {
            panic!("not an unreadable file: {e:?}");
        };
        let cause = u
            .cause()
            .downcast_ref::<CliError>()
            .expect("the front's CliError");
        assert_eq!(cause.to_string(), e.to_string());
        assert!(e.to_string().contains("r.toml"), "{e}");
    }
}
