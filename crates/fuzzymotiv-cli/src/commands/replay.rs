//! `fuzzymotiv replay`: run a saved genome again and write its trajectory (CSV and JSON) and a
//! replay page.
//!
//! The trial uses the experiment's room-modelling stream (docs/model.md §9: the run whose actions became
//! a room's stored instance), so `replay RUN_DIR` redraws exactly the paths of the run's
//! `report.html`; `--seed N` replays under another base seed. Same genome, room and seed → the
//! same trajectory, byte for byte. `--gif` adds an animated GIF per room
//! ([`fuzzymotiv_pipeline::render::frames`]); `--log` draws a robot's logged path over its room
//! (read by [`fuzzymotiv_pipeline::records::robot_log::RobotLog`], as `recognise` reads it).

use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::simulation::TrialParams;

use crate::console::note;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::{FilesState, check_files, io_err, write_files};
use fuzzymotiv_pipeline::files::inputs::{load_config, room_entry, rooms_unchanged};
use fuzzymotiv_pipeline::pipeline::replay::{
    ReplayTrial, replay_config, replay_json, replay_trials, room_files, room_gifs,
};
use fuzzymotiv_pipeline::records::context::RenderContext;
use fuzzymotiv_pipeline::records::genome::{SavedGenome, locate, read_genome};
use fuzzymotiv_pipeline::records::robot_log::RobotLog;
use fuzzymotiv_pipeline::render::frames::FrameOptions;
use fuzzymotiv_pipeline::render::frames::animate::delay_of;
use fuzzymotiv_pipeline::render::report::{replay_page_with, xs};
use fuzzymotiv_pipeline::render::svg::{LoggedPath, trajectories_svg_with};

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
    #[arg(long, allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_seed)]
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
    crate::console::config_notes(&loaded.notes);
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
    let rooms = match &args.room {
        Some(want) => vec![room_entry("--room", want, &loaded)?],
        None => loaded.raw.rooms.clone(),
    };
    let logs = logged_paths(&args.log, &rooms)?;
    let loaded = replay_config(&loaded, &genome, rooms, &source_name)?;
    let trials = replay_trials(&loaded.experiment, &genome, &crate::console::Stderr)?;
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

/// Writes the replay's CSV per room, JSON, figure and page, through the output guard: the same
/// replay again changes nothing; other files of those names are kept unless `--force`.
fn write_replay(
    args: &ReplayArgs,
    ctx: &RenderContext,
    genome: &SavedGenome,
    source_name: &str,
    trials: &[ReplayTrial],
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
        crate::console::outln!("{line}")?;
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
