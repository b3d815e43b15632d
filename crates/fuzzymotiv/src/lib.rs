//! # fuzzymotiv
//!
//! Evolutionary behaviour learning for a simulated Khepera robot under *fuzzy motivations*,
//! after "Fuzzy Motivations for Evolutionary Behavior Learning by a Mobile Robot": neural
//! controllers are evolved by a genetic algorithm whose fitness is a Takagi–Sugeno–Kang fuzzy
//! combination of curiosity, homing, orientation and energy; the best robot's action sequences
//! then model and recognise rooms (action-based environment modelling).
//!
//! ```
//! use fuzzymotiv::fuzzy::{Motivations, TskFitness};
//! let x = Motivations::new(0.8, 0.1, 0.0, 0.1).unwrap();
//! let f = TskFitness::paper().evaluate(&x, [0.95, 0.5, 0.0, 0.79]);
//! assert!((f - 0.797220).abs() < 1e-6);
//! ```
//!
//! The pieces stay usable alone: [`trial::run_trial`] runs a controller in a room,
//! [`fuzzy::TskFitness::evaluate`] combines fitness terms, [`ga::next_generation`] breeds, and
//! [`experiment::Experiment`] ties them together as the paper does.

#![warn(missing_docs)]

pub mod aem;
pub mod config;
pub mod controller;
pub mod evaluation;
pub mod evolution;
pub mod experiment;
pub mod fitness;
pub mod fll;
pub mod fuzzy;
pub mod ga;
pub mod geom;
pub mod math;
pub(crate) mod memo;
pub mod modelling;
pub mod noise;
pub mod params;
pub mod recognition;
pub mod rng;
pub mod robot;
pub mod room;
pub mod seed;
pub mod sensing;
pub mod sensor;
pub mod som;
pub mod trial;

/// The program version, written into every run directory.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
