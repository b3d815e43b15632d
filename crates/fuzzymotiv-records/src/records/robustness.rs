//! `robustness.csv` and `robustness.md`: a run's best robot under the perturbations a real
//! robot brings ([`fuzzymotiv::experiment::Experiment::robustness`]), per perturbation the mean
//! and 95 % bootstrap interval of F and of each behaviour term. `fuzzymotiv robustness` and
//! `fm.robustness` both go through [`robustness_of_run`].

use std::path::Path;

use fuzzymotiv::experiment::{Perturbation, RobustnessRow};
use fuzzymotiv::statistics::{mean, mean_interval};
use serde::{Deserialize, Serialize};

use crate::files::error::CliError;
use crate::files::inputs::load_config;
use crate::records::genome::{locate, read_genome};
use crate::records::{Fixed, to_csv};

/// The measures of a row, in column order: the column stem and the words a table or figure
/// shows. The last, recognition, is there only for a run with one room model (room modelling
/// on, all-rooms training): [`RobustnessRecord::measures`].
pub const MEASURES: [(&str, &str); 5] = [
    ("f", "F"),
    ("exploration", "exploration a"),
    ("homing", "homing g"),
    ("battery", "battery b"),
    ("recognition", "recognised"),
];

/// One perturbation: its trials and, per measure of [`MEASURES`], the mean over the trials
/// with the bounds of its 95 % percentile bootstrap interval (2000 resamples).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobustnessRecord {
    /// The perturbation's label (`none`, `noise=0.1`, `dead=3`, …).
    pub perturbation: String,
    /// Trials (per room × rooms).
    pub trials: usize,
    /// Mean F.
    pub f: Fixed<6>,
    /// Its interval's lower bound.
    pub f_lo: Fixed<6>,
    /// Its interval's upper bound.
    pub f_hi: Fixed<6>,
    /// Mean exploration term `a`.
    pub exploration: Fixed<6>,
    /// Its interval's lower bound.
    pub exploration_lo: Fixed<6>,
    /// Its interval's upper bound.
    pub exploration_hi: Fixed<6>,
    /// Mean homing term `g`.
    pub homing: Fixed<6>,
    /// Its interval's lower bound.
    pub homing_lo: Fixed<6>,
    /// Its interval's upper bound.
    pub homing_hi: Fixed<6>,
    /// Mean battery term `b`.
    pub battery: Fixed<6>,
    /// Its interval's lower bound.
    pub battery_lo: Fixed<6>,
    /// Its interval's upper bound.
    pub battery_hi: Fixed<6>,
    /// The share of trials whose actions the unperturbed robot's room model recognised as
    /// their room (none without one room model).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub recognition: Option<Fixed<6>>,
    /// Its interval's lower bound.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub recognition_lo: Option<Fixed<6>>,
    /// Its interval's upper bound.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub recognition_hi: Option<Fixed<6>>,
}

impl RobustnessRecord {
    /// The record of the `k`-th row of a study (its bootstrap on stream `k + 1`).
    pub fn of(k: usize, row: &RobustnessRow) -> RobustnessRecord {
        let stats = |v: &Vec<f64>| {
            let (lo, hi) = mean_interval(v, 0.95, 2000, k as u64 + 1);
            (Fixed(mean(v)), Fixed(lo), Fixed(hi))
        };
        let [f, e, h, b] = [&row.f, &row.exploration, &row.homing, &row.battery].map(stats);
        let r = (!row.recognised.is_empty()).then(|| stats(&row.recognised));
        RobustnessRecord {
            perturbation: row.perturbation.label(),
            trials: row.f.len(),
            f: f.0,
            f_lo: f.1,
            f_hi: f.2,
            exploration: e.0,
            exploration_lo: e.1,
            exploration_hi: e.2,
            homing: h.0,
            homing_lo: h.1,
            homing_hi: h.2,
            battery: b.0,
            battery_lo: b.1,
            battery_hi: b.2,
            recognition: r.map(|r| r.0),
            recognition_lo: r.map(|r| r.1),
            recognition_hi: r.map(|r| r.2),
        }
    }

