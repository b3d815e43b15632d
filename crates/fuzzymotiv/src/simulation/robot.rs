//! The robot's body: pose, physical parameters (from its robot file) and the two motion models — the paper's
//! executed actions ([`Motion::Actions`]) and continuous differential drive ([`Motion::Wheels`]).

use serde::{Deserialize, Serialize};

use crate::params::{FieldError, Num, check};
use crate::simulation::geom::Vec2;
use crate::simulation::math;
use crate::simulation::robot_spec::RobotSpec;
use crate::simulation::sensor_layout::SensorMount;

/// Default signed-speed difference (fractions of `v_max`) separating a turn from a straight
/// step (config key `aem.action_tolerance`).
pub const DEFAULT_ACTION_TOLERANCE: f64 = 0.25;

/// Where the robot is: centre `(x, y)` in mm and `heading` in radians (counter-clockwise from +x,
/// wrapped to (−π, π]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Centre x (mm).
    pub x: f64,
    /// Centre y (mm).
    pub y: f64,
    /// Heading (rad).
    pub heading: f64,
}

impl Pose {
    /// The pose at which the sensor at `mount` faces a wall along x = `wall_x` (to its east)
    /// head-on, `gap` mm from it along the sensor's axis, the sensor at height `y`: how a bench
    /// measures a sensor's response (`fuzzymotiv calibrate`), and how the response is drawn
    /// against Enki's.
    pub fn facing_wall(mount: &SensorMount, wall_x: f64, y: f64, gap: f64) -> Pose {
        let heading = -mount.facing_deg.to_radians();
        let (sin, cos) = heading.sin_cos();
        let x = wall_x - gap - (mount.x * cos - mount.y * sin);
        Pose::new(x, y - (mount.x * sin + mount.y * cos), heading)
    }

    /// A pose; the heading is wrapped to (−π, π].
    pub fn new(x: f64, y: f64, heading: f64) -> Self {
        Self {
            x,
            y,
            heading: wrap_angle(heading),
        }
    }

    /// The centre as a vector.
    #[inline]
    pub fn position(&self) -> Vec2 {
        Vec2::new(self.x, self.y)
    }
}

/// Wraps an angle to (−π, π].
///
/// ```
/// use fuzzymotiv::simulation::wrap_angle;
/// use std::f64::consts::PI;
/// assert!((wrap_angle(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-12);
/// ```
#[inline]
pub fn wrap_angle(theta: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    // Fast path for the usual case (a heading plus one step's turn): for |θ| < 2π the remainder
    // below is θ itself, so skipping it gives bit-identical results without a call to fmod.
    if theta.abs() < TAU {
        return if theta > PI {
            theta - TAU
        } else if theta <= -PI {
            theta + TAU
        } else {
            theta
        };
    }
    let mut t = theta % TAU;
    if t > PI {
        t -= TAU;
    } else if t <= -PI {
        t += TAU;
    }
    t
}

/// `[robot]` in a config, as written: which robot (`file`: a built-in robot's name or a robot
/// file's path; the Khepera when absent) and what of its file the config overrides; see
/// [`Robot`] for each field's unit and range; [`Robot::from_raw`] checks them. A config may
/// also name the robot alone: `robot = "epuck2"`.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct RawRobot {
    /// A built-in robot ([`crate::simulation::BUILTIN_ROBOTS`]) or a robot file's path;
    /// `None`: the paper's Khepera.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// [`Robot::radius`]; `None`: the robot file's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// [`Robot::wheel_base`]; `None`: the robot file's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wheel_base: Option<f64>,
    /// [`Robot::v_max`]; `None`: the robot file's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub v_max: Option<f64>,
    /// [`Robot::motion`].
    pub motion: Motion,
}

/// `[robot]` as a table (the fields of [`RawRobot`]).
#[derive(Deserialize)]
#[serde(default, deny_unknown_fields)]
struct RawRobotTable {
    file: Option<String>,
    radius: Option<f64>,
    wheel_base: Option<f64>,
    v_max: Option<f64>,
    motion: Motion,
}

impl Default for RawRobotTable {
    fn default() -> Self {
        let RawRobot {
            file,
            radius,
            wheel_base,
            v_max,
            motion,
        } = RawRobot::default();
        RawRobotTable {
            file,
            radius,
            wheel_base,
            v_max,
            motion,
        }
    }
}

