//! The error of the CLI, Python and the lab: what went wrong, as facts where a front words them
//! its own way ([`CliError::Output`], [`CliError::Setup`]). Each front maps the variants to its
//! own outcome: the binary to exit codes (2 bad input, 1 a failure while running, 141 a closed
//! pipe), Python to exception classes, the lab to HTTP statuses.

use std::path::PathBuf;

use fuzzymotiv::experiment::SetupError;
use fuzzymotiv::params::FieldError;

use crate::files::refusal::{OutputError, Spelling};

/// What went wrong.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// Bad input from the user (an option, a file's contents), said in a sentence naming what
    /// is wrong and what would be right.
    #[error("{0}")]
    Input(String),
    /// A config or room file that cannot be used: the source, the field and the reason
    /// ([`FieldError`]), or a room file that is not TOML.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// A study or sweep file's value that cannot be used: the file, the field (a typed
    /// [`FieldError`]) and the reason.
    #[error(transparent)]
    StudyFile(FieldError),
    /// An output the guard refuses to write or replace, as facts each front words with its own
    /// option names ([`OutputError::render`]).
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A failure while running.
    #[error("{0}")]
    Runtime(String),
    /// A file-system failure on a named path (its OS error number is [`Self::errno`]).
    #[error("{}: {source}", path.display())]
    Io {
        /// The path read or written.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// A file-system failure said in a sentence (e.g. a folder that does not exist).
    #[error("{0}")]
    FileSystem(String),
    /// Standard output was closed by its reader (`| head -1`): the command ends quietly, as a
    /// program killed by SIGPIPE does.
    #[error("standard output closed")]
    ClosedStdout,
}

impl CliError {
    /// Bad input from the user.
    pub fn input(message: impl Into<String>) -> Self {
        Self::Input(message.into())
    }

    /// A failure while running.
    pub fn runtime(message: impl Into<String>) -> Self {
        Self::Runtime(message.into())
    }

    /// A file-system failure said in a sentence (in Python both a `FuzzymotivError` and an
    /// `OSError`).
    pub fn io(message: impl Into<String>) -> Self {
        Self::FileSystem(message.into())
    }

    /// A study or sweep file's `field` that cannot be used, read from `source`.
    pub fn study_file(source: &str, field: &str, reason: impl Into<String>) -> Self {
        Self::StudyFile(FieldError::new(field, reason).in_source(source))
    }

    /// Standard output was closed by its reader.
    pub fn closed_stdout() -> Self {
        Self::ClosedStdout
    }

    /// Whether this is the user's bad input (a config, a room file, an option, an output that
    /// must not be replaced) rather than a failure while running.
    pub fn is_input(&self) -> bool {
        matches!(
            self,
            Self::Input(_) | Self::Setup(_) | Self::StudyFile(_) | Self::Output(_)
        )
    }

    /// The OS error number of a file-system failure on a named path, else None.
    pub fn errno(&self) -> Option<i32> {
        match self {
            Self::Io { source, .. } => source.raw_os_error(),
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
}

/// A value of a config or room file that cannot be used.
impl From<FieldError> for CliError {
    fn from(e: FieldError) -> Self {
        Self::Setup(SetupError::Field(e))
    }
}
