//! Experiment configuration: the raw TOML document (every key has the default of docs/model.md, unknown keys
//! are rejected), `--set key=value` overrides, and validation into [`crate::experiment::Experiment`].
//! Each section's raw struct is declared beside the validated type it turns into (`[trial]` in
//! [`crate::simulation::trial`], `[aem]` in [`crate::modelling::aem`], …) and re-exported here.
//!
//! ```
//! use fuzzymotiv::experiment::RawConfig;
//! let raw = RawConfig::parse("", "empty.toml", &["ga.population=20".to_string()]).unwrap();
//! assert_eq!(raw.ga.population, 20);
//! assert_eq!(raw.trial.steps, 400);
//! ```

use serde::{Deserialize, Serialize};

pub use crate::evolution::ga::RawGa;
use crate::fitness::terms::{Homing, WaypointOrder};
pub use crate::fitness::{Coefficients, RawFuzzy, RawMotivations};
pub use crate::modelling::aem::RawAem;
use crate::params::plain::{Fault, ReadError};
use crate::params::{BIG, FieldError, field_at};
pub use crate::simulation::controller::RawNetwork;
pub use crate::simulation::robot::RawRobot;
use crate::simulation::room::BUILTIN_ROOMS;
pub use crate::simulation::trial::RawTrial;

/// The largest base seed, 2^53 − 1: every seed (and every seed derived from it for a sweep) is
/// then exact as a JSON number, also for tools that read numbers as doubles (JavaScript, jq).
pub const MAX_SEED: u64 = (1 << 53) - 1;

/// How populations are trained over rooms (docs/model.md §10).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Training {
    /// One population per motivation setting; fitness = mean F over all rooms (default).
    #[default]
    AllRooms,
    /// One evolution per room.
    PerRoom,
}

/// Whether the battery term rewards using energy (`b`) or conserving it (`1 − b`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EnergyMode {
    /// Y₄ = b (default: energy is "the opposite of laziness").
    #[default]
    Use,
    /// Y₄ = 1 − b.
    Conserve,
}

/// When the orientation term `l` is measured (docs/model.md §10).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OrientationMode {
    /// Only after evolution, by the SOM test (the paper; default).
    #[default]
    Offline,
    /// During evolution, by two runs per room and 1-NN.
    Online,
}

/// `[fitness]`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawFitness {
    /// `"use"` (default) or `"conserve"`.
    pub energy: EnergyMode,
    /// `"offline"` (default) or `"online"`.
    pub orientation: OrientationMode,
    /// `"escape"` (default) or `"distance"`.
    pub homing: Homing,
    /// How the `waypoints` term counts: `"in-order"` (default) or `"any-order"`.
    #[serde(skip_serializing_if = "is_default")]
    pub waypoints: WaypointOrder,
    /// Whether a trial ends the step its mission is done (as it ends at home); default false.
    #[serde(skip_serializing_if = "is_default")]
    pub end_at_mission: bool,
    /// How the motivations combine the terms into F: `"tsk"` (default, the paper's),
    /// `"weighted-sum"` or `"weighted-squares"` (baselines, docs/model.md §8).
    #[serde(skip_serializing_if = "is_default")]
    pub combine: Combination,
}

/// How the motivations X combine the fuzzy inputs Y into F (docs/model.md §8, "Baselines").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Combination {
    /// The paper's TSK rule base (default).
    #[default]
    Tsk,
    /// `F = Σ X_i·Y_i`: a plain weighted sum of the same motivations.
    WeightedSum,
    /// `F = Σ X_i·Y_i²`: the TSK's value when every input sits on a peak of the default labels.
    WeightedSquares,
}

/// Whether `v` is its type's default (options added later are written only when set, so that
/// the configs of earlier runs read and write back byte for byte).
fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

/// The configuration document as written (every key optional, the defaults of docs/model.md).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawConfig {
    /// Experiment name; default "experiment".
    pub name: String,
    /// Base seed of every random stream; default 1.
    pub seed: u64,
    /// Built-in room names or room-file paths (relative to the config file); default all five.
    pub rooms: Vec<String>,
    /// `"all-rooms"` (default) or `"per-room"`.
    pub training: Training,
    /// Motivations X.
    pub motivations: RawMotivations,
    /// GA parameters.
    pub ga: RawGa,
    /// Trial parameters.
    pub trial: RawTrial,
    /// Robot body.
    pub robot: RawRobot,
    /// Network shape.
    pub network: RawNetwork,
    /// Membership peaks and coefficients.
    pub fuzzy: RawFuzzy,
    /// Fitness options.
    pub fitness: RawFitness,
    /// Environment modelling.
    pub aem: RawAem,
}

