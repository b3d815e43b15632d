//! Fuzzy-motivated fitness: the zero-order TSK-style rule base of the paper
//! "Fuzzy Motivations for Evolutionary Behavior Learning by a Mobile Robot"
//! (Fig. 3, docs/model.md §8).
//!
//! Four fitness values `Y = (a, g, l, b)` (exploration, homing,
//! orientation/recognition, battery), each in `[0, 1]`, are fuzzified with `M`
//! triangular labels (default `M = 5`: V.L., L, M, H, V.H. with peaks at
//! 0, 0.25, 0.5, 0.75, 1). Every combination of labels is a rule
//! (`M^4 = 625` rules by default). Rule `n` with labels `(x1, x2, x3, x4)` has
//!
//! ```text
//! w[n] = min_i μ_{x_i}(Y_i)                 (firing strength)
//! f[n] = Σ_i X_i · Y_i · C[x_i]             (rule output)
//! F    = Σ_n w[n]·f[n] / Σ_n w[n]           (overall fitness)
//! ```
//!
//! where `X = (C, H, O, E)` are the robot's [`Motivations`] and `C[m]` is the
//! coefficient array (see [`CoefficientScheme`]). Rules are numbered with `x1`
//! varying fastest: `n = 1 + Σ_i (x_i − 1)·M^(i−1)`, so rule 10 is
//! `(V.H., L, V.L., V.L.)`.
//!
//! [`TskFitness::evaluate`] visits only the (at most 16) rules with non-zero
//! weight, in ascending rule-number order and with the same arithmetic as the
//! full loop over all rules, so its result is bit-identical to the naive
//! evaluation (zero-weight rules contribute exactly 0). It does not allocate.

use std::fmt;

use crate::fitness::motivation::{MAX_MOTIVATIONS, Motivation, Motivations};
use crate::params::Num;

/// Tolerance on `|C + H + O + E − 1|` accepted by [`Motivations::new`].
pub const MOTIVATION_SUM_TOLERANCE: f64 = 1e-9;

/// How far `C + H + O + E` may be off 1 and still be normalised by
/// [`Motivations::normalised`] (docs/model.md §8: e.g. `.3333` three times).
pub const MOTIVATION_NORMALISE_TOLERANCE: f64 = 1e-3;

/// Largest number of labels (peaks) accepted by [`TskFitness::new`]; keeps
/// `M^4` representable in `usize` on every supported platform.
pub const MAX_LABELS: usize = 255;

/// Largest absolute coefficient accepted by [`TskFitness::new`]; keeps every
/// rule output `f[n]` finite.
pub const MAX_COEFFICIENT_MAGNITUDE: f64 = 1e300;

/// Label names used when there are exactly five labels (`M = 5`), from the
/// lowest peak to the highest.
pub const PAPER_LABEL_NAMES: [&str; 5] = ["V.L.", "L", "M", "H", "V.H."];

/// Peaks of the paper's five triangular membership functions.
pub const PAPER_PEAKS: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// Errors produced when validating motivations or a fuzzy configuration.
///
/// Every message names the offending setting and value so a user can fix it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FuzzyError {
    /// One motivation is not a finite number in `[0, 1]`.
    #[error("{name} must be a number in [0, 1], got {}", Num(*.value))]
    MotivationOutOfRange {
        /// The motivation's name: `curiosity`, `homing`, `orientation`, `energy` or the config's.
        name: String,
        /// The rejected value.
        value: f64,
    },
    /// The motivations do not sum to 1 (within [`MOTIVATION_SUM_TOLERANCE`]).
    #[error(
        "motivations must sum to 1, got {} ({}); a sum within 0.001 of 1 is normalised, farther off is an error", Num(*.sum), sum_parts(.parts)
    )]
    MotivationSum {
        /// The actual sum `Σ X_i`.
        sum: f64,
        /// Each motivation's name and weight, in input order.
        parts: Vec<(String, f64)>,
    },
    /// Fewer than one or more than [`crate::fitness::MAX_MOTIVATIONS`] motivations.
    #[error("there must be from 1 to {max} motivations, got {count}")]
    MotivationCount {
        /// Number given.
        count: usize,
        /// The most allowed.
        max: usize,
    },
    /// Two motivations have the same name.
    #[error("two motivations are named {name:?}; each needs its own name")]
    DuplicateMotivation {
        /// The repeated name.
        name: String,
    },
    /// Fewer than two or more than [`MAX_LABELS`] peaks were given.
    #[error("{of}peaks must have between 2 and {max} values, got {count}")]
    PeakCount {
        /// Where the labels were given: `fuzzy.` or `motivations.NAME.`.
        of: String,
        /// Number of peaks given.
        count: usize,
        /// Maximum allowed ([`MAX_LABELS`]).
        max: usize,
    },
    /// A peak is NaN or infinite.
    #[error("{of}peaks must be finite numbers, got {value} at position {index} (0-based)")]
    NonFinitePeak {
        /// Where the labels were given: `fuzzy.` or `motivations.NAME.`.
        of: String,
        /// 0-based position in the list.
        index: usize,
        /// The rejected value.
        value: f64,
    },
    /// The peaks are not strictly increasing.
    #[error("{of}peaks must be strictly increasing, got {peaks:?}")]
    PeaksNotIncreasing {
        /// Where the labels were given: `fuzzy.` or `motivations.NAME.`.
        of: String,
        /// The rejected list.
        peaks: Vec<f64>,
    },
    /// Two neighbouring peaks are so far apart that their gap overflows.
    #[error("{of}peaks gap between {low} and {high} is too large to represent")]
    PeakGapTooLarge {
        /// Where the labels were given: `fuzzy.` or `motivations.NAME.`.
        of: String,
        /// Lower peak.
        low: f64,
        /// Upper peak.
        high: f64,
    },
    /// The coefficient list length differs from the number of peaks.
    #[error("{of}coefficients must have {expected} values (one per label), got {got}")]
    CoefficientCount {
        /// Where the labels were given: `fuzzy.` or `motivations.NAME.`.
        of: String,
        /// Number of labels (peaks).
        expected: usize,
        /// Number of coefficients given.
        got: usize,
    },
    /// A coefficient is NaN, infinite or larger in magnitude than
    /// [`MAX_COEFFICIENT_MAGNITUDE`].
    #[error(
        "{of}coefficients must be finite numbers with magnitude at most 1e300, got {} at position {index} (0-based)", Num(*.value)
    )]
    InvalidCoefficient {
        /// Where the labels were given: `fuzzy.` or `motivations.NAME.`.
        of: String,
        /// 0-based position in the list.
        index: usize,
        /// The rejected value.
        value: f64,
    },
}

