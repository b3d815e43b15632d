//! Domain randomisation for evolution, `[trial.randomise]` (docs/model.md, "Trial"): ranges
//! from which every evaluation trial of the evolution draws its own robot — sensor and wheel
//! noise, a sensor-table scale, a wheel-speed bias, a body radius — on a stream derived from the
//! trial's own seed, so the draws do not depend on the number of threads. The draws are applied
//! as the robustness study's perturbations ([`crate::experiment::Perturbation`]).

use serde::{Deserialize, Serialize};

use crate::params::{FieldError, Num, check};
use crate::random::rng::{rng_from_seed, uniform};
use crate::random::seed::{derive, purpose};
use crate::simulation::robot::{RadiusRange, Robot};

/// `[trial.randomise]` as written: each key a range `[low, high]`; an omitted key is not
/// randomised. See [`Randomise`] for the ranges allowed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawRandomise {
    /// [`Randomise::noise`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub noise: Option<[f64; 2]>,
    /// [`Randomise::sensor_scale`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sensor_scale: Option<[f64; 2]>,
    /// [`Randomise::wheel_bias`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wheel_bias: Option<[f64; 2]>,
    /// [`Randomise::radius`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<[f64; 2]>,
}

/// Checked `[trial.randomise]`: at least one range, each `(low, high)` with `low ≤ high`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Randomise {
    /// Noise level (as `trial.noise`), within [0, 0.5].
    pub noise: Option<(f64, f64)>,
    /// Factor on every reading of the sensor table, within [0.1, 3]; drawn to 0.01 (each
    /// factor's table is kept for the rest of the process).
    pub sensor_scale: Option<(f64, f64)>,
    /// Both wheel speeds multiplied by 1 + bias, within [−0.5, 0.5].
    pub wheel_bias: Option<(f64, f64)>,
    /// Body radius (mm), within `robot.radius`'s range; a step must stay below its low end.
    pub radius: Option<(f64, f64)>,
}

/// One trial's draw: the value of each randomised quantity (none where not randomised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Draw {
    /// The noise level.
    pub noise: Option<f64>,
    /// The sensor-table scale.
    pub sensor_scale: Option<f64>,
    /// The wheel-speed bias.
    pub wheel_bias: Option<f64>,
    /// The body radius (mm).
    pub radius: Option<f64>,
}

/// A range `[low, high]` of `field` checked finite, ordered and within `[min, max]`.
fn range(
    r: Option<[f64; 2]>,
    field: &str,
    (min, max): (f64, f64),
    what: &str,
) -> Result<Option<(f64, f64)>, FieldError> {
    let Some([lo, hi]) = r else { return Ok(None) };
    check(lo.is_finite() && hi.is_finite(), field, || {
        format!(
            "must be two finite numbers [low, high], got [{}, {}]",
            Num(lo),
            Num(hi)
        )
    })?;
    check(lo <= hi, field, || {
        format!(
            "the low end {} is above the high end {}; write the range as [low, high]",
            Num(lo),
            Num(hi)
        )
    })?;
    check(lo >= min && hi <= max, field, || {
        format!(
            "must lie within [{}, {}] ({what}), got [{}, {}]",
            Num(min),
            Num(max),
            Num(lo),
            Num(hi)
        )
    })?;
    Ok(Some((lo, hi)))
}

impl Randomise {
    /// Checks `[trial.randomise]` for the robot `robot` stepping at most `step(noise)` mm at
    /// noise level `noise`; `None` when no key is given (nothing randomised).
    pub fn from_raw(
        raw: &RawRandomise,
        robot: &Robot,
        step: impl Fn(f64) -> f64,
        noise: f64,
    ) -> Result<Option<Randomise>, FieldError> {
        let r = Randomise {
            noise: range(
                raw.noise,
                "trial.randomise.noise",
                (0.0, 0.5),
                "a noise level",
            )?,
            sensor_scale: range(
                raw.sensor_scale,
                "trial.randomise.sensor_scale",
                (0.1, 3.0),
                "a factor on the sensor readings",
            )?,
            wheel_bias: range(
                raw.wheel_bias,
                "trial.randomise.wheel_bias",
                (-0.5, 0.5),
                "a bias on the wheel speeds, 0.1 for 10 % faster",
            )?,
            radius: range(
                raw.radius,
                "trial.randomise.radius",
                (0.0, 500.0),
                "a body radius in mm",
            )?,
        };
        if let Some((lo, hi)) = r.radius {
            let allowed = RadiusRange::of(robot.spec());
            for radius in [lo, hi] {
                check(allowed.contains(radius), "trial.randomise.radius", || {
                    allowed.reason("got an end", radius)
                })?;
            }
            let most = step(r.noise.map_or(noise, |n| n.1));
            check(most < lo, "trial.randomise.radius", || {
                format!(
                    "one step may move the robot {most:.1} mm, which must stay below the smallest radius {} mm so it cannot pass through walls",
                    Num(lo)
                )
            })?;
        }
        Ok((r != Randomise::NONE).then_some(r))
    }

