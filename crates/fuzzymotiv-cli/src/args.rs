//! Options shared by the commands that write an output directory (`run`, `reproduce`).

use std::path::PathBuf;

/// `--out`, `--force`, `--quiet` and `--seed`, declared once (`#[command(flatten)]`).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct OutputArgs {
    /// Output directory [default: run: runs/NAME; reproduce: results, with --quick
    /// results-quick, with --orientation results-orientation(-quick), with --ablation
    /// results-ablation(-quick)]. The same command again finishes an unfinished run there or
    /// says it is done; other results there are kept unless --force.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace other results in --out, or discard an unfinished output (a run's checkpoint),
    /// and start over.
    #[arg(long)]
    pub force: bool,
    /// No progress lines on stderr.
    #[arg(long, short)]
    pub quiet: bool,
    /// Base seed, a whole number from 0 to 2^53 − 1 [run: default the config's `seed`;
    /// reproduce: default 1, the study's first seed, the others derive from it].
    #[arg(long, allow_hyphen_values = true, value_parser = crate::inputs::parse_seed)]
    pub seed: Option<u64>,
}
