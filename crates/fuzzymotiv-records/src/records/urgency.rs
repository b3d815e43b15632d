//! `reproduce --urgency`'s records: per urgency weight and seed what the evolved robots do on
//! the `fetch` mission (`urgency_seeds.csv`), each step up in urgency as a paired comparison
//! (`urgency.csv`), and both in `summary.json`.

use serde::{Deserialize, Serialize};

use crate::records::paired::PairedStats;

/// One seed under one urgency weight: the best robot's test runs, means over rooms.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UrgencySeed {
    /// The setting (`urgency-0.1`, …).
    pub setting: String,
    /// The urgency weight u (curiosity is 0.8 − u).
    pub urgency: f64,
    /// The seed's index in the study, from 1 (its run directory `seed-NN`).
    pub index: usize,
    /// The seed.
    pub seed: u64,
    /// % of the test runs whose mission was done (the goal zone reached).
    pub success_pct: f64,
    /// Mean step (1-based) at which the successful test runs reached the goal; none when no
    /// test run did.
    pub time_to_goal: Option<f64>,
    /// Mean 100·a over the test runs.
    pub exploration_pct: f64,
    /// Mean 100·b over the test runs.
    pub battery_pct: f64,
    /// Mean 100·g over the test runs.
    pub homing_pct: f64,
}

/// One measure, one step up in urgency: the higher weight against the lower, paired by seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UrgencyRow {
    /// The measure, as the tables name it.
    pub measure: String,
    /// The lower urgency weight.
    pub from: f64,
    /// The higher urgency weight.
    pub to: f64,
    /// The seeds paired (those with a value under both weights).
    pub pairs: usize,
    /// Mean over those seeds at `from`.
    pub mean_from: f64,
    /// Mean over those seeds at `to`.
    pub mean_to: f64,
    /// `to` − `from` (a = the higher weight, b = the lower): the difference, its interval, p,
    /// the detectable difference and the verdict (`higher` / `lower` at `to`).
    #[serde(flatten)]
    pub stats: PairedStats,
}

/// `reproduce --urgency`'s `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UrgencySummary {
    /// Always `fuzzymotiv`.
    pub program: String,
    /// Program version.
    pub version: String,
    /// Model version.
    pub model: u32,
    /// `--seed`.
    pub seed: u64,
    /// The study's seeds (the same under every weight).
    pub seeds: Vec<u64>,
    /// Whether `--quick`.
    pub quick: bool,
    /// GA population.
    pub population: usize,
    /// GA generations.
    pub generations: usize,
    /// `--set` overrides.
    pub overrides: Vec<String>,
    /// The urgency weights, in the settings' order.
    pub weights: Vec<f64>,
    /// Every setting's seeds, weight by weight.
    pub per_seed: Vec<UrgencySeed>,
    /// Each step up in urgency (and the lowest against the highest), per measure.
    pub comparisons: Vec<UrgencyRow>,
    /// Wall time (s).
    pub wall_seconds: f64,
}
