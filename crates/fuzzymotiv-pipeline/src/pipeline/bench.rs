//! `fuzzymotiv bench`'s measurements: robot-steps per second on the hot path, one robot on one
//! thread and whole populations in parallel ([`measure`] → [`BenchReport`]), of the experiment
//! a [`BenchSetup`] makes ([`bench_experiment`], sizes checked by [`check_sizes`]). The command
//! line turns its arguments into them and prints the report.

use std::time::Instant;

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::simulation::{Motion, Room};

use crate::files::error::CliError;
use crate::files::inputs::{load_config, resolve};

/// What a measurement does: plain data.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BenchOptions {
    /// Robot-steps of each measurement (the population one evaluates whole populations until
    /// it has done at least this many).
    pub steps: usize,
    /// Repetitions; the median is reported.
    pub repeat: usize,
    /// The motion model's name, as the report gives it (`actions` or `wheels`).
    pub motion: String,
}

/// The median of `v` (the upper one of an even count).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// What `fuzzymotiv bench --json` prints (fields in the order serde_json's map sorts them).
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub struct BenchReport {
    /// Motion model measured.
    pub motion: String,
    /// Population size of the population measurement.
    pub population: usize,
    /// Whole-population evaluations per repetition.
    pub population_evaluations: usize,
    /// Executed robot-steps of a repetition of the population measurement (median).
    pub population_robot_steps: usize,
    /// Their rate (median repetition).
    pub population_robot_steps_per_sec: f64,
    /// Median seconds of the population measurement.
    pub population_seconds: f64,
    /// Repetitions.
    pub repeat: usize,
    /// Robot measured (its robot file's name).
    pub robot: String,
    /// Executed robot-steps of a repetition of the single-robot measurement (median).
    pub robot_steps: usize,
    /// Their rate (median repetition).
    pub robot_steps_per_sec: f64,
    /// Room measured.
    pub room: String,
    /// Median seconds of the single-robot measurement.
    pub seconds: f64,
    /// Always "median".
    pub statistic: String,
    /// Threads of the population measurement.
    pub threads: usize,
    /// Steps of one trial.
    #[serde(skip)]
    pub trial_steps: usize,
    /// fuzzymotiv's version.
    pub version: String,
}

/// Times `work(r)` for each repetition `r` of `repeat`; returns the median seconds and the median
/// executed robot-steps of a repetition. Each repetition runs new trials (new random streams), so
/// no repetition finds its poses already remembered by an earlier one (the library's memo of
/// sightings).
fn timed(repeat: usize, mut work: impl FnMut(usize) -> usize) -> (f64, usize) {
    let mut seconds = Vec::new();
    let mut steps = Vec::new();
    for r in 0..repeat {
        let t0 = Instant::now();
        steps.push(work(r) as f64);
        seconds.push(t0.elapsed().as_secs_f64());
    }
    (median(seconds), median(steps) as usize)
}

/// The two measurements of `exp`: one robot on one thread, whole trials until `steps` are done; then
/// whole populations in parallel (each takes only milliseconds: enough of them to cover
/// `steps`). Only executed steps count (idle steps are not work).
pub fn measure(exp: &Experiment, options: &BenchOptions) -> BenchReport {
    let run = &exp.runs()[0];
    let population = exp.initial_population(run);
    let trial_steps = exp.trial_params().steps();
    // One evaluation of a robot runs a trial in each of the run's rooms.
    let robot_steps_each = trial_steps * run.rooms.len();
    let mut sink = 0.0;
    let trials = options.steps.div_ceil(robot_steps_each);
    let (seconds, robot_steps) = timed(options.repeat, |r| {
        (0..trials)
            .map(|k| {
                let e = exp.evaluate(&population.network(k % population.len()), run, r, k);
                sink += e.fitness;
                e.executed()
            })
            .sum()
    });
    let evaluations = options.steps.div_ceil(population.len() * robot_steps_each);
    let (pop_seconds, pop_steps) = timed(options.repeat, |r| {
        (0..evaluations)
            .map(|e| {
                // A generation number of its own: fresh noise, as each generation of a run has.
                let evals = exp.evaluate_population(&population, run, r * evaluations + e);
                sink += evals[0].fitness;
                evals.iter().map(|e| e.executed()).sum::<usize>()
            })
            .sum()
    });
    std::hint::black_box(sink);
    BenchReport {
        motion: options.motion.clone(),
        population: population.len(),
        population_evaluations: evaluations,
        population_robot_steps: pop_steps,
        population_robot_steps_per_sec: pop_steps as f64 / pop_seconds,
        population_seconds: pop_seconds,
        repeat: options.repeat,
        robot: exp.trial_params().robot().spec().name().to_string(),
        robot_steps,
        robot_steps_per_sec: robot_steps as f64 / seconds,
        room: exp.arenas()[0].room().name.clone(),
        seconds,
        statistic: "median".to_string(),
        threads: rayon::current_num_threads(),
        trial_steps,
        version: fuzzymotiv::VERSION.to_string(),
    }
}

/// The experiment a bench measures, as `fuzzymotiv bench`'s options give it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BenchSetup {
    /// A built-in room's name or a room file.
    pub room: String,
    /// Population size of the population measurement.
    pub population: usize,
    /// `actions` or `wheels`.
    pub motion: String,
    /// A built-in robot's name or a robot file [default: the config's, the Khepera].
    pub robot: Option<String>,
    /// Config overrides, `KEY=VALUE`, after the setup's own.
    pub sets: Vec<String>,
}

