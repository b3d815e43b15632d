//! # fuzzymotiv
//!
//! Evolutionary behaviour learning for a simulated Khepera robot under *fuzzy motivations*,
//! after "Fuzzy Motivations for Evolutionary Behavior Learning by a Mobile Robot": neural
//! controllers are evolved by a genetic algorithm whose fitness is a Takagi–Sugeno–Kang fuzzy
//! combination of curiosity, homing, orientation and energy; the best robot's action sequences
//! then model and recognise rooms (action-based environment modelling).
//!
//! A whole experiment in a few lines: two built-in rooms, a small population, a few
//! generations; then the best robot's F and the room modelling's recognition test.
//!
//! ```
//! use fuzzymotiv::{BuiltinRoomsOnly, RawConfig, Setup};
//! use std::ops::ControlFlow;
//!
//! let config = r#"
//!     rooms = ["H", "square"]
//!     seed = 7
//!     [ga]
//!     population = 8
//!     generations = 3
//!     [trial]
//!     steps = 100
//!     [motivations]  # the paper's high-curiosity setting
//!     curiosity = 0.8
//!     homing = 0.1
//!     orientation = 0.0
//!     energy = 0.1
//! "#;
//! let raw = RawConfig::parse(config, "example", &[]).unwrap();
//! let setup = Setup::resolve(raw, "example", &BuiltinRoomsOnly).unwrap();
//! let exp = &setup.experiment;
//! let outcome = exp
//!     .run(&mut |_run, state| {
//!         println!("generation {}: best F {:.3}", state.history.len(), state.record().stats.max);
//!         ControlFlow::Continue(())
//!     })
//!     .unwrap();
//! let evolution = &outcome.evolutions[0];
//! println!("best robot: F = {:.3}", evolution.evaluations[evolution.best].fitness);
//! for (r, room) in exp.room_names().iter().enumerate() {
//!     let modelled = &outcome.aem_for_room(r).rooms[r];
//!     let pct = modelled.recognition_pct.unwrap_or(0.0);
//!     println!("{room}: recognised in {pct:.0} % of {} test runs", modelled.tests.len());
//! }
//! assert_eq!(evolution.history.len(), 3);
//! ```
//!
//! The pieces stay usable alone: [`simulation::run_trial`] runs a controller in a room,
//! [`fitness::TskFitness::evaluate`] combines fitness terms,
//!
//! ```
//! use fuzzymotiv::{Motivations, TskFitness};
//! let x = Motivations::new(0.8, 0.1, 0.0, 0.1).unwrap();
//! let f = TskFitness::paper().evaluate(&x, &[0.95, 0.5, 0.0, 0.79]);
//! assert!((f - 0.797220).abs() < 1e-6);
//! ```
//!
//! [`evolution::next_generation`] breeds, and [`Experiment`] ties them together as the paper does
//! ([`experiment::Evolution`] shows the loop as ask/evaluate/tell steps a custom optimiser can drive).

#![warn(missing_docs)]

pub mod evolution;
pub mod experiment;
pub mod export;
pub mod fitness;
pub mod modelling;
pub mod params;
pub mod random;
pub mod simulation;
pub mod statistics;

pub use experiment::config::RawConfig;
pub use experiment::evolution::{
    Evolution, EvolveError, GenerationRecord, GenerationState, Observer, Population, Stopped,
};
pub use experiment::outcome::{Interrupted, Outcome, RunError, RunObserver, Start};
pub use experiment::setup::{BuiltinRoomsOnly, RoomFile, RoomFiles, Setup, SetupError};
pub use experiment::{Experiment, Run};
pub use fitness::terms::FitnessTerms;
pub use fitness::{Motivations, TskFitness};
pub use params::FieldError;
pub use simulation::room::Room;
pub use simulation::trial::{Arena, Trajectory};

/// The program version, written into every run directory.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The model version: which numbers this build gives. Two builds with the same model version
/// give the same results, bit for bit, for the same config and seed; a change that alters results
/// on purpose bumps it in the same commit that regenerates the goldens (`tests/it/model_version.rs`
/// fails when the goldens change and it does not). It is written beside [`VERSION`] into every
/// run's `config.resolved.toml` (so it is part of a run's and a study's identity: a resumed run
/// or a study read back never mixes two models), checkpoints, records and tables.
///
/// History (docs/model.md, "Model versions"):
/// - 1: every build before 2026-12-02 that recorded no model version.
/// - 2: the homing term g's distance is √(dx² + dy²) of IEEE operations instead of libm's
///   `hypot` (commit fca8b79), which moves g by one ulp in some trials; at paper scale a near-tie
///   of the GA then flips and a low-curiosity run of `reproduce` diverges.
pub const MODEL_VERSION: u32 = 2;

/// The program and model version as tables and pages show them: `fuzzymotiv 0.1.0 (model 2)`.
pub fn provenance() -> String {
    format!("fuzzymotiv {VERSION} (model {MODEL_VERSION})")
}
