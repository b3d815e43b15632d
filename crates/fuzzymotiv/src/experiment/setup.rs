//! The experiment's entry: a raw config and where its room files come from → the validated
//! [`Experiment`], the config as resolved (room files named as found, motivations normalised)
//! and the notes a front end should show. The library reads no files: a front end passes a
//! [`RoomFiles`] that does (the CLI reads them relative to the config file).
//!
//! ```
//! use fuzzymotiv::experiment::RawConfig;
//! use fuzzymotiv::experiment::{BuiltinRoomsOnly, Setup};
//!
//! let sets = ["motivations.curiosity=0.8".to_string(), "motivations.homing=0.1001".to_string()];
//! let raw = RawConfig::parse("rooms = [\"H\", \"square\"]", "example", &sets).unwrap();
//! let setup = Setup::resolve(raw, "example", &BuiltinRoomsOnly).unwrap();
//! assert_eq!(setup.experiment.room_names(), ["H", "square"]);
//! // The sum 1.0001 is within 0.001 of 1: normalised, and the notes say so.
//! assert!(setup.notes[0].contains("normalised"));
//! assert!((setup.experiment.motivations().as_array().iter().sum::<f64>() - 1.0).abs() < 1e-12);
//! ```

use std::sync::Arc;

use crate::experiment::config::{RawConfig, line_column};
use crate::experiment::{Experiment, ReadFiles};
use crate::fitness::{PAPER_MOTIVATIONS, RawMotivations};
use crate::params::FieldError;
use crate::simulation::robot_spec::{BUILTIN_ROBOTS, RobotSpec};
use crate::simulation::room::{BUILTIN_ROOMS, Room};
use crate::simulation::sensor_table::{SensorScale, SensorTable};

/// A room file as a front end found it.
#[derive(Debug, Clone, PartialEq)]
pub struct RoomFile {
    /// The file's text (TOML, docs/model.md §4).
    pub text: String,
    /// The name its errors give it (usually the path).
    pub source_name: String,
    /// The config entry to record in the resolved config (e.g. the absolute path), so that
    /// the resolved config finds the same file from anywhere.
    pub entry: String,
}

/// Where the room entries of a config that are not built-in names come from.
pub trait RoomFiles {
    /// The room file that the config entry `entry` names, or `None` when there is no such file;
    /// `Err` (the front's own error, naming the file) when it exists but cannot be read.
    fn find(&self, entry: &str) -> Result<Option<RoomFile>, UnreadableFile>;

    /// Where `entry` was looked for, for the error when [`RoomFiles::find`] found nothing.
    fn looked_for(&self, entry: &str) -> String;

    /// The sensor table file `trial.sensor_table` names (found as room files are, by default).
    fn find_sensor_table(&self, entry: &str) -> Result<Option<RoomFile>, UnreadableFile> {
        self.find(entry)
    }

    /// The robot file `robot.file` names when it is not a built-in robot (found as room files
    /// are, by default).
    fn find_robot(&self, entry: &str) -> Result<Option<RoomFile>, UnreadableFile> {
        self.find(entry)
    }
}

/// A file a front found but could not read: the front's own error (which names the file), kept
/// whole so that the front gets it back ([`UnreadableFile::cause`]).
#[derive(Debug, Clone, thiserror::Error)]
#[error("{0}")]
pub struct UnreadableFile(Arc<dyn std::error::Error + Send + Sync>);

impl UnreadableFile {
    /// The file could not be read because of `cause`.
    pub fn new(cause: impl std::error::Error + Send + Sync + 'static) -> UnreadableFile {
        UnreadableFile(Arc::new(cause))
    }

    /// Why the file could not be read: the front's error (downcast it to the front's type).
    pub fn cause(&self) -> &(dyn std::error::Error + Send + Sync + 'static) {
        &*self.0
    }
}

/// The same failure (one error, cloned).
impl PartialEq for UnreadableFile {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// No room files: every room must be a built-in one (`H`, `T`, `L`, `square`, `rectangle`).
#[derive(Debug, Clone, Copy, Default)]
pub struct BuiltinRoomsOnly;

impl RoomFiles for BuiltinRoomsOnly {
    fn find(&self, _entry: &str) -> Result<Option<RoomFile>, UnreadableFile> {
        Ok(None)
    }

