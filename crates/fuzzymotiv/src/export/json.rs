//! The JSON form of an exported controller: [`ControllerDoc`] (schema in
//! docs/guide/real-robot.md).

use serde::{Deserialize, Serialize};

use super::ExportedController;
use crate::simulation::controller::OUTPUTS;
use crate::simulation::robot::Motion;

/// The document's `format` field.
pub const FORMAT: &str = "fuzzymotiv-controller";
/// The document's `format_version` field: 1 for this layout of the document.
pub const FORMAT_VERSION: u32 = 1;

/// An exported controller as a self-describing document: what a re-implementation needs (the
/// network, its activation, the input scaling, the outputs' meaning and the action labelling),
/// with the weights both as numbers and as exact IEEE-754 bit patterns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControllerDoc {
    /// Always [`FORMAT`].
    pub format: String,
    /// [`FORMAT_VERSION`].
    pub format_version: u32,
    /// The program that wrote it ([`crate::provenance`]).
    pub provenance: String,
    /// [`crate::MODEL_VERSION`] of that program.
    pub model_version: u32,
    /// The network.
    pub network: NetworkDoc,
    /// How sensor readings become the network's inputs.
    pub inputs: InputsDoc,
    /// What the network's outputs mean.
    pub outputs: OutputsDoc,
    /// How a step's action label is taken.
    pub actions: ActionsDoc,
}

/// `network`: the layout, activation and weights.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NetworkDoc {
    /// `"8-H-2"`.
    pub layout: String,
    /// 8.
    pub inputs: usize,
    /// H.
    pub hidden: usize,
    /// 2.
    pub outputs: usize,
    /// The activation of every hidden and output unit.
    pub activation: ActivationDoc,
    /// How a unit's weighted sum is added up.
    pub sum: String,
    /// The order of `weights`.
    pub weight_order: String,
    /// The weights, `H·9 + 2·(H + 1)` of them (shortest decimal that reads back exactly).
    pub weights: Vec<f64>,
    /// The same weights as IEEE-754 binary64 bit patterns, `"0x…"` (16 hex digits).
    pub weight_bits: Vec<String>,
}

/// `network.activation`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActivationDoc {
    /// `"logistic"`.
    pub name: String,
    /// `"1 / (1 + exp(-x))"`.
    pub formula: String,
    /// Which `exp`: the library's own, and where its exact operations are written down.
    pub exp: String,
}

/// `inputs`: sensor readings → network inputs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputsDoc {
    /// The robot's IR sensors (`ir0` …), in input order.
    pub sensors: Vec<String>,
    /// The largest reading: the robot's `reading_max` (1023 on the Khepera).
    pub reading_max: f64,
    /// The scaling formula.
    pub scaling: String,
}

/// `outputs`: motor outputs → wheel speeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputsDoc {
    /// `["mL", "mR"]`: left and right motor, each in [0, 1].
    pub motors: Vec<String>,
    /// `"s = (2m - 1) * v_max"`.
    pub wheel_speed: String,
    /// The robot's `v_max` (mm/s).
    pub v_max: f64,
}

/// `actions`: the step's action label.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActionsDoc {
    /// `"actions"` (the robot executes the label) or `"wheels"` (the label only records).
    pub motion: String,
    /// `aem.action_tolerance` τ.
    pub tolerance: f64,
    /// The labels in code order (0 straight, 1 left30, 2 right30, 3 turn180).
    pub labels: Vec<String>,
    /// Which speeds `sL`, `sR` (fractions of `v_max`) are labelled.
    pub labelled_speeds: String,
    /// The rule.
    pub rule: String,
    /// What the robot does with each label (with `actions` motion).
    pub effects: Vec<String>,
}

impl ControllerDoc {
    /// The document of `c`.
    pub fn of(c: &ExportedController) -> ControllerDoc {
        let h = c.shape.hidden();
        ControllerDoc {
            format: FORMAT.into(),
            format_version: FORMAT_VERSION,
            provenance: crate::provenance(),
            model_version: crate::MODEL_VERSION,
            network: NetworkDoc {
                layout: format!("{}-{h}-{OUTPUTS}", c.robot.sensors),
                inputs: c.robot.sensors,
                hidden: h,
                outputs: OUTPUTS,
                activation: ActivationDoc {
                    name: "logistic".into(),
                    formula: "1 / (1 + exp(-x))".into(),
                    exp: "fuzzymotiv's own exp (not libm's, so that every platform gives the same bits): Cody-Waite reduction x = k*ln2/128 + r with |r| <= ln2/256, a 128-entry double-double table of 2^(j/128) and a degree-5 polynomial, IEEE-754 binary64 + - * / only; fm_exp in `fuzzymotiv export --to c` is the same operations in the same order. Within 1 ulp of a correctly rounded exp, so a libm exp agrees to about 1e-15 but not bit for bit".into(),
                },
                sum: "each unit: bias, then + w_k * x_k for k = 1, 2, ... in order (binary64, round to nearest, no fused multiply-add); inputs exactly 0 may be skipped (same result)".into(),
                weight_order: format!(
                    "per hidden unit j = 0..{h}: [bias, w from input 0, ..., w from input {}]; then per output o = 0..2 (mL, mR): [bias, w from hidden 0, ..., w from hidden {}]",
                    c.robot.sensors - 1,
                    h - 1
                ),
                weights: c.weights.clone(),
                weight_bits: c.weights.iter().map(|w| format!("0x{:016x}", w.to_bits())).collect(),
            },
            inputs: InputsDoc {
                sensors: (0..c.robot.sensors).map(|k| format!("ir{k}")).collect(),
                reading_max: c.robot.reading_max,
                scaling: format!(
                    "x = reading / {max} (reading 0 gives exactly 0); readings are in the simulator's scale 0..{max} (clamp a larger one to {max})",
                    max = c.robot.reading_max
                ),
            },
            outputs: OutputsDoc {
                motors: vec!["mL".into(), "mR".into()],
                wheel_speed: "s = (2m - 1) * v_max (mm/s): 0.5 stops the wheel".into(),
                v_max: c.v_max,
            },
            actions: actions_doc(c.motion, c.tolerance),
        }
    }
}

fn actions_doc(motion: Motion, tolerance: f64) -> ActionsDoc {
    let (name, speeds) = match motion {
        Motion::Actions => (
            "actions",
            "sL = ((2 mL - 1) * v_max) / v_max, sR likewise (the commanded speeds as fractions of v_max; the simulator labels them after its wheel noise)",
        ),
        Motion::Wheels => (
            "wheels",
            "sL = 2 mL - 1, sR = 2 mR - 1 (the motor outputs before noise; the label only records the step, the wheels drive the robot)",
        ),
    };
    ActionsDoc {
        motion: name.into(),
        tolerance,
        labels: ["straight", "left30", "right30", "turn180"].map(String::from).to_vec(),
        labelled_speeds: speeds.into(),
        rule: "sL < 0 and sR < 0: turn180; else sR - sL > tolerance: left30; else sL - sR > tolerance: right30; else straight (comparisons strict)".into(),
        effects: [
            "straight: move v_max * dt forward",
            "left30: rotate on the spot by +30 degrees",
            "right30: rotate on the spot by -30 degrees",
            "turn180: rotate on the spot by 180 degrees",
        ]
        .map(String::from)
        .to_vec(),
    }
}
