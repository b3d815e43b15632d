//! `fuzzymotiv run`: evolve, model the rooms, write the run directory (what to run is
//! [`fuzzymotiv_pipeline::pipeline::run_target`]'s, the run [`fuzzymotiv_pipeline::pipeline::run_dir`]'s;
//! this front parses, shows progress and prints).

use std::path::PathBuf;

use crate::console::{Stderr, note};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::pipeline::lanes::set_threads;
use fuzzymotiv_pipeline::pipeline::run_dir::{execute, start_line};
use fuzzymotiv_pipeline::pipeline::run_target::{RunRequest, RunTarget, run_target};
use fuzzymotiv_pipeline::render::tables::table_markdown;

use crate::args::OutputArgs;
use crate::png::{add_pngs, rasteriser};
use crate::progress::Progress;

/// Arguments of `fuzzymotiv run`.
#[derive(clap::Args)]
#[command(
    mut_arg("out", |a| a.help("Output directory [default: runs/NAME]. The same command again finishes an unfinished run there or says it is done; another run's results there are kept unless --force")),
    mut_arg("force", |a| a.help("Replace the results of another run in --out, or discard an unfinished one (its checkpoint), and start over")),
    mut_arg("seed", |a| a.help("Base seed (overrides `seed` in the config): a whole number from 0 to 2^53 − 1")),
)]
pub struct RunArgs {
    /// Experiment config (TOML; every key is optional, defaults in docs/model.md). Required, unless
    /// --resume DIR is given instead.
    #[arg(value_name = "CONFIG", required_unless_present_any = ["resume", "continue_from"])]
    pub config: Option<PathBuf>,
    /// Continue a killed run: DIR is the run's output directory (its `DIR.partial/` holds the
    /// checkpoint and resolved config). The result equals an uninterrupted run.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["config", "out", "seed", "sets", "force"])]
    pub resume: Option<PathBuf>,
    /// Continue a finished run DIR to more generations (--generations N, the total) into a new
    /// directory (--out NEW); DIR is only read. The result equals a fresh N-generation run.
    #[arg(long = "continue", value_name = "DIR", requires_all = ["generations", "out"], conflicts_with_all = ["config", "resume", "seed", "sets"])]
    pub continue_from: Option<PathBuf>,
    /// With --continue: the total number of generations (more than DIR ran).
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "N",
        requires = "continue_from",
        value_parser = crate::args::whole_number
    )]
    pub generations: Option<usize>,
    /// --out, --force, --quiet, --seed.
    #[command(flatten)]
    pub output: OutputArgs,
    /// Worker threads, 1 to 256 [default: all cores]; results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_threads)]
    pub threads: Option<usize>,
    /// Override a config key, e.g. --set ga.population=20 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Also write a PNG beside every SVG figure.
    #[arg(long)]
    pub png: bool,
}

/// Entry point of `fuzzymotiv run`.
pub fn run(args: RunArgs) -> Result<(), CliError> {
    set_threads(args.threads)?;
    let target = run_target(
        &RunRequest {
            config: args.config.clone(),
            resume: args.resume.clone(),
            continue_from: args.continue_from.clone(),
            generations: args.generations,
            out: args.output.out.clone(),
            sets: args.sets.clone(),
            seed: args.output.seed,
            force: args.output.force,
        },
        &Stderr,
    )?;
    let (loaded, out, resume) = match target {
        RunTarget::Run {
            loaded,
            out,
            resume,
        } => (loaded, out, resume),
        RunTarget::Done { dir, note } => {
            note!("{note}");
            return if args.png { add_pngs(&dir) } else { Ok(()) };
        }
    };
    let progress = Progress::new(&loaded.experiment, 1, args.output.quiet).named(&format!(
        "{} seed {}",
        loaded.experiment.name(),
        loaded.experiment.seed()
    ));
    progress.note(&start_line(&loaded.experiment, &out));
    let done = execute(&loaded, &out, &progress, resume, rasteriser(args.png))?;
    progress.finish();
    crate::console::out!("{}", table_markdown(&done.rows))?;
    note!("wrote {} ({:.1} s)", out.display(), done.wall_seconds);
    Ok(())
}
