//! `fuzzymotiv replay`: run a saved genome again and write its trajectory (CSV and JSON) and a
//! replay page ([`fuzzymotiv_pipeline::pipeline::replay::replay`]; this front parses the
//! arguments and prints).
//!
//! The trial uses the experiment's room-modelling stream (docs/model.md §9: the run whose actions became
//! a room's stored instance), so `replay RUN_DIR` redraws exactly the paths of the run's
//! `report.html`; `--seed N` replays under another base seed. Same genome, room and seed → the
//! same trajectory, byte for byte. `--gif` adds an animated GIF per room
//! ([`fuzzymotiv_pipeline::render::frames`]); `--log` draws a robot's logged path over its room
//! (read by [`fuzzymotiv_pipeline::records::robot_log::RobotLog`], as `recognise` reads it).

use std::path::PathBuf;

use crate::console::note;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::FilesState;
use fuzzymotiv_pipeline::pipeline::replay::{GifSettings, ReplayOptions, replay as replay_genome};

use crate::png::rasteriser;

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
    let opts = ReplayOptions {
        source: args.source,
        config: args.config,
        room: args.room,
        seed: args.seed,
        out: args.out,
        png: rasteriser(args.png),
        gif: args.gif.then_some(GifSettings {
            size: args.size,
            stride: args.stride,
            fps: args.fps,
        }),
        logs: args.log,
        force: args.force,
    };
    let done = replay_genome(&opts, &mut |line| note!("{line}"))?;
    for line in &done.lines {
        crate::console::outln!("{line}")?;
    }
    if done.state == FilesState::Same {
        note!(
            "{} already holds this replay; nothing to do",
            opts.out.display()
        );
    } else {
        note!("wrote {}", opts.out.display());
    }
    if !done.gifs.is_empty() {
        note!("GIFs: {}", done.gifs.join(", "));
    }
    Ok(())
}
