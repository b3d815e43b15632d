//! `fuzzymotiv rooms`: the built-in rooms, or room files validated.

use std::path::PathBuf;

use crate::console::outln;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::inputs;

/// Arguments of `fuzzymotiv rooms`.
#[derive(clap::Args)]
pub struct RoomsArgs {
    /// Room files to validate (TOML, docs/model.md §4 format): one or more, e.g. --check rooms/*.toml.
    #[arg(long = "check", value_name = "FILE", num_args = 1..)]
    check: Vec<PathBuf>,
}

/// Entry point of `fuzzymotiv rooms`.
pub fn rooms(args: RoomsArgs) -> Result<(), CliError> {
    use fuzzymotiv::simulation::{BUILTIN_ROOMS, Room};
    if args.check.is_empty() {
        outln!(
            "{:<10} {:>10} {:>10}  home (x mm, y mm, heading °)",
            "room",
            "area m²",
            "perim. m"
        )?;
        for name in BUILTIN_ROOMS {
            let r = Room::builtin(name).expect("built-in");
            print_room("", &r)?;
        }
        return Ok(());
    }
    let mut failures = Vec::new();
    for path in &args.check {
        match inputs::load_room_file(path) {
            Ok(r) => outln!("ok  {}: {}", path.display(), checked_room(&r))?,
            Err(e) => failures.push(e.to_string()),
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(CliError::input(failures.join("\n")))
    }
}

fn print_room(prefix: &str, r: &fuzzymotiv::simulation::Room) -> Result<(), CliError> {
    outln!(
        "{prefix}{:<10} {:>10.3} {:>10.3}  ({}, {}, {})",
        r.name,
        r.area() / 1e6,
        r.perimeter() / 1e3,
        r.home.x,
        r.home.y,
        r.home.heading.to_degrees().round()
    )
}

/// What `rooms --check` says of a valid room, each quantity named: its name, area, perimeter,
/// home pose and mission (goal zone, waypoints in order) or that it has none.
fn checked_room(r: &fuzzymotiv::simulation::Room) -> String {
    let zone = |z: &fuzzymotiv::simulation::Zone| {
        format!("({}, {}) radius {} mm", z.centre.x, z.centre.y, z.radius)
    };
    let mut mission = Vec::new();
    if let Some(goal) = &r.mission.goal {
        mission.push(format!("goal {}", zone(goal)));
    }
    if !r.mission.waypoints.is_empty() {
        let each: Vec<String> = r.mission.waypoints.iter().map(zone).collect();
        mission.push(format!(
            "{} waypoints in file order: {}",
            each.len(),
            each.join(", ")
        ));
    }
    if mission.is_empty() {
        mission.push("no mission (no goal zone or waypoints)".into());
    }
    format!(
        "room {}, area {:.3} m², perimeter {:.3} m, home ({}, {}) mm heading {}°, {}",
        r.name,
        r.area() / 1e6,
        r.perimeter() / 1e3,
        r.home.x,
        r.home.y,
        r.home.heading.to_degrees().round(),
        mission.join(", ")
    )
}