impl<'de> Deserialize<'de> for RawRobot {
    /// A table of [`RawRobot`]'s fields, or a string naming the robot (`robot = "epuck2"`).
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Form;
        impl<'de> serde::de::Visitor<'de> for Form {
            type Value = RawRobot;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a robot's name or robot file (\"epuck2\"), or a [robot] table")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<RawRobot, E> {
                Ok(RawRobot {
                    file: Some(v.to_string()),
                    ..RawRobot::default()
                })
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<RawRobot, A::Error> {
                let de = serde::de::value::MapAccessDeserializer::new(map);
                let t = RawRobotTable::deserialize(de)?;
                Ok(RawRobot {
                    file: t.file,
                    radius: t.radius,
                    wheel_base: t.wheel_base,
                    v_max: t.v_max,
                    motion: t.motion,
                })
            }
        }
        d.deserialize_any(Form)
    }
}

impl RawRobot {
    /// The same, every value the config leaves to the robot file taken from `spec`, and the
    /// paper's Khepera named by no file (the same run as a config that names none).
    pub fn resolved(&self, spec: &RobotSpec) -> RawRobot {
        let file = match self.file.as_deref() {
            Some("khepera") | None => None,
            Some(f) => Some(f.to_string()),
        };
        RawRobot {
            file,
            radius: Some(self.radius.unwrap_or(spec.radius())),
            wheel_base: Some(self.wheel_base.unwrap_or(spec.wheel_base())),
            v_max: Some(self.v_max.unwrap_or(spec.v_max())),
            motion: self.motion,
        }
    }
}

/// A robot's body, wheels and sensors and its motion model, checked (see docs/model.md): its
/// robot file ([`RobotSpec`]) with what a config overrides, built by [`Robot::from_raw`] (or
/// [`Robot::default`], the paper's Khepera). All lengths in mm, speeds in mm/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Robot {
    radius: f64,
    wheel_base: f64,
    v_max: f64,
    motion: Motion,
    spec: &'static RobotSpec,
}

impl Robot {
    /// Body radius (mm); the robot file's (Khepera: 27.5, a 55 mm body) unless the config
    /// sets `robot.radius`; at least the farthest sensor's distance from the centre, at most
    /// 500.
    #[inline]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Distance between the wheels (mm); Khepera 53 (used by `wheels` motion only); range
    /// (0, 1000].
    #[inline]
    pub fn wheel_base(&self) -> f64 {
        self.wheel_base
    }

    /// Maximum wheel speed (mm/s); Khepera 80; > 0, finite. With `actions` motion a straight
    /// step moves `v_max · dt` (8 mm on the Khepera).
    #[inline]
    pub fn v_max(&self) -> f64 {
        self.v_max
    }

    /// How the network's motor commands move the robot; default `"actions"` (the paper's).
    #[inline]
    pub fn motion(&self) -> Motion {
        self.motion
    }

    /// The robot file: name, sensors and their response, reading scale.
    #[inline]
    pub fn spec(&self) -> &'static RobotSpec {
        self.spec
    }

    /// Number of proximity sensors (the network's inputs).
    #[inline]
    pub fn sensors(&self) -> usize {
        self.spec.sensors()
    }

    /// The same robot with body radius `radius` (for perturbation studies and randomised
    /// trials; checked by the caller).
    pub(crate) fn with_radius(self, radius: f64) -> Robot {
        Robot { radius, ..self }
    }

    /// Checks `[robot]` for the robot file `spec` against the ranges documented on the
    /// accessors, naming the first field out of range as `robot.FIELD`.
    pub fn from_raw(raw: &RawRobot, spec: &'static RobotSpec) -> Result<Robot, FieldError> {
        let raw = raw.resolved(spec);
        let (radius, wheel_base, v_max) = (
            raw.radius.unwrap_or_default(),
            raw.wheel_base.unwrap_or_default(),
            raw.v_max.unwrap_or_default(),
        );
        check(v_max.is_finite() && v_max > 0.0, "robot.v_max", || {
            format!("must be a speed > 0 (mm/s), got {}", Num(v_max))
        })?;
        let allowed = RadiusRange::of(spec);
        check(allowed.contains(radius), "robot.radius", || {
            allowed.reason("got", radius)
        })?;
        check(
            wheel_base.is_finite() && wheel_base > 0.0 && wheel_base <= 1000.0,
            "robot.wheel_base",
            || format!("must be in (0, 1000] mm, got {}", Num(wheel_base)),
        )?;
        Ok(Robot {
            radius,
            wheel_base,
            v_max,
            motion: raw.motion,
            spec,
        })
    }
}

