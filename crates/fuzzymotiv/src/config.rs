//! Experiment configuration: the raw TOML document (every key has the SPEC default, unknown keys
//! are rejected), `--set key=value` overrides, and validation into [`crate::experiment::Experiment`].
//!
//! ```
//! use fuzzymotiv::config::RawConfig;
//! let raw = RawConfig::parse("", "empty.toml", &["ga.population=20".to_string()]).unwrap();
//! assert_eq!(raw.ga.population, 20);
//! assert_eq!(raw.trial.steps, 400);
//! ```

use serde::{Deserialize, Serialize};

use crate::aem::Encoder;
use crate::fitness::Homing;
use crate::fuzzy::{CoefficientScheme, PAPER_PEAKS};
use crate::ga::GaParams;
use crate::robot::Khepera;
use crate::room::{BUILTIN_ROOMS, field_from_toml_message};
use crate::sensor::SensorModel;

/// A configuration that cannot be used: the file, the field and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{source_name}: field `{field}`: {reason}")]
pub struct ConfigError {
    /// File (or other source) of the configuration.
    pub source_name: String,
    /// Dotted key, e.g. `ga.population`.
    pub field: String,
    /// What is wrong and what would be right.
    pub reason: String,
}

/// How populations are trained over rooms (SPEC §12).
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

/// When the orientation term `l` is measured (SPEC §13).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OrientationMode {
    /// Only after evolution, by the SOM test (the paper; default).
    #[default]
    Offline,
    /// During evolution, by two runs per room and 1-NN.
    Online,
}

/// `[motivations]`: X = (C, H, O, E), defaults to the paper's high-curiosity setting.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawMotivations {
    /// Curiosity C (weight of exploration a); default 0.8.
    pub curiosity: f64,
    /// Homing H (weight of homing g); default 0.1.
    pub homing: f64,
    /// Orientation O (weight of recognition l); default 0.
    pub orientation: f64,
    /// Energy E (weight of battery b); default 0.1.
    pub energy: f64,
}

impl Default for RawMotivations {
    fn default() -> Self {
        Self {
            curiosity: 0.8,
            homing: 0.1,
            orientation: 0.0,
            energy: 0.1,
        }
    }
}

/// `[trial]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawTrial {
    /// Steps per trial T; default 400.
    pub steps: usize,
    /// Control step (s); default 0.1.
    pub dt: f64,
    /// Noise level; default 0.06.
    pub noise: f64,
    /// `"sampled"` (default) or `"linear"`.
    pub sensor_model: SensorModel,
    /// End a trial when the robot is back in the home zone after escaping it; default true.
    pub end_at_home: bool,
}

impl Default for RawTrial {
    fn default() -> Self {
        Self {
            steps: 400,
            dt: 0.1,
            noise: 0.06,
            sensor_model: SensorModel::Sampled,
            end_at_home: true,
        }
    }
}

/// `[network]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawNetwork {
    /// Hidden units; default 6.
    pub hidden: usize,
}

impl Default for RawNetwork {
    fn default() -> Self {
        Self { hidden: 6 }
    }
}

/// Coefficient array: a scheme name or explicit values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Coefficients {
    /// `"linear"` (default) or `"ratio"`.
    Scheme(CoefficientScheme),
    /// One value per label.
    Values(Vec<f64>),
}

/// `[fuzzy]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawFuzzy {
    /// Peaks of the triangular labels; default [0, 0.25, 0.5, 0.75, 1].
    pub peaks: Vec<f64>,
    /// Coefficient array; default `"linear"`.
    pub coefficients: Coefficients,
}

impl Default for RawFuzzy {
    fn default() -> Self {
        Self {
            peaks: PAPER_PEAKS.to_vec(),
            coefficients: Coefficients::Scheme(CoefficientScheme::Linear),
        }
    }
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
}

