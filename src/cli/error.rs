//! The command line's error: bad input, printed as one line `ehlmap: message`, exit code 2.

/// An input error: printed as one line, exit code [`InputError::EXIT_CODE`].
#[derive(Debug)]
pub struct InputError(pub String);

impl InputError {
    /// The exit code of bad input (a numerical failure is a result and exits 0).
    pub const EXIT_CODE: i32 = 2;
}

impl std::fmt::Display for InputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}
