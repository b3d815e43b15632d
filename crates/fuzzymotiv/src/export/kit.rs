//! Deployment kits: an exported controller as the files of one robot's firmware project
//! (`fuzzymotiv export RUN --to c --target ROBOT`), with what the kit needs to know of the
//! robot the controller was evolved for ([`KitRobot`]).

/// What a deployment kit needs to know of the robot the controller drives: how its readings
/// become the network's inputs and its outputs wheel speeds and actions.
#[derive(Debug, Clone, PartialEq)]
pub struct KitRobot {
    /// The robot's name (a built-in robot's, e.g. `khepera`, `epuck2`, `thymio2`, or the
    /// robot file's `name`).
    pub name: String,
    /// Number of proximity sensors = network inputs (1–24).
    pub sensors: usize,
    /// The simulator's largest reading: an input is `min(reading, reading_max) / reading_max`.
    pub reading_max: f64,
    /// Maximum wheel speed (mm/s): a motor output m gives the wheel speed `(2m − 1)·v_max`.
    pub v_max: f64,
    /// Distance between the wheels (mm).
    pub wheel_base: f64,
    /// Control period (s): the network runs once per period.
    pub dt: f64,
    /// Degrees a `left30`/`right30` action rotates on the spot (`actions` motion).
    pub turn_deg: f64,
}

impl KitRobot {
    /// Length of a straight action (mm): `v_max · dt` (8 mm for the paper's Khepera).
    pub fn straight_step(&self) -> f64 {
        self.v_max * self.dt
    }
}

/// One file of a kit: its name (relative to the kit's directory) and contents.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KitFile {
    /// File name, relative to the kit's directory (may contain `/`).
    pub name: String,
    /// The file's bytes.
    pub contents: Vec<u8>,
}

impl KitFile {
    /// A text file `name` holding `text`.
    pub fn text(name: &str, text: String) -> KitFile {
        KitFile {
            name: name.to_string(),
            contents: text.into_bytes(),
        }
    }
}

/// A deployment kit: its files, and a few lines a front end prints after writing them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Kit {
    /// The files, in the order they are written.
    pub files: Vec<KitFile>,
    /// What to tell the user (how to build and load the kit).
    pub notes: Vec<String>,
}
