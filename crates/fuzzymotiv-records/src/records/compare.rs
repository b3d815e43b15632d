//! `compare.csv`: one row per (setting, metric, room or overall) of `fuzzymotiv compare`,
//! written and read by this module.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::files::error::CliError;
use crate::records::{read_csv, to_csv};

/// The `room` of the rows over all rooms (per seed, replicate or test run, the mean over rooms).
pub const OVERALL: &str = "overall";

/// One comparison of A with B: a metric in a room (or over all rooms) of one setting.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompareRow {
    /// The setting compared: A's, and B's after " vs " when they differ.
    pub setting: String,
    /// The metric (a column of the per-room table, e.g. `exploration_pct`).
    pub metric: String,
    /// The room, or [`OVERALL`].
    pub room: String,
    /// `paired` (the two share their seeds) or `unpaired`.
    pub design: String,
    /// Values of A (seeds, replicates or test runs).
    pub n_a: usize,
    /// Values of B.
    pub n_b: usize,
    /// Mean of A.
    pub mean_a: f64,
    /// Mean of B.
    pub mean_b: f64,
    /// A − B (paired: the mean of the per-seed differences).
    pub difference: f64,
    /// Lower bound of the percentile bootstrap interval of the difference.
    pub ci_low: f64,
    /// Upper bound of the interval.
    pub ci_high: f64,
    /// Two-sided permutation p-value.
    pub p: f64,
    /// Whether `p` enumerated every arrangement (else resampled).
    pub exact: bool,
    /// `p` Holm-adjusted over the rooms of this setting and metric (the overall row: `p`).
    pub p_holm: f64,
    /// The smallest difference detectable with 80 % power at α; empty with fewer than two
    /// values in a sample.
    pub mdd: Option<f64>,
}

/// `compare.csv`'s text.
pub fn to_text(rows: &[CompareRow]) -> String {
    to_csv(rows)
}

/// Reads a `compare.csv`.
pub fn read(path: &Path) -> Result<Vec<CompareRow>, CliError> {
    read_csv(path)
}
