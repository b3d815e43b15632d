//! The files of fuzzymotiv, shared by the `fuzzymotiv` command line and the Python bindings:
//! reading configs and rooms, the output guard every writer goes through, the records written
//! and read back, tables, SVG figures and the report page, and the pipeline that evolves with
//! checkpoints and writes a run directory (or runs a sweep's jobs).
//!
//! No terminal front end is compiled in (no clap, indicatif or resvg): progress is reported
//! through [`pipeline::progress`] ([`pipeline::progress::NoProgress`] shows nothing), and PNG
//! figures are drawn by a [`render::figures::Rasterise`] the caller passes, or not at all.
//!
//! Layers, each using only itself and the ones below it (`crates/fuzzymotiv-cli/tests/layers.rs`
//! checks the order and that no modules import each other in a circle):
//!
//! - [`pipeline`]: a run directory (evolve with checkpoints, model the rooms, write it, read it
//!   back), a sweep's plan, jobs and merge, runs side by side, the progress it reports;
//! - [`render`]: from records only: tables, the paper's study and its statistics, SVG figures,
//!   the report page;
//! - [`records`]: the output model (one serde type per file) and the checkpoint;
//! - [`files`]: the output guard, config and room loading, the error and the terminal macros.

#![warn(missing_docs)]

pub mod files;
pub mod pipeline;
pub mod records;
pub mod render;
