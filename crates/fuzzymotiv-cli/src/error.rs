//! The CLI's error: bad input (exit code 2) or a failure while running (exit code 1).

use std::fmt;

/// An error with the exit code it deserves.
#[derive(Debug)]
pub struct CliError {
    message: String,
    input: bool,
}

impl CliError {
    /// Bad input from the user: exit code 2.
    pub fn input(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            input: true,
        }
    }

    /// A failure while running (I/O and the like): exit code 1.
    pub fn runtime(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            input: false,
        }
    }

    /// The process exit code.
    pub fn exit_code(&self) -> u8 {
        if self.input { 2 } else { 1 }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// A config or room file that cannot be used ([`fuzzymotiv::config::ConfigError`] and
/// [`fuzzymotiv::room::RoomError`] are this one type).
impl From<fuzzymotiv::params::FieldError> for CliError {
    fn from(e: fuzzymotiv::params::FieldError) -> Self {
        CliError::input(e.to_string())
    }
}
