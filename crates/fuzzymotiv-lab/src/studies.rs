//! The lab's studies (issue #55): a study file's text — picked from the study folder the lab
//! lists (`--studies`, default `studies/`), uploaded or pasted — checked and run by the
//! library's study pipeline (`fuzzymotiv_pipeline::study`, what `fuzzymotiv study` runs) into
//! `DIR/studies/ID/`, one study at a time in a thread of its own on a pool of the lab's
//! `--threads`. The page polls the list for progress (runs done of the total) and, once a study
//! is analysed, shows its pooled claims and its forest plot. Nothing here judges a hypothesis:
//! the claims are the library's `ClaimRow`s.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;

use fuzzymotiv_pipeline::files::bounded::read_input;
use fuzzymotiv_pipeline::files::notes::Notes;
use fuzzymotiv_pipeline::records::hypotheses::{ClaimRow, POOLED};
use fuzzymotiv_pipeline::study::{
    STUDY_FILE, Study, StudyCounter, StudyOptions, StudyOutcome, run_study,
};
use serde_json::{Value, json};

use crate::errors::ApiError;
use crate::runs::Status;

/// The folder of the lab's study directories, under its directory.
pub const STUDY_DIR: &str = "studies";

/// The source a pasted or uploaded study is named by in its errors.
const PASTED: &str = "(pasted study)";

/// One study of the lab.
pub struct StudyEntry {
    pub id: String,
    /// The study's `[study] name`.
    pub name: String,
    /// Where its text came from: a listed file, or [`PASTED`].
    pub source: String,
    /// Its runs planned.
    total: usize,
    /// Its runs finished (before or now), and the flag that stops them.
    counter: StudyCounter,
    state: Mutex<(Status, Option<Vec<ClaimRow>>, Option<String>)>,
}

impl StudyEntry {
    fn lock(&self) -> MutexGuard<'_, (Status, Option<Vec<ClaimRow>>, Option<String>)> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// What the page shows of it: status, progress, error and (analysed) the pooled claims.
    fn view(&self) -> Value {
        let (status, claims, error) = &*self.lock();
        let pooled: Option<Vec<&ClaimRow>> =
            (claims.as_ref()).map(|c| c.iter().filter(|c| c.scope == POOLED).collect());
        let mut notes = self.counter.notes();
        notes.extend(self.counter.summary().map(|s| s.to_string()));
        json!({ "id": self.id, "name": self.name, "source": self.source, "status": status,
                "done": self.counter.done(), "total": self.total,
                "error": error, "notes": notes, "claims": pooled })
    }
}

/// The studies of a lab.
pub struct Studies {
    dir: PathBuf,
    /// The folder of study files the page lists.
    folder: PathBuf,
    threads: Option<usize>,
    list: Mutex<Vec<Arc<StudyEntry>>>,
    workers: Mutex<Vec<JoinHandle<()>>>,
    count: AtomicU64,
    closing: AtomicBool,
}

impl Studies {
    /// The studies of the lab in `dir`, listing the study files of `folder`.
    pub fn new(dir: &Path, folder: PathBuf, threads: Option<usize>) -> Self {
        Self {
            dir: dir.to_path_buf(),
            folder,
            threads,
            list: Mutex::new(Vec::new()),
            workers: Mutex::new(Vec::new()),
            count: AtomicU64::new(0),
            closing: AtomicBool::new(false),
        }
    }

    fn list(&self) -> MutexGuard<'_, Vec<Arc<StudyEntry>>> {
        self.list.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The `*.toml` files of the study folder, by name, with their text.
    pub fn files(&self) -> Vec<Value> {
        let mut names: Vec<String> = (std::fs::read_dir(&self.folder).into_iter().flatten())
            .flatten()
            .filter_map(|e| e.file_name().into_string().ok())
            .filter(|n| n.ends_with(".toml"))
            .collect();
        names.sort();
        (names.into_iter())
            .filter_map(|name| {
                let text = read_input(&self.folder.join(&name), STUDY_FILE).ok()?;
                Some(json!({ "file": name, "toml": text }))
            })
            .collect()
    }

    /// Every study, newest first.
    pub fn summaries(&self) -> Vec<Value> {
        self.list().iter().rev().map(|e| e.view()).collect()
    }

    pub fn get(&self, id: &str) -> Option<Arc<StudyEntry>> {
        self.list().iter().find(|e| e.id == id).cloned()
    }

