//! The records of fuzzymotiv, shared by the `fuzzymotiv` command line, the lab and the Python
//! bindings: reading configs and rooms, the output guard every writer goes through, a sweep
//! job's lock, the errors, and the records written and read back (one serde type per file, the
//! checkpoint).
//!
//! It knows no rendering and no pipeline: `fuzzymotiv-render` and `fuzzymotiv-pipeline` stand on it,
//! and Cargo keeps it so. Inside, two layers (`crates/fuzzymotiv-cli/tests/it/layers.rs` checks
//! that [`records`] may use [`files`] and not the other way round):
//!
//! - [`records`]: the output model (one serde type per file) and the checkpoint;
//! - [`files`]: the output guard, config and room loading, the errors and the notes a
//!   library returns instead of printing (it has no terminal: the fronts print).

#![warn(missing_docs)]

pub mod files;
pub mod records;
