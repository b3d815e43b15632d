//! `fuzzymotiv replay`: run a saved genome again and write its trajectory (CSV and JSON) and a
//! replay page.
//!
//! The trial uses the experiment's room-modelling stream (docs/model.md §9: the run whose actions became
//! a room's stored instance), so `replay RUN_DIR` redraws exactly the paths of the run's
//! `report.html`; `--seed N` replays under another base seed. Same genome, room and seed → the
//! same trajectory, byte for byte. `--gif` adds an animated GIF per room
//! ([`fuzzymotiv_io::render::frames`]); `--log` draws a robot's logged path over its room
//! (read by [`fuzzymotiv_io::records::robot_log::RobotLog`], as `recognise` reads it).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::InstanceRun;
use fuzzymotiv::experiment::{Experiment, Run};
use fuzzymotiv::experiment::{OrientationMode, Training};
use fuzzymotiv::fitness::MissionTerms;
use fuzzymotiv::simulation::MlpShape;
use fuzzymotiv::simulation::{Trajectory, TrialParams};
use rayon::prelude::*;

use fuzzymotiv_io::files::error::CliError;
use fuzzymotiv_io::files::guard::{FilesState, check_files, io_err, num, write_files};
use fuzzymotiv_io::files::inputs::{load_config, resolve, room_entry, rooms_unchanged};
use fuzzymotiv_io::note;
use fuzzymotiv_io::records::PROGRAM;
use fuzzymotiv_io::records::context::RenderContext;
use fuzzymotiv_io::records::genome::{SavedGenome, locate, read_genome};
use fuzzymotiv_io::records::robot_log::RobotLog;
use fuzzymotiv_io::render::frames::animate::delay_of;
use fuzzymotiv_io::render::frames::{self, FrameOptions, Track};
use fuzzymotiv_io::render::report::{replay_page_with, xs};
use fuzzymotiv_io::render::svg::{LoggedPath, trajectories_svg_with};

use crate::png::svg_to_png;

/// Arguments of `fuzzymotiv replay`.
#[derive(clap::Args)]
pub struct ReplayArgs {
    /// A run directory (its best_genome.json and config.resolved.toml), or a genome file
    /// (best_genome.json: its rooms and trial settings come from --config, else from the
    /// config.resolved.toml beside it, else from the built-in defaults; the program says which).
    #[arg(value_name = "RUN_DIR|GENOME.json")]
    pub source: PathBuf,
    /// The config to replay under (rooms, trial steps, noise), e.g. the run's
    /// config.resolved.toml [default: the run's own config].
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The room to replay: a room of the config, a built-in room or a room file
    /// [default: every room of the config].
    #[arg(long, value_name = "NAME|FILE")]
    pub room: Option<String>,
    /// Base seed of the replay's noise [default: the run's seed, so the run's own paths]: a
    /// whole number from 0 to 2^53 − 1.
    #[arg(long, allow_hyphen_values = true, value_parser = fuzzymotiv_io::files::inputs::parse_seed)]
    pub seed: Option<u64>,
    /// The replay page to write; the trajectories go beside it as STEM.json, STEM-ROOM.csv and
    /// the figure as STEM.svg.
    #[arg(long, value_name = "FILE", default_value = "replay.html")]
    pub out: PathBuf,
    /// Also write STEM.png beside STEM.svg.
    #[arg(long)]
    pub png: bool,
    /// Also write an animated GIF per room, STEM-ROOM.gif: the room, home zone, the path so
    /// far, body and heading, IR rays, step counter and action label.
    #[arg(long)]
    pub gif: bool,
    /// Side of the GIFs' square frames (pixels, 64 to 2048).
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "PIXELS",
        default_value_t = 320,
        requires = "gif"
    )]
    pub size: u32,
    /// A GIF frame every N steps (the last pose always gets one).
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "N",
        default_value_t = 1,
        requires = "gif",
        value_parser = crate::args::whole_number
    )]
    pub stride: usize,
    /// GIF frames per second (0.01 to 50; the last frame is held for a second).
    #[arg(
        long,
        allow_hyphen_values = true,
        value_name = "FPS",
        default_value_t = 25.0,
        requires = "gif"
    )]
    pub fps: f64,
    /// A robot's log (CSV with `x` and `y` columns: mm in the room's frame; `x_mm`, `y_mm` too)
    /// whose path is drawn, dashed in a colour of its own, over the replayed room in STEM.svg
    /// and the page; other columns are read past (a replay's own CSV is such a log). Repeat
    /// for several logs. With a config of
    /// several rooms, --room says which room the logs were recorded in.
    #[arg(long, value_name = "LOG")]
    pub log: Vec<PathBuf>,
    /// Replace existing files of these names that hold something else (only regular files:
    /// a directory, device or link is never replaced). The same replay again changes nothing.
    #[arg(long)]
    pub force: bool,
}

