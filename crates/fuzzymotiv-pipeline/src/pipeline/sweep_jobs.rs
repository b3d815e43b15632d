//! A sweep's jobs run into `DIR/jobs/ID/` (each a run directory, [`super::run_dir`]), and
//! the sweep directory they share: who may run in it, and what `--force` removes. A job runs
//! under its lock ([`JobLock`]): a worker that finds a job locked waits, then skips it if it
//! was finished meanwhile or resumes it if its holder died.

use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::files::guard::{
    OutputError, StagedDir, ensure_replaceable, foreign_files, io_err, refuse_current_dir,
    refuse_non_directory, refuse_staging_name, remove_ours, write_atomic,
};
use crate::files::job_lock::{JobLock, lock_path};
use crate::files::notes::Notes;
use crate::pipeline::lanes::run_concurrently;
use crate::pipeline::progress::{JobsSummary, SweepProgress};
use crate::pipeline::run_dir::execute_or_resume;
use crate::pipeline::sweep_plan::Sweep;
use crate::records::{Job, to_json};

/// What became of one job of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JobOutcome {
    /// It ran (or resumed) here and is finished.
    Ran,
    /// It was finished already (by this or another worker); nothing ran.
    Skipped,
    /// Another worker holds its lock and waiting was not asked for; nothing ran.
    Running,
}

impl JobOutcome {
    /// `ran`, `skipped` or `running`.
    pub fn as_str(self) -> &'static str {
        match self {
            JobOutcome::Ran => "ran",
            JobOutcome::Skipped => "skipped",
            JobOutcome::Running => "running",
        }
    }
}

/// Runs the `selected` jobs of `sweep` into `out/jobs/ID/`, skipping finished ones, as many at
/// a time as there are threads ([`run_concurrently`]), reporting to `progress` (the command
/// line: on a terminal a bar counts jobs; otherwise each job prints plain progress lines), its
/// notes included (how many jobs ran, of how many).
pub fn run_jobs(
    sweep: &Sweep,
    text: &str,
    selected: &[usize],
    out: &Path,
    force: bool,
    progress: &dyn SweepProgress,
) -> Result<(), CliError> {
    let jobs_dir = prepare_sweep_dir(sweep, text, out, force, progress)?;
    let todo: Vec<usize> = selected
        .iter()
        .copied()
        .filter(|&k| !is_done(&jobs_dir, &sweep.jobs[k]))
        .collect();
    let skipped = selected.len() - todo.len();
    progress.begin(selected.len(), skipped);
    let numbered: Vec<(usize, usize)> = todo.iter().copied().enumerate().collect();
    let outcomes = run_concurrently(&numbered, |&(n, k)| {
        let outcome = run_job(
            sweep,
            &sweep.jobs[k],
            &jobs_dir,
            true,
            progress,
            skipped + n + 1,
        )?;
        progress.job_done();
        Ok(outcome)
    })?;
    let ran = outcomes.iter().filter(|&&o| o == JobOutcome::Ran).count();
    progress.end(&JobsSummary {
        ran,
        already_done: selected.len() - ran,
        selected: selected.len(),
        planned: sweep.jobs.len(),
    });
    Ok(())
}

/// Runs job `index` of `sweep` into the sweep directory `out` as `fuzzymotiv sweep --index` does
/// (the same checks of `out`, the same files; `text` is the sweep file's text), unless it is
/// finished. A job another worker holds is waited for when `wait`, else left to it
/// ([`JobOutcome::Running`]). Many workers may call this at once on one `out`.
pub fn run_one_job(
    sweep: &Sweep,
    text: &str,
    index: usize,
    out: &Path,
    wait: bool,
    progress: &dyn SweepProgress,
) -> Result<JobOutcome, CliError> {
    let job = sweep.jobs.get(index).ok_or_else(|| {
        CliError::input(format!(
            "job index {index} is out of range: the plan has {} jobs",
            sweep.jobs.len()
        ))
    })?;
    let jobs_dir = prepare_sweep_dir(sweep, text, out, false, progress)?;
    if is_done(&jobs_dir, job) {
        return Ok(JobOutcome::Skipped);
    }
    run_job(sweep, job, &jobs_dir, wait, progress, 1)
}

