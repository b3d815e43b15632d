//! The HTTP API and the page: one handler per route, each a few calls into the lab's modules.

use std::convert::Infallible;
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use axum::body::Bytes;
use axum::extract::{DefaultBodyLimit, Path as UrlPath, Query, State};
use axum::http::{StatusCode, header};
use axum::response::sse::{Event, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use futures_util::Stream;
use fuzzymotiv::experiment::Combination;
use fuzzymotiv::fitness::TskFitness;
use fuzzymotiv_pipeline::files::guard::{OutState, Spelling, StagedDir, check_out_as};
use fuzzymotiv_pipeline::files::notes::NoNotes;
use serde::Deserialize;
use serde_json::{Value, json};
use tokio::sync::watch;

use crate::assets;
use crate::errors::{ApiError, parse_body};
use crate::limits;
use crate::motivations;
use crate::robots;
use crate::rooms::{self, RoomRequest};
use crate::runs::{Runs, Status};
use crate::settings::Settings;
use crate::start::StartConfig;
use crate::studies::Studies;

/// What every handler shares.
pub struct AppState {
    pub dir: std::path::PathBuf,
    pub runs: Arc<Runs>,
    pub studies: Arc<Studies>,
    /// The config the lab started on (`--config`), if any.
    pub start: Option<StartConfig>,
    /// Turns true when the lab stops: event streams end.
    pub closing: watch::Receiver<bool>,
}

type Shared = State<Arc<AppState>>;

/// The routes (without the access guard, added by the server).
pub fn router(state: Arc<AppState>) -> Router {
    Router::new()
        .route("/", get(|| async { assets::page() }))
        .route("/lab.js", get(|| async { assets::script() }))
        .route("/lab.css", get(|| async { assets::style() }))
        .route("/api/info", get(info))
        .route("/api/explain", post(explain))
        .route("/api/config", post(config_motivations))
        .route("/api/rooms", get(room_list).post(room_check))
        .route("/api/robots", get(|| async { Json(robots::list()) }))
        .route("/api/runs", get(run_list).post(run_start))
        .route("/api/runs/{id}", get(run_detail))
        .route("/api/runs/{id}/cancel", post(run_cancel))
        .route("/api/runs/{id}/events", get(run_events))
        .route("/api/runs/{id}/save", post(run_save))
        .route("/api/runs/{id}/config.toml", get(run_config))
        .route("/runs/{id}/report.html", get(run_report))
        .route("/api/compare", get(compare))
        .route("/api/studies", get(study_list).post(study_start))
        .route("/api/studies/{id}/cancel", post(study_cancel))
        .route("/api/studies/{id}/forest.svg", get(study_forest))
        .layer(DefaultBodyLimit::max(limits::MAX_BODY))
        .with_state(state)
}

/// Presets (each motivation preset a slider list), limits, the TSK's membership functions and
/// the config the lab started on (`start`, null without `--config`), for the page to draw.
async fn info(State(s): Shared) -> Result<Json<Value>, ApiError> {
    let tsk = TskFitness::paper();
    let mut motivations = serde_json::Map::new();
    for (name, raw) in motivations::presets() {
        motivations.insert(name.into(), json!(motivations::listed(&raw, "preset")?));
    }
    Ok(Json(json!({
        "version": fuzzymotiv::VERSION,
        "model": fuzzymotiv::MODEL_VERSION,
        "presets": {
            "motivations": motivations,
            "ga": { "quick": [30, 30], "medium": [80, 80], "paper": [200, 200] },
        },
        "start": s.start.as_ref().map(StartConfig::view),
        "terms": fuzzymotiv::fitness::LIBRARY_TERMS,
        "peaks": tsk.peaks(),
        "limits": { "population": limits::MAX_POPULATION, "generations": limits::MAX_GENERATIONS,
            "rooms": limits::MAX_ROOMS, "steps": limits::MAX_STEPS, "body_bytes": limits::MAX_BODY,
            "room_vertices": limits::MAX_ROOM_VERTICES, "queued": limits::MAX_QUEUED },
    })))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ExplainRequest {
    /// `[C, H, O, E]`, or named as a config's `[motivations]`.
    motivations: Value,
    /// `[a, g, l, b]` (one value per motivation), or `{ term: value }`.
    fitness: Value,
    /// The run form's `[fitness] combine`; default the TSK.
    #[serde(default)]
    combine: Combination,
}

/// "What would F be": the library's explain (the TSK's F and its firing rules) over N inputs,
/// and F under the chosen combination (`combined`; the TSK's F when it is the TSK).
async fn explain(body: Bytes) -> Result<Json<Value>, ApiError> {
    let req: ExplainRequest = parse_body(&body)?;
    let m = motivations::explain_motivations(req.motivations)?;
    let y = motivations::explain_inputs(&m, req.fitness)?;
    let tsk = TskFitness::paper();
    let x = tsk.explain(&m, &y);
    let combined = req.combine.fitness(&tsk, &m, &y);
    let names: Vec<&str> = m.iter().map(|m| m.name()).collect();
    Ok(Json(
        json!({ "fitness": x.fitness, "rules": x.rules, "weight_sum": x.weight_sum,
        "inputs": x.inputs, "names": names, "weights": m.weights(),
        "motivations": m.as_array(), "combine": req.combine, "combined": combined }),
    ))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ConfigRequest {
    /// A config file's text.
    toml: String,
}

/// "Load config": the motivations of a config file, for the sliders.
async fn config_motivations(body: Bytes) -> Result<Json<Value>, ApiError> {
    let req: ConfigRequest = parse_body(&body)?;
    Ok(Json(
        json!({ "motivations": motivations::of_config(&req.toml)? }),
    ))
}

/// The start config's room files first, then the built-in rooms and the lab's saved ones.
async fn room_list(State(s): Shared) -> Json<Value> {
    let saved = rooms::list(&s.dir);
    let config = s.start.iter().flat_map(StartConfig::room_views);
    Json(json!(config.chain(&saved).collect::<Vec<_>>()))
}

/// Checks a drawn or uploaded room (and saves it with `save`): 200 with the room, or 400
/// with the message and the field `rooms --check` names.
async fn room_check(State(s): Shared, body: Bytes) -> Result<Response, ApiError> {
    let req: RoomRequest = parse_body(&body)?;
    let (room, text) = match rooms::check(&req)? {
        Ok(ok) => ok,
        Err(problem) => return Ok((StatusCode::BAD_REQUEST, Json(json!(problem))).into_response()),
    };
    let entry = if req.save {
        Some(rooms::save(&s.dir, &room, &text)?)
    } else {
        None
    };
    Ok(Json(json!({ "ok": true, "room": room, "entry": entry, "toml": text })).into_response())
}

async fn run_list(State(s): Shared) -> Json<Value> {
    Json(json!(s.runs.summaries()))
}

async fn run_start(State(s): Shared, body: Bytes) -> Result<Response, ApiError> {
    let settings: Settings = parse_body(&body)?;
    let runs = s.runs.clone();
    let entry = tokio::task::spawn_blocking(move || runs.submit(settings))
        .await
        .map_err(|e| ApiError::busy(e.to_string()))??;
    Ok((StatusCode::CREATED, Json(json!({ "id": entry.id }))).into_response())
}

async fn run_detail(
    State(s): Shared,
    UrlPath(id): UrlPath<String>,
) -> Result<Json<Value>, ApiError> {
    let e = s.runs.get(&id).ok_or_else(|| no_run(&id))?;
    let (status, shown) = &*e.lock();
    Ok(Json(
        json!({ "id": e.id, "about": e.about, "status": status,
        "generations": shown.generations, "paths": shown.paths, "result": shown.result,
        "error": shown.error, "settings": e.settings }),
    ))
}

fn no_run(id: &str) -> ApiError {
    ApiError::not_found(format!("no run `{id}` in this lab"))
}

async fn run_cancel(
    State(s): Shared,
    UrlPath(id): UrlPath<String>,
) -> Result<Json<Value>, ApiError> {
    let status = s.runs.cancel(&id)?;
    Ok(Json(json!({ "id": id, "status": status })))
}

/// The run's events (server-sent): every generation from the first, the latest paths, and
/// the end (`finished`, `stopped`, `failed`); then the stream closes.
async fn run_events(
    State(s): Shared,
    UrlPath(id): UrlPath<String>,
) -> Result<Sse<impl Stream<Item = Result<Event, Infallible>>>, ApiError> {
    let entry = s.runs.get(&id).ok_or_else(|| no_run(&id))?;
    let cursor = Cursor {
        entry,
        sent: 0,
        paths_version: 0,
        ended: false,
        changed: None,
        closing: s.closing.clone(),
    };
    let stream = futures_util::stream::unfold(cursor, |mut c| async move {
        let events = c.next_events().await?;
        Some((futures_util::stream::iter(events.into_iter().map(Ok)), c))
    });
    use futures_util::StreamExt;
    Ok(Sse::new(stream.flatten()).keep_alive(KeepAlive::new().interval(Duration::from_secs(15))))
}

/// Where one event stream stands.
struct Cursor {
    entry: Arc<crate::runs::RunEntry>,
    sent: usize,
    paths_version: u64,
    ended: bool,
    changed: Option<watch::Receiver<u64>>,
    closing: watch::Receiver<bool>,
}

impl Cursor {
    /// The events not yet sent, waiting for some; `None` once the run's end was sent.
    async fn next_events(&mut self) -> Option<Vec<Event>> {
        if self.ended || *self.closing.borrow() {
            return None;
        }
        let mut changed = self
            .changed
            .take()
            .unwrap_or_else(|| self.entry.subscribe());
        loop {
            changed.borrow_and_update();
            let events = self.pending();
            if !events.is_empty() {
                self.changed = Some(changed);
                return Some(events);
            }
            tokio::select! {
                r = changed.changed() => if r.is_err() { return None },
                _ = self.closing.changed() => return None,
            }
        }
    }

    fn pending(&mut self) -> Vec<Event> {
        let (status, shown) = &*self.entry.lock();
        let mut out: Vec<Event> = shown.generations[self.sent.min(shown.generations.len())..]
            .iter()
            .map(|g| Event::default().event("generation").data(g.to_string()))
            .collect();
        self.sent = shown.generations.len();
        if shown.paths_version != self.paths_version {
            self.paths_version = shown.paths_version;
            if let Some(p) = &shown.paths {
                out.push(Event::default().event("paths").data(p.to_string()));
            }
        }
        if matches!(status, Status::Finished | Status::Stopped | Status::Failed) {
            self.ended = true;
            let end = json!({ "status": status, "result": shown.result, "error": shown.error });
            out.push(Event::default().event("end").data(end.to_string()));
        }
        out
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SaveRequest {
    /// The run directory's name under `DIR/saved/` (letters, digits, - and _).
    name: String,
}

/// "Save as run directory": the finished run copied to `DIR/saved/NAME/` through the output
/// guard (staged, then renamed); another run there is never replaced.
async fn run_save(
    State(s): Shared,
    UrlPath(id): UrlPath<String>,
    body: Bytes,
) -> Result<Json<Value>, ApiError> {
    let req: SaveRequest = parse_body(&body)?;
    if !rooms::valid_room_name(&req.name) {
        return Err(ApiError::bad(format!(
            "request body: field `name`: `{}` cannot name a run directory of the lab: use 1 to 40 letters, digits, - or _",
            req.name
        )));
    }
    let entry = s.runs.get(&id).ok_or_else(|| no_run(&id))?;
    if entry.status() != Status::Finished {
        return Err(ApiError::conflict(format!(
            "run `{id}` has not finished: nothing to save"
        )));
    }
    let (from, to) = (s.runs.run_dir(&id), s.dir.join("saved").join(&req.name));
    let dest = tokio::task::spawn_blocking(move || save_copy(&from, &to))
        .await
        .map_err(|e| ApiError::busy(e.to_string()))??;
    Ok(Json(json!({ "saved": dest })))
}

/// How the lab names the output options in the guard's messages.
const SAVE: Spelling = Spelling {
    out: "the save name",
    force: "another save name (the lab never replaces a run directory)",
};

fn save_copy(from: &Path, to: &Path) -> Result<String, ApiError> {
    let io = |p: &Path, e| ApiError::from(fuzzymotiv_pipeline::files::guard::io_err(p, e));
    let config = std::fs::read_to_string(from.join("config.resolved.toml"))
        .map_err(|e| io(&from.join("config.resolved.toml"), e))?;
    let id = [("config.resolved.toml".to_string(), config)];
    if let Some(parent) = to.parent() {
        std::fs::create_dir_all(parent).map_err(|e| io(parent, e))?;
    }
    match check_out_as(to, &id, false, &SAVE, &NoNotes)
        .map_err(|e| ApiError::conflict(e.render(&SAVE)))?
    {
        OutState::Done => return Ok(to.display().to_string()),
        OutState::Unfinished => {
            return Err(ApiError::conflict(format!(
                "{} is being written",
                to.display()
            )));
        }
        OutState::Fresh => {}
    }
    let staged = StagedDir::new(to)?;
    for file in std::fs::read_dir(from).map_err(|e| io(from, e))?.flatten() {
        let path = file.path();
        if path.is_file() {
            let bytes = std::fs::read(&path).map_err(|e| io(&path, e))?;
            staged.write(&file.file_name().to_string_lossy(), bytes)?;
        }
    }
    Ok(staged.commit()?.display().to_string())
}

/// "Download config": the run's resolved config, which `fuzzymotiv run` runs again exactly.
async fn run_config(State(s): Shared, UrlPath(id): UrlPath<String>) -> Result<Response, ApiError> {
    let entry = s.runs.get(&id).ok_or_else(|| no_run(&id))?;
    let text = match &entry.settings {
        Some(settings) => {
            let loaded = s.runs.load(settings)?;
            fuzzymotiv_pipeline::files::inputs::resolved_toml(&loaded.raw)
        }
        None => std::fs::read_to_string(s.runs.run_dir(&id).join("config.resolved.toml"))
            .map_err(|e| ApiError::not_found(e.to_string()))?,
    };
    let disposition = format!("attachment; filename=\"{id}.toml\"");
    Ok((
        [
            (
                header::CONTENT_TYPE,
                "text/plain; charset=utf-8".to_string(),
            ),
            (header::CONTENT_DISPOSITION, disposition),
        ],
        text,
    )
        .into_response())
}

/// A finished run's `report.html` (the replay widget), with a policy that lets its inline
/// scripts run but request nothing.
async fn run_report(State(s): Shared, UrlPath(id): UrlPath<String>) -> Result<Response, ApiError> {
    let entry = s.runs.get(&id).ok_or_else(|| no_run(&id))?;
    if entry.status() != Status::Finished {
        return Err(ApiError::conflict(format!("run `{id}` has not finished")));
    }
    let path = s.runs.run_dir(&id).join("report.html");
    let html = std::fs::read_to_string(&path)
        .map_err(|e| ApiError::not_found(format!("{}: {e}", path.display())))?;
    Ok(([(header::CONTENT_TYPE, "text/html; charset=utf-8")], html).into_response())
}

#[derive(Deserialize)]
struct CompareQuery {
    a: String,
    b: String,
}

async fn compare(
    State(s): Shared,
    q: Result<Query<CompareQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Json<Value>, ApiError> {
    let Query(q) = q.map_err(|e| ApiError::bad(format!("query: {e} (expected ?a=RUN&b=RUN)")))?;
    let runs = s.runs.clone();
    let v = tokio::task::spawn_blocking(move || crate::compare::compare(&runs, &q.a, &q.b))
        .await
        .map_err(|e| ApiError::busy(e.to_string()))??;
    Ok(Json(v))
}

/// The study files the page may pick (`files`) and the lab's studies, newest first.
async fn study_list(State(s): Shared) -> Result<Json<Value>, ApiError> {
    let studies = s.studies.clone();
    let (files, list) = tokio::task::spawn_blocking(move || (studies.files(), studies.summaries()))
        .await
        .map_err(|e| ApiError::busy(e.to_string()))?;
    Ok(Json(json!({ "files": files, "studies": list })))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StudyRequest {
    /// The study file's text.
    toml: String,
    /// The listed study file it is (its configs relative to the study folder); none for a
    /// pasted or uploaded study.
    #[serde(default)]
    file: Option<String>,
}

/// Starts a study: 201 with it, or 400 with the message naming the file and field.
async fn study_start(State(s): Shared, body: Bytes) -> Result<Response, ApiError> {
    let req: StudyRequest = parse_body(&body)?;
    let studies = s.studies.clone();
    let view = tokio::task::spawn_blocking(move || studies.submit(&req.toml, req.file.as_deref()))
        .await
        .map_err(|e| ApiError::busy(e.to_string()))??;
    Ok((StatusCode::CREATED, Json(view)).into_response())
}

async fn study_cancel(
    State(s): Shared,
    UrlPath(id): UrlPath<String>,
) -> Result<Json<Value>, ApiError> {
    Ok(Json(s.studies.cancel(&id)?))
}

/// An analysed study's `forest.svg`.
async fn study_forest(
    State(s): Shared,
    UrlPath(id): UrlPath<String>,
) -> Result<Response, ApiError> {
    if s.studies.get(&id).is_none() {
        return Err(ApiError::not_found(format!("no study `{id}` in this lab")));
    }
    let path = s.studies.study_dir(&id).join("forest.svg");
    let svg = std::fs::read_to_string(&path)
        .map_err(|e| ApiError::not_found(format!("{}: {e}", path.display())))?;
    Ok(([(header::CONTENT_TYPE, "image/svg+xml")], svg).into_response())
}
