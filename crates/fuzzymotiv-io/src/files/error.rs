//! The CLI's error: bad input (exit code 2) or a failure while running (exit code 1), which
//! may be a file-system failure ([`CliError::io`]).

use std::fmt;

/// What kind of failure a [`CliError`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// Bad input from the user (a config, a room file, an option, an output directory that
    /// must not be replaced): exit code 2.
    Input,
    /// A failure while running: exit code 1.
    Runtime,
    /// A file-system failure (reading or writing a named path): exit code 1.
    Io,
    /// Standard output was closed by its reader (`| head -1`): the command ends quietly with
    /// exit code 141, as a program killed by SIGPIPE does.
    ClosedStdout,
}

/// An error with the exit code it deserves.
#[derive(Debug)]
pub struct CliError {
    message: String,
    kind: ErrorKind,
    /// The operating system's error number of a file-system failure, when it has one.
    errno: Option<i32>,
}

impl CliError {
    /// Bad input from the user: exit code 2.
    pub fn input(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            kind: ErrorKind::Input,
            errno: None,
        }
    }

    /// A failure while running: exit code 1.
    pub fn runtime(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            kind: ErrorKind::Runtime,
            errno: None,
        }
    }

    /// A file-system failure: exit code 1 (in Python both a `FuzzymotivError` and an `OSError`).
    pub fn io(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            kind: ErrorKind::Io,
            errno: None,
        }
    }

    /// A file-system failure caused by `cause`, whose OS error number it keeps ([`Self::errno`];
    /// Python's `FuzzymotivOSError.errno`).
    pub fn io_from(message: impl Into<String>, cause: &std::io::Error) -> Self {
        Self {
            errno: cause.raw_os_error(),
            ..Self::io(message)
        }
    }

    /// Standard output was closed by its reader: no message, exit code 141.
    pub fn closed_stdout() -> Self {
        Self {
            message: "standard output closed".into(),
            kind: ErrorKind::ClosedStdout,
            errno: None,
        }
    }

    /// What kind of failure this is.
    pub fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// The OS error number of a file-system failure made by [`Self::io_from`], else None.
    pub fn errno(&self) -> Option<i32> {
        self.errno
    }

    /// The process exit code.
    pub fn exit_code(&self) -> u8 {
        match self.kind {
            ErrorKind::Input => 2,
            ErrorKind::Runtime | ErrorKind::Io => 1,
            ErrorKind::ClosedStdout => 141,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// A config or room file that cannot be used ([`fuzzymotiv::experiment::ConfigError`] and
/// [`fuzzymotiv::simulation::RoomError`] are this one type).
impl From<fuzzymotiv::experiment::SetupError> for CliError {
    fn from(e: fuzzymotiv::experiment::SetupError) -> Self {
        CliError::input(e.to_string())
    }
}

impl From<fuzzymotiv::params::FieldError> for CliError {
    fn from(e: fuzzymotiv::params::FieldError) -> Self {
        CliError::input(e.to_string())
    }
}
