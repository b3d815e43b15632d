//! `fuzzymotiv`: evolve Khepera controllers under fuzzy motivations, from the command line.

mod args;
mod commands;
mod console;
mod png;
mod progress;

use std::io::IsTerminal;
use std::process::ExitCode;

use crate::console::note;
use clap::{Parser, Subcommand};
use fuzzymotiv_pipeline::files::error::CliError;

use crate::commands::{
    bench, calibrate, claims, compare, export, fuzzy, lab, recognise, replay, reproduce,
    robustness, rooms, run, study, sweep, transfer,
};

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
        override_usage = "fuzzymotiv run CONFIG [OPTIONS]\n       fuzzymotiv run --resume DIR [--threads N] [--png] [--quiet]\n       fuzzymotiv run --continue DIR --generations N --out NEW [OPTIONS]"
    )]
    Run(run::RunArgs),
    /// Run the paper's whole study (both motivation settings, five rooms) and write its tables
    /// and figures.
    Reproduce(reproduce::ReproduceArgs),
    /// Run a saved genome again: write its trajectory (CSV, JSON) and a replay page (HTML).
    Replay(replay::ReplayArgs),
    /// Export an evolved controller for a real robot: C99 (the simulator's outputs bit for bit),
    /// a self-describing JSON document or an ONNX model.
    Export(export::ExportArgs),
    /// Turn bench measurements of a robot's IR sensors (CSV) into a sensor table file for
    /// `trial.sensor_table`, and estimate the sensor noise from their spread.
    Calibrate(calibrate::CalibrateArgs),
    /// Evaluate a run's best robot under the perturbations a real robot brings (sensor noise,
    /// sensor sensitivity, a dead sensor, wheel bias, a larger body) on paired streams.
    Robustness(robustness::RobustnessArgs),
    /// Recognise the room of a real robot's logs with a run's room model (its SOM): one CSV
    /// per log, a row per step with the action or the motor outputs.
    Recognise(recognise::RecogniseArgs),
    /// Drive a run's evolved controller in Enki, an independent simulator (its exported C on
    /// Enki's own robot model): a robot log per test run, measured as the simulator measures
    /// its trials, beside the run's own test runs.
    Transfer(transfer::TransferArgs),
    /// Recompute a finished study's claims from its records (summary.json), e.g. at another
    /// significance level: effect, interval, p-value, verdict and minimum detectable difference.
    Claims(claims::ClaimsArgs),
    /// Compare two runs (over their test runs), two studies or two sweep settings (over seeds
    /// or replicates), per room and overall: means, difference, interval and p-value.
    Compare(compare::CompareArgs),
    /// Evaluate the TSK fuzzy fitness F for motivations X and fitness values Y.
    Fuzzy(fuzzy::FuzzyArgs),
    /// List the built-in rooms and validate room files.
    Rooms(rooms::RoomsArgs),
    /// Measure simulation speed (robot-steps per second).
    Bench(bench::BenchArgs),
    /// Run a study of your own: arms (any config, robot or motivations), paired seeds and
    /// typed hypotheses, judged by the study's declared analysis (claims, forest plot, report).
    Study(study::StudyArgs),
    /// Expand a sweep file into its jobs (one JSON line each), or count them.
    Plan(sweep::PlanArgs),
    /// Run a sweep's jobs (all, a shard, or one array-task index) into DIR/jobs/ID/.
    Sweep(sweep::SweepArgs),
    /// Merge a sweep directory into results.csv, aggregate tables and summary plots.
    Merge(sweep::MergeArgs),
    /// Start the lab: a local web page to set the motivations, draw rooms, evolve live and
    /// compare runs.
    Lab(lab::LabArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // `--help` and `--version`: on standard output like every result, so a failure to write
        // it is the same one-line error (and a closed one the same quiet end).
        Err(e) if !e.use_stderr() => return finish(show_help(&e)),
        // A usage error: clap's message on standard error, status 2.
        Err(e) => e.exit(),
    };
    finish(execute(cli))
}

/// Clap's help or version text on standard output through [`crate::console::out!`] (plain
/// text unless standard output is a terminal, where clap's colours are kept).
fn show_help(e: &clap::Error) -> Result<(), CliError> {
    let text = e.render();
    if std::io::stdout().is_terminal() {
        crate::console::out!("{}", text.ansi())
    } else {
        crate::console::out!("{text}")
    }
}

fn execute(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Run(args) => run::run(args),
        Command::Reproduce(args) => reproduce::reproduce(args),
        Command::Replay(args) => replay::replay(args),
        Command::Export(args) => export::export(args),
        Command::Calibrate(args) => calibrate::calibrate_command(args),
        Command::Robustness(args) => robustness::robustness(args),
        Command::Recognise(args) => recognise::recognise(args),
        Command::Transfer(args) => transfer::transfer_command(args),
        Command::Claims(args) => claims::claims_command(args),
        Command::Compare(args) => compare::compare_command(args),
        Command::Fuzzy(args) => fuzzy::fuzzy(args),
        Command::Rooms(args) => rooms::rooms(args),
        Command::Bench(args) => bench::bench(args),
        Command::Study(args) => study::study(args),
        Command::Plan(args) => sweep::plan(args),
        Command::Sweep(args) => sweep::sweep(args),
        Command::Merge(args) => sweep::merge(args),
        Command::Lab(args) => lab::lab(args),
    }
}

/// The exit status of a command's outcome, with its error (if any) on standard error.
fn finish(result: Result<(), CliError>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader has gone (`| head -1`): end quietly, as a program killed by SIGPIPE.
        Err(CliError::ClosedStdout) => ExitCode::from(141),
        Err(e) => {
            note!("error: {e}");
            ExitCode::from(exit_code(&e))
        }
    }
}

/// The exit code of an error: 2 for bad input (a config, a room file, an option, an output that
/// must not be replaced), 1 for a failure while running, 141 for a closed standard output (as a
/// program killed by SIGPIPE).
fn exit_code(e: &CliError) -> u8 {
    match e {
        CliError::Input(_) | CliError::Setup(_) | CliError::StudyFile(_) | CliError::Output(_) => 2,
        CliError::Runtime(_) | CliError::Io { .. } | CliError::FileSystem(_) => 1,
        CliError::ClosedStdout => 141,
    }
}
