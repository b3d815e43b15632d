//! The pipeline of fuzzymotiv, shared by the `fuzzymotiv` command line, the lab and the Python
//! bindings: the pipeline that evolves with checkpoints and writes a run directory (or runs a
//! sweep's jobs), over the records and the rendering, which it re-exports under their old
//! module names ([`files`], [`records`], [`render`]) so that one dependency gives the fronts all
//! three.
//!
//! No terminal front end is compiled in (no clap, indicatif or resvg): progress is reported
//! through [`pipeline::progress`] ([`pipeline::progress::NoProgress`] shows nothing), notes are
//! returned or handed to the caller's [`files::notes::Notes`] (nothing here prints, exits or
//! aborts), and PNG figures are drawn by a [`render::figures::Rasterise`] the caller passes, or
//! not at all.
//!
//! The crates, each using only the ones below it (Cargo enforces the order):
//!
//! - `fuzzymotiv-pipeline` ([`pipeline`]): a run directory (evolve with checkpoints, model the rooms,
//!   write it, read it back), a sweep's plan, jobs and merge, runs side by side, the progress it
//!   reports;
//! - `fuzzymotiv-render` ([`render`]): from records only: tables, the paper's study and its
//!   statistics, SVG figures, the report page, rollout frames and GIFs;
//! - `fuzzymotiv-records` ([`records`], [`files`]): the output model (one serde type per file)
//!   and the checkpoint; the output guard, config and room loading, the errors and the notes.

#![warn(missing_docs)]

pub mod pipeline;
pub mod study;

pub use fuzzymotiv_records::{files, records};
pub use fuzzymotiv_render as render;
