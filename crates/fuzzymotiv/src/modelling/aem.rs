//! Action-based environment modelling (AEM): per-step action labels and environment vectors.
//!
//! Each control step is one of four [`Action`]s (with `actions` motion the robot executes it;
//! with `wheels` motion it labels the motor outputs); a run of `T` actions is then encoded as a
//! `T`-dimensional environment vector (docs/model.md). The default
//! [`Encoder::ChainCode`] is the paper's unwrapped 12-direction chain code divided by 12.

use serde::{Deserialize, Serialize};

use crate::modelling::som::{RawSom, SomParams};
use crate::params::{FieldError, check};

pub use crate::simulation::robot::DEFAULT_ACTION_TOLERANCE;

/// Checked AEM parameters (`[aem]` in a config, docs/model.md §9), built by
/// [`AemParams::from_raw`] (or [`AemParams::default`]). The action tolerance of `[aem]` labels
/// every step of a trial, so it lives in the trial's parameters
/// ([`crate::simulation::trial::TrialParams::action_tolerance`]).
#[derive(Debug, Clone, PartialEq)]
pub struct AemParams {
    enabled: bool,
    encoder: Encoder,
    som: SomParams,
    threshold: usize,
    test_runs: usize,
}

impl Default for AemParams {
    fn default() -> Self {
        AemParams {
            enabled: true,
            encoder: Encoder::ChainCode,
            som: SomParams::default(),
            threshold: 10,
            test_runs: 10,
        }
    }
}

impl AemParams {
    /// Whether AEM runs after evolution; default true (needs at least 2 rooms).
    pub fn enabled(&self) -> bool {
        self.enabled
    }

    /// Action sequence → vector encoding; default `chain-code`.
    pub fn encoder(&self) -> Encoder {
        self.encoder
    }

    /// SOM training parameters (defaults [`SomParams::default`]; ranges on its accessors),
    /// with nodes × `trial.steps` ≤ 5·10⁷.
    pub fn som(&self) -> &SomParams {
        &self.som
    }

    /// r-node gate (nodes); default 10.
    pub fn threshold(&self) -> usize {
        self.threshold
    }

    /// Test runs per room; default 10; range 1..=100000.
    pub fn test_runs(&self) -> usize {
        self.test_runs
    }
}

/// The most test runs per room (`aem.test_runs`).
pub const MAX_TEST_RUNS: usize = 100_000;

/// `[aem]` in a config, as written (docs/model.md §9): see [`AemParams`] and [`SomParams`] for
/// each field's unit, default and range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawAem {
    /// [`AemParams::enabled`].
    pub enabled: bool,
    /// [`AemParams::encoder`]: `"chain-code"`, `"heading"` or `"symbols"`.
    pub encoder: Encoder,
    /// [`SomParams::nodes`].
    pub som_nodes: usize,
    /// [`SomParams::epochs`].
    pub epochs: usize,
    /// [`AemParams::threshold`].
    pub threshold: usize,
    /// [`AemParams::test_runs`].
    pub test_runs: usize,
    /// [`crate::simulation::trial::TrialParams::action_tolerance`] (checked with the trial).
    pub action_tolerance: f64,
    /// [`SomParams::sigma_start`].
    pub sigma_start: f64,
    /// [`SomParams::sigma_end`].
    pub sigma_end: f64,
    /// [`SomParams::rate_start`].
    pub rate_start: f64,
    /// [`SomParams::rate_end`].
    pub rate_end: f64,
}

impl Default for RawAem {
    fn default() -> Self {
        let d = AemParams::default();
        Self {
            enabled: d.enabled,
            encoder: d.encoder,
            som_nodes: d.som.nodes(),
            epochs: d.som.epochs(),
            threshold: d.threshold,
            test_runs: d.test_runs,
            action_tolerance: DEFAULT_ACTION_TOLERANCE,
            sigma_start: d.som.sigma_start(),
            sigma_end: d.som.sigma_end(),
            rate_start: d.som.rate_start(),
            rate_end: d.som.rate_end(),
        }
    }
}

impl RawAem {
    /// The SOM's parameters as given here.
    pub fn som(&self) -> RawSom {
        RawSom {
            nodes: self.som_nodes,
            epochs: self.epochs,
            sigma_start: self.sigma_start,
            sigma_end: self.sigma_end,
            rate_start: self.rate_start,
            rate_end: self.rate_end,
        }
    }
}

impl AemParams {
    /// Checks `[aem]` for trials of `steps` steps in `rooms` rooms (the SOM's fields by
    /// [`SomParams::from_raw`]; `action_tolerance` is the trial's,
    /// [`crate::simulation::trial::TrialParams::from_raw`]).
    pub fn from_raw(a: &RawAem, steps: usize, rooms: usize) -> Result<AemParams, FieldError> {
        let som = SomParams::from_raw(&a.som())?;
        check(
            (1..=MAX_TEST_RUNS).contains(&a.test_runs),
            "aem.test_runs",
            || format!("must be in 1..={MAX_TEST_RUNS}, got {}", a.test_runs),
        )?;
        check(
            !a.enabled || steps.saturating_mul(a.som_nodes) <= 50_000_000,
            "aem.som_nodes",
            || {
                format!(
                    "the SOM would hold aem.som_nodes × trial.steps = {} × {} weights; keep the product ≤ 5e7",
                    a.som_nodes, steps
                )
            },
        )?;
        check(!a.enabled || rooms >= 2, "aem.enabled", || {
            format!(
                "room recognition needs at least 2 rooms, got {rooms}; add rooms or set aem.enabled = false"
            )
        })?;
        Ok(AemParams {
            enabled: a.enabled,
            encoder: a.encoder,
            som,
            threshold: a.threshold,
            test_runs: a.test_runs,
        })
    }
}