/// The body radii a robot file's robot may have: from the farthest sensor's distance from the
/// centre (the sensors must sit inside the body) to 80 mm for the Khepera's layout, 500 mm for
/// another.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RadiusRange {
    /// The farthest IR sensor's distance from the centre (mm).
    mounts: f64,
    /// The largest radius (mm).
    most: f64,
    /// The robot file's name.
    robot: &'static str,
}

impl RadiusRange {
    /// The radii the robot of `spec` may have.
    pub(crate) fn of(spec: &'static RobotSpec) -> RadiusRange {
        let mounts = (spec.mounts().iter())
            .map(|m| m.x.hypot(m.y))
            .fold(0.0, f64::max);
        let most = if spec.is_khepera_layout() {
            80.0
        } else {
            500.0
        };
        RadiusRange {
            mounts,
            most,
            robot: spec.name(),
        }
    }

    /// Whether `radius` is one of them.
    pub(crate) fn contains(&self, radius: f64) -> bool {
        radius.is_finite() && radius >= self.mounts && radius <= self.most
    }

    /// What a radius must be, and the value `radius` given, introduced by `got` ("got", or
    /// "got an end" for a range's end).
    pub(crate) fn reason(&self, got: &str, radius: f64) -> String {
        let RadiusRange {
            mounts,
            most,
            robot,
        } = *self;
        format!(
            "must be in [{mounts:.2}, {most}] mm (the {robot}'s IR sensors sit up to {mounts:.2} mm from the centre), {got} {}",
            Num(radius)
        )
    }
}

/// How the network's two motor commands move the robot (config `[robot] motion`).
///
/// ```
/// use fuzzymotiv::simulation::Action;
/// use fuzzymotiv::simulation::{Compass, Motion, Pose};
/// let compass = Compass::new(0.0);
/// let home = Pose::new(40.0, 40.0, 0.0);
/// // A straight action moves 8 mm along the heading; a turn rotates on the spot.
/// let (p, dir) = Motion::execute(home, 0, Action::Straight, 8.0, &compass);
/// assert_eq!((p.x, p.y, dir), (48.0, 40.0, 0));
/// let (q, dir) = Motion::execute(home, 0, Action::Left30, 8.0, &compass);
/// assert_eq!((q.x, q.y, q.heading, dir), (40.0, 40.0, std::f64::consts::FRAC_PI_6, 1));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Motion {
    /// The paper's robot (default): each step's noisy wheel speeds are labelled as one of the
    /// four AEM actions and the robot executes it exactly: `straight` moves `v_max · dt`
    /// forward, `left30` / `right30` rotate on the spot by ±30°, `turn180` by 180°. The
    /// heading stays on the 30° grid from the home heading; one step uses one unit of energy.
    #[default]
    Actions,
    /// Continuous differential drive (the first release's model): the noisy wheel speeds are
    /// integrated exactly along the arc; the action label only records the step, taken from
    /// the motor outputs before noise; energy is (|sL| + |sR|) / (2·v_max).
    Wheels,
}

impl Motion {
    /// The action label of a step. `motors` are the network outputs `mL, mR` ∈ [0, 1];
    /// `noisy` the wheel speeds after noise (mm/s). `actions` motion labels the noisy speeds
    /// as fractions of `v_max` (they drive the robot); `wheels` labels the motor outputs
    /// before noise, as the first release did.
    #[inline]
    pub fn label(self, motors: [f64; 2], noisy: [f64; 2], v_max: f64, tolerance: f64) -> Action {
        match self {
            Motion::Actions => Action::from_speeds(noisy[0] / v_max, noisy[1] / v_max, tolerance),
            Motion::Wheels => Action::from_motors(motors[0], motors[1], tolerance),
        }
    }

