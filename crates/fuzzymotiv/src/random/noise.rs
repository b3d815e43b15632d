//! The one place values are perturbed: the paper's "6 %" multiplicative noise (docs/model.md §3).

use crate::random::rng::{Rng, uniform};

/// Multiplies `value` by a draw from U(1 − level, 1 + level). With `level == 0` nothing is
/// drawn and the value is returned unchanged, so noise-free trials are exactly repeatable.
///
/// ```
/// use fuzzymotiv::random::{perturb, rng_from_seed};
/// let mut rng = rng_from_seed(1);
/// assert_eq!(perturb(100.0, 0.0, &mut rng), 100.0);
/// let v = perturb(100.0, 0.06, &mut rng);
/// assert!((94.0..106.0).contains(&v));
/// ```
#[inline]
pub fn perturb<R: Rng + ?Sized>(value: f64, level: f64, rng: &mut R) -> f64 {
    if level == 0.0 {
        value
    } else {
        value * uniform(rng, 1.0 - level, 1.0 + level)
    }
}

/// Sensor noise: perturbs each reading and clamps to [0, `max`].
#[inline(always)]
pub fn perturb_sensors<R: Rng + ?Sized>(values: &mut [f64], level: f64, max: f64, rng: &mut R) {
    if level == 0.0 {
        return;
    }
    // Eight readings (the Khepera's, the e-puck2's) in a loop of known length, which the
    // compiler unrolls; any other count in the same loop over the slice: the same draws.
    match <&mut [f64; 8]>::try_from(&mut *values) {
        Ok(eight) => perturb_each(eight, level, max, rng),
        Err(_) => perturb_each(values, level, max, rng),
    }
}

/// [`perturb_sensors`]' loop.
#[inline(always)]
fn perturb_each<R: Rng + ?Sized>(values: &mut [f64], level: f64, max: f64, rng: &mut R) {
    for v in values.iter_mut() {
        if *v == 0.0 {
            // 0 · u = 0 for every draw: skip the arithmetic, keep the stream in step.
            rng.next_u64();
        } else {
            *v = perturb(*v, level, rng).clamp(0.0, max);
        }
    }
}
