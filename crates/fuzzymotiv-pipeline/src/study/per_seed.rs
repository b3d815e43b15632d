//! A study's per-seed values (`per_seed.csv`): every run's value of each measure its
//! hypotheses read and `[study] measures` names, per room and over the rooms (their mean), and
//! the first and last generation's mean F. Most measures are columns of the run's records
//! (`summary.json`'s rooms); the end spread and the time to the goal are not, and are computed
//! from the run read back (`read_back_values`): its final population evaluated again and its
//! test runs run again, which gives the bits it had when it ran, so no run directory writes
//! more for them.

use std::path::Path;

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::statistics::mean;

use crate::files::error::CliError;
use crate::pipeline::progress::NoProgress;
use crate::pipeline::run_dir::read_back;
use crate::records::hypotheses::{FIRST_MEAN_F, LAST_MEAN_F, Measure, PerSeedRow};
use crate::records::{Finished, Job, RoomRow, RunRecord, RunSummary, read_json};
use crate::study::file::Study;
use crate::study::transfer;

/// The measures of `study` with a value per room, each once: its hypotheses', then those of
/// `[study] measures`.
pub fn room_measures(study: &Study) -> Vec<Measure> {
    let mut measures: Vec<Measure> = Vec::new();
    let named = (study.hypotheses.iter().filter_map(|h| h.measure())).chain(&study.measures);
    for m in named {
        if m.per_room() && !measures.contains(m) {
            measures.push(m.clone());
        }
    }
    measures
}

/// Every run's values (plan order) of the measures of [`room_measures`], then its first and
/// last generation's mean F; the runs are those of `out/jobs/`.
pub fn per_seed(study: &Study, out: &Path) -> Result<Vec<PerSeedRow>, CliError> {
    let measures = room_measures(study);
    let read_back: Vec<Measure> = measures.iter().filter(|m| m.read_back()).cloned().collect();
    let arms = study.arms.len();
    let mut rows = Vec::new();
    for job in &study.plan.jobs {
        let base_seed = study.base_seeds[job.index / (arms * study.seeds)];
        let dir = out.join("jobs").join(&job.id);
        let summary: RunSummary = read_json(&dir.join("summary.json"))?;
        let row = |measure: String, room: &str, value: f64| PerSeedRow {
            base_seed,
            replicate: job.replicate,
            seed: job.seed,
            arm: job.setting.clone(),
            measure,
            room: room.to_string(),
            value,
        };
        let mut from_runs = read_back_values(study, job, &dir, &read_back)?.into_iter();
        for m in &measures {
            if matches!(m, Measure::Enki(_) | Measure::Gap(_)) {
                let (per_room, over) = transferred(study, out, job, &summary, m)?;
                for (room, v) in &per_room {
                    rows.push(row(m.column(), room, *v));
                }
                rows.push(row(m.column(), "", over));
                continue;
            }
            let per_room = if m.read_back() {
                from_runs.next().expect("one per read-back measure")
            } else {
                of_rooms(study, job, m, &summary.rooms)?
            };
            for (r, v) in summary.rooms.iter().zip(&per_room) {
                rows.push(row(m.column(), &r.room, *v));
            }
            rows.push(row(m.column(), "", mean(&per_room)));
        }
        let mean_f = |f: &dyn Fn(&RunRecord) -> f64| {
            let v: Vec<f64> = summary.runs.iter().map(f).collect();
            mean(&v)
        };
        let first = mean_f(&|r| r.first_generation.mean);
        rows.push(row(FIRST_MEAN_F.into(), "", first));
        let last = mean_f(&|r| r.last_generation.mean);
        rows.push(row(LAST_MEAN_F.into(), "", last));
    }
    Ok(rows)
}

/// A measure of the run's robots transferred to Enki (`Measure::Enki`, `Measure::Gap`), per
/// room it was transferred in and over those rooms ([`transfer::values`]).
fn transferred(
    study: &Study,
    out: &Path,
    job: &Job,
    summary: &RunSummary,
    m: &Measure,
) -> Result<(Vec<(String, f64)>, f64), CliError> {
    let k = study.arm_index(&job.setting).expect("a job of an arm");
    let spec = (study.arms[k].transfer.as_ref()).expect("checked by the loader");
    transfer::values(spec, out, &job.id, summary, m)
}

/// Measure `m` in each room of a run's records.
fn of_rooms(
    study: &Study,
    job: &Job,
    m: &Measure,
    rooms: &[RoomRow],
) -> Result<Vec<f64>, CliError> {
    (rooms.iter())
        .map(|r| {
            m.of_room(r).ok_or_else(|| {
                CliError::input(format!(
                    "{}: run {} has no `{}` in room {}",
                    study.source,
                    job.key,
                    m.column(),
                    r.room
                ))
            })
        })
        .collect()
}

/// The values per room of the read-back measures `wanted` of the run in `dir` (none read back
/// when `wanted` is empty).
fn read_back_values(
    study: &Study,
    job: &Job,
    dir: &Path,
    wanted: &[Measure],
) -> Result<Vec<Vec<f64>>, CliError> {
    if wanted.is_empty() {
        return Ok(Vec::new());
    }
    let loaded = study.plan.load_job(job)?;
    let exp = &loaded.experiment;
    let done = read_back(exp, dir, &NoProgress)?;
    (wanted.iter())
        .map(|m| match m {
            Measure::EndSpread => exp.end_spreads(&done.outcome).map_err(|e| {
                CliError::input(format!(
                    "{}: run {}'s best genome does not fit its network: {e}",
                    study.source, job.key
                ))
            }),
            Measure::TimeToGoal => Ok(time_to_goal(exp, &done)),
            other => unreachable!("{} is in the run's records", other.column()),
        })
        .collect()
}

/// Per room, the mean step at which the test runs of the robot standing for it completed
/// their mission, T (the trial's steps) for a test run that never did.
pub fn time_to_goal(exp: &Experiment, done: &Finished) -> Vec<f64> {
    let never = exp.trial_params().steps();
    (0..done.rows.len())
        .map(|r| {
            let tests = &done.outcome.aem_for_room(r).rooms[r].tests;
            let steps: Vec<f64> = (tests.iter())
                .map(|t| t.terms.mission.and_then(|m| m.done_at).unwrap_or(never) as f64)
                .collect();
            mean(&steps)
        })
        .collect()
}
