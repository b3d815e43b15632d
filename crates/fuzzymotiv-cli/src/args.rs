//! Options shared by the commands that write an output directory (`run`, `reproduce`).

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
    #[arg(long, allow_hyphen_values = true, value_parser = fuzzymotiv_io::files::inputs::parse_seed)]
    pub seed: Option<u64>,
}
