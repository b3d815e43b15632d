//! The progress of a study that a front polls from another thread ([`StudyCounter`]): runs
//! finished of the selection's, and a stop flag every run watches at its next generation. The
//! lab's studies and Python's `fuzzymotiv.study` run a study on a worker thread and read it from
//! theirs; the command line shows its own progress bars instead.

use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use fuzzymotiv::experiment::Experiment;

use crate::files::notes::{NoteList, Notes};
use crate::pipeline::progress::{JobsSummary, RunProgress, StopOnFlag, SweepProgress};
use crate::records::Job;
use crate::records::hypotheses::ClaimRow;
use crate::study::StudyProgress;

/// Runs finished and selected, counted as a study runs, and the flag that stops its runs: a
/// [`StudyProgress`] that shows nothing, read from any thread.
#[derive(Debug, Default)]
pub struct StudyCounter {
    done: AtomicUsize,
    total: AtomicUsize,
    stop: AtomicBool,
    /// The pipeline's notes (what `force` replaced, a job waiting for another worker), for
    /// the front to show.
    notes: NoteList,
    /// How the runs went, once the last finished.
    summary: std::sync::Mutex<Option<JobsSummary>>,
}

impl StudyCounter {
    /// Runs of the selection finished: before this call (found on disk) or in it.
    pub fn done(&self) -> usize {
        self.done.load(Ordering::SeqCst)
    }

    /// Runs of the selection (the study's, or its shard's); 0 until the runs begin.
    pub fn total(&self) -> usize {
        self.total.load(Ordering::SeqCst)
    }

    /// Stops every run at its next generation (its checkpoint stays: the study resumes).
    pub fn stop(&self) {
        self.stop.store(true, Ordering::SeqCst);
    }

    /// The notes so far, in order (the lab shows them on its page, Python warns).
    pub fn notes(&self) -> Vec<String> {
        self.notes.lines()
    }

    /// How the runs went (how many ran, were already done, selected, planned), once the last
    /// finished: the lab shows it with the notes; Python returns the counts instead.
    pub fn summary(&self) -> Option<JobsSummary> {
        *self.summary.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Whether [`StudyCounter::stop`] was called.
    pub fn stopped(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }
}

impl Notes for StudyCounter {
    fn note(&self, line: &str) {
        self.notes.note(line);
    }
}

impl SweepProgress for StudyCounter {
    fn begin(&self, selected: usize, skipped: usize) {
        self.total.store(selected, Ordering::SeqCst);
        self.done.store(skipped, Ordering::SeqCst);
    }
    fn job(&self, _job: &Job, _nth: usize, _exp: &Experiment) -> Box<dyn RunProgress + '_> {
        Box::new(StopOnFlag(&self.stop))
    }
    fn job_done(&self) {
        self.done.fetch_add(1, Ordering::SeqCst);
    }
    fn end(&self, summary: &JobsSummary) {
        *self.summary.lock().unwrap_or_else(|e| e.into_inner()) = Some(*summary);
    }
}

impl StudyProgress for StudyCounter {
    fn waiting(&self, _done: usize, _total: usize) {}
    fn analysed(&self, _out: &Path, _claims: &[ClaimRow]) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The runs found on disk count as done when the runs begin, each finished run adds one,
    /// and a stop reaches every run's progress.
    #[test]
    fn a_study_counter_counts_the_runs_found_and_finished_and_stops_its_runs() {
        let c = StudyCounter::default();
        assert_eq!((c.done(), c.total()), (0, 0));
        c.begin(6, 2);
        c.job_done();
        assert_eq!((c.done(), c.total()), (3, 6));
        let exp = crate::files::inputs::load_config(None, &[], None)
            .unwrap()
            .experiment;
        let job = Job {
            index: 0,
            id: "j".into(),
            key: "rep=0".into(),
            setting: String::new(),
            replicate: 0,
            seed: 1,
            overrides: Vec::new(),
            model: fuzzymotiv::MODEL_VERSION,
        };
        let run = c.job(&job, 0, &exp);
        assert!(!run.stop());
        c.stop();
        assert!(run.stop() && c.stopped());
    }
}
