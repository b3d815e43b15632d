//! A run directory: evolve (with a checkpoint after every generation), model the rooms, write
//! its records, figures and report; resume an interrupted one; read a finished one back.

use std::ops::ControlFlow;
use std::path::Path;
use std::time::Instant;

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::experiment::Training;
use fuzzymotiv::experiment::{GenerationState, Observer};
use fuzzymotiv::experiment::{Outcome, RunError};

use crate::files::error::CliError;
use crate::files::guard::{StagedDir, io_err, matches};
use crate::files::inputs::{Loaded, resolved_toml, run_identity};
use crate::pipeline::progress::RunProgress;
use crate::records::checkpoint::{CHECKPOINT, Checkpoint, CheckpointRun, POPULATION};
use crate::records::context::RenderContext;
use crate::records::test_runs;
use crate::records::{
    BestGenome, Finished, GenerationRow, RecognitionTable, RunSummary, extra_terms,
    generations_csv, read_json, to_json,
};
use crate::render::figures::{Rasterise, add_missing_pngs, write_figure};
use crate::render::report;
use crate::render::svg::{best_paths_svg, fitness_svg, term_curves, terms_svg_of};
use crate::render::tables::{provenance_line, table_markdown};

/// What is about to run, said before the first generation (which may take long).
pub fn start_line(exp: &Experiment, out: &Path) -> String {
    format!(
        "{}: seed {}, {} × {} generations of {} robots, {} room(s) × {} steps per trial → {}",
        exp.name(),
        exp.seed(),
        exp.runs().len(),
        exp.ga().generations(),
        exp.ga().population(),
        exp.arenas().len(),
        exp.trial_params().steps(),
        out.display()
    )
}

/// Runs a loaded config and writes its run directory `out` (atomically), with `report.html`
/// and the figures (and their PNGs with `png`). After every generation a checkpoint is written
/// into the staging directory; with `resume`, an interrupted run continues from its last
/// checkpoint and ends with the same files.
pub fn execute(
    loaded: &Loaded,
    out: &Path,
    progress: &dyn RunProgress,
    resume: bool,
    png: Option<&dyn Rasterise>,
) -> Result<Finished, CliError> {
    execute_with(loaded, out, progress, resume, png, &mut |_| {
        ControlFlow::Continue(())
    })
}

/// [`execute`], calling the observer `hook` after every generation once its checkpoint is saved
/// (the Python bindings report progress there, and stop on Ctrl-C by breaking: the run then ends
/// with an error and its staging directory is resumable).
pub fn execute_with(
    loaded: &Loaded,
    out: &Path,
    progress: &dyn RunProgress,
    resume: bool,
    png: Option<&dyn Rasterise>,
    hook: &mut Observer<'_>,
) -> Result<Finished, CliError> {
    let exp = &loaded.experiment;
    let staged = if resume {
        StagedDir::reopen(out)?
    } else {
        let staged = StagedDir::new(out)?;
        staged.write("config.resolved.toml", resolved_toml(&loaded.raw))?;
        staged
    };
    let mut session = Session::open(&staged, exp, out, progress, resume)?;
    let outcome = session.run(exp, progress, hook)?;
    let generations = GenerationRow::all_of(&extra_terms(exp), &outcome.evolutions);
    staged.write("generations.csv", generations_csv(&generations))?;
    let done = Finished::new(exp, outcome, session.wall_seconds());
    write_run(&staged, loaded, &done, png, &session.checkpoint)?;
    staged.commit()?;
    Ok(done)
}

/// Runs a loaded config into the run directory `out` whatever it holds: a finished run of the
/// same resolved config is read back (its final population, [`POPULATION`], re-evaluated and its
/// rooms modelled again: the same [`Finished`], with PNGs added when `png`), an unfinished one
/// resumes from its checkpoint, anything else starts afresh. A study's runs go through here, so
/// the same `reproduce` command continues a killed study. The caller has checked `out` belongs
/// to this output.
pub fn execute_or_resume(
    loaded: &Loaded,
    out: &Path,
    progress: &dyn RunProgress,
    png: Option<&dyn Rasterise>,
) -> Result<Finished, CliError> {
    let id = run_identity(&loaded.raw);
    if matches(out, &id) && out.join("summary.json").is_file() && out.join(POPULATION).is_file() {
        let done = read_back(&loaded.experiment, out, progress)?;
        if let Some(png) = png {
            add_missing_pngs(out, png)?;
        }
        return Ok(done);
    }
    let resume = matches(&StagedDir::staging_path(out), &id);
    execute(loaded, out, progress, resume, png)
}

