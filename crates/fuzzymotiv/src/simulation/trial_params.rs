//! The parameters of a trial: `[trial]` as written ([`RawTrial`]) and checked, with the robot's
//! body and the action tolerance ([`TrialParams`]).

use serde::{Deserialize, Serialize};

use crate::params::{FieldError, Num, check};
use crate::simulation::randomise::{Randomise, RawRandomise};
use crate::simulation::robot::{Motion, RawRobot, Robot};
use crate::simulation::robot_spec::RobotSpec;
use crate::simulation::sensor::{SensorModel, TableRef};
use crate::simulation::sensor_table::SensorTable;

/// Checked parameters of a trial (docs/model.md, "Robot", "Noise" and "Home zone"), built by
/// [`TrialParams::from_raw`] (or [`TrialParams::default`]); read through the accessors, each
/// documented with its unit, default and range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrialParams {
    pub(super) steps: usize,
    pub(super) dt: f64,
    pub(super) noise: f64,
    pub(super) sensor_model: SensorModel,
    pub(super) robot: Robot,
    pub(super) end_at_home: bool,
    pub(super) action_tolerance: f64,
}

impl Default for TrialParams {
    fn default() -> Self {
        Self {
            steps: 400,
            dt: 0.1,
            noise: 0.06,
            sensor_model: SensorModel::Sampled,
            robot: Robot::default(),
            end_at_home: true,
            action_tolerance: crate::simulation::robot::DEFAULT_ACTION_TOLERANCE,
        }
    }
}

/// The most steps a trial may have (`trial.steps`).
pub const MAX_STEPS: usize = 10_000_000;

/// `[trial]` in a config, as written: see [`TrialParams`] for each field's unit, default and
/// range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawTrial {
    /// [`TrialParams::steps`].
    pub steps: usize,
    /// [`TrialParams::dt`]; `None`: the robot file's control period.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt: Option<f64>,
    /// [`TrialParams::noise`]; `None`: the robot file's noise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub noise: Option<f64>,
    /// [`TrialParams::sensor_model`].
    pub sensor_model: SensorModel,
    /// A sensor table file (path relative to the config) read by the `sampled` model instead of
    /// the built-in Khepera tables; the front end reads it ([`crate::experiment::Setup::resolve`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sensor_table: Option<String>,
    /// [`TrialParams::end_at_home`].
    pub end_at_home: bool,
    /// `[trial.randomise]` ([`TrialParams::randomise_of`]), absent when nothing is randomised.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub randomise: Option<RawRandomise>,
}

impl Default for RawTrial {
    fn default() -> Self {
        let d = TrialParams::default();
        Self {
            steps: d.steps,
            dt: None,
            noise: None,
            sensor_model: d.sensor_model,
            sensor_table: None,
            end_at_home: d.end_at_home,
            randomise: None,
        }
    }
}

impl RawTrial {
    /// The same, the values the config leaves to the robot file (`dt`, `noise`) taken from
    /// `spec`.
    pub fn resolved(&self, spec: &RobotSpec) -> RawTrial {
        RawTrial {
            dt: Some(self.dt.unwrap_or(spec.dt())),
            noise: Some(self.noise.unwrap_or(spec.noise())),
            ..self.clone()
        }
    }
}

impl TrialParams {
    /// Checks `[trial]` with the robot (`[robot]` and its robot file `spec`,
    /// [`Robot::from_raw`]) and the action tolerance (`aem.action_tolerance`), naming the first
    /// field out of range.
    pub fn from_raw(
        t: &RawTrial,
        robot: &RawRobot,
        spec: &'static RobotSpec,
        action_tolerance: f64,
    ) -> Result<TrialParams, FieldError> {
        let t = &t.resolved(spec);
        let (dt, noise) = (t.dt.unwrap_or_default(), t.noise.unwrap_or_default());
        check((1..=MAX_STEPS).contains(&t.steps), "trial.steps", || {
            format!("must be an integer in 1..={MAX_STEPS}, got {}", t.steps)
        })?;
        check(dt.is_finite() && dt > 0.0 && dt <= 10.0, "trial.dt", || {
            format!("must be a time step in (0, 10] seconds, got {}", Num(dt))
        })?;
        check(
            noise.is_finite() && (0.0..=0.5).contains(&noise),
            "trial.noise",
            || {
                format!(
                    "must be a noise level in [0, 0.5] (0.06 is the paper's 6 %), got {}",
                    Num(noise)
                )
            },
        )?;
        check(
            t.sensor_table.is_none() || t.sensor_model == SensorModel::Sampled,
            "trial.sensor_table",
            || {
                "a sensor table is read by the \"sampled\" sensor model; remove trial.sensor_table or set trial.sensor_model = \"sampled\"".into()
            },
        )?;
        let robot = Robot::from_raw(robot, spec)?;
        let trial = TrialParams {
            steps: t.steps,
            dt,
            noise,
            sensor_model: t.sensor_model,
            robot,
            end_at_home: t.end_at_home,
            action_tolerance,
        };
        check(trial.max_step() < robot.radius(), "trial.dt", || {
            format!(
                "one step may move the robot {:.1} mm (robot.v_max × trial.dt × (1 + trial.noise)), which must stay below the body radius {} mm so it cannot pass through walls; use a smaller dt or v_max",
                trial.max_step(),
                robot.radius()
            )
        })?;
        check(
            action_tolerance.is_finite() && (0.0..=2.0).contains(&action_tolerance),
            "aem.action_tolerance",
            || {
                format!(
                    "must be in [0, 2] (signed-speed units), got {}",
                    Num(action_tolerance)
                )
            },
        )?;
        Ok(trial)
    }

