//! Progress on stderr: a bar on a terminal; otherwise (SLURM, `nohup`, `| tee`) one plain line
//! every few seconds; nothing with `--quiet`. [`Progress`] shows runs (the pipeline's
//! [`RunProgress`]), [`JobsProgress`] a sweep's jobs ([`SweepProgress`]), [`ReproduceBar`] a
//! study's runs ([`ReproduceProgress`]). The pipeline's notes go to stderr as they come, with
//! `--quiet` too. The kill tests' abort point ([`kill_point`]) is here, in the binary.

use crate::console::note;
use std::io::IsTerminal;
use std::sync::LazyLock;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, PoisonError};
use std::time::{Duration, Instant};

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv_pipeline::files::notes::Notes;
use fuzzymotiv_pipeline::pipeline::progress::{JobsSummary, RunProgress, SweepProgress};
use fuzzymotiv_pipeline::pipeline::reproduce::ReproduceProgress;
use fuzzymotiv_pipeline::records::Job;
use indicatif::{ProgressBar, ProgressStyle};

/// Seconds between two plain progress lines.
const PLAIN_INTERVAL: Duration = Duration::from_secs(5);

/// Generations timed before an ETA is shown. The first one warms up (rooms prepared, tables of
/// sightings filled, threads started) and says little of the rest: the rate comes from the
/// generations after it, so none is shown before a few of them are done.
const ETA_AFTER: u64 = 3;

/// Progress over all generations of one or more experiments, or a view of it for one run
/// ([`Progress::named`]); runs may go on side by side, each with its own view.
pub struct Progress {
    shared: Arc<Shared>,
    /// The run this view is for, e.g. `high-curiosity seed 1` (none for the whole).
    name: Option<String>,
    /// When this view last printed a plain line.
    last_line: Mutex<Option<Instant>>,
}

/// What the views of one progress share.
struct Shared {
    bar: ProgressBar,
    /// Plain lines instead of a bar (stderr is not a terminal).
    plain: bool,
    quiet: bool,
    total: u64,
    /// Generations counted so far, and those done before a resume (not timed here).
    pos: AtomicU64,
    skipped: AtomicU64,
    start: Instant,
    /// When the first generation timed here was done (the end of the warm-up).
    first_done: OnceLock<Instant>,
    /// The names of the runs going on, shown before the bar.
    running: Mutex<Vec<String>>,
}

/// The lock, also after a panic elsewhere (progress is only shown, never relied on).
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

impl Progress {
    /// Progress over all generations of `settings` experiments like `exp`.
    pub fn new(exp: &Experiment, settings: usize, quiet: bool) -> Self {
        let total = (exp.runs().len() * exp.ga().generations() * settings) as u64;
        let plain = !std::io::stderr().is_terminal();
        let bar = if quiet || plain {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::new(total);
            bar.set_style(
                ProgressStyle::with_template(
                    "{prefix} [{elapsed_precise}] {wide_bar} gen {pos}/{len} {msg}",
                )
                .expect("valid template"),
            );
            bar.enable_steady_tick(Duration::from_millis(500));
            bar
        };
        Self::with_bar(bar, plain, quiet, total)
    }

    /// No output at all (e.g. a sweep's jobs under the sweep's own bar).
    pub fn hidden() -> Self {
        Self::with_bar(ProgressBar::hidden(), false, true, 0)
    }

    fn with_bar(bar: ProgressBar, plain: bool, quiet: bool, total: u64) -> Self {
        let shared = Shared {
            bar,
            plain,
            quiet,
            total,
            pos: AtomicU64::new(0),
            skipped: AtomicU64::new(0),
            start: Instant::now(),
            first_done: OnceLock::new(),
            running: Mutex::new(Vec::new()),
        };
        Self {
            shared: Arc::new(shared),
            name: None,
            last_line: Mutex::new(None),
        }
    }

    /// A view for one run, named e.g. `high-curiosity seed 1`: its plain lines start with the
    /// name (one every few seconds for each run), and the bar shows it (with the other runs
    /// going on) for as long as the view lives.
    pub fn named(&self, name: &str) -> Progress {
        let mut running = lock(&self.shared.running);
        running.push(name.to_string());
        self.shared.bar.set_prefix(bar_prefix(&running));
        Progress {
            shared: Arc::clone(&self.shared),
            name: Some(name.to_string()),
            last_line: Mutex::new(None),
        }
    }

    /// A one-line note on stderr (unless quiet), above the bar.
    pub fn note(&self, message: &str) {
        if !self.shared.quiet {
            self.shared.bar.suspend(|| note!("{message}"));
        }
    }

    /// Generations done before a resume.
    pub fn skip(&self, n: usize) {
        self.shared.bar.inc(n as u64);
        self.shared.pos.fetch_add(n as u64, Ordering::Relaxed);
        self.shared.skipped.fetch_add(n as u64, Ordering::Relaxed);
    }

