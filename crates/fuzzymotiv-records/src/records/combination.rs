//! `reproduce --combination`'s records: the behaviour under each baseline combination against
//! the TSK (`behaviour.csv`, and `summary.json`).

use serde::{Deserialize, Serialize};

use crate::records::paired::PairedStats;
use crate::records::paper_claims::ClaimId;
use crate::records::{ClaimRecord, VariantSummary};

/// One measure of one setting: a baseline against the TSK, paired by seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BehaviourRow {
    /// The baseline (`weighted-sum`, `weighted-squares`).
    pub combination: String,
    /// The setting (`high-curiosity`, `low-curiosity`).
    pub setting: String,
    /// The measure (`% optimal exploration`, `% homing`, `% battery usage`, `% recognition`).
    pub measure: String,
    /// Mean over seeds under the baseline.
    pub mean_combination: f64,
    /// Mean over seeds under the TSK.
    pub mean_tsk: f64,
    /// Baseline − TSK (a = the baseline, b = the TSK): the difference, its interval, p, the
    /// detectable difference (in `behaviour.csv` `NaN` where there is none) and the verdict
    /// (`higher` / `lower` under the baseline).
    #[serde(flatten)]
    pub stats: PairedStats,
}

/// One comparison claim (high − low curiosity on a measure, paired by seed) under a baseline
/// against the TSK: the difference in differences, per seed (high − low)_baseline −
/// (high − low)_TSK, paired by seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimDifferenceRow {
    /// The baseline (`weighted-sum`, `weighted-squares`).
    pub combination: String,
    /// The claim (written as its sentence, as the claims tables word it).
    pub claim: ClaimId,
    /// The claim's effect under the baseline: mean over seeds of high − low.
    pub effect_combination: f64,
    /// The claim's effect under the TSK.
    pub effect_tsk: f64,
    /// Baseline's effect − TSK's effect, paired by seed (a = the baseline's high − low, b = the
    /// TSK's): the difference, its interval, p, the detectable difference and the verdict
    /// (`higher` / `lower`: a larger / smaller high − low under the baseline).
    #[serde(flatten)]
    pub stats: PairedStats,
}

/// `reproduce --combination`'s `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CombinationSummary {
    /// Always `fuzzymotiv`.
    pub program: String,
    /// Program version.
    pub version: String,
    /// Model version.
    pub model: u32,
    /// `--seed`.
    pub seed: u64,
    /// The study's seeds.
    pub seeds: Vec<u64>,
    /// Whether `--quick`.
    pub quick: bool,
    /// GA population.
    pub population: usize,
    /// GA generations.
    pub generations: usize,
    /// `--set` overrides.
    pub overrides: Vec<String>,
    /// The paper's claims under each combination (the TSK first).
    pub combinations: Vec<VariantSummary>,
    /// Each baseline against the TSK, per setting and measure.
    pub behaviour: Vec<BehaviourRow>,
    /// Per combination (in `combinations`' order), setting and seed: the end spread, the
    /// root-mean-square distance of the best robot's test runs' final positions from their
    /// centroid in % of the room's largest distance, mean over rooms.
    #[serde(default)]
    pub end_spreads: Vec<Vec<Vec<f64>>>,
    /// Each baseline against the TSK, per comparison claim: whether the claim's effect differs
    /// (none in files written before it was measured).
    #[serde(default)]
    pub claim_differences: Vec<ClaimDifferenceRow>,
    /// Wall time (s).
    pub wall_seconds: f64,
}

/// The claims of a combination study, by combination (for tables that read them back).
pub fn claims_of(summary: &CombinationSummary) -> Vec<(&str, &[ClaimRecord])> {
    summary
        .combinations
        .iter()
        .map(|v| (v.name.as_str(), v.claims.as_slice()))
        .collect()
}
