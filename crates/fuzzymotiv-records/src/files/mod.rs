//! The file layer: the output guard every writer goes through ([`guard`]), the bounded reader
//! every input file goes through ([`bounded`]), config and room loading ([`inputs`]), the
//! error with its exit codes ([`error`]) and the guard's refusals ([`refusal`]), the terminal
//! ([`console`]: `out!`, `outln!`, `note!`), a sweep job's lock ([`job_lock`]) and a
//! calibration's measurements ([`measurements`]).

pub mod bounded;
pub mod console;
pub mod error;
pub mod guard;
pub mod inputs;
pub mod job_lock;
pub mod measurements;
pub mod refusal;