    /// Generation `g` (1-based) of `of` of run `run` finished with best F `best`.
    pub fn generation(&self, run: &str, g: usize, of: usize, best: f64) {
        let shared = &self.shared;
        shared.first_done.get_or_init(Instant::now);
        shared.bar.inc(1);
        shared.pos.fetch_add(1, Ordering::Relaxed);
        let eta = self
            .eta()
            .map_or(String::new(), |e| format!(" (eta {})", clock(e)));
        shared.bar.set_message(format!("best F {best:.3}{eta}"));
        if shared.quiet || !shared.plain {
            return;
        }
        let mut last_line = lock(&self.last_line);
        let now = Instant::now();
        let due = last_line.is_none_or(|t| now - t >= PLAIN_INTERVAL);
        if g == 1 || g == of || due {
            *last_line = Some(now);
            note!("{}", self.line(run, g, of, best));
        }
    }

    fn line(&self, run: &str, g: usize, of: usize, best: f64) -> String {
        let shared = &self.shared;
        let elapsed = shared.start.elapsed().as_secs_f64();
        let eta = self
            .eta()
            .map_or("? (after a few generations)".to_string(), clock);
        let name = self.name.as_deref().unwrap_or("");
        let run = if run.is_empty() || run == "all" {
            String::new()
        } else {
            format!(", robot of {run}")
        };
        format!(
            "{name}{run}: generation {g}/{of}, best F {best:.3}, elapsed {}, ETA {eta}",
            clock(elapsed)
        )
    }

    /// Seconds left, once [`ETA_AFTER`] generations were timed here ([`eta_seconds`]).
    fn eta(&self) -> Option<f64> {
        let shared = &self.shared;
        let pos = shared.pos.load(Ordering::Relaxed);
        let timed = pos.saturating_sub(shared.skipped.load(Ordering::Relaxed));
        let since_first = shared.first_done.get()?.elapsed().as_secs_f64();
        eta_seconds(since_first, timed, shared.total.saturating_sub(pos))
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.shared.bar.finish_and_clear();
    }
}

impl RunProgress for Progress {
    fn note(&self, message: &str) {
        Progress::note(self, message);
    }

    fn skip(&self, n: usize) {
        Progress::skip(self, n);
    }

    fn generation(&self, run: &str, g: usize, of: usize, best: f64) {
        Progress::generation(self, run, g, of, best);
    }

    /// Asked after every generation once its checkpoint is saved: the kill tests' abort point.
    fn stop(&self) -> bool {
        kill_point();
        false
    }
}

/// The environment variable of the kill tests: `FUZZYMOTIV_TEST_ABORT_AFTER=N`.
const ABORT_AFTER: &str = "FUZZYMOTIV_TEST_ABORT_AFTER";

/// For kill tests only: with [`ABORT_AFTER`]`=N` in the environment, the process aborts (as
/// `kill -9` would: no clean-up) once N generations have been checkpointed in it, counted over
/// all its runs. A deterministic kill point, unlike a timer; the binary's alone (the libraries,
/// linked into Python and the lab, never abort).
fn kill_point() {
    static LIMIT: LazyLock<Option<usize>> =
        LazyLock::new(|| std::env::var(ABORT_AFTER).ok().and_then(|v| v.parse().ok()));
    static SAVED: AtomicUsize = AtomicUsize::new(0);
    if let Some(limit) = *LIMIT
        && SAVED.fetch_add(1, Ordering::SeqCst) + 1 >= limit
    {
        std::process::abort();
    }
}

impl Drop for Progress {
    /// A run's view leaves the bar's list of runs going on.
    fn drop(&mut self) {
        let Some(name) = &self.name else { return };
        let mut running = lock(&self.shared.running);
        if let Some(k) = running.iter().position(|r| r == name) {
            running.remove(k);
        }
        self.shared.bar.set_prefix(bar_prefix(&running));
    }
}

/// Progress of a sweep's jobs: on a terminal a bar counting jobs (showing the key of the one
/// started last); otherwise each job's plain progress lines, under its name (`job ID (3/8 here)
/// KEY seed S`); nothing with `--quiet`.
pub struct JobsProgress {
    /// Stderr is a terminal.
    terminal: bool,
    quiet: bool,
    /// The bar over the selected jobs (hidden but on a terminal), from [`SweepProgress::begin`].
    bar: OnceLock<ProgressBar>,
    /// How many jobs are selected.
    selected: AtomicUsize,
}

impl JobsProgress {
    /// Progress of a sweep's jobs, none with `quiet`.
    pub fn new(quiet: bool) -> Self {
        Self {
            terminal: std::io::stderr().is_terminal(),
            quiet,
            bar: OnceLock::new(),
            selected: AtomicUsize::new(0),
        }
    }

    /// Whether it shows nothing (`--quiet`).
    pub fn quiet(&self) -> bool {
        self.quiet
    }
}

impl Notes for JobsProgress {
    fn note(&self, line: &str) {
        note!("{line}");
    }
}

impl SweepProgress for JobsProgress {
    fn begin(&self, selected: usize, skipped: usize) {
        let bar = if self.terminal && !self.quiet {
            ProgressBar::new(selected as u64)
        } else {
            ProgressBar::hidden()
        };
        bar.inc(skipped as u64);
        self.selected.store(selected, Ordering::Relaxed);
        let _ = self.bar.set(bar);
    }

