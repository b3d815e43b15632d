//! The infrared proximity sensors: their layout (a robot file's `[[sensor]]`, the Khepera's
//! by default) and response models.

use serde::{Deserialize, Serialize};

use crate::simulation::geom::Vec2;
use crate::simulation::sensor_table::SensorTable;

use crate::simulation::robot_spec::RobotSpec;
pub use crate::simulation::sensor_layout::{
    AXIS_SAMPLES, MAX_SENSORS, Readings, SENSOR_LAYOUT, SENSOR_MAX, SENSORS, SIDE_RAY_DEG,
    SIDE_SAMPLES, SensorMount,
};

/// How a sensor turns wall distances into a value in [0, reading_max] (1023 on the Khepera).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SensorModel {
    /// The robot file's rays and sample tables (default); the Khepera's: three rays (axis,
    /// ±24.2°) read through the classic simulator's sample tables.
    #[default]
    Sampled,
    /// One axis ray, `reading_max·(1 − d/linear_range)` below `linear_range` (the Khepera's:
    /// `1023·(1 − d/50)` below 50 mm).
    Linear,
    /// `sampled` reading a sensor table file instead of the built-in tables
    /// (`trial.sensor_table`; never written in a config: the file is named there).
    #[serde(skip)]
    Table(TableRef),
}

impl SensorModel {
    /// Whether every sensor value is a whole number (what lets a trial remember its poses):
    /// the sample tables' values are, the `linear` model's are not.
    pub fn whole_valued(self) -> bool {
        !matches!(self, SensorModel::Linear)
    }
}

/// A sensor table kept for the process ([`SensorTable::intern`]): equal tables are one copy,
/// so two references are equal exactly when they are the same.
#[derive(Debug, Clone, Copy)]
pub struct TableRef(pub &'static SensorTable);

impl PartialEq for TableRef {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self.0, other.0)
    }
}

impl Eq for TableRef {}

impl std::hash::Hash for TableRef {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        std::ptr::hash(self.0, state)
    }
}

/// One ray of one sensor in the robot frame, with its response table.
#[derive(Debug, Clone, Copy)]
pub struct RayMount {
    /// Origin (robot frame, mm).
    pub origin: Vec2,
    /// Direction angle in the robot frame (rad).
    pub angle: f64,
    /// Which table reads the hit distance: 0 axis, 1 side, 2 linear, 3 `samples`.
    kind: u8,
    /// The samples of a sensor table file's ray (kind 3; empty for a ray that reads nothing).
    samples: &'static [(f64, f64)],
    /// The `linear` model's range (mm) and largest value (kind 2).
    linear: (f64, f64),
}

impl RayMount {
    /// Longest distance at which this ray can read a non-zero value (mm).
    pub fn range(&self) -> f64 {
        match self.kind {
            0 => AXIS_SAMPLES[4].0,
            1 => SIDE_SAMPLES[4].0,
            3 => self.samples.last().map_or(0.0, |s| s.0),
            _ => self.linear.0,
        }
    }

    /// The built-in sample table this ray reads ([`RayMount::value`]: the value of the first
    /// sample at or beyond the distance, 0 beyond the last), if it reads one.
    pub(crate) fn builtin_table(&self) -> Option<&'static [(f64, f64); 5]> {
        match self.kind {
            0 => Some(&AXIS_SAMPLES),
            1 => Some(&SIDE_SAMPLES),
            _ => None,
        }
    }

    /// The ray's value for a wall at distance `d` along it (`f64::INFINITY` for none).
    ///
    /// ```
    /// use fuzzymotiv::simulation::{RobotSpec, SensorModel, rays};
    /// let axis = rays(SensorModel::Sampled, RobotSpec::khepera())[2][0];
    /// assert_eq!(axis.value(15.0), 750.0); // first sample at or beyond 15 mm is 20 mm
    /// assert_eq!(axis.value(58.0), 40.0);
    /// assert_eq!(axis.value(60.0), 0.0);
    /// ```
    #[inline]
    pub fn value(&self, d: f64) -> f64 {
        let table = match self.kind {
            0 => &AXIS_SAMPLES,
            1 => &SIDE_SAMPLES,
            3 => return table_value(self.samples, d),
            _ => {
                let (range, max) = self.linear;
                return if d < range {
                    max * (1.0 - d / range)
                } else {
                    0.0
                };
            }
        };
        // Beyond the last sample (no hit: d = ∞) the value is 0; most rays see nothing.
        if d > table[table.len() - 1].0 {
            return 0.0;
        }
        for &(s, v) in table {
            if s >= d {
                return v;
            }
        }
        0.0
    }
}

