//! The robot as data: a robot file (TOML) gives the body, the wheels, the control period, the
//! noise and the proximity sensors — where each sits, where it faces and how it responds
//! (docs/model.md, "Robots"; docs/guide/robots.md). Built-in robots are robot files kept in the
//! program ([`BUILTIN_ROBOTS`]): `khepera` (the paper's, the default), `epuck2`, `thymio2`.
//!
//! ```
//! use fuzzymotiv::simulation::RobotSpec;
//! let text = r#"
//! name = "disc"
//! radius = 40.0
//! wheel_base = 60.0
//! v_max = 100.0
//! reading_max = 4095
//! [[ray]]
//! distance_mm = [10, 30, 60]
//! reading = [4000, 1500, 100]
//! [[sensor]]
//! x = 38.0
//! y = 0.0
//! facing_deg = 0.0
//! "#;
//! let robot = RobotSpec::from_toml_str(text, "disc.toml").unwrap();
//! assert_eq!((robot.name(), robot.sensors()), ("disc", 1));
//! let outside = text.replace("x = 38.0", "x = 45.0");
//! let e = RobotSpec::from_toml_str(&outside, "disc.toml").unwrap_err();
//! assert_eq!((e.source_name.as_str(), e.field.as_str()), ("disc.toml", "sensor[0].x"));
//! ```

use std::collections::BTreeMap;
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use crate::params::{FieldError, Num, check};
use crate::simulation::sensor_layout::{MAX_SENSORS, SENSOR_LAYOUT, SensorMount};
use crate::simulation::sensor_table::{
    RawRay, RawSensorRays, RawSensorTable, SensorScale, SensorTable,
};

/// The built-in robots' names, the default first.
pub const BUILTIN_ROBOTS: [&str; 3] = ["khepera", "epuck2", "thymio2"];

/// The built-in robot files' texts, by name.
const BUILTIN_FILES: [(&str, &str); 3] = [
    ("khepera", include_str!("../../../../robots/khepera.toml")),
    ("epuck2", include_str!("../../../../robots/epuck2.toml")),
    ("thymio2", include_str!("../../../../robots/thymio2.toml")),
];

/// One sensor of a robot file, as written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSensor {
    /// A label (free text, e.g. the maker's name of the sensor).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Forward offset from the wheel axle's centre (mm).
    pub x: f64,
    /// Leftward offset (mm).
    pub y: f64,
    /// Direction it faces, degrees counter-clockwise from forward.
    pub facing_deg: f64,
    /// Its own rays, instead of the file's shared `[[ray]]`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ray: Vec<RawRay>,
}

/// A robot file as written (every length in mm, angle in degrees, time in s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRobotFile {
    /// [`RobotSpec::name`].
    pub name: String,
    /// A longer name (free text).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    /// Where the real body is not the disc (free text).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body_note: Option<String>,
    /// [`RobotSpec::radius`].
    pub radius: f64,
    /// [`RobotSpec::wheel_base`].
    pub wheel_base: f64,
    /// [`RobotSpec::v_max`].
    pub v_max: f64,
    /// [`RobotSpec::dt`]; default 0.1.
    #[serde(default = "default_dt")]
    pub dt: f64,
    /// [`RobotSpec::noise`]; default 0.06.
    #[serde(default = "default_noise")]
    pub noise: f64,
    /// [`RobotSpec::reading_max`].
    pub reading_max: f64,
    /// [`RobotSpec::linear_range`]; default 50.
    #[serde(default = "default_linear_range")]
    pub linear_range: f64,
    /// The rays of every sensor without its own.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ray: Vec<RawRay>,
    /// The sensors, in the order of the network's inputs.
    #[serde(default)]
    pub sensor: Vec<RawSensor>,
}

fn default_dt() -> f64 {
    0.1
}

fn default_noise() -> f64 {
    0.06
}

fn default_linear_range() -> f64 {
    50.0
}

