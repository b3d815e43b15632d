//! A saved genome run again (`fuzzymotiv replay`): the config it is replayed under
//! ([`replay_config`]), its room-modelling run in every room ([`replay_trials`]), each room's
//! trajectory as CSV ([`trajectory_csv`]) with its line and its entry in the replay's JSON
//! ([`room_files`], [`replay_json`]), and its GIFs ([`room_gifs`]). The command line loads the
//! config, refuses what does not fit and writes the files through the output guard.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::{Experiment, InstanceRun, OrientationMode, Run, Training};
use fuzzymotiv::fitness::MissionTerms;
use fuzzymotiv::simulation::{MlpShape, Trajectory};
use rayon::prelude::*;

use crate::files::error::CliError;
use crate::files::guard::num;
use crate::files::inputs::{Loaded, resolve};
use crate::files::notes::Notes;
use crate::records::PROGRAM;
use crate::records::context::RenderContext;
use crate::records::genome::SavedGenome;
use crate::render::frames::{self, FrameOptions, Track};

/// One room's replay: the room's index, the label of the run whose robot it is, and the run.
pub type ReplayTrial = (usize, String, InstanceRun);

/// A file-name-safe version of a room name.
pub fn file_tag(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The trajectory as CSV: one row per step `t` with the pose at the start of the step, the
/// sensor values read there, the motor outputs, the action, whether the move collided and
/// whether the step was idle (after the trial ended at home); a last row `t = steps` holds the
/// final pose only.
pub fn trajectory_csv(tr: &Trajectory) -> String {
    let sensors = tr.sensors.first().map_or(8, |s| s.len());
    let columns: String = (0..sensors).map(|k| format!("s{k},")).collect();
    let mut s = format!("step,x_mm,y_mm,heading_rad,{columns}mL,mR,action,collision,idle\n");
    for t in 0..tr.len() {
        let p = tr.poses[t];
        let _ = write!(s, "{t},{},{},{}", num(p.x), num(p.y), num(p.heading));
        for &v in tr.sensors[t].iter() {
            let _ = write!(s, ",{}", num(v));
        }
        let [ml, mr] = tr.motors[t];
        let _ = writeln!(
            s,
            ",{},{},{},{},{}",
            num(ml),
            num(mr),
            tr.actions[t].label(),
            u8::from(tr.collisions[t]),
            u8::from(tr.idle[t])
        );
    }
    if let Some(p) = tr.poses.last() {
        let _ = writeln!(
            s,
            "{},{},{},{}{}",
            tr.len(),
            num(p.x),
            num(p.y),
            num(p.heading),
            ",".repeat(sensors + 5)
        );
    }
    s
}

/// The config a genome is replayed under: `loaded`'s in `rooms` (names or files as a config
/// gives them), with the genome's hidden units, and without room recognition or online
/// orientation (they would demand more rooms; neither changes a trajectory).
pub fn replay_config(
    loaded: &Loaded,
    genome: &SavedGenome,
    rooms: Vec<String>,
    source: &str,
) -> Result<Loaded, CliError> {
    let mut raw = loaded.raw.clone();
    raw.rooms = rooms;
    raw.network.hidden = genome.hidden;
    raw.aem.enabled = false;
    raw.fitness.orientation = OrientationMode::Offline;
    resolve(raw, Path::new("."), source)
}

/// The animated GIF of every room's replay, `DIR/STEM-ROOM.gif`, drawn side by side on
/// rayon's pool (the bytes do not depend on it).
pub fn room_gifs(
    ctx: &RenderContext,
    dir: &Path,
    stem: &str,
    trials: &[ReplayTrial],
    (opts, delay): (FrameOptions, u16),
) -> Result<Vec<(PathBuf, Vec<u8>)>, CliError> {
    trials
        .par_iter()
        .map(|(r, _, run)| {
            let room = &ctx.rooms[*r];
            let path = dir.join(format!("{stem}-{}.gif", file_tag(&room.name)));
            let bytes = frames::gif(room, Track::of(&run.trajectory), opts, delay)
                .map_err(|e| CliError::runtime(format!("{}: {e}", path.display())))?;
            Ok((path, bytes))
        })
        .collect()
}

/// The room-modelling run of the genome (per-room training: of the room's own robot) in every
/// room of `exp`, with its run label; a room without a robot of its own is said to `notes`.
pub fn replay_trials(
    exp: &Experiment,
    genome: &SavedGenome,
    notes: &dyn Notes,
) -> Result<Vec<ReplayTrial>, CliError> {
    let runs = exp.runs();
    let in_file =
        |e: &dyn std::fmt::Display| CliError::input(format!("{}: {e}", genome.path.display()));
    // The robot's sensors are the network's inputs (7 on the Thymio II, not the Khepera's 8).
    let shape = MlpShape::with_hidden(genome.hidden)
        .map_err(|e| in_file(&e))?
        .with_inputs(exp.shape().inputs())
        .map_err(|e| in_file(&e))?;
    let want_len = shape.genome_len();
    let mut trials = Vec::new();
    for r in 0..exp.arenas().len() {
        let name = &exp.arenas()[r].room().name;
        let (run, weights): (&Run, &Vec<f64>) = match exp.training() {
            Training::AllRooms => (&runs[0], &genome.weights),
            Training::PerRoom => match genome.runs.iter().find(|(label, _)| label == name) {
                Some((_, w)) => (&runs[r], w),
                None => {
                    notes.note(&format!(
                        "note: no robot was evolved in room {name}; replaying the genome's main robot"
                    ));
                    (&runs[r], &genome.weights)
                }
            },
        };
        if weights.len() != want_len {
            return Err(CliError::input(format!(
                "{}: {} weights, but a {}-{}-2 network needs {want_len}",
                genome.path.display(),
                weights.len(),
                shape.inputs(),
                genome.hidden
            )));
        }
        let network = exp.network(weights).map_err(|e| in_file(&e))?;
        trials.push((r, run.label.clone(), exp.instance_run(&network, run, r)));
    }
    Ok(trials)
}

/// Per room of the replay: its trajectory's CSV file (`DIR/STEM-ROOM.csv`, added to `files`),
/// and returned the line printed for it and its entry in the replay's JSON.
pub fn room_files(
    ctx: &RenderContext,
    dir: &Path,
    stem: &str,
    trials: &[ReplayTrial],
    files: &mut Vec<(PathBuf, Vec<u8>)>,
) -> (Vec<String>, Vec<serde_json::Value>) {
    let mut lines = Vec::new();
    let mut rooms_json = Vec::new();
    for (r, label, run) in trials {
        let name = &ctx.rooms[*r].name;
        let csv = dir.join(format!("{stem}-{}.csv", file_tag(name)));
        files.push((csv.clone(), trajectory_csv(&run.trajectory).into_bytes()));
        let (tr, terms) = (&run.trajectory, run.terms);
        let mission = (terms.mission).map_or(String::new(), |m| mission_text(&m, &ctx.rooms[*r]));
        lines.push(format!(
            "{name}: a = {:.3}, g = {:.3}, b = {:.3}{mission}, F = {:.4}, {} collisions → {}",
            terms.a,
            terms.g,
            terms.b,
            run.f,
            tr.collisions.iter().filter(|&&c| c).count(),
            csv.display()
        ));
        let mut room_json = serde_json::json!({
            "room": name,
            "run": label,
            "steps": tr.len(),
            "terms": terms,
            "f": run.f,
            "executed_steps": tr.executed(),
            "actions": tr.actions.iter().map(|a| a.label()).collect::<Vec<_>>(),
            "trajectory": tr,
        });
        add_mission(&mut room_json, &ctx.rooms[*r]);
        rooms_json.push(room_json);
    }
    (lines, rooms_json)
}

/// A replay line's mission terms: `goal` only for a room with a goal zone and `waypoints` only
/// for one with waypoints (as `table.md` has no column for a zone no room has), then
/// `urgency`, `safety` and whether the mission was done.
fn mission_text(m: &MissionTerms, room: &fuzzymotiv::simulation::Room) -> String {
    let mut text = String::new();
    if room.mission.goal.is_some() {
        let _ = write!(text, ", goal = {:.3}", m.goal);
    }
    let _ = write!(text, ", urgency = {:.3}", m.urgency);
    if !room.mission.waypoints.is_empty() {
        let _ = write!(text, ", waypoints = {:.3}", m.waypoints);
    }
    let done = m
        .done_at
        .map_or("not done".into(), |t| format!("done at step {t}"));
    let _ = write!(text, ", safety = {:.3} (mission {done})", m.safety);
    text
}

/// A room's mission in the replay's JSON, only when it has one (the paper's replays keep their
/// bytes): `goal` as {x, y, radius} and `waypoints` as a list of them, in order.
fn add_mission(room_json: &mut serde_json::Value, room: &fuzzymotiv::simulation::Room) {
    let zone = |z: &fuzzymotiv::simulation::HomeZone| serde_json::json!({"x": z.centre.x, "y": z.centre.y, "radius": z.radius});
    if let Some(goal) = &room.mission.goal {
        room_json["goal"] = zone(goal);
    }
    if !room.mission.waypoints.is_empty() {
        room_json["waypoints"] = room.mission.waypoints.iter().map(zone).collect();
    }
}

/// The replay's JSON document: program, genome, config, seed and every room's trajectory.
pub fn replay_json(
    genome: &str,
    source_name: &str,
    ctx: &RenderContext,
    rooms_json: Vec<serde_json::Value>,
) -> Vec<u8> {
    let doc = serde_json::json!({
        "program": PROGRAM,
        "version": fuzzymotiv::VERSION,
        "model": fuzzymotiv::MODEL_VERSION,
        "genome": genome,
        "config": source_name,
        "seed": ctx.seed,
        "note": "poses[t] is the pose at the start of step t (poses[0] = home, poses[steps] = the end); sensors[t], motors[t], speeds[t] and collisions[t] belong to step t",
        "rooms": rooms_json,
    });
    (serde_json::to_string(&doc).expect("serialisable") + "\n").into_bytes()
}
