//! Statistics over seeds: is a difference between two settings real, how large is it, and how
//! large a difference could the study have seen? One implementation for the study's claims,
//! comparisons of runs and the Python package; it uses nothing of the experiment, only the
//! crate's random generator.
//!
//! - **Paired** ([`paired`]): two settings that share each seed's random streams. The effect
//!   is the mean of the per-seed differences a − b; the p-value is the two-sided sign-flip
//!   permutation test ([`permutation::sign_flip_p`]): exact over all 2^n sign patterns for
//!   n ≤ 16, else [`PERMUTATION_RESAMPLES`] random patterns.
//! - **Unpaired** ([`unpaired`]): independent runs. The effect is mean(a) − mean(b); the
//!   p-value is the two-sided permutation test over splits of the pooled values
//!   ([`permutation::two_sample_p`]): exact when there are at most 2^16 splits, else random
//!   splits.
//! - **Two-sided p** is twice the smaller one-sided p-value, at most 1 (SciPy's
//!   `permutation_test`); for the paired test's symmetric null distribution this is the share
//!   of sign patterns at least as far from 0 as the observed mean. Resampled p-values count
//!   the observed arrangement once more ((k + 1) / (R + 1)), so they are never 0.
//! - **Interval**: a percentile bootstrap ([`mean_interval`], [`difference_interval`]) with [`BOOTSTRAP_RESAMPLES`]
//!   resamples, at `confidence` (95 % by default).
//! - **Minimum detectable difference** at power 1 − β (80 % by default), by the normal
//!   approximation (z_{1−α/2} + z_{1−β}) · SE, where SE is sd/√n of the paired differences, or
//!   √(s_a²/n_a + s_b²/n_b) unpaired; z from [`normal_quantile`]. With few seeds it is
//!   optimistic (a t quantile would be larger), and no difference at all can be detected when
//!   the smallest attainable p-value ([`Comparison::min_p`]) is not below α: with five paired
//!   seeds that is 2/32 = 1/16 > 0.05.
//! - **Several tests** (one per room): [`holm`] adjusts their p-values (Holm's step-down
//!   method, which keeps the family-wise error rate at α).
//!
//! Everything is deterministic: the same values and [`Settings`] give the same bits.
//!
//! ```
//! use fuzzymotiv::statistics::{Expect, Settings, Verdict, paired};
//! // Five seeds, the first setting ahead on every one.
//! let high = [80.0, 75.0, 90.0, 70.0, 85.0];
//! let low = [70.0, 72.0, 80.0, 69.0, 75.0];
//! let c = paired(&high, &low, &Settings::default()).unwrap();
//! assert_eq!(c.difference, 6.8);
//! assert_eq!(c.p, 1.0 / 16.0); // the smallest p five paired seeds can give
//! assert!(1.0 <= c.ci_low && c.ci_high <= 10.0); // between the smallest and largest difference
//! assert_eq!(c.verdict(Expect::Higher), Verdict::NotSignificant); // 1/16 ≥ 0.05
//! ```

pub(crate) mod bootstrap;
pub(crate) mod normal;
pub(crate) mod permutation;

pub use bootstrap::{difference_interval, mean_interval, quantile};
pub use normal::normal_quantile;
pub use permutation::{EXACT_LIMIT, PermutationP, sign_flip_p, two_sample_p};

use crate::random::seed::derive;

/// Bootstrap resamples of an interval (the default of [`Settings::bootstrap_resamples`]).
pub const BOOTSTRAP_RESAMPLES: usize = 10_000;

/// Random arrangements of a permutation test too large to enumerate (the default of
/// [`Settings::permutation_resamples`]): p-values are then multiples of 1 / 100 000.
pub const PERMUTATION_RESAMPLES: usize = 99_999;

