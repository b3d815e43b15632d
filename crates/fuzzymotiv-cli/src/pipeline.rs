//! The shared pipeline of the commands: evolve (with a checkpoint after every generation),
//! model the rooms, write a run directory's records, figures and report; and run a study's runs
//! or a sweep's jobs side by side.

use std::ops::ControlFlow;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::Instant;

use fuzzymotiv::config::Training;
use fuzzymotiv::evolution::{Evolution, GenerationState, Observer};
use fuzzymotiv::experiment::{Experiment, Run};
use fuzzymotiv::modelling::AemReport;
use indicatif::ProgressBar;

use crate::checkpoint::{CHECKPOINT, Checkpoint, CheckpointRun, POPULATION};
use crate::error::CliError;
use crate::files::{
    StagedDir, ensure_replaceable, foreign_files, io_err, matches, refuse_current_dir,
    refuse_non_directory, remove_ours, write_atomic,
};
use crate::inputs::{Loaded, resolved_toml, run_identity};
use crate::note;
use crate::png::{add_missing_pngs, write_figure};
use crate::progress::Progress;
use crate::records::{
    BestGenome, Finished, GenerationRow, Job, RecognitionTable, RunSummary, read_json, to_csv,
    to_json,
};
use crate::report;
use crate::svg::{best_paths_svg, fitness_svg, terms_svg};
use crate::sweep_plan::Sweep;
use crate::tables::{provenance_line, table_markdown};

/// Configures rayon's global pool.
pub fn set_threads(threads: Option<usize>) -> Result<(), CliError> {
    if let Some(n) = threads {
        if n == 0 {
            return Err(CliError::input("--threads must be at least 1"));
        }
        // A second call (e.g. in-process tests) keeps the first pool; results do not depend on it.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global();
    }
    Ok(())
}

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
    progress: &Progress,
    resume: bool,
    png: bool,
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
    progress: &Progress,
    resume: bool,
    png: bool,
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
    let evolutions = exp
        .runs()
        .iter()
        .enumerate()
        .map(|(k, run)| session.evolve(exp, run, k, progress, hook))
        .collect::<Result<Vec<_>, _>>()?;
    staged.write("generations.csv", to_csv(&GenerationRow::all(&evolutions)))?;
    let aem = model_rooms(exp, &evolutions)?;
    let done = Finished::new(exp, evolutions, aem, session.wall_seconds());
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
    progress: &Progress,
    png: bool,
) -> Result<Finished, CliError> {
    let id = run_identity(&loaded.raw);
    if matches(out, &id) && out.join("summary.json").is_file() && out.join(POPULATION).is_file() {
        let done = read_back(&loaded.experiment, out, progress)?;
        if png {
            add_missing_pngs(out)?;
        }
        return Ok(done);
    }
    let resume = matches(&StagedDir::staging_path(out), &id);
    execute(loaded, out, progress, resume, png)
}

/// A finished run directory read back: its final population and history ([`POPULATION`])
/// evaluated again and its rooms modelled again, which gives the run's [`Finished`] exactly.
pub fn read_back(exp: &Experiment, dir: &Path, progress: &Progress) -> Result<Finished, CliError> {
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
    let evolutions: Vec<Evolution> = runs
        .iter()
        .zip(saved.runs)
        .map(|(run, r)| Ok(exp.finished(run, r.population(exp)?, r.history)))
        .collect::<Result<_, CliError>>()?;
    let aem = model_rooms(exp, &evolutions)?;
    let summary: RunSummary = read_json(&dir.join("summary.json"))?;
    Ok(Finished::new(exp, evolutions, aem, summary.wall_seconds))
}