/// Checks `out` for `sweep` as `fuzzymotiv sweep` checks `--out` (with `force`, another plan's
/// sweep is replaced, which is said to `notes`) and writes its plan and sweep file; returns its
/// `jobs/` folder.
pub fn prepare_sweep_dir(
    sweep: &Sweep,
    text: &str,
    out: &Path,
    force: bool,
    notes: &dyn Notes,
) -> Result<PathBuf, CliError> {
    open_sweep_dir(sweep, out, force, notes)?;
    // The plan first: it is what makes the directory a sweep for the tasks that start with this.
    std::fs::create_dir_all(out).map_err(|e| io_err(out, e))?;
    write_atomic(&out.join("plan.jsonl"), sweep.plan_jsonl())?;
    write_atomic(&out.join(sweep.file_name()), text)?;
    let jobs_dir = out.join("jobs");
    std::fs::create_dir_all(&jobs_dir).map_err(|e| io_err(&jobs_dir, e))?;
    Ok(jobs_dir)
}

/// Whether `job` is finished in `jobs_dir`.
fn is_done(jobs_dir: &Path, job: &Job) -> bool {
    jobs_dir.join(&job.id).join("DONE").is_file()
}

/// The files of a sweep directory besides its job folders (written by `sweep` and `merge`, or
/// by a study: [`crate::study`]).
const SWEEP_FILES: [&str; 14] = [
    "plan.jsonl",
    "sweep.toml",
    "study.toml",
    "per_seed.csv",
    "claims.csv",
    "rooms.csv",
    "study.json",
    "report.md",
    "forest.svg",
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
/// a fuzzymotiv output, a file, a `.partial` name and the current directory are refused. What
/// `force` keeps or removes is said to `notes`.
fn open_sweep_dir(
    sweep: &Sweep,
    out: &Path,
    force: bool,
    notes: &dyn Notes,
) -> Result<(), CliError> {
    refuse_current_dir(out)?;
    refuse_staging_name(out)?;
    refuse_non_directory(out)?;
    if !out.exists() {
        return Ok(());
    }
    let plan = out.join("plan.jsonl");
    if !plan.is_file() {
        // A task starting beside this one may write its plan while `out` is listed (by a
        // rename: a plan seen once stays), so the plan is looked for again after the listing.
        let starting = starting_sweep(out);
        if !plan.is_file() {
            return if starting {
                Ok(())
            } else {
                refuse_other_output(out, force, notes)
            };
        }
    }
    let old = Job::read_plan(&plan)?;
    let conflict = plan_conflict(&old, &sweep.jobs);
    let same_plan = conflict.is_none() && old.len() == sweep.jobs.len();
    if force && same_plan {
        // Safe in an array script whose every task passes --force: nothing is lost.
        notes.note(&format!(
            "note: --force: the sweep in {} has this very plan; its finished jobs are kept \
             (remove the directory yourself to run them again)",
            out.display()
        ));
        return Ok(());
    }
    if force {
        notes.note(&format!(
            "note: --force: the sweep in {} will be replaced",
            out.display()
        ));
        return remove_sweep(out, &old);
    }
    match conflict {
        None => Ok(()),
        Some(why) => Err(OutputError::OtherPlan {
            dir: out.to_path_buf(),
            why,
        }
        .into()),
    }
}

/// `out` holds another fuzzymotiv output (or something else): removed with `force`, else an
/// error.
fn refuse_other_output(out: &Path, force: bool, notes: &dyn Notes) -> Result<(), CliError> {
    ensure_replaceable(out)?;
    if !force {
        return Err(OutputError::NotASweep {
            dir: out.to_path_buf(),
        }
        .into());
    }
    notes.note(&format!(
        "note: --force: {} will be replaced",
        out.display()
    ));
    remove_ours(out)
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
    if let Some(o) = old.iter().find(|o| o.model != fuzzymotiv::MODEL_VERSION) {
        return Some(format!(
            "it was planned by model {} of fuzzymotiv, and this build is model {}, whose \
             results differ (finishing it would mix two models in one sweep)",
            o.model,
            fuzzymotiv::MODEL_VERSION
        ));
    }
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

/// Removes a sweep's own files and its jobs' folders (their staging folders and locks) from `out`;
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
        let lock = lock_path(&jobs_dir, &job.id);
        if lock.is_file() {
            std::fs::remove_file(&lock).map_err(|e| io_err(&lock, e))?;
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

/// Runs one job of a sweep into `jobs_dir/ID/` under its lock (waited for when `wait`),
/// resuming it if a checkpoint is there, and marks it `DONE`, reporting to the progress
/// `progress` gives it as the `nth` job of the selection. A job finished while this worker
/// waited is skipped.
fn run_job(
    sweep: &Sweep,
    job: &Job,
    jobs_dir: &Path,
    wait: bool,
    progress: &dyn SweepProgress,
    nth: usize,
) -> Result<JobOutcome, CliError> {
    let _lock = if wait {
        JobLock::acquire(jobs_dir, &job.id, progress)?
    } else {
        match JobLock::try_acquire(jobs_dir, &job.id)? {
            Some(lock) => lock,
            None => return Ok(JobOutcome::Running),
        }
    };
    if is_done(jobs_dir, job) {
        return Ok(JobOutcome::Skipped);
    }
    let dir = jobs_dir.join(&job.id);
    let loaded = sweep.load_job(job)?;
    let progress = progress.job(job, nth, &loaded.experiment);
    execute_or_resume(&loaded, &dir, &*progress, None)?;
    write_atomic(&dir.join("job.json"), to_json(job))?;
    write_atomic(&dir.join("DONE"), "")?;
    Ok(JobOutcome::Ran)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::notes::NoteList;
    use crate::pipeline::progress::NoProgress;

    /// Issue #56 item 2: what `--force` does to a sweep directory is said to the caller's
    /// notes (the CLI prints them, Python warns), not printed by the library.
    #[test]
    fn force_on_a_sweep_directory_is_a_note_to_the_caller() {
        let one = "[sweep]\nreplicates = 1\nmotivations = [[0.8, 0.1, 0.0, 0.1]]\n";
        let two = "[sweep]\nreplicates = 2\nmotivations = [[0.8, 0.1, 0.0, 0.1]]\n";
        let parse = |t| Sweep::parse_str(t, "sweep.toml", Path::new(".")).unwrap();
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("s");
        let notes = NoteList::default();
        prepare_sweep_dir(&parse(two), two, &out, false, &notes).unwrap();
        assert!(notes.take().is_empty());
        prepare_sweep_dir(&parse(two), two, &out, true, &notes).unwrap();
        assert_eq!(notes.take().len(), 1);
        prepare_sweep_dir(&parse(one), one, &out, true, &notes).unwrap();
        assert_eq!(
            notes.take(),
            [format!(
                "note: --force: the sweep in {} will be replaced",
                out.display()
            )]
        );
    }

    /// Tasks of one sweep starting at once all join it: none mistakes the directory another is
    /// setting up for a foreign output. Repeated, as the window is a few system calls wide:
    /// with the plan looked for only before the listing, this failed by round 30 in each of
    /// three tries (as `fm.sweep`'s threads once did in CI).
    #[test]
    fn tasks_starting_together_all_join_the_sweep() {
        let text = "[sweep]\nreplicates = 2\nmotivations = [[0.8, 0.1, 0.0, 0.1]]\n";
        let sweep = Sweep::parse_str(text, "sweep.toml", Path::new(".")).unwrap();
        let tmp = tempfile::tempdir().unwrap();
        for round in 0..300 {
            let out = tmp.path().join(round.to_string());
            std::thread::scope(|s| {
                let tasks: Vec<_> = (0..4)
                    .map(|_| s.spawn(|| prepare_sweep_dir(&sweep, text, &out, false, &NoProgress)))
                    .collect();
                for t in tasks {
                    if let Err(e) = t.join().unwrap() {
                        panic!("round {round}: {e}");
                    }
                }
            });
        }
    }
}