/// How a comparison is computed. `Settings::default()` is the study's: α = 0.05, 95 %
/// intervals, 80 % power, [`BOOTSTRAP_RESAMPLES`], [`PERMUTATION_RESAMPLES`], seed 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Significance level α of the two-sided tests (0 < α < 1; default 0.05).
    pub alpha: f64,
    /// Coverage of the bootstrap interval (0 < c < 1; default 0.95).
    pub confidence: f64,
    /// Power 1 − β of the minimum detectable difference (0 < power < 1; default 0.8).
    pub power: f64,
    /// Bootstrap resamples (≥ 1; default [`BOOTSTRAP_RESAMPLES`]).
    pub bootstrap_resamples: usize,
    /// Random arrangements when a permutation test is not enumerated (≥ 1; default
    /// [`PERMUTATION_RESAMPLES`]).
    pub permutation_resamples: usize,
    /// Seed of the resampling streams (the bootstrap's and the permutation test's are derived
    /// from it; default 0).
    pub seed: u64,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            alpha: 0.05,
            confidence: 0.95,
            power: 0.8,
            bootstrap_resamples: BOOTSTRAP_RESAMPLES,
            permutation_resamples: PERMUTATION_RESAMPLES,
            seed: 0,
        }
    }
}

impl Settings {
    /// The settings if usable: α, confidence and power strictly between 0 and 1, resample
    /// counts at least 1.
    pub fn check(&self) -> Result<&Settings, StatsError> {
        for (name, v) in [
            ("alpha", self.alpha),
            ("confidence", self.confidence),
            ("power", self.power),
        ] {
            if v.is_nan() || v <= 0.0 || v >= 1.0 {
                return Err(StatsError::Setting(format!(
                    "{name} must be between 0 and 1 (exclusive), got {}",
                    crate::params::Num(v)
                )));
            }
        }
        for (name, v) in [
            ("bootstrap_resamples", self.bootstrap_resamples),
            ("permutation_resamples", self.permutation_resamples),
        ] {
            if v == 0 {
                return Err(StatsError::Setting(format!("{name} must be at least 1")));
            }
        }
        Ok(self)
    }

    /// The seed of the permutation test's random arrangements.
    fn permutation_seed(&self) -> u64 {
        derive(self.seed, &[1])
    }

    /// The seed of the bootstrap's resamples.
    fn bootstrap_seed(&self) -> u64 {
        derive(self.seed, &[2])
    }
}

/// Values a comparison cannot use.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StatsError {
    /// A sample without values.
    #[error("sample `{0}` has no values: a comparison needs at least one in each")]
    Empty(&'static str),
    /// Paired samples of different lengths.
    #[error("paired samples must have one value per seed each, got {a} and {b} values")]
    Lengths {
        /// Values in `a`.
        a: usize,
        /// Values in `b`.
        b: usize,
    },
    /// A NaN or infinite value.
    #[error("{sample}[{index}] is {value}: every value must be a finite number")]
    NotFinite {
        /// `a` or `b`.
        sample: &'static str,
        /// Its position.
        index: usize,
        /// The value.
        value: f64,
    },
    /// Unusable [`Settings`].
    #[error("statistics settings: {0}")]
    Setting(String),
}

/// The design of a comparison.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Design {
    /// One pair (a, b) per seed.
    Paired {
        /// Pairs.
        n: usize,
    },
    /// Two independent samples.
    Unpaired {
        /// Values in `a`.
        n_a: usize,
        /// Values in `b`.
        n_b: usize,
    },
}

/// Which way a claim says `a` differs from `b`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Expect {
    /// a > b.
    Higher,
    /// a < b.
    Lower,
}

/// What the data say of a directional claim at level α.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The difference has the claimed sign and p < α.
    Holds,
    /// The difference has the opposite sign and p < α.
    Opposite,
    /// p ≥ α (or no difference, or a NaN one): the data cannot tell.
    NotSignificant,
    /// |difference| < the minimum detectable difference, whatever p: the design is at the edge
    /// of its power and another base seed may give the other verdict
    /// ([`Comparison::verdict_with_power`]).
    Inconclusive,
}

impl Verdict {
    /// The verdict on a claim from a difference a − b and its two-sided p-value.
    pub fn of(difference: f64, p: f64, expect: Expect, alpha: f64) -> Verdict {
        let significant = p < alpha; // false for a NaN p
        if !significant || difference == 0.0 || difference.is_nan() {
            return Verdict::NotSignificant;
        }
        if (difference > 0.0) == (expect == Expect::Higher) {
            Verdict::Holds
        } else {
            Verdict::Opposite
        }
    }

