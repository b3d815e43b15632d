//! The lab's runs: a list every tab sees (kept under `DIR/runs/`), a queue, and one worker
//! that runs them one at a time on a pool of `--threads` threads (as `fuzzymotiv run` would),
//! each through the run-directory pipeline, so a finished run is a normal run directory.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};

use fuzzymotiv::experiment::GenerationState;
use fuzzymotiv_pipeline::files::guard::StagedDir;
use fuzzymotiv_pipeline::pipeline::progress::NoProgress;
use fuzzymotiv_pipeline::pipeline::run_dir::execute_with;
use fuzzymotiv_pipeline::records::{GenerationRow, RunSummary, read_csv, read_json};
use serde::Serialize;
use serde_json::{Value, json};
use tokio::sync::watch;

use crate::errors::ApiError;
use crate::limits::{MAX_FORGOTTEN, MAX_QUEUED, MAX_STOPPED_LISTED};
use crate::live::{Live, Shows, result};
use crate::settings::Settings;

/// The folder of the lab's run directories, under its directory.
pub const RUN_DIR: &str = "runs";

/// Where a run stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    Queued,
    Running,
    Finished,
    Stopped,
    Failed,
}

/// What a run has shown so far.
#[derive(Debug, Default)]
pub struct Shown {
    pub generations: Vec<Value>,
    pub paths: Option<Value>,
    /// Bumped whenever `paths` changes.
    pub paths_version: u64,
    pub result: Option<Value>,
    pub error: Option<String>,
}

/// One run of the lab.
pub struct RunEntry {
    pub id: String,
    /// What it is: name, seed, motivations, sizes, rooms (for the list).
    pub about: Value,
    pub settings: Option<Settings>,
    cancel: AtomicBool,
    state: Mutex<(Status, Shown)>,
    changed: watch::Sender<u64>,
}

impl RunEntry {
    fn new(id: String, about: Value, settings: Option<Settings>, status: Status) -> Self {
        Self {
            id,
            about,
            settings,
            cancel: AtomicBool::new(false),
            state: Mutex::new((status, Shown::default())),
            changed: watch::channel(0).0,
        }
    }

    /// The state, even after a panic elsewhere (it holds plain data).
    pub fn lock(&self) -> MutexGuard<'_, (Status, Shown)> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A receiver woken at every change.
    pub fn subscribe(&self) -> watch::Receiver<u64> {
        self.changed.subscribe()
    }

    fn update(&self, f: impl FnOnce(&mut (Status, Shown))) {
        f(&mut self.lock());
        self.changed.send_modify(|v| *v += 1);
    }

    pub fn status(&self) -> Status {
        self.lock().0
    }

    fn end(&self, status: Status, result: Option<Value>, error: Option<String>) {
        self.record_end(status, result, error);
        self.announce();
    }

    /// Sets the end in the state without waking the event streams (see [`Runs::work`]).
    fn record_end(&self, status: Status, result: Option<Value>, error: Option<String>) {
        let s = &mut *self.lock();
        s.0 = status;
        if let Some(r) = &result {
            s.1.paths = r.get("paths").cloned();
            s.1.paths_version += 1;
        }
        s.1.result = result;
        s.1.error = error;
    }

    /// Wakes the event streams: the state changed.
    fn announce(&self) {
        self.changed.send_modify(|v| *v += 1);
    }

    pub fn is_cancelled(&self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }
}

impl Shows for RunEntry {
    fn push_generation(&self, g: Value) {
        self.update(|s| s.1.generations.push(g));
    }

    fn set_paths(&self, p: Value) {
        self.update(|s| {
            s.1.paths = Some(p);
            s.1.paths_version += 1;
        });
    }

    fn is_cancelled(&self) -> bool {
        RunEntry::is_cancelled(self)
    }
}

/// The runs of a lab and its queue.
pub struct Runs {
    dir: PathBuf,
    /// The room files of the config the lab started on, which runs may name.
    config_rooms: Vec<String>,
    list: Mutex<Vec<Arc<RunEntry>>>,
    queue: Mutex<VecDeque<Arc<RunEntry>>>,
    wake: Condvar,
    closing: AtomicBool,
    count: AtomicU64,
}

impl Runs {
    /// The runs of `dir`: the finished run directories under `DIR/runs/`; runs may name the
    /// room files `config_rooms` (the start config's).
    pub fn open(dir: &Path, config_rooms: Vec<String>) -> Self {
        let runs = Self {
            dir: dir.to_path_buf(),
            config_rooms,
            list: Mutex::new(Vec::new()),
            queue: Mutex::new(VecDeque::new()),
            wake: Condvar::new(),
            closing: AtomicBool::new(false),
            count: AtomicU64::new(0),
        };
        let mut found = finished_on_disk(&dir.join(RUN_DIR));
        found.sort_by(|a, b| a.id.cmp(&b.id));
        *runs.list() = found.into_iter().map(Arc::new).collect();
        runs
    }

