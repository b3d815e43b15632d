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

/// Short names of the four fitness inputs `Y = (a, g, l, b)`: exploration
/// (`a`), homing (`g`), orientation/recognition (`l`) and battery (`b`).
pub const INPUT_NAMES: [&str; 4] = ["a", "g", "l", "b"];

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
        /// Field name: `curiosity`, `homing`, `orientation` or `energy`.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// The four motivations do not sum to 1 (within
    /// [`MOTIVATION_SUM_TOLERANCE`]).
    #[error(
        "motivations must sum to 1, got {} (curiosity {} + homing {} + orientation {} + energy {}); a sum within 0.001 of 1 is normalised, farther off is an error", Num(*.sum), Num(*.curiosity), Num(*.homing), Num(*.orientation), Num(*.energy)
    )]
    MotivationSum {
        /// The actual sum `C + H + O + E`.
        sum: f64,
        /// Curiosity `C`.
        curiosity: f64,
        /// Homing `H`.
        homing: f64,
        /// Orientation `O`.
        orientation: f64,
        /// Energy `E`.
        energy: f64,
    },
    /// Fewer than two or more than [`MAX_LABELS`] peaks were given.
    #[error("fuzzy.peaks must have between 2 and {max} values, got {count}")]
    PeakCount {
        /// Number of peaks given.
        count: usize,
        /// Maximum allowed ([`MAX_LABELS`]).
        max: usize,
    },
    /// A peak is NaN or infinite.
    #[error("fuzzy.peaks must be finite numbers, got {value} at position {index} (0-based)")]
    NonFinitePeak {
        /// 0-based position in the list.
        index: usize,
        /// The rejected value.
        value: f64,
    },
    /// The peaks are not strictly increasing.
    #[error("fuzzy.peaks must be strictly increasing, got {peaks:?}")]
    PeaksNotIncreasing {
        /// The rejected list.
        peaks: Vec<f64>,
    },
    /// Two neighbouring peaks are so far apart that their gap overflows.
    #[error("fuzzy.peaks gap between {low} and {high} is too large to represent")]
    PeakGapTooLarge {
        /// Lower peak.
        low: f64,
        /// Upper peak.
        high: f64,
    },
    /// The coefficient list length differs from the number of peaks.
    #[error("fuzzy.coefficients must have {expected} values (one per label), got {got}")]
    CoefficientCount {
        /// Number of labels (peaks).
        expected: usize,
        /// Number of coefficients given.
        got: usize,
    },
    /// A coefficient is NaN, infinite or larger in magnitude than
    /// [`MAX_COEFFICIENT_MAGNITUDE`].
    #[error(
        "fuzzy.coefficients must be finite numbers with magnitude at most 1e300, got {} at position {index} (0-based)", Num(*.value)
    )]
    InvalidCoefficient {
        /// 0-based position in the list.
        index: usize,
        /// The rejected value.
        value: f64,
    },
}

/// Motivations `X = (C, H, O, E)`: curiosity `C`, homing `H`, orientation `O`
/// and energy `E`. Dimensionless weights, each in `[0, 1]`, summing to 1.
///
/// Built only by checking: [`Motivations::new`], [`Motivations::normalised`],
/// [`RawMotivations::validated`], or the paper's settings ([`Motivations::HIGH_CURIOSITY`],
/// [`Motivations::LOW_CURIOSITY`]); read through the accessors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motivations {
    curiosity: f64,
    homing: f64,
    orientation: f64,
    energy: f64,
}

/// `[motivations]` in a config, as written: X = (C, H, O, E), each in [0, 1], summing to 1;
/// default the paper's high-curiosity setting [`Motivations::HIGH_CURIOSITY`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RawMotivations {
    /// Curiosity C (weight of exploration a); default 0.8.
    pub curiosity: f64,
    /// Homing H (weight of homing g); default 0.1.
    pub homing: f64,
    /// Orientation O (weight of recognition l); default 0.
    pub orientation: f64,
    /// Energy E (weight of battery b); default 0.1.
    pub energy: f64,
}

impl Default for RawMotivations {
    fn default() -> Self {
        let m = Motivations::HIGH_CURIOSITY;
        Self {
            curiosity: m.curiosity,
            homing: m.homing,
            orientation: m.orientation,
            energy: m.energy,
        }
    }
}