impl Default for RawConfig {
    fn default() -> Self {
        Self {
            name: "experiment".into(),
            seed: 1,
            rooms: BUILTIN_ROOMS.iter().map(|s| s.to_string()).collect(),
            training: Training::AllRooms,
            motivations: RawMotivations::default(),
            ga: RawGa::default(),
            trial: RawTrial::default(),
            robot: RawRobot::default(),
            network: RawNetwork::default(),
            fuzzy: RawFuzzy::default(),
            fitness: RawFitness::default(),
            aem: RawAem::default(),
        }
    }
}

impl RawConfig {
    /// Parses a TOML document and applies `key=value` overrides (dotted keys; the value is read
    /// as TOML, and as a plain string if it is not valid TOML).
    pub fn parse(text: &str, source_name: &str, sets: &[String]) -> Result<RawConfig, FieldError> {
        let err = |field: &str, reason: String| FieldError {
            source_name: source_name.to_string(),
            field: field.to_string(),
            reason,
        };
        let mut table: toml::Table = toml::from_str(text).map_err(|e| {
            let msg = e.message().trim();
            err(
                &field_at(text, e.span(), None),
                format!("not valid TOML{}: {msg}", at_line(text, e.span())),
            )
        })?;
        if sets.is_empty() {
            return Self::from_text(text, source_name, true);
        }
        default_motivations_for_sets(&mut table, sets);
        apply_sets(&mut table, sets)?;
        let merged = toml::to_string(&table).map_err(|e| err("(document)", e.to_string()))?;
        let source_name = format!("{source_name} (with --set overrides)");
        Self::from_text(&merged, &source_name, false).map_err(|e| blame_set(e, sets))
    }

    /// Reads the document `text` of `source_name`; `own_text`: whether `text` is the user's
    /// own file (so that line numbers point into it), not a document with overrides merged.
    fn from_text(text: &str, source_name: &str, own_text: bool) -> Result<RawConfig, FieldError> {
        let raw: RawConfig =
            crate::params::plain::from_str(text, whole_number_range).map_err(|e| {
                let at = if own_text {
                    at_line(text, e.span())
                } else {
                    String::new()
                };
                let reason = format!("{}{at}{}", e.message(), room_file_hint(&e));
                FieldError {
                    source_name: source_name.to_string(),
                    field: e.field(text),
                    reason,
                }
            })?;
        if raw.seed > MAX_SEED {
            return Err(FieldError {
                source_name: source_name.to_string(),
                field: "seed".into(),
                reason: format!(
                    "{} is too large; a seed is a whole number from 0 to {MAX_SEED} (2^53 − 1)",
                    raw.seed
                ),
            });
        }
        Ok(raw)
    }

    /// The document as TOML (all keys, resolved).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("the config is always serialisable")
    }
}

/// ` (line L, column C)` of the start of `span` in `text`, or nothing without a span.
pub fn at_line(text: &str, span: Option<std::ops::Range<usize>>) -> String {
    line_column(text, span).map_or(String::new(), |(line, column)| {
        format!(" (line {line}, column {column})")
    })
}

/// The line and column (from 1) of the start of `span` in `text`.
pub fn line_column(text: &str, span: Option<std::ops::Range<usize>>) -> Option<(usize, usize)> {
    let before = &text[..span?.start.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    Some((line, column))
}

/// The range of a whole-number field as its own check states it (a type error, e.g. `1.5` or
/// `-1`, is reported while reading, before that check runs: [`crate::params::plain`]), from the
/// constants the checks use; "≥ 0" for a field that takes any.
pub(crate) fn whole_number_range(field: &str) -> String {
    use crate::modelling::{aem::MAX_TEST_RUNS, som::MAX_NODES};
    use crate::simulation::{controller::MlpShape, trial::MAX_STEPS};
    let (low, high) = match field {
        "seed" => return format!("from 0 to {MAX_SEED} (2^53 − 1)"),
        "ga.elite" => return "from 0 to ga.population − 1".into(),
        "ga.population" => (2, BIG),
        "ga.generations" | "aem.epochs" => (1, BIG),
        "trial.steps" => (1, MAX_STEPS),
        "aem.test_runs" => (1, MAX_TEST_RUNS),
        "aem.som_nodes" => (1, MAX_NODES),
        "network.hidden" => (1, MlpShape::MAX_HIDDEN),
        _ => return "≥ 0".into(),
    };
    format!("from {low} to {high}")
}

/// A hint when a room file (docs/model.md §4) was given where a config belongs: the document
/// has a room's key (`outline`, `home`, `obstacles`), which a config does not take.
fn room_file_hint(e: &ReadError) -> &'static str {
    let room_keys = ["outline", "home", "obstacles"];
    if matches!(&e.fault, Some(Fault::Unknown(key)) if room_keys.contains(&key.as_str())) {
        ". This looks like a room file, not a config: list it in a config's `rooms = [\"path/to/room.toml\"]`, or check it with `fuzzymotiv rooms --check FILE`"
    } else {
        ""
    }
}

