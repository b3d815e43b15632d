//! Fitness: the terms a trial is scored by (exploration a, homing g, orientation l, battery b)
//! and the Takagi–Sugeno–Kang fuzzy combination of them under the motivations X.

pub(crate) mod episode;
pub(crate) mod fll;
pub(crate) mod fuzzy;
pub(crate) mod motivation;
pub(crate) mod rules;
pub(crate) mod terms;

pub use episode::Episode;
pub use fll::to_fll;
pub use fuzzy::{
    CoefficientScheme, Coefficients, FuzzyError, LABEL_RANGE, MAX_LABELS,
    MOTIVATION_NORMALISE_TOLERANCE, MOTIVATION_SUM_TOLERANCE, PAPER_LABEL_NAMES, PAPER_PEAKS,
    RawFuzzy, TskFitness, label_name,
};
pub use motivation::{
    MAX_MOTIVATIONS, Motivation, Motivations, PAPER_MOTIVATIONS, PAPER_TERMS, RawMotivation,
    RawMotivationTable, RawMotivations,
};
pub use rules::{Explanation, FiringRule};
pub use terms::{
    FitnessTerms, Homing, LIBRARY_TERMS, MAX_USER_TERMS, MissionTerms, MissionTracker,
    RECORD_COLUMN_NAMES, TERM_ALIASES, Term, TermId, TermsRecorder, TrialRecord, UserValues,
    WaypointOrder,
};