/// The action taken in one control step: defined with the robot's motion ([`crate::simulation::Motion`]),
/// re-exported here where the chain code and the environment vectors use it.
pub use crate::simulation::robot::Action;

/// How a sequence of actions becomes an environment vector (one element per action).
///
/// Config spelling is kebab-case: `"chain-code"` (default), `"heading"`, `"symbols"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Encoder {
    /// The paper's encoding (default): the cumulative chain code after each step, starting
    /// from code 0 and kept unwrapped (no mod 12), divided by 12 — i.e. the total heading
    /// change in full turns.
    #[default]
    ChainCode,
    /// The cumulative chain code wrapped into 0..12 (`rem_euclid(12)`), divided by 12 — the
    /// current heading as a fraction of a full turn, in [0, 1).
    Heading,
    /// The raw action symbol of each step, not accumulated: Straight 0, Left30 1/3,
    /// Right30 2/3, Turn180 1 (see [`Action::symbol_value`]).
    Symbols,
}

/// The environment vector of an action sequence: element `t` (0-based) encodes the state after
/// action `t`, so `T` actions give a `T`-dimensional vector (empty input → empty vector).
pub fn environment_vector(actions: &[Action], encoder: Encoder) -> Vec<f64> {
    let mut out = Vec::with_capacity(actions.len());
    environment_vector_into(actions, encoder, &mut out);
    out
}

/// As [`environment_vector`], but writes into `out` (cleared first), reusing its allocation.
pub fn environment_vector_into(actions: &[Action], encoder: Encoder, out: &mut Vec<f64>) {
    out.clear();
    out.reserve(actions.len());
    match encoder {
        Encoder::ChainCode | Encoder::Heading => {
            let mut code: i64 = 0;
            for &a in actions {
                code += i64::from(a.chain_step());
                let c = if encoder == Encoder::Heading {
                    code.rem_euclid(12)
                } else {
                    code
                };
                out.push(c as f64 / 12.0);
            }
        }
        Encoder::Symbols => out.extend(actions.iter().map(|a| a.symbol_value())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Action::*;

    fn scaled(codes: &[i64]) -> Vec<f64> {
        codes.iter().map(|&c| c as f64 / 12.0).collect()
    }

    #[test]
    fn chain_code_hand_made() {
        let seq = [Straight, Left30, Left30, Right30, Turn180];
        assert_eq!(
            environment_vector(&seq, Encoder::ChainCode),
            scaled(&[0, 1, 2, 1, 7])
        );
        assert_eq!(
            environment_vector(&[], Encoder::ChainCode),
            Vec::<f64>::new()
        );
        let rights = [Right30; 3];
        assert_eq!(
            environment_vector(&rights, Encoder::ChainCode),
            scaled(&[-1, -2, -3])
        );
    }

    #[test]
    fn chain_code_is_unwrapped_heading_wraps() {
        let seq = [Left30; 13];
        let v = environment_vector(&seq, Encoder::ChainCode);
        assert_eq!(v.len(), 13);
        assert_eq!(*v.last().unwrap(), 13.0 / 12.0);
        let h = environment_vector(&seq, Encoder::Heading);
        assert_eq!(*h.last().unwrap(), 1.0 / 12.0);
        assert_eq!(h[11], 0.0);
        // Negative codes wrap into [0, 1).
        let h = environment_vector(&[Right30, Turn180, Turn180], Encoder::Heading);
        assert_eq!(h, scaled(&[11, 5, 11]));
    }

    #[test]
    fn symbols_values() {
        let seq = [Straight, Left30, Right30, Turn180];
        assert_eq!(
            environment_vector(&seq, Encoder::Symbols),
            vec![0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0]
        );
    }

    #[test]
    fn into_reuses_buffer() {
        let mut buf = vec![9.0; 50];
        environment_vector_into(&[Left30, Left30], Encoder::ChainCode, &mut buf);
        assert_eq!(buf, scaled(&[1, 2]));
    }

    #[test]
    fn from_motors_thresholds() {
        let tol = 0.25;
        assert_eq!(Action::from_motors(0.2, 0.3, tol), Turn180);
        assert_eq!(Action::from_motors(0.5, 0.7, tol), Left30);
        assert_eq!(Action::from_motors(0.7, 0.5, tol), Right30);
        assert_eq!(Action::from_motors(0.6, 0.65, tol), Straight);
        // Exactly representable boundary: sR − sL = 0.25 exactly → Straight (strict >).
        assert_eq!(Action::from_motors(0.5, 0.625, tol), Straight);
        assert_eq!(Action::from_motors(0.625, 0.5, tol), Straight);
        // One wheel backwards, other forward: a turn, not Turn180.
        assert_eq!(Action::from_motors(0.4, 0.9, tol), Left30);
        assert_eq!(Action::from_motors(f64::NAN, 0.5, tol), Straight);
    }

    #[test]
    fn labels_and_steps() {
        let all = [Straight, Left30, Right30, Turn180];
        let labels: Vec<_> = all.iter().map(|a| a.label()).collect();
        assert_eq!(labels, ["straight", "left30", "right30", "turn180"]);
        let steps: Vec<_> = all.iter().map(|a| a.chain_step()).collect();
        assert_eq!(steps, [0, 1, -1, 6]);
    }
}