/// Applies `key=value` overrides to a TOML document: dotted keys create or descend into tables;
/// the value is read as TOML, and as a plain string if it is not valid TOML. A table value
/// (`ga={generations=3}`) sets the keys it names and keeps the table's others, as the dotted
/// keys would; a value followed by more TOML (`4\ntrial.steps=5`) is an error.
pub fn apply_sets(table: &mut toml::Table, sets: &[String]) -> Result<(), FieldError> {
    for set in sets {
        let Some((key, value)) = set.split_once('=') else {
            return Err(FieldError {
                source_name: "--set".into(),
                field: set.clone(),
                reason: "expected key=value, e.g. --set ga.population=20".into(),
            });
        };
        let key = key.trim();
        let value = value.trim();
        let parsed: toml::Value = match set_value_table(value) {
            Some(mut t) => {
                let v = t.remove("v");
                if !t.is_empty() {
                    return Err(FieldError {
                        source_name: "--set".into(),
                        field: key.trim().to_string(),
                        reason: format!(
                            "the value `{value}` has more TOML after it; give one value per \
                             override (each key its own --set)"
                        ),
                    });
                }
                v.unwrap_or(toml::Value::String(value.to_string()))
            }
            None => toml::Value::String(value.to_string()),
        };
        let parts: Vec<&str> = key.split('.').collect();
        if parts.iter().any(|p| p.is_empty()) {
            return Err(FieldError {
                source_name: "--set".into(),
                field: key.to_string(),
                reason: "empty key part; use dotted keys such as ga.population".into(),
            });
        }
        let mut t = &mut *table;
        for part in &parts[..parts.len() - 1] {
            let entry = t
                .entry(part.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            t = match entry {
                toml::Value::Table(inner) => inner,
                _ => {
                    return Err(FieldError {
                        source_name: "--set".into(),
                        field: key.to_string(),
                        reason: format!("`{part}` is not a table, so it has no key below it"),
                    });
                }
            };
        }
        if key == "motivations" {
            // A [motivations] table defines the whole set (docs/model.md §8).
            t.insert(key.to_string(), parsed);
        } else {
            merge_value(t, parts[parts.len() - 1], parsed);
        }
    }
    Ok(())
}

/// A `--set motivations.NAME…` changes the config's motivations as they stand: where the
/// document has no `[motivations]` (or an empty one), those are the paper's four with their
/// defaults, so they are written out first (a table in the file defines the whole set;
/// docs/model.md §8). A bare `--set motivations={…}` is a table of its own: it replaces them.
fn default_motivations_for_sets(table: &mut toml::Table, sets: &[String]) {
    let touches = |set: &String| set_key(set).starts_with("motivations.");
    let empty = match table.get("motivations") {
        None => true,
        Some(toml::Value::Table(t)) => t.is_empty(),
        Some(_) => false,
    };
    if empty && sets.iter().any(touches) {
        if let Ok(defaults) = toml::Value::try_from(RawMotivations::default()) {
            table.insert("motivations".into(), defaults);
        }
    }
}

/// The error `e` of a value given by `--set` named as coming from that `--set KEY=VALUE`, not
/// from the file: its field is the key set or lies inside what the `--set`'s value gives
/// (`ga={population=1}` → `ga.population`, but not `ga={generations=5}` → `ga.population`, a
/// value of the file). An error in a table a `--set` reaches into, or in a table holding the
/// key set (`motivations.x` after `--set motivations.x.weight=…`, the motivations' sum after
/// `--set motivations.curiosity=…`), may come from the file as well: it is named as the file
/// with those `--set`s, `c.toml with --set motivations.curiosity=0.8`; other errors as they are.
pub fn blame_set(e: FieldError, sets: &[String]) -> FieldError {
    let field = e.field.as_str();
    if let Some(set) = sets.iter().rev().find(|set| set_gives(set, field)) {
        return FieldError {
            source_name: format!("--set {set}"),
            ..e
        };
    }
    let within: Vec<&str> = (sets.iter())
        .filter(|set| {
            let key = set_key(set);
            !key.is_empty() && (inside(key, field) || inside(field, key))
        })
        .map(String::as_str)
        .collect();
    if within.is_empty() {
        return e;
    }
    FieldError {
        source_name: format!("{} with --set {}", e.source_name, within.join(", --set ")),
        ..e
    }
}

/// Whether the field path `a` is `b` or lies under it (`b.…`, `b[…]`).
fn inside(a: &str, b: &str) -> bool {
    a.strip_prefix(b)
        .is_some_and(|rest| rest.is_empty() || rest.starts_with(['.', '[']))
}

/// The key of `--set KEY=VALUE`.
fn set_key(set: &str) -> &str {
    set.split_once('=').map_or(set, |(k, _)| k).trim()
}

/// `v = VALUE` read as TOML, if it is.
fn set_value_table(value: &str) -> Option<toml::Table> {
    toml::from_str::<toml::Table>(&format!("v = {value}")).ok()
}

/// Whether `--set KEY=VALUE` gives the value of `field`: `field` is `KEY` (or an element of
/// it, `KEY[i]`), or `KEY.rest` where VALUE is a table holding `rest`.
fn set_gives(set: &str, field: &str) -> bool {
    let key = set_key(set);
    let Some(rest) = field.strip_prefix(key).filter(|_| !key.is_empty()) else {
        return false;
    };
    if rest.is_empty() || rest.starts_with('[') {
        return true;
    }
    let Some(rest) = rest.strip_prefix('.') else {
        return false;
    };
    let value = set.split_once('=').map_or("", |(_, v)| v);
    let Some(mut value) = set_value_table(value).and_then(|mut t| t.remove("v")) else {
        return false;
    };
    for part in rest.split('.') {
        let name = part.split_once('[').map_or(part, |(n, _)| n);
        match value {
            toml::Value::Table(mut t) => match t.remove(name) {
                Some(v) => value = v,
                None => return false,
            },
            _ => return false,
        }
    }
    true
}

/// Sets `t[key]` to `value`; where both are tables, key by key (recursively), so that the
/// table's other keys stay.
fn merge_value(t: &mut toml::Table, key: &str, value: toml::Value) {
    match (t.get_mut(key), value) {
        (Some(toml::Value::Table(old)), toml::Value::Table(new)) => {
            for (k, v) in new {
                merge_value(old, &k, v);
            }
        }
        (_, value) => {
            t.insert(key.to_string(), value);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_document_has_spec_defaults() {
        let raw = RawConfig::parse("", "x", &[]).unwrap();
        assert_eq!(raw, RawConfig::default());
        assert_eq!(raw.rooms.len(), 5);
        let again = RawConfig::parse(&raw.to_toml(), "x", &[]).unwrap();
        assert_eq!(again, raw);
    }

    #[test]
    fn set_overrides_nested_keys() {
        let raw = RawConfig::parse(
            "[ga]\npopulation = 50\n",
            "x",
            &[
                "ga.population=20".into(),
                "rooms=[\"H\",\"T\"]".into(),
                "name=hello world".into(),
            ],
        )
        .unwrap();
        assert_eq!(raw.ga.population, 20);
        assert_eq!(raw.rooms, vec!["H", "T"]);
        assert_eq!(raw.name, "hello world");
    }

    #[test]
    fn a_table_value_sets_its_keys_and_keeps_the_others() {
        let config = "[ga]\npopulation = 50\n[trial]\nsteps = 200\nnoise = 0.1\n";
        let sets = ["ga={generations=3}".into(), "trial={noise=0.0}".into()];
        let raw = RawConfig::parse(config, "x", &sets).unwrap();
        assert_eq!(raw.ga.population, 50);
        assert_eq!(raw.ga.generations, 3);
        assert_eq!(raw.trial.steps, 200);
        assert_eq!(raw.trial.noise, Some(0.0));
    }

    #[test]
    fn a_value_with_more_toml_after_it_is_an_error() {
        let e = RawConfig::parse("", "x", &["ga.population=4\ntrial.steps=5".into()]).unwrap_err();
        assert_eq!(e.field, "ga.population", "{e}");
        assert!(e.reason.contains("one value per"), "{e}");
    }

    #[test]
    fn errors_name_the_field() {
        let e = RawConfig::parse("[ga]\npopulaton = 5\n", "c.toml", &[]).unwrap_err();
        assert_eq!(e.field, "ga.populaton", "{e}");
        let e = RawConfig::parse("[trial]\nsteps = \"many\"\n", "c.toml", &[]).unwrap_err();
        assert_eq!(e.field, "trial.steps", "{e}");
        let e = RawConfig::parse("", "c.toml", &["ga.population=-3".into()]).unwrap_err();
        assert_eq!(e.field, "ga.population", "{e}");
        let e = RawConfig::parse("[trial]\nsensor_model = \"laser\"\n", "c.toml", &[]).unwrap_err();
        assert_eq!(e.field, "trial.sensor_model", "{e}");
        let e = RawConfig::parse("seed = [", "c.toml", &[]).unwrap_err();
        assert_eq!(e.field, "seed", "{e}");
    }

    /// `--set motivations.NAME=…` on a config without `[motivations]` changes the paper's four
    /// that the config stands for (as before); on a written table, that table.
    #[test]
    fn a_set_motivation_changes_the_configs_motivations_as_they_stand() {
        let sets = [
            "motivations.curiosity=0.5".to_string(),
            "motivations.homing=0.4".into(),
        ];
        let raw = RawConfig::parse("seed = 3\n", "c.toml", &sets).unwrap();
        assert_eq!(
            raw.motivations,
            crate::fitness::RawMotivations::paper([0.5, 0.4, 0.0, 0.1])
        );
        let written = "[motivations]\ncuriosity = 0.6\nurgency = 0.4\n";
        let sets = [
            "motivations.urgency=0.3".to_string(),
            "motivations.homing=0.1".into(),
        ];
        let raw = RawConfig::parse(written, "c.toml", &sets).unwrap();
        assert_eq!(
            raw.motivations
                .list
                .iter()
                .map(|(n, _)| n.as_str())
                .collect::<Vec<_>>(),
            ["curiosity", "homing", "urgency"]
        );
    }

    /// A bad value of a `--set` is named as that `--set`, not as the file's (issue #52 item 7).
    #[test]
    fn a_value_given_by_set_is_blamed_on_the_set_not_the_file() {
        let sets = ["ga.population=x".to_string()];
        let e = RawConfig::parse("[ga]\npopulation = 4\n", "g.toml", &sets).unwrap_err();
        assert_eq!(e.source_name, "--set ga.population=x", "{e}");
        assert_eq!(e.field, "ga.population", "{e}");
    }

    /// A `--set` of a whole table is blamed only for what its value holds, and a `--set` of
    /// one key of a table not for the table's other keys: those come from the file, named as
    /// the file with the `--set`.
    #[test]
    fn a_set_is_blamed_only_for_what_its_value_holds() {
        let sets = [
            "ga={population=1}".to_string(),
            "motivations.x.weight=2".into(),
        ];
        let checked = |field: &str| FieldError::new(field, "bad").in_source("g.toml");
        let blamed = |field: &str| blame_set(checked(field), &sets).source_name;
        assert_eq!(blamed("ga.population"), "--set ga={population=1}");
        assert_eq!(
            blamed("ga.generations"),
            "g.toml with --set ga={population=1}"
        );
        assert_eq!(
            blamed("motivations.x"),
            "g.toml with --set motivations.x.weight=2"
        );
        assert_eq!(blamed("motivations.x.term"), "g.toml");
        assert_eq!(
            blamed("motivations.x.weight"),
            "--set motivations.x.weight=2"
        );
        // A whole section's error (the motivations' sum) comes from the file with the --set.
        assert_eq!(
            blamed("motivations"),
            "g.toml with --set motivations.x.weight=2"
        );
        assert_eq!(blamed("trial.steps"), "g.toml");
    }

    /// `--set motivations={…}` defines the whole set, as a `[motivations]` table does: the
    /// paper's four are not added first (without a table) nor the file's kept (with one).
    #[test]
    fn a_set_of_the_whole_motivations_table_replaces_the_set() {
        let sets = ["motivations={curiosity=0.7,urgency=0.3}".to_string()];
        let names = |text: &str| {
            let raw = RawConfig::parse(text, "c.toml", &sets).unwrap();
            (raw.motivations.list.iter())
                .map(|(n, w)| (n.clone(), w.weight()))
                .collect::<Vec<_>>()
        };
        let two = vec![("curiosity".to_string(), 0.7), ("urgency".to_string(), 0.3)];
        assert_eq!(names("seed = 3\n"), two);
        assert_eq!(names("[motivations]\nhoming = 0.5\nenergy = 0.5\n"), two);
    }
}