    /// "holds", "opposite", "not significant" or "inconclusive".
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::Opposite => "opposite",
            Verdict::NotSignificant => "not significant",
            Verdict::Inconclusive => "inconclusive",
        }
    }

    /// The label of a verdict on "a is higher than b" said as a direction: "higher" (holds),
    /// "lower" (opposite), else [`Verdict::label`].
    pub fn direction_label(self) -> &'static str {
        match self {
            Verdict::Holds => "higher",
            Verdict::Opposite => "lower",
            other => other.label(),
        }
    }
}

/// A comparison of a with b: the effect, its interval, the test and what it could detect.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Paired or unpaired, and the sample sizes.
    pub design: Design,
    /// Mean of `a`.
    pub mean_a: f64,
    /// Mean of `b`.
    pub mean_b: f64,
    /// The effect: the mean of the per-pair differences a − b (paired) or mean(a) − mean(b).
    pub difference: f64,
    /// Lower bound of the percentile bootstrap interval of `difference`.
    pub ci_low: f64,
    /// Upper bound of the interval.
    pub ci_high: f64,
    /// The interval's coverage (e.g. 0.95).
    pub confidence: f64,
    /// Two-sided permutation p-value.
    pub p: f64,
    /// Whether `p` enumerated every arrangement (else resampled).
    pub exact: bool,
    /// Arrangements enumerated or drawn.
    pub arrangements: u64,
    /// The smallest p-value this design can give: below α or no claim can ever be shown.
    pub min_p: f64,
    /// The α of `mdd` and [`Comparison::verdict`].
    pub alpha: f64,
    /// The power of `mdd`.
    pub power: f64,
    /// The minimum detectable difference at level α and `power` (normal approximation); `None`
    /// with fewer than two values in a sample (no spread to estimate).
    pub mdd: Option<f64>,
}

impl Comparison {
    /// The verdict on "a is `expect` than b" at this comparison's α.
    pub fn verdict(&self, expect: Expect) -> Verdict {
        Verdict::of(self.difference, self.p, expect, self.alpha)
    }

    /// The project's verdict rule: [`Verdict::Inconclusive`] when the effect lies within the
    /// difference the design detects (|difference| < `mdd`), else [`Comparison::verdict`].
    pub fn verdict_with_power(&self, expect: Expect) -> Verdict {
        if self.mdd.is_some_and(|m| self.difference.abs() < m) {
            Verdict::Inconclusive
        } else {
            self.verdict(expect)
        }
    }

    /// Whether this design can reach p < α at all (its smallest p-value is below α).
    pub fn can_detect(&self) -> bool {
        self.min_p < self.alpha
    }
}

/// The mean of `values` (their sum in order, divided by the count; NaN for none).
pub fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len() as f64
}

/// The sample standard deviation (divided by n − 1); `None` for fewer than two values.
pub fn sample_sd(values: &[f64]) -> Option<f64> {
    let n = values.len();
    (n >= 2).then(|| {
        let m = mean(values);
        (values.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (n - 1) as f64).sqrt()
    })
}

/// The mean and the sample standard deviation of `values` ([`mean`], [`sample_sd`]), the std 0
/// for fewer than two values (no spread: the tables show a dash there).
///
/// ```
/// use fuzzymotiv::statistics::mean_std;
/// let (mean, std) = mean_std(&[1.0, 2.0, 3.0, 4.0]);
/// assert_eq!(mean, 2.5);
/// assert!((std - (5.0f64 / 3.0).sqrt()).abs() < 1e-15); // divided by n − 1, not n
/// assert_eq!(mean_std(&[7.0]), (7.0, 0.0));
/// ```
pub fn mean_std(values: &[f64]) -> (f64, f64) {
    (mean(values), sample_sd(values).unwrap_or(0.0))
}

/// The smallest true difference a two-sided test at level `alpha` detects with probability
/// `power`, for an estimate with standard error `se`: (z_{1−α/2} + z_power) · se (normal
/// approximation).
///
/// ```
/// use fuzzymotiv::statistics::minimum_detectable_difference;
/// let mdd = minimum_detectable_difference(1.0, 0.05, 0.8);
/// assert!((mdd - 2.801_585).abs() < 1e-6); // 1.959964 + 0.841621
/// ```
pub fn minimum_detectable_difference(se: f64, alpha: f64, power: f64) -> f64 {
    (normal_quantile(1.0 - alpha / 2.0) + normal_quantile(power)) * se
}

