//! Hand-computed cases of the tests, intervals, verdicts and the Holm adjustment.

use super::permutation::{sign_flip_p, two_sample_p};
use super::*;

const R: usize = PERMUTATION_RESAMPLES;

/// Five positive differences: of the 32 sign patterns only the observed one reaches its mean
/// (one-sided 1/32), so p = 2/32 = 1/16, the smallest five pairs can give.
#[test]
fn five_positive_pairs_give_one_sixteenth() {
    let c = paired(&[3.0, 4.0, 5.0, 6.0, 7.0], &[1.0; 5], &Settings::default()).unwrap();
    assert_eq!((c.p, c.exact, c.arrangements), (1.0 / 16.0, true, 32));
    assert_eq!(c.min_p, 1.0 / 16.0);
    assert!(!c.can_detect(), "1/16 is not below 0.05");
    assert_eq!(c.verdict(Expect::Higher), Verdict::NotSignificant);
    assert_eq!(
        Verdict::of(c.difference, c.p, Expect::Higher, 0.1),
        Verdict::Holds
    );
    assert_eq!(
        Verdict::of(c.difference, c.p, Expect::Lower, 0.1),
        Verdict::Opposite
    );
}

/// Differences symmetric about 0: the mean is 0 and half of the patterns lie on each side,
/// so p = 1.
#[test]
fn symmetric_differences_give_p_one() {
    let r = sign_flip_p(&[1.0, -1.0, 2.0, -2.0], R, 0);
    assert_eq!((r.p, r.exact, r.arrangements), (1.0, true, 16));
    let c = paired(&[1.0, 2.0, 3.0], &[1.0, 2.0, 3.0], &Settings::default()).unwrap();
    assert_eq!(
        (c.difference, c.p, c.ci_low, c.ci_high),
        (0.0, 1.0, 0.0, 0.0)
    );
    assert_eq!(c.verdict(Expect::Higher), Verdict::NotSignificant);
}

/// d = (1, 2, 3, −4): the 16 sums ±1 ±2 ±3 ±4 are 10 − 2s over the subset sums s of
/// {1, 2, 3, 4}: 10 8 6 4 2 4 2 0 0 −2 −4 −2 −4 −6 −8 −10. The observed sum 2 is reached or
/// exceeded by 7 patterns and not exceeded by 11: p = 2 · 7/16 = 7/8.
#[test]
fn four_pairs_enumerated_by_hand() {
    let r = sign_flip_p(&[1.0, 2.0, 3.0, -4.0], R, 0);
    assert_eq!(r.p, 7.0 / 8.0);
    // Ties across float sums: 0.1 + 0.2 ≠ 0.3 in floating point, but the patterns tie.
    let r = sign_flip_p(&[0.1, 0.2, 0.3], R, 0);
    // Sums ±0.1 ±0.2 ±0.3: 0.6 is the largest, reached by one pattern of 8: p = 2/8.
    assert_eq!(r.p, 0.25);
}

/// Unpaired, a = {1, 2}, b = {3, 4}: the 6 splits of {1, 2, 3, 4} into two pairs give mean
/// differences −2, −1, 0, 0, 1, 2; the observed −2 is the lowest: p = 2 · 1/6 = 1/3.
#[test]
fn two_pairs_unpaired_by_hand() {
    let c = unpaired(&[1.0, 2.0], &[3.0, 4.0], &Settings::default()).unwrap();
    assert_eq!(
        (c.difference, c.p, c.exact, c.arrangements),
        (-2.0, 1.0 / 3.0, true, 6)
    );
    assert_eq!(c.min_p, 1.0 / 3.0);
}

/// Unpaired, a = {5}, b = {1, 2, 3}: the 4 splits give x − mean(rest) = −7/3, −1, 1/3, 3 for
/// x = 1, 2, 3, 5; the observed 3 is the highest: p = 2 · 1/4 = 1/2. Swapped samples give
/// the same p.
#[test]
fn unequal_sizes_unpaired_by_hand() {
    let r = two_sample_p(&[5.0], &[1.0, 2.0, 3.0], R, 0);
    assert_eq!((r.p, r.arrangements), (0.5, 4));
    assert_eq!(two_sample_p(&[1.0, 2.0, 3.0], &[5.0], R, 0).p, 0.5);
    // a = {1, 4}, b = {2, 3}: the mean differences of the 6 splits are −2, −1, 0, 0, 1, 2
    // (observed 0: 4 at or below, 4 at or above), p = min(1, 2 · 4/6) = 1.
    assert_eq!(two_sample_p(&[1.0, 4.0], &[2.0, 3.0], R, 0).p, 1.0);
}