/// A checked robot file: see each accessor for its unit and range.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotSpec {
    name: String,
    title: String,
    body_note: Option<String>,
    radius: f64,
    wheel_base: f64,
    v_max: f64,
    dt: f64,
    noise: f64,
    reading_max: f64,
    linear_range: f64,
    mounts: Vec<SensorMount>,
    labels: Vec<String>,
    table: &'static SensorTable,
}

impl RobotSpec {
    /// The built-in robot `name` ([`BUILTIN_ROBOTS`]), kept for the process.
    pub fn builtin(name: &str) -> Option<&'static RobotSpec> {
        let (_, text) = BUILTIN_FILES.iter().find(|(n, _)| *n == name)?;
        let spec = RobotSpec::from_toml_str(text, &format!("built-in robot {name}"))
            .expect("the built-in robot files are valid (tested)");
        Some(spec.intern())
    }

    /// The paper's Khepera, the default robot.
    pub fn khepera() -> &'static RobotSpec {
        Self::builtin("khepera").expect("khepera is built in")
    }

    /// The text of the built-in robot file `name`.
    pub fn builtin_text(name: &str) -> Option<&'static str> {
        BUILTIN_FILES.iter().find(|(n, _)| *n == name).map(|f| f.1)
    }

    /// Parses and checks a robot file's text; errors name `source_name` and the field.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<RobotSpec, FieldError> {
        // Its values are numbers and names, no whole numbers: their range is not asked.
        let raw: RawRobotFile = crate::params::plain::from_str(text, |_| "≥ 0".into())
            .map_err(|e| FieldError::new(e.field(text), e.message()).in_source(source_name))?;
        RobotSpec::from_raw(&raw).map_err(|e| e.in_source(source_name))
    }

    /// Checks a robot file as written, naming the first wrong field.
    pub fn from_raw(raw: &RawRobotFile) -> Result<RobotSpec, FieldError> {
        check_name(&raw.name)?;
        check_body(raw)?;
        check(
            (1..=MAX_SENSORS).contains(&raw.sensor.len()),
            "sensor",
            || {
                format!(
                    "a robot has 1 to {MAX_SENSORS} sensors ([[sensor]] entries), got {}",
                    raw.sensor.len()
                )
            },
        )?;
        for (i, s) in raw.sensor.iter().enumerate() {
            check_mount(s, i, raw.radius)?;
        }
        let table = sensor_table(raw)?;
        Ok(RobotSpec {
            name: raw.name.clone(),
            title: raw.title.clone().unwrap_or_else(|| raw.name.clone()),
            body_note: raw.body_note.clone(),
            radius: raw.radius,
            wheel_base: raw.wheel_base,
            v_max: raw.v_max,
            dt: raw.dt,
            noise: raw.noise,
            reading_max: raw.reading_max,
            linear_range: raw.linear_range,
            mounts: (raw.sensor.iter())
                .map(|s| SensorMount {
                    x: s.x,
                    y: s.y,
                    facing_deg: s.facing_deg,
                })
                .collect(),
            labels: (raw.sensor.iter().enumerate())
                .map(|(i, s)| s.name.clone().unwrap_or_else(|| format!("sensor {i}")))
                .collect(),
            table: table.intern(),
        })
    }

    /// This robot, kept for the rest of the process: equal robots share one copy.
    pub fn intern(self) -> &'static RobotSpec {
        static ROBOTS: Mutex<Vec<&'static RobotSpec>> = Mutex::new(Vec::new());
        let mut robots = ROBOTS.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(r) = robots.iter().find(|r| ***r == self) {
            return r;
        }
        let r: &'static RobotSpec = Box::leak(Box::new(self));
        robots.push(r);
        r
    }

    /// The robot's name (a plain name: letters, digits, `_` and `-`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// A longer name (the file's `title`, else its name).
    pub fn title(&self) -> &str {
        &self.title
    }

    /// Where the real body is not the disc the simulator collides, if the file says.
    pub fn body_note(&self) -> Option<&str> {
        self.body_note.as_deref()
    }

    /// Radius of the body's disc (mm), in (0, 500]; every sensor sits inside it.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Distance between the wheels (mm), in (0, 2 × radius].
    pub fn wheel_base(&self) -> f64 {
        self.wheel_base
    }

    /// Largest wheel speed (mm/s), in (0, 10000].
    pub fn v_max(&self) -> f64 {
        self.v_max
    }

    /// Control period (s), in (0, 10]: a config's `trial.dt` when it gives none.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Multiplicative noise on readings and wheels, in [0, 0.5]: a config's `trial.noise`
    /// when it gives none.
    pub fn noise(&self) -> f64 {
        self.noise
    }

    /// The largest reading (a whole number in 1..=65535): a network input is
    /// `reading / reading_max`.
    pub fn reading_max(&self) -> f64 {
        self.reading_max
    }

    /// Range of the `linear` sensor model (mm), in (0, 1000].
    pub fn linear_range(&self) -> f64 {
        self.linear_range
    }

    /// Number of proximity sensors (network inputs), 1 to [`MAX_SENSORS`].
    pub fn sensors(&self) -> usize {
        self.mounts.len()
    }

    /// Where each sensor sits and faces, in input order.
    pub fn mounts(&self) -> &[SensorMount] {
        &self.mounts
    }

    /// Each sensor's label, in input order.
    pub fn labels(&self) -> &[String] {
        &self.labels
    }

    /// The sensors' response (the `sampled` model's rays).
    pub fn table(&self) -> &'static SensorTable {
        self.table
    }

    /// The scale a sensor table for this robot is checked against.
    pub fn scale(&self) -> SensorScale {
        SensorScale {
            sensors: self.sensors(),
            reading_max: self.reading_max,
        }
    }

    /// Whether this is the paper's Khepera layout and response (the classic simulator's
    /// built-in tables: [`crate::simulation::SensorModel::Sampled`]'s own code path).
    pub(crate) fn is_khepera_layout(&self) -> bool {
        self.mounts == SENSOR_LAYOUT
            && self.reading_max == crate::simulation::sensor_layout::SENSOR_MAX
            && *self.table == SensorTable::khepera()
            && self.linear_range == crate::simulation::sensor_layout::LINEAR_RANGE
    }
}

