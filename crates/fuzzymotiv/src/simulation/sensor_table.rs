//! Your robot's sensors: a sensor table file (`trial.sensor_table`) read by the `sampled`
//! model instead of the built-in Khepera tables (docs/model.md §3), and the calibration that
//! turns bench measurements into such a table ([`calibrate`]).
//!
//! A table gives, per ray, sample distances (mm) and the readings (0–1023) there, read as the
//! built-in tables are: the reading of the first sample distance at or beyond the nearest wall
//! hit along the ray, 0 beyond the last sample. A sensor's value is the sum of its rays (1 to
//! 3), capped at 1023.
//!
//! ```
//! use fuzzymotiv::simulation::SensorTable;
//! let text = "[[ray]]\ndistance_mm = [10, 30, 60]\nreading = [1000, 400, 50]\n";
//! let table = SensorTable::from_toml_str(text, "my-robot.toml").unwrap();
//! assert_eq!(table.rays_of(5)[0].samples(), [(10.0, 1000.0), (30.0, 400.0), (60.0, 50.0)]);
//! let bad = "[[ray]]\ndistance_mm = [10, 30]\nreading = [400, 1000]\n";
//! let e = SensorTable::from_toml_str(bad, "my-robot.toml").unwrap_err();
//! assert_eq!(e.field, "ray[0].reading");
//! ```

use std::collections::BTreeMap;
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use crate::params::{FieldError, Num, check};
use crate::simulation::sensor_layout::{
    AXIS_SAMPLES, SENSOR_MAX, SENSORS, SIDE_RAY_DEG, SIDE_SAMPLES,
};

/// The sensors a table is for: how many, and the largest reading (a robot file's
/// `[[sensor]]` count and `reading_max`; the Khepera's are 8 and 1023).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorScale {
    /// Number of sensors (1 to [`crate::simulation::MAX_SENSORS`]).
    pub sensors: usize,
    /// Largest reading (a whole number).
    pub reading_max: f64,
}

impl SensorScale {
    /// The paper's Khepera: eight sensors reading 0–1023.
    pub const KHEPERA: SensorScale = SensorScale {
        sensors: SENSORS,
        reading_max: SENSOR_MAX,
    };
}

/// The most rays a sensor may have.
pub const MAX_RAYS: usize = 3;
/// The most samples a ray may have.
pub const MAX_SAMPLES: usize = 64;
/// The longest sample distance a table may give (mm).
pub const MAX_DISTANCE_MM: f64 = 1000.0;

/// One ray of a sensor table file, as written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRay {
    /// The ray's direction from the sensor's axis, degrees counter-clockwise; default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub angle_deg: f64,
    /// Sample distances along the ray (mm), increasing.
    pub distance_mm: Vec<f64>,
    /// The reading at each sample distance (whole numbers in 0..=1023, not increasing).
    pub reading: Vec<f64>,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// One sensor's own rays (`[[sensor.N.ray]]`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSensorRays {
    /// The sensor's rays (1 to 3).
    pub ray: Vec<RawRay>,
}

/// A sensor table file as written (TOML).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSensorTable {
    /// A name for the table (free text).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Where the numbers come from (free text).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// The rays of every sensor not listed under `sensor`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ray: Vec<RawRay>,
    /// Sensors with their own rays, by number ("0" to the robot's last).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub sensor: BTreeMap<String, RawSensorRays>,
}

/// One ray of a checked table.
#[derive(Debug, Clone, PartialEq)]
pub struct TableRay {
    angle_deg: f64,
    samples: Vec<(f64, f64)>,
}

impl TableRay {
    /// The ray's direction from the sensor's axis (degrees, counter-clockwise).
    pub fn angle_deg(&self) -> f64 {
        self.angle_deg
    }

    /// (distance mm, reading) pairs, distances increasing, readings not increasing.
    pub fn samples(&self) -> &[(f64, f64)] {
        &self.samples
    }
}

/// A checked sensor table: 1 to 3 rays for each sensor of a robot.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorTable {
    rays: Vec<Vec<TableRay>>,
}

