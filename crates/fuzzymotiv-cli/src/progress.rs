//! Progress on stderr: a bar on a terminal; otherwise (SLURM, `nohup`, `| tee`) one plain line
//! every few seconds; nothing with `--quiet`.

use std::cell::Cell;
use std::io::IsTerminal;
use std::time::{Duration, Instant};

use fuzzymotiv::experiment::Experiment;
use indicatif::{ProgressBar, ProgressStyle};

/// Seconds between two plain progress lines.
const PLAIN_INTERVAL: Duration = Duration::from_secs(5);

/// Progress over all generations of one or more experiments.
pub struct Progress {
    bar: ProgressBar,
    /// Plain lines instead of a bar (stderr is not a terminal).
    plain: bool,
    quiet: bool,
    prefix: std::cell::RefCell<String>,
    total: u64,
    /// Generations counted so far, and those done before a resume (not timed here).
    pos: Cell<u64>,
    skipped: Cell<u64>,
    start: Instant,
    last_line: Cell<Option<Instant>>,
}

impl Progress {
    /// Progress over all generations of `settings` experiments like `exp`.
    pub fn new(exp: &Experiment, settings: usize, quiet: bool) -> Self {
        let total = (exp.runs().len() * exp.ga().generations * settings) as u64;
        let plain = !std::io::stderr().is_terminal();
        let bar = if quiet || plain {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::new(total);
            bar.set_style(
                ProgressStyle::with_template(
                    "{prefix} [{elapsed_precise}] {wide_bar} gen {pos}/{len} {msg} (eta {eta})",
                )
                .expect("valid template"),
            );
            bar.enable_steady_tick(Duration::from_millis(500));
            bar
        };
        Self {
            bar,
            plain,
            quiet,
            prefix: Default::default(),
            total,
            pos: Cell::new(0),
            skipped: Cell::new(0),
            start: Instant::now(),
            last_line: Cell::new(None),
        }
    }

    /// No output at all (e.g. a sweep's jobs under the sweep's own bar).
    pub fn hidden() -> Self {
        Self {
            bar: ProgressBar::hidden(),
            plain: false,
            quiet: true,
            prefix: Default::default(),
            total: 0,
            pos: Cell::new(0),
            skipped: Cell::new(0),
            start: Instant::now(),
            last_line: Cell::new(None),
        }
    }

    /// Names what is running, e.g. `high-curiosity seed 1`.
    pub fn set_prefix(&self, prefix: &str) {
        self.bar.set_prefix(prefix.to_string());
        *self.prefix.borrow_mut() = prefix.to_string();
    }

    /// A one-line note on stderr (unless quiet), above the bar.
    pub fn note(&self, message: &str) {
        if !self.quiet {
            self.bar.suspend(|| eprintln!("{message}"));
        }
    }

    /// Generations done before a resume.
    pub fn skip(&self, n: usize) {
        self.bar.inc(n as u64);
        self.pos.set(self.pos.get() + n as u64);
        self.skipped.set(self.skipped.get() + n as u64);
    }

    /// Generation `g` (1-based) of `of` of run `run` finished with best F `best`.
    pub fn generation(&self, run: &str, g: usize, of: usize, best: f64) {
        self.bar.inc(1);
        self.bar.set_message(format!("best F {best:.3}"));
        self.pos.set(self.pos.get() + 1);
        if self.quiet || !self.plain {
            return;
        }
        let now = Instant::now();
        let due = self
            .last_line
            .get()
            .is_none_or(|t| now - t >= PLAIN_INTERVAL);
        if g == 1 || g == of || due {
            self.last_line.set(Some(now));
            eprintln!("{}", self.line(run, g, of, best));
        }
    }

    fn line(&self, run: &str, g: usize, of: usize, best: f64) -> String {
        let elapsed = self.start.elapsed().as_secs_f64();
        let timed = (self.pos.get() - self.skipped.get()) as f64;
        let left = self.total.saturating_sub(self.pos.get()) as f64;
        let eta = if timed > 0.0 {
            clock(elapsed / timed * left)
        } else {
            "?".to_string()
        };
        let prefix = self.prefix.borrow();
        let run = if run.is_empty() || run == "all" {
            String::new()
        } else {
            format!(", robot of {run}")
        };
        format!(
            "{prefix}{run}: generation {g}/{of}, best F {best:.3}, elapsed {}, ETA {eta}",
            clock(elapsed)
        )
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
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
