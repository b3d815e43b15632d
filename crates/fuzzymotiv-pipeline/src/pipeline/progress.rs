//! The progress the pipeline reports while it runs, and how it is shown is the caller's: the
//! command line draws a bar or plain lines on stderr (its `progress.rs`), the Python bindings
//! show nothing here ([`NoProgress`]) and report generations through their observer instead.
//! The notes a sweep's or a study's progress receives ([`Notes`]) are the pipeline's only
//! words to its user: it prints nothing itself.

use std::sync::atomic::{AtomicBool, Ordering};

use fuzzymotiv::experiment::Experiment;

use crate::files::notes::Notes;
use crate::records::Job;

/// Progress of one run (or of several, for a view that counts them together): what
/// [`run_dir`](super::run_dir) reports as it evolves, resumes and reads back.
pub trait RunProgress {
    /// A one-line note, e.g. that a run resumes from its checkpoint or was read back.
    fn note(&self, message: &str);
    /// `n` generations that were done before (a resume, a finished run read back).
    fn skip(&self, n: usize);
    /// Generation `g` (1-based) of `of` of the run labelled `run` finished with best F `best`.
    fn generation(&self, run: &str, g: usize, of: usize, best: f64);
    /// Whether the run should stop now (asked after every generation, once its checkpoint is
    /// saved): a front's cancel (Ctrl-C in Python, the lab's cancel button). A stopped run ends
    /// with an error and its staging directory resumes; by default a run never stops.
    fn stop(&self) -> bool {
        false
    }
}

/// Progress of a sweep's jobs: what [`run_jobs`](super::sweep_jobs::run_jobs) reports, its
/// notes included (`--force` replaced a sweep, a job waits for another worker, how many jobs
/// ran). Jobs run side by side, so it is shared between threads.
pub trait SweepProgress: Notes {
    /// `selected` jobs are selected, of which `skipped` were already done; the others run now.
    fn begin(&self, selected: usize, skipped: usize);
    /// The progress of `job`, the `nth` (1-based) of the selection, about to run `exp`.
    fn job(&self, job: &Job, nth: usize, exp: &Experiment) -> Box<dyn RunProgress + '_>;
    /// A job has finished.
    fn job_done(&self);
    /// The last job has finished: how the selection went (the command line notes it; a front
    /// that returns the counts itself need not).
    fn end(&self, summary: &JobsSummary);
}

/// How a sweep's selection went, once its last job has finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct JobsSummary {
    /// Jobs run by this call.
    pub ran: usize,
    /// Selected jobs already done (earlier calls, other workers).
    pub already_done: usize,
    /// Jobs in this selection (a shard, an index, or the plan).
    pub selected: usize,
    /// Jobs in the plan.
    pub planned: usize,
}

impl std::fmt::Display for JobsSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} jobs run, {} already done, {} in this selection, {} in the plan",
            self.ran, self.already_done, self.selected, self.planned
        )
    }
}

/// Progress that shows nothing, notes included.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Notes for NoProgress {
    fn note(&self, _line: &str) {}
}

impl RunProgress for NoProgress {
    fn note(&self, _message: &str) {}
    fn skip(&self, _n: usize) {}
    fn generation(&self, _run: &str, _g: usize, _of: usize, _best: f64) {}
}

impl SweepProgress for NoProgress {
    fn begin(&self, _selected: usize, _skipped: usize) {}
    fn job(&self, _job: &Job, _nth: usize, _exp: &Experiment) -> Box<dyn RunProgress + '_> {
        Box::new(NoProgress)
    }
    fn job_done(&self) {}
    fn end(&self, _summary: &JobsSummary) {}
}

/// A run's progress that shows nothing and stops the run once `flag` is set: a front that
/// reports whole runs itself and cancels them (the lab's Stop button, Ctrl-C in Python).
#[derive(Debug, Clone, Copy)]
pub struct StopOnFlag<'a>(pub &'a AtomicBool);

impl RunProgress for StopOnFlag<'_> {
    fn note(&self, _message: &str) {}
    fn skip(&self, _n: usize) {}
    fn generation(&self, _run: &str, _g: usize, _of: usize, _best: f64) {}
    fn stop(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}