    /// Energy used by an executed step, in units where 1 is a full step: one unit per action
    /// with `actions` motion; `(|sL| + |sR|) / (2·v_max)` of the commanded speeds `speeds`
    /// (before noise) with `wheels` motion.
    #[inline]
    pub fn energy(self, speeds: [f64; 2], v_max: f64) -> f64 {
        match self {
            Motion::Actions => 1.0,
            Motion::Wheels => (speeds[0].abs() + speeds[1].abs()) / (2.0 * v_max),
        }
    }

    /// Executes `action` from `pose`, whose heading is `compass`'s direction `dir` (0..12):
    /// the candidate pose and its direction. `step` is the length of a straight move (mm).
    #[inline]
    pub fn execute(
        pose: Pose,
        dir: usize,
        action: Action,
        step: f64,
        compass: &Compass,
    ) -> (Pose, usize) {
        let dir = match action {
            Action::Straight => {
                let p = Pose {
                    x: pose.x + step * compass.cos[dir],
                    y: pose.y + step * compass.sin[dir],
                    heading: pose.heading,
                };
                return (p, dir);
            }
            Action::Left30 => (dir + 1) % 12,
            Action::Right30 => (dir + 11) % 12,
            Action::Turn180 => (dir + 6) % 12,
        };
        let p = Pose {
            heading: compass.heading[dir],
            ..pose
        };
        (p, dir)
    }
}

/// The twelve headings of the 30° grid from a home heading, with their cosines and sines, so
/// that `actions` motion needs no trigonometry per step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compass {
    /// `heading[k]` = home heading + k·30°, wrapped to (−π, π] (rad).
    pub heading: [f64; 12],
    /// Cosine of each heading.
    pub cos: [f64; 12],
    /// Sine of each heading.
    pub sin: [f64; 12],
}

/// `k·30°` for k = 0..12, wrapped to (−π, π], each the correctly rounded double.
const GRID_ANGLES: [f64; 12] = {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_3, FRAC_PI_6, PI};
    [
        0.0,
        FRAC_PI_6,
        FRAC_PI_3,
        FRAC_PI_2,
        2.094_395_102_393_195_7, // 2π/3
        2.617_993_877_991_494_4, // 5π/6
        PI,
        -2.617_993_877_991_494_4,
        -2.094_395_102_393_195_7,
        -FRAC_PI_2,
        -FRAC_PI_3,
        -FRAC_PI_6,
    ]
};

impl Compass {
    /// The grid from `home_heading` (rad). Direction 0 is the home heading itself. When the
    /// home heading is itself a multiple of 30° (every built-in room's is 0), every heading,
    /// cosine and sine is the correctly rounded value, so no trigonometry is computed;
    /// otherwise cosines and sines are computed once here (with the project's own `math::sin`,
    /// `math::cos`).
    pub fn new(home_heading: f64) -> Compass {
        if let Some(k0) = GRID_ANGLES.iter().position(|&a| a == home_heading) {
            let at = |k: usize| (k0 + k) % 12;
            return Compass {
                heading: std::array::from_fn(|k| GRID_ANGLES[at(k)]),
                cos: std::array::from_fn(|k| math::GRID_30[at(k)].0),
                sin: std::array::from_fn(|k| math::GRID_30[at(k)].1),
            };
        }
        let heading: [f64; 12] = std::array::from_fn(|k| {
            if k == 0 {
                home_heading
            } else {
                wrap_angle(home_heading + GRID_ANGLES[k])
            }
        });
        Compass {
            heading,
            cos: heading.map(math::cos),
            sin: heading.map(math::sin),
        }
    }
}

/// The Khepera's body radius (mm), also used to validate room files.
pub const KHEPERA_RADIUS: f64 = 27.5;

impl Default for Robot {
    /// The paper's Khepera with `actions` motion.
    fn default() -> Self {
        let spec = RobotSpec::khepera();
        Self {
            radius: spec.radius(),
            wheel_base: spec.wheel_base(),
            v_max: spec.v_max(),
            motion: Motion::Actions,
            spec,
        }
    }
}

