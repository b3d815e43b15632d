//! Two-sided permutation tests: sign flips of paired differences, and relabelling of two
//! independent samples. Exact enumeration up to [`EXACT_LIMIT`] arrangements, else seeded
//! random arrangements.

use crate::random::rng::{Rng, rng_from_seed, shuffle};

use super::mean;

/// The most arrangements (sign patterns, or splits of the pooled values) enumerated exactly:
/// 2^16 = 65 536 (16 paired values; 8 + 8, 5 + 13, … unpaired).
pub const EXACT_LIMIT: u64 = 1 << 16;

/// Values of the statistic closer than this, relative to the observed one, count as equal
/// (ties), so that sums added in another order tie as they do in exact arithmetic: SciPy's
/// `permutation_test` tolerance (100 machine epsilons).
pub const TIE_TOLERANCE: f64 = 100.0 * f64::EPSILON;

/// A permutation test's p-value and how it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PermutationP {
    /// The two-sided p-value: twice the smaller one-sided p-value, at most 1.
    pub p: f64,
    /// Whether every arrangement was enumerated (else `arrangements` random ones).
    pub exact: bool,
    /// Arrangements enumerated (exact) or drawn (resampled).
    pub arrangements: u64,
    /// The smallest p-value the test could give with this design: 2 / arrangements when exact
    /// (at most 1), 2 / (resamples + 1) when resampled.
    pub min_p: f64,
}

/// Counts of the statistic's null values at or below, and at or above, the observed one.
struct Tally {
    observed: f64,
    tolerance: f64,
    le: u64,
    ge: u64,
    n: u64,
}

impl Tally {
    fn new(observed: f64) -> Tally {
        Tally {
            observed,
            tolerance: (TIE_TOLERANCE * observed).abs(),
            le: 0,
            ge: 0,
            n: 0,
        }
    }

    fn add(&mut self, t: f64) {
        self.n += 1;
        self.le += u64::from(t <= self.observed + self.tolerance);
        self.ge += u64::from(t >= self.observed - self.tolerance);
    }

    /// Exact: 2 min(le, ge) / n. Resampled (the observed arrangement counted once more, so a
    /// p-value is never 0): 2 (min(le, ge) + 1) / (n + 1). At most 1.
    fn p(&self, exact: bool) -> PermutationP {
        let extra = u64::from(!exact);
        let tail = self.le.min(self.ge) + extra;
        let total = (self.n + extra) as f64;
        PermutationP {
            p: (2.0 * tail as f64 / total).min(1.0),
            exact,
            arrangements: self.n,
            min_p: (2.0 * extra.max(1) as f64 / total).min(1.0),
        }
    }
}

/// The sign-flip test of paired differences `d` (their mean is the statistic): under the null
/// hypothesis each difference is as likely negated, so the 2^n sign patterns are equally
/// likely. Exact for n ≤ 16; else `resamples` random patterns from `seed`.
///
/// ```
/// use fuzzymotiv::statistics::sign_flip_p;
/// // Five positive differences: only the observed pattern is as extreme on its side.
/// let r = sign_flip_p(&[1.0, 2.0, 0.5, 3.0, 1.5], 99_999, 7);
/// assert_eq!((r.p, r.exact, r.arrangements), (1.0 / 16.0, true, 32));
/// ```
pub fn sign_flip_p(d: &[f64], resamples: usize, seed: u64) -> PermutationP {
    let n = d.len();
    // Difference i is negated where bit i of `signs` is set.
    let flipped = |signs: u64| -> f64 {
        let sum: f64 = d
            .iter()
            .enumerate()
            .map(|(i, &v)| if signs >> i & 1 == 1 { -v } else { v })
            .sum();
        sum / n as f64
    };
    let mut tally = Tally::new(mean(d));
    if n < 64 && (1u64 << n) <= EXACT_LIMIT {
        for signs in 0..1u64 << n {
            tally.add(flipped(signs));
        }
        return tally.p(true);
    }
    let mut rng = rng_from_seed(seed);
    let mut signs = vec![false; n];
    for _ in 0..resamples {
        for chunk in signs.chunks_mut(64) {
            let bits = rng.next_u64();
            for (i, s) in chunk.iter_mut().enumerate() {
                *s = bits >> i & 1 == 1;
            }
        }
        let sum: f64 = d
            .iter()
            .zip(&signs)
            .map(|(&v, &s)| if s { -v } else { v })
            .sum();
        tally.add(sum / n as f64);
    }
    tally.p(false)
}

/// C(n, k), or `None` above [`EXACT_LIMIT`].
fn choose_within_limit(n: usize, k: usize) -> Option<u64> {
    let k = k.min(n - k) as u128;
    let mut c: u128 = 1;
    for i in 0..k {
        c = c * (n as u128 - i) / (i + 1);
        if c > EXACT_LIMIT as u128 {
            return None;
        }
    }
    Some(c as u64)
}

/// The two-sample permutation test of independent samples `a` and `b` (the statistic is
/// mean(a) − mean(b)): under the null hypothesis every split of the pooled values into groups
/// of their sizes is equally likely. Exact when there are at most [`EXACT_LIMIT`] splits
/// (C(n_a + n_b, n_a)); else `resamples` random splits from `seed`.
///
/// ```
/// use fuzzymotiv::statistics::two_sample_p;
/// // {1, 2} vs {3, 4}: of the 6 splits only the observed one has a difference of −2 or less.
/// let r = two_sample_p(&[1.0, 2.0], &[3.0, 4.0], 99_999, 7);
/// assert_eq!((r.p, r.arrangements), (2.0 / 6.0, 6));
/// ```
pub fn two_sample_p(a: &[f64], b: &[f64], resamples: usize, seed: u64) -> PermutationP {
    let pooled: Vec<f64> = a.iter().chain(b).copied().collect();
    let (na, total) = (a.len(), pooled.len());
    let mut tally = Tally::new(mean(a) - mean(b));
    let mut in_a = vec![false; total];
    let split = |in_a: &[bool], tally: &mut Tally| {
        let (mut sa, mut sb) = (0.0, 0.0);
        for (&v, &first) in pooled.iter().zip(in_a) {
            if first { sa += v } else { sb += v }
        }
        tally.add(sa / na as f64 - sb / (total - na) as f64);
    };
    if choose_within_limit(total, na).is_some() {
        // Every combination of na indices, in lexicographic order.
        let mut idx: Vec<usize> = (0..na).collect();
        loop {
            in_a.iter_mut().for_each(|f| *f = false);
            idx.iter().for_each(|&i| in_a[i] = true);
            split(&in_a, &mut tally);
            let Some(i) = (0..na).rev().find(|&i| idx[i] < total - na + i) else {
                break;
            };
            idx[i] += 1;
            for j in i + 1..na {
                idx[j] = idx[j - 1] + 1;
            }
        }
        return tally.p(true);
    }
    let mut rng = rng_from_seed(seed);
    let mut order: Vec<usize> = (0..total).collect();
    for _ in 0..resamples {
        shuffle(&mut rng, &mut order);
        in_a.iter_mut().for_each(|f| *f = false);
        order[..na].iter().for_each(|&i| in_a[i] = true);
        split(&in_a, &mut tally);
    }
    tally.p(false)
}
