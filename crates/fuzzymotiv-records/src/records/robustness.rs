//! `robustness.csv` and `robustness.md`: a run's best robot under the perturbations a real
//! robot brings ([`fuzzymotiv::experiment::Experiment::robustness`]), per perturbation the mean
//! and 95 % bootstrap interval of F and of each behaviour term. A run that follows missions or
//! weighs terms of its own has more columns, after the paper's: the share of missions done and
//! each term beyond a, g, l, b that `table.md` shows ([`crate::records::extra_terms`]).
//! `fuzzymotiv robustness` and `fm.robustness` both go through [`robustness_of_run`].

use std::path::Path;

use fuzzymotiv::experiment::{Perturbation, RobustnessRow};
use fuzzymotiv::fitness::TermId;
use fuzzymotiv::statistics::{mean, mean_interval};
use serde::{Deserialize, Serialize};

use crate::files::error::CliError;
use crate::files::inputs::load_config;
use crate::records::genome::{locate, read_genome};
use crate::records::test_runs::in_table_order;
use crate::records::{Fixed, csv_text, csv_writer, extra_terms, to_csv, write_row};

/// The measures of a row, in column order: the column stem and the words a table or figure
/// shows. The last, recognition, is there only for a run with one room model (room modelling
/// on, all-rooms training): [`RobustnessRecord::measures`]. A run's measures beyond these
/// follow them ([`RobustnessRecord::extra`]).
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
    /// The measures of a run beyond the paper's, in column order after them: the share of
    /// trials whose mission was done (`missions_done`, when the run follows missions), then
    /// each term beyond a, g, l, b the run measures, by name ([`extra_terms`]); none for the
    /// paper's model (columns written by [`robustness_csv`]).
    #[serde(skip)]
    pub extra: Vec<ExtraMeasure>,
}

/// One measure of a [`RobustnessRecord`] beyond the paper's: its mean over the trials and the
/// bounds of its 95 % interval.
#[derive(Debug, Clone, PartialEq)]
pub struct ExtraMeasure {
    /// The column stem (`missions_done`, or the term's name).
    pub stem: String,
    /// The words a table or figure shows (`missions done`, or the term's name).
    pub words: String,
    /// The mean.
    pub mean: Fixed<6>,
    /// Its interval's lower bound.
    pub lo: Fixed<6>,
    /// Its interval's upper bound.
    pub hi: Fixed<6>,
}

/// The stem of the share of missions done.
pub const MISSIONS_DONE: (&str, &str) = ("missions_done", "missions done");

