//! The eight infrared sensors' layout and the built-in response tables (docs/model.md §3):
//! constants that the response models ([`crate::simulation::sensor`]) and sensor table files
//! ([`crate::simulation::sensor_table`]) share.

use std::mem::MaybeUninit;

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

/// The most proximity sensors a robot may have (a robot file's `[[sensor]]` entries).
pub const MAX_SENSORS: usize = 24;

/// One reading of every sensor of a robot (its `len` sensors, 1 to [`MAX_SENSORS`]), in the
/// robot's order: a slice of values ([`std::ops::Deref`]) kept without allocation.
///
/// ```
/// use fuzzymotiv::simulation::Readings;
/// let mut r = Readings::zeros(7);
/// r[2] = 512.0;
/// assert_eq!(r.len(), 7);
/// assert_eq!(&r[..3], [0.0, 0.0, 512.0]);
/// assert_eq!(Readings::from_slice(&r), r);
/// ```
#[derive(Clone, Copy)]
pub struct Readings {
    /// The readings; only the first `len` are written (the rest are never read, so a
    /// robot's readings are made without filling 24 values: a step makes them every time).
    values: [MaybeUninit<f64>; MAX_SENSORS],
    len: u8,
}

impl Readings {
    /// `len` readings of 0 (`len` at most [`MAX_SENSORS`]).
    #[inline]
    pub fn zeros(len: usize) -> Readings {
        assert!(len <= MAX_SENSORS, "{len} sensors: at most {MAX_SENSORS}");
        let mut values = [MaybeUninit::uninit(); MAX_SENSORS];
        for v in &mut values[..len] {
            v.write(0.0);
        }
        Readings {
            values,
            len: len as u8,
        }
    }

    /// The readings `values` (at most [`MAX_SENSORS`]).
    pub fn from_slice(values: &[f64]) -> Readings {
        let mut r = Readings::zeros(values.len());
        r.copy_from_slice(values);
        r
    }

    /// `f` of each reading, in order (only the robot's readings are written: no copy of all 24).
    #[inline(always)]
    pub fn map(&self, mut f: impl FnMut(f64) -> f64) -> Readings {
        let mut values = [MaybeUninit::uninit(); MAX_SENSORS];
        for (slot, &v) in values.iter_mut().zip(self.iter()) {
            slot.write(f(v));
        }
        Readings {
            values,
            len: self.len,
        }
    }

    /// The first eight readings as an array (zeros past `len`).
    #[inline]
    pub(crate) fn first_eight(&self) -> [f64; 8] {
        std::array::from_fn(|k| self.get(k).copied().unwrap_or(0.0))
    }

    /// Eight readings, of which the first `len` (at most 8) count.
    #[inline]
    pub(crate) fn from_eight(values: [f64; 8], len: usize) -> Readings {
        debug_assert!(len <= 8);
        let mut all = [MaybeUninit::uninit(); MAX_SENSORS];
        for (slot, v) in all.iter_mut().zip(values) {
            slot.write(v);
        }
        Readings {
            values: all,
            len: len.min(8) as u8,
        }
    }
}

impl std::ops::Deref for Readings {
    type Target = [f64];
    #[inline]
    fn deref(&self) -> &[f64] {
        let len = usize::from(self.len);
        // SAFETY: the first `len` values are written by every constructor (`zeros`,
        // `from_eight` with `len` ≤ 8) and stay written; `MaybeUninit<f64>` has `f64`'s layout.
        unsafe { std::slice::from_raw_parts(self.values.as_ptr().cast::<f64>(), len) }
    }
}

impl std::ops::DerefMut for Readings {
    #[inline]
    fn deref_mut(&mut self) -> &mut [f64] {
        let len = usize::from(self.len);
        // SAFETY: as for `deref`; writes through the slice keep the values written.
        unsafe { std::slice::from_raw_parts_mut(self.values.as_mut_ptr().cast::<f64>(), len) }
    }
}

impl PartialEq for Readings {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl std::fmt::Debug for Readings {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl serde::Serialize for Readings {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.iter())
    }
}

impl<'de> serde::Deserialize<'de> for Readings {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let values = Vec::<f64>::deserialize(d)?;
        if values.len() > MAX_SENSORS {
            return Err(serde::de::Error::invalid_length(
                values.len(),
                &"at most 24 readings",
            ));
        }
        Ok(Readings::from_slice(&values))
    }
}

impl<const N: usize> PartialEq<[f64; N]> for Readings {
    fn eq(&self, other: &[f64; N]) -> bool {
        **self == other[..]
    }
}
