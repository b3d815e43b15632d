//! A study's transfers: the evolved robots of an arm with a `transfer` table measured in Enki
//! by `fuzzymotiv transfer` ([`crate::pipeline::transfer::transfer`]), each run in each of its
//! rooms into `OUT/transfer/JOB/ROOM/` (kept once there: a study resumes), and the
//! [`Measure::Enki`] and [`Measure::Gap`] values read back from their `measures.csv`.

use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::pipeline::transfer::{MeasureRow, TransferRequest, transfer};
use crate::records::hypotheses::{Measure, TransferSpec};
use crate::records::{RoomRow, RunSummary, read_csv};
use crate::study::file::Study;
use crate::study::progress::StudyProgress;

/// The directory of job `id`'s transfer to `room`.
pub fn transfer_dir(out: &Path, id: &str, room: &str) -> PathBuf {
    out.join("transfer").join(id).join(room)
}

/// The rooms a transfer covers: those it names, else every room of the run.
fn rooms_of(spec: &TransferSpec, summary: &RunSummary) -> Vec<String> {
    if spec.rooms.is_empty() {
        summary.rooms.iter().map(|r| r.room.clone()).collect()
    } else {
        spec.rooms.clone()
    }
}

/// Every transfer of the study not yet made (each run of a transferring arm, in each of its
/// rooms), in plan order, each announced to `progress`; how many were made.
pub fn transfer_runs(
    study: &Study,
    out: &Path,
    progress: &dyn StudyProgress,
) -> Result<usize, CliError> {
    let mut todo = Vec::new();
    for job in &study.plan.jobs {
        let k = study.arm_index(&job.setting).expect("a job of an arm");
        let Some(spec) = &study.arms[k].transfer else {
            continue;
        };
        let run = out.join("jobs").join(&job.id);
        let summary: RunSummary = crate::records::read_json(&run.join("summary.json"))?;
        for room in rooms_of(spec, &summary) {
            if !transfer_dir(out, &job.id, &room)
                .join("measures.csv")
                .is_file()
            {
                todo.push((job, spec, room));
            }
        }
    }
    for (done, (job, spec, room)) in todo.iter().enumerate() {
        progress.transferring(done, todo.len(), &job.key, room);
        transfer(&TransferRequest {
            run: &out.join("jobs").join(&job.id),
            room,
            runs: spec.runs,
            out: &transfer_dir(out, &job.id, room),
            seed: None,
            force: true,
        })
        .map_err(|e| {
            let message = format!("{}: run {}, room {room}: {e}", study.source, job.key);
            if e.is_input() {
                CliError::input(message)
            } else {
                CliError::runtime(message)
            }
        })?;
    }
    Ok(todo.len())
}

/// The mean over `world`'s test runs of `m` (a transferable measure) in `rows`; for the
/// simulator's recognition, which a run directory's test runs may not record, the run's own
/// (`summary.json`'s room row).
fn world_mean(
    rows: &[MeasureRow],
    world: &str,
    m: &Measure,
    room: Option<&RoomRow>,
    path: &Path,
) -> Result<f64, CliError> {
    let mut values = Vec::new();
    for r in rows.iter().filter(|r| r.world == world) {
        let v = match m {
            Measure::Exploration => Some(r.exploration_pct),
            Measure::Homing => Some(r.homing_pct),
            Measure::Battery => Some(r.battery_pct),
            _ => r.recognition_pct,
        };
        values.push(v);
    }
    let missing = values.is_empty() || values.iter().any(Option::is_none);
    if missing
        && world == "fuzzymotiv"
        && *m == Measure::Recognition
        && let Some(v) = room.and_then(|r| r.recognition_pct)
    {
        return Ok(v);
    }
    if missing {
        return Err(CliError::input(format!(
            "{}: no `{}` for every {world} test run",
            path.display(),
            m.column()
        )));
    }
    let values: Vec<f64> = values.into_iter().flatten().collect();
    Ok(fuzzymotiv::statistics::mean(&values))
}

/// A transferred measure of job `id` (its run's `summary`): per room of its transfer, and over
/// them: an Enki measure's mean over the rooms, a gap's |Enki − fuzzymotiv| of the two
/// worlds' means over the rooms (as `transfer_study pair` takes a seed's gap).
pub fn values(
    spec: &TransferSpec,
    out: &Path,
    id: &str,
    summary: &RunSummary,
    m: &Measure,
) -> Result<(Vec<(String, f64)>, f64), CliError> {
    let (inner, gap) = match m {
        Measure::Enki(inner) => (inner.as_ref(), false),
        Measure::Gap(inner) => (inner.as_ref(), true),
        _ => unreachable!("a transferred measure"),
    };
    let (mut enki, mut sim, mut per_room) = (Vec::new(), Vec::new(), Vec::new());
    for room in rooms_of(spec, summary) {
        let path = transfer_dir(out, id, &room).join("measures.csv");
        let rows: Vec<MeasureRow> = read_csv(&path)?;
        let row = summary.rooms.iter().find(|r| r.room == room);
        let e = world_mean(&rows, "enki", inner, row, &path)?;
        let s = world_mean(&rows, "fuzzymotiv", inner, row, &path)?;
        per_room.push((room, if gap { (e - s).abs() } else { e }));
        enki.push(e);
        sim.push(s);
    }
    let mean = fuzzymotiv::statistics::mean;
    let over = if gap {
        (mean(&enki) - mean(&sim)).abs()
    } else {
        mean(&enki)
    };
    Ok((per_room, over))
}