impl RawMotivations {
    /// The validated motivations, normalised as [`Motivations::normalised`] says (as the
    /// error text promises); an error names `motivations.NAME` or `motivations`.
    pub fn validated(&self) -> Result<Motivations, crate::params::FieldError> {
        let (c, h, o, e) = (self.curiosity, self.homing, self.orientation, self.energy);
        Motivations::normalised(c, h, o, e)
            .map(|(m, _)| m)
            .map_err(|e| {
                let field = match &e {
                    FuzzyError::MotivationOutOfRange { name, .. } => format!("motivations.{name}"),
                    _ => "motivations".to_string(),
                };
                crate::params::FieldError::new(field, e.to_string())
            })
    }
}

/// Coefficient array of `[fuzzy]`: a scheme name or explicit values.
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
        match &self.coefficients {
            Coefficients::Scheme(s) => TskFitness::with_scheme(self.peaks.clone(), *s),
            Coefficients::Values(v) => TskFitness::new(self.peaks.clone(), v.clone()),
        }
        .map_err(|e| {
            let field = match e {
                FuzzyError::CoefficientCount { .. } | FuzzyError::InvalidCoefficient { .. } => {
                    "fuzzy.coefficients"
                }
                _ => "fuzzy.peaks",
            };
            crate::params::FieldError::new(field, e.to_string())
        })
    }
}

impl Motivations {
    /// The paper's high-curiosity setting `(C, H, O, E) = (0.8, 0.1, 0, 0.1)`.
    pub const HIGH_CURIOSITY: Motivations = Motivations {
        curiosity: 0.8,
        homing: 0.1,
        orientation: 0.0,
        energy: 0.1,
    };

    /// The paper's low-curiosity setting `(C, H, O, E) = (0.5, 0.3, 0, 0.2)`.
    pub const LOW_CURIOSITY: Motivations = Motivations {
        curiosity: 0.5,
        homing: 0.3,
        orientation: 0.0,
        energy: 0.2,
    };

    /// Validates and builds motivations. Each value must be a finite number
    /// in `[0, 1]` and the four must sum to 1 within
    /// [`MOTIVATION_SUM_TOLERANCE`]; nothing is renormalised.
    pub fn new(
        curiosity: f64,
        homing: f64,
        orientation: f64,
        energy: f64,
    ) -> Result<Self, FuzzyError> {
        check_each_in_unit_range([curiosity, homing, orientation, energy])?;
        let sum = curiosity + homing + orientation + energy;
        if (sum - 1.0).abs() > MOTIVATION_SUM_TOLERANCE {
            return Err(FuzzyError::MotivationSum {
                sum,
                curiosity,
                homing,
                orientation,
                energy,
            });
        }
        Ok(Self {
            curiosity,
            homing,
            orientation,
            energy,
        })
    }

    /// Like [`Motivations::new`], but a sum within [`MOTIVATION_NORMALISE_TOLERANCE`] of 1 is
    /// normalised (each value divided by the sum); then the original sum is returned as well,
    /// so the caller can say so.
    pub fn normalised(
        curiosity: f64,
        homing: f64,
        orientation: f64,
        energy: f64,
    ) -> Result<(Self, Option<f64>), FuzzyError> {
        // Each value first: a NaN or out-of-range one would otherwise make the sum NaN (or
        // near 1) and be divided into the others, and the error would name the wrong field.
        check_each_in_unit_range([curiosity, homing, orientation, energy])?;
        let sum = curiosity + homing + orientation + energy;
        let off = (sum - 1.0).abs();
        if off <= MOTIVATION_SUM_TOLERANCE || off > MOTIVATION_NORMALISE_TOLERANCE {
            return Self::new(curiosity, homing, orientation, energy).map(|m| (m, None));
        }
        let [c, h, o, e] = [curiosity, homing, orientation, energy].map(|v| v / sum);
        Self::new(c, h, o, e).map(|m| (m, Some(sum)))
    }

    /// Curiosity `C`: weight of exploration fitness `a`.
    pub fn curiosity(&self) -> f64 {
        self.curiosity
    }

    /// Homing `H`: weight of homing fitness `g`.
    pub fn homing(&self) -> f64 {
        self.homing
    }

    /// Orientation `O`: weight of orientation/recognition fitness `l`.
    pub fn orientation(&self) -> f64 {
        self.orientation
    }

