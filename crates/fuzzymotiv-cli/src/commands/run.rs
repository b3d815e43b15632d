//! `fuzzymotiv run`: evolve, model the rooms, write the run directory.

use std::path::{Path, PathBuf};

use crate::console::{Stderr, config_notes, note};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::{OutState, StagedDir, check_out};
use fuzzymotiv_pipeline::files::inputs::{Loaded, load_config, rooms_unchanged, run_identity};
use fuzzymotiv_pipeline::pipeline::continuation::{
    continued_config, finished_config, stage_continued,
};
use fuzzymotiv_pipeline::pipeline::lanes::set_threads;
use fuzzymotiv_pipeline::pipeline::run_dir::{execute, start_line};
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

/// What `run` is asked to do.
enum Target {
    /// Nothing (but the missing PNGs with `--png`): the run is already there.
    Done(PathBuf),
    /// Run (or resume) `loaded` into `out`.
    Run {
        loaded: Box<Loaded>,
        out: PathBuf,
        resume: bool,
    },
}

/// Entry point of `fuzzymotiv run`.
pub fn run(args: RunArgs) -> Result<(), CliError> {
    set_threads(args.threads)?;
    if args.generations.is_some() && args.continue_from.is_none() {
        // clap's `requires` does not catch it beside a CONFIG; unchecked, it would be ignored.
        return Err(CliError::input(
            "--generations N goes with --continue DIR (the total to continue it to); \
             to run a config for N generations, use --set ga.generations=N",
        ));
    }
    let target = match (&args.resume, &args.config) {
        _ if args.continue_from.is_some() => continue_target(&args)?,
        (Some(dir), _) => resume_target(dir)?,
        (None, Some(config)) => config_target(config, &args)?,
        (None, None) => return Err(CliError::input("give a CONFIG file or --resume DIR")),
    };
    let (loaded, out, resume) = match target {
        Target::Run {
            loaded,
            out,
            resume,
        } => (loaded, out, resume),
        Target::Done(dir) if args.png => return add_pngs(&dir),
        Target::Done(_) => return Ok(()),
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

/// `--resume DIR`: the interrupted run in `DIR.partial/`.
fn resume_target(dir: &Path) -> Result<Target, CliError> {
    let staging = StagedDir::staging_path(dir);
    let cfg = staging.join("config.resolved.toml");
    if !cfg.is_file() {
        if dir.join("summary.json").is_file() {
            note!("{} is already complete; nothing to resume", dir.display());
            return Ok(Target::Done(dir.to_path_buf()));
        }
        return Err(CliError::input(format!(
            "--resume {}: no interrupted run there ({} not found); start it with `fuzzymotiv run CONFIG --out {}`",
            dir.display(),
            cfg.display(),
            dir.display()
        )));
    }
    let loaded = load_config(Some(&cfg), &[], None)?;
    config_notes(&loaded.notes);
    let remedy = "resuming would evolve the rest of the run in another room. Restore the file, \
                  or start the run over with `fuzzymotiv run CONFIG --out DIR --force`";
    rooms_unchanged(&cfg, &loaded, remedy)?;
    Ok(Target::Run {
        loaded: Box::new(loaded),
        out: dir.to_path_buf(),
        resume: true,
    })
}

/// `CONFIG [--out DIR]`: a fresh run, or the unfinished one of the same config in `DIR`.
fn config_target(config: &Path, args: &RunArgs) -> Result<Target, CliError> {
    let loaded = load_config(Some(config), &args.sets, args.output.seed)?;
    config_notes(&loaded.notes);
    let out = args
        .output
        .out
        .clone()
        .unwrap_or_else(|| Path::new("runs").join(&loaded.raw.name));
    let resume = match check_out(&out, &run_identity(&loaded.raw), args.output.force, &Stderr)? {
        OutState::Done => {
            note!(
                "{} already holds this run, finished (same resolved config); nothing to do. --force runs it again",
                out.display()
            );
            return Ok(Target::Done(out));
        }
        OutState::Unfinished => true,
        OutState::Fresh => false,
    };
    Ok(Target::Run {
        loaded: Box::new(loaded),
        out,
        resume,
    })
}

/// `--continue DIR --generations N --out NEW`: the finished run in `DIR` continued to N
/// generations in `NEW` (staged from `DIR`'s final population; `DIR` is never written).
fn continue_target(args: &RunArgs) -> Result<Target, CliError> {
    let (Some(dir), Some(n), Some(out)) = (&args.continue_from, args.generations, &args.output.out)
    else {
        return Err(CliError::input(
            "--continue DIR needs --generations N (the total) and --out NEW",
        ));
    };
    let old = finished_config(dir)?;
    config_notes(&old.notes);
    let new = continued_config(dir, &old, n)?;
    if same_place(dir, out) {
        return Err(CliError::input(format!(
            "--out {}: is the run being continued; --continue never changes it: choose a new --out",
            out.display()
        )));
    }
    let resume = match check_out(out, &run_identity(&new.raw), args.output.force, &Stderr)? {
        OutState::Done => {
            note!(
                "{} already holds this run, finished ({n} generations); nothing to do. --force runs it again",
                out.display()
            );
            return Ok(Target::Done(out.clone()));
        }
        OutState::Unfinished => true,
        OutState::Fresh => {
            stage_continued(dir, &old, &new, out)?;
            true
        }
    };
    Ok(Target::Run {
        loaded: Box::new(new),
        out: out.clone(),
        resume,
    })
}

/// Whether two paths name the same directory (or `b` lies inside `a`).
fn same_place(a: &Path, b: &Path) -> bool {
    let canon = |p: &Path| {
        let parent = p.parent().filter(|q| !q.as_os_str().is_empty());
        let base = parent.map_or_else(|| Path::new(".").canonicalize(), |q| q.canonicalize());
        base.ok().map(|d| d.join(p.file_name().unwrap_or_default()))
    };
    match (a.canonicalize().ok(), canon(b)) {
        (Some(a), Some(b)) => b.starts_with(&a),
        _ => false,
    }
}