    /// Checks `[trial.randomise]` of `t` (checked into these parameters) for their robot:
    /// the ranges each evaluation trial of the evolution draws its robot from; `None` when
    /// nothing is randomised.
    pub fn randomise_of(&self, t: &RawTrial) -> Result<Option<Randomise>, FieldError> {
        let Some(raw) = &t.randomise else {
            return Ok(None);
        };
        check(
            raw.sensor_scale.is_none() || t.sensor_model == SensorModel::Sampled,
            "trial.randomise.sensor_scale",
            || {
                "scales the readings of a sensor table, which the \"sampled\" sensor model reads; remove it or set trial.sensor_model = \"sampled\"".into()
            },
        )?;
        let step = |noise| self.with_noise(noise).max_step();
        Randomise::from_raw(raw, &self.robot, step, self.noise)
    }

    /// The same parameters, the `sampled` model reading `table` instead of the built-in tables
    /// (`trial.sensor_table`).
    pub fn with_sensor_table(self, table: &'static SensorTable) -> TrialParams {
        TrialParams {
            sensor_model: SensorModel::Table(TableRef(table)),
            ..self
        }
    }

    /// The same parameters with noise level `noise` (in [0, 0.5]; for perturbation studies).
    pub fn with_noise(self, noise: f64) -> TrialParams {
        TrialParams { noise, ..self }
    }

    /// The same parameters with the body `robot` (for perturbation studies; its step must stay
    /// below its radius as [`TrialParams::from_raw`] requires).
    pub fn with_robot(self, robot: Robot) -> TrialParams {
        TrialParams { robot, ..self }
    }

    /// Steps per trial `T`; default 400; range 1..=10⁷.
    #[inline]
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Control step (s); default 0.1; range (0, 10], and one step must move the robot less than
    /// its radius ([`TrialParams::max_step`]).
    #[inline]
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Multiplicative noise level on sensors and wheels; default 0.06 (the paper's 6 %); range
    /// [0, 0.5]; 0 disables it.
    #[inline]
    pub fn noise(&self) -> f64 {
        self.noise
    }

    /// IR response model; default `sampled` ([`SensorModel::Table`] when `trial.sensor_table`
    /// names a file).
    #[inline]
    pub fn sensor_model(&self) -> SensorModel {
        self.sensor_model
    }

    /// The robot's body and motion model.
    #[inline]
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// End the trial when the robot, having escaped the home zone, is back inside it; the
    /// remaining steps are idle. Default true.
    #[inline]
    pub fn end_at_home(&self) -> bool {
        self.end_at_home
    }

    /// Signed-speed difference (fractions of `v_max`) separating a turn from a straight step
    /// in the action labels; default 0.25 (config `aem.action_tolerance`); range [0, 2].
    #[inline]
    pub fn action_tolerance(&self) -> f64 {
        self.action_tolerance
    }

    /// Longest distance the centre can move in one step (mm), noise included.
    pub fn max_step(&self) -> f64 {
        match self.robot.motion() {
            Motion::Actions => self.straight_step(),
            Motion::Wheels => self.robot.v_max() * self.dt * (1.0 + self.noise),
        }
    }

    /// Length of a straight action (mm): `v_max · dt`, 8 mm by default.
    #[inline]
    pub fn straight_step(&self) -> f64 {
        self.robot.v_max() * self.dt
    }
}