impl SensorTable {
    /// Parses and checks a table file's text for the Khepera's eight sensors; errors name
    /// `source_name` and the field.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<SensorTable, FieldError> {
        Self::from_toml_str_for(text, source_name, SensorScale::KHEPERA)
    }

    /// Parses and checks a table file's text for the sensors `scale`; errors name
    /// `source_name` and the field.
    pub fn from_toml_str_for(
        text: &str,
        source_name: &str,
        scale: SensorScale,
    ) -> Result<SensorTable, FieldError> {
        // Its values are numbers and names, no whole numbers: their range is not asked.
        let raw: RawSensorTable = crate::params::plain::from_str(text, |_| "≥ 0".into())
            .map_err(|e| FieldError::new(e.field(text), e.message()).in_source(source_name))?;
        SensorTable::from_raw_for(&raw, scale).map_err(|e| e.in_source(source_name))
    }

    /// Checks a table as written for the Khepera's eight sensors, naming the first wrong field.
    pub fn from_raw(raw: &RawSensorTable) -> Result<SensorTable, FieldError> {
        Self::from_raw_for(raw, SensorScale::KHEPERA)
    }

    /// Checks a table as written for the sensors `scale`, naming the first wrong field.
    pub fn from_raw_for(
        raw: &RawSensorTable,
        scale: SensorScale,
    ) -> Result<SensorTable, FieldError> {
        let default = if raw.ray.is_empty() {
            None
        } else {
            Some(check_rays(&raw.ray, "ray", scale.reading_max)?)
        };
        let n = scale.sensors;
        let mut own: Vec<Option<Vec<TableRay>>> = vec![None; n];
        for (key, rays) in &raw.sensor {
            let s = key.parse::<usize>().ok().filter(|&s| s < n);
            let Some(s) = s else {
                return Err(FieldError::new(
                    format!("sensor.{key}"),
                    format!(
                        "sensors are numbered 0 to {} ({}), got \"{key}\"",
                        n - 1,
                        if n == SENSORS {
                            "0 left, 1 front-left, 2 and 3 front, 4 front-right, 5 right, 6 and 7 back on the Khepera"
                        } else {
                            "in the robot file's [[sensor]] order"
                        }
                    ),
                ));
            };
            let field = format!("sensor.{key}.ray");
            own[s] = Some(check_rays(&rays.ray, &field, scale.reading_max)?);
        }
        let mut out: Vec<Vec<TableRay>> = vec![Vec::new(); n];
        for (s, slot) in out.iter_mut().enumerate() {
            *slot = match (own[s].take(), &default) {
                (Some(r), _) => r,
                (None, Some(d)) => d.clone(),
                (None, None) => {
                    return Err(FieldError::new(
                        format!("sensor.{s}"),
                        format!(
                            "sensor {s} has no rays: give [[ray]] tables for every sensor, or [[sensor.{s}.ray]] for this one"
                        ),
                    ));
                }
            };
        }
        Ok(SensorTable { rays: out })
    }

    /// The built-in Khepera tables as a table (axis ray and two side rays at ±24.2°): a file
    /// holding them gives the same readings as `sensor_model = "sampled"` alone.
    pub fn khepera() -> SensorTable {
        let ray = |angle_deg: f64, t: &[(f64, f64)]| TableRay {
            angle_deg,
            samples: t.to_vec(),
        };
        let rays = vec![
            ray(0.0, &AXIS_SAMPLES),
            ray(SIDE_RAY_DEG, &SIDE_SAMPLES),
            ray(-SIDE_RAY_DEG, &SIDE_SAMPLES),
        ];
        SensorTable {
            rays: vec![rays; SENSORS],
        }
    }

    /// Number of sensors.
    pub fn sensors(&self) -> usize {
        self.rays.len()
    }

    /// The rays of sensor `s` (0 to [`SensorTable::sensors`] − 1).
    pub fn rays_of(&self, s: usize) -> &[TableRay] {
        &self.rays[s]
    }

    /// The same table with every reading multiplied by `factor`, rounded to a whole number and
    /// capped at `reading_max` (a more or less sensitive sensor; still a valid table for
    /// `factor ≥ 0`).
    pub fn scaled(&self, factor: f64, reading_max: f64) -> SensorTable {
        let mut t = self.clone();
        for ray in t.rays.iter_mut().flatten() {
            for (_, v) in &mut ray.samples {
                *v = (*v * factor).round().clamp(0.0, reading_max);
            }
        }
        t
    }

    /// The table as a file (every sensor's rays written out), with `header` as comment lines.
    pub fn to_toml(&self, header: &str) -> String {
        let raw = RawSensorTable {
            sensor: (0..self.rays.len())
                .map(|s| {
                    let ray = self.rays[s]
                        .iter()
                        .map(|r| RawRay {
                            angle_deg: r.angle_deg,
                            distance_mm: r.samples.iter().map(|p| p.0).collect(),
                            reading: r.samples.iter().map(|p| p.1).collect(),
                        })
                        .collect();
                    (s.to_string(), RawSensorRays { ray })
                })
                .collect(),
            ..RawSensorTable::default()
        };
        let comments: String = header.lines().map(|l| format!("# {l}\n")).collect();
        let body = toml::to_string(&raw).expect("a sensor table is always serialisable");
        format!("{comments}{body}")
    }

    /// This table, kept for the rest of the process: equal tables share one copy, so a
    /// program that loads the same file again and again keeps one.
    pub fn intern(self) -> &'static SensorTable {
        static TABLES: Mutex<Vec<&'static SensorTable>> = Mutex::new(Vec::new());
        let mut tables = TABLES.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = tables.iter().find(|t| ***t == self) {
            return t;
        }
        let t: &'static SensorTable = Box::leak(Box::new(self));
        tables.push(t);
        t
    }
}

