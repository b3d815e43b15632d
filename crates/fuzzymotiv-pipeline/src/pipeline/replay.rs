//! A saved genome run again (`fuzzymotiv replay`, [`replay`] with its [`ReplayOptions`]): the
//! config it is replayed under ([`replay_config`]), its room-modelling run in every room
//! ([`replay_trials`]), each room's trajectory as CSV ([`trajectory_csv`]) with its line and its
//! entry in the replay's JSON ([`room_files`], [`replay_json`]), its GIFs ([`room_gifs`]), the
//! logged paths drawn over it, the figure and the page, written through the output guard. The
//! command line parses the arguments and prints what [`replay`] returns.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::{Experiment, InstanceRun, OrientationMode, Run, Training};
use fuzzymotiv::fitness::MissionTerms;
use fuzzymotiv::simulation::{MlpShape, Trajectory, TrialParams};
use rayon::prelude::*;

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files, io_err, num, write_files};
use crate::files::inputs::{Loaded, load_config, resolve, room_entry, rooms_unchanged};
use crate::records::PROGRAM;
use crate::records::context::RenderContext;
use crate::records::genome::{SavedGenome, locate, read_genome};
use crate::records::robot_log::RobotLog;
use crate::render::figures::Rasterise;
use crate::render::frames::animate::delay_of;
use crate::render::frames::{self, FrameOptions, Track};
use crate::render::report::{replay_page_with, xs};
use crate::render::svg::{LoggedPath, trajectories_svg_with};

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
/// room of `exp`, with its run label; a room without a robot of its own is said to `note`.
pub fn replay_trials(
    exp: &Experiment,
    genome: &SavedGenome,
    note: &mut dyn FnMut(&str),
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
                    note(&format!(
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

/// The GIFs a replay draws (`fuzzymotiv replay --gif`): frame side, a frame every `stride`
/// steps, frames per second.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GifSettings {
    /// Side of the square frames, pixels (64 to 2048).
    pub size: u32,
    /// A frame every `stride` steps (the last pose always gets one).
    pub stride: usize,
    /// Frames per second (0.01 to 50).
    pub fps: f64,
}

/// What to replay and where to write it (`fuzzymotiv replay`'s arguments, the command line's
/// option names in its errors).
pub struct ReplayOptions<'a> {
    /// A run directory, or a genome file.
    pub source: PathBuf,
    /// The config to replay under [default: the run's own, beside the genome].
    pub config: Option<PathBuf>,
    /// The one room to replay (a room of the config, a built-in room or a room file)
    /// [default: every room of the config].
    pub room: Option<String>,
    /// The replay's base seed [default: the run's].
    pub seed: Option<u64>,
    /// The replay page; the other files go beside it, named after its stem.
    pub out: PathBuf,
    /// Draws `STEM.png` beside `STEM.svg`, if given.
    pub png: Option<&'a dyn Rasterise>,
    /// An animated GIF per room, if given.
    pub gif: Option<GifSettings>,
    /// Robot logs whose paths are drawn over the one replayed room.
    pub logs: Vec<PathBuf>,
    /// Replace other files of the replay's names.
    pub force: bool,
}

/// What a replay did: a line per room (its terms, F, collisions and CSV), whether the files
/// were written or already held this replay, and the GIFs written.
#[derive(Debug)]
pub struct ReplayDone {
    /// One line per room, in the config's order.
    pub lines: Vec<String>,
    /// [`FilesState::Write`]: written; [`FilesState::Same`]: the files already held it.
    pub state: FilesState,
    /// The GIFs' paths, as given.
    pub gifs: Vec<String>,
}

/// Replays a saved genome as `fuzzymotiv replay` does: the genome and its config found
/// ([`locate`]), the config loaded (a genome alone: the defaults and the genome's seed), the
/// logs read, every room replayed ([`replay_trials`]) and its CSV, the JSON, the figure (and
/// PNG), the page and the GIFs written through the output guard: the same replay again
/// changes nothing, another file of those names is kept unless `force`. `note` receives what
/// the replay says on the way (the config used, a room changed since the run, logs outside
/// their room), each before anything that can fail after it.
pub fn replay(opts: &ReplayOptions, note: &mut dyn FnMut(&str)) -> Result<ReplayDone, CliError> {
    let (genome_path, found_config) = locate(&opts.source)?;
    let config_path = opts.config.clone().or(found_config);
    let genome = read_genome(&genome_path)?;
    // A genome alone is replayed under the default config and, unless --seed says otherwise,
    // the seed it was evolved with.
    let seed = opts.seed.or(if config_path.is_none() {
        genome.seed
    } else {
        None
    });
    let loaded = load_config(config_path.as_deref(), &[], seed)?;
    for line in &loaded.notes {
        note(&format!("note: {line}"));
    }
    if let Some(path) = &config_path {
        let remedy = "the replay uses the room as it is now, so its paths are not the run's";
        if let Err(e) = rooms_unchanged(path, &loaded, remedy) {
            note(&format!("warning: {e}"));
        }
    }
    let source_name = config_path
        .as_ref()
        .map_or("(built-in defaults)".to_string(), |p| {
            p.display().to_string()
        });
    let beside = " (no config beside the genome; --config FILE replays under the run's own)";
    note(&format!(
        "config: {source_name}{}",
        if config_path.is_none() { beside } else { "" }
    ));
    if config_path.is_some() && loaded.raw.network.hidden != genome.hidden {
        return Err(CliError::input(format!(
            "{}: the genome has {} hidden units but the config says network.hidden = {}",
            genome_path.display(),
            genome.hidden,
            loaded.raw.network.hidden
        )));
    }
    let rooms = match &opts.room {
        Some(want) => vec![room_entry("--room", want, &loaded)?],
        None => loaded.raw.rooms.clone(),
    };
    let logs = logged_paths(&opts.logs, &rooms)?;
    let loaded = replay_config(&loaded, &genome, rooms, &source_name)?;
    let trials = replay_trials(&loaded.experiment, &genome, note)?;
    let ctx = RenderContext::of(&loaded);
    let gifs = match opts.gif {
        Some(g) => Some(gif_options(g, loaded.experiment.trial_params())?),
        None => None,
    };
    for line in outside_warnings(&logs, &loaded.experiment) {
        note(&line);
    }
    let written = Replayed {
        ctx: &ctx,
        genome: &genome,
        source_name: &source_name,
        trials: &trials,
        logs: &logs,
    };
    write_replay(opts, &written, gifs)
}

/// The paths of the logs, each over the replay's one room (several rooms: `--room` must say
/// which); refused before anything is replayed.
fn logged_paths(logs: &[PathBuf], rooms: &[String]) -> Result<Vec<LoggedPath>, CliError> {
    if logs.is_empty() {
        return Ok(Vec::new());
    }
    if rooms.len() != 1 {
        return Err(CliError::input(format!(
            "--log: the config has {} rooms ({}); a log is drawn over the room it was recorded in, so say which with --room ROOM",
            rooms.len(),
            rooms.join(", ")
        )));
    }
    logs.iter()
        .map(|path| {
            Ok(LoggedPath {
                label: path.display().to_string(),
                room: 0,
                points: RobotLog::read(path)?.path()?,
            })
        })
        .collect()
}

/// A warning per logged path with positions outside its room's outline's bounds (mm in
/// another frame, or in other units, draw outside the room).
fn outside_warnings(logs: &[LoggedPath], exp: &Experiment) -> Vec<String> {
    let mut warnings = Vec::new();
    for log in logs {
        let room = exp.arenas()[log.room].room();
        let (lo, hi) = room.bounds();
        let outside = (log.points.iter())
            .filter(|&&(x, y)| x < lo.x || x > hi.x || y < lo.y || y > hi.y)
            .count();
        if outside > 0 {
            warnings.push(format!(
                "warning: {}: {outside} of {} positions lie outside room {}; --log wants x and y in mm, in the room's frame",
                log.label,
                log.points.len(),
                room.name
            ));
        }
    }
    warnings
}

/// The frame options and delay of the GIFs, for the trial's robot.
fn gif_options(g: GifSettings, trial: &TrialParams) -> Result<(FrameOptions, u16), CliError> {
    let opts = FrameOptions::new(g.size, g.stride)
        .map_err(|e| CliError::input(format!("--{}: {e}", e.field().unwrap_or("size"))))?;
    let delay = delay_of(g.fps).map_err(|why| CliError::input(format!("--fps: {why}")))?;
    Ok((opts.for_trial(trial), delay))
}

/// What a replay writes its files from.
struct Replayed<'a> {
    ctx: &'a RenderContext,
    genome: &'a SavedGenome,
    source_name: &'a str,
    trials: &'a [ReplayTrial],
    logs: &'a [LoggedPath],
}

