//! Sweeps from Python (`fuzzymotiv.plan`, `run_job`, `sweep`): the CLI's own planning, job
//! running (under the job's lock) and merging of `fuzzymotiv-pipeline`, reached with plain values —
//! the sweep's text, its source and folder, a job's index and id — so that a job is a picklable
//! value any executor can ship to another process.

use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv_pipeline::files::bounded::read_input;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::notes::{NoteList, Notes};
use fuzzymotiv_pipeline::pipeline::progress::{
    JobsSummary, NoProgress, RunProgress, SweepProgress,
};
use fuzzymotiv_pipeline::pipeline::sweep_jobs::{prepare_sweep_dir, run_one_job};
use fuzzymotiv_pipeline::pipeline::sweep_merge::write_merge;
use fuzzymotiv_pipeline::pipeline::sweep_plan::{SWEEP_FILE, Sweep};
use fuzzymotiv_pipeline::records::Job;
use pyo3::prelude::*;

use crate::{config_err, py_err, warn_notes};

/// A sweep's progress from Python: nothing shown while it runs, its notes kept (then warned).
#[derive(Default)]
struct Noted(NoteList);

/// A note is shown at once, as a Python warning (re-taking the GIL the job's thread let go
/// of): a worker waiting for another's lock says so while it waits, as the CLI does. A
/// warning that cannot be shown now (an error filter) is kept and raised when the job returns.
impl Notes for Noted {
    fn note(&self, line: &str) {
        if warn_notes(&[line.to_string()]).is_err() {
            self.0.note(line);
        }
    }
}

impl SweepProgress for Noted {
    fn begin(&self, _selected: usize, _skipped: usize) {}
    fn job(&self, _job: &Job, _nth: usize, _exp: &Experiment) -> Box<dyn RunProgress + '_> {
        Box::new(NoProgress)
    }
    fn job_done(&self) {}
    /// Not a warning: `fm.sweep_run_job` and `fm.study` return what ran.
    fn end(&self, _summary: &JobsSummary) {}
}

/// The source name of a sweep given as text (a dict in Python), in error messages.
const TEXT_SOURCE: &str = "(sweep dict)";

/// `folder` made absolute (room files are relative to it, and a job may run in a process with
/// another working directory).
fn absolute(folder: &Path) -> Result<PathBuf, CliError> {
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    std::path::absolute(folder).map_err(|e| fuzzymotiv_pipeline::files::guard::io_err(folder, e))
}

/// A sweep file (`path`) or sweep text planned as `fuzzymotiv plan` plans it: `(text, source,
/// base_dir, plan_jsonl)`, the first three being what [`sweep_run_job`] needs to run a job.
#[pyfunction]
#[pyo3(signature = (path=None, text=None))]
pub fn sweep_plan(
    py: Python<'_>,
    path: Option<PathBuf>,
    text: Option<String>,
) -> PyResult<(String, String, String, String)> {
    py.detach(|| {
        let (text, source, base_dir) = match (path, text) {
            (Some(p), _) => {
                let text = read_input(&p, SWEEP_FILE)?;
                let dir = absolute(p.parent().unwrap_or(Path::new("")))?;
                (text, p.display().to_string(), dir)
            }
            (None, Some(t)) => (t, TEXT_SOURCE.to_string(), absolute(Path::new(""))?),
            (None, None) => return Err(CliError::input("plan: give a sweep file or a dict")),
        };
        let sweep = Sweep::parse_str(&text, &source, &base_dir)?;
        let dir = base_dir.display().to_string();
        Ok((text, source, dir, sweep.plan_jsonl(), sweep.notes))
    })
    .map_err(config_err)
    .and_then(|(text, source, dir, plan, notes)| {
        warn_notes(&notes)?;
        Ok((text, source, dir, plan))
    })
}

/// Runs job `index` (whose id must be `id`) of the sweep `text` into the sweep directory `out`
/// as `fuzzymotiv sweep --index INDEX` does, under the job's lock (waited for when `wait`):
/// `"ran"`, `"skipped"` (finished before) or `"running"` (locked, not waited for). The GIL is
/// released.
#[pyfunction]
#[pyo3(signature = (text, source, base_dir, index, id, out, wait=true))]
#[allow(clippy::too_many_arguments)]
pub fn sweep_run_job(
    py: Python<'_>,
    text: String,
    source: String,
    base_dir: PathBuf,
    index: usize,
    id: String,
    out: PathBuf,
    wait: bool,
) -> PyResult<&'static str> {
    let noted = Noted::default();
    let outcome = py.detach(|| {
        let sweep = Sweep::parse_str(&text, &source, &base_dir)?;
        match sweep.jobs.get(index) {
            Some(job) if job.id == id => {}
            _ => {
                return Err(CliError::input(format!(
                    "job {id} (index {index}) is not a job of {source} as it plans now ({} jobs): \
                     plan it again with fuzzymotiv.plan",
                    sweep.jobs.len()
                )));
            }
        }
        run_one_job(&sweep, &text, index, &out, wait, &noted).map(|o| o.as_str())
    })
    .map_err(py_err);
    warn_notes(&noted.0.take())?;
    outcome
}

/// Checks the sweep directory `out` for the sweep `text` and writes its plan, as `fuzzymotiv
/// sweep` does before its first job: another plan's sweep there is replaced only with `force`.
#[pyfunction]
#[pyo3(signature = (text, source, base_dir, out, force=false))]
pub fn sweep_prepare(
    py: Python<'_>,
    text: String,
    source: String,
    base_dir: PathBuf,
    out: PathBuf,
    force: bool,
) -> PyResult<()> {
    let sweep = Sweep::parse_str(&text, &source, &base_dir).map_err(config_err)?;
    // The directory's check: a refused output is an `OutputExistsError` (`py_err`).
    let notes = NoteList::default();
    py.detach(|| prepare_sweep_dir(&sweep, &text, &out, force, &notes).map(|_| ()))
        .map_err(py_err)?;
    warn_notes(&notes.take())
}

/// Merges the sweep directory `dir` as `fuzzymotiv merge` does (the same `results.csv`,
/// `aggregate.csv`, `aggregate.md`, `summary.svg`), printing nothing: `(markdown, jobs,
/// missing, rows)`.
#[pyfunction]
pub fn sweep_merge(py: Python<'_>, dir: PathBuf) -> PyResult<(String, usize, usize, usize)> {
    py.detach(|| write_merge(&dir))
        .map(|m| (m.markdown, m.jobs, m.missing, m.rows))
        .map_err(py_err)
}
