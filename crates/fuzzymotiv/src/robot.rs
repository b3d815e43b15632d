//! The Khepera I body: pose, physical parameters and pure differential-drive kinematics.

use serde::{Deserialize, Serialize};

use crate::geom::Vec2;
use crate::math;

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
/// use fuzzymotiv::robot::wrap_angle;
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

/// Physical parameters of the Khepera I (SPEC §3). All lengths in mm, speeds in mm/s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Khepera {
    /// Body radius; default 27.5 mm (diameter 55 mm).
    pub radius: f64,
    /// Distance between the wheels; default 53 mm.
    pub wheel_base: f64,
    /// Maximum wheel speed; default 80 mm/s.
    pub v_max: f64,
}

/// The Khepera's body radius (mm), also used to validate room files.
pub const KHEPERA_RADIUS: f64 = 27.5;

impl Default for Khepera {
    fn default() -> Self {
        Self {
            radius: KHEPERA_RADIUS,
            wheel_base: 53.0,
            v_max: 80.0,
        }
    }
}

/// Differential-drive kinematics: the pose after `dt` seconds with wheel speeds `s_left`,
/// `s_right` (mm/s), integrated exactly along the arc (a straight line when the speeds are
/// equal).
///
/// ```
/// use fuzzymotiv::robot::{Pose, drive};
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
    // The project's own sin/cos (≤ 1 ulp, |x| ≤ 10⁶: see `crate::math`), not libm's.
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
    fn wrap_angle_keeps_range() {
        for k in -20..20 {
            let t = wrap_angle(k as f64 * 0.7);
            assert!(t > -PI && t <= PI);
        }
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(-PI), PI);
    }
}
