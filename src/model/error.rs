//! The model layer's error: an input value out of its domain, named with the reason.

/// Invalid case input; the message names the offending value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParamError {
    /// A numeric input that is not finite or outside its domain.
    #[error("{name} = {} is invalid: {why}", num(*value))]
    Invalid {
        /// The input's name as the user knows it (`M`, `L`, `D`, `z`, `ph` ...).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// Why it was rejected: the domain the value must lie in.
        why: &'static str,
    },
    /// An input rejected, with the reason (the message names the input).
    #[error("{0}")]
    Input(String),
    /// A name (of a contact, model, status ...) that is not one of the known ones.
    #[error("unknown {what} {name:?}: expected {expected}")]
    Unknown {
        /// What kind of name it is (`contact`, `elasticity` ...).
        what: &'static str,
        /// The name given.
        name: String,
        /// The accepted names, as a phrase for the message (`line or point`).
        expected: &'static str,
    },
}

/// A number as a message or a file name shows it: as Rust prints it when that is short, else
/// in exponent form (`1e-300`, not 300 digits).
pub fn num(x: f64) -> String {
    let s = format!("{x}");
    if s.len() <= 16 {
        s
    } else {
        format!("{x:e}")
    }
}

pub(crate) fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    why: &'static str,
) -> Result<(), ParamError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(ParamError::Invalid { name, value, why })
    }
}

impl From<String> for ParamError {
    fn from(msg: String) -> Self {
        ParamError::Input(msg)
    }
}

impl From<&str> for ParamError {
    fn from(msg: &str) -> Self {
        ParamError::Input(msg.to_string())
    }
}
