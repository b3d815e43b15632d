//! The network in 16-bit fixed point for the Aseba VM, and the float network it approximates.
//!
//! **Inputs** are the readings themselves, clamped to `[0, R]` (`R` = the robot's
//! `reading_max`, 4505 on the Thymio II), so that 1.0 is the integer `R` and no input is
//! rounded; a constant input `R` carries the bias, so a hidden unit's row `[bias, w₁ … w_N]` is
//! used in the genome's order. The hidden activations, inputs of the output layer, are Q12
//! (1.0 = 4096), with a constant 4096 for the outputs' bias.
//!
//! **Weights** are quantised per unit (hidden or output): with `one` the integer that stands
//! for an input of 1.0 (`R` or 4096), the row's weights become `u = round(w · 2^(e+12) / one)`
//! with the largest exponent `e` (at most [`E_MAX`]) for which every `|u| ≤ 32767` and the
//! row's largest possible 32-bit accumulator `Σ|u| · one` stays below 2³¹. Then
//! `Σ u · v ≈ 2^(e+12) · s` for the real sum `s`. A weight far outside the 16-bit range
//! lowers its own row's `e` (the row's small weights lose precision, or round to 0) instead of
//! wrapping.
//!
//! **Sums**: `math.dot(s, u, v, shift)` adds `Σ u · v` in 32 bits and shifts right (floor)
//! by `shift = e + 12 − L`, giving the sum in Q`L`: `L` = [`SUM_Q`] (10) unless the row's
//! largest possible sum would not fit 16 bits, then the largest `L` that fits. The sum is
//! clamped to ±8.0 (`math.clamp` with `±2^(L+3)`) and brought to Q10 by a multiplication by
//! `2^(10−L)` (`math.mul`); with `L < −3` every non-zero sum is beyond ±8 and saturates the
//! logistic anyway, so the factor stops at 2¹³ (a sum of ±1 becomes ±8.0).
//!
//! **Logistic**: `σ(u)` for `u` in Q10 on [−8, 8], as Q12 (0 … 4096): a table of
//! `round(4096 · σ(i/16))` for `i = 0 … 128` (one more entry repeats the last, so that the
//! interpolation may read `T[k+1]` at `|u| = 8`), linear interpolation in steps of 1/16 on
//! `|u|`, and `σ(−u) = 1 − σ(u)`. The interpolation's error is below `σ''·(1/16)²/8 < 5·10⁻⁵`,
//! the table's rounding 1.2·10⁻⁴ (half a Q12 step), and beyond ±8 `σ` is within 3.4·10⁻⁴ of
//! the table's end.

use crate::simulation::math::logistic;

/// Q-format of the inputs, hidden activations and motor outputs: 1.0 is `2^12` = 4096.
pub(crate) const Q: i32 = 12;
/// 1.0 in Q12.
pub(crate) const ONE: i32 = 1 << Q;
/// Q-format of a sum fed to the logistic (Q10: 1.0 = 1024, ±8.0 = ±8192).
pub(crate) const SUM_Q: i32 = 10;
/// Largest weight exponent used (weights below `2^-20` round to 0 at it; a larger `e` would
/// need a shift beyond `math.dot`'s 32).
pub(crate) const E_MAX: i32 = 20;
/// Table step on `|u|` in Q10 (1/16): `k = |u| >> TABLE_SHIFT`.
pub(crate) const TABLE_SHIFT: i32 = 6;
/// Table entries: `i = 0 … 128` (|u| ≤ 8.0) and a repeat of the last.
pub(crate) const TABLE_LEN: usize = 130;

/// One unit (hidden or output) in fixed point.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct QUnit {
    /// `round(w · 2^(e+12) / one)` for the row `[bias, w₁, …]`.
    pub weights: Vec<i16>,
    /// The weight exponent `e`.
    pub e: i32,
    /// The sum's Q-format `L` after `math.dot` (10 unless the row's sums are too large).
    pub l: i32,
    /// `math.dot`'s shift `e + 12 − L` (0 … 32).
    pub shift: i16,
    /// The clamp bound of the sum in Q`L` (±8.0).
    pub bound: i16,
    /// The factor bringing a clamped sum to Q10.
    pub up: i16,
}

/// The row `[bias, w…]` (finite weights) quantised for inputs where the integer `one`
/// (1 … 32767) stands for 1.0, as the module doc says.
pub(crate) fn quantise_row(row: &[f64], one: i64) -> QUnit {
    let max = row.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let scale = |e: i32| 2f64.powi(e + Q) / one as f64;
    let mut e = if max > 0.0 {
        ((32767.0 / (max * scale(0))).log2().floor() as i32).min(E_MAX)
    } else {
        E_MAX
    };
    let weights = loop {
        let u: Vec<i64> = row.iter().map(|w| (w * scale(e)).round() as i64).collect();
        let fits = u.iter().all(|v| v.abs() <= 32767);
        let acc: i64 = u.iter().map(|v| v.abs()).sum::<i64>() * one;
        if fits && acc < (1i64 << 31) {
            break u;
        }
        e -= 1;
    };
    let acc: i64 = weights.iter().map(|v| v.abs()).sum::<i64>() * one;
    let mut l = SUM_Q.min(e + Q);
    while (acc >> (e + Q - l)) > 32767 {
        l -= 1;
    }
    let up_shift = (SUM_Q - l).min(SUM_Q + 3);
    QUnit {
        weights: weights.iter().map(|&v| v as i16).collect(),
        e,
        l,
        shift: (e + Q - l) as i16,
        bound: ((1 << (SUM_Q + 3)) >> up_shift) as i16,
        up: (1 << up_shift) as i16,
    }
}

