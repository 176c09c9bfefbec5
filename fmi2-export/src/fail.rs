//! A failed call (its status and message), and panics of model code turned
//! into failures.

use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::types::Status;

/// A failed call: its status (Discard, Error or Fatal) and message.
#[derive(Debug)]
pub struct Fail {
    pub status: Status,
    pub message: String,
}

pub type Res<T> = Result<T, Fail>;

pub fn error<T>(message: impl Into<String>) -> Res<T> {
    Err(Fail {
        status: Status::Error,
        message: message.into(),
    })
}

pub fn discard<T>(message: impl Into<String>) -> Res<T> {
    Err(Fail {
        status: Status::Discard,
        message: message.into(),
    })
}

/// The message of a caught panic.
pub fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic".to_string()
    }
}

/// Runs model code, turning a panic into an error.
pub(crate) fn guarded<T>(what: &str, f: impl FnOnce() -> Result<T, String>) -> Res<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(x)) => Ok(x),
        Ok(Err(m)) => error(m),
        Err(p) => error(format!(
            "internal error in the model during {what}: {}",
            panic_message(&*p)
        )),
    }
}