/// Environment modelling of every evolution's best robot.
pub fn model_rooms(exp: &Experiment, evolutions: &[Evolution]) -> Result<Vec<AemReport>, CliError> {
    evolutions
        .iter()
        .map(|evo| {
            let best = exp
                .network(&evo.population[evo.best])
                .map_err(|e| e.to_string())?;
            exp.environment_modelling(&best, &evo.run)
                .map_err(|e| e.to_string())
        })
        .collect::<Result<_, _>>()
        .map_err(|e| CliError::runtime(format!("environment modelling failed: {e}")))
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
        progress: &Progress,
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
            Checkpoint::fresh(&runs)
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

    /// Evolves run `k` from where the checkpoint left it, saving the checkpoint after every
    /// generation.
    fn evolve(
        &mut self,
        exp: &Experiment,
        run: &Run,
        k: usize,
        progress: &Progress,
        hook: &mut Observer<'_>,
    ) -> Result<Evolution, CliError> {
        let saved = self.checkpoint.runs[k].clone();
        progress.skip(saved.history.len());
        if saved.done {
            return Ok(exp.finished(run, saved.population(exp)?, saved.history));
        }
        let population = if saved.population.is_empty() {
            exp.initial_population(run)
        } else {
            saved.population(exp)?
        };
        // A checkpoint that cannot be written stops the run (its error is returned).
        let mut write_error = None;
        let mut on_generation = |state: &GenerationState<'_>| {
            let (g, best) = (state.history.len(), state.record().stats.max);
            progress.generation(&run.label, g, exp.ga().generations(), best);
            if let Err(e) = self.save(k, &run.label, state) {
                write_error = Some(e);
                return ControlFlow::Break(());
            }
            hook(state)
        };
        let done = saved.history.len();
        let evo = exp.evolve_from(run, done, population, saved.history, &mut on_generation);
        match (evo, write_error) {
            (_, Some(e)) => Err(e),
            (Ok(evo), None) => Ok(evo),
            (Err(stopped), None) => Err(CliError::runtime(format!(
                "the run was stopped after generation {}; the same command resumes it",
                stopped.generation
            ))),
        }
    }

    fn save(&mut self, k: usize, label: &str, state: &GenerationState<'_>) -> Result<(), CliError> {
        self.checkpoint.runs[k] = CheckpointRun::from_state(label, state);
        self.checkpoint.wall_seconds = self.wall_seconds();
        self.checkpoint.save(&self.staged.path(CHECKPOINT))?;
        abort_point();
        Ok(())
    }
}

/// For kill tests only: with `FUZZYMOTIV_TEST_ABORT_AFTER=N` in the environment, the process
/// aborts (as `kill -9` would: no clean-up) once N generations have been checkpointed in it,
/// counted over all its runs. A deterministic kill point, unlike a timer.
fn abort_point() {
    static LIMIT: std::sync::LazyLock<Option<usize>> = std::sync::LazyLock::new(|| {
        std::env::var("FUZZYMOTIV_TEST_ABORT_AFTER")
            .ok()
            .and_then(|v| v.parse().ok())
    });
    static SAVED: AtomicUsize = AtomicUsize::new(0);
    if let Some(limit) = *LIMIT
        && SAVED.fetch_add(1, Ordering::SeqCst) + 1 >= limit
    {
        std::process::abort();
    }
}

/// The records, figures and report of a finished run; the checkpoint stays as the final
/// population.
fn write_run(
    staged: &StagedDir,
    loaded: &Loaded,
    done: &Finished,
    png: bool,
    last: &Checkpoint,
) -> Result<(), CliError> {
    let exp = &loaded.experiment;
    staged.write(
        "best_genome.json",
        to_json(&BestGenome::of(exp, &done.evolutions)),
    )?;
    staged.write("recognition.csv", RecognitionTable::of(exp, done).to_csv())?;
    staged.write(
        "table.md",
        table_markdown(&done.rows) + &provenance_line(loaded),
    )?;
    write_run_figures(staged, exp, done, png)?;
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
    staged.write("report.html", report::run_page(loaded, done))
}

/// `fitness.svg`, `terms.svg` and `trajectories.svg` (with PNGs when `png`).
fn write_run_figures(
    staged: &StagedDir,
    exp: &Experiment,
    done: &Finished,
    png: bool,
) -> Result<(), CliError> {
    let setting = format!(
        "{} (C,H,O,E) = {:?}",
        exp.name(),
        exp.motivations().as_array()
    );
    let panels: Vec<_> = done
        .evolutions
        .iter()
        .map(|e| {
            let title = match exp.training() {
                Training::AllRooms => setting.clone(),
                Training::PerRoom => format!("{}: robot evolved in {}", exp.name(), e.run.label),
            };
            (title, e.history.clone())
        })
        .collect();
    write_figure(staged, "fitness", &fitness_svg(&panels), png)?;
    write_figure(staged, "terms", &terms_svg(&panels), png)?;
    let title = format!(
        "Best robot, {} (C, H, O, E) = {:?}",
        exp.name(),
        exp.motivations().as_array()
    );
    let paths = best_paths_svg(&title, exp, &done.trajectories());
    write_figure(staged, "trajectories", &paths, png)
}

