//! `fuzzymotiv robustness`: a run's best robot under the perturbations a real robot brings
//! (paired streams), F and behaviour per perturbation with 95 % intervals, as CSV, Markdown and
//! a figure ([`fuzzymotiv_pipeline::records::robustness::robustness_of_run`] over
//! [`fuzzymotiv::experiment::Experiment::robustness`]).

use std::path::PathBuf;

use crate::console::{note, outln};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::FilesState;
use fuzzymotiv_pipeline::pipeline::robustness::robustness_into;

use crate::png::rasteriser;

/// Arguments of `fuzzymotiv robustness`.
#[derive(clap::Args)]
pub struct RobustnessArgs {
    /// A run directory (its best_genome.json and config.resolved.toml).
    #[arg(value_name = "RUN_DIR")]
    pub run: PathBuf,
    /// The directory to write robustness.csv, robustness.md and robustness.svg into (created
    /// if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Trials per room and perturbation (the same streams under every perturbation).
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u32).range(2..=10_000))]
    pub trials: u32,
    /// Also write robustness.png beside robustness.svg.
    #[arg(long)]
    pub png: bool,
    /// Replace existing files of these names that hold something else.
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv robustness`.
pub fn robustness(args: RobustnessArgs) -> Result<(), CliError> {
    let png = rasteriser(args.png);
    let done = robustness_into(&args.run, &args.out, args.trials as usize, png, args.force)?;
    if done.state == FilesState::Same {
        note!(
            "{} already holds these files; nothing to do",
            args.out.display()
        );
    }
    note!(
        "{} perturbations × {} trials per room",
        done.perturbations,
        args.trials
    );
    outln!("{}", done.md)
}
