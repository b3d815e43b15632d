//! Value-stability of every individual: the fitness F and the terms a, g, l, b of each individual
//! in each room, for every generation of small runs of the paper's two settings (high and low
//! curiosity) and of the wheels model, written with every bit (Rust's shortest round-trip
//! decimal) and compared with `tests/golden/individuals/`. A change of one ulp in any
//! individual's terms or F fails here, where the 9-decimal tables of the CLI's goldens could
//! hide it.
//!
//! A change that alters results on purpose regenerates these files
//! (`FUZZYMOTIV_BLESS=1 cargo test -p fuzzymotiv --test it golden_individuals::`) and bumps
//! [`fuzzymotiv::MODEL_VERSION`] in the same commit (`tests/it/model_version.rs` holds it to that).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use fuzzymotiv::{BuiltinRoomsOnly, RawConfig, Setup};

/// The generations of the golden runs.
const GENERATIONS: usize = 4;

/// The GA and trial sizes of the golden runs: big enough that trials end at home, escape the
/// home zone and hit walls, and that reverting one ulp-sized change of g (hypot against
/// √(dx² + dy²)) fails every file; small enough for a debug build.
const SIZES: [&str; 3] = ["ga.population=16", "ga.generations=4", "trial.steps=200"];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/individuals")
}

/// Every individual of every generation of `config` (a file under `configs/`) with `extra`
/// settings: one CSV row per individual and room, then one per individual over its rooms
/// (`room` = `all`, F the GA's fitness and the terms' means).
fn individuals(config: &str, extra: &[&str]) -> String {
    let path = repo().join("configs").join(config);
    let text = std::fs::read_to_string(&path).unwrap();
    let sets: Vec<String> = SIZES.iter().chain(extra).map(|s| s.to_string()).collect();
    let raw = RawConfig::parse(&text, config, &sets).unwrap();
    let exp = Setup::resolve(raw, config, &BuiltinRoomsOnly)
        .unwrap()
        .experiment;
    let run = &exp.runs()[0];
    let names = exp.room_names();
    let mut out = String::from("generation,individual,room,F,a,g,l,b\n");
    let mut population = exp.initial_population(run);
    for generation in 0..GENERATIONS {
        let evals = exp.evaluate_population(&population, run, generation);
        for (i, e) in evals.iter().enumerate() {
            for (k, s) in e.per_room.iter().enumerate() {
                let room = &names[run.rooms[k]];
                let t = s.terms;
                let _ = writeln!(
                    out,
                    "{generation},{i},{room},{},{},{},{},{}",
                    s.f, t.a, t.g, t.l, t.b
                );
            }
            let t = e.mean_terms();
            let f = e.fitness;
            let _ = writeln!(
                out,
                "{generation},{i},all,{f},{},{},{},{}",
                t.a, t.g, t.l, t.b
            );
        }
        if generation + 1 < GENERATIONS {
            let fitness: Vec<f64> = evals.iter().map(|e| e.fitness).collect();
            population = exp.breed(&population, &fitness, run, generation).unwrap();
        }
    }
    out
}

/// Compares `got` with the golden file `name`, naming the first line that differs; with
/// `FUZZYMOTIV_BLESS=1` writes it instead.
fn assert_golden(name: &str, got: &str) {
    let path = golden_dir().join(name);
    if std::env::var_os("FUZZYMOTIV_BLESS").is_some() {
        std::fs::create_dir_all(golden_dir()).unwrap();
        std::fs::write(&path, got).unwrap();
        return;
    }
    let want = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (FUZZYMOTIV_BLESS=1 writes it)", path.display()));
    if want == got {
        return;
    }
    let line = (want.lines().zip(got.lines()))
        .enumerate()
        .find(|(_, (w, g))| w != g);
    match line {
        Some((n, (w, g))) => panic!(
            "{name} differs from the golden at line {}:\n  golden: {w}\n  now:    {g}\n\
             Results changed. If on purpose: regenerate (FUZZYMOTIV_BLESS=1) and bump \
             fuzzymotiv::MODEL_VERSION in the same commit; if not, it is a bug.",
            n + 1
        ),
        None => panic!(
            "{name}: {} lines in the golden, {} now",
            want.lines().count(),
            got.lines().count()
        ),
    }
}

/// The paper's high-curiosity setting (C, H, O, E) = (.8, .1, 0, .1), the default model.
#[test]
fn every_individual_of_high_curiosity_is_pinned() {
    assert_golden(
        "high-curiosity.csv",
        &individuals("high-curiosity.toml", &[]),
    );
}

/// The paper's low-curiosity setting (C, H, O, E) = (.5, .3, 0, .2), the default model.
#[test]
fn every_individual_of_low_curiosity_is_pinned() {
    assert_golden("low-curiosity.csv", &individuals("low-curiosity.toml", &[]));
}

/// The wheels model (continuous motor outputs, battery from wheel speeds) in the
/// low-curiosity setting.
#[test]
fn every_individual_of_the_wheels_model_is_pinned() {
    let wheels = ["robot.motion=\"wheels\""];
    assert_golden("wheels.csv", &individuals("low-curiosity.toml", &wheels));
}
