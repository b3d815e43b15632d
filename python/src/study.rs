//! Studies of one's own from Python (`fuzzymotiv.study`): a study file or its text checked and
//! run by the library's study pipeline (`fuzzymotiv_pipeline::study`, what `fuzzymotiv study` runs),
//! in a worker thread while the Python thread reports progress (runs done of the total) and
//! watches for Ctrl-C, which stops every run at its next generation (`RunProgress::stop`): the
//! same call again resumes the study from its runs' checkpoints.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::study::{
    Study, StudyCounter, StudyOptions, StudyOutcome, parse_shard, run_study,
};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

use crate::{config_err, py_err, thread_pool};

/// The source name of a study given as text (a dict in Python), in error messages.
const TEXT_SOURCE: &str = "(study dict)";

/// What the worker tells the Python thread, and the Python thread the worker: the study's
/// progress (runs done of the selection's; Ctrl-C or a failing progress callback stop every
/// run at its next generation), and whether the worker is done.
#[derive(Default)]
struct Shared {
    counter: StudyCounter,
    finished: AtomicBool,
}

/// `folder` made absolute (the arms' config files are relative to it).
fn absolute(folder: &Path) -> Result<PathBuf, CliError> {
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    std::path::absolute(folder).map_err(|e| fuzzymotiv_pipeline::files::guard::io_err(folder, e))
}

/// The study file `path`, or the study `text` whose config files are relative to `base_dir`
/// (the working directory by default), checked as `fuzzymotiv study` checks it.
fn load(path: Option<PathBuf>, text: Option<String>, base_dir: Option<PathBuf>) -> PyResult<Study> {
    let study = match (path, text) {
        (Some(p), _) => Study::load(&p),
        (None, Some(t)) => absolute(base_dir.as_deref().unwrap_or(Path::new("")))
            .and_then(|dir| Study::parse_str(&t, TEXT_SOURCE, &dir)),
        (None, None) => Err(CliError::input("study: give a study file or a dict")),
    };
    study.map_err(config_err)
}

/// Runs a study as `fuzzymotiv study FILE --out OUT` does (its shard `"K/N"`, if given) and
/// returns `(analysed, done, total)`: whether the analysis is written (every run finished),
/// and how many of the study's runs are finished, of how many. `progress(done, total)` (runs
/// of this call's selection: the shard's) is called from this thread whenever a run finishes; Ctrl-C or an error in it stop the runs at their next
/// generation and are raised; the same call again resumes.
#[pyfunction]
#[pyo3(signature = (out, path=None, text=None, base_dir=None, threads=None, force=false, shard=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn study_run(
    py: Python<'_>,
    out: PathBuf,
    path: Option<PathBuf>,
    text: Option<String>,
    base_dir: Option<PathBuf>,
    threads: Option<Bound<'_, PyAny>>,
    force: bool,
    shard: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(bool, usize, usize)> {
    let pool = thread_pool(threads.as_ref())?;
    let shard = shard
        .as_deref()
        .map(parse_shard)
        .transpose()
        .map_err(py_err)?;
    let study = py.detach(|| load(path, text, base_dir))?;
    crate::warn_notes(&study.plan.notes)?;
    let planned = study.plan.jobs.len();
    let options = StudyOptions {
        out,
        threads: None,
        force,
        shard,
    };
    let shared = Shared::default();
    let error: Mutex<Option<PyErr>> = Mutex::new(None);
    let result = std::thread::scope(|s| {
        let worker = s.spawn(|| {
            let body = || run_study(&study, &options, &shared.counter);
            let r = match &pool {
                Some(p) => p.install(body),
                None => body(),
            };
            shared.finished.store(true, Ordering::SeqCst);
            r
        });
        watch(py, &shared, progress.as_ref(), &error);
        worker.join()
    });
    if let Some(e) = error.lock().expect("not poisoned").take() {
        return Err(e);
    }
    let result = result.map_err(|_| PyRuntimeError::new_err("fuzzymotiv panicked (a bug)"))?;
    crate::warn_notes(&shared.counter.notes())?;
    match result.map_err(py_err)? {
        StudyOutcome::Analysed(_) => Ok((true, planned, planned)),
        StudyOutcome::Waiting { done, total } => Ok((false, done, total)),
    }
}

/// The Python thread while the study runs: every 50 ms (without the GIL in between) it calls
/// `progress` when more runs are done and checks for Ctrl-C; the first error of either stops
/// the runs and is kept in `error`. Once the worker is done, both are checked a last time.
fn watch(
    py: Python<'_>,
    shared: &Shared,
    progress: Option<&Py<PyAny>>,
    error: &Mutex<Option<PyErr>>,
) {
    let mut reported = None;
    loop {
        let finished = shared.finished.load(Ordering::SeqCst);
        let counts = (shared.counter.done(), shared.counter.total());
        let mut failed = None;
        if let Some(cb) = progress
            && counts.1 > 0
            && reported != Some(counts)
        {
            reported = Some(counts);
            failed = cb.call1(py, counts).err();
        }
        if failed.is_none() {
            failed = py.check_signals().err();
        }
        if let Some(e) = failed {
            shared.counter.stop();
            error.lock().expect("not poisoned").get_or_insert(e);
        }
        if finished {
            break;
        }
        py.detach(|| {
            for _ in 0..50 {
                if shared.finished.load(Ordering::SeqCst) {
                    break;
                }
                std::thread::sleep(Duration::from_millis(1));
            }
        });
    }
}