/// A file-name-safe version of a room name.
fn file_tag(name: &str) -> String {
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

/// Entry point of `fuzzymotiv replay`.
pub fn replay(args: ReplayArgs) -> Result<(), CliError> {
    let (genome_path, found_config) = locate(&args.source)?;
    let config_path = args.config.clone().or(found_config);
    let genome = read_genome(&genome_path)?;
    // A genome alone is replayed under the default config and, unless --seed says otherwise,
    // the seed it was evolved with.
    let seed = args.seed.or(if config_path.is_none() {
        genome.seed
    } else {
        None
    });
    let loaded = load_config(config_path.as_deref(), &[], seed)?;
    if let Some(path) = &config_path {
        let remedy = "the replay uses the room as it is now, so its paths are not the run's";
        if let Err(e) = rooms_unchanged(path, &loaded, remedy) {
            note!("warning: {e}");
        }
    }
    let source_name = config_path
        .as_ref()
        .map_or("(built-in defaults)".to_string(), |p| {
            p.display().to_string()
        });
    note!(
        "config: {source_name}{}",
        if config_path.is_none() {
            " (no config beside the genome; --config FILE replays under the run's own)"
        } else {
            ""
        }
    );
    if config_path.is_some() && loaded.raw.network.hidden != genome.hidden {
        return Err(CliError::input(format!(
            "{}: the genome has {} hidden units but the config says network.hidden = {}",
            genome_path.display(),
            genome.hidden,
            loaded.raw.network.hidden
        )));
    }
    let mut raw = loaded.raw.clone();
    raw.rooms = match &args.room {
        Some(want) => vec![room_entry("--room", want, &loaded)?],
        None => loaded.raw.rooms.clone(),
    };
    raw.network.hidden = genome.hidden;
    let logs = logged_paths(&args.log, &raw.rooms)?;
    // Replaying needs neither room recognition nor online orientation (they would demand more
    // rooms); neither changes a trajectory.
    raw.aem.enabled = false;
    raw.fitness.orientation = OrientationMode::Offline;
    let loaded = resolve(raw, Path::new("."), &source_name)?;
    let trials = replay_trials(&loaded.experiment, &genome)?;
    let ctx = RenderContext::of(&loaded);
    let gifs = if args.gif {
        Some(gif_options(&args, loaded.experiment.trial_params())?)
    } else {
        None
    };
    warn_outside(&logs, &loaded.experiment);
    write_replay(&args, &ctx, &genome, &source_name, &trials, gifs, &logs)
}

/// The paths of `--log`, each over the replay's one room (several rooms: `--room` must say
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
fn warn_outside(logs: &[LoggedPath], exp: &Experiment) {
    for log in logs {
        let room = exp.arenas()[log.room].room();
        let (lo, hi) = room.bounds();
        let outside = (log.points.iter())
            .filter(|&&(x, y)| x < lo.x || x > hi.x || y < lo.y || y > hi.y)
            .count();
        if outside > 0 {
            note!(
                "warning: {}: {outside} of {} positions lie outside room {}; --log wants x and y in mm, in the room's frame",
                log.label,
                log.points.len(),
                room.name
            );
        }
    }
}

/// The frame options and delay of `--gif` (`--size`, `--stride`, `--fps`), for the trial's robot.
fn gif_options(args: &ReplayArgs, trial: &TrialParams) -> Result<(FrameOptions, u16), CliError> {
    let opts = FrameOptions::new(args.size, args.stride)
        .map_err(|(name, why)| CliError::input(format!("--{name}: {why}")))?;
    let delay = delay_of(args.fps).map_err(|why| CliError::input(format!("--fps: {why}")))?;
    Ok((opts.for_trial(trial), delay))
}

/// The animated GIF of every room's replay, `DIR/STEM-ROOM.gif`, drawn side by side on
/// rayon's pool (the bytes do not depend on it).
fn room_gifs(
    ctx: &RenderContext,
    dir: &Path,
    stem: &str,
    trials: &[(usize, String, InstanceRun)],
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
/// room of `exp`, with its run label.
fn replay_trials(
    exp: &Experiment,
    genome: &SavedGenome,
) -> Result<Vec<(usize, String, InstanceRun)>, CliError> {
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
                    note!(
                        "note: no robot was evolved in room {name}; replaying the genome's main robot"
                    );
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
fn room_files(
    ctx: &RenderContext,
    dir: &Path,
    stem: &str,
    trials: &[(usize, String, InstanceRun)],
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

/// Writes the replay's CSV per room, JSON, figure and page, through the output guard: the same
/// replay again changes nothing; other files of those names are kept unless `--force`.
fn write_replay(
    args: &ReplayArgs,
    ctx: &RenderContext,
    genome: &SavedGenome,
    source_name: &str,
    trials: &[(usize, String, InstanceRun)],
    gifs: Option<(FrameOptions, u16)>,
    logs: &[LoggedPath],
) -> Result<(), CliError> {
    let out = &args.out;
    let (dir, stem) = out_parts(out)?;
    let mut files = Vec::new();
    let (lines, rooms_json) = room_files(ctx, &dir, &stem, trials, &mut files);
    let gif_files = match gifs {
        Some(gifs) => room_gifs(ctx, &dir, &stem, trials, gifs)?,
        None => Vec::new(),
    };
    let gif_names: Vec<String> = (gif_files.iter())
        .map(|(p, _)| p.display().to_string())
        .collect();
    files.extend(gif_files);
    let genome_path = genome.path.display();
    files.push((
        dir.join(format!("{stem}.json")),
        replay_json(&genome_path.to_string(), source_name, ctx, rooms_json),
    ));
    let pairs: Vec<_> = trials
        .iter()
        .map(|(r, _, run)| (&ctx.rooms[*r], &run.trajectory))
        .collect();
    let title = format!("Replay of {genome_path} (seed {})", ctx.seed);
    let svg = trajectories_svg_with(&title, &pairs, logs);
    let svg_path = dir.join(format!("{stem}.svg"));
    if args.png {
        let png_path = svg_path.with_extension("png");
        let png = svg_to_png(&svg).map_err(|e| io_err(&png_path, std::io::Error::other(e)))?;
        files.push((png_path, png));
    }
    files.push((svg_path, svg.into_bytes()));
    let about = format!(
        "genome {genome_path} · config {source_name} · seed {} · motivations (C, H, O, E) = {} · {} steps per trial",
        ctx.seed,
        xs(ctx),
        ctx.steps
    );
    let page = replay_page_with("fuzzymotiv replay", &about, ctx, trials, logs);
    files.push((out.clone(), page.into_bytes()));
    let state = check_files(&files, "--out", args.force)?;
    if state == FilesState::Write {
        std::fs::create_dir_all(&dir).map_err(|e| io_err(&dir, e))?;
        write_files(&files)?;
    }
    for line in &lines {
        fuzzymotiv_io::outln!("{line}")?;
    }
    if state == FilesState::Same {
        note!("{} already holds this replay; nothing to do", out.display());
    } else {
        note!("wrote {}", out.display());
    }
    if !gif_names.is_empty() {
        note!("GIFs: {}", gif_names.join(", "));
    }
    Ok(())
}

/// The replay's JSON document: program, genome, config, seed and every room's trajectory.
fn replay_json(
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

/// The directory and file stem of `--out FILE`; a directory is refused (the replay is a page
/// with files beside it, e.g. --out DIR/replay.html).
fn out_parts(out: &Path) -> Result<(PathBuf, String), CliError> {
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