/// Coefficient array of `[fuzzy]`: a scheme name or explicit values (default `"linear"`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(untagged)]
pub enum Coefficients {
    /// `"linear"` (default) or `"ratio"`.
    Scheme(CoefficientScheme),
    /// One value per label.
    Values(Vec<f64>),
}

/// `[fuzzy]` in a config, as written.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawFuzzy {
    /// Peaks of the triangular labels, increasing in [0, 1]; default [0, 0.25, 0.5, 0.75, 1]
    /// ([`PAPER_PEAKS`]).
    pub peaks: Vec<f64>,
    /// Coefficient array, one per label; default `"linear"`.
    pub coefficients: Coefficients,
}

impl Default for Coefficients {
    fn default() -> Self {
        Coefficients::Scheme(CoefficientScheme::Linear)
    }
}

impl Default for RawFuzzy {
    fn default() -> Self {
        Self {
            peaks: PAPER_PEAKS.to_vec(),
            coefficients: Coefficients::Scheme(CoefficientScheme::Linear),
        }
    }
}

impl RawFuzzy {
    /// The validated evaluator; an error names `fuzzy.peaks` or `fuzzy.coefficients`.
    pub fn validated(&self) -> Result<TskFitness, crate::params::FieldError> {
        TskFitness::of_raw(self.peaks.clone(), &self.coefficients, "fuzzy.")
    }
}

impl FuzzyError {
    /// The field a label error is about (`{of}peaks` or `{of}coefficients`), for the other
    /// errors `None`.
    fn label_field(&self) -> Option<String> {
        match self {
            FuzzyError::CoefficientCount { of, .. } | FuzzyError::InvalidCoefficient { of, .. } => {
                Some(format!("{of}coefficients"))
            }
            FuzzyError::PeakCount { of, .. }
            | FuzzyError::NonFinitePeak { of, .. }
            | FuzzyError::PeaksNotIncreasing { of, .. }
            | FuzzyError::PeakGapTooLarge { of, .. } => Some(format!("{of}peaks")),
            _ => None,
        }
    }
}

/// Built-in coefficient arrays `C[m]`, `m = 1..M`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CoefficientScheme {
    /// Default: `C[m] = (m − 1)/(M − 1)`, i.e. 0, 0.25, 0.5, 0.75, 1 for `M = 5`.
    #[default]
    Linear,
    /// `C[m] = m/M`, i.e. 0.2, 0.4, 0.6, 0.8, 1 for `M = 5`.
    Ratio,
}

impl CoefficientScheme {
    /// The `m` coefficients of this scheme (index 0 is label 1). For `m = 1`
    /// both schemes give `[1.0]`; for `m = 0` the list is empty.
    pub fn values(self, m: usize) -> Vec<f64> {
        match self {
            CoefficientScheme::Linear if m == 1 => vec![1.0],
            CoefficientScheme::Linear => (0..m).map(|k| k as f64 / (m - 1) as f64).collect(),
            CoefficientScheme::Ratio => (1..=m).map(|k| k as f64 / m as f64).collect(),
        }
    }
}

/// Name of label `m_index_zero_based` out of `m_count` labels: for
/// `m_count == 5` one of `"V.L.", "L", "M", "H", "V.H."`; otherwise
/// `"L1"`..`"LM"` (1-based).
pub fn label_name(m_index_zero_based: usize, m_count: usize) -> String {
    if m_count == PAPER_LABEL_NAMES.len() && m_index_zero_based < m_count {
        PAPER_LABEL_NAMES[m_index_zero_based].to_string()
    } else {
        format!("L{}", m_index_zero_based + 1)
    }
}