/// A finished run directory read back: its final population and history ([`POPULATION`])
/// evaluated again and its rooms modelled again, which gives the run's [`Finished`] exactly.
pub fn read_back(
    exp: &Experiment,
    dir: &Path,
    progress: &dyn RunProgress,
) -> Result<Finished, CliError> {
    let runs = exp.runs();
    let saved = Checkpoint::load(&dir.join(POPULATION), &runs, exp)?;
    if saved.runs.iter().any(|r| !r.done) {
        return Err(CliError::input(format!(
            "{}: not the population of a finished run",
            dir.join(POPULATION).display()
        )));
    }
    progress.skip(saved.runs.iter().map(|r| r.history.len()).sum());
    progress.note(&format!("{} is finished: read back", dir.display()));
    let starts = (saved.runs.iter())
        .map(|r| r.start(exp))
        .collect::<Result<_, _>>()?;
    let outcome = exp
        .run_from(starts, &mut |_, _| ControlFlow::Continue(()))
        .map_err(|e| CliError::runtime(e.to_string()))?;
    let summary: RunSummary = read_json(&dir.join("summary.json"))?;
    Ok(Finished::new(exp, outcome, summary.wall_seconds))
}

/// A run being evolved in a staging directory: its checkpoint and its wall time.
struct Session<'a> {
    staged: &'a StagedDir,
    checkpoint: Checkpoint,
    /// Wall time of earlier sessions (before a resume): it counts too.
    earlier_seconds: f64,
    start: Instant,
}

impl<'a> Session<'a> {
    /// A fresh session, or the one a checkpoint continues.
    fn open(
        staged: &'a StagedDir,
        exp: &Experiment,
        out: &Path,
        progress: &dyn RunProgress,
        resume: bool,
    ) -> Result<Session<'a>, CliError> {
        let runs = exp.runs();
        let checkpoint = if resume {
            // Killed after the last checkpoint became population.json: the evolution is done.
            let (cp, last) = (staged.path(CHECKPOINT), staged.path(POPULATION));
            let path = if !cp.is_file() && last.is_file() {
                last
            } else {
                cp
            };
            let cp = Checkpoint::load(&path, &runs, exp)?;
            progress.note(&cp.resume_note(out, exp.ga().generations()));
            cp
        } else {
            Checkpoint::fresh(exp, &runs)
        };
        Ok(Session {
            staged,
            earlier_seconds: checkpoint.wall_seconds,
            checkpoint,
            start: Instant::now(),
        })
    }

    fn wall_seconds(&self) -> f64 {
        self.earlier_seconds + self.start.elapsed().as_secs_f64()
    }

    /// Runs the experiment from where the checkpoint left it (the library's
    /// [`Experiment::run_from`]), saving the checkpoint after every generation.
    fn run(
        &mut self,
        exp: &Experiment,
        progress: &dyn RunProgress,
        hook: &mut Observer<'_>,
    ) -> Result<Outcome, CliError> {
        let runs = exp.runs();
        let mut starts = Vec::with_capacity(runs.len());
        for saved in &self.checkpoint.runs {
            progress.skip(saved.history.len());
            starts.push(saved.start(exp)?);
        }
        // A checkpoint that cannot be written stops the run (its error is returned).
        let mut write_error = None;
        let mut on_generation = |k: usize, state: &GenerationState<'_>| {
            let (g, best) = (state.history.len(), state.record().stats.max);
            progress.generation(&runs[k].label, g, exp.ga().generations(), best);
            if let Err(e) = self.save(k, &runs[k].label, state) {
                write_error = Some(e);
                return ControlFlow::Break(());
            }
            match hook(state) {
                ControlFlow::Continue(()) if progress.stop() => ControlFlow::Break(()),
                flow => flow,
            }
        };
        let outcome = exp.run_from(starts, &mut on_generation);
        match (outcome, write_error) {
            (_, Some(e)) => Err(e),
            (Ok(outcome), None) => Ok(outcome),
            (Err(RunError::Interrupted(i)), None) => Err(CliError::runtime(format!(
                "the run was stopped after generation {}; the same command resumes it",
                i.stopped.generation
            ))),
            (Err(e), None) => Err(CliError::runtime(e.to_string())),
        }
    }

    fn save(&mut self, k: usize, label: &str, state: &GenerationState<'_>) -> Result<(), CliError> {
        self.checkpoint.runs[k] = CheckpointRun::from_state(label, state);
        self.checkpoint.wall_seconds = self.wall_seconds();
        self.checkpoint.save(&self.staged.path(CHECKPOINT))?;
        Ok(())
    }
}

