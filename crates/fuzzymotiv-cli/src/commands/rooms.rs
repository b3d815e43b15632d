//! `fuzzymotiv rooms`: the built-in rooms, or room files validated.

use std::path::PathBuf;

use fuzzymotiv_io::files::error::CliError;
use fuzzymotiv_io::files::inputs;
use fuzzymotiv_io::outln;

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
            Ok(r) => print_room(&format!("ok  {}: ", path.display()), &r)?,
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
