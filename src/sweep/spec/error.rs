//! The error of a spec: the file, the line and the key of the offending entry, displayed as
//! `FILE:LINE: KEY: message` (`FILE:LINE: message` when no key applies).

use std::fmt;

/// A spec error: file, line (1-based) and key of the offending entry.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecError {
    pub file: String,
    pub line: usize,
    pub key: String,
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
