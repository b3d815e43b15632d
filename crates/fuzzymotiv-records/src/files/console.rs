//! The terminal: results on standard output, notes on standard error, and neither ever panics
//! (`println!` and `eprintln!` panic when the stream is closed or full).
//!
//! A closed standard output (`fuzzymotiv plan BIG.toml | head -1`) ends the command quietly
//! with a non-zero status, as `grep` does ([`CliError::ClosedStdout`]); another write failure
//! (a full disk) is an error naming standard output. A closed standard error only drops notes
//! and progress lines: the command goes on.
//!
//! [`CliError::ClosedStdout`]: crate::files::error::CliError::ClosedStdout

use std::fmt::Arguments;
use std::io::Write;

use crate::files::error::CliError;

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

/// `print!` that returns an error instead of panicking: `out!("{x}")?`.
#[macro_export]
macro_rules! out {
    ($($arg:tt)*) => { $crate::files::console::write_out(format_args!($($arg)*)) };
}

/// `println!` that returns an error instead of panicking: `outln!("{x}")?`.
#[macro_export]
macro_rules! outln {
    () => { $crate::files::console::write_out(format_args!("\n")) };
    ($($arg:tt)*) => { $crate::files::console::write_out(format_args!("{}\n", format_args!($($arg)*))) };
}

/// `eprintln!` that never panics: a closed or full stderr drops the line.
#[macro_export]
macro_rules! note {
    ($($arg:tt)*) => { $crate::files::console::write_err(format_args!("{}\n", format_args!($($arg)*))) };
}
