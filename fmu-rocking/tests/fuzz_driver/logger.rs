//! The logger the driver passes: what the FMU reported, per instance.

use super::*;

/// What the logger saw for one instance (its `componentEnvironment`).
pub struct LogSink {
    /// The instance name the FMU must pass back (lossy UTF-8 of ours).
    pub(crate) name: Vec<u8>,
    /// Messages per status 0..=4.
    pub(crate) by_status: [Cell<u64>; 5],
    /// Whether debug logging is on (OK messages allowed).
    pub(crate) debug: Cell<bool>,
    /// The first broken rule, if any (the logger must not panic: it is
    /// called through C).
    pub(crate) problem: std::cell::RefCell<Option<String>>,
    /// Run the message through a real check of its text (else count only).
    pub(crate) inspect: bool,
}

impl LogSink {
    pub(crate) fn new(name: &[u8], debug: bool, inspect: bool) -> Box<LogSink> {
        Box::new(LogSink {
            name: String::from_utf8_lossy(name).into_owned().into_bytes(),
            by_status: Default::default(),
            debug: Cell::new(debug),
            problem: Default::default(),
            inspect,
        })
    }

    pub(crate) fn complain(&self, m: String) {
        if let Ok(mut p) = self.problem.try_borrow_mut() {
            if p.is_none() {
                *p = Some(m);
            }
        }
    }

    pub(crate) fn counts(&self) -> [u64; 5] {
        std::array::from_fn(|i| self.by_status[i].get())
    }

    pub(crate) fn take_problem(&self) -> Option<String> {
        self.problem.borrow_mut().take()
    }
}

/// The logger as the FMU calls it; declared without the variadic part (the
/// FMU passes no arguments after the message; on x86-64 System V and AArch64
/// Linux a non-variadic callee receives such a call unchanged).
pub(crate) type PlainLogger =
    unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String);

/// `fmi2CallbackFunctions` with the logger declared as [`PlainLogger`].
#[repr(C)]
pub(crate) struct Callbacks {
    pub(crate) logger: Option<PlainLogger>,
    pub(crate) allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    pub(crate) free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    pub(crate) step_finished: Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>,
    pub(crate) environment: fmi2ComponentEnvironment,
}

pub(crate) unsafe extern "C" fn logger(
    env: fmi2ComponentEnvironment,
    name: fmi2String,
    status: fmi2Status,
    category: fmi2String,
    message: fmi2String,
) {
    if env.is_null() {
        return; // cannot report; the driver notices the missing message
    }
    // SAFETY: env is the LogSink given at instantiation, alive until the
    // instance is freed (kept by the driver).
    let sink = unsafe { &*(env as *const LogSink) };
    if !(0..=4).contains(&status) {
        sink.complain(format!("logger called with status {status}"));
        return;
    }
    sink.by_status[status as usize].set(sink.by_status[status as usize].get() + 1);
    if status == fmi2OK && !sink.debug.get() {
        sink.complain("an fmi2OK message with debug logging off".into());
    }
    if !sink.inspect {
        return;
    }
    if name.is_null() || category.is_null() || message.is_null() {
        sink.complain("logger called with a NULL string".into());
        return;
    }
    // SAFETY: the FMU passes NUL-terminated strings (ASan checks the reads).
    let (name, category, message) = unsafe {
        (
            CStr::from_ptr(name).to_bytes(),
            CStr::from_ptr(category).to_bytes(),
            CStr::from_ptr(message).to_bytes(),
        )
    };
    if name != sink.name.as_slice() {
        sink.complain(format!(
            "instance name {:?}, expected {:?}",
            String::from_utf8_lossy(name),
            String::from_utf8_lossy(&sink.name)
        ));
    }
    let Ok(category) = std::str::from_utf8(category) else {
        sink.complain("category is not UTF-8".into());
        return;
    };
    if !LOG_CATEGORIES.iter().any(|c| c.name == category) {
        sink.complain(format!("undeclared category {category:?}"));
    }
    let expected = match status {
        fmi2Warning | fmi2Discard => Some("logStatusWarning"),
        fmi2Error | fmi2Fatal => Some("logStatusError"),
        _ => None,
    };
    if let Some(e) = expected {
        if category != e {
            sink.complain(format!("status {status} in category {category}"));
        }
    }
    let Ok(text) = std::str::from_utf8(message) else {
        sink.complain("message is not UTF-8".into());
        return;
    };
    if text.is_empty() {
        sink.complain("empty message".into());
    }
    // A printf format with no conversion left: every % doubled.
    let mut run = 0usize;
    for ch in text.chars().chain(std::iter::once('\n')) {
        if ch == '%' {
            run += 1;
        } else {
            if run % 2 == 1 {
                sink.complain(format!("a lone % in the format: {text:?}"));
                break;
            }
            run = 0;
        }
    }
}
