// A term of your own, end to end (docs/guide/motivations.md §5, which quotes this file from
// `use` on; tests/it/guide_rust.rs checks the quote and runs it): a `Term` registered under a
// name, a motivation weighing it, a few generations evolved, and the best robot's F and term
// read back.
//
//     cargo run --release -p fuzzymotiv --example own_term

use std::ops::ControlFlow;
use std::sync::Arc;

use fuzzymotiv::experiment::UserTerm;
use fuzzymotiv::fitness::{Term, TrialRecord};
use fuzzymotiv::{Experiment, RawConfig, Room};

/// Smoothness: 1 − the share of executed steps that turned.
#[derive(Debug)]
struct Smooth;

impl Term for Smooth {
    fn value(&self, trial: &TrialRecord<'_>) -> f64 {
        let t = trial.trajectory;
        let steps = t.idle.iter().filter(|i| !**i).count().max(1);
        let turns = t
            .poses
            .windows(2)
            .filter(|p| p[0].heading != p[1].heading)
            .count();
        1.0 - turns as f64 / steps as f64
    }
}

const CONFIG: &str = r#"
rooms = ["H", "T"]
[ga]
population = 20
generations = 5
[trial]
steps = 200
[aem]
enabled = false
[motivations]
curiosity = 0.6
homing = 0.1
orientation = 0.0
energy = 0.1
smooth = 0.2   # weighs the term registered as "smooth" below
"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // 1. Register the term under the name the motivation weighs.
    let raw = RawConfig::parse(CONFIG, "mine.toml", &[])?;
    let rooms = vec![Room::builtin("H").unwrap(), Room::builtin("T").unwrap()];
    let smooth = UserTerm::computed("smooth", Arc::new(Smooth));
    let exp = Experiment::with_terms(&raw, rooms, &[smooth], "mine.toml")?;
    println!("inputs: {:?}", exp.motivations().input_names()); // a, g, l, b, smooth

    // 2. Evolve: the observer sees every generation's record (the generations.csv row).
    let outcome = exp.run(&mut |_run, state| {
        let record = state.record();
        let smooth = record.terms.user.as_slice()[0]; // population mean, the `smooth` column
        println!(
            "generation {}: best F {:.3}, mean F {:.3}, mean smooth {smooth:.3}",
            record.generation, record.stats.max, record.stats.mean
        );
        ControlFlow::Continue(())
    })?;

    // 3. Read the result: the best robot of the last generation, its F and its term per room.
    let evolution = &outcome.evolutions[0];
    let best = &evolution.evaluations[evolution.best];
    println!("best robot: F = {:.3}", best.fitness);
    for (room, score) in exp.room_names().iter().zip(&best.per_room) {
        let smooth = score.terms.user.as_slice()[0];
        let (f, a) = (score.f, score.terms.a);
        println!("  {room}: F = {f:.3}, a = {a:.2}, smooth = {smooth:.2}");
    }
    Ok(())
}