    fn list(&self) -> MutexGuard<'_, Vec<Arc<RunEntry>>> {
        self.list.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn queue(&self) -> MutexGuard<'_, VecDeque<Arc<RunEntry>>> {
        self.queue.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Every run, oldest first, with its queue position (1 = next).
    pub fn summaries(&self) -> Vec<Value> {
        let queue: Vec<String> = self.queue().iter().map(|e| e.id.clone()).collect();
        self.list()
            .iter()
            .map(|e| {
                let pos = queue.iter().position(|q| *q == e.id).map(|p| p + 1);
                let (status, shown) = &*e.lock();
                json!({ "id": e.id, "about": e.about, "status": status, "queue_position": pos,
                        "generations": shown.generations.len(), "error": shown.error })
            })
            .collect()
    }

    /// Checks `settings` and resolves them into a config ready to run.
    pub fn load(
        &self,
        settings: &Settings,
    ) -> Result<fuzzymotiv_pipeline::files::inputs::Loaded, ApiError> {
        settings.load(&self.dir, &self.config_rooms)
    }

    pub fn get(&self, id: &str) -> Option<Arc<RunEntry>> {
        self.list().iter().find(|e| e.id == id).cloned()
    }

    /// Queues a run of `settings` (checked first: a bad one is refused here, not later).
    pub fn submit(&self, settings: Settings) -> Result<Arc<RunEntry>, ApiError> {
        let loaded = self.load(&settings)?;
        if self.closing.load(Ordering::SeqCst) {
            return Err(ApiError::busy("the lab is shutting down"));
        }
        let mut queue = self.queue();
        if queue.len() >= MAX_QUEUED {
            return Err(ApiError::busy(format!(
                "{MAX_QUEUED} runs are waiting already; stop some or wait"
            )));
        }
        let id = self.fresh_id(&loaded.raw.name, loaded.raw.seed);
        let about = about(&settings, &loaded);
        let entry = Arc::new(RunEntry::new(id, about, Some(settings), Status::Queued));
        self.list().push(entry.clone());
        queue.push_back(entry.clone());
        drop(queue);
        self.forget_old();
        self.wake.notify_all();
        Ok(entry)
    }

    /// An id no run of this lab has, nor any folder under `DIR/runs/`.
    fn fresh_id(&self, name: &str, seed: u64) -> String {
        loop {
            let n = self.count.fetch_add(1, Ordering::SeqCst) + 1;
            let id = format!("{name}-seed{seed}-{n}");
            let out = self.dir.join(RUN_DIR).join(&id);
            let taken =
                self.get(&id).is_some() || out.exists() || StagedDir::staging_path(&out).exists();
            if !taken {
                return id;
            }
        }
    }

    /// Stops a run: a queued one leaves the queue, a running one stops after its generation.
    pub fn cancel(&self, id: &str) -> Result<Status, ApiError> {
        let entry = self
            .get(id)
            .ok_or_else(|| ApiError::not_found(format!("no run `{id}` in this lab")))?;
        entry.cancel.store(true, Ordering::SeqCst);
        let was_queued = {
            let mut queue = self.queue();
            let before = queue.len();
            queue.retain(|e| e.id != id);
            queue.len() != before
        };
        if was_queued {
            entry.end(Status::Stopped, None, None);
        }
        Ok(entry.status())
    }

    /// Keeps memory bounded while ended runs stay listed: beyond the newest [`MAX_FORGOTTEN`]
    /// ended runs (finished, stopped or failed), their curves and paths are let go (a finished
    /// run keeps its result, and its files are on disk); beyond [`MAX_STOPPED_LISTED`] stopped
    /// or failed runs, the oldest of them leave the list.
    fn forget_old(&self) {
        let mut list = self.list();
        let gone = |e: &Arc<RunEntry>| matches!(e.status(), Status::Stopped | Status::Failed);
        let count = list.iter().filter(|e| gone(e)).count();
        let mut unlisted = count.saturating_sub(MAX_STOPPED_LISTED);
        list.retain(|e| {
            let drop_it = unlisted > 0 && gone(e);
            unlisted -= usize::from(drop_it);
            !drop_it
        });
        // Curves and paths are let go for every ended run but the newest few (finished runs
        // too: a lab under load ends thousands, and each held its curves for good).
        let ended = |e: &Arc<RunEntry>| gone(e) || e.status() == Status::Finished;
        let old = list
            .iter()
            .filter(|e| ended(e))
            .count()
            .saturating_sub(MAX_FORGOTTEN);
        for e in list.iter().filter(|e| ended(e)).take(old) {
            let mut state = e.lock();
            state.1.generations = Vec::new();
            state.1.paths = None;
        }
    }

