//! The robots a lab run may drive: the built-in robot files
//! ([`fuzzymotiv::simulation::BUILTIN_ROBOTS`]: khepera, epuck2, thymio2), listed for the
//! page's robot picker with what it draws of each (the body's disc, each sensor's mount, facing
//! and reach). A run names one as a config does (`robot = "epuck2"`); robot files by path are
//! `fuzzymotiv run`'s, not the lab's (a path would reach outside the lab's directory).

use fuzzymotiv::params::joined_list;
use fuzzymotiv::simulation::{BUILTIN_ROBOTS, RobotSpec, SensorModel, rays};
use serde_json::{Value, json};

use crate::errors::ApiError;

/// The robot of a run that names none: the paper's Khepera.
pub const DEFAULT_ROBOT: &str = BUILTIN_ROBOTS[0];

/// Every built-in robot as the page lists and draws it, the default first.
pub fn list() -> Vec<Value> {
    BUILTIN_ROBOTS
        .iter()
        .filter_map(|name| RobotSpec::builtin(name))
        .map(view)
        .collect()
}

/// One robot: its name and title, sensor count, body radius (mm), largest reading, what the
/// file says of the real body (`body_note`, or null) and its sensors in input order (`layout`:
/// `x`, `y` in mm from the wheel axle's centre, x forward and y left; `facing_deg`
/// counter-clockwise from forward; `range`, the farthest wall (mm) the sensor's axis ray reads
/// under the default sensor model; `label`).
fn view(spec: &RobotSpec) -> Value {
    let axes = rays(SensorModel::default(), spec);
    let layout: Vec<Value> = (spec.mounts().iter())
        .zip(spec.labels())
        .zip(&axes)
        .map(|((m, label), ray)| {
            json!({ "x": m.x, "y": m.y, "facing_deg": m.facing_deg, "range": ray[0].range(),
                    "label": label })
        })
        .collect();
    json!({ "name": spec.name(), "title": spec.title(), "sensors": spec.sensors(),
            "radius": spec.radius(), "reading_max": spec.reading_max(),
            "body_note": spec.body_note(), "layout": layout })
}

/// Whether `name` is a robot a lab run may name; otherwise a 400 naming it, the field
/// (`source`'s `robot`) and the choices.
pub fn check(name: &str, source: &str) -> Result<(), ApiError> {
    if RobotSpec::builtin(name).is_some() {
        return Ok(());
    }
    Err(ApiError::bad(format!(
        "{source}: field `robot`: `{name}` is not a built-in robot ({}); the lab runs the built-in robots (a robot file runs with `fuzzymotiv run`)",
        joined_list(&BUILTIN_ROBOTS, "or")
    )))
}