    /// Per measure of [`MEASURES`] the record has (recognition only with a room model):
    /// (mean, lower bound, upper bound).
    pub fn measures(&self) -> Vec<(f64, f64, f64)> {
        let mut all = vec![
            (self.f, self.f_lo, self.f_hi),
            (self.exploration, self.exploration_lo, self.exploration_hi),
            (self.homing, self.homing_lo, self.homing_hi),
            (self.battery, self.battery_lo, self.battery_hi),
        ];
        if let (Some(m), Some(lo), Some(hi)) =
            (self.recognition, self.recognition_lo, self.recognition_hi)
        {
            all.push((m, lo, hi));
        }
        all.into_iter()
            .map(|(m, lo, hi)| (m.0, lo.0, hi.0))
            .collect()
    }
}

/// The measures of [`MEASURES`] that `records` have: recognition when the first has it.
pub fn measures_of(records: &[RobustnessRecord]) -> &'static [(&'static str, &'static str)] {
    let n = records.first().map_or(4, |r| r.measures().len());
    &MEASURES[..n]
}

/// `robustness.csv`'s text.
pub fn robustness_csv(records: &[RobustnessRecord]) -> String {
    to_csv(records)
}

/// A robustness study of a run: its rows and what they change ([`Perturbation::notes`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RobustnessStudy {
    /// One record per perturbation, `none` first.
    pub records: Vec<RobustnessRecord>,
    /// One sentence per perturbation family present (what it changes and what not), and the
    /// rows left out for this robot.
    pub notes: Vec<String>,
}

/// `robustness.md`'s text: one table row per perturbation, each measure as `mean [lo, hi]`,
/// then the `notes` as a list.
pub fn robustness_md(records: &[RobustnessRecord], notes: &[String]) -> String {
    let measures = measures_of(records);
    let mut md = String::from("| perturbation |");
    for (k, (_, words)) in measures.iter().enumerate() {
        md.push_str(&format!(
            " {words}{} |",
            if k == 0 { " (95 % CI)" } else { "" }
        ));
    }
    md.push_str(&format!("\n|---|{}\n", "---|".repeat(measures.len())));
    for r in records {
        md.push_str(&format!("| {} |", r.perturbation));
        for (m, lo, hi) in r.measures() {
            md.push_str(&format!(" {m:.3} [{lo:.3}, {hi:.3}] |"));
        }
        md.push('\n');
    }
    if !notes.is_empty() {
        md.push_str("\nNotes:\n\n");
        for n in notes {
            md.push_str(&format!("- {n}\n"));
        }
    }
    md
}

/// The robustness study of a run directory's best robot: the standard perturbations
/// ([`Perturbation::standard_for`] the run's robot), `trials` trials per room and perturbation on paired streams.
pub fn robustness_of_run(run: &Path, trials: usize) -> Result<RobustnessStudy, CliError> {
    let (genome_path, config) = locate(run)?;
    let Some(config) = config else {
        return Err(CliError::input(format!(
            "{}: no config.resolved.toml beside the genome; robustness needs a run directory",
            run.display()
        )));
    };
    if !(2..=10_000).contains(&trials) {
        return Err(CliError::input(format!(
            "trials must be a whole number in 2..=10000 (an interval needs two trials), got {trials}"
        )));
    }
    let genome = read_genome(&genome_path)?;
    let loaded = load_config(Some(&config), &[], None)?;
    let exp = &loaded.experiment;
    let perturbations = Perturbation::standard_for(exp.trial_params());
    let at = |e: &dyn std::fmt::Display| CliError::input(format!("{}: {e}", genome_path.display()));
    // The room model the robot built unperturbed (one, with all-rooms training): is a
    // perturbed trial still recognised as its room?
    let recognizer = match exp.runs().as_slice() {
        [one] => {
            let network = exp.network(&genome.weights).map_err(|e| at(&e))?;
            exp.recognizer(&network, one).map_err(|e| at(&e))?
        }
        _ => None,
    };
    let rows = exp
        .robustness_recognising(&genome.weights, &perturbations, trials, recognizer.as_ref())
        .map_err(|e| at(&e))?;
    Ok(RobustnessStudy {
        records: rows
            .iter()
            .enumerate()
            .map(|(k, r)| RobustnessRecord::of(k, r))
            .collect(),
        notes: Perturbation::notes(&perturbations, exp.trial_params()),
    })
}
