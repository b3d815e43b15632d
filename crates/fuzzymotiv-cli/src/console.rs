//! The terminal: results on standard output, notes on standard error, and neither ever panics
//! (`println!` and `eprintln!` panic when the stream is closed or full).
//!
//! A closed standard output (`fuzzymotiv plan BIG.toml | head -1`) ends the command quietly
//! with a non-zero status, as `grep` does ([`CliError::ClosedStdout`]); another write failure
//! (a full disk) is an error naming standard output. A closed standard error only drops notes
//! and progress lines: the command goes on.
//!
//! The libraries print nothing: their notes come back as data or through a [`Notes`], and
//! [`Stderr`] is the command line's (each note a line on stderr, as given).
//!
//! [`CliError::ClosedStdout`]: fuzzymotiv_pipeline::files::error::CliError::ClosedStdout

use std::fmt::Arguments;
use std::io::Write;

use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::notes::Notes;

/// Writes to standard output; a failure becomes a [`CliError`] (see the module docs).
pub fn write_out(args: Arguments<'_>) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    out.write_fmt(args)
        .and_then(|()| out.flush())
        .map_err(stdout_error)
}

/// Writes `bytes` (a file's contents, `--out -`) to standard output; a failure becomes a
/// [`CliError`] (see the module docs).
pub fn write_out_bytes(bytes: &[u8]) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)
        .and_then(|()| out.flush())
        .map_err(stdout_error)
}

/// Writes to standard error, ignoring failures (a closed stderr drops the note).
pub fn write_err(args: Arguments<'_>) {
    let _ = std::io::stderr().lock().write_fmt(args);
}

/// A failed write to standard output.
pub fn stdout_error(e: std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::closed_stdout()
    } else {
        CliError::io(format!("standard output: {e}"))
    }
}

/// The command line's [`Notes`]: each note a line on stderr, as given.
#[derive(Debug, Clone, Copy, Default)]
pub struct Stderr;

impl Notes for Stderr {
    fn note(&self, line: &str) {
        write_err(format_args!("{line}\n"));
    }
}

/// A loaded config's notes (the library's, e.g. that its motivations were normalised), each
/// on stderr after `note: `.
pub fn config_notes(notes: &[String]) {
    for line in notes {
        write_err(format_args!("note: {line}\n"));
    }
}

/// `print!` that returns an error instead of panicking: `out!("{x}")?`.
macro_rules! out {
    ($($arg:tt)*) => { $crate::console::write_out(format_args!($($arg)*)) };
}

/// `println!` that returns an error instead of panicking: `outln!("{x}")?`.
macro_rules! outln {
    () => { $crate::console::write_out(format_args!("\n")) };
    ($($arg:tt)*) => { $crate::console::write_out(format_args!("{}\n", format_args!($($arg)*))) };
}

/// `eprintln!` that never panics: a closed or full stderr drops the line.
macro_rules! note {
    ($($arg:tt)*) => { $crate::console::write_err(format_args!("{}\n", format_args!($($arg)*))) };
}

pub(crate) use {note, out, outln};
