//! The host's logger: every message an instance sends, recorded in the
//! [`Log`] its `componentEnvironment` points at, so that tests running in
//! parallel never see each other's messages.

use std::ffi::{c_char, c_void, CStr};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use crate::types::*;

/// One message the FMU sent to the logger.
#[derive(Clone, Debug, PartialEq)]
pub struct Message {
    pub status: fmi2Status,
    /// Lossy UTF-8; `<NULL>` for a NULL pointer.
    pub category: String,
    /// As a printf-style logger prints it: the FMU doubles `%`.
    pub text: String,
    /// The instance name, category and message as passed (`None`: NULL).
    pub raw: [Option<Vec<u8>>; 3],
}

/// What a [`Log`] keeps of the messages (the counts are always kept).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Keep {
    /// Every message, until taken.
    All,
    /// The last message only: a long run does not grow the host's memory.
    Last,
    /// None.
    Count,
}

/// The messages of one instance and their count per status.
pub struct Log {
    keep: Keep,
    messages: Mutex<Vec<Message>>,
    /// Messages per status `fmi2OK` ..= `fmi2Fatal`.
    counts: [AtomicU64; 5],
    /// Messages with a status outside `fmi2OK` ..= `fmi2Fatal`.
    unknown_status: AtomicU64,
}

impl Log {
    pub fn new(keep: Keep) -> Box<Log> {
        Box::new(Log {
            keep,
            messages: Mutex::new(Vec::new()),
            counts: Default::default(),
            unknown_status: AtomicU64::new(0),
        })
    }

    /// Callbacks whose logger (if `with_logger`) records into this log; the
    /// log must outlive the instance given them.
    pub fn callbacks(&self, with_logger: bool) -> fmi2CallbackFunctions {
        fmi2CallbackFunctions {
            logger: with_logger.then_some(LOGGER),
            allocateMemory: None,
            freeMemory: None,
            stepFinished: None,
            componentEnvironment: self as *const Log as *mut c_void,
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<Message>> {
        // a panicking test thread must not hide the others' messages
        self.messages.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The messages kept so far.
    pub fn messages(&self) -> Vec<Message> {
        self.lock().clone()
    }

    /// The messages kept so far; the log emptied (the counts stay).
    pub fn take(&self) -> Vec<Message> {
        std::mem::take(&mut *self.lock())
    }

    pub fn clear(&self) {
        self.lock().clear();
    }

    /// The text of the last message kept, or "" if none.
    pub fn last_text(&self) -> String {
        self.lock().last().map_or(String::new(), |m| m.text.clone())
    }

    /// Messages so far per status `fmi2OK` ..= `fmi2Fatal`.
    pub fn counts(&self) -> [u64; 5] {
        std::array::from_fn(|i| self.counts[i].load(Ordering::Relaxed))
    }

    /// Messages so far with a status outside `fmi2OK` ..= `fmi2Fatal`.
    pub fn unknown_statuses(&self) -> u64 {
        self.unknown_status.load(Ordering::Relaxed)
    }

    fn record(&self, status: fmi2Status, raw: [Option<Vec<u8>>; 3]) {
        match usize::try_from(status)
            .ok()
            .and_then(|s| self.counts.get(s))
        {
            Some(n) => n.fetch_add(1, Ordering::Relaxed),
            None => self.unknown_status.fetch_add(1, Ordering::Relaxed),
        };
        if self.keep == Keep::Count {
            return;
        }
        let lossy = |s: &Option<Vec<u8>>| {
            s.as_deref()
                .map_or("<NULL>".into(), |b| String::from_utf8_lossy(b).into_owned())
        };
        let message = Message {
            status,
            category: lossy(&raw[1]),
            text: lossy(&raw[2]).replace("%%", "%"),
            raw,
        };
        let mut messages = self.lock();
        if self.keep == Keep::Last {
            messages.clear();
        }
        messages.push(message);
    }
}

fn bytes(p: *const c_char) -> Option<Vec<u8>> {
    // SAFETY: the FMU passes NUL-terminated strings that outlive the call.
    (!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_bytes().to_vec())
}

/// The logger, declared without the variadic part: the FMU formats its
/// messages itself and passes no arguments after them.
extern "C" fn record(
    env: *mut c_void,
    instance: *const c_char,
    status: fmi2Status,
    category: *const c_char,
    message: *const c_char,
) {
    if env.is_null() {
        return;
    }
    // SAFETY: env is the `Log` given with the callbacks, alive as long as
    // the instance.
    let log = unsafe { &*(env as *const Log) };
    log.record(status, [bytes(instance), bytes(category), bytes(message)]);
}

// SAFETY: a call without variadic arguments reaches a non-variadic callee
// unchanged (x86-64 System V, AArch64): the FMU never passes any.
const LOGGER: fmi2CallbackLogger = unsafe {
    std::mem::transmute::<
        extern "C" fn(*mut c_void, *const c_char, fmi2Status, *const c_char, *const c_char),
        fmi2CallbackLogger,
    >(record)
};