/// Above 2^16 arrangements the tests resample: 20 positive pairs (2^20 patterns) and 10 + 10
/// values (C(20, 10) = 184 756 splits). The observed arrangement is the most extreme, so
/// p = 2 (k + 1) / (R + 1) with k the random ones as extreme (at most a few).
#[test]
fn large_designs_resample_with_the_observed_counted_once_more() {
    let d: Vec<f64> = (1..=20).map(f64::from).collect();
    let r = sign_flip_p(&d, R, 3);
    assert!(!r.exact && r.arrangements == R as u64);
    assert_eq!(r.min_p, 2.0 / (R + 1) as f64);
    assert!(r.p >= r.min_p && r.p <= 4.0 / (R + 1) as f64, "{r:?}");
    assert_eq!(r, sign_flip_p(&d, R, 3), "deterministic");
    let (a, b) = (&d[10..], &d[..10]);
    let r = two_sample_p(a, b, R, 3);
    assert!(!r.exact && r.p <= 4.0 / (R + 1) as f64, "{r:?}");
    // 8 + 8 = C(16, 8) = 12 870 splits: exact.
    assert!(two_sample_p(&d[..8], &d[8..16], R, 3).exact);
}

/// The interval: identical differences give a point; the bootstrap means lie between the
/// smallest and largest difference, and the same seed gives the same bits.
#[test]
fn bootstrap_interval_is_bounded_and_deterministic() {
    let c = paired(&[3.0, 3.0, 3.0], &[1.0, 1.0, 1.0], &Settings::default()).unwrap();
    assert_eq!((c.ci_low, c.ci_high), (2.0, 2.0));
    let a = [12.0, 15.0, 9.0, 20.0, 14.0, 11.0];
    let b = [10.0, 10.0, 10.0, 10.0, 10.0, 10.0];
    let s = Settings::default();
    let c = paired(&a, &b, &s).unwrap();
    assert!(-1.0 <= c.ci_low && c.ci_low < c.difference && c.difference < c.ci_high);
    assert!(c.ci_high <= 10.0);
    assert_eq!(c, paired(&a, &b, &s).unwrap());
    let other = paired(&a, &b, &Settings { seed: 1, ..s }).unwrap();
    // Another seed, other resamples: the bounds move by at most a step of the discrete
    // bootstrap distribution here (means of six values are multiples of 1/6).
    assert!((c.ci_low - other.ci_low).abs() <= 0.5 && (c.ci_high - other.ci_high).abs() <= 0.5);
    assert_eq!(c.p, other.p, "an exact p does not depend on the seed");
}

/// Value stability: the default settings' interval for fixed data, pinned bit for bit.
#[test]
fn bootstrap_values_are_stable() {
    let a = [12.0, 15.0, 9.0, 20.0, 14.0, 11.0];
    let b = [10.0; 6];
    let c = paired(&a, &b, &Settings::default()).unwrap();
    assert_eq!((c.ci_low, c.ci_high), (0.833_333_333_333_333_4, 6.5));
    let u = unpaired(&a, &[10.0, 8.0, 13.0], &Settings::default()).unwrap();
    assert_eq!((u.ci_low, u.ci_high), (-0.5, 6.833_333_333_333_334));
}

/// d = (1, 2, 3, 4): sd = √(5/3) = 1.2910, SE = sd/2, MDD = (1.959964 + 0.841621) · SE.
#[test]
fn minimum_detectable_difference_by_hand() {
    let c = paired(&[1.0, 2.0, 3.0, 4.0], &[0.0; 4], &Settings::default()).unwrap();
    let expected = 2.801_585 * (5.0f64 / 3.0).sqrt() / 2.0;
    assert!((c.mdd.unwrap() - expected).abs() < 1e-5, "{:?}", c.mdd);
    let one = paired(&[1.0], &[0.0], &Settings::default()).unwrap();
    assert_eq!((one.mdd, one.p), (None, 1.0));
    // Unpaired {1, 2} vs {0, 1}: s² = 1/2 each, SE = √(s_a²/n_a + s_b²/n_b) = √(1/2).
    let u = unpaired(&[1.0, 2.0], &[0.0, 1.0], &Settings::default()).unwrap();
    assert!((u.mdd.unwrap() - 2.801_585 * 0.5f64.sqrt()).abs() < 1e-5);
}

