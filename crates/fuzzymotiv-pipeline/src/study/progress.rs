//! What a study reports while it runs ([`StudyProgress`]): its runs' progress (as a sweep's
//! jobs'), the transfers to another world, the analysis waiting for other shards or written.

use std::path::Path;

use crate::pipeline::progress::SweepProgress;
use crate::records::hypotheses::ClaimRow;

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
