//! The model layer's error: an input value out of its domain, named with the reason.

/// Invalid case input; the message names the offending value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParamError {
    #[error("{name} = {value} is invalid: {why}")]
    Invalid {
        name: &'static str,
        value: f64,
        why: &'static str,
    },
    /// An input rejected, with the reason (the message names the input).
    #[error("{0}")]
    Input(String),
    /// A name (of a contact, model, status ...) that is not one of the known ones.
    #[error("unknown {what} {name:?}: expected {expected}")]
    Unknown {
        what: &'static str,
        name: String,
        expected: &'static str,
    },
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
