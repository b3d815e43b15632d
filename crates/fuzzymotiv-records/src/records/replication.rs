//! `reproduce --replication`'s records: the paper's claims from two independent studies (two
//! base seeds) and from their seeds pooled, and at how many seeds the verdicts replicate
//! (`replication.csv`, `replication_seeds.csv`, `summary.json`).

use serde::{Deserialize, Serialize};

use crate::records::ClaimRecord;
use crate::records::paper_claims::ClaimId;

/// One claim: its verdict under each base seed's study and under the pooled seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReplicationRow {
    /// The claim (written as its sentence).
    pub claim: ClaimId,
    /// Its verdict from the first base seed's study (all its seeds).
    pub verdict_a: String,
    /// Its verdict from the second base seed's study.
    pub verdict_b: String,
    /// Its verdict from both studies' seeds pooled.
    pub verdict_pooled: String,
    /// The pooled effect (high − low, points); none for the checks of Fig. 6's curves.
    pub effect: Option<f64>,
    /// Lower bound of its 95 % interval.
    pub ci_low: Option<f64>,
    /// Upper bound.
    pub ci_high: Option<f64>,
    /// The pooled p-value.
    pub p: Option<f64>,
    /// The smallest difference the pooled seeds detect with 80 % power.
    pub mdd: Option<f64>,
    /// Whether the claim is at the edge of its power: |effect| within the detectable
    /// difference of one base seed's study.
    pub at_edge: bool,
    /// The verdict the study reports: the pooled one, or `inconclusive` when the two base
    /// seeds disagree with it at every number of seeds tried and the claim is at the edge.
    pub verdict: String,
}

/// The verdicts at the first `seeds` seeds of each base seed's study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeedsRow {
    /// Seeds per base seed.
    pub seeds: usize,
    /// Per claim (in the rows' order), the verdict of the first base seed's first `seeds`.
    pub verdicts_a: Vec<String>,
    /// The same for the second base seed.
    pub verdicts_b: Vec<String>,
    /// Per claim, the p-value of the first base seed (none for Fig. 6's checks).
    pub p_a: Vec<Option<f64>>,
    /// The same for the second base seed.
    pub p_b: Vec<Option<f64>>,
    /// Whether every verdict of both equals the pooled verdict.
    pub agree: bool,
}

/// `reproduce --replication`'s `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReplicationSummary {
    /// Always `fuzzymotiv`.
    pub program: String,
    /// Program version.
    pub version: String,
    /// Model version.
    pub model: u32,
    /// The two base seeds.
    pub base_seeds: [u64; 2],
    /// Seeds per base seed.
    pub seeds: usize,
    /// Whether `--quick`.
    pub quick: bool,
    /// GA population.
    pub population: usize,
    /// GA generations.
    pub generations: usize,
    /// `--set` overrides.
    pub overrides: Vec<String>,
    /// Per claim, the verdicts.
    pub rows: Vec<ReplicationRow>,
    /// Per number of seeds, the verdicts of both base seeds.
    pub by_seeds: Vec<SeedsRow>,
    /// The smallest number of seeds from which on both base seeds' verdicts equal the pooled
    /// ones (at every larger number tried too); none if even all seeds do not.
    pub seeds_needed: Option<usize>,
    /// The claims from the pooled seeds.
    pub pooled: Vec<ClaimRecord>,
    /// Wall time (s).
    pub wall_seconds: f64,
}