/// The records, figures and report of a finished run; the checkpoint stays as the final
/// population.
fn write_run(
    staged: &StagedDir,
    loaded: &Loaded,
    done: &Finished,
    png: Option<&dyn Rasterise>,
    last: &Checkpoint,
) -> Result<(), CliError> {
    let exp = &loaded.experiment;
    let ctx = RenderContext::of(loaded);
    staged.write(
        "best_genome.json",
        to_json(&BestGenome::of(exp, &done.outcome.evolutions)),
    )?;
    staged.write("recognition.csv", RecognitionTable::of(exp, done).to_csv())?;
    staged.write(
        test_runs::TEST_RUNS,
        test_runs::to_text(&test_runs::test_runs(done, &extra_terms(exp))),
    )?;
    staged.write(
        "table.md",
        table_markdown(&done.rows) + &provenance_line(&ctx),
    )?;
    write_run_figures(staged, &ctx, done, png)?;
    staged.write("summary.json", to_json(&RunSummary::of(exp, done)))?;
    // The last checkpoint (in memory: the file may already be gone, when a run killed after
    // this step resumes from population.json) holds the final population: kept as
    // `population.json`, without the wall time (which is in summary.json), so that it is the
    // same bytes for the same run.
    Checkpoint {
        wall_seconds: 0.0,
        ..last.clone()
    }
    .save(&staged.path(POPULATION))?;
    let checkpoint = staged.path(CHECKPOINT);
    if checkpoint.exists() {
        std::fs::remove_file(&checkpoint).map_err(|e| io_err(&checkpoint, e))?;
    }
    staged.write("report.html", report::run_page(&ctx, done))
}

/// `fitness.svg`, `terms.svg` and `trajectories.svg` (with PNGs when `png`).
fn write_run_figures(
    staged: &StagedDir,
    ctx: &RenderContext,
    done: &Finished,
    png: Option<&dyn Rasterise>,
) -> Result<(), CliError> {
    let setting = format!("{} {}", ctx.name, ctx.motivations.label());
    let panels: Vec<_> = done
        .outcome
        .evolutions
        .iter()
        .map(|e| {
            let title = match ctx.training {
                Training::AllRooms => setting.clone(),
                Training::PerRoom => format!("{}: robot evolved in {}", ctx.name, e.run.label),
            };
            (title, e.history.clone())
        })
        .collect();
    write_figure(staged, "fitness", &fitness_svg(&panels), png)?;
    let curves = term_curves(&ctx.motivations.table, &ctx.extra_terms);
    let terms = terms_svg_of(&panels, &curves);
    write_figure(staged, "terms", &terms, png)?;
    let title = if ctx.motivations.table.is_empty() {
        format!(
            "Best robot, {} (C, H, O, E) = {:?}",
            ctx.name,
            ctx.motivations.as_array()
        )
    } else {
        format!("Best robot, {}: {}", ctx.name, ctx.motivations.label())
    };
    let paths = best_paths_svg(&title, &ctx.rooms, &done.trajectories());
    write_figure(staged, "trajectories", &paths, png)
}