/// Checks the rays of one sensor (or the default rays), `field` naming them, readings in
/// 0..=`max`.
fn check_rays(rays: &[RawRay], field: &str, max: f64) -> Result<Vec<TableRay>, FieldError> {
    check((1..=MAX_RAYS).contains(&rays.len()), field, || {
        format!("a sensor has 1 to {MAX_RAYS} rays, got {}", rays.len())
    })?;
    rays.iter()
        .enumerate()
        .map(|(k, r)| check_ray(r, &format!("{field}[{k}]"), max))
        .collect()
}

/// Checks one ray: the angle, the distances (finite, increasing, 2 to 64 of them, within
/// 0..=1000 mm) and the readings (as many, whole numbers in 0..=`max`, not increasing).
fn check_ray(r: &RawRay, field: &str, max: f64) -> Result<TableRay, FieldError> {
    let f = |name: &str| format!("{field}.{name}");
    check(
        r.angle_deg.is_finite() && (-90.0..=90.0).contains(&r.angle_deg),
        &f("angle_deg"),
        || {
            format!(
                "must be an angle in [-90, 90] degrees from the sensor's axis, got {}",
                Num(r.angle_deg)
            )
        },
    )?;
    let d = &r.distance_mm;
    check(
        (2..=MAX_SAMPLES).contains(&d.len()),
        &f("distance_mm"),
        || format!("needs 2 to {MAX_SAMPLES} sample distances, got {}", d.len()),
    )?;
    for (i, &x) in d.iter().enumerate() {
        check(
            x.is_finite() && (0.0..=MAX_DISTANCE_MM).contains(&x),
            &f("distance_mm"),
            || {
                format!(
                    "entry {i} must be a distance in [0, {MAX_DISTANCE_MM}] mm, got {}",
                    Num(x)
                )
            },
        )?;
        check(i == 0 || x > d[i - 1], &f("distance_mm"), || {
            format!(
                "must increase: entry {i} ({}) is not beyond entry {} ({})",
                Num(x),
                i - 1,
                Num(d[i - 1])
            )
        })?;
    }
    let v = &r.reading;
    check(v.len() == d.len(), &f("reading"), || {
        format!(
            "needs one reading per distance ({}), got {}",
            d.len(),
            v.len()
        )
    })?;
    for (i, &x) in v.iter().enumerate() {
        check(
            x.is_finite() && (0.0..=max).contains(&x) && x.fract() == 0.0,
            &f("reading"),
            || {
                format!(
                    "entry {i} must be a whole number in 0..={}, got {}",
                    Num(max),
                    Num(x)
                )
            },
        )?;
        check(i == 0 || x <= v[i - 1], &f("reading"), || {
            format!(
                "must not increase with distance: entry {i} ({}) is above entry {} ({}); a sensor reads less the farther the wall",
                Num(x),
                i - 1,
                Num(v[i - 1])
            )
        })?;
    }
    Ok(TableRay {
        angle_deg: r.angle_deg,
        samples: d.iter().copied().zip(v.iter().copied()).collect(),
    })
}

/// One bench measurement: sensor `sensor` facing a wall `distance_mm` away read `reading`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// Sensor number (0 to the robot's last).
    pub sensor: usize,
    /// Distance from the sensor to the wall, along its axis (mm).
    pub distance_mm: f64,
    /// The raw reading (0 to the robot's `reading_max`).
    pub reading: f64,
}

