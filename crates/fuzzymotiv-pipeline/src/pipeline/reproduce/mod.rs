//! `reproduce`: the paper's study (docs/model.md §10) and the studies built on it, from the
//! library: [`ReproduceOptions`] say which study, where and at what size (plain data, no
//! command line), [`ReproduceProgress`] receives its progress, and [`reproduce`] runs it (resumable
//! through the output guard's staging directory) and returns what to show.
//!
//! One module per kind of study ([`StudyKind`]): [`paper`] (the paper's two settings and its
//! claims), [`ablation`], [`search_strength`], [`combination`], [`replication`], [`urgency`]
//! and [`orientation`]; [`runs`] loads, runs and stages the (setting, seed) runs they share,
//! [`variants`] runs the study once per variant of the model.

pub mod ablation;
pub mod combination;
pub mod orientation;
pub mod paper;
pub mod replication;
pub mod runs;
pub mod search_strength;
pub mod urgency;
pub mod variants;

use std::path::PathBuf;

use fuzzymotiv::experiment::Experiment;

use crate::files::error::CliError;
use crate::files::notes::Notes;
use crate::pipeline::lanes::set_threads;
use crate::pipeline::progress::{NoProgress, RunProgress, SweepProgress};
use crate::render::figures::Rasterise;

/// Which study [`reproduce`] runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StudyKind {
    /// The paper's study: high against low curiosity, the paper's claims.
    #[default]
    Paper,
    /// The orientation study (configs/orientation-study.toml), a built-in sweep.
    Orientation,
    /// The study with each new modelling choice switched back.
    Ablation,
    /// The study at GA populations 30, 60, 100 and 200.
    SearchStrength,
    /// The study under the paper's TSK and the two baselines of `[fitness] combine`.
    Combination,
    /// The study at two base seeds, and from how many seeds on their verdicts agree.
    Replication,
    /// The fetch mission at urgency weights 0, 0.1, 0.2 and 0.3.
    Urgency,
}

impl StudyKind {
    /// The default output directory of the study (`-quick` appended for a quick look, so that
    /// it never lands in the full study's directory).
    pub fn default_out(self, quick: bool) -> PathBuf {
        let base = match self {
            StudyKind::Paper => "results",
            StudyKind::Orientation => "results-orientation",
            StudyKind::Ablation => "results-ablation",
            StudyKind::SearchStrength => "results-search-strength",
            StudyKind::Combination => "results-combination",
            StudyKind::Replication => "results-replication",
            StudyKind::Urgency => "results-urgency",
        };
        PathBuf::from(if quick {
            format!("{base}-quick")
        } else {
            base.to_string()
        })
    }

    /// The kind of output its `identity.json` names (what makes two studies "the same").
    pub(crate) fn identity(self) -> &'static str {
        match self {
            StudyKind::Ablation => "ablation",
            StudyKind::SearchStrength => "search-strength",
            StudyKind::Combination => "combination",
            StudyKind::Replication => "replication",
            StudyKind::Urgency => "urgency",
            StudyKind::Paper | StudyKind::Orientation => "study",
        }
    }
}

/// What [`reproduce`] runs: plain data, filled by the command line from its arguments, or by
/// any other front.
#[derive(Debug, Clone, PartialEq)]
pub struct ReproduceOptions {
    /// The study.
    pub kind: StudyKind,
    /// The output directory ([`StudyKind::default_out`] for the usual one).
    pub out: PathBuf,
    /// Replace another study's results in `out` (or an unfinished one) and start over.
    pub force: bool,
    /// The base seed: the study's first seed is this seed, the others derive from it.
    pub seed: u64,
    /// Seeds per setting.
    pub seeds: u64,
    /// A fast look: GA 30 × 30 instead of the paper's 200 × 200.
    pub quick: bool,
    /// Worker threads (none: all cores); results do not depend on it.
    pub threads: Option<usize>,
    /// Config overrides of every setting (`KEY=VALUE`).
    pub sets: Vec<String>,
}

impl ReproduceOptions {
    /// The options of `kind` at the command line's defaults: base seed 1, twenty seeds, the
    /// full size, the default output directory, all cores, no overrides.
    pub fn new(kind: StudyKind) -> Self {
        Self {
            kind,
            out: kind.default_out(false),
            force: false,
            seed: 1,
            seeds: 20,
            quick: false,
            threads: None,
            sets: Vec::new(),
        }
    }
}

/// Progress of a study's runs: [`begin`](ReproduceProgress::begin) once with how many runs will
/// evolve, a view per run while it evolves ([`run`](ReproduceProgress::run); runs go on side by side,
/// so it is shared between threads), [`end`](ReproduceProgress::end) when the last is done. The
/// orientation study, a sweep, reports its jobs through [`jobs`](ReproduceProgress::jobs). The
/// study's notes (where it was written, that it resumes, its configs' notes) go to its
/// [`Notes`].
pub trait ReproduceProgress: Notes {
    /// `runs` runs of experiments like `exp` are about to evolve (some may be read back).
    fn begin(&self, exp: &Experiment, runs: usize);
    /// The progress of the run named `name` (e.g. `high-curiosity seed #03`), for as long as
    /// it evolves.
    fn run(&self, name: &str) -> Box<dyn RunProgress + '_>;
    /// The last run is done.
    fn end(&self);
    /// The progress of a sweep's jobs (the orientation study).
    fn jobs(&self) -> Box<dyn SweepProgress + '_>;
}

impl ReproduceProgress for NoProgress {
    fn begin(&self, _exp: &Experiment, _runs: usize) {}
    fn run(&self, _name: &str) -> Box<dyn RunProgress + '_> {
        Box::new(NoProgress)
    }
    fn end(&self) {}
    fn jobs(&self) -> Box<dyn SweepProgress + '_> {
        Box::new(NoProgress)
    }
}

/// What a study needs besides its options: where progress goes and how figures become PNGs
/// (none: SVG only).
#[derive(Clone, Copy)]
pub struct Front<'a> {
    /// Progress of the runs.
    pub progress: &'a dyn ReproduceProgress,
    /// Draws a PNG beside every SVG figure.
    pub png: Option<&'a dyn Rasterise>,
}

/// Runs the study of `options` into `options.out` and returns the text to show (its tables,
/// and the paper's claims one a line; the orientation study's merged table; empty when `out`
/// already held it), its notes said to `front.progress`. An unfinished study of the same configs resumes; another
/// study in `out` is replaced only with `force`; bad options are refused before anything is
/// written.
pub fn reproduce(options: &ReproduceOptions, front: Front<'_>) -> Result<String, CliError> {
    set_threads(options.threads)?;
    match options.kind {
        StudyKind::Paper => paper::paper(options, front),
        StudyKind::Orientation => orientation::orientation(options, front),
        StudyKind::Ablation => ablation::ablation(options, front),
        StudyKind::SearchStrength => search_strength::search_strength(options, front),
        StudyKind::Combination => combination::combination(options, front),
        StudyKind::Replication => replication::replication(options, front),
        StudyKind::Urgency => urgency::urgency(options, front),
    }
}
