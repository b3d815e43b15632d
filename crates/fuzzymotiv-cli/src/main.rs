//! `fuzzymotiv`: evolve Khepera controllers under fuzzy motivations, from the command line.

use fuzzymotiv_cli::{bench, error, inputs, note, outln, replay, reproduce, run, sweep};

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use error::CliError;

/// Evolutionary behaviour learning for a simulated Khepera robot under fuzzy motivations.
#[derive(Parser)]
#[command(name = "fuzzymotiv", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Evolve controllers as a config file says and write a run directory.
    #[command(
        override_usage = "fuzzymotiv run CONFIG [OPTIONS]\n       fuzzymotiv run --resume DIR [--threads N] [--png] [--quiet]"
    )]
    Run(run::RunArgs),
    /// Run the paper's whole study (both motivation settings, five rooms) and write its tables
    /// and figures.
    Reproduce(reproduce::ReproduceArgs),
    /// Run a saved genome again: write its trajectory (CSV, JSON) and a replay page (HTML).
    Replay(replay::ReplayArgs),
    /// Evaluate the TSK fuzzy fitness F for motivations X and fitness values Y.
    Fuzzy(FuzzyArgs),
    /// List the built-in rooms and validate room files.
    Rooms(RoomsArgs),
    /// Measure simulation speed (robot-steps per second).
    Bench(bench::BenchArgs),
    /// Expand a sweep file into its jobs (one JSON line each), or count them.
    Plan(sweep::PlanArgs),
    /// Run a sweep's jobs (all, a shard, or one array-task index) into DIR/jobs/ID/.
    Sweep(sweep::SweepArgs),
    /// Merge a sweep directory into results.csv, aggregate tables and summary plots.
    Merge(sweep::MergeArgs),
}

#[derive(clap::Args)]
struct FuzzyArgs {
    /// Motivations C,H,O,E (each in [0, 1], summing to 1; a sum within 0.001 of 1 is
    /// normalised), e.g. 0.8,0.1,0,0.1.
    #[arg(long, value_name = "C,H,O,E")]
    motivations: String,
    /// Fitness values a,g,l,b (each clamped to [0, 1]), e.g. 0.95,0.5,0,0.79.
    #[arg(long, value_name = "a,g,l,b", required_unless_present = "export_fll")]
    fitness: Option<String>,
    /// Also list the firing rules with their labels, weights and outputs.
    #[arg(long, requires = "fitness")]
    explain: bool,
    /// Write the 625-rule TSK of these motivations as a fuzzylite FLL file (`-`: standard
    /// output). The same file again is left as it is; another file there is kept unless --force.
    #[arg(long, value_name = "FILE")]
    export_fll: Option<PathBuf>,
    /// Replace an existing --export-fll FILE with other contents (only a regular file: a
    /// directory, device or link is never replaced).
    #[arg(long, requires = "export_fll")]
    force: bool,
}

#[derive(clap::Args)]
struct RoomsArgs {
    /// Room files to validate (TOML, docs/model.md §4 format): one or more, e.g. --check rooms/*.toml.
    #[arg(long = "check", value_name = "FILE", num_args = 1..)]
    check: Vec<PathBuf>,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(args) => run::run(args),
        Command::Reproduce(args) => reproduce::reproduce(args),
        Command::Replay(args) => replay::replay(args),
        Command::Fuzzy(args) => fuzzy(args),
        Command::Rooms(args) => rooms(args),
        Command::Bench(args) => bench::bench(args),
        Command::Plan(args) => sweep::plan(args),
        Command::Sweep(args) => sweep::sweep(args),
        Command::Merge(args) => sweep::merge(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader has gone (`| head -1`): end quietly, as a program killed by SIGPIPE.
        Err(e) if e.kind() == error::ErrorKind::ClosedStdout => ExitCode::from(e.exit_code()),
        Err(e) => {
            note!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

fn parse_four(text: &str, option: &str, names: [&str; 4]) -> Result<[f64; 4], CliError> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let usage = || {
        format!(
            "expected four comma-separated numbers {}, e.g. {option} 0.8,0.1,0,0.1",
            names.join(",")
        )
    };
    if parts.len() != 4 {
        return Err(CliError::input(format!(
            "{option}: got {} values; {}",
            parts.len(),
            usage()
        )));
    }
    let mut out = [0.0; 4];
    for (k, p) in parts.iter().enumerate() {
        out[k] = p
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                CliError::input(format!(
                    "{option}: `{p}` ({}) is not a finite number; {}",
                    names[k],
                    usage()
                ))
            })?;
    }
    Ok(out)
}

fn fuzzy(args: FuzzyArgs) -> Result<(), CliError> {
    use fuzzymotiv::fitness::fuzzy::{Motivations, TskFitness};
    let x = parse_four(&args.motivations, "--motivations", ["C", "H", "O", "E"])?;
    let (m, sum) = Motivations::normalised(x[0], x[1], x[2], x[3])
        .map_err(|e| CliError::input(format!("--motivations: {e}")))?;
    if let Some(sum) = sum {
        note!(
            "note: --motivations summed to {sum}, normalised to (C, H, O, E) = {:?}",
            m.as_array()
        );
    }
    let tsk = TskFitness::paper();
    if let Some(fitness) = &args.fitness {
        let y = parse_four(fitness, "--fitness", ["a", "g", "l", "b"])?;
        let f = tsk.evaluate(&m, y);
        outln!("{f:.12}")?;
        if args.explain {
            fuzzymotiv_cli::out!("{}", tsk.explain(&m, y))?;
        }
    }
    if let Some(path) = &args.export_fll {
        export_fll(path, &tsk, &m, args.force)?;
    }
    Ok(())
}

/// Writes the FLL engine to `path` (`-`: standard output) through the output guard.
fn export_fll(
    path: &std::path::Path,
    tsk: &fuzzymotiv::fitness::fuzzy::TskFitness,
    m: &fuzzymotiv::fitness::fuzzy::Motivations,
    force: bool,
) -> Result<(), CliError> {
    use fuzzymotiv_cli::files::{FilesState, check_files, write_files};
    let stdout = path.as_os_str() == "-";
    let name = match path.file_stem() {
        Some(s) if !stdout => s.to_string_lossy().into_owned(),
        _ => "fuzzymotiv".into(),
    };
    let text = fuzzymotiv::fitness::fll::to_fll(tsk, m, &name);
    if stdout {
        return fuzzymotiv_cli::out!("{text}");
    }
    let files = [(path.to_path_buf(), text.into_bytes())];
    if check_files(&files, "--export-fll", force)? == FilesState::Same {
        note!(
            "{} already holds this engine; nothing to do",
            path.display()
        );
        return Ok(());
    }
    write_files(&files)?;
    note!(
        "wrote {} ({} rules, fuzzylite FLL)",
        path.display(),
        tsk.rule_count()
    );
    Ok(())
}

fn rooms(args: RoomsArgs) -> Result<(), CliError> {
    use fuzzymotiv::simulation::room::{BUILTIN_ROOMS, Room};
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

fn print_room(prefix: &str, r: &fuzzymotiv::simulation::room::Room) -> Result<(), CliError> {
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
