//! `fuzzymotiv bench`: robot-steps per second on the hot path (the experiment and the
//! measurement are [`fuzzymotiv_pipeline::pipeline::bench`]'s; this front parses and prints).

use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::pipeline::bench::{
    BenchOptions, BenchReport, BenchSetup, bench_experiment, check_sizes, measure,
};

/// Arguments of `fuzzymotiv bench`.
#[derive(clap::Args)]
pub struct BenchArgs {
    /// Room: a built-in name or a room file.
    #[arg(long, default_value = "H")]
    pub room: String,
    /// Robot-steps of each measurement (the population one evaluates whole populations until
    /// it has done at least this many, so its time is long enough to measure).
    #[arg(long, allow_hyphen_values = true, default_value_t = 2_000_000, value_parser = crate::args::whole_number)]
    pub steps: usize,
    /// Threads for the population measurement, 1 to 256 [default: all cores].
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = fuzzymotiv_pipeline::files::inputs::parse_threads)]
    pub threads: Option<usize>,
    /// Population size of the population measurement (each robot runs one 400-step trial per
    /// room; `--set rooms=[...]` evaluates in several rooms).
    #[arg(long, allow_hyphen_values = true, default_value_t = 200, value_parser = crate::args::whole_number)]
    pub population: usize,
    /// Repetitions; the median is reported.
    #[arg(long, allow_hyphen_values = true, default_value_t = 5, value_parser = crate::args::whole_number)]
    pub repeat: usize,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Motion model: "actions" (the paper's robot, default) or "wheels" (differential drive,
    /// the workload the Enki harness compares). Only executed steps count: idle steps after a
    /// trial ended at home are not work.
    #[arg(long, default_value = "actions", value_parser = ["actions", "wheels"])]
    pub motion: String,
    /// Robot: a built-in robot's name (khepera, epuck2, thymio2, khepera4) or a robot file
    /// [default: the paper's Khepera]; the same as --set robot.file=NAME. A robot larger than
    /// the Khepera needs rooms it fits (the Thymio II's: --room rooms/thymio2/H.toml).
    #[arg(long, value_name = "NAME")]
    pub robot: Option<String>,
    /// Override a config key (repeatable), e.g. --set trial.end_at_home=false; another robot:
    /// --set robot.file=epuck2 (a built-in name or a robot file).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

/// Entry point of `fuzzymotiv bench`.
pub fn bench(args: BenchArgs) -> Result<(), CliError> {
    fuzzymotiv_pipeline::pipeline::lanes::set_threads(args.threads)?;
    check_sizes(args.steps, args.repeat, args.population)?;
    let exp = bench_experiment(&BenchSetup {
        room: args.room.clone(),
        population: args.population,
        motion: args.motion.clone(),
        robot: args.robot.clone(),
        sets: args.sets.clone(),
    })?;
    let options = BenchOptions {
        steps: args.steps,
        repeat: args.repeat,
        motion: args.motion.clone(),
    };
    let report = measure(&exp, &options);
    if args.json {
        crate::console::outln!(
            "{}",
            serde_json::to_string_pretty(&report).expect("serialisable")
        )
    } else {
        print_report(&report)
    }
}

/// The report as two lines of text.
fn print_report(r: &BenchReport) -> Result<(), CliError> {
    crate::console::outln!(
        "{} in room {}, {} motion: single robot, 1 thread: {:.3} M robot-steps/s ({} executed steps, median {:.3} s of {})",
        r.robot,
        r.room,
        r.motion,
        r.robot_steps_per_sec / 1e6,
        r.robot_steps,
        r.seconds,
        r.repeat
    )?;
    crate::console::outln!(
        "population {} x {} steps, {} evaluations, {} threads: {:.3} M robot-steps/s (median {:.3} s)",
        r.population,
        r.trial_steps,
        r.population_evaluations,
        r.threads,
        r.population_robot_steps_per_sec / 1e6,
        r.population_seconds
    )
}