    fn looked_for(&self, entry: &str) -> String {
        format!("no file: only built-in rooms are read here, {entry} is none of them")
    }
}

/// What keeps a config from becoming an experiment.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SetupError {
    /// A value of the config or of a room file: the source, the field, what is wrong.
    #[error(transparent)]
    Field(#[from] FieldError),
    /// A room, robot or sensor table file that is not TOML: the file, where and TOML's words.
    #[error("{source_name}: not valid TOML{}: {message}", at_line_column(*.at))]
    NotToml {
        /// The file's name (usually its path).
        source_name: String,
        /// The line and column (from 1) where TOML stopped, if it said.
        at: Option<(usize, usize)>,
        /// What TOML said.
        message: String,
    },
    /// A room, robot or sensor table file a front found but could not read.
    #[error(transparent)]
    Unreadable(#[from] UnreadableFile),
}

/// ` (line L, column C)`, or nothing.
fn at_line_column(at: Option<(usize, usize)>) -> String {
    at.map_or(String::new(), |(line, column)| {
        format!(" (line {line}, column {column})")
    })
}

impl SetupError {
    /// The error of `text` (the file `source_name`) that TOML could not read.
    fn not_toml(source_name: &str, text: &str, e: &toml::de::Error) -> SetupError {
        SetupError::NotToml {
            source_name: source_name.to_string(),
            at: line_column(text, e.span()),
            message: e.message().trim().to_string(),
        }
    }
}

/// A config made ready to run.
#[derive(Debug, Clone)]
pub struct Setup {
    /// The config as resolved: room files as [`RoomFile::entry`] names them, motivations
    /// normalised (what a front end records, e.g. `config.resolved.toml`).
    pub raw: RawConfig,
    /// The validated experiment.
    pub experiment: Experiment,
    /// What a front end should tell its user (e.g. that the motivations were normalised).
    pub notes: Vec<String>,
}

impl Setup {
    /// Resolves `raw` (read from `source_name`): built-in rooms by name, other entries through
    /// `files`; motivations summing to within 0.001 of 1 normalised (docs/model.md §8); then
    /// the whole config validated into an [`Experiment`].
    pub fn resolve(
        mut raw: RawConfig,
        source_name: &str,
        files: &dyn RoomFiles,
    ) -> Result<Setup, SetupError> {
        let mut rooms = Vec::with_capacity(raw.rooms.len());
        for (i, entry) in raw.rooms.iter_mut().enumerate() {
            rooms.push(resolve_room(i, entry, source_name, files)?);
        }
        let shared = raw.fuzzy.validated().ok();
        let mut notes: Vec<String> = shared
            .and_then(|shared| raw.motivations.normalise(&shared))
            .map(|sum| normalised_note(source_name, sum, &raw.motivations))
            .into_iter()
            .collect();
        notes.extend(left_out_note(source_name, &raw.motivations));
        let robot = resolve_robot(&mut raw.robot.file, source_name, files)?;
        raw.robot = raw.robot.resolved(robot);
        raw.trial = raw.trial.resolved(robot);
        let scale = robot.scale();
        let table = resolve_sensor_table(&mut raw.trial.sensor_table, source_name, files, scale)?;
        let read = ReadFiles {
            sensor_table: table,
            robot: Some(robot),
        };
        let experiment = Experiment::with_files(&raw, rooms, &[], read, source_name)?;
        Ok(Setup {
            raw,
            experiment,
            notes,
        })
    }
}

/// Room `i` of a config: a built-in room, or the room file `files` finds (its entry then
/// rewritten as the file asks).
fn resolve_room(
    i: usize,
    entry: &mut String,
    source_name: &str,
    files: &dyn RoomFiles,
) -> Result<Room, SetupError> {
    if let Some(room) = Room::builtin(entry) {
        return Ok(room);
    }
    let Some(file) = files.find(entry)? else {
        let reason = format!(
            "\"{entry}\" is neither a built-in room ({}) nor a room file (looked for {})",
            BUILTIN_ROOMS.join(", "),
            files.looked_for(entry)
        );
        return Err(FieldError::new(format!("rooms[{i}]"), reason)
            .in_source(source_name)
            .into());
    };
    let room = parse_room_file(&file.text, &file.source_name)?;
    *entry = file.entry;
    Ok(room)
}

/// The sensor table file a config names (`trial.sensor_table`), read through `files` and
/// checked (errors name the table file and its field), its entry rewritten as the file asks.
fn resolve_sensor_table(
    entry: &mut Option<String>,
    source_name: &str,
    files: &dyn RoomFiles,
    scale: SensorScale,
) -> Result<Option<&'static SensorTable>, SetupError> {
    let Some(name) = entry.as_mut() else {
        return Ok(None);
    };
    let Some(file) = files.find_sensor_table(name)? else {
        let reason = format!(
            "no sensor table file \"{name}\" (looked for {})",
            files.looked_for(name)
        );
        return Err(FieldError::new("trial.sensor_table", reason)
            .in_source(source_name)
            .into());
    };
    check_toml(&file)?;
    let table = SensorTable::from_toml_str_for(&file.text, &file.source_name, scale)?;
    *name = file.entry;
    Ok(Some(table.intern()))
}

/// A TOML syntax error in `file`, naming the file and the line.
fn check_toml(file: &RoomFile) -> Result<(), SetupError> {
    match toml::from_str::<toml::Table>(&file.text) {
        Ok(_) => Ok(()),
        Err(e) => Err(SetupError::not_toml(&file.source_name, &file.text, &e)),
    }
}

/// The robot a config names (`robot.file`): a built-in robot, or the robot file read through
/// `files` and checked (errors name the robot file and its field), its entry rewritten as the
/// file asks; the paper's Khepera when it names none.
fn resolve_robot(
    entry: &mut Option<String>,
    source_name: &str,
    files: &dyn RoomFiles,
) -> Result<&'static RobotSpec, SetupError> {
    let Some(name) = entry.as_mut() else {
        return Ok(RobotSpec::khepera());
    };
    if let Some(robot) = RobotSpec::builtin(name) {
        return Ok(robot);
    }
    let Some(file) = files.find_robot(name)? else {
        let reason = format!(
            "\"{name}\" is neither a built-in robot ({}) nor a robot file (looked for {})",
            BUILTIN_ROBOTS.join(", "),
            files.looked_for(name)
        );
        return Err(FieldError::new("robot.file", reason)
            .in_source(source_name)
            .into());
    };
    check_toml(&file)?;
    let robot = RobotSpec::from_toml_str(&file.text, &file.source_name)?;
    *name = file.entry;
    Ok(robot.intern())
}

