//! Reading user input: config files with `--set` overrides, and room files.

use std::path::{Path, PathBuf};

use fuzzymotiv::config::{ConfigError, RawConfig};
use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::fuzzy::Motivations;
use fuzzymotiv::room::{BUILTIN_ROOMS, Room};

use crate::error::CliError;
use crate::note;

/// Reads and validates a room file.
pub fn load_room_file(path: &Path) -> Result<Room, CliError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::input(format!("{}: cannot read room file: {e}", path.display())))?;
    if let Err(e) = toml::from_str::<toml::Table>(&text) {
        return Err(CliError::input(format!(
            "{}: not valid TOML{}: {}",
            path.display(),
            fuzzymotiv::config::at_line(&text, e.span()),
            e.message().trim()
        )));
    }
    Ok(Room::from_toml_str(&text, &path.display().to_string())?)
}

/// A config ready to run: the raw document (room paths made absolute) and the experiment.
pub struct Loaded {
    /// The resolved document, as written to `config.resolved.toml`.
    pub raw: RawConfig,
    /// The validated experiment.
    pub experiment: Experiment,
}

/// Loads rooms named in `raw.rooms`: built-in names, or room files relative to `base_dir`.
pub fn resolve(mut raw: RawConfig, base_dir: &Path, source: &str) -> Result<Loaded, CliError> {
    let mut rooms = Vec::with_capacity(raw.rooms.len());
    for (i, entry) in raw.rooms.clone().iter().enumerate() {
        if let Some(r) = Room::builtin(entry) {
            rooms.push(r);
            continue;
        }
        let path = base_dir.join(entry);
        if !path.is_file() {
            return Err(ConfigError {
                source_name: source.to_string(),
                field: format!("rooms[{i}]"),
                reason: format!(
                    "\"{entry}\" is neither a built-in room ({}) nor a room file (looked for {})",
                    BUILTIN_ROOMS.join(", "),
                    path.display()
                ),
            }
            .into());
        }
        rooms.push(load_room_file(&path)?);
        let abs: PathBuf = path.canonicalize().unwrap_or(path);
        raw.rooms[i] = abs.display().to_string();
    }
    normalise_motivations(&mut raw, source);
    let experiment = Experiment::new(&raw, rooms, source)?;
    Ok(Loaded { raw, experiment })
}

/// docs/model.md §8: motivations summing to within 1e-3 of 1 are normalised (the resolved config records
/// the normalised values), and the program says so once; farther off is left to validation.
fn normalise_motivations(raw: &mut RawConfig, source: &str) {
    static SAID: std::sync::Once = std::sync::Once::new();
    let m = raw.motivations;
    if let Ok((n, Some(sum))) =
        Motivations::normalised(m.curiosity, m.homing, m.orientation, m.energy)
    {
        raw.motivations.curiosity = n.curiosity();
        raw.motivations.homing = n.homing();
        raw.motivations.orientation = n.orientation();
        raw.motivations.energy = n.energy();
        SAID.call_once(|| {
            note!(
                "note: {source}: motivations summed to {sum}, normalised to (C, H, O, E) = {:?}",
                n.as_array()
            );
        });
    }
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
            let text = std::fs::read_to_string(p).map_err(|e| {
                CliError::input(format!("{}: cannot read config file: {e}", p.display()))
            })?;
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
    resolve(raw, &base, &source)
}

/// The largest seed: 2^53 − 1, so every seed is exact in JSON for tools that read numbers as
/// doubles (JavaScript, jq).
pub const MAX_SEED: u64 = fuzzymotiv::config::MAX_SEED;

/// Parses `--seed`: a whole number from 0 to 2^53 − 1, with a plain message otherwise.
pub fn parse_seed(text: &str) -> Result<u64, String> {
    text.trim()
        .parse::<u64>()
        .ok()
        .filter(|&s| s <= MAX_SEED)
        .ok_or_else(|| {
            format!(
                "`{text}` is not a seed; a seed is a whole number from 0 to {MAX_SEED} (2^53 − 1)"
            )
        })
}

/// The contents of `config.resolved.toml`: the resolved config with the program version on top.
pub fn resolved_toml(raw: &RawConfig) -> String {
    format!(
        "# Resolved configuration written by fuzzymotiv {} (all keys, with the seed).\n# Re-run: fuzzymotiv run config.resolved.toml\n{}",
        fuzzymotiv::VERSION,
        raw.to_toml()
    )
}

/// What makes an output directory "the same run": its `config.resolved.toml` holds exactly
/// [`resolved_toml`] of the config (the identity [`crate::files::check_out`] compares).
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
            .map_err(|e| crate::files::io_err(path, e))?;
        Ok(abs.display().to_string())
    } else {
        Err(CliError::input(format!(
            "{option} {want}: not a room of the config ({}), a built-in room ({}) or a room file",
            names.join(", "),
            BUILTIN_ROOMS.join(", ")
        )))
    }
}