/// Runs the `selected` jobs of `sweep` into `out/jobs/ID/`, skipping finished ones, as many at
/// a time as there are threads ([`run_concurrently`]). On a terminal a bar counts jobs;
/// otherwise each job prints plain progress lines (not with `quiet`).
pub fn run_jobs(
    sweep: &Sweep,
    text: &str,
    selected: &[usize],
    out: &Path,
    quiet: bool,
    force: bool,
) -> Result<(), CliError> {
    open_sweep_dir(sweep, out, force)?;
    let terminal = std::io::IsTerminal::is_terminal(&std::io::stderr());
    // The plan first: it is what makes the directory a sweep for the tasks that start with this.
    std::fs::create_dir_all(out).map_err(|e| io_err(out, e))?;
    write_atomic(&out.join("plan.jsonl"), sweep.plan_jsonl())?;
    write_atomic(&out.join("sweep.toml"), text)?;
    let jobs_dir = out.join("jobs");
    std::fs::create_dir_all(&jobs_dir).map_err(|e| io_err(&jobs_dir, e))?;
    let bar = if terminal && !quiet {
        ProgressBar::new(selected.len() as u64)
    } else {
        ProgressBar::hidden()
    };
    let todo: Vec<usize> = selected
        .iter()
        .copied()
        .filter(|&k| !jobs_dir.join(&sweep.jobs[k].id).join("DONE").is_file())
        .collect();
    let skipped = selected.len() - todo.len();
    bar.inc(skipped as u64);
    let numbered: Vec<(usize, usize)> = todo.iter().copied().enumerate().collect();
    let plain_lines = !(terminal || quiet);
    run_concurrently(&numbered, |&(n, k)| {
        let job = &sweep.jobs[k];
        bar.set_message(job.key.clone());
        let line = plain_lines.then(|| {
            format!(
                "job {} ({}/{} here)",
                job.id,
                skipped + n + 1,
                selected.len()
            )
        });
        run_job(sweep, job, &jobs_dir.join(&job.id), line)?;
        bar.inc(1);
        Ok(())
    })?;
    bar.finish_and_clear();
    note!(
        "{} jobs run, {skipped} already done, {} in this selection, {} in the plan",
        todo.len(),
        selected.len(),
        sweep.jobs.len()
    );
    Ok(())
}

/// The files of a sweep directory besides its job folders (written by `sweep` and `merge`).
const SWEEP_FILES: [&str; 7] = [
    "plan.jsonl",
    "sweep.toml",
    "results.csv",
    "aggregate.csv",
    "aggregate.md",
    "summary.svg",
    "summary.png",
];

/// Checks a sweep's `--out` before any work. A sweep directory belongs to its plan: the same
/// plan (another shard or array task, or the same command again) goes on; a plan that only adds
/// jobs (more replicates or points, no id clash) keeps the finished ones; any other plan, or
/// another kind of output, is refused unless `force`, which removes the old sweep's own files
/// and job folders (or the other output), never a file of the user's. A directory that is not
/// a fuzzymotiv output, a file, and the current directory are refused.
fn open_sweep_dir(sweep: &Sweep, out: &Path, force: bool) -> Result<(), CliError> {
    refuse_current_dir(out)?;
    refuse_non_directory(out)?;
    if !out.exists() {
        return Ok(());
    }
    let plan = out.join("plan.jsonl");
    if !plan.is_file() {
        if starting_sweep(out) {
            return Ok(());
        }
        ensure_replaceable(out)?;
        if !force {
            return Err(CliError::input(format!(
                "--out {}: holds another fuzzymotiv output (a run or a study), not a sweep; it is \
                 kept. Choose another --out, or pass --force to replace it",
                out.display()
            )));
        }
        note!("note: --force: {} will be replaced", out.display());
        return remove_ours(out);
    }
    let old = Job::read_plan(&plan)?;
    let conflict = plan_conflict(&old, &sweep.jobs);
    let same_plan = conflict.is_none() && old.len() == sweep.jobs.len();
    if force && same_plan {
        // Safe in an array script whose every task passes --force: nothing is lost.
        note!(
            "note: --force: the sweep in {} has this very plan; its finished jobs are kept \
             (remove the directory yourself to run them again)",
            out.display()
        );
        return Ok(());
    }
    if force {
        note!(
            "note: --force: the sweep in {} will be replaced",
            out.display()
        );
        return remove_sweep(out, &old);
    }
    match conflict {
        None => Ok(()),
        Some(why) => Err(CliError::input(format!(
            "--out {}: holds a sweep of another plan ({why}); its results are kept. Choose \
             another --out, pass --force to replace that sweep, or run the sweep file that made it \
             ({})",
            out.display(),
            out.join("sweep.toml").display()
        ))),
    }
}

