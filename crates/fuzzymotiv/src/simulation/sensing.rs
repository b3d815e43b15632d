//! What the eight IR sensors read: their rays turned to the robot's heading and cast against
//! the walls near it.
//!
//! [`Eyes`] holds the sensors' rays in the body frame and, for `actions` motion, already turned
//! to each of the twelve headings of the [`Compass`] (the same products a turn per step would
//! compute, done once). [`Eyes::read`] casts them: a wall farther from a sensor than its
//! longest ray cannot change the sensor's value, so it is skipped; the others are tested
//! against every ray of the sensor at once ([`PreparedSegment::lower_ray_hits`]).

use crate::simulation::geom::{PreparedSegment, Vec2};
use crate::simulation::robot::Compass;
use crate::simulation::sensor::SENSORS as INPUTS;
use crate::simulation::sensor::{RayMount, SENSOR_MAX, SensorModel, ray_count, rays};

/// The sensors' rays turned to one heading: each sensor's origin relative to the body centre
/// and its ray directions, in the world frame.
#[derive(Debug, Clone, Copy)]
pub struct TurnedRays {
    origins: [Vec2; INPUTS],
    dirs: [[Vec2; 3]; INPUTS],
}

/// The eight sensors of one response model, ready to read.
#[derive(Debug, Clone)]
pub struct Eyes {
    mounts: [[RayMount; 3]; INPUTS],
    /// The rays at heading 0 (body frame): origins and unit directions.
    body: TurnedRays,
    /// Rays per sensor (3 with `sampled`, 1 with `linear`).
    per_sensor: usize,
    /// Squared longest ray range, with a 10⁻⁶ mm margin over the rounding of the culling test.
    range2: f64,
    /// The rays turned to each compass heading.
    compass: [TurnedRays; 12],
}

impl Eyes {
    /// The sensors of `model`, with their rays turned to each heading of `compass`.
    pub fn new(model: SensorModel, compass: &Compass) -> Eyes {
        let mounts = rays(model);
        let per_sensor = ray_count(model);
        let body = TurnedRays {
            origins: mounts.map(|m| m[0].origin),
            dirs: mounts.map(|m| m.map(|r| Vec2::from_angle(r.angle))),
        };
        let range = mounts
            .iter()
            .flat_map(|m| m[..per_sensor].iter())
            .map(|r| r.range())
            .fold(0.0, f64::max)
            + 1e-6;
        Eyes {
            mounts,
            body,
            per_sensor,
            range2: range * range,
            compass: std::array::from_fn(|k| body.turned(compass.sin[k], compass.cos[k])),
        }
    }

    /// The rays turned to compass direction `dir` (0..12).
    #[inline]
    pub fn on_compass(&self, dir: usize) -> &TurnedRays {
        &self.compass[dir]
    }

    /// Noise-free sensor values (0–1023) of a robot centred at `pos` facing `facing`, seeing
    /// the walls `near` (indices into `walls`).
    #[inline]
    pub fn read(
        &self,
        pos: Vec2,
        facing: Facing<'_>,
        walls: &[PreparedSegment],
        near: &[u32],
    ) -> [f64; INPUTS] {
        match self.per_sensor {
            3 => self.read_rays::<3>(pos, facing, walls, near),
            _ => self.read_rays::<1>(pos, facing, walls, near),
        }
    }

    /// [`Eyes::read`] with `N` rays per sensor.
    #[inline]
    fn read_rays<const N: usize>(
        &self,
        pos: Vec2,
        facing: Facing<'_>,
        walls: &[PreparedSegment],
        near: &[u32],
    ) -> [f64; INPUTS] {
        let mut out = [0.0; INPUTS];
        for (s, o) in out.iter_mut().enumerate() {
            let origin = pos + facing.origin(&self.body, s);
            let mut nearest = [f64::INFINITY; N];
            // Turned only when a wall is in range (with `Facing::Angle`, most sensors see none).
            let mut dirs = None;
            for &k in near {
                let wall = &walls[k as usize];
                if wall.dist2_to(origin) <= self.range2 {
                    let dirs = dirs.get_or_insert_with(|| facing.dirs(&self.body, s));
                    wall.lower_ray_hits(origin, &dirs[..N], &mut nearest);
                }
            }
            if dirs.is_none() {
                continue; // no wall in range: the sensor reads 0
            }
            let mut total = 0.0;
            for (ray, &d) in self.mounts[s][..N].iter().zip(&nearest) {
                total += ray.value(d);
            }
            *o = total.min(SENSOR_MAX);
        }
        out
    }
}