/// Differential-drive kinematics: the pose after `dt` seconds with wheel speeds `s_left`,
/// `s_right` (mm/s), integrated exactly along the arc (a straight line when the speeds are
/// equal).
///
/// ```
/// use fuzzymotiv::simulation::{Pose, drive};
/// // Both wheels at 80 mm/s for 0.1 s: 8 mm straight ahead.
/// let p = drive(Pose::new(0.0, 0.0, 0.0), 80.0, 80.0, 53.0, 0.1);
/// assert_eq!((p.x, p.y, p.heading), (8.0, 0.0, 0.0));
/// // Opposite wheels: a turn on the spot.
/// let q = drive(Pose::new(0.0, 0.0, 0.0), -53.0, 53.0, 53.0, 0.5);
/// assert_eq!((q.x, q.y), (0.0, 0.0));
/// assert!((q.heading - 1.0).abs() < 1e-12);
/// ```
#[inline]
pub fn drive(pose: Pose, s_left: f64, s_right: f64, wheel_base: f64, dt: f64) -> Pose {
    let v = 0.5 * (s_left + s_right);
    let dtheta = (s_right - s_left) / wheel_base * dt;
    let half = 0.5 * dtheta;
    // Chord length of the arc: v·dt·sin(half)/half (→ v·dt as half → 0).
    // The project's own sin/cos (≤ 1 ulp, |x| ≤ 10⁶: see `crate::simulation::math`), not libm's.
    let sinc = if half.abs() < 1e-6 {
        1.0 - half * half / 6.0
    } else {
        math::sin(half) / half
    };
    let chord = v * dt * sinc;
    let (s, c) = math::sin_cos(pose.heading + half);
    Pose::new(
        pose.x + chord * c,
        pose.y + chord * s,
        pose.heading + dtheta,
    )
}

/// The action taken in one control step, derived from the two motor outputs.
///
/// Its chain-code step ([`Action::chain_step`]) is the heading change in units of 30°.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Action {
    /// Both wheels forward at about the same speed; heading change 0.
    Straight,
    /// Right wheel faster than the left by more than the tolerance; heading change +30°.
    Left30,
    /// Left wheel faster than the right by more than the tolerance; heading change −30°.
    Right30,
    /// Both wheels backwards; heading change 180°.
    Turn180,
}

impl Action {
    /// Classifies one control step from the motor outputs `m_left`, `m_right` ∈ [0, 1].
    ///
    /// With signed speeds `sL = 2·m_left − 1` and `sR = 2·m_right − 1`: both `< 0` → `Turn180`;
    /// else `sR − sL > tolerance` → `Left30`; else `sL − sR > tolerance` → `Right30`; else
    /// `Straight`. Comparisons are strict, so a difference exactly equal to `tolerance` is
    /// `Straight`. `tolerance` is in signed-speed units (range [−1, 1]); the project default is
    /// 0.25 (config key `aem.action_tolerance`). NaN inputs fail every comparison and give
    /// `Straight`.
    pub fn from_motors(m_left: f64, m_right: f64, tolerance: f64) -> Action {
        Action::from_speeds(2.0 * m_left - 1.0, 2.0 * m_right - 1.0, tolerance)
    }

    /// Classifies wheel speeds given as fractions of `v_max`, `s_left`, `s_right` (nominally in
    /// [−1, 1]; noise may take them a little beyond): both `< 0` → `Turn180`; else
    /// `sR − sL > tolerance` → `Left30`; else `sL − sR > tolerance` → `Right30`; else
    /// `Straight` (see [`Action::from_motors`]).
    ///
    /// ```
    /// use fuzzymotiv::simulation::Action;
    /// assert_eq!(Action::from_speeds(-0.1, -0.9, 0.25), Action::Turn180);
    /// assert_eq!(Action::from_speeds(0.2, 0.6, 0.25), Action::Left30);
    /// assert_eq!(Action::from_speeds(0.9, 0.8, 0.25), Action::Straight);
    /// ```
    #[inline]
    pub fn from_speeds(s_left: f64, s_right: f64, tolerance: f64) -> Action {
        if s_left < 0.0 && s_right < 0.0 {
            Action::Turn180
        } else if s_right - s_left > tolerance {
            Action::Left30
        } else if s_left - s_right > tolerance {
            Action::Right30
        } else {
            Action::Straight
        }
    }

