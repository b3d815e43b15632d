//! Options shared by the commands that write an output directory (`run`, `reproduce`), and
//! the value parser of plain counts ([`whole_number`]).

use std::path::PathBuf;

/// `--out`, `--force`, `--quiet` and `--seed`, declared once (`#[command(flatten)]`); each
/// command words the help of `--out`, `--force` and `--seed` for itself (`mut_arg`).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct OutputArgs {
    /// Output directory.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace the results in --out and start over.
    #[arg(long)]
    pub force: bool,
    /// No progress lines on stderr.
    #[arg(long, short)]
    pub quiet: bool,
    /// Base seed: a whole number from 0 to 2^53 − 1.
    #[arg(long, allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_seed)]
    pub seed: Option<u64>,
}

/// A whole number ≥ 0 (a clap value parser for counts and indices without a fixed upper
/// bound): a negative or non-numeric value gets a message saying so, not clap's "invalid
/// digit found in string".
pub fn whole_number(text: &str) -> Result<usize, String> {
    match text.trim().parse::<i128>() {
        Ok(n) => usize::try_from(n).map_err(|_| {
            if n < 0 {
                format!("must be a whole number ≥ 0, got {n}")
            } else {
                format!("must be a whole number from 0 to {}, got {n}", usize::MAX)
            }
        }),
        Err(_) => Err(format!("must be a whole number ≥ 0, got `{text}`")),
    }
}
