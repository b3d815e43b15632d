//! The file layer: the output guard every writer goes through ([`guard`]), config and room
//! loading ([`inputs`]), the error with its exit codes ([`error`]) and the terminal
//! ([`console`]: `out!`, `outln!`, `note!`).

pub mod console;
pub mod error;
pub mod guard;
pub mod inputs;