/// Whether `out` is a sweep directory another task is just starting (no plan yet; only a `jobs/`
/// folder of job folders and temporary files), which this task joins.
fn starting_sweep(out: &Path) -> bool {
    let Ok(entries) = out.read_dir() else {
        return false;
    };
    entries.flatten().all(|e| {
        let name = e.file_name().to_string_lossy().into_owned();
        name.starts_with(".tmp") || (name == "jobs" && foreign_files(&e.path()).is_empty())
    })
}

/// Why the plan `new` cannot take over a sweep directory of the plan `old`, if it cannot: it
/// must hold every old job (by id) with the same key and seed; it may add jobs.
fn plan_conflict(old: &[Job], new: &[Job]) -> Option<String> {
    let missing: Vec<&Job> = old
        .iter()
        .filter(|o| !new.iter().any(|n| n.id == o.id))
        .collect();
    if let Some(first) = missing.first() {
        return Some(format!(
            "{} of its {} jobs are not in this plan, e.g. `{}`",
            missing.len(),
            old.len(),
            first.key
        ));
    }
    old.iter().find_map(|o| {
        let n = new.iter().find(|n| n.id == o.id)?;
        (n.key != o.key || n.seed != o.seed || n.overrides != o.overrides)
            .then(|| format!("job {} is `{}` there but `{}` here", o.id, o.key, n.key))
    })
}

/// Removes a sweep's own files and its jobs' folders (and their staging folders) from `out`;
/// anything else in it stays.
fn remove_sweep(out: &Path, jobs: &[Job]) -> Result<(), CliError> {
    let jobs_dir = out.join("jobs");
    let plan = out.join("plan.jsonl");
    if let Some(bad) = jobs.iter().find(|j| !is_job_id(&j.id)) {
        return Err(CliError::input(format!(
            "{}: job {} has the id `{}`, which is not 16 hexadecimal digits: not a plan that \
             fuzzymotiv wrote, so nothing is removed",
            plan.display(),
            bad.index,
            bad.id
        )));
    }
    for job in jobs {
        let dir = jobs_dir.join(&job.id);
        for d in [StagedDir::staging_path(&dir), dir] {
            if d.is_dir() {
                remove_ours(&d)?;
            }
        }
    }
    if jobs_dir.read_dir().is_ok_and(|mut d| d.next().is_none()) {
        std::fs::remove_dir(&jobs_dir).map_err(|e| io_err(&jobs_dir, e))?;
    }
    for name in SWEEP_FILES {
        let f = out.join(name);
        if f.is_file() {
            std::fs::remove_file(&f).map_err(|e| io_err(&f, e))?;
        }
    }
    Ok(())
}

/// A job id as plans hold them: 16 lowercase hexadecimal digits (never a path).
fn is_job_id(id: &str) -> bool {
    id.len() == 16
        && id
            .bytes()
            .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b))
}

/// Runs one job of a sweep into `dir` (resuming it if a checkpoint is there) and marks it
/// `DONE`; with `line` (e.g. `job ID (3/8 here)`), prints plain progress lines under that name.
fn run_job(sweep: &Sweep, job: &Job, dir: &Path, line: Option<String>) -> Result<(), CliError> {
    let loaded = sweep.load_job(job)?;
    let progress = match line {
        Some(line) => Progress::new(&loaded.experiment, 1, false)
            .named(&format!("{line} {} seed {}", job.key, job.seed)),
        None => Progress::hidden(),
    };
    execute_or_resume(&loaded, dir, &progress, false)?;
    write_atomic(&dir.join("job.json"), to_json(job))?;
    write_atomic(&dir.join("DONE"), "")
}

