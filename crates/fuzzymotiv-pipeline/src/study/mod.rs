//! Studies of one's own (`fuzzymotiv study STUDY.toml`): a study file's arms (any config,
//! robot or motivations, with overrides), paired seeds (one base seed or several) and typed
//! hypotheses ([`mod@file`]); its runs as a sweep plan's jobs, sharded or not, and its analysis
//! written once they are all there ([`run`]), the progress a front polls ([`counter`]); the analysis itself, pure ([`analysis`]). The
//! records are `fuzzymotiv_records::records::hypotheses`'s, the report and forest plot the
//! render crate's `hypotheses`.

pub mod analysis;
pub mod counter;
pub mod file;
pub mod run;

pub use counter::StudyCounter;
pub use file::{STUDY_FILE, Study};
pub use run::{StudyOptions, StudyOutcome, StudyProgress, parse_shard, run_study};