    /// A short lowercase name: `"straight"`, `"left30"`, `"right30"` or `"turn180"`.
    pub fn label(self) -> &'static str {
        match self {
            Action::Straight => "straight",
            Action::Left30 => "left30",
            Action::Right30 => "right30",
            Action::Turn180 => "turn180",
        }
    }

    /// The change of the chain code in 30° units: Straight 0, Left30 +1, Right30 −1, Turn180 +6.
    pub fn chain_step(self) -> i32 {
        match self {
            Action::Straight => 0,
            Action::Left30 => 1,
            Action::Right30 => -1,
            Action::Turn180 => 6,
        }
    }

    /// The raw symbol value used by [`crate::modelling::aem::Encoder::Symbols`]: Straight 0, Left30 1/3,
    /// Right30 2/3, Turn180 1.
    pub fn symbol_value(self) -> f64 {
        match self {
            Action::Straight => 0.0,
            Action::Left30 => 1.0 / 3.0,
            Action::Right30 => 2.0 / 3.0,
            Action::Turn180 => 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn quarter_circle_ends_on_the_arc() {
        // Left wheel still, right wheel moving: pivot about the left wheel (radius wb/2 for the
        // centre). Choose dt so the heading turns by π/2.
        let wb = 53.0;
        let s = 100.0;
        let dt = (PI / 2.0) * wb / s;
        let p = drive(Pose::new(0.0, 0.0, 0.0), 0.0, s, wb, dt);
        let r = wb / 2.0;
        assert!((p.x - r).abs() < 1e-9, "{p:?}");
        assert!((p.y - r).abs() < 1e-9, "{p:?}");
        assert!((p.heading - PI / 2.0).abs() < 1e-12);
    }

    #[test]
    fn wrap_angle_fast_path_equals_remainder() {
        let slow = |theta: f64| {
            let mut t = theta % std::f64::consts::TAU;
            if t > PI {
                t -= std::f64::consts::TAU;
            } else if t <= -PI {
                t += std::f64::consts::TAU;
            }
            t
        };
        for i in -300_000..300_000 {
            let theta = i as f64 * 3.1e-5 + (i % 7) as f64 * 1e-9;
            assert_eq!(
                wrap_angle(theta).to_bits(),
                slow(theta).to_bits(),
                "{theta}"
            );
        }
        for theta in [
            PI,
            -PI,
            2.0 * PI - 1e-12,
            -2.0 * PI + 1e-12,
            2.0 * PI,
            -2.0 * PI,
            3.0 * PI,
        ] {
            assert_eq!(
                wrap_angle(theta).to_bits(),
                slow(theta).to_bits(),
                "{theta}"
            );
        }
    }

    #[test]
    fn compass_grid_is_exact() {
        let c = Compass::new(0.0);
        for k in 0..12 {
            let a = k as f64 * PI / 6.0;
            assert!((c.cos[k] - a.cos()).abs() < 1e-15, "{k}");
            assert!((c.sin[k] - a.sin()).abs() < 1e-15, "{k}");
            assert!((wrap_angle(c.heading[k] - a)).abs() < 1e-15, "{k}");
        }
        assert_eq!(c.heading[1], std::f64::consts::FRAC_PI_6);
        assert_eq!(c.heading[6], PI);
        assert_eq!(c.sin[3], 1.0);
        // A home heading on the grid (90°) rotates the exact table.
        let up = Compass::new(90f64.to_radians());
        assert_eq!(up.heading[0], std::f64::consts::FRAC_PI_2);
        assert_eq!((up.cos[0], up.sin[0]), (0.0, 1.0));
        assert_eq!((up.cos[3], up.sin[3]), (-1.0, 0.0));
        // Off the grid: computed once.
        let odd = Compass::new(0.1);
        assert_eq!(odd.heading[0], 0.1);
        assert!((odd.heading[6] - (0.1 - PI)).abs() < 1e-15);
    }

    #[test]
    fn wrap_angle_keeps_range() {
        for k in -20..20 {
            let t = wrap_angle(k as f64 * 0.7);
            assert!(t > -PI && t <= PI);
        }
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(-PI), PI);
    }
}
