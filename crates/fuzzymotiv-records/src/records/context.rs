//! What the pages and figures say about a run besides its results: its name, seed, rooms,
//! sizes, model choices and resolved config, copied once out of the experiment
//! ([`RenderContext::of`]), so that rendering reads records and this, never the live
//! experiment.

use fuzzymotiv::experiment::{Combination, EnergyMode, OrientationMode, Training};
use fuzzymotiv::fitness::Homing;
use fuzzymotiv::fitness::label_name;
use fuzzymotiv::simulation::Motion;
use fuzzymotiv::simulation::Room;

use crate::files::inputs::{Loaded, resolved_toml};
use crate::records::MotivationsRecord;

/// A run's setting as the report, the figures and the tables show it.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderContext {
    /// The experiment's name.
    pub name: String,
    /// Base seed.
    pub seed: u64,
    /// The rooms, in order (their geometry is drawn).
    pub rooms: Vec<Room>,
    /// All-rooms or per-room training.
    pub training: Training,
    /// GA population.
    pub population: usize,
    /// GA generations.
    pub generations: usize,
    /// Steps per trial (T).
    pub steps: usize,
    /// Robot body radius (mm), for the replay.
    pub robot_radius: f64,
    /// The robot (its sensors' layout, names and largest reading), for the replay.
    pub robot: &'static fuzzymotiv::simulation::RobotSpec,
    /// The sensor response model, for the replay's rays.
    pub sensor_model: fuzzymotiv::simulation::SensorModel,
    /// Step length (s), for the replay.
    pub dt: f64,
    /// The motivations X = (C, H, O, E).
    pub motivations: MotivationsRecord,
    /// The TSK's rule base.
    pub fuzzy: FuzzySetting,
    /// How F combines the motivations (the TSK, or a baseline).
    pub combine: Combination,
    /// Whether the fuzzy input of b is b or 1 − b.
    pub energy: EnergyMode,
    /// How g is measured.
    pub homing: Homing,
    /// The motion model.
    pub motion: Motion,
    /// When l is measured.
    pub orientation: OrientationMode,
    /// Room recognition.
    pub aem: AemSetting,
    /// The resolved config (`config.resolved.toml`).
    pub config_text: String,
    /// The terms measured beyond a, g, l, b ([`crate::records::extra_terms`]), by name.
    pub extra_terms: Vec<(String, fuzzymotiv::fitness::TermId)>,
}

/// The TSK rule base (docs/model.md §8) as the report describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct FuzzySetting {
    /// The label peaks.
    pub peaks: Vec<f64>,
    /// The coefficients c, one per label.
    pub coefficients: Vec<f64>,
    /// The label names, lowest first.
    pub label_names: Vec<String>,
    /// Number of rules (Π M_i: labels⁴ for the paper's four).
    pub rule_count: usize,
    /// The motivations with labels of their own, in input order (none for the paper's model).
    pub own_labels: Vec<OwnLabels>,
}

/// A motivation's own labels (`peaks`, `coefficients` in its `[motivations]` table).
#[derive(Debug, Clone, PartialEq)]
pub struct OwnLabels {
    /// The motivation's name.
    pub motivation: String,
    /// The term it weighs.
    pub term: String,
    /// Its label peaks.
    pub peaks: Vec<f64>,
    /// Its coefficients, one per label.
    pub coefficients: Vec<f64>,
    /// Its label names, lowest first.
    pub label_names: Vec<String>,
}

impl FuzzySetting {
    /// The rule base of `tsk` over the motivations `m`.
    fn of(tsk: &fuzzymotiv::fitness::TskFitness, m: &fuzzymotiv::fitness::Motivations) -> Self {
        FuzzySetting {
            peaks: tsk.peaks().to_vec(),
            coefficients: tsk.coefficients().to_vec(),
            label_names: label_names(tsk.labels()),
            rule_count: tsk.rule_count(m),
            own_labels: (m.iter())
                .filter_map(|x| {
                    let own = x.labels()?;
                    Some(OwnLabels {
                        motivation: x.name().to_string(),
                        term: x.term().to_string(),
                        peaks: own.peaks().to_vec(),
                        coefficients: own.coefficients().to_vec(),
                        label_names: label_names(own.labels()),
                    })
                })
                .collect(),
        }
    }
}

/// The names of `m` labels, lowest first.
fn label_names(m: usize) -> Vec<String> {
    (0..m).map(|k| label_name(k, m)).collect()
}

/// Room recognition's sizes (docs/model.md §9).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AemSetting {
    /// Whether it runs.
    pub enabled: bool,
    /// SOM nodes.
    pub som_nodes: usize,
    /// Candidate window (nodes).
    pub threshold: usize,
    /// Test runs per room.
    pub test_runs: usize,
}

impl RenderContext {
    /// The setting of a loaded config.
    pub fn of(loaded: &Loaded) -> RenderContext {
        let exp = &loaded.experiment;
        let (trial, tsk, aem) = (exp.trial_params(), exp.fuzzy(), exp.aem());
        RenderContext {
            name: exp.name().to_string(),
            seed: exp.seed(),
            rooms: exp.arenas().iter().map(|a| a.room().clone()).collect(),
            training: exp.training(),
            population: exp.ga().population(),
            generations: exp.ga().generations(),
            steps: trial.steps(),
            robot_radius: trial.robot().radius(),
            robot: trial.robot().spec(),
            sensor_model: trial.sensor_model(),
            dt: trial.dt(),
            motivations: MotivationsRecord::of(exp.motivations()),
            fuzzy: FuzzySetting::of(tsk, exp.motivations()),
            combine: exp.combination(),
            energy: exp.energy(),
            homing: exp.homing(),
            motion: trial.robot().motion(),
            orientation: exp.orientation(),
            aem: AemSetting {
                enabled: aem.enabled(),
                som_nodes: aem.som().nodes(),
                threshold: aem.threshold(),
                test_runs: aem.test_runs(),
            },
            config_text: resolved_toml(&loaded.raw),
            extra_terms: crate::records::extra_terms(exp),
        }
    }

    /// The room names, in order.
    pub fn room_names(&self) -> Vec<String> {
        self.rooms.iter().map(|r| r.name.clone()).collect()
    }

    /// Whether l is measured during evolution (online orientation with O > 0).
    pub fn online_orientation(&self) -> bool {
        self.orientation == OrientationMode::Online && self.motivations.orientation > 0.0
    }
}
