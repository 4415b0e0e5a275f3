//! The error of a spec: the file, the line and the key of the offending entry, displayed as
//! `FILE:LINE: KEY: message` (`FILE:LINE: message` when no key applies).

use std::fmt;

/// A spec error: file, line (1-based) and key of the offending entry.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecError {
    /// The spec file as given on the command line.
    pub file: String,
    /// Line of the offending entry, 1-based; 0 when the file cannot be read.
    pub line: usize,
    /// Dotted key of the offending entry (e.g. `axes.M`); empty when no key applies.
    pub key: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for SpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.key.is_empty() {
            write!(f, "{}:{}: {}", self.file, self.line, self.message)
        } else {
            write!(
                f,
                "{}:{}: {}: {}",
                self.file, self.line, self.key, self.message
            )
        }
    }
}

impl std::error::Error for SpecError {}