/// The readings of one sensor at one distance.
#[derive(Debug, Clone, PartialEq)]
pub struct Spread {
    /// Sensor number.
    pub sensor: usize,
    /// Distance (mm).
    pub distance_mm: f64,
    /// Number of readings.
    pub count: usize,
    /// Their median (what the table holds, before the monotone fit).
    pub median: f64,
    /// Their mean.
    pub mean: f64,
    /// Their sample standard deviation (0 for one reading).
    pub std: f64,
}

impl Spread {
    /// std / mean, or `None` when the mean is 0 or there is a single reading.
    pub fn relative(&self) -> Option<f64> {
        (self.mean > 0.0 && self.count >= 2).then(|| self.std / self.mean)
    }
}

/// What [`calibrate`] makes of bench measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// The table: one axis ray per sensor (one sensor measured: its ray for all).
    pub table: SensorTable,
    /// Per sensor and distance: count, median, mean, std.
    pub spread: Vec<Spread>,
    /// The relative spread: the sum of the standard deviations over the sum of the means (per
    /// sensor and distance, where there are 2 readings or more).
    pub relative_spread: f64,
    /// The `trial.noise` with that spread: the simulator multiplies each reading by
    /// U(1 − n, 1 + n), whose relative std is n/√3, so n = √3 × spread (capped at 0.5).
    pub noise: f64,
    /// What the user should know (medians pooled to keep the table monotone, one sensor for all).
    pub notes: Vec<String>,
}

/// Turns bench measurements into a table: per sensor and distance the median reading (rounded
/// to a whole number), made non-increasing with distance by pooling neighbours that rise
/// (weighted by their counts); the spread of the readings is the sensor noise estimate. Every
/// sensor of `scale` measured, or a single one (its table then serves all); each measured
/// sensor needs at least 2 distances. Errors name the `row` (1-based data row) or the sensor.
pub fn calibrate(rows: &[Measurement], scale: SensorScale) -> Result<Calibration, FieldError> {
    let mut by: BTreeMap<usize, BTreeMap<u64, Vec<f64>>> = BTreeMap::new();
    for (i, m) in rows.iter().enumerate() {
        check_measurement(m, i + 1, scale)?;
        let d = by.entry(m.sensor).or_default();
        d.entry(m.distance_mm.to_bits())
            .or_default()
            .push(m.reading);
    }
    let sensors: Vec<usize> = by.keys().copied().collect();
    check(
        sensors.len() == 1 || sensors.len() == scale.sensors,
        "sensor",
        || {
            format!(
                "measure every sensor 0–{}, or one sensor for all {}; got sensors {sensors:?}",
                scale.sensors - 1,
                scale.sensors
            )
        },
    )?;
    let mut spread = Vec::new();
    let mut notes = Vec::new();
    let mut rays = Vec::new();
    for (&s, dists) in &by {
        let (ray, stats) = measured_ray(s, dists, scale.reading_max, &mut notes)?;
        rays.push(ray);
        spread.extend(stats);
    }
    let raw = if rays.len() == 1 {
        notes.push(format!(
            "only sensor {} was measured: its table serves all {} sensors",
            sensors[0], scale.sensors
        ));
        RawSensorTable {
            ray: rays,
            ..RawSensorTable::default()
        }
    } else {
        let sensor = rays
            .into_iter()
            .enumerate()
            .map(|(s, r)| (s.to_string(), RawSensorRays { ray: vec![r] }))
            .collect();
        RawSensorTable {
            sensor,
            ..RawSensorTable::default()
        }
    };
    let table = SensorTable::from_raw_for(&raw, scale)?;
    // Σ std / Σ mean: readings near 0 (the converter's offset, not the multiplicative noise the
    // simulator models) weigh as little as they read.
    let repeated = spread.iter().filter(|g| g.count >= 2);
    let (std, mean) = repeated.fold((0.0, 0.0), |(s, m), g| (s + g.std, m + g.mean));
    let relative_spread = if mean > 0.0 { std / mean } else { 0.0 };
    Ok(Calibration {
        table,
        spread,
        relative_spread,
        noise: (3f64.sqrt() * relative_spread).min(0.5),
        notes,
    })
}