impl RobustnessRecord {
    /// The record of the `k`-th row of a study (its bootstrap on stream `k + 1`), with a
    /// measure per term of `extra` (by name; [`extra_terms`]) that the row kept.
    pub fn of(k: usize, row: &RobustnessRow, extra: &[(String, TermId)]) -> RobustnessRecord {
        let stats = |v: &Vec<f64>| {
            let (lo, hi) = mean_interval(v, 0.95, 2000, k as u64 + 1);
            (Fixed(mean(v)), Fixed(lo), Fixed(hi))
        };
        let [f, e, h, b] = [&row.f, &row.exploration, &row.homing, &row.battery].map(stats);
        let r = (!row.recognised.is_empty()).then(|| stats(&row.recognised));
        let done = (!row.missions_done.is_empty()).then_some((MISSIONS_DONE, &row.missions_done));
        let terms = extra.iter().filter_map(|(name, id)| {
            let (_, values) = row.terms.iter().find(|(t, _)| t == id)?;
            Some(((name.as_str(), name.as_str()), values))
        });
        let extra = (done.into_iter().chain(terms))
            .map(|((stem, words), values)| {
                let (mean, lo, hi) = stats(values);
                ExtraMeasure {
                    stem: stem.to_string(),
                    words: words.to_string(),
                    mean,
                    lo,
                    hi,
                }
            })
            .collect();
        RobustnessRecord {
            extra,
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

    /// Per measure the record has ([`measures_of`]: those of [`MEASURES`], recognition only
    /// with a room model, then [`RobustnessRecord::extra`]): (mean, lower bound, upper bound).
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
        all.extend(self.extra.iter().map(|e| (e.mean, e.lo, e.hi)));
        all.into_iter()
            .map(|(m, lo, hi)| (m.0, lo.0, hi.0))
            .collect()
    }
}

/// The measures that `records` have, (column stem, words) in [`RobustnessRecord::measures`]
/// order: those of [`MEASURES`] (recognition when the first record has it), then the first
/// record's [`RobustnessRecord::extra`].
pub fn measures_of(records: &[RobustnessRecord]) -> Vec<(String, String)> {
    let Some(first) = records.first() else {
        return own(&MEASURES[..4]);
    };
    let paper = first.measures().len() - first.extra.len();
    let mut all = own(&MEASURES[..paper]);
    all.extend(
        first
            .extra
            .iter()
            .map(|e| (e.stem.clone(), e.words.clone())),
    );
    all
}

fn own(measures: &[(&str, &str)]) -> Vec<(String, String)> {
    (measures.iter())
        .map(|(stem, words)| (stem.to_string(), words.to_string()))
        .collect()
}

/// `robustness.csv`'s text: per measure of [`measures_of`] its mean and bounds (`f`, `f_lo`,
/// `f_hi`, …). Records of the paper's model give the bytes they always gave.
pub fn robustness_csv(records: &[RobustnessRecord]) -> String {
    if records.iter().all(|r| r.extra.is_empty()) {
        return to_csv(records);
    }
    let mut w = csv_writer();
    let mut header = vec!["perturbation".to_string(), "trials".to_string()];
    for (stem, _) in measures_of(records) {
        header.extend(["", "_lo", "_hi"].map(|s| format!("{stem}{s}")));
    }
    write_row(&mut w, header);
    for r in records {
        let mut cells = vec![r.perturbation.clone(), r.trials.to_string()];
        for (m, lo, hi) in r.measures() {
            cells.extend([m, lo, hi].map(|v| Fixed::<6>(v).to_string()));
        }
        write_row(&mut w, cells);
    }
    csv_text(w)
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
    let extra = in_table_order(extra_terms(exp), |(name, _)| name);
    Ok(RobustnessStudy {
        records: rows
            .iter()
            .enumerate()
            .map(|(k, r)| RobustnessRecord::of(k, r, &extra))
            .collect(),
        notes: Perturbation::notes(&perturbations, exp.trial_params()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use fuzzymotiv::fitness::RECORD_COLUMN_NAMES;

    /// Every fixed column `robustness.csv` writes (the paper's measures, recognition and the
    /// missions done, each with `_lo` and `_hi`), less `_lo`/`_hi`, is a name the engine refuses
    /// to a user term, so no term's `NAME`, `NAME_lo` or `NAME_hi` repeats one.
    #[test]
    fn every_fixed_robustness_column_is_a_name_a_user_term_cannot_take() {
        let x = Fixed(0.0);
        let record = RobustnessRecord {
            perturbation: "none".into(),
            trials: 2,
            f: x,
            f_lo: x,
            f_hi: x,
            exploration: x,
            exploration_lo: x,
            exploration_hi: x,
            homing: x,
            homing_lo: x,
            homing_hi: x,
            battery: x,
            battery_lo: x,
            battery_hi: x,
            recognition: Some(x),
            recognition_lo: Some(x),
            recognition_hi: Some(x),
            extra: vec![ExtraMeasure {
                stem: MISSIONS_DONE.0.to_string(),
                words: MISSIONS_DONE.1.to_string(),
                mean: x,
                lo: x,
                hi: x,
            }],
        };
        let text = robustness_csv(&[record]);
        let header = text.lines().next().unwrap();
        assert_eq!(
            header.split(',').count(),
            2 + 3 * (MEASURES.len() + 1),
            "{header}"
        );
        for column in header.split(',') {
            let stem = ["_lo", "_hi"]
                .iter()
                .find_map(|s| column.strip_suffix(s))
                .unwrap_or(column);
            assert!(RECORD_COLUMN_NAMES.contains(&stem), "{column}");
        }
    }
}