/// The logistic table: `round(4096 · σ(i / 16))`, `i = 0 … 128`, then the last again.
pub(crate) fn logistic_table() -> Vec<i16> {
    let mut t: Vec<i16> = (0..TABLE_LEN - 1)
        .map(|i| (f64::from(ONE) * logistic(i as f64 / 16.0)).round() as i16)
        .collect();
    t.push(t[TABLE_LEN - 2]);
    t
}

/// The float network: `n` inputs, `h` hidden units, weights in the genome's order (per hidden
/// unit `[bias, n weights]`, per output `[bias, h weights]`), logistic units, inputs
/// `min(reading, reading_max) / reading_max`; the motor outputs `[mL, mR]` ∈ [0, 1]. Each
/// sum is the bias plus the products in input order, as the simulator's network adds them.
pub(crate) fn float_step(
    weights: &[f64],
    n: usize,
    h: usize,
    readings: &[f64],
    reading_max: f64,
) -> [f64; 2] {
    let x: Vec<f64> = readings
        .iter()
        .map(|&r| {
            if r <= 0.0 {
                0.0
            } else {
                r.min(reading_max) / reading_max
            }
        })
        .collect();
    let (hidden_w, out_w) = weights.split_at((h * (n + 1)).min(weights.len()));
    let hidden: Vec<f64> = hidden_w
        .chunks_exact(n + 1)
        .map(|w| logistic(w[1..].iter().zip(&x).fold(w[0], |s, (wk, xk)| s + wk * xk)))
        .collect();
    let mut out = [0.5; 2];
    for (o, w) in out.iter_mut().zip(out_w.chunks_exact(h + 1)) {
        *o = logistic(
            w[1..]
                .iter()
                .zip(&hidden)
                .fold(w[0], |s, (wk, hk)| s + wk * hk),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_weights_get_the_finest_exponent_and_q10_sums() {
        let u = quantise_row(&[0.5, -1.25, 3.0], 4096);
        // 32767 / 3 = 10922 → e = 13 (3 · 2^13 = 24576).
        assert_eq!(u.e, 13);
        assert_eq!(u.weights, vec![4096, -10240, 24576]);
        assert_eq!(u.l, 10);
        assert_eq!(u.shift, 15);
        assert_eq!((u.bound, u.up), (8192, 1));
    }

    #[test]
    fn raw_readings_fold_the_input_scale_into_the_weights() {
        // One = 4505: u = round(w · 2^(e+12) / 4505); 3 · 2^25 / 4505 = 22344.8.
        let u = quantise_row(&[0.5, -1.25, 3.0], 4505);
        assert_eq!(u.e, 13);
        assert_eq!(u.weights, vec![3724, -9310, 22345]);
        // Σ u · v with v = [4505, 0, 4505] is 2^25 · 3.5 within the weights' rounding.
        let dot = 3724 * 4505 + 22345 * 4505;
        assert!((f64::from(dot) / 2f64.powi(25) - 3.5).abs() < 1e-3);
    }

    #[test]
    fn a_huge_weight_lowers_its_rows_scale_instead_of_wrapping() {
        let u = quantise_row(&[1.0e9, 1.0, -2.0], 4096);
        assert!(u.weights.iter().all(|w| w.unsigned_abs() <= 32767));
        assert!(u.weights[0] > 16000, "{u:?}");
        assert_eq!(&u.weights[1..], &[0, 0]);
        assert!(u.l < -3, "{u:?}");
        assert_eq!((u.bound, u.up), (1, 8192));
        let acc: i64 = u
            .weights
            .iter()
            .map(|w| i64::from(w.unsigned_abs()))
            .sum::<i64>()
            * 4096;
        assert!(acc < 1 << 31 && (acc >> u.shift) <= 32767);
    }

    #[test]
    fn rows_whose_sums_overflow_q10_get_a_coarser_sum_format() {
        // |bias| + Σ|w| = 400 > 31.99 (the Q10 range): L = floor(log2(32767 / 400)) = 6.
        let row = [100.0, 100.0, -100.0, 100.0];
        let u = quantise_row(&row, 4096);
        assert_eq!(u.l, 6);
        assert_eq!((u.bound, u.up), (512, 16));
    }

    #[test]
    fn the_table_is_the_logistic_at_sixteenths() {
        let t = logistic_table();
        assert_eq!(t.len(), TABLE_LEN);
        assert_eq!(t[0], 2048);
        assert_eq!(t[16], (4096.0 * logistic(1.0)).round() as i16);
        assert_eq!(t[128], 4095);
        assert_eq!(t[129], t[128]);
    }
}
