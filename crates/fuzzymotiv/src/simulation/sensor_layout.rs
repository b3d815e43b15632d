//! The eight infrared sensors' layout and the built-in response tables (docs/model.md §3):
//! constants that the response models ([`crate::simulation::sensor`]) and sensor table files
//! ([`crate::simulation::sensor_table`]) share.

/// Where one sensor sits on the body, in the robot frame (x forward, y left).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorMount {
    /// Forward offset from the centre (mm).
    pub x: f64,
    /// Leftward offset from the centre (mm).
    pub y: f64,
    /// Direction the sensor faces, degrees counter-clockwise from forward.
    pub facing_deg: f64,
}

/// The number of IR sensors (the controller's inputs).
pub const SENSORS: usize = 8;

/// The classic Khepera simulator layout (docs/model.md §3), sensors 0–7.
pub const SENSOR_LAYOUT: [SensorMount; SENSORS] = [
    SensorMount {
        x: 9.5,
        y: 23.0,
        facing_deg: 90.0,
    },
    SensorMount {
        x: 18.0,
        y: 17.5,
        facing_deg: 45.0,
    },
    SensorMount {
        x: 24.5,
        y: 5.5,
        facing_deg: 0.0,
    },
    SensorMount {
        x: 24.5,
        y: -5.5,
        facing_deg: 0.0,
    },
    SensorMount {
        x: 18.0,
        y: -17.5,
        facing_deg: -45.0,
    },
    SensorMount {
        x: 9.5,
        y: -23.0,
        facing_deg: -90.0,
    },
    SensorMount {
        x: -23.0,
        y: -9.5,
        facing_deg: 180.0,
    },
    SensorMount {
        x: -23.0,
        y: 9.5,
        facing_deg: 180.0,
    },
];

/// Largest raw sensor value.
pub const SENSOR_MAX: f64 = 1023.0;

/// Angle between a side ray and the sensor axis in the `sampled` model (degrees).
pub const SIDE_RAY_DEG: f64 = 24.2;
/// Sample distances along the axis ray (mm) and their values.
pub const AXIS_SAMPLES: [(f64, f64); 5] = [
    (12.0, 900.0),
    (20.0, 750.0),
    (32.0, 650.0),
    (44.0, 160.0),
    (58.0, 40.0),
];
/// Sample distances along each side ray (mm) and their values.
pub const SIDE_SAMPLES: [(f64, f64); 5] = [
    (5.7, 1023.0),
    (11.3, 800.0),
    (18.9, 600.0),
    (29.5, 400.0),
    (43.9, 60.0),
];
/// Range of the `linear` model (mm).
pub const LINEAR_RANGE: f64 = 50.0;