/// The most robot-steps of one measurement (about an hour at 3 M robot-steps per second).
pub const MAX_BENCH_STEPS: usize = 10_000_000_000;

/// Refuses a measurement size out of range: steps (1 to [`MAX_BENCH_STEPS`]), repetitions
/// (1 to 10,000) and population (2 to `params::BIG`), naming the option.
pub fn check_sizes(steps: usize, repeat: usize, population: usize) -> Result<(), CliError> {
    let checks = [
        ("--steps", steps, 1, MAX_BENCH_STEPS),
        ("--repeat", repeat, 1, 10_000),
        ("--population", population, 2, fuzzymotiv::params::BIG),
    ];
    for (option, value, low, high) in checks {
        if !(low..=high).contains(&value) {
            return Err(CliError::input(format!(
                "{option}: must be from {low} to {high}, got {value}"
            )));
        }
    }
    Ok(())
}

/// The experiment measured: one room, the population size asked for, no AEM, the motion and
/// robot asked for, then the overrides; refused when the overrides leave the robot another
/// motion than `setup.motion`.
pub fn bench_experiment(setup: &BenchSetup) -> Result<Experiment, CliError> {
    let mut sets = vec![
        format!("rooms=[{}]", toml::Value::String(setup.room.clone())),
        format!("ga.population={}", setup.population),
        format!("ga.elite={}", setup.population.min(3) - 1),
        "aem.enabled=false".to_string(),
        format!("robot.motion=\"{}\"", setup.motion),
    ];
    if let Some(robot) = &setup.robot {
        sets.push(format!("robot.file={}", toml::Value::String(robot.clone())));
    }
    sets.extend(setup.sets.iter().cloned());
    let loaded = if Room::builtin(&setup.room).is_some() {
        load_config(None, &sets, None)?
    } else {
        let raw = fuzzymotiv::experiment::RawConfig::parse("", "bench", &sets)?;
        resolve(raw, std::path::Path::new("."), "--room")?
    };
    check_motion(&loaded.experiment, &setup.motion)?;
    Ok(loaded.experiment)
}

/// The experiment runs the motion `--motion` asked for: a `--set robot=NAME` replaces the whole
/// `[robot]` table, and with it the `robot.motion` that `--motion` set, so the robot would run
/// its default motion under another motion's name.
fn check_motion(exp: &Experiment, asked: &str) -> Result<(), CliError> {
    let name = match exp.trial_params().robot().motion() {
        Motion::Actions => "actions",
        Motion::Wheels => "wheels",
    };
    if name == asked {
        return Ok(());
    }
    Err(CliError::input(format!(
        "--motion {asked}: the --set options leave the robot with {name} motion (a --set \
         robot.motion, or a --set robot=NAME, which replaces the whole [robot] table and \
         robot.motion with it); choose the motion with --motion and name the robot with \
         --set robot.file=NAME"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::inputs::load_config;

    /// A measurement runs from the library on an experiment of the caller's: whole trials of
    /// one robot and whole populations, each counted by its executed steps, the medians of
    /// the repetitions.
    #[test]
    fn a_bench_measures_an_experiment_from_the_library() {
        let sets: Vec<String> = [
            "rooms=[\"H\"]",
            "ga.population=4",
            "ga.elite=2",
            "trial.steps=50",
            "aem.enabled=false",
        ]
        .map(String::from)
        .to_vec();
        let loaded = load_config(None, &sets, None).unwrap();
        let options = BenchOptions {
            steps: 120,
            repeat: 3,
            motion: "actions".into(),
        };
        let report = measure(&loaded.experiment, &options);
        assert_eq!((report.population, report.repeat), (4, 3));
        assert_eq!(report.trial_steps, 50);
        assert_eq!(
            report.population_evaluations, 1,
            "4 robots × 50 steps ≥ 120"
        );
        assert!(
            report.robot_steps > 0 && report.robot_steps <= 150,
            "{report:?}"
        );
        assert!(report.population_robot_steps <= 200, "{report:?}");
        assert_eq!(
            (report.room.as_str(), report.robot.as_str()),
            ("H", "khepera")
        );
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
    }

    /// The setup's experiment has its room, population and motion; a `--set robot=NAME`
    /// that undoes `--motion wheels` is refused, and sizes out of range name their option.
    #[test]
    fn a_bench_setup_makes_its_experiment_and_refuses_a_set_that_undoes_its_motion() {
        let setup = BenchSetup {
            room: "H".into(),
            population: 5,
            motion: "wheels".into(),
            robot: None,
            sets: Vec::new(),
        };
        let exp = bench_experiment(&setup).unwrap();
        assert_eq!(exp.trial_params().robot().motion(), Motion::Wheels);
        assert_eq!(exp.arenas().len(), 1);
        let undone = BenchSetup {
            sets: vec!["robot=\"khepera\"".into()],
            ..setup
        };
        let e = bench_experiment(&undone).unwrap_err().to_string();
        assert!(
            e.contains("--motion wheels: the --set options leave"),
            "{e}"
        );
        let e = check_sizes(1, 1, 1).unwrap_err().to_string();
        assert!(e.starts_with("--population: must be from 2"), "{e}");
        assert!(check_sizes(1, 1, 2).is_ok());
    }
}