/// Writes the replay's CSV per room, JSON, figure and page, through the output guard.
fn write_replay(
    opts: &ReplayOptions,
    r: &Replayed,
    gifs: Option<(FrameOptions, u16)>,
) -> Result<ReplayDone, CliError> {
    let (ctx, out) = (r.ctx, &opts.out);
    let (dir, stem) = out_parts(out)?;
    let mut files = Vec::new();
    let (lines, rooms_json) = room_files(ctx, &dir, &stem, r.trials, &mut files);
    let gif_files = match gifs {
        Some(gifs) => room_gifs(ctx, &dir, &stem, r.trials, gifs)?,
        None => Vec::new(),
    };
    let gif_names: Vec<String> = (gif_files.iter())
        .map(|(p, _)| p.display().to_string())
        .collect();
    files.extend(gif_files);
    let genome_path = r.genome.path.display();
    files.push((
        dir.join(format!("{stem}.json")),
        replay_json(&genome_path.to_string(), r.source_name, ctx, rooms_json),
    ));
    let pairs: Vec<_> = (r.trials.iter())
        .map(|(k, _, run)| (&ctx.rooms[*k], &run.trajectory))
        .collect();
    let title = format!("Replay of {genome_path} (seed {})", ctx.seed);
    let svg = trajectories_svg_with(&title, &pairs, r.logs);
    let svg_path = dir.join(format!("{stem}.svg"));
    if let Some(png) = opts.png {
        let png_path = svg_path.with_extension("png");
        let bytes = (png.png(&svg)).map_err(|e| io_err(&png_path, std::io::Error::other(e)))?;
        files.push((png_path, bytes));
    }
    files.push((svg_path, svg.into_bytes()));
    let about = format!(
        "genome {genome_path} · config {} · seed {} · motivations (C, H, O, E) = {} · {} steps per trial",
        r.source_name,
        ctx.seed,
        xs(ctx),
        ctx.steps
    );
    let page = replay_page_with("fuzzymotiv replay", &about, ctx, r.trials, r.logs);
    files.push((out.clone(), page.into_bytes()));
    let state = check_files(&files, "--out", opts.force)?;
    if state == FilesState::Write {
        std::fs::create_dir_all(&dir).map_err(|e| io_err(&dir, e))?;
        write_files(&files)?;
    }
    Ok(ReplayDone {
        lines,
        state,
        gifs: gif_names,
    })
}

