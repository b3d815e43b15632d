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
pub(crate) mod json;
pub(crate) mod kit;
pub(crate) mod onnx;

pub use aseba::thymio2_kit;
pub use c::CSources;
pub use json::{ControllerDoc, FORMAT, FORMAT_VERSION};
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
    /// A weight is NaN or infinite (no evolved genome has one).
    #[error("weight {index} is {value}, not a finite number")]
    NotFinite {
        /// The weight's index in the genome (0-based).
        index: usize,
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
        if let Some((index, &value)) = genome.iter().enumerate().find(|(_, w)| !w.is_finite()) {
            return Err(ExportError::NotFinite { index, value });
        }
        Ok(ExportedController {
            shape,
            weights: genome.to_vec(),
            v_max: params.robot().v_max(),
            motion: params.robot().motion(),
            tolerance: params.action_tolerance(),
            robot: KitRobot {
                name: "khepera".into(),
                sensors: shape.inputs(),
                reading_max: crate::simulation::SENSOR_MAX,
                v_max: params.robot().v_max(),
                wheel_base: params.robot().wheel_base(),
                dt: params.dt(),
                turn_deg: 30.0,
            },
        })
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