#[test]
fn holm_adjusts_step_down_and_keeps_order() {
    assert_eq!(holm(&[0.01, 0.04, 0.03]), vec![0.03, 0.06, 0.06]);
    assert_eq!(holm(&[0.5, 0.01]), vec![0.5, 0.02]);
    assert_eq!(holm(&[0.6, 0.4]), vec![0.8, 0.8]);
    assert_eq!(holm(&[]), Vec::<f64>::new());
}

#[test]
fn bad_input_is_named() {
    let s = Settings::default();
    assert_eq!(paired(&[], &[], &s), Err(StatsError::Empty("a")));
    assert_eq!(
        paired(&[1.0], &[1.0, 2.0], &s),
        Err(StatsError::Lengths { a: 1, b: 2 })
    );
    let e = unpaired(&[1.0], &[f64::NAN], &s).unwrap_err();
    assert_eq!(
        e.to_string(),
        "b[0] is NaN: every value must be a finite number"
    );
    let e = paired(&[1.0], &[1.0], &Settings { alpha: 1.0, ..s }).unwrap_err();
    assert!(
        e.to_string().contains("alpha must be between 0 and 1"),
        "{e}"
    );
}

/// Type 7 quantiles (R's and NumPy's default), as the study's fitness figure draws medians and
/// quartiles over seeds.
#[test]
fn quantile_interpolates_linearly_between_order_statistics() {
    assert_eq!(quantile(&[3.0, 1.0, 2.0], 0.5), 2.0);
    assert_eq!(quantile(&[4.0, 1.0, 2.0, 3.0], 0.5), 2.5);
    assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0, 5.0], 0.25), 2.0);
    assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0], 0.25), 1.75);
    assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0], 0.75), 3.25);
    assert_eq!(quantile(&[7.0], 0.75), 7.0);
    assert!(quantile(&[], 0.5).is_nan());
}

#[test]
fn mean_std_is_the_sample_std_and_zero_for_one_value() {
    let (m, s) = mean_std(&[1.0, 2.0, 3.0, 4.0]);
    assert_eq!(m, 2.5);
    assert_eq!(s, sample_sd(&[1.0, 2.0, 3.0, 4.0]).unwrap());
    assert_eq!(mean_std(&[7.0]), (7.0, 0.0));
    let (m, s) = mean_std(&[]);
    assert!(m.is_nan() && s == 0.0);
}

/// Six positive differences 1..6 (p = 2/64 < 0.05, MDD ≈ 2.1 < 3.5): the test's verdict;
/// the same comparison with a detectable difference above |3.5| is inconclusive whatever p,
/// and without one (no spread) the test's verdict again.
#[test]
fn an_effect_within_the_detectable_difference_is_inconclusive() {
    let a = [2.0, 3.0, 4.0, 5.0, 6.0, 7.0];
    let mut c = paired(&a, &[1.0; 6], &Settings::default()).unwrap();
    assert_eq!((c.difference, c.p), (3.5, 1.0 / 32.0));
    assert!(c.mdd.is_some_and(|m| m < 3.5), "{:?}", c.mdd);
    assert_eq!(c.verdict_with_power(Expect::Higher), Verdict::Holds);
    assert_eq!(c.verdict_with_power(Expect::Lower), Verdict::Opposite);
    assert_eq!(
        c.verdict_with_power(Expect::Higher).direction_label(),
        "higher"
    );
    assert_eq!(
        c.verdict_with_power(Expect::Lower).direction_label(),
        "lower"
    );
    c.mdd = Some(3.6);
    assert_eq!(c.verdict_with_power(Expect::Higher), Verdict::Inconclusive);
    assert_eq!(Verdict::Inconclusive.label(), "inconclusive");
    assert_eq!(Verdict::Inconclusive.direction_label(), "inconclusive");
    c.mdd = None;
    assert_eq!(c.verdict_with_power(Expect::Higher), Verdict::Holds);
    c.p = 0.5;
    assert_eq!(
        c.verdict_with_power(Expect::Higher).direction_label(),
        "not significant"
    );
}

/// A difference with no sign (NaN) says nothing, even at a small p.
#[test]
fn a_nan_difference_is_not_significant() {
    let v = Verdict::of(f64::NAN, 0.001, Expect::Higher, 0.05);
    assert_eq!(v, Verdict::NotSignificant);
}