    const NONE: Randomise = Randomise {
        noise: None,
        sensor_scale: None,
        wheel_bias: None,
        radius: None,
    };

    /// The draw of the trial whose stream is `trial_seed`: uniform in each range, on the
    /// stream `derive(trial_seed, [RANDOMISE])`, one number per quantity in the order noise,
    /// sensor scale, wheel bias, radius (drawn whether or not it is randomised, so that
    /// randomising one more quantity leaves the others' draws as they were).
    pub fn draw(&self, trial_seed: u64) -> Draw {
        let mut rng = rng_from_seed(derive(trial_seed, &[purpose::RANDOMISE]));
        let mut next = |r: Option<(f64, f64)>| {
            let u = uniform(&mut rng, 0.0, 1.0);
            r.map(|(lo, hi)| (lo + u * (hi - lo)).clamp(lo, hi))
        };
        Draw {
            noise: next(self.noise),
            sensor_scale: next(self.sensor_scale).map(|k| (k * 100.0).round() / 100.0),
            wheel_bias: next(self.wheel_bias),
            radius: next(self.radius),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checked(raw: RawRandomise) -> Result<Option<Randomise>, FieldError> {
        Randomise::from_raw(&raw, &Robot::default(), |n| 8.0 * (1.0 + n), 0.06)
    }

    #[test]
    fn draws_lie_in_their_ranges_and_follow_the_trial_seed() {
        let r = checked(RawRandomise {
            noise: Some([0.0, 0.2]),
            sensor_scale: Some([0.7, 1.3]),
            ..RawRandomise::default()
        })
        .unwrap()
        .unwrap();
        let a = r.draw(7);
        assert_eq!(a, r.draw(7));
        assert_ne!(a, r.draw(8));
        assert!((0.0..=0.2).contains(&a.noise.unwrap()));
        let k = a.sensor_scale.unwrap();
        assert!((0.7..=1.3).contains(&k) && (k * 100.0 - (k * 100.0).round()).abs() < 1e-9);
        assert_eq!((a.wheel_bias, a.radius), (None, None));
    }

    #[test]
    fn an_empty_randomise_table_randomises_nothing() {
        assert_eq!(checked(RawRandomise::default()), Ok(None));
    }

    #[test]
    fn bad_ranges_name_their_key() {
        let e = checked(RawRandomise {
            noise: Some([0.3, 0.1]),
            ..RawRandomise::default()
        })
        .unwrap_err();
        assert_eq!(e.field, "trial.randomise.noise");
        assert!(
            e.reason.contains("low end 0.3 is above the high end 0.1"),
            "{}",
            e.reason
        );
        let e = checked(RawRandomise {
            wheel_bias: Some([-0.1, 0.9]),
            ..RawRandomise::default()
        })
        .unwrap_err();
        assert_eq!(e.field, "trial.randomise.wheel_bias");
        let e = checked(RawRandomise {
            radius: Some([10.0, 30.0]),
            ..RawRandomise::default()
        })
        .unwrap_err();
        assert_eq!(e.field, "trial.randomise.radius");
    }

    /// A radius range's end the robot cannot have says so in the robot check's own words, with
    /// "got an end" (worded once from the range, not rewritten from the robot check's message).
    #[test]
    fn a_radius_end_the_robot_cannot_have_says_got_an_end() {
        let e = checked(RawRandomise {
            radius: Some([27.5, 90.0]),
            ..RawRandomise::default()
        })
        .unwrap_err();
        assert_eq!(e.field, "trial.randomise.radius");
        let allowed = RadiusRange::of(Robot::default().spec());
        assert_eq!(e.reason, allowed.reason("got an end", 90.0));
        assert!(e.reason.starts_with("must be in ["), "{}", e.reason);
        assert!(
            e.reason.ends_with("mm from the centre), got an end 90"),
            "{}",
            e.reason
        );
    }
}