/// Checks a robot's name: a plain name, 1 to 40 of `a-z`, `A-Z`, `0-9`, `_`, `-`.
fn check_name(name: &str) -> Result<(), FieldError> {
    let plain = name
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    check(plain && (1..=40).contains(&name.len()), "name", || {
        format!(
            "must be a plain name of 1 to 40 letters, digits, _ or - (it names the robot in records), got \"{name}\""
        )
    })
}

/// Checks the body, wheels, period, noise and reading scale.
fn check_body(raw: &RawRobotFile) -> Result<(), FieldError> {
    let within = |v: f64, lo: f64, hi: f64| v.is_finite() && v > lo && v <= hi;
    check(within(raw.radius, 0.0, 500.0), "radius", || {
        format!(
            "must be a body radius in (0, 500] mm, got {}",
            Num(raw.radius)
        )
    })?;
    check(
        within(raw.wheel_base, 0.0, 2.0 * raw.radius),
        "wheel_base",
        || {
            format!(
                "must be in (0, {}] mm (the wheels sit on the body: at most twice radius), got {}",
                Num(2.0 * raw.radius),
                Num(raw.wheel_base)
            )
        },
    )?;
    check(within(raw.v_max, 0.0, 10_000.0), "v_max", || {
        format!(
            "must be a wheel speed in (0, 10000] mm/s, got {}",
            Num(raw.v_max)
        )
    })?;
    check(within(raw.dt, 0.0, 10.0), "dt", || {
        format!("must be a control period in (0, 10] s, got {}", Num(raw.dt))
    })?;
    check(
        raw.noise.is_finite() && (0.0..=0.5).contains(&raw.noise),
        "noise",
        || format!("must be a noise level in [0, 0.5], got {}", Num(raw.noise)),
    )?;
    let step = raw.v_max * raw.dt * (1.0 + raw.noise);
    check(step < raw.radius, "v_max", || {
        format!(
            "one step may move the robot {:.1} mm (v_max × dt × (1 + noise)), which must stay below the body radius {} mm so it cannot pass through walls; use a smaller dt or v_max",
            step,
            Num(raw.radius)
        )
    })?;
    check(
        within(raw.reading_max, 0.0, 65_535.0) && raw.reading_max.fract() == 0.0,
        "reading_max",
        || {
            format!(
                "must be a whole number in 1..=65535 (the largest reading), got {}",
                Num(raw.reading_max)
            )
        },
    )?;
    check(
        within(raw.linear_range, 0.0, 1000.0),
        "linear_range",
        || {
            format!(
                "must be a range in (0, 1000] mm, got {}",
                Num(raw.linear_range)
            )
        },
    )
}