/// Which way the robot faces, as [`Eyes::read`] needs it.
#[derive(Debug, Clone, Copy)]
pub enum Facing<'a> {
    /// A compass heading, its rays turned in advance ([`Eyes::on_compass`]).
    Compass(&'a TurnedRays),
    /// Any heading, by its sine and cosine: the rays are turned as they are needed.
    Angle {
        /// Sine of the heading.
        sin: f64,
        /// Cosine of the heading.
        cos: f64,
    },
}

impl Facing<'_> {
    /// Sensor `s`'s origin relative to the body centre, turned to this heading (`body`: the
    /// rays at heading 0).
    #[inline]
    fn origin(self, body: &TurnedRays, s: usize) -> Vec2 {
        match self {
            Facing::Compass(t) => t.origins[s],
            Facing::Angle { sin, cos } => body.origins[s].rotate_by(sin, cos),
        }
    }

    /// Sensor `s`'s ray directions turned to this heading.
    #[inline]
    fn dirs(self, body: &TurnedRays, s: usize) -> [Vec2; 3] {
        match self {
            Facing::Compass(t) => t.dirs[s],
            Facing::Angle { sin, cos } => body.dirs[s].map(|d| d.rotate_by(sin, cos)),
        }
    }
}

impl TurnedRays {
    /// These rays turned by the rotation with sine `s` and cosine `c`.
    fn turned(&self, s: f64, c: f64) -> TurnedRays {
        TurnedRays {
            origins: self.origins.map(|v| v.rotate_by(s, c)),
            dirs: self.dirs.map(|d| d.map(|v| v.rotate_by(s, c))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::geom::Segment;

    /// The compass table holds exactly the products a per-step turn computes.
    #[test]
    fn compass_rays_equal_rays_turned_per_step() {
        let compass = Compass::new(0.3);
        let eyes = Eyes::new(SensorModel::Sampled, &compass);
        for k in 0..12 {
            let (sin, cos) = (compass.sin[k], compass.cos[k]);
            let (fresh, table) = (
                Facing::Angle { sin, cos },
                Facing::Compass(eyes.on_compass(k)),
            );
            for s in 0..INPUTS {
                assert_eq!(fresh.origin(&eyes.body, s), table.origin(&eyes.body, s));
                assert_eq!(fresh.dirs(&eyes.body, s), table.dirs(&eyes.body, s));
            }
        }
    }

    /// A wall beyond every ray's range is skipped and reads 0, as a wall not listed at all.
    #[test]
    fn far_walls_read_zero() {
        let eyes = Eyes::new(SensorModel::Sampled, &Compass::new(0.0));
        let far =
            PreparedSegment::new(&Segment::new(Vec2::new(90.0, -50.0), Vec2::new(90.0, 50.0)));
        let near =
            PreparedSegment::new(&Segment::new(Vec2::new(60.0, -50.0), Vec2::new(60.0, 50.0)));
        let turned = Facing::Compass(eyes.on_compass(0));
        assert_eq!(eyes.read(Vec2::default(), turned, &[far], &[0]), [0.0; 8]);
        // 60 − 24.5 = 35.5 mm along the front axes → 44 mm sample (160); the side rays hit at
        // 35.5 / cos 24.2° = 38.9 mm → 43.9 mm sample (60 each).
        let s = eyes.read(Vec2::default(), turned, &[far, near], &[0, 1]);
        assert_eq!((s[2], s[3], s[0], s[6]), (280.0, 280.0, 0.0, 0.0));
    }
}
