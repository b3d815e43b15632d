//! Fitness: the terms a trial is scored by (exploration a, homing g, orientation l, battery b)
//! and the Takagi–Sugeno–Kang fuzzy combination of them under the motivations X.

pub(crate) mod episode;
pub(crate) mod fll;
pub(crate) mod fuzzy;
pub(crate) mod terms;

pub use episode::Episode;
pub use fll::to_fll;
pub use fuzzy::{
    CoefficientScheme, Explanation, FiringRule, FuzzyError, MAX_COEFFICIENT_MAGNITUDE, MAX_LABELS,
    MOTIVATION_NORMALISE_TOLERANCE, MOTIVATION_SUM_TOLERANCE, Motivations, PAPER_LABEL_NAMES,
    PAPER_PEAKS, TskFitness, label_name,
};
pub use terms::{FitnessTerms, Homing, TermsRecorder};