    /// The directory of study `id`.
    pub fn study_dir(&self, id: &str) -> PathBuf {
        self.dir.join(STUDY_DIR).join(id)
    }

    /// Checks the study `text` — the listed file `file` (its configs relative to the study
    /// folder) or, without one, a pasted study (configs relative to the lab's working
    /// directory) — and starts it; a bad study is refused here, naming its field.
    pub fn submit(self: &Arc<Self>, text: &str, file: Option<&str>) -> Result<Value, ApiError> {
        let (source, base) = match file {
            Some(name) if self.files().iter().any(|f| f["file"] == name) => (
                self.folder.join(name).display().to_string(),
                self.folder.clone(),
            ),
            Some(name) => {
                return Err(ApiError::bad(format!(
                    "request body: field `file`: `{name}` is not a study file of {}",
                    self.folder.display()
                )));
            }
            None => (PASTED.to_string(), PathBuf::from(".")),
        };
        let study = Study::parse_str(text, &source, &base)?;
        if self.closing.load(Ordering::SeqCst) {
            return Err(ApiError::busy("the lab is shutting down"));
        }
        let mut list = self.list();
        if list.iter().any(|e| e.lock().0 == Status::Running) {
            return Err(ApiError::conflict(
                "a study is running: wait for it or stop it first",
            ));
        }
        let id = self.fresh_id(&list);
        let entry = Arc::new(StudyEntry {
            id: id.clone(),
            name: study.name.clone(),
            source,
            total: study.plan.jobs.len(),
            counter: StudyCounter::default(),
            state: Mutex::new((Status::Running, None, None)),
        });
        for line in &study.plan.notes {
            entry.counter.note(&format!("note: {line}"));
        }
        list.push(entry.clone());
        drop(list);
        let (me, run) = (self.clone(), entry.clone());
        let worker = std::thread::Builder::new()
            .name("lab-study".into())
            .spawn(move || me.execute(&study, &run))
            .map_err(|e| ApiError::busy(format!("a study's thread: {e}")))?;
        self.workers
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(worker);
        Ok(entry.view())
    }

    /// An id no study of `list` (the lab's, locked) has, nor any folder under `DIR/studies/`.
    fn fresh_id(&self, list: &[Arc<StudyEntry>]) -> String {
        loop {
            let n = self.count.fetch_add(1, Ordering::SeqCst) + 1;
            let id = format!("study-{n}");
            if list.iter().all(|e| e.id != id) && !self.study_dir(&id).exists() {
                return id;
            }
        }
    }

    /// Runs `study` for `entry` into its directory and records how it ended.
    fn execute(&self, study: &Study, entry: &StudyEntry) {
        let options = StudyOptions {
            out: self.study_dir(&entry.id),
            threads: None,
            force: false,
            shard: None,
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads.unwrap_or(0))
            .thread_name(|i| format!("lab-study-{i}"))
            .build();
        let outcome = match pool {
            Ok(pool) => pool.install(|| run_study(study, &options, &entry.counter)),
            Err(e) => Err(fuzzymotiv_pipeline::files::error::CliError::runtime(
                e.to_string(),
            )),
        };
        let end = match outcome {
            Ok(StudyOutcome::Analysed(claims)) => (Status::Finished, Some(claims), None),
            Ok(StudyOutcome::Waiting { done, total }) => {
                let why = format!("only {done} of its {total} runs are finished");
                (Status::Failed, None, Some(why))
            }
            Err(_) if entry.counter.stopped() => (Status::Stopped, None, None),
            Err(e) => (Status::Failed, None, Some(e.to_string())),
        };
        *entry.lock() = end;
    }

    /// Stops a running study: its runs stop after their generation (their checkpoints stay).
    pub fn cancel(&self, id: &str) -> Result<Value, ApiError> {
        let entry = self
            .get(id)
            .ok_or_else(|| ApiError::not_found(format!("no study `{id}` in this lab")))?;
        entry.counter.stop();
        Ok(entry.view())
    }

    /// Stops every study and waits for their threads.
    pub fn close(&self) {
        self.closing.store(true, Ordering::SeqCst);
        for e in self.list().iter() {
            e.counter.stop();
        }
        let workers: Vec<_> = self
            .workers
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .drain(..)
            .collect();
        for w in workers {
            let _ = w.join();
        }
    }
}