/// `[aem]`: action-based environment modelling (SPEC §11).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawAem {
    /// Run AEM after evolution; default true (needs at least 2 rooms).
    pub enabled: bool,
    /// `"chain-code"` (default), `"heading"` or `"symbols"`.
    pub encoder: Encoder,
    /// SOM nodes; default 128.
    pub som_nodes: usize,
    /// SOM epochs; default 1000.
    pub epochs: usize,
    /// r-node gate (nodes); default 10.
    pub threshold: usize,
    /// Test runs per room; default 10.
    pub test_runs: usize,
    /// Signed-speed difference separating turns from straight; default 0.25.
    pub action_tolerance: f64,
    /// Neighbourhood width at the first epoch; default 32.
    pub sigma_start: f64,
    /// Neighbourhood width at the last epoch; default 1.
    pub sigma_end: f64,
    /// Learning rate at the first epoch; default 0.5.
    pub rate_start: f64,
    /// Learning rate at the last epoch; default 0.01.
    pub rate_end: f64,
}

impl Default for RawAem {
    fn default() -> Self {
        Self {
            enabled: true,
            encoder: Encoder::ChainCode,
            som_nodes: 128,
            epochs: 1000,
            threshold: 10,
            test_runs: 10,
            action_tolerance: 0.25,
            sigma_start: 32.0,
            sigma_end: 1.0,
            rate_start: 0.5,
            rate_end: 0.01,
        }
    }
}

/// The configuration document as written (every key optional, SPEC defaults).
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
    pub ga: GaParams,
    /// Trial parameters.
    pub trial: RawTrial,
    /// Robot body.
    pub robot: Khepera,
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
            ga: GaParams::default(),
            trial: RawTrial::default(),
            robot: Khepera::default(),
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
    pub fn parse(text: &str, source_name: &str, sets: &[String]) -> Result<RawConfig, ConfigError> {
        let err = |field: &str, reason: String| ConfigError {
            source_name: source_name.to_string(),
            field: field.to_string(),
            reason,
        };
        let mut table: toml::Table = toml::from_str(text).map_err(|e| {
            let msg = e.message().trim().to_string();
            err(
                &field_from_toml_message(&msg, text, e.span()),
                format!("not valid TOML: {msg}"),
            )
        })?;
        if sets.is_empty() {
            return Self::from_text(text, source_name);
        }
        apply_sets(&mut table, sets)?;
        let merged = toml::to_string(&table).map_err(|e| err("(document)", e.to_string()))?;
        Self::from_text(&merged, &format!("{source_name} (with --set overrides)"))
    }

    fn from_text(text: &str, source_name: &str) -> Result<RawConfig, ConfigError> {
        toml::from_str(text).map_err(|e| {
            let msg = e.message().trim().to_string();
            ConfigError {
                source_name: source_name.to_string(),
                field: field_from_toml_message(&msg, text, e.span()),
                reason: msg,
            }
        })
    }

    /// The document as TOML (all keys, resolved).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("the config is always serialisable")
    }
}

/// Applies `key=value` overrides to a TOML document: dotted keys create or descend into tables;
/// the value is read as TOML, and as a plain string if it is not valid TOML.
pub fn apply_sets(table: &mut toml::Table, sets: &[String]) -> Result<(), ConfigError> {
    for set in sets {
        let Some((key, value)) = set.split_once('=') else {
            return Err(ConfigError {
                source_name: "--set".into(),
                field: set.clone(),
                reason: "expected key=value, e.g. --set ga.population=20".into(),
            });
        };
        let key = key.trim();
        let value = value.trim();
        let parsed: toml::Value = match toml::from_str::<toml::Table>(&format!("v = {value}")) {
            Ok(mut t) => t
                .remove("v")
                .unwrap_or(toml::Value::String(value.to_string())),
            Err(_) => toml::Value::String(value.to_string()),
        };
        let parts: Vec<&str> = key.split('.').collect();
        if parts.iter().any(|p| p.is_empty()) {
            return Err(ConfigError {
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
                    return Err(ConfigError {
                        source_name: "--set".into(),
                        field: key.to_string(),
                        reason: format!("`{part}` is not a table, so it has no key below it"),
                    });
                }
            };
        }
        t.insert(parts[parts.len() - 1].to_string(), parsed);
    }
    Ok(())
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
}
