//! The `fuzzymotiv` command line as a library: the binary (`main.rs`) parses arguments and
//! calls these modules; the Python bindings (`python/`) call the same code to load configs and
//! write run directories.

pub mod bench;
pub mod error;
pub mod files;
pub mod inputs;
pub mod png;
pub mod progress;
pub mod replay;
pub mod report;
pub mod reproduce;
pub mod run;
pub mod svg;
pub mod sweep;