/// Holm's step-down adjustment of `p` (one p-value per test of a family): sorted ascending,
/// the i-th smallest (from 1) becomes max over j ≤ i of min(1, (m − j + 1) p_(j)); returned in
/// the input's order. A test is significant at family-wise level α when its adjusted p < α.
///
/// ```
/// use fuzzymotiv::statistics::holm;
/// assert_eq!(holm(&[0.01, 0.04, 0.03]), vec![0.03, 0.06, 0.06]);
/// ```
pub fn holm(p: &[f64]) -> Vec<f64> {
    let m = p.len();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&i, &j| p[i].total_cmp(&p[j]));
    let mut adjusted = vec![0.0; m];
    let mut running: f64 = 0.0;
    for (rank, &i) in order.iter().enumerate() {
        running = running.max(((m - rank) as f64 * p[i]).min(1.0));
        adjusted[i] = running;
    }
    adjusted
}

/// The checked samples: non-empty and finite.
fn check_samples(a: &[f64], b: &[f64]) -> Result<(), StatsError> {
    for (name, sample) in [("a", a), ("b", b)] {
        if sample.is_empty() {
            return Err(StatsError::Empty(name));
        }
        if let Some((index, &value)) = sample.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(StatsError::NotFinite {
                sample: name,
                index,
                value,
            });
        }
    }
    Ok(())
}

/// Paired comparison of `a` and `b` (one pair per seed, in the same order): the mean of the
/// differences a − b, its percentile bootstrap interval, the sign-flip permutation p-value and
/// the minimum detectable difference (see the [module docs](self)).
pub fn paired(a: &[f64], b: &[f64], settings: &Settings) -> Result<Comparison, StatsError> {
    settings.check()?;
    check_samples(a, b)?;
    if a.len() != b.len() {
        return Err(StatsError::Lengths {
            a: a.len(),
            b: b.len(),
        });
    }
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    let test = permutation::sign_flip_p(
        &d,
        settings.permutation_resamples,
        settings.permutation_seed(),
    );
    let (ci_low, ci_high) = bootstrap::mean_interval(
        &d,
        settings.confidence,
        settings.bootstrap_resamples,
        settings.bootstrap_seed(),
    );
    let se = sample_sd(&d).map(|sd| sd / (d.len() as f64).sqrt());
    Ok(Comparison {
        design: Design::Paired { n: d.len() },
        mean_a: mean(a),
        mean_b: mean(b),
        difference: mean(&d),
        ci_low,
        ci_high,
        confidence: settings.confidence,
        p: test.p,
        exact: test.exact,
        arrangements: test.arrangements,
        min_p: test.min_p,
        alpha: settings.alpha,
        power: settings.power,
        mdd: se.map(|se| minimum_detectable_difference(se, settings.alpha, settings.power)),
    })
}

/// Unpaired comparison of independent samples `a` and `b`: mean(a) − mean(b), its percentile
/// bootstrap interval (each sample resampled on its own), the two-sample permutation p-value
/// and the minimum detectable difference (see the [module docs](self)).
pub fn unpaired(a: &[f64], b: &[f64], settings: &Settings) -> Result<Comparison, StatsError> {
    settings.check()?;
    check_samples(a, b)?;
    let test = permutation::two_sample_p(
        a,
        b,
        settings.permutation_resamples,
        settings.permutation_seed(),
    );
    let (ci_low, ci_high) = bootstrap::difference_interval(
        a,
        b,
        settings.confidence,
        settings.bootstrap_resamples,
        settings.bootstrap_seed(),
    );
    let se = match (sample_sd(a), sample_sd(b)) {
        (Some(sa), Some(sb)) => Some((sa * sa / a.len() as f64 + sb * sb / b.len() as f64).sqrt()),
        _ => None,
    };
    Ok(Comparison {
        design: Design::Unpaired {
            n_a: a.len(),
            n_b: b.len(),
        },
        mean_a: mean(a),
        mean_b: mean(b),
        difference: mean(a) - mean(b),
        ci_low,
        ci_high,
        confidence: settings.confidence,
        p: test.p,
        exact: test.exact,
        arrangements: test.arrangements,
        min_p: test.min_p,
        alpha: settings.alpha,
        power: settings.power,
        mdd: se.map(|se| minimum_detectable_difference(se, settings.alpha, settings.power)),
    })
}

#[cfg(test)]
mod tests;