/// `curiosity 0.8 + homing 0.1 + …`: the parts of a sum of motivations.
fn sum_parts(parts: &[(String, f64)]) -> String {
    parts
        .iter()
        .map(|(name, w)| format!("{name} {}", Num(*w)))
        .collect::<Vec<_>>()
        .join(" + ")
}

/// Clamps a fitness value to `[0, 1]`; NaN becomes 0.
fn clamp_unit(y: f64) -> f64 {
    if y.is_nan() { 0.0 } else { y.clamp(0.0, 1.0) }
}

/// The fuzzy fitness function: triangular membership functions (given by
/// their peaks) and one output coefficient per label.
///
/// Defaults ([`TskFitness::paper`]): peaks 0, 0.25, 0.5, 0.75, 1 and linear
/// coefficients 0, 0.25, 0.5, 0.75, 1.
#[derive(Debug, Clone, PartialEq)]
pub struct TskFitness {
    /// Strictly increasing, finite peaks; one label per peak.
    peaks: Vec<f64>,
    /// One finite coefficient `C[m]` per label.
    coefficients: Vec<f64>,
}

impl Default for TskFitness {
    /// Same as [`TskFitness::paper`].
    fn default() -> Self {
        Self::paper()
    }
}

/// Labels (0-based) that may have non-zero membership for one input, ascending.
#[derive(Clone, Copy)]
struct Candidates {
    labels: [usize; 2],
    mu: [f64; 2],
    len: usize,
}

impl Candidates {
    /// No input (the unused slots of a fixed-size array).
    const NONE: Candidates = Candidates {
        labels: [0; 2],
        mu: [0.0; 2],
        len: 0,
    };
}

impl TskFitness {
    /// Validates and builds a fuzzy fitness function.
    ///
    /// `peaks`: 2..=[`MAX_LABELS`] finite, strictly increasing values (the
    /// first need not be 0 nor the last 1); label `m` is a triangle peaking at
    /// `peaks[m]` and reaching zero at its neighbours' peaks, the first and
    /// last labels being shoulders (1 beyond their peak).
    /// `coefficients`: one finite value per peak (magnitude at most
    /// [`MAX_COEFFICIENT_MAGNITUDE`]); see [`CoefficientScheme::values`].
    pub fn new(peaks: Vec<f64>, coefficients: Vec<f64>) -> Result<Self, FuzzyError> {
        Self::new_in(peaks, coefficients, "fuzzy.")
    }

