//! What the page asks a run to be: its settings (JSON) → a config document → the library's
//! checks (`Setup::resolve`, through `fuzzymotiv_pipeline::files::inputs::resolve`), so that every
//! bad value gets the CLI's message naming its field.

use std::path::Path;

use fuzzymotiv::experiment::RawConfig;
use fuzzymotiv::fitness::RawMotivations;
use fuzzymotiv::simulation::Room;
use fuzzymotiv_pipeline::files::inputs::{Loaded, resolve};
use serde::{Deserialize, Serialize};

use crate::errors::ApiError;
use crate::limits::{MAX_GENERATIONS, MAX_POPULATION, MAX_ROOMS, MAX_STEPS};
use crate::rooms::{ROOM_DIR, valid_room_name};

/// The source name of settings in error messages.
pub const SOURCE: &str = "lab settings";

/// A run's settings as the page sends them; every key but the motivations is optional (the
/// config defaults of docs/model.md).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Settings {
    /// The run's name (the config's `name`); default "lab".
    #[serde(default = "default_name")]
    pub name: String,
    /// Base seed; default 1.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// The motivations as a config's `[motivations]` writes them: `name` → weight, or
    /// `name` → `{ weight, term, peaks, coefficients }`; the paper's four
    /// `{ curiosity, homing, orientation, energy }` as before.
    pub motivations: RawMotivations,
    /// GA population (`ga.population`); default 30 (the quick preset).
    #[serde(default = "default_size")]
    pub population: usize,
    /// GA generations (`ga.generations`); default 30.
    #[serde(default = "default_size")]
    pub generations: usize,
    /// The robot (`robot.file`): a built-in robot's name (`khepera`, `epuck2`, `thymio2`);
    /// default the paper's Khepera. Left out of the settings shown when not given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robot: Option<String>,
    /// `robot.motion`: "actions" or "wheels"; default the config's.
    #[serde(default)]
    pub motion: Option<String>,
    /// `trial.steps`; default the config's (1000).
    #[serde(default)]
    pub steps: Option<usize>,
    /// Built-in room names, or rooms saved in the lab (`NAME.toml`); default all five
    /// built-in rooms.
    #[serde(default)]
    pub rooms: Option<Vec<String>>,
    /// `aem.enabled`: room recognition after the evolution (it needs two rooms or more);
    /// default the config's (on).
    #[serde(default)]
    pub recognition: Option<bool>,
    /// `fitness.combine`: how the motivations combine the terms into F, "tsk",
    /// "weighted-sum" or "weighted-squares"; default the config's (the TSK). Left out of the
    /// settings shown when not given, as before it existed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub combine: Option<String>,
}

fn default_name() -> String {
    "lab".into()
}
fn default_seed() -> u64 {
    1
}
fn default_size() -> usize {
    30
}

impl Settings {
    /// The settings as a config document (TOML), read by the CLI's parser.
    pub fn document(&self) -> String {
        use toml::{Table, Value};
        let section = |key: &str, v: Value| Value::Table(Table::from_iter([(key.to_string(), v)]));
        let mut doc = Table::new();
        doc.insert("name".into(), Value::String(self.name.clone()));
        doc.insert(
            "seed".into(),
            Value::Integer(self.seed.min(i64::MAX as u64) as i64),
        );
        if let Some(rooms) = &self.rooms {
            let list = rooms.iter().map(|r| Value::String(r.clone())).collect();
            doc.insert("rooms".into(), Value::Array(list));
        }
        // Serialised as written (a plain weight stays a plain weight), in input order.
        if let Ok(x) = Value::try_from(&self.motivations) {
            doc.insert("motivations".into(), x);
        }
        let mut ga = Table::new();
        ga.insert("population".into(), Value::Integer(self.population as i64));
        ga.insert(
            "generations".into(),
            Value::Integer(self.generations as i64),
        );
        doc.insert("ga".into(), Value::Table(ga));
        if let Some(steps) = self.steps {
            doc.insert(
                "trial".into(),
                section("steps", Value::Integer(steps as i64)),
            );
        }
        if let Some(on) = self.recognition {
            doc.insert("aem".into(), section("enabled", Value::Boolean(on)));
        }
        let mut robot = Table::new();
        if let Some(name) = &self.robot {
            robot.insert("file".into(), Value::String(name.clone()));
        }
        if let Some(motion) = &self.motion {
            robot.insert("motion".into(), Value::String(motion.clone()));
        }
        if !robot.is_empty() {
            doc.insert("robot".into(), Value::Table(robot));
        }
        if let Some(combine) = &self.combine {
            let combine = Value::String(combine.clone());
            doc.insert("fitness".into(), section("combine", combine));
        }
        toml::to_string(&doc).unwrap_or_default()
    }

    /// The lab's own limits (the library accepts larger runs; a shared server does not);
    /// `source` names the settings in the message.
    pub fn check_limits(&self, source: &str) -> Result<(), ApiError> {
        let over = |field: &str, got: usize, max: usize| {
            ApiError::bad(format!(
                "{source}: field `{field}`: {got} is more than the lab allows ({max}; run larger experiments with `fuzzymotiv run`)"
            ))
        };
        if self.population > MAX_POPULATION {
            return Err(over("ga.population", self.population, MAX_POPULATION));
        }
        if self.generations > MAX_GENERATIONS {
            return Err(over("ga.generations", self.generations, MAX_GENERATIONS));
        }
        if let Some(steps) = self.steps.filter(|&s| s > MAX_STEPS) {
            return Err(over("trial.steps", steps, MAX_STEPS));
        }
        let rooms = self.rooms.as_deref().unwrap_or_default();
        if rooms.len() > MAX_ROOMS {
            return Err(over("rooms", rooms.len(), MAX_ROOMS));
        }
        Ok(())
    }

    /// The rooms must be built-in, saved in the lab, or room files of the config the lab
    /// started on (`config_rooms`, absolute paths): no other path reaches outside its directory.
    fn check_rooms(&self, dir: &Path, config_rooms: &[String]) -> Result<(), ApiError> {
        for (i, entry) in self.rooms.iter().flatten().enumerate() {
            if Room::builtin(entry).is_some() || config_rooms.contains(entry) {
                continue;
            }
            let stem = entry.strip_suffix(".toml").unwrap_or("");
            if !valid_room_name(stem) || !dir.join(ROOM_DIR).join(entry).is_file() {
                let config = if config_rooms.is_empty() {
                    ""
                } else {
                    " nor a room file of the config the lab started on"
                };
                return Err(ApiError::bad(format!(
                    "{SOURCE}: field `rooms[{i}]`: `{entry}` is neither a built-in room (H, T, L, square, rectangle) nor a room saved in the lab (NAME.toml, see the room list){config}"
                )));
            }
        }
        Ok(())
    }

    /// Checks the settings and resolves them into a config ready to run (room files from
    /// `DIR/rooms/`, or the start config's `config_rooms`).
    pub fn load(&self, dir: &Path, config_rooms: &[String]) -> Result<Loaded, ApiError> {
        self.check_limits(SOURCE)?;
        if let Some(robot) = &self.robot {
            crate::robots::check(robot, SOURCE)?;
        }
        self.check_rooms(dir, config_rooms)?;
        let raw = RawConfig::parse(&self.document(), SOURCE, &[])
            .map_err(|e| ApiError::bad(e.to_string()))?;
        Ok(resolve(raw, &dir.join(ROOM_DIR), SOURCE)?)
    }
}
