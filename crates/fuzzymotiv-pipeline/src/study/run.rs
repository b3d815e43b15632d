//! Running a study: its runs as a sweep's jobs into `OUT/jobs/ID/` ([`run_jobs`]; a shard of
//! them on one machine, the others elsewhere), then, once every run is there, the analysis
//! written beside them: `per_seed.csv`, `claims.csv`, `rooms.csv`, `study.json`, `report.md`
//! and `forest.svg` (with several base seeds `agreement.csv` too). The analysis reads only the
//! runs' records, so a study run in shards gives the same bytes as one run on one machine.

use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::files::guard::write_files;
use crate::pipeline::lanes::set_threads;
use crate::pipeline::progress::SweepProgress;
use crate::pipeline::sweep_jobs::run_jobs;
use crate::records::hypotheses::{
    ClaimRow, FIRST_MEAN_F, LAST_MEAN_F, Measure, PerSeedRow, StudyRecord,
};
use crate::records::{PROGRAM, RunSummary, read_json, to_csv, to_json};
use crate::render::hypotheses::{forest_svg, report_md};
use crate::study::file::Study;
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

/// The progress of a study: its runs' (as a sweep's jobs') and its end.
pub trait StudyProgress: SweepProgress {
    /// Only `done` of the study's `total` runs are finished: the analysis waits for the others
    /// (other shards).
    fn waiting(&self, done: usize, total: usize);
    /// The analysis was written into `out`.
    fn analysed(&self, out: &Path, claims: &[ClaimRow]);
    /// Transfer `done` + 1 of the `total` still to make (a transferring arm's run `key` to
    /// Enki in `room`) begins.
    fn transferring(&self, _done: usize, _total: usize, _key: &str, _room: &str) {}
}

impl StudyProgress for crate::pipeline::progress::NoProgress {
    fn waiting(&self, _done: usize, _total: usize) {}
    fn analysed(&self, _out: &Path, _claims: &[ClaimRow]) {}
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
        agreement,
    };
    let mut files = vec![
        ("per_seed.csv", to_csv(&rows)),
        ("claims.csv", to_csv(&record.claims)),
        ("rooms.csv", to_csv(&record.rooms)),
        ("study.json", to_json(&record)),
        ("report.md", report_md(&record, &rows, &study.text)),
        ("forest.svg", forest_svg(&record)),
    ];
    if !record.agreement.is_empty() {
        files.push(("agreement.csv", to_csv(&record.agreement)));
    }
    let files: Vec<(PathBuf, Vec<u8>)> = (files.into_iter())
        .map(|(name, text)| (out.join(name), text.into_bytes()))
        .collect();
    write_files(&files)?;
    Ok(record)
}

/// A measure of job `job` (its run's `summary`) per room, and over the rooms: from the run's
/// per-room table (their mean), or from its transfers to Enki ([`transfer::values`]).
fn room_values(
    study: &Study,
    out: &Path,
    job: &crate::records::Job,
    summary: &RunSummary,
    m: &Measure,
) -> Result<(Vec<(String, f64)>, f64), CliError> {
    if matches!(m, Measure::Enki(_) | Measure::Gap(_)) {
        let k = study.arm_index(&job.setting).expect("a job of an arm");
        let spec = study.arms[k]
            .transfer
            .as_ref()
            .expect("checked by the loader");
        return transfer::values(spec, out, &job.id, summary, m);
    }
    let mut per_room = Vec::new();
    for r in &summary.rooms {
        let v = m.of_room(r).ok_or_else(|| {
            CliError::input(format!(
                "{}: run {} has no `{}` in room {}",
                study.source,
                job.key,
                m.column(),
                r.room
            ))
        })?;
        per_room.push((r.room.clone(), v));
    }
    let values: Vec<f64> = per_room.iter().map(|(_, v)| *v).collect();
    Ok((per_room, fuzzymotiv::statistics::mean(&values)))
}

/// Every run's values of the measures the hypotheses read: per room and over the rooms (their
/// mean), and the first and last generation's mean F (the measure [`FIRST_MEAN_F`] reads).
fn per_seed(study: &Study, out: &Path) -> Result<Vec<PerSeedRow>, CliError> {
    let mut measures: Vec<_> = Vec::new();
    for m in study.hypotheses.iter().filter_map(|h| h.measure()) {
        if m.per_room() && !measures.contains(m) {
            measures.push(m.clone());
        }
    }
    let arms = study.arms.len();
    let mut rows = Vec::new();
    for job in &study.plan.jobs {
        let base_seed = study.base_seeds[job.index / (arms * study.seeds)];
        let summary: RunSummary = read_json(&out.join("jobs").join(&job.id).join("summary.json"))?;
        let row = |measure: String, room: &str, value: f64| PerSeedRow {
            base_seed,
            replicate: job.replicate,
            seed: job.seed,
            arm: job.setting.clone(),
            measure,
            room: room.to_string(),
            value,
        };
        for m in &measures {
            let (per_room, over) = room_values(study, out, job, &summary, m)?;
            for (room, v) in &per_room {
                rows.push(row(m.column(), room, *v));
            }
            rows.push(row(m.column(), "", over));
        }
        let mean_f = |f: &dyn Fn(&crate::records::RunRecord) -> f64| {
            let v: Vec<f64> = summary.runs.iter().map(f).collect();
            fuzzymotiv::statistics::mean(&v)
        };
        rows.push(row(
            FIRST_MEAN_F.into(),
            "",
            mean_f(&|r| r.first_generation.mean),
        ));
        rows.push(row(
            LAST_MEAN_F.into(),
            "",
            mean_f(&|r| r.last_generation.mean),
        ));
    }
    Ok(rows)
}