/// Parses and validates a room file's text: a TOML syntax error names the line, a wrong or
/// missing value its field (as [`Room::from_toml_str`]).
pub fn parse_room_file(text: &str, source_name: &str) -> Result<Room, SetupError> {
    if let Err(e) = toml::from_str::<toml::Table>(text) {
        return Err(SetupError::not_toml(source_name, text, &e));
    }
    Ok(Room::from_toml_str(text, source_name)?)
}

/// The note of a `[motivations]` that names some of the paper's four but not all
/// ([`RawMotivations::left_out_said`]), naming `source_name`.
fn left_out_note(source_name: &str, m: &RawMotivations) -> Option<String> {
    m.left_out_said()
        .map(|said| format!("{source_name}: {said}"))
}

/// What normalising the motivations did: `(C, H, O, E) = [..]` for the paper's four.
fn normalised_note(source_name: &str, sum: f64, m: &RawMotivations) -> String {
    let paper = m.list.len() == 4
        && m.list
            .iter()
            .zip(PAPER_MOTIVATIONS)
            .all(|((n, _), p)| n == p);
    if paper {
        let x: Vec<f64> = m.list.iter().map(|(_, w)| w.weight()).collect();
        format!("{source_name}: motivations summed to {sum}, normalised to (C, H, O, E) = {x:?}")
    } else {
        let x: Vec<String> = m
            .list
            .iter()
            .map(|(n, w)| format!("{n} = {}", w.weight()))
            .collect();
        format!(
            "{source_name}: motivations summed to {sum}, normalised to {}",
            x.join(", ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct OneFile(&'static str);

    impl RoomFiles for OneFile {
        fn find(&self, entry: &str) -> Result<Option<RoomFile>, UnreadableFile> {
            Ok((entry == "mine.toml").then(|| RoomFile {
                text: self.0.to_string(),
                source_name: "mine.toml".into(),
                entry: "/abs/mine.toml".into(),
            }))
        }

        fn looked_for(&self, entry: &str) -> String {
            format!("/abs/{entry}")
        }
    }

    const BOX: &str = "name = \"box\"\noutline = [[0, 0], [400, 0], [400, 400], [0, 400]]\nhome = { x = 200, y = 200, heading_deg = 0 }\n";

    fn raw(rooms: &str) -> RawConfig {
        RawConfig::parse(&format!("rooms = {rooms}"), "c.toml", &[]).unwrap()
    }

    /// A room file found by the front end is read, and the resolved config names it as asked.
    #[test]
    fn room_files_come_from_the_front_end() {
        let setup = Setup::resolve(raw("[\"H\", \"mine.toml\"]"), "c.toml", &OneFile(BOX)).unwrap();
        assert_eq!(setup.raw.rooms, ["H", "/abs/mine.toml"]);
        assert_eq!(setup.experiment.room_names(), ["H", "box"]);
        assert!(setup.notes.is_empty());
    }

    /// A room that is neither built in nor found names its entry and where it was looked for.
    #[test]
    fn a_missing_room_names_its_entry() {
        let e = Setup::resolve(raw("[\"H\", \"nope.toml\"]"), "c.toml", &OneFile(BOX)).unwrap_err();
        let text = e.to_string();
        assert!(
            text.starts_with("c.toml: field `rooms[1]`: \"nope.toml\" is neither"),
            "{text}"
        );
        assert!(text.contains("looked for /abs/nope.toml"), "{text}");
    }

    /// A room file that is not TOML names its line.
    #[test]
    fn a_broken_room_file_names_its_line() {
        let e =
            Setup::resolve(raw("[\"mine.toml\"]"), "c.toml", &OneFile("name = \n")).unwrap_err();
        assert!(matches!(e, SetupError::NotToml { .. }));
        assert!(
            e.to_string()
                .starts_with("mine.toml: not valid TOML (line 1"),
            "{e}"
        );
    }

    /// A config relying on the earlier fill-in (`curiosity = 0.8` alone, once 0.8/0.1/0/0.1)
    /// is refused for its sum with the reason: a table defines the whole set, and which of
    /// the paper's four it leaves out.
    #[test]
    fn a_sum_error_of_a_table_leaving_out_paper_motivations_says_a_table_defines_the_set() {
        let c = RawConfig::parse("[motivations]\ncuriosity = 0.8\n", "old.toml", &[]).unwrap();
        let Err(SetupError::Field(e)) = Setup::resolve(c, "old.toml", &BuiltinRoomsOnly) else {
            panic!("a sum of 0.8 is refused for a field");
        };
        assert_eq!(
            (e.source_name.as_str(), e.field.as_str()),
            ("old.toml", "motivations")
        );
        assert!(
            e.reason.starts_with("motivations must sum to 1, got 0.8"),
            "{e}"
        );
        assert!(
            e.reason.contains(
                "leaves out `homing`, `orientation` and `energy` of the paper's four, so the \
                 motivations are curiosity alone: a table defines the whole set"
            ),
            "{e}"
        );
        let c = RawConfig::parse("[motivations]\nx = 0.5\n", "new.toml", &[]).unwrap();
        let e = Setup::resolve(c, "new.toml", &BuiltinRoomsOnly).unwrap_err();
        assert!(!e.to_string().contains("paper's four"), "{e}");
    }

    /// A table that leaves out three of the paper's four says to write all three at 0, not
    /// one of them.
    #[test]
    fn the_left_out_note_names_every_paper_motivation_left_out() {
        let c = RawConfig::parse(
            "[motivations]\ncuriosity = 0.7\nurgency = 0.3\n",
            "two.toml",
            &[],
        )
        .unwrap();
        let note = left_out_note("two.toml", &c.motivations).unwrap();
        assert!(
            note.contains(
                "(write `homing = 0.0`, `orientation = 0.0` and `energy = 0.0` to keep the paper's four)"
            ),
            "{note}"
        );
        let c = RawConfig::parse(
            "[motivations]\ncuriosity = 0.8\nhoming = 0.1\norientation = 0.1\n",
            "three.toml",
            &[],
        )
        .unwrap();
        let note = left_out_note("three.toml", &c.motivations).unwrap();
        assert!(
            note.contains("(write `energy = 0.0` to keep the paper's four)"),
            "{note}"
        );
    }

    /// Motivations a little off 1 are normalised (and said); far off is an error.
    #[test]
    fn motivations_are_normalised_once_and_said() {
        let shared = crate::fitness::TskFitness::paper();
        let mut m = RawMotivations::paper([0.3333, 0.3333, 0.0, 0.3333]);
        let sum = m.normalise(&shared).unwrap();
        assert!((sum - 0.9999).abs() < 1e-12);
        let n = m.validated(&shared).unwrap();
        assert_eq!(m.weight_of("curiosity"), Some(n.curiosity()));
        assert_eq!(m.normalise(&shared), None, "already normalised");
        let mut far = RawMotivations::paper([0.5, 0.3333, 0.0, 0.3333]);
        assert_eq!(far.normalise(&shared), None);
        assert_eq!(
            far.weight_of("curiosity"),
            Some(0.5),
            "left for validation to refuse"
        );
    }
}
