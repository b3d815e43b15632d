//! The config a lab starts on (`fuzzymotiv lab --config FILE`): read and checked at start as
//! `fuzzymotiv run` reads it, and what the page opens on (its `start` in `/api/info`): the
//! config's motivations as sliders, its rooms chosen (room files listed beside the built-in
//! ones), its robot if built in, the settings the lab's form has, and the keys it sets that
//! the lab cannot.

use std::path::Path;

use fuzzymotiv::experiment::RawConfig;
use fuzzymotiv::simulation::{RobotSpec, Room};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::inputs::load_config;
use serde_json::{Value, json};

use crate::motivations;
use crate::robots::DEFAULT_ROBOT;
use crate::rooms::RoomView;
use crate::settings::Settings;

/// A checked start config.
pub struct StartConfig {
    /// The file as given on the command line.
    file: String,
    /// The settings the page's form starts from.
    settings: Settings,
    /// The sliders: `{name, weight, term, spec}` per motivation.
    motivations: Vec<Value>,
    /// Its rooms, in its order (room files under their absolute paths).
    rooms: Vec<RoomView>,
    /// Dotted keys whose values the lab's settings cannot give.
    not_set: Vec<String>,
}

impl StartConfig {
    /// Reads `path` as `fuzzymotiv run` does (rooms relative to it, every field checked), then
    /// the lab's own checks (terms it knows, its size limits); each error names the file and
    /// the field (exit 2).
    pub fn load(path: &Path) -> Result<StartConfig, CliError> {
        let file = path.display().to_string();
        let loaded = load_config(Some(path), &[], None)?;
        let raw = &loaded.raw;
        let input = |e: crate::errors::ApiError| CliError::input(e.message);
        let motivations = motivations::listed(&raw.motivations, &file).map_err(input)?;
        let settings = settings_of(raw);
        settings.check_limits(&file).map_err(input)?;
        let rooms = (raw.rooms.iter())
            .zip(loaded.experiment.arenas())
            .map(|(entry, arena)| RoomView {
                entry: entry.clone(),
                builtin: Room::builtin(entry).is_some(),
                config: true,
                room: arena.room().clone(),
            })
            .collect();
        let not_set = not_set(raw, &settings, &file)?;
        Ok(StartConfig {
            file,
            settings,
            motivations,
            rooms,
            not_set,
        })
    }

    /// The room files a run of the lab may name (absolute paths, as resolved).
    pub fn room_files(&self) -> Vec<String> {
        (self.rooms.iter())
            .filter(|r| !r.builtin)
            .map(|r| r.entry.clone())
            .collect()
    }

    /// Its room files as the room list shows them (built-in rooms are listed anyway).
    pub fn room_views(&self) -> impl Iterator<Item = &RoomView> {
        self.rooms.iter().filter(|r| !r.builtin)
    }

    /// The `start` object of `/api/info`: the file, the form's `settings` (the motivations
    /// apart, in their order, as `motivations`) and the keys the lab cannot set (`not_set`).
    pub fn view(&self) -> Value {
        let mut settings = json!(self.settings);
        if let Some(s) = settings.as_object_mut() {
            s.remove("motivations");
        }
        json!({ "config": self.file, "settings": settings,
                "motivations": self.motivations, "not_set": self.not_set })
    }
}

/// What the lab's form can hold of `raw`.
fn settings_of(raw: &RawConfig) -> Settings {
    let motion = serde_json::to_value(raw.robot.motion)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string));
    // A robot file by path is not the lab's to run: the page's robot is then the default,
    // and `robot.file` is among the keys it cannot set.
    let robot = raw.robot.file.as_deref().unwrap_or(DEFAULT_ROBOT);
    Settings {
        name: raw.name.clone(),
        seed: raw.seed,
        motivations: raw.motivations.clone(),
        population: raw.ga.population,
        generations: raw.ga.generations,
        robot: RobotSpec::builtin(robot).map(|_| robot.to_string()),
        motion,
        steps: Some(raw.trial.steps),
        rooms: Some(raw.rooms.clone()),
        recognition: Some(raw.aem.enabled),
        combine: serde_json::to_value(raw.fitness.combine)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string)),
    }
}

/// The dotted keys where `raw` (resolved) differs from the config the lab writes of
/// `settings`, resolved as a run resolves it (what its robot file gives the robot and the
/// trial written out).
fn not_set(raw: &RawConfig, settings: &Settings, file: &str) -> Result<Vec<String>, CliError> {
    let mut lab = RawConfig::parse(&settings.document(), file, &[])?;
    let robot = settings.robot.as_deref().unwrap_or(DEFAULT_ROBOT);
    let spec = RobotSpec::builtin(robot).unwrap_or_else(RobotSpec::khepera);
    lab.robot = lab.robot.resolved(spec);
    lab.trial = lab.trial.resolved(spec);
    let table = |c: &RawConfig| toml::from_str::<toml::Table>(&c.to_toml()).unwrap_or_default();
    let mut keys = Vec::new();
    differences("", &table(raw), &table(&lab), &mut keys);
    Ok(keys)
}

/// Appends to `out` the dotted keys (under `prefix`) whose values differ between `a` and `b`.
fn differences(prefix: &str, a: &toml::Table, b: &toml::Table, out: &mut Vec<String>) {
    let mut names: Vec<&String> = a.keys().chain(b.keys()).collect();
    names.sort();
    names.dedup();
    for name in names {
        let key = format!("{prefix}{name}");
        match (a.get(name), b.get(name)) {
            (Some(toml::Value::Table(x)), Some(toml::Value::Table(y))) => {
                differences(&format!("{key}."), x, y, out);
            }
            (x, y) if x != y => out.push(key),
            _ => {}
        }
    }
}
