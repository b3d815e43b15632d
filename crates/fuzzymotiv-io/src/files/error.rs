//! The CLI's error: bad input (exit code 2) or a failure while running (exit code 1), which
//! may be a file-system failure ([`CliError::io`]).

use crate::files::refusal::{OutputError, Spelling};

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

/// An error of the CLI, Python and the lab: its kind tells the exit code it deserves.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// Bad input from the user (exit code 2), said in a sentence naming what is wrong.
    #[error("{0}")]
    Input(String),
    /// An output the guard refuses to write or replace (exit code 2), as facts each front
    /// words with its own option names ([`OutputError::render`]).
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A failure while running (exit code 1).
    #[error("{0}")]
    Runtime(String),
    /// A file-system failure (exit code 1).
    #[error("{message}")]
    Io {
        /// What failed, naming the path.
        message: String,
        /// The operating system's error number, when it gave one.
        errno: Option<i32>,
    },
    /// Standard output was closed by its reader (exit code 141, no message).
    #[error("standard output closed")]
    ClosedStdout,
}

impl CliError {
    /// Bad input from the user: exit code 2.
    pub fn input(message: impl Into<String>) -> Self {
        Self::Input(message.into())
    }

    /// A failure while running: exit code 1.
    pub fn runtime(message: impl Into<String>) -> Self {
        Self::Runtime(message.into())
    }

    /// A file-system failure: exit code 1 (in Python both a `FuzzymotivError` and an `OSError`).
    pub fn io(message: impl Into<String>) -> Self {
        Self::Io {
            message: message.into(),
            errno: None,
        }
    }

    /// A file-system failure caused by `cause`, whose OS error number it keeps ([`Self::errno`];
    /// Python's `FuzzymotivOSError.errno`).
    pub fn io_from(message: impl Into<String>, cause: &std::io::Error) -> Self {
        Self::Io {
            message: message.into(),
            errno: cause.raw_os_error(),
        }
    }

    /// Standard output was closed by its reader: no message, exit code 141.
    pub fn closed_stdout() -> Self {
        Self::ClosedStdout
    }

    /// What kind of failure this is (a refused output is bad input).
    pub fn kind(&self) -> ErrorKind {
        match self {
            Self::Input(_) | Self::Output(_) => ErrorKind::Input,
            Self::Runtime(_) => ErrorKind::Runtime,
            Self::Io { .. } => ErrorKind::Io,
            Self::ClosedStdout => ErrorKind::ClosedStdout,
        }
    }

    /// The OS error number of a file-system failure made by [`Self::io_from`], else None.
    pub fn errno(&self) -> Option<i32> {
        match self {
            Self::Io { errno, .. } => *errno,
            _ => None,
        }
    }

    /// The message in the words of a front whose output options are spelled as `s` spells
    /// them: a refused output is worded from its facts ([`OutputError::render`]), any other
    /// error is its message.
    pub fn render(&self, s: &Spelling) -> String {
        match self {
            Self::Output(e) => e.render(s),
            other => other.to_string(),
        }
    }

    /// The process exit code.
    pub fn exit_code(&self) -> u8 {
        match self.kind() {
            ErrorKind::Input => 2,
            ErrorKind::Runtime | ErrorKind::Io => 1,
            ErrorKind::ClosedStdout => 141,
        }
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
