//! Sweeps: `plan` expands a `[sweep]` into a stable list of jobs, `sweep` runs (a shard of)
//! them into `DIR/jobs/ID/`, `merge` builds the tables and plots.

use std::path::PathBuf;

use fuzzymotiv_pipeline::files::bounded::read_input;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::{FilesState, check_files, write_files};
use fuzzymotiv_pipeline::pipeline::lanes::set_threads;
use fuzzymotiv_pipeline::pipeline::sweep_jobs::run_jobs;
use fuzzymotiv_pipeline::pipeline::sweep_merge::merge_dir;
use fuzzymotiv_pipeline::pipeline::sweep_plan::{SWEEP_FILE, Sweep, select_jobs};
use fuzzymotiv_pipeline::render::figures::png_beside;

use crate::console::{Stderr, config_notes};
use crate::png::{Resvg, add_pngs};
use crate::progress::JobsProgress;

/// Arguments of `fuzzymotiv plan`.
#[derive(clap::Args)]
pub struct PlanArgs {
    /// Sweep file (a config with a `[sweep]` table).
    pub sweep: PathBuf,
    /// Print only the number of jobs (to size an array job).
    #[arg(long)]
    pub count: bool,
    /// Write the plan to this file instead of stdout (the same plan again changes nothing;
    /// another file there is kept unless --force).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace another --out file (only a regular file).
    #[arg(long, requires = "out")]
    pub force: bool,
}

/// Entry point of `fuzzymotiv plan`.
pub fn plan(args: PlanArgs) -> Result<(), CliError> {
    let sweep = Sweep::load(&args.sweep)?;
    config_notes(&sweep.notes);
    if args.count {
        crate::console::outln!("{}", sweep.jobs.len())?;
    } else if let Some(out) = args.out {
        let files = [(out, sweep.plan_jsonl().into_bytes())];
        if check_files(&files, "--out", args.force)? == FilesState::Write {
            write_files(&files)?;
        }
    } else {
        crate::console::out!("{}", sweep.plan_jsonl())?;
    }
    Ok(())
}

/// Arguments of `fuzzymotiv sweep`.
#[derive(clap::Args)]
pub struct SweepArgs {
    /// Sweep file (a config with a `[sweep]` table).
    pub sweep: PathBuf,
    /// Output directory; jobs go to DIR/jobs/ID/.
    #[arg(long)]
    pub out: PathBuf,
    /// Run shard I of N (0-based): the jobs whose index ≡ I mod N.
    #[arg(long, allow_hyphen_values = true, value_name = "I/N", conflicts_with_all = ["index", "index_from_env"])]
    pub shard: Option<String>,
    /// Run only job K (0-based plan index).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "index_from_env", value_parser = crate::args::whole_number)]
    pub index: Option<usize>,
    /// Read the job index from an environment variable, e.g. SLURM_ARRAY_TASK_ID,
    /// JOB_COMPLETION_INDEX (Kubernetes) or an HTCondor $(Process) passed in the environment.
    #[arg(long, value_name = "VAR")]
    pub index_from_env: Option<String>,
    /// Worker threads, 1 to 256 [default: all cores]; up to this many jobs run at once, sharing them;
    /// results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_threads)]
    pub threads: Option<usize>,
    /// No progress lines on stderr.
    #[arg(long, short)]
    pub quiet: bool,
    /// Replace the sweep (or other fuzzymotiv output) in --out and start over: the old sweep's
    /// own files and job folders are removed, never another file.
    #[arg(long)]
    pub force: bool,
}

/// The job index of `--index` or `--index-from-env VAR`.
fn index_of(args: &SweepArgs) -> Result<Option<usize>, CliError> {
    match (&args.index, &args.index_from_env) {
        (Some(i), _) => Ok(Some(*i)),
        (None, Some(var)) => {
            let v = std::env::var(var).map_err(|_| {
                CliError::input(format!("--index-from-env {var}: the variable is not set"))
            })?;
            let i = v.trim().parse().map_err(|_| {
                CliError::input(format!("--index-from-env {var}: `{v}` is not a job index"))
            })?;
            Ok(Some(i))
        }
        (None, None) => Ok(None),
    }
}

/// Entry point of `fuzzymotiv sweep`.
pub fn sweep(args: SweepArgs) -> Result<(), CliError> {
    set_threads(args.threads)?;
    let sweep = Sweep::load(&args.sweep)?;
    config_notes(&sweep.notes);
    let selected = select_jobs(sweep.jobs.len(), args.shard.as_deref(), index_of(&args)?)?;
    let text = read_input(&args.sweep, SWEEP_FILE)?;
    let progress = JobsProgress::new(args.quiet);
    run_jobs(&sweep, &text, &selected, &args.out, args.force, &progress)
}

/// Arguments of `fuzzymotiv merge`.
#[derive(clap::Args)]
pub struct MergeArgs {
    /// A sweep output directory (with plan.jsonl and jobs/).
    pub dir: PathBuf,
    /// Also write summary.png beside summary.svg (and the PNGs the jobs' figures lack).
    #[arg(long)]
    pub png: bool,
}

/// Entry point of `fuzzymotiv merge`.
pub fn merge(args: MergeArgs) -> Result<(), CliError> {
    let merged = merge_dir(&args.dir, &Stderr)?;
    crate::console::out!("{}", merged.markdown)?;
    if args.png {
        png_beside(&args.dir.join("summary.svg"), &Resvg)?;
        add_pngs(&args.dir)?;
    }
    Ok(())
}