    /// Stops every run and the worker.
    pub fn close(&self) {
        self.closing.store(true, Ordering::SeqCst);
        for e in self.list().iter() {
            e.cancel.store(true, Ordering::SeqCst);
        }
        let queued: Vec<_> = self.queue().drain(..).collect();
        for e in queued {
            e.end(Status::Stopped, None, None);
        }
        self.wake.notify_all();
    }

    /// The next run to do, waiting for one; `None` once closing.
    fn next(&self) -> Option<Arc<RunEntry>> {
        let mut queue = self.queue();
        loop {
            if self.closing.load(Ordering::SeqCst) {
                return None;
            }
            if let Some(e) = queue.pop_front() {
                return Some(e);
            }
            queue = self.wake.wait(queue).unwrap_or_else(|e| e.into_inner());
        }
    }

    /// The worker: runs the queue one run at a time on `pool` until the lab closes. A run's
    /// end is announced once the older runs' curves are let go, so that a client told of the
    /// end sees the list as it stays.
    pub fn work(&self, pool: &rayon::ThreadPool) {
        while let Some(entry) = self.next() {
            entry.update(|s| s.0 = Status::Running);
            let (status, result, error) = pool.install(|| self.execute(&entry));
            entry.record_end(status, result, error);
            self.forget_old();
            entry.announce();
        }
    }

    /// Runs `entry`: its end (status, what it shows, the error).
    fn execute(&self, entry: &RunEntry) -> (Status, Option<Value>, Option<String>) {
        let Some(settings) = &entry.settings else {
            return (Status::Failed, None, Some("a run without settings".into()));
        };
        let loaded = match self.load(settings) {
            Ok(l) => l,
            Err(e) => return (Status::Failed, None, Some(e.message)),
        };
        let out = self.dir.join(RUN_DIR).join(&entry.id);
        let mut live = Live::new(&loaded.experiment, entry);
        let mut hook = |s: &GenerationState<'_>| live.on_generation(s);
        let done = execute_with(&loaded, &out, &NoProgress, false, None, &mut hook);
        match done {
            Ok(done) => (
                Status::Finished,
                Some(result(&loaded.experiment, &done)),
                None,
            ),
            Err(e) => {
                // A stopped run's staging folder is the lab's own: nothing of it is kept.
                let _ = std::fs::remove_dir_all(StagedDir::staging_path(&out));
                if entry.is_cancelled() {
                    (Status::Stopped, None, None)
                } else {
                    (Status::Failed, None, Some(e.to_string()))
                }
            }
        }
    }

    /// The run directory of a finished run.
    pub fn run_dir(&self, id: &str) -> PathBuf {
        self.dir.join(RUN_DIR).join(id)
    }
}

/// What the list says of a run: its robot, its motivations' weights in input order, and their
/// names.
fn about(s: &Settings, loaded: &fuzzymotiv_pipeline::files::inputs::Loaded) -> Value {
    let raw = &loaded.raw;
    let m = &raw.motivations.list;
    let robot = loaded.experiment.trial_params().robot().spec().name();
    json!({ "name": raw.name, "seed": raw.seed, "population": s.population,
            "generations": s.generations, "rooms": raw.rooms, "combine": raw.fitness.combine,
            "robot": robot, "notes": loaded.notes,
            "motivations": m.iter().map(|(_, w)| w.weight()).collect::<Vec<_>>(),
            "motivation_names": m.iter().map(|(n, _)| n).collect::<Vec<_>>() })
}

/// The finished run directories under `runs` (those of earlier sessions too).
fn finished_on_disk(runs: &Path) -> Vec<RunEntry> {
    let dirs = std::fs::read_dir(runs).into_iter().flatten().flatten();
    dirs.filter_map(|d| {
        let id = d.file_name().into_string().ok()?;
        let summary: RunSummary = read_json(&d.path().join("summary.json")).ok()?;
        let rows: Vec<GenerationRow> = read_csv(&d.path().join("generations.csv")).ok()?;
        let m = &summary.motivations;
        let about = json!({ "name": summary.name, "seed": summary.seed,
            "population": summary.population, "generations": summary.generations,
            "rooms": summary.rooms.iter().map(|r| r.room.clone()).collect::<Vec<_>>(),
            "motivations": m });
        let entry = RunEntry::new(id, about, None, Status::Finished);
        let generations = rows.iter().map(generation_json).collect();
        let result = json!({ "rows": summary.rooms, "wall_seconds": summary.wall_seconds });
        entry.update(|s| {
            s.1.generations = generations;
            s.1.result = Some(result);
        });
        Some(entry)
    })
    .collect()
}

/// A row of `generations.csv` as the page's generation event.
fn generation_json(r: &GenerationRow) -> Value {
    json!({ "label": r.room, "generation": r.generation, "best": r.best.0, "mean": r.mean.0,
            "min": r.min.0, "std": r.std.0, "a": r.a.0, "g": r.g.0, "l": r.l.0, "b": r.b.0 })
}
