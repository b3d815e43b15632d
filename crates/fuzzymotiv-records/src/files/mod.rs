//! The file layer: the output guard every writer goes through ([`guard`]), the bounded reader
//! every input file goes through ([`bounded`]), config and room loading ([`inputs`]), the
//! error with its exit codes ([`error`]) and the guard's refusals ([`refusal`]), the notes a
//! library returns instead of printing them ([`notes`]), a sweep job's lock ([`job_lock`]) and
//! a calibration's measurements ([`measurements`]). No terminal: the fronts print.

pub mod bounded;
pub mod error;
pub mod guard;
pub mod inputs;
pub mod job_lock;
pub mod measurements;
pub mod notes;
pub mod refusal;
