//! The shared pipeline: a run directory ([`run_dir`]: evolve with a checkpoint per generation,
//! model the rooms, write the records, figures and report; read a finished one back) and what
//! `run` is asked to do ([`run_target`]), a sweep's plan ([`sweep_plan`]), jobs ([`sweep_jobs`])
//! and merge ([`sweep_merge`]), runs or jobs side by side ([`lanes`]), the progress all of it
//! reports ([`progress`]), a finished run continued to more generations ([`continuation`]), a
//! saved genome replayed ([`replay`]), the TSK by hand and as an FLL file ([`fuzzy`]), `bench`'s
//! measurements ([`mod@bench`]), `calibrate`'s sensor table ([`calibrate`]), a study's claims
//! recomputed ([`claims`]), a robot's robustness ([`robustness`]), rooms recognised in a
//! robot's logs ([`recognise`]), and the paper's study and the studies built on it
//! ([`reproduce`]: `ReproduceOptions` in, tables and records out).

pub mod bench;
pub mod calibrate;
pub mod claims;
pub mod compare;
pub mod continuation;
pub mod fuzzy;
pub mod lanes;
pub mod progress;
pub mod recognise;
pub mod replay;
pub mod reproduce;
pub mod robustness;
pub mod run_dir;
pub mod run_target;
pub mod sweep_jobs;
pub mod sweep_merge;
pub mod sweep_plan;
pub mod transfer;