/// The directory and file stem of the replay page `out`; a directory is refused (the replay
/// is a page with files beside it, e.g. --out DIR/replay.html).
pub fn out_parts(out: &Path) -> Result<(PathBuf, String), CliError> {
    if out.is_dir() || out.as_os_str().to_string_lossy().ends_with('/') {
        return Err(CliError::input(format!(
            "--out {}: is a directory; give the replay page's file name, e.g. --out {}",
            out.display(),
            out.join("replay.html").display()
        )));
    }
    let dir = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let stem = out
        .file_stem()
        .map_or("replay".to_string(), |s| s.to_string_lossy().into_owned());
    Ok((dir, stem))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Draws every SVG as the same few bytes.
    struct FakePng;
    impl Rasterise for FakePng {
        fn png(&self, _svg: &str) -> Result<Vec<u8>, crate::render::figures::RasterError> {
            Ok(b"png".to_vec())
        }
    }

    /// The library replays a genome from options alone, as `fuzzymotiv replay` does: it says
    /// which config it used, returns a line per room, writes the page, JSON, CSV, figure and
    /// the PNG its rasteriser draws, and the same replay again changes nothing.
    #[test]
    fn a_replay_from_its_options_writes_its_files_and_again_changes_nothing() {
        let dir = std::env::temp_dir().join(format!("fm-replay-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let genome = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../fuzzymotiv-cli/tests/golden/default/best_genome.json");
        let opts = ReplayOptions {
            source: genome,
            config: None,
            room: Some("H".into()),
            seed: None,
            out: dir.join("r.html"),
            png: Some(&FakePng),
            gif: None,
            logs: Vec::new(),
            force: false,
        };
        let mut notes = Vec::new();
        let done = replay(&opts, &mut |n| notes.push(n.to_string())).unwrap();
        assert!(notes.iter().any(|n| n.starts_with("config: ")), "{notes:?}");
        assert_eq!(done.lines.len(), 1, "{:?}", done.lines);
        assert!(done.lines[0].starts_with("H: a = "), "{:?}", done.lines);
        assert_eq!(done.state, FilesState::Write);
        for name in ["r.html", "r.json", "r-H.csv", "r.svg"] {
            assert!(dir.join(name).is_file(), "{name}");
        }
        assert_eq!(std::fs::read(dir.join("r.png")).unwrap(), b"png");
        let again = replay(&opts, &mut |_| {}).unwrap();
        assert_eq!(again.state, FilesState::Same);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
