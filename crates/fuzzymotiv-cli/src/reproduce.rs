//! `fuzzymotiv reproduce`: the paper's study in one command.

use crate::error::CliError;

/// Arguments of `fuzzymotiv reproduce`.
#[derive(clap::Args)]
pub struct ReproduceArgs {}

/// Entry point.
pub fn reproduce(_args: ReproduceArgs) -> Result<(), CliError> {
    Err(CliError::input("reproduce: not built yet"))
}
