//! Running a study: its runs as a sweep's jobs into `OUT/jobs/ID/` ([`run_jobs`]; a shard of
//! them on one machine, the others elsewhere), then, once every run is there, the analysis
//! written beside them: `per_seed.csv`, `arms.csv`, `study.json`, `report.md`, with hypotheses
//! `claims.csv`, `rooms.csv` and `forest.svg`, with several base seeds `agreement.csv` too. The analysis
//! reads only the runs' records, so a study run in shards gives the same bytes as one run on
//! one machine.

use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::files::guard::write_files;
use crate::pipeline::lanes::set_threads;
use crate::pipeline::sweep_jobs::run_jobs;
use crate::records::hypotheses::{ClaimRow, StudyRecord};
use crate::records::{PROGRAM, to_csv, to_json};
use crate::render::hypotheses::{forest_svg, report_md};
use crate::study::file::Study;
use crate::study::per_seed::per_seed;
pub use crate::study::progress::StudyProgress;
use crate::study::{agreement, analysis, transfer};

/// How a study runs.
#[derive(Debug, Clone, Default)]
pub struct StudyOptions {
    /// The study's directory (its runs in `jobs/`, its analysis beside them).
    pub out: PathBuf,
    /// Worker threads (`None`: all cores); results do not depend on it.
    pub threads: Option<usize>,
    /// Replace another study (or other fuzzymotiv output) in `out`.
    pub force: bool,
    /// Run only shard `(k, n)`: the runs whose plan index ≡ k (mod n).
    pub shard: Option<(usize, usize)>,
}

/// What a study run did.
#[derive(Debug, Clone, PartialEq)]
pub enum StudyOutcome {
    /// Every run is there and the analysis was written: its claims.
    Analysed(Vec<ClaimRow>),
    /// Runs are missing (other shards'): `done` of `total`.
    Waiting {
        /// Runs finished.
        done: usize,
        /// Runs planned.
        total: usize,
    },
}

/// `K/N` of `--shard`: run k of n (0 ≤ k < n).
pub fn parse_shard(text: &str) -> Result<(usize, usize), CliError> {
    let bad = || {
        CliError::input(format!(
            "--shard {text}: expected K/N with 0 ≤ K < N, e.g. 0/3"
        ))
    };
    let (k, n) = text.split_once('/').ok_or_else(bad)?;
    let k: usize = k.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || k >= n {
        return Err(bad());
    }
    Ok((k, n))
}

/// Runs `study` (its shard, if `options` name one) into `options.out`; once every run is
/// there, writes its analysis.
pub fn run_study(
    study: &Study,
    options: &StudyOptions,
    progress: &dyn StudyProgress,
) -> Result<StudyOutcome, CliError> {
    set_threads(options.threads)?;
    let total = study.plan.jobs.len();
    let selected: Vec<usize> = match options.shard {
        Some((k, n)) => (0..total).filter(|j| j % n == k).collect(),
        None => (0..total).collect(),
    };
    let out = &options.out;
    run_jobs(
        &study.plan,
        &study.text,
        &selected,
        out,
        options.force,
        progress,
    )?;
    let done = (study.plan.jobs.iter())
        .filter(|j| out.join("jobs").join(&j.id).join("DONE").is_file())
        .count();
    if done < total {
        progress.waiting(done, total);
        return Ok(StudyOutcome::Waiting { done, total });
    }
    transfer::transfer_runs(study, out, progress)?;
    let record = analyse(study, out)?;
    progress.analysed(out, &record.claims);
    Ok(StudyOutcome::Analysed(record.claims))
}

/// The per-seed values of every run (plan order), the room names, then the analysis, written
/// into `out`.
fn analyse(study: &Study, out: &Path) -> Result<StudyRecord, CliError> {
    let rows = per_seed(study, out)?;
    let level = |arm: &str| {
        (study.arm_index(arm))
            .and_then(|k| study.arms[k].level)
            .unwrap_or(f64::NAN)
    };
    let a = &study.analysis;
    let bases = &study.base_seeds;
    let claims = analysis::claims(&study.hypotheses, &rows, bases, &level, a)?;
    let room_rows = analysis::room_results(&study.hypotheses, &rows, bases, &level, a)?;
    let arms: Vec<&str> = study.arms.iter().map(|a| a.name.as_str()).collect();
    let measures = analysis::arm_measures(&rows, &arms, bases);
    let hs = &study.hypotheses;
    let agreement = agreement::agreement(hs, &rows, bases, study.seeds, &level, a, &claims)?;
    let record = StudyRecord {
        program: PROGRAM.into(),
        model: fuzzymotiv::MODEL_VERSION,
        name: study.name.clone(),
        analysis: *a,
        base_seeds: bases.clone(),
        seeds: study.seeds,
        arms: study.arms.clone(),
        hypotheses: study.hypotheses.clone(),
        claims,
        rooms: room_rows,
        measures,
        agreement,
    };
    let mut files = vec![
        ("per_seed.csv", to_csv(&rows)),
        ("arms.csv", to_csv(&record.measures)),
        ("study.json", to_json(&record)),
        ("report.md", report_md(&record, &rows, &study.text)),
    ];
    // A study without hypotheses (a sweep of arms) has no claims, rooms or forest to write.
    if !record.hypotheses.is_empty() {
        files.push(("claims.csv", to_csv(&record.claims)));
        files.push(("rooms.csv", to_csv(&record.rooms)));
        files.push(("forest.svg", forest_svg(&record)));
    }
    if !record.agreement.is_empty() {
        files.push(("agreement.csv", to_csv(&record.agreement)));
    }
    let files: Vec<(PathBuf, Vec<u8>)> = (files.into_iter())
        .map(|(name, text)| (out.join(name), text.into_bytes()))
        .collect();
    write_files(&files)?;
    Ok(record)
}
