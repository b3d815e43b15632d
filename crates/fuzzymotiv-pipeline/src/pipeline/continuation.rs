//! Continuing a finished run directory to more generations (`fuzzymotiv run --continue DIR
//! --generations N --out NEW`, Python's `GA.from_run`): its final population ([`POPULATION`])
//! is evaluated again (the library's [`Start::Finished`], same evaluations), bred once more,
//! and evolution goes on from there, so the new run equals a fresh N-generation run. The
//! finished directory is only read.

use std::path::Path;

use fuzzymotiv::experiment::Start;
use fuzzymotiv::experiment::{Evolution, Population};
use fuzzymotiv::experiment::{Experiment, SetupError};

use crate::files::error::CliError;
use crate::files::guard::StagedDir;
use crate::files::inputs::{Loaded, load_config, resolved_toml, rooms_unchanged};
use crate::records::checkpoint::{CHECKPOINT, Checkpoint, CheckpointRun, POPULATION};

/// The config file of a run directory.
const CONFIG: &str = "config.resolved.toml";

/// A finished run directory's config (`config.resolved.toml`), checked to be a finished run
/// that saved its final population: anything else is an error that says what `dir` lacks.
pub fn finished_config(dir: &Path) -> Result<Loaded, CliError> {
    let what = |lacks: &str, hint: &str| {
        CliError::input(format!(
            "{}: {lacks}; expected the directory of a finished `fuzzymotiv run`{hint}",
            dir.display()
        ))
    };
    if StagedDir::staging_path(dir).join(CONFIG).is_file() && !dir.join(CONFIG).is_file() {
        return Err(what(
            "an unfinished run",
            &format!(
                " (finish it first with `fuzzymotiv run --resume {}`)",
                dir.display()
            ),
        ));
    }
    if dir.exists() && !dir.is_dir() {
        return Err(what("a file, not a directory", ""));
    }
    if !dir.is_dir() {
        return Err(what("no such directory", ""));
    }
    if !dir.join(CONFIG).is_file() {
        return Err(what(&format!("no {CONFIG}"), ""));
    }
    if !dir.join("summary.json").is_file() {
        return Err(what("no summary.json (an unfinished run)", ""));
    }
    if !dir.join(POPULATION).is_file() {
        return Err(what(
            &format!(
                "no {POPULATION} (written by an older fuzzymotiv, which did not save the final population)"
            ),
            "; run it again with this version to continue it",
        ));
    }
    let loaded = load_config(Some(&dir.join(CONFIG)), &[], None)?;
    let remedy = "continuing would evolve the rest of the run in another room. Restore the file, \
                  or start a new run";
    rooms_unchanged(&dir.join(CONFIG), &loaded, remedy)?;
    Ok(loaded)
}

/// The config of `dir`'s run with `generations` generations in all: more than it ran.
pub fn continued_config(dir: &Path, old: &Loaded, generations: usize) -> Result<Loaded, CliError> {
    let done = old.experiment.ga().generations();
    if generations <= done {
        return Err(CliError::input(format!(
            "--generations {generations}: {} already ran {done} generation(s); expected a total greater than {done}",
            dir.display()
        )));
    }
    let set = [format!("ga.generations={generations}")];
    // The only value changed is --generations: a limit it breaks is said of it, not the file.
    load_config(Some(&dir.join(CONFIG)), &set, None).map_err(|e| match e {
        CliError::Setup(SetupError::Field(f)) if f.field == "ga.generations" => {
            CliError::input(format!("--generations {generations}: {}", f.reason))
        }
        e => e,
    })
}

/// One evolution of a finished run, continued: the finished evolution (its final generation
/// evaluated again) and the next generation bred from it, not yet evaluated.
pub struct Continued {
    /// The finished evolution (history, final population and its evaluations).
    pub finished: Evolution,
    /// The generation after the last, bred as a longer run breeds it.
    pub next: Population,
}

/// Every evolution of the finished run in `dir` (checked by [`finished_config`]; `exp` is its
/// experiment), continued by one breeding.
pub fn continue_runs(dir: &Path, exp: &Experiment) -> Result<Vec<Continued>, CliError> {
    let runs = exp.runs();
    let path = dir.join(POPULATION);
    let remedy = "the run is only read, so nothing is replaced: was its config.resolved.toml \
                  or population.json edited after it ran?";
    let saved = Checkpoint::load_or(&path, &runs, exp, remedy)?;
    if saved.runs.iter().any(|r| !r.done) {
        return Err(CliError::input(format!(
            "{}: not the population of a finished run",
            path.display()
        )));
    }
    let mut out = Vec::with_capacity(runs.len());
    for (run, r) in runs.iter().zip(&saved.runs) {
        let Start::Finished {
            population,
            history,
        } = r.start(exp)?
        else {
            unreachable!("a done run starts finished")
        };
        let finished = exp.finished(run, population.clone(), history);
        let fitness: Vec<f64> = finished.evaluations.iter().map(|e| e.fitness).collect();
        let next = exp
            .breed(&population, &fitness, run, finished.history.len() - 1)
            .map_err(|e| CliError::input(format!("{}: {e}", path.display())))?;
        out.push(Continued { finished, next });
    }
    Ok(out)
}

/// Starts the staging directory of `out` for `new` (the continued config) with a checkpoint
/// at the generation after `dir`'s last: [`crate::pipeline::run_dir::execute`] with `resume`
/// then evolves the remaining generations and writes the run. `dir` is only read.
pub fn stage_continued(dir: &Path, old: &Loaded, new: &Loaded, out: &Path) -> Result<(), CliError> {
    let continued = continue_runs(dir, &old.experiment)?;
    let mut checkpoint = Checkpoint::fresh(&new.experiment, &new.experiment.runs());
    for (saved, c) in checkpoint.runs.iter_mut().zip(&continued) {
        *saved = CheckpointRun {
            label: saved.label.clone(),
            done: false,
            history: c.finished.history.clone(),
            population: (c.next.iter())
                .map(|g| g.iter().map(|v| v.to_bits()).collect())
                .collect(),
        };
    }
    let staged = StagedDir::new(out)?;
    staged.write(CONFIG, resolved_toml(&new.raw))?;
    checkpoint.save(&staged.path(CHECKPOINT))?;
    Ok(())
}