/// Sensor `s`'s measured ray: per distance (`dists`: distance bits → readings) the median,
/// made non-increasing (a note in `notes` when medians had to be pooled), rounded and capped at
/// `max`; with the spread of each distance's readings.
fn measured_ray(
    s: usize,
    dists: &BTreeMap<u64, Vec<f64>>,
    max: f64,
    notes: &mut Vec<String>,
) -> Result<(RawRay, Vec<Spread>), FieldError> {
    let mut groups: Vec<(f64, Vec<f64>)> = dists
        .iter()
        .map(|(&d, v)| (f64::from_bits(d), v.clone()))
        .collect();
    groups.sort_by(|a, b| a.0.total_cmp(&b.0));
    check(groups.len() >= 2, "distance_mm", || {
        format!(
            "sensor {s} was measured at {} distance; a table needs at least 2",
            groups.len()
        )
    })?;
    let stats: Vec<Spread> = groups.iter().map(|(d, v)| spread_of(s, *d, v)).collect();
    let medians: Vec<(f64, usize)> = stats.iter().map(|g| (g.median, g.count)).collect();
    let fitted = non_increasing(&medians);
    if fitted.iter().zip(&medians).any(|(f, m)| *f != m.0) {
        notes.push(format!("sensor {s}: the medians rise with distance somewhere; neighbouring distances were pooled (weighted means) to keep the table non-increasing"));
    }
    let ray = RawRay {
        angle_deg: 0.0,
        distance_mm: groups.iter().map(|g| g.0).collect(),
        reading: fitted.iter().map(|v| v.round().clamp(0.0, max)).collect(),
    };
    Ok((ray, stats))
}

/// Checks one measurement (`row`: its 1-based data row).
fn check_measurement(m: &Measurement, row: usize, scale: SensorScale) -> Result<(), FieldError> {
    check(m.sensor < scale.sensors, "sensor", || {
        format!(
            "row {row}: sensors are numbered 0 to {}, got {}",
            scale.sensors - 1,
            m.sensor
        )
    })?;
    check(
        m.distance_mm.is_finite() && (0.0..=MAX_DISTANCE_MM).contains(&m.distance_mm),
        "distance_mm",
        || {
            format!(
                "row {row}: must be a distance in [0, {MAX_DISTANCE_MM}] mm, got {}",
                Num(m.distance_mm)
            )
        },
    )?;
    check(
        m.reading.is_finite() && (0.0..=scale.reading_max).contains(&m.reading),
        "reading",
        || {
            format!(
                "row {row}: must be a reading in [0, {}], got {}",
                Num(scale.reading_max),
                Num(m.reading)
            )
        },
    )
}

/// Count, median, mean and sample std of one sensor's readings at one distance.
fn spread_of(sensor: usize, distance_mm: f64, v: &[f64]) -> Spread {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    let median = if n % 2 == 1 {
        s[n / 2]
    } else {
        (s[n / 2 - 1] + s[n / 2]) / 2.0
    };
    let mean = s.iter().sum::<f64>() / n as f64;
    let var = if n > 1 {
        s.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64
    } else {
        0.0
    };
    Spread {
        sensor,
        distance_mm,
        count: n,
        median,
        mean,
        std: var.sqrt(),
    }
}

