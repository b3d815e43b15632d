//! An evolved controller taken out of the simulator: the network of a genome with the input
//! scaling, the output → wheel-speed mapping and the action labelling of its experiment, as a
//! self-describing JSON document ([`ExportedController::json`]) or as dependency-free C99
//! ([`ExportedController::c`]) that gives the simulator's motor outputs bit for bit
//! (docs/guide/real-robot.md).
//!
//! ```
//! use fuzzymotiv::export::ExportedController;
//! use fuzzymotiv::simulation::{MlpShape, TrialParams};
//!
//! let genome = vec![0.25; MlpShape::default().genome_len()];
//! let export = ExportedController::new(MlpShape::default(), &genome, &TrialParams::default())?;
//! let doc: serde_json::Value = serde_json::from_str(&export.json())?;
//! assert_eq!(doc["network"]["layout"], "8-6-2");
//! let c = export.c();
//! assert!(c.header.contains("fm_controller_step(const uint16_t ir[8], double motors[2], int *action)"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub(crate) mod aseba;
pub(crate) mod c;
pub(crate) mod epuck2;
pub(crate) mod executor;
pub(crate) mod golden;
pub(crate) mod json;
pub(crate) mod khepera;
pub(crate) mod kit;
#[cfg(test)]
mod kit_tests;
pub(crate) mod onnx;

pub use aseba::thymio2_kit;
pub use c::CSources;
pub use epuck2::{
    EPUCK2_MOTOR_SPEED_LIMIT, EPUCK2_STEPS_PER_TURN, EPUCK2_WHEEL_DIAMETER_MM, epuck2_kit,
};
pub use json::{ControllerDoc, FORMAT, FORMAT_VERSION};
pub use khepera::khepera_kit;
pub use kit::{Kit, KitFile, KitRobot};

use crate::simulation::controller::{GenomeError, MlpShape};
use crate::simulation::robot::Motion;
use crate::simulation::trial::TrialParams;

/// A genome that cannot be exported.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// The genome's length is not its network's.
    #[error(transparent)]
    Length(#[from] GenomeError),
    /// The network's inputs are not the robot's sensors.
    #[error("the network has {network} inputs, the robot {robot} has {sensors} sensors")]
    Inputs {
        /// The network's inputs.
        network: usize,
        /// The robot's name.
        robot: String,
        /// Its sensors.
        sensors: usize,
    },
    /// A weight is NaN or infinite (no evolved genome has one).
    #[error("weight {index} is {value}, not a finite number")]
    NotFinite {
        /// The weight's index in the genome (0-based).
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A kit's robot whose sensors are not the network's inputs.
    #[error("the robot `{robot}` has {sensors} sensors but the network has {inputs} inputs")]
    SensorCount {
        /// The robot's name.
        robot: String,
        /// Its number of sensors.
        sensors: usize,
        /// The network's inputs.
        inputs: usize,
    },
    /// A kit's robot with a quantity that is not a positive number.
    #[error("the robot `{robot}`'s {field} is {value}, not a positive number")]
    RobotQuantity {
        /// The robot's name.
        robot: String,
        /// The quantity (`reading_max`, `v_max`, `wheel_base`, `dt`, `turn_deg`).
        field: &'static str,
        /// Its value.
        value: f64,
    },
}

/// A genome's network with what turns its inputs and outputs into a robot's: the sensor scale,
/// the maximum wheel speed, the motion model and the action tolerance of its experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportedController {
    pub(crate) shape: MlpShape,
    pub(crate) weights: Vec<f64>,
    pub(crate) v_max: f64,
    pub(crate) motion: Motion,
    pub(crate) tolerance: f64,
    pub(crate) robot: KitRobot,
    /// The trial parameters of the experiment (its robot is simulated for golden vectors).
    pub(crate) trial: TrialParams,
}

impl ExportedController {
    /// The controller of `genome` (laid out as [`MlpShape::genome_len`] says) in an experiment
    /// with trial parameters `params` (its robot's `v_max` and motion, `aem.action_tolerance`).
    pub fn new(
        shape: MlpShape,
        genome: &[f64],
        params: &TrialParams,
    ) -> Result<ExportedController, ExportError> {
        shape.check(genome)?;
        let spec = params.robot().spec();
        if shape.inputs() != spec.sensors() {
            return Err(ExportError::Inputs {
                network: shape.inputs(),
                robot: spec.name().into(),
                sensors: spec.sensors(),
            });
        }
        if let Some((index, &value)) = genome.iter().enumerate().find(|(_, w)| !w.is_finite()) {
            return Err(ExportError::NotFinite { index, value });
        }
        Ok(ExportedController {
            shape,
            weights: genome.to_vec(),
            v_max: params.robot().v_max(),
            motion: params.robot().motion(),
            tolerance: params.action_tolerance(),
            trial: *params,
            robot: KitRobot {
                name: params.robot().spec().name().into(),
                sensors: shape.inputs(),
                reading_max: params.robot().spec().reading_max(),
                v_max: params.robot().v_max(),
                wheel_base: params.robot().wheel_base(),
                dt: params.dt(),
                turn_deg: 30.0,
            },
        })
    }

    /// The same controller on `robot` (e.g. a robot file's values): a deployment kit then
    /// writes its reading scale, speed, wheel base, period and turn where the experiment's
    /// were, and `v_max` is the robot's. An error when its sensors are not the network's inputs
    /// or a quantity is not a positive number.
    pub fn for_robot(mut self, robot: KitRobot) -> Result<ExportedController, ExportError> {
        if robot.sensors != self.shape.inputs() {
            return Err(ExportError::SensorCount {
                robot: robot.name,
                sensors: robot.sensors,
                inputs: self.shape.inputs(),
            });
        }
        for (field, value) in [
            ("reading_max", robot.reading_max),
            ("v_max", robot.v_max),
            ("wheel_base", robot.wheel_base),
            ("dt", robot.dt),
            ("turn_deg", robot.turn_deg),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ExportError::RobotQuantity {
                    robot: robot.name,
                    field,
                    value,
                });
            }
        }
        self.v_max = robot.v_max;
        self.robot = robot;
        Ok(self)
    }

    /// The network's shape.
    pub fn shape(&self) -> MlpShape {
        self.shape
    }

    /// The robot the controller drives, as a deployment kit needs it.
    pub fn robot(&self) -> &KitRobot {
        &self.robot
    }

    /// The weights, in the genome's order.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The self-describing JSON document ([`ControllerDoc`], pretty-printed, ending in a
    /// newline).
    pub fn json(&self) -> String {
        let doc = ControllerDoc::of(self);
        serde_json::to_string_pretty(&doc).expect("a controller document serialises") + "\n"
    }

    /// The network as an ONNX model (opset 13, double precision; input `ir` `[N, 8]` raw
    /// readings, output `motors` `[N, 2]`), protobuf bytes.
    pub fn onnx(&self) -> Vec<u8> {
        onnx::model(self)
    }

    /// The C99 header and source ([`CSources`]).
    pub fn c(&self) -> CSources {
        c::sources(self)
    }
}