    /// Energy `E`: weight of battery fitness `b`.
    pub fn energy(&self) -> f64 {
        self.energy
    }

    /// The motivations as `[C, H, O, E]`, matching the order of `Y = [a, g, l, b]`.
    pub fn as_array(&self) -> [f64; 4] {
        [self.curiosity, self.homing, self.orientation, self.energy]
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

/// Each motivation `(C, H, O, E)` is a number in `[0, 1]` (so not NaN); the error names the
/// first that is not.
fn check_each_in_unit_range(values: [f64; 4]) -> Result<(), FuzzyError> {
    const NAMES: [&str; 4] = ["curiosity", "homing", "orientation", "energy"];
    match values.iter().position(|v| !(0.0..=1.0).contains(v)) {
        Some(k) => Err(FuzzyError::MotivationOutOfRange {
            name: NAMES[k],
            value: values[k],
        }),
        None => Ok(()),
    }
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
        if peaks.len() < 2 || peaks.len() > MAX_LABELS {
            return Err(FuzzyError::PeakCount {
                count: peaks.len(),
                max: MAX_LABELS,
            });
        }
        if let Some((index, &value)) = peaks.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(FuzzyError::NonFinitePeak { index, value });
        }
        for pair in peaks.windows(2) {
            let (low, high) = (pair[0], pair[1]);
            if low >= high {
                return Err(FuzzyError::PeaksNotIncreasing { peaks });
            }
            if !(high - low).is_finite() {
                return Err(FuzzyError::PeakGapTooLarge { low, high });
            }
        }
        if coefficients.len() != peaks.len() {
            return Err(FuzzyError::CoefficientCount {
                expected: peaks.len(),
                got: coefficients.len(),
            });
        }
        if let Some((index, &value)) = coefficients
            .iter()
            .enumerate()
            .find(|(_, c)| !(c.is_finite() && c.abs() <= MAX_COEFFICIENT_MAGNITUDE))
        {
            return Err(FuzzyError::InvalidCoefficient { index, value });
        }
        Ok(Self {
            peaks,
            coefficients,
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

    /// Number of rules `M^4` (625 by default).
    pub fn rule_count(&self) -> usize {
        self.labels().pow(4)
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

    /// Visits every rule that may have non-zero weight, in ascending rule
    /// number, passing 0-based labels, weight `w` and output `f`. The
    /// arithmetic matches the naive loop over all `M^4` rules exactly.
    #[inline]
    fn for_each_rule(&self, x: [f64; 4], y: [f64; 4], mut visit: impl FnMut([usize; 4], f64, f64)) {
        let cand = y.map(|v| self.candidates(v));
        let c = &self.coefficients;
        for jb in 0..cand[3].len {
            for jl in 0..cand[2].len {
                for jg in 0..cand[1].len {
                    for ja in 0..cand[0].len {
                        let labels = [
                            cand[0].labels[ja],
                            cand[1].labels[jg],
                            cand[2].labels[jl],
                            cand[3].labels[jb],
                        ];
                        let w = cand[0].mu[ja]
                            .min(cand[1].mu[jg])
                            .min(cand[2].mu[jl])
                            .min(cand[3].mu[jb]);
                        let f = x[0] * y[0] * c[labels[0]]
                            + x[1] * y[1] * c[labels[1]]
                            + x[2] * y[2] * c[labels[2]]
                            + x[3] * y[3] * c[labels[3]];
                        visit(labels, w, f);
                    }
                }
            }
        }
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

    /// The fuzzy fitness `F` for motivations `x` and fitness values
    /// `y = [a, g, l, b]`.
    ///
    /// Each `y` value is clamped to `[0, 1]` first (NaN becomes 0). For valid
    /// motivations and coefficients in `[0, 1]` the result lies in `[0, 1]`.
    /// Returns 0 if the total weight were 0 (impossible with a partition of
    /// unity). Does not allocate; never panics.
    pub fn evaluate(&self, x: &Motivations, y: [f64; 4]) -> f64 {
        let y = y.map(clamp_unit);
        let mut numerator = 0.0;
        let mut weight_sum = 0.0;
        self.for_each_rule(x.as_array(), y, |_, w, f| {
            numerator += w * f;
            weight_sum += w;
        });
        Self::ratio(numerator, weight_sum)
    }

    /// Like [`TskFitness::evaluate`] but also lists every firing rule
    /// (`w > 0`) in ascending rule number. `fitness` is bit-identical to
    /// `evaluate`; `weight_sum` is `Σ w` over all rules.
    pub fn explain(&self, x: &Motivations, y: [f64; 4]) -> Explanation {
        let y = y.map(clamp_unit);
        let m = self.labels();
        let mut numerator = 0.0;
        let mut weight_sum = 0.0;
        let mut rules = Vec::new();
        self.for_each_rule(x.as_array(), y, |labels0, w, f| {
            numerator += w * f;
            weight_sum += w;
            if w > 0.0 {
                let labels = labels0.map(|l| l + 1);
                rules.push(FiringRule {
                    number: self.rule_number(labels),
                    labels,
                    label_names: labels0.map(|l| label_name(l, m)),
                    weight: w,
                    output: f,
                });
            }
        });
        Explanation {
            fitness: Self::ratio(numerator, weight_sum),
            rules,
            weight_sum,
        }
    }

    /// Rule number `n = 1 + Σ_i (x_i − 1)·M^(i−1)` (1-based) of the 1-based
    /// labels `[x_a, x_g, x_l, x_b]`; `x_a` varies fastest.
    ///
    /// # Panics
    /// If any label is 0 or greater than `M` (a programming error).
    pub fn rule_number(&self, labels: [usize; 4]) -> usize {
        let m = self.labels();
        assert!(
            labels.iter().all(|&l| (1..=m).contains(&l)),
            "rule labels must be in 1..={m}, got {labels:?}"
        );
        1 + labels.iter().rev().fold(0, |acc, &l| acc * m + (l - 1))
    }

    /// The 1-based labels `[x_a, x_g, x_l, x_b]` of rule `n` (1-based); the
    /// inverse of [`TskFitness::rule_number`].
    ///
    /// # Panics
    /// If `n` is 0 or greater than [`TskFitness::rule_count`] (a programming
    /// error).
    pub fn rule_labels(&self, n: usize) -> [usize; 4] {
        let m = self.labels();
        assert!(
            (1..=self.rule_count()).contains(&n),
            "rule number must be in 1..={}, got {n}",
            self.rule_count()
        );
        let mut rest = n - 1;
        let mut labels = [0; 4];
        for l in &mut labels {
            *l = rest % m + 1;
            rest /= m;
        }
        labels
    }
}

/// One rule with non-zero firing strength, as listed by
/// [`TskFitness::explain`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FiringRule {
    /// Rule number `n` (1-based, `x_a` varies fastest).
    pub number: usize,
    /// 1-based labels for `[a, g, l, b]`.
    pub labels: [usize; 4],
    /// Label names for `[a, g, l, b]` (see [`label_name`]).
    pub label_names: [String; 4],
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
}

impl fmt::Display for Explanation {
    /// A table of the firing rules followed by the final `F`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{:>6}  {:<56}  {:>10}  {:>10}", "rule", "if", "w", "f")?;
        for rule in &self.rules {
            let condition = INPUT_NAMES
                .iter()
                .zip(&rule.label_names)
                .map(|(input, name)| format!("{input} is {name}"))
                .collect::<Vec<_>>()
                .join(" and ");
            writeln!(
                f,
                "{:>6}  {:<56}  {:>10.6}  {:>10.6}",
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

    /// Straightforward reference: loop over all M^4 rules in rule-number order.
    fn reference(t: &TskFitness, x: &Motivations, y: [f64; 4]) -> f64 {
        let y = y.map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) });
        let x = x.as_array();
        let c = t.coefficients();
        let m = t.labels();
        let mut num = 0.0;
        let mut den = 0.0;
        for b in 0..m {
            for l in 0..m {
                for g in 0..m {
                    for a in 0..m {
                        let w = t
                            .membership(a, y[0])
                            .min(t.membership(g, y[1]))
                            .min(t.membership(l, y[2]))
                            .min(t.membership(b, y[3]));
                        let f = x[0] * y[0] * c[a]
                            + x[1] * y[1] * c[g]
                            + x[2] * y[2] * c[l]
                            + x[3] * y[3] * c[b];
                        num += w * f;
                        den += w;
                    }
                }
            }
        }
        if den > 0.0 { num / den } else { 0.0 }
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-6
    }

    #[test]
    fn worked_values() {
        let t = TskFitness::paper();
        let f1 = t.evaluate(&Motivations::HIGH_CURIOSITY, [0.95, 0.5, 0.0, 0.79]);
        assert!(close(f1, 0.797220), "{f1}");
        let f2 = t.evaluate(&Motivations::LOW_CURIOSITY, [0.55, 0.3, 0.0, 0.58]);
        assert!(close(f2, 0.263309), "{f2}");
        let x = Motivations::new(0.25, 0.25, 0.25, 0.25).unwrap();
        let f3 = t.evaluate(&x, [1.0, 1.0, 1.0, 1.0]);
        assert!(close(f3, 1.0), "{f3}");
    }

    #[test]
    fn constants_are_valid() {
        for m in [Motivations::HIGH_CURIOSITY, Motivations::LOW_CURIOSITY] {
            let [c, h, o, e] = m.as_array();
            assert_eq!(Motivations::new(c, h, o, e), Ok(m));
        }
    }

    #[test]
    fn rule_numbering() {
        let t = TskFitness::paper();
        assert_eq!(t.labels(), 5);
        assert_eq!(t.rule_count(), 625);
        assert_eq!(t.rule_number([5, 2, 1, 1]), 10);
        assert_eq!(t.rule_labels(10), [5, 2, 1, 1]);
        assert_eq!(t.rule_number([1, 1, 1, 1]), 1);
        assert_eq!(t.rule_number([5, 5, 5, 5]), 625);
        for n in 1..=625 {
            assert_eq!(t.rule_number(t.rule_labels(n)), n);
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
        let mut rng = Lcg(12345);
        let specials = [0.0, 0.25, 0.5, 0.75, 1.0, 0.35, -0.2, 1.5, f64::NAN];
        for t in &ts {
            for _ in 0..3000 {
                let raw = [0.0; 4].map(|_| rng.next_f64());
                let total: f64 = raw.iter().sum();
                let x = Motivations {
                    curiosity: raw[0] / total,
                    homing: raw[1] / total,
                    orientation: raw[2] / total,
                    energy: raw[3] / total,
                };
                let y = [0.0; 4].map(|_| {
                    let r = rng.next_f64();
                    if r < 0.3 {
                        specials[(rng.next_f64() * specials.len() as f64) as usize]
                    } else {
                        rng.next_f64() * 1.4 - 0.2
                    }
                });
                let fast = t.evaluate(&x, y);
                let slow = reference(t, &x, y);
                assert_eq!(fast.to_bits(), slow.to_bits(), "{x:?} {y:?}");
                assert_eq!(t.explain(&x, y).fitness.to_bits(), fast.to_bits());
            }
        }
    }

    #[test]
    fn explanation_is_consistent() {
        let t = TskFitness::paper();
        let x = Motivations::HIGH_CURIOSITY;
        let y = [0.95, 0.5, 0.0, 0.79];
        let e = t.explain(&x, y);
        assert_eq!(e.fitness, t.evaluate(&x, y));
        assert_eq!(e.rules.len(), 4);
        let s: f64 = e.rules.iter().map(|r| r.weight).sum();
        assert!((s - e.weight_sum).abs() < 1e-12);
        assert!(e.rules.iter().all(|r| r.weight > 0.0));
        assert!(e.rules.windows(2).all(|p| p[0].number < p[1].number));
        for r in &e.rules {
            assert_eq!(t.rule_labels(r.number), r.labels);
        }
        let text = e.to_string();
        assert!(text.contains("V.H."), "{text}");
        assert!(text.contains("if a is V.H. and g is M and l is V.L. and b is H"));
        assert!(text.contains("0.797220"), "{text}");

        let sample = t.explain(&x, [1.0, 0.25, 0.0, 0.0]);
        assert_eq!(sample.rules.len(), 1);
        assert_eq!(sample.rules[0].number, 10);
        assert_eq!(sample.rules[0].label_names, ["V.H.", "L", "V.L.", "V.L."]);
    }

    #[test]
    fn out_of_range_y_is_clamped() {
        let t = TskFitness::paper();
        let x = Motivations::LOW_CURIOSITY;
        assert_eq!(
            t.evaluate(&x, [1.7, -0.3, f64::NAN, f64::INFINITY]),
            t.evaluate(&x, [1.0, 0.0, 0.0, 1.0])
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
                    matches!(err, FuzzyError::MotivationOutOfRange { name: n, value }
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
