//! Messages to the host's logger, with categories and `fmi2SetDebugLogging`.
//!
//! Messages are formatted on the Rust side and passed as the logger's format
//! string with every `%` doubled, so a C logger that runs them through
//! `printf` prints them unchanged. Messages with a non-OK status always reach
//! the logger (the standard expects a message with every such status); the
//! others only with debug logging on and their category enabled.

use std::ffi::CString;

use model_description::ModelDescription;

use crate::types::*;

/// Events of the model (impacts, regime changes...).
pub const LOG_EVENTS: &str = "logEvents";
/// Messages with `fmi2Warning` or `fmi2Discard`.
pub const LOG_STATUS_WARNING: &str = "logStatusWarning";
/// Messages with `fmi2Error` or `fmi2Fatal`.
pub const LOG_STATUS_ERROR: &str = "logStatusError";
/// Everything, including a trace of the FMI calls.
pub const LOG_ALL: &str = "logAll";

/// The categories the generic layer uses; a model must declare them.
pub const GENERIC_CATEGORIES: [&str; 4] =
    [LOG_EVENTS, LOG_STATUS_WARNING, LOG_STATUS_ERROR, LOG_ALL];

/// `%` doubled and NUL removed: safe as a printf format string.
pub fn escape_format(message: &str) -> CString {
    let mut s = String::with_capacity(message.len() + 8);
    for c in message.chars() {
        match c {
            '%' => s.push_str("%%"),
            '\0' => {}
            c => s.push(c),
        }
    }
    CString::new(s).expect("NUL bytes were removed")
}

/// The host's logger: FMI 2.0's (printf-like, with the instance name) or
/// FMI 3.0's (`fmi3LogMessageCallback`: the message as it is).
#[derive(Clone, Copy)]
pub enum Callback {
    Fmi2(fmi2CallbackLogger),
    Fmi3(fmi3LogMessageCallback),
}

pub struct Logger {
    callback: Option<Callback>,
    env: fmi2ComponentEnvironment,
    instance_name: CString,
    md: &'static ModelDescription,
    debug: bool,
    /// Per declared category (same order as the model description).
    enabled: Vec<bool>,
}

impl Logger {
    pub fn new(
        md: &'static ModelDescription,
        callback: Option<fmi2CallbackLogger>,
        env: fmi2ComponentEnvironment,
        instance_name: CString,
        debug: bool,
    ) -> Logger {
        Logger::with(md, callback.map(Callback::Fmi2), env, instance_name, debug)
    }

    /// A logger with either standard's callback.
    pub fn with(
        md: &'static ModelDescription,
        callback: Option<Callback>,
        env: fmi2ComponentEnvironment,
        instance_name: CString,
        debug: bool,
    ) -> Logger {
        Logger {
            callback,
            env,
            instance_name,
            md,
            debug,
            enabled: vec![true; md.log_categories.len()],
        }
    }

    pub fn instance_name(&self) -> &str {
        self.instance_name.to_str().unwrap_or("?")
    }

    /// `fmi2SetDebugLogging`: returns the unknown category names (ignored).
    pub fn set_debug_logging(&mut self, on: bool, categories: &[String]) -> Vec<String> {
        self.debug = on;
        let mut unknown = Vec::new();
        if categories.is_empty() {
            self.enabled.iter_mut().for_each(|e| *e = true);
        } else {
            self.enabled.iter_mut().for_each(|e| *e = false);
            for c in categories {
                match self.md.log_categories.iter().position(|x| x.name == c) {
                    Some(i) => self.enabled[i] = true,
                    None => unknown.push(c.clone()),
                }
            }
        }
        unknown
    }

    fn category_on(&self, category: &str) -> bool {
        let on = |name: &str| {
            self.md
                .log_categories
                .iter()
                .position(|x| x.name == name)
                .is_some_and(|i| self.enabled[i])
        };
        on(category) || on(LOG_ALL)
    }

    /// Whether a message of this status and category would reach the logger.
    pub fn wants(&self, status: Status, category: &str) -> bool {
        self.callback.is_some()
            && (status != Status::Ok || (self.debug && self.category_on(category)))
    }

    pub fn log(&self, status: Status, category: &str, message: &str) {
        if !self.wants(status, category) {
            return;
        }
        let Some(cb) = self.callback else { return };
        let category = CString::new(category).unwrap_or_default();
        match cb {
            // SAFETY: the host gave us this callback for this purpose; every
            // pointer is a valid NUL-terminated string that outlives the call,
            // and the format string has no conversion specifications left.
            Callback::Fmi2(cb) => unsafe {
                cb(
                    self.env,
                    self.instance_name.as_ptr(),
                    status.raw(),
                    category.as_ptr(),
                    escape_format(message).as_ptr(),
                );
            },
            // SAFETY: as above; FMI 3.0 passes the message as it is, in
            // its own names.
            Callback::Fmi3(cb) => unsafe {
                let words = crate::fmi3_wording::fmi3_words(message);
                let text = CString::new(words.replace('\0', "")).unwrap_or_default();
                cb(self.env, status.raw(), category.as_ptr(), text.as_ptr());
            },
        }
    }

    /// A message with a non-OK status, in the matching status category.
    pub fn status(&self, status: Status, message: &str) {
        let category = match status {
            Status::Ok => LOG_ALL,
            Status::Warning | Status::Discard => LOG_STATUS_WARNING,
            Status::Error | Status::Fatal => LOG_STATUS_ERROR,
        };
        self.log(status, category, message);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_is_escaped() {
        assert_eq!(
            escape_format("50% of %s\0x").to_str().unwrap(),
            "50%% of %%sx"
        );
    }
}