    fn job(&self, job: &Job, nth: usize, exp: &Experiment) -> Box<dyn RunProgress + '_> {
        if let Some(bar) = self.bar.get() {
            bar.set_message(job.key.clone());
        }
        let plain_lines = !(self.terminal || self.quiet);
        let line = plain_lines.then(|| {
            format!(
                "job {} ({}/{} here)",
                job.id,
                nth,
                self.selected.load(Ordering::Relaxed)
            )
        });
        Box::new(match line {
            Some(line) => {
                Progress::new(exp, 1, false).named(&format!("{line} {} seed {}", job.key, job.seed))
            }
            None => Progress::hidden(),
        })
    }

    fn job_done(&self) {
        if let Some(bar) = self.bar.get() {
            bar.inc(1);
        }
    }

    fn end(&self, summary: &JobsSummary) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
        note!("{summary}");
    }
}

/// Progress of a study's runs (`reproduce`): one [`Progress`] over all of them from
/// [`ReproduceProgress::begin`], a named view of it per run; a sweep's jobs as [`JobsProgress`];
/// nothing with `--quiet`.
pub struct ReproduceBar {
    quiet: bool,
    /// The progress over the study's runs, from [`ReproduceProgress::begin`].
    runs: OnceLock<Progress>,
}

impl ReproduceBar {
    /// Progress of a study, none with `quiet`.
    pub fn new(quiet: bool) -> Self {
        Self {
            quiet,
            runs: OnceLock::new(),
        }
    }
}

impl Notes for ReproduceBar {
    fn note(&self, line: &str) {
        note!("{line}");
    }
}

impl ReproduceProgress for ReproduceBar {
    fn begin(&self, exp: &Experiment, runs: usize) {
        let _ = self.runs.set(Progress::new(exp, runs, self.quiet));
    }

    fn run(&self, name: &str) -> Box<dyn RunProgress + '_> {
        Box::new(match self.runs.get() {
            Some(all) => all.named(name),
            None => Progress::hidden(),
        })
    }

    fn end(&self) {
        if let Some(all) = self.runs.get() {
            all.finish();
        }
    }

    fn jobs(&self) -> Box<dyn SweepProgress + '_> {
        Box::new(JobsProgress::new(self.quiet))
    }
}

/// The bar's prefix for the runs going on: their names, or the first and how many more when
/// there are more than two (the bar keeps its room on the line).
fn bar_prefix(running: &[String]) -> String {
    match running {
        [first, _, _, ..] => format!("{first} + {} more", running.len() - 1),
        _ => running.join(" + "),
    }
}

/// The seconds the `left` generations will take, from the rate of those done since the first
/// one timed (`since_first` seconds for `timed − 1` generations): none before [`ETA_AFTER`]
/// generations are timed, so that the warm-up of the first is not extrapolated.
fn eta_seconds(since_first: f64, timed: u64, left: u64) -> Option<f64> {
    (timed >= ETA_AFTER).then(|| since_first / (timed - 1) as f64 * left as f64)
}

/// Seconds as `m:ss` (or `h:mm:ss`).
fn clock(seconds: f64) -> String {
    let s = seconds.round() as u64;
    if s >= 3600 {
        format!("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
    } else {
        format!("{}:{:02}", s / 60, s % 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bar names one or two runs going on; with more, the first and how many more.
    #[test]
    fn the_bar_names_the_runs_going_on() {
        let names = |n: usize| (1..=n).map(|k| format!("seed {k}")).collect::<Vec<_>>();
        assert_eq!(bar_prefix(&names(0)), "");
        assert_eq!(bar_prefix(&names(1)), "seed 1");
        assert_eq!(bar_prefix(&names(2)), "seed 1 + seed 2");
        assert_eq!(bar_prefix(&names(5)), "seed 1 + 4 more");
    }

    /// Issue #52 item 7: no ETA is shown until a few generations are done, and then it comes
    /// from the generations after the first: a first generation of 10 s (its warm-up) and
    /// generations of 1 s after it give 97 s for 97 left, not the 970 s the first would give.
    #[test]
    fn the_first_eta_is_not_extrapolated_from_the_warm_up() {
        assert_eq!(eta_seconds(0.0, 1, 99), None);
        assert_eq!(eta_seconds(1.0, 2, 98), None);
        assert_eq!(eta_seconds(2.0, 3, 97), Some(97.0));
        let p = Progress::with_bar(ProgressBar::hidden(), true, true, 100);
        p.generation("all", 1, 100, 0.5);
        assert!(
            p.line("all", 1, 100, 0.5)
                .contains("ETA ? (after a few generations)")
        );
    }

    /// A view leaves the list when dropped; views of the same name come and go one by one.
    #[test]
    fn views_leave_the_list_when_dropped() {
        let all = Progress::hidden();
        let a = all.named("a");
        let b = all.named("b");
        let a2 = all.named("a");
        drop(a);
        assert_eq!(*lock(&all.shared.running), ["b", "a"]);
        drop(a2);
        drop(b);
        assert!(lock(&all.shared.running).is_empty());
    }
}
