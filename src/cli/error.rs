//! The command line's error and its exit code (the table in docs/cli.md):
//!
//! | code | meaning |
//! |---|---|
//! | 0 | done, including a numerical failure (a result: its `status` says so), and a stdout closed by its reader (the command stops quietly) |
//! | 1 | I/O error: an output (file, directory, dataset, stdout) cannot be written, or a dataset being extended cannot be read |
//! | 2 | bad input: a value, option, or input file (spec, case file, fit dataset) that is missing, unreadable or invalid; nothing ran |
//!
//! Every error is printed as one line, `ehlmap: message`, naming the input (the flag or key).

/// Why a command stopped; [`CliError::exit_code`] is its exit code.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CliError {
    /// Bad input (a value, an option, an input file): exit code 2.
    Input(String),
    /// An output that cannot be written, or an I/O failure while running: exit code 1.
    Io(String),
    /// Stdout was closed by its reader (EPIPE): the command stops quietly, exit code 0.
    Closed,
}

/// The exit code of a command that did its work.
pub const EXIT_OK: i32 = 0;
/// The exit code of an I/O error.
pub const EXIT_IO: i32 = 1;
/// The exit code of bad input.
pub const EXIT_INPUT: i32 = 2;
/// The exit code when stdout was closed by its reader: the command stops quietly.
pub const EXIT_CLOSED: i32 = EXIT_OK;

impl CliError {
    /// The process exit code of this error.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Input(_) => EXIT_INPUT,
            CliError::Io(_) => EXIT_IO,
            CliError::Closed => EXIT_CLOSED,
        }
    }
}

/// Bad input: exit code 2.
pub fn input(msg: impl Into<String>) -> CliError {
    CliError::Input(msg.into())
}

/// An I/O error: exit code 1.
pub fn io(msg: impl Into<String>) -> CliError {
    CliError::Io(msg.into())
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::Input(m) | CliError::Io(m) => f.write_str(m),
            CliError::Closed => f.write_str("stdout closed"),
        }
    }
}

impl std::error::Error for CliError {}