/// Runs `job` on every item, as many at a time as the thread pool has threads (one at a time
/// with `--threads 1`): one lane per thread ([`rayon::broadcast`]), each taking the next item
/// until none is left. Each item (a run) also evaluates its populations in parallel, so a thread
/// whose own run waits at the end of a generation takes work from the others, and no core idles
/// while one run trains its maps or writes its files. Results come in item order and do not
/// depend on the timing: items are independent. After an error or a panic no new item starts;
/// the first error in item order is returned (a panic goes on once the lanes have stopped).
pub fn run_concurrently<T, R>(
    items: &[T],
    job: impl Fn(&T) -> Result<R, CliError> + Sync,
) -> Result<Vec<R>, CliError>
where
    T: Sync,
    R: Send,
{
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let results: Vec<Mutex<Option<Result<R, CliError>>>> =
        items.iter().map(|_| Default::default()).collect();
    rayon::broadcast(|_| {
        let _on_panic = StopOnPanic(&stop);
        while !stop.load(Ordering::Relaxed) {
            let k = next.fetch_add(1, Ordering::Relaxed);
            let Some(item) = items.get(k) else { break };
            let result = job(item);
            stop.fetch_or(result.is_err(), Ordering::Relaxed);
            *results[k].lock().unwrap_or_else(PoisonError::into_inner) = Some(result);
        }
    });
    results
        .into_iter()
        .filter_map(|r| r.into_inner().unwrap_or_else(PoisonError::into_inner))
        .collect()
}

/// Tells the other lanes of [`run_concurrently`] to start nothing new when its lane panics.
struct StopOnPanic<'a>(&'a AtomicBool);

impl Drop for StopOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.store(true, Ordering::Relaxed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    }

    /// Results come in item order whatever the number of threads, and the items really run
    /// side by side when there are threads for it.
    #[test]
    fn runs_come_back_in_item_order() {
        let items: Vec<u64> = (0..9).collect();
        for threads in [1, 2, 4] {
            let at_once = AtomicUsize::new(0);
            let most = AtomicUsize::new(0);
            let got = pool(threads).install(|| {
                run_concurrently(&items, |&k| {
                    let now = at_once.fetch_add(1, Ordering::SeqCst) + 1;
                    most.fetch_max(now, Ordering::SeqCst);
                    std::thread::sleep(std::time::Duration::from_millis(20));
                    at_once.fetch_sub(1, Ordering::SeqCst);
                    Ok(k * k)
                })
            });
            assert_eq!(
                got.unwrap(),
                items.iter().map(|k| k * k).collect::<Vec<_>>()
            );
            let most = most.into_inner();
            assert!(most <= threads, "{most} at once on {threads} threads");
            assert!(
                threads == 1 || most >= 2,
                "never two at once on {threads} threads"
            );
        }
    }

    /// The first error in item order is returned; no item starts after an error.
    #[test]
    fn the_first_error_in_item_order_is_returned() {
        let items: Vec<usize> = (0..40).collect();
        let started = AtomicUsize::new(0);
        let got = pool(2).install(|| {
            run_concurrently(&items, |&k| {
                started.fetch_add(1, Ordering::SeqCst);
                if k == 3 || k == 5 {
                    Err(CliError::runtime(format!("item {k} failed")))
                } else {
                    Ok(k)
                }
            })
        });
        let message = got.expect_err("an error").to_string();
        assert!(message.contains("item 3 failed"), "{message}");
        assert!(
            started.into_inner() < items.len(),
            "items started after the error"
        );
    }

    /// A panic in one lane stops the others from starting new items, then goes on.
    #[test]
    fn a_panic_stops_new_items() {
        let items: Vec<usize> = (0..40).collect();
        let started = AtomicUsize::new(0);
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool(2).install(|| {
                run_concurrently(&items, |&k| {
                    started.fetch_add(1, Ordering::SeqCst);
                    assert_ne!(k, 2, "item 2 panics");
                    // Long enough to outlast the panic hook (a backtrace takes a while).
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    Ok(k)
                })
            })
        }));
        assert!(outcome.is_err(), "the panic goes on");
        let started = started.into_inner();
        assert!(started < items.len(), "all {started} items started");
    }
}