    /// [`TskFitness::new`], its errors naming the labels given at `of` (`fuzzy.` or
    /// `motivations.NAME.`).
    fn new_in(peaks: Vec<f64>, coefficients: Vec<f64>, of: &str) -> Result<Self, FuzzyError> {
        let of = of.to_string();
        if peaks.len() < 2 || peaks.len() > MAX_LABELS {
            return Err(FuzzyError::PeakCount {
                of,
                count: peaks.len(),
                max: MAX_LABELS,
            });
        }
        if let Some((index, &value)) = peaks.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(FuzzyError::NonFinitePeak { of, index, value });
        }
        for pair in peaks.windows(2) {
            let (low, high) = (pair[0], pair[1]);
            if low >= high {
                return Err(FuzzyError::PeaksNotIncreasing { of, peaks });
            }
            if !(high - low).is_finite() {
                return Err(FuzzyError::PeakGapTooLarge { of, low, high });
            }
        }
        if coefficients.len() != peaks.len() {
            return Err(FuzzyError::CoefficientCount {
                of,
                expected: peaks.len(),
                got: coefficients.len(),
            });
        }
        if let Some((index, &value)) = coefficients
            .iter()
            .enumerate()
            .find(|(_, c)| !(c.is_finite() && c.abs() <= MAX_COEFFICIENT_MAGNITUDE))
        {
            return Err(FuzzyError::InvalidCoefficient { of, index, value });
        }
        Ok(Self {
            peaks,
            coefficients,
        })
    }

    /// Labels from `peaks` and coefficients as a config writes them, given at `of` (`fuzzy.`
    /// or `motivations.NAME.`); an error names `{of}peaks` or `{of}coefficients`.
    pub(crate) fn of_raw(
        peaks: Vec<f64>,
        coefficients: &Coefficients,
        of: &str,
    ) -> Result<TskFitness, crate::params::FieldError> {
        let values = match coefficients {
            Coefficients::Scheme(s) => s.values(peaks.len()),
            Coefficients::Values(v) => v.clone(),
        };
        Self::new_in(peaks, values, of).map_err(|e| {
            let field = e.label_field().unwrap_or_else(|| format!("{of}peaks"));
            crate::params::FieldError::new(field, e.to_string())
        })
    }

    /// Convenience: validates `peaks` and uses the coefficients of `scheme`.
    pub fn with_scheme(peaks: Vec<f64>, scheme: CoefficientScheme) -> Result<Self, FuzzyError> {
        let coefficients = scheme.values(peaks.len());
        Self::new(peaks, coefficients)
    }

    /// The paper's configuration: peaks 0, 0.25, 0.5, 0.75, 1 (V.L. .. V.H.)
    /// and linear coefficients 0, 0.25, 0.5, 0.75, 1.
    pub fn paper() -> Self {
        Self {
            peaks: PAPER_PEAKS.to_vec(),
            coefficients: CoefficientScheme::Linear.values(PAPER_PEAKS.len()),
        }
    }

    /// The membership-function peaks, one per label, ascending.
    pub fn peaks(&self) -> &[f64] {
        &self.peaks
    }

    /// The coefficients `C[m]`, one per label (index 0 is label 1).
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// Number of labels `M` per input (5 by default).
    pub fn labels(&self) -> usize {
        self.peaks.len()
    }

    /// Membership degree in `[0, 1]` of value `y` in label `label` (0-based).
    ///
    /// `y` is used as given (no clamping; the first and last labels are
    /// shoulders extending to −∞ and +∞); NaN is treated as 0. A label index
    /// `>= M` has membership 0. The labels form a partition of unity.
    pub fn membership(&self, label: usize, y: f64) -> f64 {
        let p = &self.peaks;
        let m = p.len();
        if label >= m {
            return 0.0;
        }
        let y = if y.is_nan() { 0.0 } else { y };
        let peak = p[label];
        if y <= peak {
            if label == 0 {
                return 1.0;
            }
            let low = p[label - 1];
            if y <= low {
                0.0
            } else {
                (y - low) / (peak - low)
            }
        } else {
            if label == m - 1 {
                return 1.0;
            }
            let high = p[label + 1];
            if y >= high {
                0.0
            } else {
                (high - y) / (high - peak)
            }
        }
    }

    /// The (at most two) labels that can be non-zero at `y`, with memberships.
    fn candidates(&self, y: f64) -> Candidates {
        let p = &self.peaks;
        let last = p.len() - 1;
        let (labels, len) = if y <= p[0] {
            ([0, 0], 1)
        } else if y >= p[last] {
            ([last, last], 1)
        } else {
            // p[0] < y < p[last]: the segment k with p[k] <= y < p[k + 1].
            let k = p[1..last].iter().take_while(|&&q| q <= y).count();
            ([k, k + 1], 2)
        };
        Candidates {
            labels,
            mu: [self.membership(labels[0], y), self.membership(labels[1], y)],
            len,
        }
    }

    /// Visits every rule that may have non-zero weight, in ascending rule number, passing
    /// 0-based labels (one per motivation), weight `w` and output `f`. The arithmetic matches
    /// the naive loop over all rules exactly: `w` is the minimum taken left to right and `f`
    /// the sum of `X_i·Y_i·C_i[x_i]` added left to right, input 1 varying fastest. `y` is
    /// already clamped; one value per motivation.
    #[inline]
    fn for_each_rule(&self, x: &Motivations, y: &[f64], mut visit: impl FnMut(&[usize], f64, f64)) {
        let n = x.len().min(y.len()).min(MAX_MOTIVATIONS);
        if n == 0 {
            return;
        }
        let mut cand = [Candidates::NONE; MAX_MOTIVATIONS];
        let mut coef: [&[f64]; MAX_MOTIVATIONS] = [&[]; MAX_MOTIVATIONS];
        let mut weight = [0.0; MAX_MOTIVATIONS];
        for (i, m) in x.iter().take(n).enumerate() {
            let labels = self.labels_of(m);
            cand[i] = labels.candidates(y[i]);
            coef[i] = &labels.coefficients;
            weight[i] = m.weight();
        }
        let mut at = [0usize; MAX_MOTIVATIONS];
        let mut labels = [0usize; MAX_MOTIVATIONS];
        loop {
            labels[0] = cand[0].labels[at[0]];
            let mut w = cand[0].mu[at[0]];
            let mut f = weight[0] * y[0] * coef[0][labels[0]];
            for i in 1..n {
                labels[i] = cand[i].labels[at[i]];
                w = w.min(cand[i].mu[at[i]]);
                f += weight[i] * y[i] * coef[i][labels[i]];
            }
            visit(&labels[..n], w, f);
            // The next combination, input 1 fastest.
            let mut i = 0;
            loop {
                at[i] += 1;
                if at[i] < cand[i].len {
                    break;
                }
                at[i] = 0;
                i += 1;
                if i == n {
                    return;
                }
            }
        }
    }

    /// The labels motivation `m` is fuzzified with: its own, or these shared ones.
    fn labels_of<'a>(&'a self, m: &'a Motivation) -> &'a TskFitness {
        m.labels().unwrap_or(self)
    }

    /// `F = Σ w·f / Σ w` from the sums; 0 when `Σ w` is not positive.
    fn ratio(numerator: f64, weight_sum: f64) -> f64 {
        // With a partition of unity some label of every input has membership
        // >= 0.5, so Σ w >= 0.5 and this guard never fires; it is kept for
        // robustness.
        if weight_sum > 0.0 {
            numerator / weight_sum
        } else {
            0.0
        }
    }

    /// The fuzzy fitness `F` for motivations `x` and fitness values `y`, one per motivation
    /// (the value of the term it weighs; for the paper's four `y = [a, g, l, b]`).
    ///
    /// Each `y` value is clamped to `[0, 1]` first (NaN becomes 0); values beyond the number of
    /// motivations are ignored and missing ones count as 0. For valid motivations and
    /// coefficients in `[0, 1]` the result lies in `[0, 1]`. Does not allocate; never panics.
    pub fn evaluate(&self, x: &Motivations, y: &[f64]) -> f64 {
        let y = clamped(x, y);
        let mut numerator = 0.0;
        let mut weight_sum = 0.0;
        self.for_each_rule(x, &y, |_, w, f| {
            numerator += w * f;
            weight_sum += w;
        });
        Self::ratio(numerator, weight_sum)
    }

    /// Like [`TskFitness::evaluate`] but also lists every firing rule
    /// (`w > 0`) in ascending rule number. `fitness` is bit-identical to
    /// `evaluate`; `weight_sum` is `Σ w` over all rules.
    pub fn explain(&self, x: &Motivations, y: &[f64]) -> Explanation {
        let y = clamped(x, y);
        let mut numerator = 0.0;
        let mut weight_sum = 0.0;
        let mut rules = Vec::new();
        self.for_each_rule(x, &y, |labels0, w, f| {
            numerator += w * f;
            weight_sum += w;
            if w > 0.0 {
                let labels: Vec<usize> = labels0.iter().map(|l| l + 1).collect();
                let label_names = x
                    .iter()
                    .zip(labels0)
                    .map(|(m, &l)| label_name(l, self.labels_of(m).labels()))
                    .collect();
                rules.push(FiringRule {
                    number: self.rule_number(x, &labels),
                    labels,
                    label_names,
                    weight: w,
                    output: f,
                });
            }
        });
        Explanation {
            fitness: Self::ratio(numerator, weight_sum),
            rules,
            weight_sum,
            inputs: x.input_names(),
        }
    }

    /// Number of labels `M_i` of each motivation's input.
    pub fn label_counts(&self, x: &Motivations) -> Vec<usize> {
        x.iter().map(|m| self.labels_of(m).labels()).collect()
    }

    /// Number of rules `Π M_i` (625 for the paper's four inputs of five labels); saturates at
    /// `usize::MAX`.
    pub fn rule_count(&self, x: &Motivations) -> usize {
        self.label_counts(x)
            .iter()
            .try_fold(1usize, |n, &m| n.checked_mul(m))
            .unwrap_or(usize::MAX)
    }

    /// Rule number `n = 1 + Σ_i (x_i − 1)·Π_{j<i} M_j` (1-based) of the 1-based labels
    /// `[x_1, …, x_N]`; `x_1` varies fastest.
    ///
    /// # Panics
    /// If a label is 0 or greater than its input's `M_i`, or the count is not N (a
    /// programming error).
    pub fn rule_number(&self, x: &Motivations, labels: &[usize]) -> usize {
        let counts = self.label_counts(x);
        assert!(
            labels.len() == counts.len()
                && labels
                    .iter()
                    .zip(&counts)
                    .all(|(&l, &m)| (1..=m).contains(&l)),
            "rule labels must be one per input, in 1..=M_i ({counts:?}), got {labels:?}"
        );
        1 + labels
            .iter()
            .zip(&counts)
            .rev()
            .fold(0, |acc, (&l, &m)| acc * m + (l - 1))
    }

    /// The 1-based labels `[x_1, …, x_N]` of rule `n` (1-based); the inverse of
    /// [`TskFitness::rule_number`].
    ///
    /// # Panics
    /// If `n` is 0 or greater than [`TskFitness::rule_count`] (a programming error).
    pub fn rule_labels(&self, x: &Motivations, n: usize) -> Vec<usize> {
        let count = self.rule_count(x);
        assert!(
            (1..=count).contains(&n),
            "rule number must be in 1..={count}, got {n}"
        );
        let mut rest = n - 1;
        self.label_counts(x)
            .into_iter()
            .map(|m| {
                let l = rest % m + 1;
                rest /= m;
                l
            })
            .collect()
    }
}

