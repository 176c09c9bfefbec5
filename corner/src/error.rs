//! The error every entry point returns: the refused input, named.

use std::fmt;

/// An input the model refuses, named.
#[derive(Debug, Clone, PartialEq)]
pub struct CornerError {
    /// The offending parameter, by the name the interfaces use (`t`, `mu`, `k`, ...).
    pub parameter: &'static str,
    /// What is wrong with it.
    pub reason: String,
}

impl fmt::Display for CornerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid {}: {}", self.parameter, self.reason)
    }
}

impl std::error::Error for CornerError {}

pub(crate) fn err(parameter: &'static str, reason: impl Into<String>) -> CornerError {
    CornerError {
        parameter,
        reason: reason.into(),
    }
}
