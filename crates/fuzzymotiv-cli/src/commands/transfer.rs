//! `fuzzymotiv transfer`: a run's evolved controller driven in Enki, an independent simulator
//! ([`fuzzymotiv_pipeline::pipeline::transfer`]): one robot log per test run, the trial's terms and
//! the study's measures computed from each log by the simulator's own code, beside the run's
//! own test runs.

use std::path::PathBuf;

use crate::console::{note, outln};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::pipeline::transfer::{TransferRequest, transfer};

/// Arguments of `fuzzymotiv transfer`.
#[derive(clap::Args)]
pub struct TransferArgs {
    /// A run directory (its best_genome.json and config.resolved.toml) of a khepera, epuck2 or
    /// thymio2 robot.
    #[arg(value_name = "RUN_DIR")]
    pub run: PathBuf,
    /// The room to build in Enki: a room of the run, by name.
    #[arg(long, value_name = "NAME")]
    pub room: String,
    /// Test runs in Enki (Enki seeds SEED, SEED + 1, …).
    #[arg(long, value_name = "N", value_parser = crate::args::whole_number)]
    pub runs: usize,
    /// The directory to write run-K.csv (one robot log per test run), test_runs.csv (the
    /// run's test_runs.csv columns), measures.csv (both worlds' measures) and transfer.md.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Enki's base seed (its IR and wheel noise) [default: the run's seed].
    #[arg(long, allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_seed)]
    pub seed: Option<u64>,
    /// Replace existing files of these names that hold something else.
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv transfer`.
pub fn transfer_command(args: TransferArgs) -> Result<(), CliError> {
    let done = transfer(&TransferRequest {
        run: &args.run,
        room: &args.room,
        runs: args.runs,
        out: &args.out,
        seed: args.seed,
        force: args.force,
    })?;
    for n in &done.notes {
        note!("note: {n}");
    }
    if done.unchanged {
        note!(
            "{} already holds these files; nothing to do",
            args.out.display()
        );
    } else {
        note!("wrote {}", args.out.display());
    }
    outln!("{}", done.comparison)
}