/// One value per motivation, each clamped to `[0, 1]` (NaN and missing values become 0).
fn clamped(x: &Motivations, y: &[f64]) -> [f64; MAX_MOTIVATIONS] {
    let mut out = [0.0; MAX_MOTIVATIONS];
    for (o, &v) in out.iter_mut().zip(y).take(x.len()) {
        *o = clamp_unit(v);
    }
    out
}

/// One rule with non-zero firing strength, as listed by
/// [`TskFitness::explain`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FiringRule {
    /// Rule number `n` (1-based, input 1 varies fastest).
    pub number: usize,
    /// 1-based labels, one per motivation (for the paper's four: `[a, g, l, b]`).
    pub labels: Vec<usize>,
    /// Label names, one per motivation (see [`label_name`]).
    pub label_names: Vec<String>,
    /// Firing strength `w[n] = min_i μ(Y_i)`, in `(0, 1]`.
    pub weight: f64,
    /// Rule output `f[n] = Σ_i X_i·Y_i·C[x_i]`.
    pub output: f64,
}

/// Breakdown of one fuzzy fitness evaluation.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Explanation {
    /// The fitness `F` (bit-identical to [`TskFitness::evaluate`]).
    pub fitness: f64,
    /// Rules with `w > 0`, in ascending rule number.
    pub rules: Vec<FiringRule>,
    /// `Σ w` over all rules.
    pub weight_sum: f64,
    /// The terms the inputs are (for the paper's four `a, g, l, b`), in input order.
    #[serde(skip)]
    pub inputs: Vec<String>,
}

