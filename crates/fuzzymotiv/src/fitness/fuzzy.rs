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

use crate::params::Num;

/// Tolerance on `|C + H + O + E − 1|` accepted by [`crate::fitness::Motivations::new`].
pub const MOTIVATION_SUM_TOLERANCE: f64 = 1e-9;

/// How far `C + H + O + E` may be off 1 and still be normalised by
/// [`crate::fitness::Motivations::normalised`] (docs/model.md §8: e.g. `.3333` three times).
pub const MOTIVATION_NORMALISE_TOLERANCE: f64 = 1e-3;

/// Largest number of labels (peaks) accepted by [`TskFitness::new`]; keeps
/// `M^4` representable in `usize` on every supported platform.
pub const MAX_LABELS: usize = 255;

/// The range of every peak and every coefficient accepted by [`TskFitness::new`]: a fitness
/// term is a value in [0, 1], and with coefficients in [0, 1] every rule output `f[n]` (a mean
/// of coefficients weighted by the motivations) and so F are too, as the tables and figures
/// show them (docs/model.md §8).
pub const LABEL_RANGE: std::ops::RangeInclusive<f64> = 0.0..=1.0;

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
    /// A peak is not a number in [0, 1] ([`LABEL_RANGE`]).
    #[error(
        "{of}peaks must be numbers from 0 to 1 (a fitness term is a value in [0, 1]), got {} at position {index} (0-based)", Num(*.value)
    )]
    PeakOutOfRange {
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
    /// A coefficient is not a number in [0, 1] ([`LABEL_RANGE`]).
    #[error(
        "{of}coefficients must be numbers from 0 to 1 (so that F, a weighted mean of them, is a fitness in [0, 1]), got {} at position {index} (0-based)", Num(*.value)
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
/// Read by hand, so that a wrong value is answered in plain words (`"linear"`, `"ratio"` or a
/// list of numbers) rather than serde's "did not match any variant of untagged enum".
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
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

impl<'de> serde::Deserialize<'de> for Coefficients {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::{self, SeqAccess, Visitor};
        const EXPECTED: &str = "\"linear\", \"ratio\" or a list of numbers, one per peak";
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Coefficients;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(EXPECTED)
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Coefficients, E> {
                match v {
                    "linear" => Ok(Coefficients::Scheme(CoefficientScheme::Linear)),
                    "ratio" => Ok(Coefficients::Scheme(CoefficientScheme::Ratio)),
                    _ => Err(E::custom(format!(
                        "unknown coefficients {v:?}; expected {EXPECTED}"
                    ))),
                }
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Coefficients, A::Error> {
                let mut values = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(MAX_LABELS));
                while let Some(v) = seq.next_element::<f64>()? {
                    values.push(v);
                }
                Ok(Coefficients::Values(values))
            }
        }
        d.deserialize_any(V)
    }
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
            | FuzzyError::PeakOutOfRange { of, .. }
            | FuzzyError::PeaksNotIncreasing { of, .. } => Some(format!("{of}peaks")),
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
pub(crate) fn clamp_unit(y: f64) -> f64 {
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
pub(crate) struct Candidates {
    pub(crate) labels: [usize; 2],
    pub(crate) mu: [f64; 2],
    pub(crate) len: usize,
}

impl Candidates {
    /// No input (the unused slots of a fixed-size array).
    pub(crate) const NONE: Candidates = Candidates {
        labels: [0; 2],
        mu: [0.0; 2],
        len: 0,
    };
}

impl TskFitness {
    /// Validates and builds a fuzzy fitness function.
    ///
    /// `peaks`: 2..=[`MAX_LABELS`] strictly increasing values in [0, 1] ([`LABEL_RANGE`]; the
    /// first need not be 0 nor the last 1); label `m` is a triangle peaking at
    /// `peaks[m]` and reaching zero at its neighbours' peaks, the first and
    /// last labels being shoulders (1 beyond their peak).
    /// `coefficients`: one value in [0, 1] per peak; see [`CoefficientScheme::values`].
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
        if let Some((index, &value)) =
            (peaks.iter().enumerate()).find(|(_, p)| !LABEL_RANGE.contains(*p))
        {
            return Err(FuzzyError::PeakOutOfRange { of, index, value });
        }
        if peaks.windows(2).any(|pair| pair[0] >= pair[1]) {
            return Err(FuzzyError::PeaksNotIncreasing { of, peaks });
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
            .find(|(_, c)| !LABEL_RANGE.contains(*c))
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
    pub(crate) fn candidates(&self, y: f64) -> Candidates {
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity() {
        let ts = [
            TskFitness::paper(),
            TskFitness::with_scheme(vec![0.1, 0.3, 0.35, 0.9], CoefficientScheme::Ratio).unwrap(),
            TskFitness::with_scheme(vec![0.2, 0.7], CoefficientScheme::Linear).unwrap(),
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
        assert!(matches!(err, FuzzyError::PeakOutOfRange { index: 1, .. }));
        let err = TskFitness::new(vec![0.0, f64::INFINITY], lin(2)).unwrap_err();
        assert!(matches!(err, FuzzyError::PeakOutOfRange { .. }));
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
        assert_eq!(
            TskFitness::new(PAPER_PEAKS.to_vec(), lin(5)),
            Ok(TskFitness::paper())
        );
    }

    /// Issue #52 item 7: peaks and coefficients are numbers in [0, 1], so that F is a fitness
    /// in [0, 1]; ±1e300 (F 3e299, std inf, 300-digit tables) and peaks outside are refused
    /// naming the list and the value, compactly.
    #[test]
    fn peaks_and_coefficients_outside_0_1_are_refused() {
        let err = TskFitness::new(vec![0.0, 1.0], vec![0.0, 1e300]).unwrap_err();
        assert!(matches!(
            err,
            FuzzyError::InvalidCoefficient { index: 1, .. }
        ));
        assert!(err.to_string().contains("from 0 to 1") && err.to_string().contains("got 1e300"));
        assert!(TskFitness::new(vec![0.0, 1.0], vec![-1e300, 1.0]).is_err());
        assert!(TskFitness::new(vec![0.0, 1.0], vec![-0.1, 1.0]).is_err());
        let err = TskFitness::new(vec![-1.0, 2.0], vec![0.0, 1.0]).unwrap_err();
        assert!(
            matches!(err, FuzzyError::PeakOutOfRange { index: 0, .. }),
            "{err}"
        );
        assert!(TskFitness::new(vec![0.0, 1.5], vec![0.0, 1.0]).is_err());
        assert!(TskFitness::new(vec![0.0, 1.0], vec![0.0, 1.0]).is_ok());
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