/// A sensor table file's ray read as the built-in tables are: the value of the first sample at
/// or beyond `d`, 0 beyond the last (and for no samples).
fn table_value(samples: &[(f64, f64)], d: f64) -> f64 {
    match samples.last() {
        Some(&(last, _)) if d <= last => samples.iter().find(|s| s.0 >= d).map_or(0.0, |s| s.1),
        _ => 0.0,
    }
}

/// The rays of every sensor of `robot` for a model: `rays(model, robot)[sensor]` lists up to 3
/// rays (unused entries have `angle = NaN` and are skipped via `ray_count`); sensors past the
/// robot's last have none. The Khepera's `sampled` rays read the built-in tables.
pub fn rays(model: SensorModel, robot: &RobotSpec) -> [[RayMount; 3]; MAX_SENSORS] {
    let side = SIDE_RAY_DEG.to_radians();
    let linear = (robot.linear_range(), robot.reading_max());
    let unused = RayMount {
        origin: Vec2::new(0.0, 0.0),
        angle: f64::NAN,
        kind: 2,
        samples: &[],
        linear,
    };
    let mut out = [[unused; 3]; MAX_SENSORS];
    let table = match model {
        SensorModel::Sampled if robot.is_khepera_layout() => None,
        SensorModel::Sampled => Some(robot.table()),
        SensorModel::Table(TableRef(t)) => Some(t),
        SensorModel::Linear => None,
    };
    for (s, m) in robot.mounts().iter().enumerate() {
        let origin = Vec2::new(m.x, m.y);
        let axis = m.facing_deg.to_radians();
        let ray = |angle: f64, kind: u8, samples: &'static [(f64, f64)]| RayMount {
            origin,
            angle,
            kind,
            samples,
            linear,
        };
        out[s] = match (model, table) {
            (SensorModel::Linear, _) => [ray(axis, 2, &[]), unused, unused],
            (_, None) => [
                ray(axis, 0, &[]),
                ray(axis + side, 1, &[]),
                ray(axis - side, 1, &[]),
            ],
            (_, Some(table)) => {
                let own = table.rays_of(s);
                // Sensors with fewer rays than 3 get rays along the axis that read nothing.
                std::array::from_fn(|k| {
                    let turn = own.get(k).map_or(0.0, |r| r.angle_deg().to_radians());
                    ray(axis + turn, 3, own.get(k).map_or(&[], |r| r.samples()))
                })
            }
        };
    }
    out
}

/// Rays per sensor in a model.
pub fn ray_count(model: SensorModel, robot: &RobotSpec) -> usize {
    let table = match model {
        SensorModel::Linear => return 1,
        SensorModel::Sampled if robot.is_khepera_layout() => return 3,
        SensorModel::Sampled => robot.table(),
        SensorModel::Table(TableRef(t)) => t,
    };
    if (0..table.sensors()).all(|s| table.rays_of(s).len() == 1) {
        1
    } else {
        3
    }
}

/// Farthest distance from the robot's centre at which any ray of the model can see a wall (mm).
pub fn sensing_reach(model: SensorModel, robot: &RobotSpec) -> f64 {
    let rays = rays(model, robot);
    let n = ray_count(model, robot);
    rays[..robot.sensors()]
        .iter()
        .flat_map(|r| r[..n].iter())
        .map(|r| r.origin.norm() + r.range())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn side_ray_table() {
        let side = rays(SensorModel::Sampled, RobotSpec::khepera())[0][1];
        assert_eq!(side.value(0.0), 1023.0);
        assert_eq!(side.value(5.7), 1023.0);
        assert_eq!(side.value(5.8), 800.0);
        assert_eq!(side.value(43.9), 60.0);
        assert_eq!(side.value(44.0), 0.0);
    }

    #[test]
    fn linear_model() {
        let r = rays(SensorModel::Linear, RobotSpec::khepera())[2][0];
        assert_eq!(r.value(0.0), 1023.0);
        assert_eq!(r.value(25.0), 511.5);
        assert_eq!(r.value(50.0), 0.0);
    }

    #[test]
    fn reach_covers_front_sensor() {
        let reach = sensing_reach(SensorModel::Sampled, RobotSpec::khepera());
        // Front sensors 2, 3 sit at |(24.5, 5.5)| = 25.11 mm from the centre; plus 58 mm axis range.
        assert!(
            (reach - (24.5f64.hypot(5.5) + 58.0)).abs() < 1e-9,
            "{reach}"
        );
    }
}