impl fmt::Display for Explanation {
    /// A table of the firing rules followed by the final `F`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let width = 14 * self.inputs.len().max(4);
        writeln!(
            f,
            "{:>6}  {:<width$}  {:>10}  {:>10}",
            "rule", "if", "w", "f"
        )?;
        for rule in &self.rules {
            let condition = self
                .inputs
                .iter()
                .zip(&rule.label_names)
                .map(|(input, name)| format!("{input} is {name}"))
                .collect::<Vec<_>>()
                .join(" and ");
            writeln!(
                f,
                "{:>6}  {:<width$}  {:>10.6}  {:>10.6}",
                rule.number,
                format!("if {condition}"),
                rule.weight,
                rule.output
            )?;
        }
        write!(
            f,
            "sum of w = {:.6}; F = sum(w*f) / sum(w) = {:.6}",
            self.weight_sum, self.fitness
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tiny deterministic LCG (Knuth MMIX constants).
    struct Lcg(u64);

    impl Lcg {
        fn next_f64(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Straightforward reference: loop over all Π M_i rules in rule-number order (input 1
    /// fastest), each motivation with its own labels or the shared ones.
    fn reference(t: &TskFitness, x: &Motivations, y: &[f64]) -> f64 {
        let y: Vec<f64> = y
            .iter()
            .map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) })
            .collect();
        let inputs: Vec<(&TskFitness, f64)> = x
            .iter()
            .map(|m| (m.labels().unwrap_or(t), m.weight()))
            .collect();
        let mut num = 0.0;
        let mut den = 0.0;
        for n in 1..=t.rule_count(x) {
            let labels = t.rule_labels(x, n);
            let mut w = f64::INFINITY;
            let mut f = None;
            for (i, &l) in labels.iter().enumerate() {
                let (labels_i, weight) = inputs[i];
                w = if i == 0 {
                    labels_i.membership(l - 1, y[i])
                } else {
                    w.min(labels_i.membership(l - 1, y[i]))
                };
                let term = weight * y[i] * labels_i.coefficients()[l - 1];
                f = Some(f.map_or(term, |s| s + term));
            }
            num += w * f.unwrap();
            den += w;
        }
        if den > 0.0 { num / den } else { 0.0 }
    }

    /// Random motivations: `n` of them, some with their own labels.
    fn random_motivations(rng: &mut Lcg, n: usize, own: &[TskFitness]) -> Motivations {
        let raw: Vec<f64> = (0..n).map(|_| rng.next_f64() + 1e-3).collect();
        let total: f64 = raw.iter().sum();
        let list = raw
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let m = Motivation::new(format!("m{i}"), w / total, "a");
                let pick = (rng.next_f64() * (own.len() + 2) as f64) as usize;
                match own.get(pick) {
                    Some(labels) => m.with_labels(labels.clone()),
                    None => m,
                }
            })
            .collect();
        Motivations::from_list(list).unwrap().0
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-6
    }

    #[test]
    fn worked_values() {
        let t = TskFitness::paper();
        let f1 = t.evaluate(&Motivations::high_curiosity(), &[0.95, 0.5, 0.0, 0.79]);
        assert!(close(f1, 0.797220), "{f1}");
        let f2 = t.evaluate(&Motivations::low_curiosity(), &[0.55, 0.3, 0.0, 0.58]);
        assert!(close(f2, 0.263309), "{f2}");
        let x = Motivations::new(0.25, 0.25, 0.25, 0.25).unwrap();
        let f3 = t.evaluate(&x, &[1.0, 1.0, 1.0, 1.0]);
        assert!(close(f3, 1.0), "{f3}");
    }

    #[test]
    fn constants_are_valid() {
        for m in [Motivations::high_curiosity(), Motivations::low_curiosity()] {
            let [c, h, o, e] = m.as_array();
            assert_eq!(Motivations::new(c, h, o, e), Ok(m));
        }
    }

    #[test]
    fn rule_numbering() {
        let t = TskFitness::paper();
        assert_eq!(t.labels(), 5);
        let x = Motivations::high_curiosity();
        assert_eq!(t.rule_count(&x), 625);
        assert_eq!(t.rule_number(&x, &[5, 2, 1, 1]), 10);
        assert_eq!(t.rule_labels(&x, 10), [5, 2, 1, 1]);
        assert_eq!(t.rule_number(&x, &[1, 1, 1, 1]), 1);
        assert_eq!(t.rule_number(&x, &[5, 5, 5, 5]), 625);
        for n in 1..=625 {
            assert_eq!(t.rule_number(&x, &t.rule_labels(&x, n)), n);
        }
    }

    #[test]
    fn partition_of_unity() {
        let ts = [
            TskFitness::paper(),
            TskFitness::with_scheme(vec![0.1, 0.3, 0.35, 0.9], CoefficientScheme::Ratio).unwrap(),
            TskFitness::with_scheme(vec![-1.0, 2.0], CoefficientScheme::Linear).unwrap(),
        ];
        for t in &ts {
            for i in -300..=1300 {
                let y = i as f64 / 1000.0;
                let s: f64 = (0..t.labels()).map(|m| t.membership(m, y)).sum();
                assert!((s - 1.0).abs() < 1e-12, "sum {s} at {y}");
                let nonzero = (0..t.labels())
                    .filter(|&m| t.membership(m, y) > 0.0)
                    .count();
                assert!((1..=2).contains(&nonzero));
                for m in 0..t.labels() {
                    assert!((0.0..=1.0).contains(&t.membership(m, y)));
                }
            }
            assert_eq!(t.membership(t.labels(), 0.5), 0.0);
        }
    }

    #[test]
    fn membership_at_peaks() {
        let t = TskFitness::paper();
        for (k, &p) in PAPER_PEAKS.iter().enumerate() {
            for m in 0..5 {
                assert_eq!(t.membership(m, p), if m == k { 1.0 } else { 0.0 });
            }
        }
        assert_eq!(t.membership(0, -3.0), 1.0);
        assert_eq!(t.membership(4, 7.0), 1.0);
        assert_eq!(t.membership(0, f64::NAN), 1.0);
        assert_eq!(t.membership(1, 0.125), 0.5);
    }

    /// The fast path (at most 2^N rules visited) is bit-identical to the naive loop over all
    /// rules, for N = 1 … 8 motivations, shared and own labels.
    #[test]
    fn fast_path_is_bit_identical_to_full_loop() {
        let ts = [
            TskFitness::paper(),
            TskFitness::with_scheme(PAPER_PEAKS.to_vec(), CoefficientScheme::Ratio).unwrap(),
            TskFitness::new(vec![0.1, 0.3, 0.35, 0.9], vec![-0.5, 2.0, 0.3, 1.0]).unwrap(),
            TskFitness::with_scheme(vec![0.0, 1.0], CoefficientScheme::Linear).unwrap(),
            TskFitness::with_scheme(
                vec![0.0, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.2],
                CoefficientScheme::Linear,
            )
            .unwrap(),
        ];
        let own = [
            TskFitness::with_scheme(vec![0.0, 0.5, 1.0], CoefficientScheme::Ratio).unwrap(),
            TskFitness::new(vec![0.2, 0.4], vec![1.0, 0.3]).unwrap(),
        ];
        let mut rng = Lcg(12345);
        let specials = [0.0, 0.25, 0.5, 0.75, 1.0, 0.35, -0.2, 1.5, f64::NAN];
        for n in 1..=MAX_MOTIVATIONS {
            // The naive loop visits Π M_i rules (5^8 = 390 625 for eight inputs): fewer rounds
            // and at most five labels for many inputs.
            let rounds = match n {
                1..=4 => 3000,
                5..=6 => 60,
                _ => 12,
            };
            let shared: Vec<&TskFitness> =
                ts.iter().filter(|t| n <= 4 || t.labels() <= 5).collect();
            for t in shared {
                for _ in 0..rounds {
                    let x = random_motivations(&mut rng, n, &own);
                    let y: Vec<f64> = (0..n)
                        .map(|_| {
                            let r = rng.next_f64();
                            if r < 0.3 {
                                specials[(rng.next_f64() * specials.len() as f64) as usize]
                            } else {
                                rng.next_f64() * 1.4 - 0.2
                            }
                        })
                        .collect();
                    let fast = t.evaluate(&x, &y);
                    let slow = reference(t, &x, &y);
                    assert_eq!(fast.to_bits(), slow.to_bits(), "{x:?} {y:?}");
                    assert_eq!(t.explain(&x, &y).fitness.to_bits(), fast.to_bits());
                }
            }
        }
    }

    #[test]
    fn explanation_is_consistent() {
        let t = TskFitness::paper();
        let x = Motivations::high_curiosity();
        let y = [0.95, 0.5, 0.0, 0.79];
        let e = t.explain(&x, &y);
        assert_eq!(e.fitness, t.evaluate(&x, &y));
        assert_eq!(e.rules.len(), 4);
        let s: f64 = e.rules.iter().map(|r| r.weight).sum();
        assert!((s - e.weight_sum).abs() < 1e-12);
        assert!(e.rules.iter().all(|r| r.weight > 0.0));
        assert!(e.rules.windows(2).all(|p| p[0].number < p[1].number));
        for r in &e.rules {
            assert_eq!(t.rule_labels(&x, r.number), r.labels);
        }
        let text = e.to_string();
        assert!(text.contains("V.H."), "{text}");
        assert!(text.contains("if a is V.H. and g is M and l is V.L. and b is H"));
        assert!(text.contains("0.797220"), "{text}");

        let sample = t.explain(&x, &[1.0, 0.25, 0.0, 0.0]);
        assert_eq!(sample.rules.len(), 1);
        assert_eq!(sample.rules[0].number, 10);
        assert_eq!(sample.rules[0].label_names, ["V.H.", "L", "V.L.", "V.L."]);
    }

    #[test]
    fn out_of_range_y_is_clamped() {
        let t = TskFitness::paper();
        let x = Motivations::low_curiosity();
        assert_eq!(
            t.evaluate(&x, &[1.7, -0.3, f64::NAN, f64::INFINITY]),
            t.evaluate(&x, &[1.0, 0.0, 0.0, 1.0])
        );
    }

    #[test]
    fn a_nan_motivation_is_blamed_on_its_own_field() {
        let names = ["curiosity", "homing", "orientation", "energy"];
        for (k, name) in names.into_iter().enumerate() {
            let mut x = [0.25; 4];
            x[k] = f64::NAN;
            for err in [
                Motivations::new(x[0], x[1], x[2], x[3]).unwrap_err(),
                Motivations::normalised(x[0], x[1], x[2], x[3]).unwrap_err(),
            ] {
                assert!(
                    matches!(&err, FuzzyError::MotivationOutOfRange { name: n, value }
                        if n == name && value.is_nan()),
                    "{name}: {err}"
                );
            }
        }
    }

    #[test]
    fn motivation_errors() {
        let err = Motivations::new(0.5, 0.3, 0.0, 0.1).unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("sum to 1"), "{msg}");
        assert!(msg.contains("0.9"), "{msg}");
        assert!(matches!(err, FuzzyError::MotivationSum { .. }));

        let msg = Motivations::new(1.5, 0.0, 0.0, 0.0)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("curiosity") && msg.contains("1.5"), "{msg}");
        let msg = Motivations::new(0.5, -0.1, 0.3, 0.3)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("homing") && msg.contains("-0.1"), "{msg}");
        let msg = Motivations::new(0.5, 0.5, f64::NAN, 0.0)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("orientation") && msg.contains("NaN"), "{msg}");
        let msg = Motivations::new(0.5, 0.5, 0.0, f64::INFINITY)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("energy"), "{msg}");

        assert!(Motivations::new(0.5, 0.5, 0.0, 1e-10).is_ok());
        assert!(Motivations::new(0.5, 0.5, 0.0, 1e-8).is_err());
    }

    #[test]
    fn tsk_errors() {
        let lin = |n| CoefficientScheme::Linear.values(n);
        let err = TskFitness::new(vec![0.0, 0.5, 0.5, 1.0], lin(4)).unwrap_err();
        assert!(matches!(err, FuzzyError::PeaksNotIncreasing { .. }));
        assert!(err.to_string().contains("strictly increasing"));
        assert!(TskFitness::new(vec![1.0, 0.0], lin(2)).is_err());

        let err = TskFitness::new(PAPER_PEAKS.to_vec(), lin(3)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "fuzzy.coefficients must have 5 values (one per label), got 3"
        );

        let err = TskFitness::new(vec![0.0, f64::NAN, 1.0], lin(3)).unwrap_err();
        assert!(matches!(err, FuzzyError::NonFinitePeak { index: 1, .. }));
        let err = TskFitness::new(vec![0.0, f64::INFINITY], lin(2)).unwrap_err();
        assert!(matches!(err, FuzzyError::NonFinitePeak { .. }));
        let err = TskFitness::new(vec![0.0, 1.0], vec![0.0, f64::NAN]).unwrap_err();
        assert!(matches!(
            err,
            FuzzyError::InvalidCoefficient { index: 1, .. }
        ));
        assert!(TskFitness::new(vec![0.0, 1.0], vec![0.0, f64::NEG_INFINITY]).is_err());

        assert!(matches!(
            TskFitness::new(vec![0.5], vec![1.0]),
            Err(FuzzyError::PeakCount { count: 1, .. })
        ));
        assert!(TskFitness::new(vec![], vec![]).is_err());
        assert!(matches!(
            TskFitness::new(vec![-f64::MAX, f64::MAX], lin(2)),
            Err(FuzzyError::PeakGapTooLarge { .. })
        ));
        assert_eq!(
            TskFitness::new(PAPER_PEAKS.to_vec(), lin(5)),
            Ok(TskFitness::paper())
        );
    }

    #[test]
    fn coefficient_schemes() {
        assert_eq!(
            CoefficientScheme::Ratio.values(5),
            vec![0.2, 0.4, 0.6, 0.8, 1.0]
        );
        assert_eq!(
            CoefficientScheme::Linear.values(5),
            vec![0.0, 0.25, 0.5, 0.75, 1.0]
        );
        assert_eq!(CoefficientScheme::Linear.values(1), vec![1.0]);
        assert!(CoefficientScheme::Ratio.values(0).is_empty());
        assert_eq!(
            TskFitness::paper().coefficients(),
            &[0.0, 0.25, 0.5, 0.75, 1.0]
        );
    }

    #[test]
    fn label_names() {
        let names: Vec<String> = (0..5).map(|m| label_name(m, 5)).collect();
        assert_eq!(names, ["V.L.", "L", "M", "H", "V.H."]);
        assert_eq!(label_name(0, 3), "L1");
        assert_eq!(label_name(2, 3), "L3");
    }
}