/// The closest non-increasing sequence to `values` (value, weight) in weighted least squares
/// (pool adjacent violators).
fn non_increasing(values: &[(f64, usize)]) -> Vec<f64> {
    // Blocks of (mean, weight, length).
    let mut blocks: Vec<(f64, f64, usize)> = Vec::new();
    for &(v, w) in values {
        blocks.push((v, w as f64, 1));
        while blocks.len() >= 2 && blocks[blocks.len() - 2].0 < blocks[blocks.len() - 1].0 {
            let (b, a) = (blocks.pop().unwrap(), blocks.pop().unwrap());
            let w = a.1 + b.1;
            blocks.push(((a.0 * a.1 + b.0 * b.1) / w, w, a.2 + b.2));
        }
    }
    blocks
        .iter()
        .flat_map(|&(m, _, n)| std::iter::repeat_n(m, n))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> FieldError {
        SensorTable::from_toml_str(text, "t.toml").unwrap_err()
    }

    #[test]
    fn bad_tables_name_the_field() {
        let ray = |d: &str, v: &str| format!("[[ray]]\ndistance_mm = {d}\nreading = {v}\n");
        assert_eq!(err(&ray("[10]", "[5]")).field, "ray[0].distance_mm");
        assert_eq!(err(&ray("[20, 10]", "[5, 4]")).field, "ray[0].distance_mm");
        assert_eq!(err(&ray("[10, 10]", "[5, 4]")).field, "ray[0].distance_mm");
        assert_eq!(err(&ray("[10, 20]", "[5, 6]")).field, "ray[0].reading");
        assert_eq!(err(&ray("[10, 20]", "[2000, 6]")).field, "ray[0].reading");
        assert_eq!(err(&ray("[10, 20]", "[5.5, 1]")).field, "ray[0].reading");
        assert_eq!(err(&ray("[10, 20]", "[5]")).field, "ray[0].reading");
        assert_eq!(err(&ray("[10, nan]", "[5, 1]")).field, "ray[0].distance_mm");
        let e = err("[[sensor.2.ray]]\ndistance_mm = [1, 2]\nreading = [3, 2]\n");
        assert_eq!(e.field, "sensor.0", "{e}");
        let e = err("[[sensor.9.ray]]\ndistance_mm = [1, 2]\nreading = [3, 2]\n");
        assert_eq!(e.field, "sensor.9", "{e}");
        let e = err("[[ray]]\ndistance = [1, 2]\nreading = [3, 2]\n");
        assert_eq!(e.source_name, "t.toml");
        assert!(e.to_string().contains("distance"), "{e}");
    }

    #[test]
    fn own_rays_replace_the_default_rays() {
        let text = "[[ray]]\ndistance_mm = [10, 20]\nreading = [500, 100]\n\n[[sensor.3.ray]]\nangle_deg = 10\ndistance_mm = [5, 50]\nreading = [900, 0]\n";
        let t = SensorTable::from_toml_str(text, "t.toml").unwrap();
        assert_eq!(t.rays_of(2)[0].samples(), [(10.0, 500.0), (20.0, 100.0)]);
        assert_eq!(t.rays_of(3)[0].samples(), [(5.0, 900.0), (50.0, 0.0)]);
        assert_eq!(t.rays_of(3)[0].angle_deg(), 10.0);
    }

    #[test]
    fn a_written_table_reads_back_the_same() {
        let k = SensorTable::khepera();
        let back = SensorTable::from_toml_str(&k.to_toml("khepera"), "k.toml").unwrap();
        assert_eq!(back, k);
        assert!(std::ptr::eq(k.clone().intern(), back.intern()));
    }

    #[test]
    fn calibration_takes_medians_and_reports_the_spread() {
        let m = |d: f64, v: f64| Measurement {
            sensor: 4,
            distance_mm: d,
            reading: v,
        };
        let rows = [
            m(10.0, 900.0),
            m(10.0, 1000.0),
            m(10.0, 950.0),
            m(30.0, 300.0),
            m(30.0, 320.0),
            m(50.0, 10.0),
            m(50.0, 30.0),
        ];
        let c = calibrate(&rows, SensorScale::KHEPERA).unwrap();
        assert_eq!(
            c.table.rays_of(0)[0].samples(),
            [(10.0, 950.0), (30.0, 310.0), (50.0, 20.0)]
        );
        assert_eq!(c.spread[0].std, 50.0);
        let rel = (50.0 + 2.0 * 200f64.sqrt()) / (950.0 + 310.0 + 20.0);
        assert!((c.relative_spread - rel).abs() < 1e-12);
        assert!((c.noise - 0.5f64.min(3f64.sqrt() * c.relative_spread)).abs() < 1e-12);
    }

    #[test]
    fn calibration_pools_medians_that_rise_with_distance() {
        let m = |d: f64, v: f64| Measurement {
            sensor: 0,
            distance_mm: d,
            reading: v,
        };
        let c = calibrate(
            &[m(10.0, 800.0), m(20.0, 100.0), m(30.0, 120.0), m(40.0, 0.0)],
            SensorScale::KHEPERA,
        )
        .unwrap();
        assert_eq!(
            c.table.rays_of(0)[0].samples(),
            [(10.0, 800.0), (20.0, 110.0), (30.0, 110.0), (40.0, 0.0)]
        );
        assert_eq!(c.notes.len(), 2, "{:?}", c.notes);
        let e = calibrate(
            &[
                m(10.0, 800.0),
                Measurement {
                    sensor: 1,
                    distance_mm: 10.0,
                    reading: 5.0,
                },
            ],
            SensorScale::KHEPERA,
        )
        .unwrap_err();
        assert_eq!(e.field, "sensor", "{e}");
    }
}
