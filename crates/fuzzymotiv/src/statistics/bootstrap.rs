//! Percentile bootstrap intervals: the statistic recomputed on resamples drawn with
//! replacement, and the interval between two quantiles of those values.

use crate::random::rng::{index, rng_from_seed};

/// The `q`-quantile (0 ≤ q ≤ 1) of `values` by linear interpolation between order
/// statistics: sorted ascending and counted from 0, the value at rank h = (n − 1) q,
/// interpolated between ranks ⌊h⌋ and ⌈h⌉ (Hyndman and Fan's type 7, the default of R and
/// NumPy). NaN for no values.
///
/// ```
/// use fuzzymotiv::statistics::quantile;
/// assert_eq!(quantile(&[4.0, 1.0, 3.0, 2.0], 0.5), 2.5);
/// assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0, 5.0], 0.25), 2.0);
/// ```
pub fn quantile(values: &[f64], q: f64) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    quantile_sorted(&v, q)
}

/// [`quantile`] of values already sorted ascending.
fn quantile_sorted(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let h = (v.len() - 1) as f64 * q.clamp(0.0, 1.0);
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    v[lo] + (h - lo as f64) * (v[hi] - v[lo])
}

/// The central `confidence` interval of the bootstrap values `boot`: their (1 − c)/2 and
/// (1 + c)/2 quantiles ([`quantile`], as SciPy's `bootstrap(method='percentile')`).
fn percentile_interval(mut boot: Vec<f64>, confidence: f64) -> (f64, f64) {
    boot.sort_by(f64::total_cmp);
    let tail = (1.0 - confidence) / 2.0;
    (
        quantile_sorted(&boot, tail),
        quantile_sorted(&boot, 1.0 - tail),
    )
}

/// The percentile bootstrap `confidence` interval of the mean of `d` (for paired data, the
/// per-pair differences): `resamples` resamples of n values drawn with replacement from `d`
/// (uniform indices from the stream of `seed`), each one's mean, and the interval between
/// their (1 − c)/2 and (1 + c)/2 quantiles. The same inputs and seed give the same bits.
///
/// ```
/// use fuzzymotiv::statistics::mean_interval;
/// let (lo, hi) = mean_interval(&[1.0, 2.0, 3.0, 4.0, 5.0], 0.95, 10_000, 7);
/// assert!(1.0 < lo && lo < 3.0 && 3.0 < hi && hi < 5.0);
/// ```
pub fn mean_interval(d: &[f64], confidence: f64, resamples: usize, seed: u64) -> (f64, f64) {
    let mut rng = rng_from_seed(seed);
    let n = d.len();
    let boot = (0..resamples)
        .map(|_| (0..n).map(|_| d[index(&mut rng, n)]).sum::<f64>() / n as f64)
        .collect();
    percentile_interval(boot, confidence)
}

/// The percentile bootstrap `confidence` interval of mean(a) − mean(b) for independent
/// samples: each resample draws n_a values from `a` and then n_b from `b`, with replacement
/// (one stream, from `seed`); then as [`mean_interval`].
///
/// ```
/// use fuzzymotiv::statistics::difference_interval;
/// let (lo, hi) = difference_interval(&[5.0, 6.0, 7.0], &[1.0, 2.0, 3.0], 0.95, 10_000, 7);
/// assert!(2.0 < lo && lo < 4.0 && 4.0 < hi && hi < 6.0);
/// ```
pub fn difference_interval(
    a: &[f64],
    b: &[f64],
    confidence: f64,
    resamples: usize,
    seed: u64,
) -> (f64, f64) {
    let mut rng = rng_from_seed(seed);
    let mut resample_mean = |x: &[f64]| {
        let n = x.len();
        (0..n).map(|_| x[index(&mut rng, n)]).sum::<f64>() / n as f64
    };
    let boot = (0..resamples)
        .map(|_| {
            let ma = resample_mean(a);
            ma - resample_mean(b)
        })
        .collect();
    percentile_interval(boot, confidence)
}