/// Checks sensor `i`'s position (inside the body) and facing.
fn check_mount(s: &RawSensor, i: usize, radius: f64) -> Result<(), FieldError> {
    let f = |name: &str| format!("sensor[{i}].{name}");
    check(s.x.is_finite(), &f("x"), || {
        format!("must be a number (mm), got {}", Num(s.x))
    })?;
    check(s.y.is_finite(), &f("y"), || {
        format!("must be a number (mm), got {}", Num(s.y))
    })?;
    let from_centre = s.x.hypot(s.y);
    let field = if s.x.abs() >= s.y.abs() {
        f("x")
    } else {
        f("y")
    };
    check(from_centre <= radius + 1e-9, &field, || {
        format!(
            "sensor {i} at ({}, {}) is {from_centre:.1} mm from the centre, outside the body (radius {} mm): a sensor sits on or inside the body",
            Num(s.x),
            Num(s.y),
            Num(radius)
        )
    })?;
    check(
        s.facing_deg.is_finite() && (-360.0..=360.0).contains(&s.facing_deg),
        &f("facing_deg"),
        || {
            format!(
                "must be an angle in [-360, 360] degrees counter-clockwise from forward, got {}",
                Num(s.facing_deg)
            )
        },
    )
}

/// The sensors' response as a sensor table: the shared `[[ray]]` and each sensor's own rays;
/// errors name the robot file's fields (`ray[k]…`, `sensor[i].ray[k]…`).
fn sensor_table(raw: &RawRobotFile) -> Result<SensorTable, FieldError> {
    let sensor: BTreeMap<String, RawSensorRays> = (raw.sensor.iter().enumerate())
        .filter(|(_, s)| !s.ray.is_empty())
        .map(|(i, s)| (i.to_string(), RawSensorRays { ray: s.ray.clone() }))
        .collect();
    let table = RawSensorTable {
        ray: raw.ray.clone(),
        sensor,
        ..RawSensorTable::default()
    };
    let scale = SensorScale {
        sensors: raw.sensor.len(),
        reading_max: raw.reading_max,
    };
    SensorTable::from_raw_for(&table, scale).map_err(|e| {
        let field = match e.field.strip_prefix("sensor.") {
            Some(rest) => match rest.split_once('.') {
                Some((i, tail)) => format!("sensor[{i}].{tail}"),
                None if raw.ray.is_empty() => format!("sensor[{rest}].ray"),
                None => format!("sensor[{rest}]"),
            },
            None => e.field.clone(),
        };
        FieldError::new(field, e.reason)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const DISC: &str = "name = \"disc\"\nradius = 40.0\nwheel_base = 60.0\nv_max = 100.0\nreading_max = 4095\n[[ray]]\ndistance_mm = [10, 30, 60]\nreading = [4000, 1500, 100]\n[[sensor]]\nx = 38.0\ny = 0.0\nfacing_deg = 0.0\n[[sensor]]\nx = 0.0\ny = 38.0\nfacing_deg = 90.0\n";

    fn field_of(text: &str) -> String {
        RobotSpec::from_toml_str(text, "r.toml").unwrap_err().field
    }

    #[test]
    fn the_built_in_khepera_is_the_classic_simulators_robot() {
        let k = RobotSpec::khepera();
        assert!(k.is_khepera_layout());
        assert_eq!(k.mounts(), SENSOR_LAYOUT);
        assert_eq!((k.radius(), k.wheel_base(), k.v_max()), (27.5, 53.0, 80.0));
        assert_eq!((k.dt(), k.noise(), k.reading_max()), (0.1, 0.06, 1023.0));
    }

    #[test]
    fn every_built_in_robot_file_is_valid() {
        for name in BUILTIN_ROBOTS {
            let r = RobotSpec::builtin(name).unwrap();
            assert_eq!(r.name(), name);
            assert!(std::ptr::eq(r, RobotSpec::builtin(name).unwrap()));
        }
        assert!(RobotSpec::builtin("khepera9").is_none());
    }

    #[test]
    fn hostile_robot_files_name_the_field() {
        let cases = [
            ("x = 38.0", "x = 45.0", "sensor[0].x"),
            ("radius = 40.0", "radius = -1.0", "radius"),
            ("wheel_base = 60.0", "wheel_base = 100.0", "wheel_base"),
            ("v_max = 100.0", "v_max = 500.0", "v_max"),
            ("reading_max = 4095", "reading_max = 4095.5", "reading_max"),
            ("[4000, 1500, 100]", "[4000, 1500, 1600]", "ray[0].reading"),
            ("[4000, 1500, 100]", "[5000, 1500, 100]", "ray[0].reading"),
            ("name = \"disc\"", "name = \"my disc\"", "name"),
            (
                "facing_deg = 90.0",
                "facing_deg = nan",
                "sensor[1].facing_deg",
            ),
        ];
        for (from, to, field) in cases {
            assert_eq!(field_of(&DISC.replacen(from, to, 1)), field, "{to}");
        }
        let no_sensors = DISC.split("[[sensor]]").next().unwrap();
        assert_eq!(field_of(no_sensors), "sensor");
        let no_rays = DISC.replace(
            "[[ray]]\ndistance_mm = [10, 30, 60]\nreading = [4000, 1500, 100]\n",
            "",
        );
        assert_eq!(field_of(&no_rays), "sensor[0].ray");
        let own = DISC.replace(
            "facing_deg = 90.0\n",
            "facing_deg = 90.0\n[[sensor.ray]]\ndistance_mm = [5, 1]\nreading = [9, 1]\n",
        );
        assert_eq!(field_of(&own), "sensor[1].ray[0].distance_mm");
        assert_eq!(field_of(&format!("{DISC}colour = 1\n")), "sensor[1].colour");
        assert_eq!(field_of(&format!("colour = 1\n{DISC}")), "colour");
        assert_eq!(
            field_of(&DISC.replace("wheel_base = 60.0\n", "")),
            "wheel_base"
        );
    }

    #[test]
    fn a_sensor_reads_its_own_rays_or_the_shared_ones() {
        let own = DISC.replace(
            "facing_deg = 90.0\n",
            "facing_deg = 90.0\n[[sensor.ray]]\ndistance_mm = [5, 50]\nreading = [900, 0]\n",
        );
        let r = RobotSpec::from_toml_str(&own, "r.toml").unwrap();
        assert_eq!(r.table().rays_of(0)[0].samples()[0], (10.0, 4000.0));
        assert_eq!(r.table().rays_of(1)[0].samples()[0], (5.0, 900.0));
        assert_eq!(r.labels(), ["sensor 0", "sensor 1"]);
    }
}
