//! The `fuzzymotiv` command line as a library: the binary (`main.rs`) parses arguments and
//! calls these modules; the Python bindings (`python/`) call the same code to load configs and
//! write run directories.

//!
//! Layers, each using only the ones below it (`tests/layers.rs` checks that no module imports
//! one that imports it back):
//!
//! - commands: `run`, `reproduce`, `sweep` (with `plan` and `merge`), `replay`, `bench`;
//! - the shared pipeline: `pipeline` (evolve with checkpoints, model rooms, write a run
//!   directory; run a sweep's jobs), `sweep_plan`, `sweep_merge`, `checkpoint`, `args`;
//! - rendering, from records only: `report`, `tables`, `study` (the paper's settings, the
//!   statistics over seeds and the claims), `svg`, `png`, `progress`;
//! - the files: `records` (the output model), `files`, `inputs`, `error`.

pub mod args;
pub mod bench;
pub mod checkpoint;
pub mod console;
pub mod error;
pub mod files;
pub mod inputs;
pub mod pipeline;
pub mod png;
pub mod progress;
pub mod records;
pub mod replay;
pub mod report;
pub mod reproduce;
pub mod run;
pub mod study;
pub mod svg;
pub mod sweep;
pub mod sweep_merge;
pub mod sweep_plan;
pub mod tables;
