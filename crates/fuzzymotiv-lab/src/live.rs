//! What a run shows while it goes on: one event per generation (F's statistics and the mean
//! terms a, g, l, b) and, every few generations, the current best robot's paths in every room
//! (each with its final pose, and the robot's name, for the page to draw the body there); and
//! what it shows when it ends (the per-room table, recognition, the final paths).

use std::ops::ControlFlow;

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::experiment::GenerationState;
use fuzzymotiv::fitness::FitnessTerms;
use fuzzymotiv::simulation::Mlp;
use fuzzymotiv::simulation::{Trajectory, Vec2};
use fuzzymotiv_pipeline::records::Finished;
use serde_json::{Value, json};

use crate::limits::{PATH_POINTS, PATHS_EVERY};

/// A path as the page draws it: at most [`PATH_POINTS`] points `[x, y]` (mm), the first home
/// and the last the robot's final position.
pub fn path_points(t: &Trajectory) -> Vec<[f64; 2]> {
    let stride = t.poses.len().div_ceil(PATH_POINTS).max(1);
    let mut points: Vec<[f64; 2]> = t.poses.iter().step_by(stride).map(|p| [p.x, p.y]).collect();
    if let Some(last) = t.poses.last()
        && t.poses.len() % stride != 1
        && stride > 1
    {
        points.push([last.x, last.y]);
    }
    points
}

/// Where a path ends: `[x, y, heading]` (mm, mm, rad) of the last pose, where the page draws
/// the robot's body and sensors; `None` for an empty path.
pub fn final_pose(t: &Trajectory) -> Option<[f64; 3]> {
    t.poses.last().map(|p| [p.x, p.y, p.heading])
}

/// The name of the robot a run drives (the page draws it from `/api/robots`).
fn robot_name(exp: &Experiment) -> &str {
    exp.trial_params().robot().spec().name()
}

/// Where a run's events go (the run's entry in the lab's list).
pub trait Shows {
    /// A generation's record.
    fn push_generation(&self, g: Value);
    /// The current best robot's paths.
    fn set_paths(&self, p: Value);
    /// Whether someone asked to stop the run.
    fn is_cancelled(&self) -> bool;
}

/// The observer of a lab run: reports every generation to `entry`, stops when it is cancelled.
pub struct Live<'a> {
    exp: &'a Experiment,
    entry: &'a dyn Shows,
    /// The evolution (of the protocol's runs) going on: counted from generation 0s seen.
    run: usize,
    started: bool,
}

impl<'a> Live<'a> {
    pub fn new(exp: &'a Experiment, entry: &'a dyn Shows) -> Self {
        Self {
            exp,
            entry,
            run: 0,
            started: false,
        }
    }

    /// After each generation: the record, sometimes the paths; `Break` once cancelled.
    pub fn on_generation(&mut self, state: &GenerationState<'_>) -> ControlFlow<()> {
        let record = state.record();
        if record.generation == 0 && std::mem::replace(&mut self.started, true) {
            self.run += 1;
        }
        let runs = self.exp.runs();
        let label = runs.get(self.run).map_or("", |r| r.label.as_str());
        let (s, t) = (record.stats, &record.terms);
        self.entry.push_generation(json!({
            "run": self.run, "label": label, "generation": record.generation,
            "best": s.max, "mean": s.mean, "min": s.min, "std": s.std,
            "a": t.a, "g": t.g, "l": t.l, "b": t.b, "terms": measured_terms(self.exp, t),
        }));
        let g = record.generation + 1;
        if g % PATHS_EVERY == 1 || PATHS_EVERY == 1 {
            // The elite robot leads the next generation (ga.elite ≥ 1): this generation's best.
            if let (Some(next), true) = (state.next, self.exp.ga().elite() > 0)
                && let Some(paths) = self.paths(&next[0], record.generation)
            {
                self.entry.set_paths(paths);
            }
        }
        if self.entry.is_cancelled() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }

    /// The paths of `genome` in every room (its room-modelling runs).
    fn paths(&self, genome: &[f64], generation: usize) -> Option<Value> {
        let net = Mlp::from_genome(self.exp.shape(), genome).ok()?;
        let run = self.exp.runs().get(self.run)?.clone();
        let names = self.exp.room_names();
        let rooms: Vec<Value> = (0..names.len())
            .map(|r| {
                let i = self.exp.instance_run(&net, &run, r);
                json!({ "room": names[r], "points": path_points(&i.trajectory), "f": i.f,
                        "pose": final_pose(&i.trajectory),
                        "goal_step": goal_step(self.exp, r, &i.trajectory) })
            })
            .collect();
        Some(json!({ "generation": generation, "rooms": rooms, "robot": robot_name(self.exp) }))
    }
}

/// The mission and user-defined terms a run measures, by name (population means; empty for
/// the paper's four alone, whose a, g, l, b the record has already).
fn measured_terms(exp: &Experiment, t: &FitnessTerms) -> Value {
    let mut out = serde_json::Map::new();
    if let Some(m) = t.mission.filter(|_| exp.measures_mission()) {
        for (k, v) in [
            ("goal", m.goal),
            ("urgency", m.urgency),
            ("waypoints", m.waypoints),
            ("safety", m.safety),
        ] {
            out.insert(k.into(), json!(v));
        }
    }
    for (u, v) in exp.user_terms().iter().zip(t.user.as_slice()) {
        out.insert(u.name.clone(), json!(v));
    }
    Value::Object(out)
}

/// The first step (0 = the start) at which the robot's centre is in room `r`'s goal zone;
/// `None` when it never is or the room has no goal.
fn goal_step(exp: &Experiment, r: usize, t: &Trajectory) -> Option<usize> {
    let goal = exp.arenas().get(r)?.room().mission.goal?;
    t.poses
        .iter()
        .position(|p| goal.contains(Vec2::new(p.x, p.y)))
}

/// What the page shows when a run has finished.
pub fn result(exp: &Experiment, done: &Finished) -> Value {
    let names = exp.room_names();
    let paths: Vec<Value> = done
        .trajectories()
        .iter()
        .zip(&names)
        .enumerate()
        .map(|(r, (t, name))| {
            json!({ "room": name, "points": path_points(t), "pose": final_pose(t),
                    "goal_step": goal_step(exp, r, t) })
        })
        .collect();
    let confusion: Vec<Value> = done
        .outcome
        .modelling
        .iter()
        .map(|m| json!({ "counts": m.confusion.counts, "som_nodes": m.som_nodes }))
        .collect();
    json!({
        "rows": done.rows,
        "paths": { "generation": exp.ga().generations().saturating_sub(1), "rooms": paths,
                   "final": true, "robot": robot_name(exp) },
        "recognition": confusion,
        "wall_seconds": done.wall_seconds,
        "combine": exp.combination(),
    })
}
