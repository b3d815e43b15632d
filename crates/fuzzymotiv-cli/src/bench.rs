//! `fuzzymotiv bench`: robot-steps per second on the hot path.

use std::time::Instant;

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::room::Room;

use crate::error::CliError;
use crate::inputs::{load_config, resolve};

/// Arguments of `fuzzymotiv bench`.
#[derive(clap::Args)]
pub struct BenchArgs {
    /// Room: a built-in name or a room file.
    #[arg(long, default_value = "H")]
    pub room: String,
    /// Robot-steps of each measurement (the population one evaluates whole populations until
    /// it has done at least this many, so its time is long enough to measure).
    #[arg(long, default_value_t = 2_000_000)]
    pub steps: usize,
    /// Threads for the population measurement [default: all cores].
    #[arg(long)]
    pub threads: Option<usize>,
    /// Population size of the population measurement (each runs one 400-step trial).
    #[arg(long, default_value_t = 200)]
    pub population: usize,
    /// Repetitions; the median is reported.
    #[arg(long, default_value_t = 5)]
    pub repeat: usize,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Motion model: "actions" (the paper's robot, default) or "wheels" (differential drive,
    /// the workload the Enki harness compares). Only executed steps count: idle steps after a
    /// trial ended at home are not work.
    #[arg(long, default_value = "actions", value_parser = ["actions", "wheels"])]
    pub motion: String,
    /// Override a config key (repeatable), e.g. --set trial.end_at_home=false.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Entry point of `fuzzymotiv bench`.
pub fn bench(args: BenchArgs) -> Result<(), CliError> {
    crate::run::set_threads(args.threads)?;
    if args.steps == 0 || args.repeat == 0 || args.population < 2 {
        return Err(CliError::input(
            "--steps and --repeat must be ≥ 1 and --population ≥ 2",
        ));
    }
    let sets = vec![
        format!("rooms=[{}]", toml::Value::String(args.room.clone())),
        format!("ga.population={}", args.population),
        format!("ga.elite={}", args.population.min(3) - 1),
        "aem.enabled=false".to_string(),
        format!("robot.motion=\"{}\"", args.motion),
    ];
    let sets: Vec<String> = sets.into_iter().chain(args.sets.iter().cloned()).collect();
    let loaded = if Room::builtin(&args.room).is_some() {
        load_config(None, &sets, None)?
    } else {
        let raw = fuzzymotiv::config::RawConfig::parse("", "bench", &sets)?;
        resolve(raw, std::path::Path::new("."), "--room")?
    };
    let exp: Experiment = loaded.experiment;
    let run = &exp.runs()[0];
    let population = exp.initial_population(run);
    let trial_steps = exp.trial_params().steps;
    // Single robot, single thread: whole trials of the paper's length until `steps` are done.
    let trials = args.steps.div_ceil(trial_steps);
    // Every repetition does the same work; its executed steps (idle steps are not work) are
    // counted by the evaluations themselves.
    let mut single = Vec::new();
    let mut sink = 0.0;
    let mut robot_steps = 0;
    for _ in 0..args.repeat {
        let t0 = Instant::now();
        robot_steps = 0;
        for k in 0..trials {
            let e = exp.evaluate(&population[k % population.len()], run, 0, k);
            sink += e.fitness;
            robot_steps += e.executed();
        }
        single.push(t0.elapsed().as_secs_f64());
    }
    // One population evaluation takes only milliseconds: time enough of them to cover `steps`.
    let evaluations = args.steps.div_ceil(population.len() * trial_steps);
    let mut pop = Vec::new();
    let mut pop_steps = 0;
    for _ in 0..args.repeat {
        let t0 = Instant::now();
        pop_steps = 0;
        for _ in 0..evaluations {
            let evals = exp.evaluate_population(&population, run, 0);
            sink += evals[0].fitness;
            pop_steps += evals.iter().map(|e| e.executed()).sum::<usize>();
        }
        pop.push(t0.elapsed().as_secs_f64());
    }
    let seconds = median(single);
    let pop_seconds = median(pop);
    let threads = rayon::current_num_threads();
    std::hint::black_box(sink);
    if args.json {
        let doc = serde_json::json!({
            "room": exp.arenas()[0].room().name,
            "motion": args.motion,
            "robot_steps": robot_steps,
            "seconds": seconds,
            "robot_steps_per_sec": robot_steps as f64 / seconds,
            "population": population.len(),
            "population_evaluations": evaluations,
            "population_robot_steps": pop_steps,
            "population_seconds": pop_seconds,
            "population_robot_steps_per_sec": pop_steps as f64 / pop_seconds,
            "threads": threads,
            "repeat": args.repeat,
            "statistic": "median",
            "version": fuzzymotiv::VERSION,
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serialisable")
        );
    } else {
        println!(
            "room {}, {} motion: single robot, 1 thread: {:.3} M robot-steps/s ({robot_steps} executed steps, median {:.3} s of {})",
            exp.arenas()[0].room().name,
            args.motion,
            robot_steps as f64 / seconds / 1e6,
            seconds,
            args.repeat
        );
        println!(
            "population {} x {trial_steps} steps, {evaluations} evaluations, {threads} threads: {:.3} M robot-steps/s (median {:.3} s)",
            population.len(),
            pop_steps as f64 / pop_seconds / 1e6,
            pop_seconds
        );
    }
    Ok(())
}
