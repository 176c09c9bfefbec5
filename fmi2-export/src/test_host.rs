//! A minimal in-process host for the tests of an FMU built on this layer
//! (feature `test-host`): instantiate through the same code path as
//! `fmi2Instantiate`, with a logger that keeps every message.

use std::ffi::{c_char, c_void, CStr, CString};
use std::ptr;
use std::sync::Mutex;

use crate::slave::Slave;
use crate::types::*;

/// Every message logged in this process: (status, message). Tests run in
/// parallel and share it.
pub static LOG: Mutex<Vec<(fmi2Status, String)>> = Mutex::new(Vec::new());

extern "C" fn logger(
    _env: *mut c_void,
    _name: *const c_char,
    status: fmi2Status,
    _category: *const c_char,
    message: *const c_char,
) {
    let m = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .into_owned();
    LOG.lock().unwrap().push((status, m));
}

/// A co-simulation instance of `S` named `name`, with [`LOG`]'s logger
/// (the callbacks are leaked: they must outlive the instance).
pub fn instantiate<S: Slave>(name: &str) -> fmi2Component {
    let name = CString::new(name).unwrap();
    let guid = CString::new(S::guid()).unwrap();
    let callbacks = Box::leak(Box::new(fmi2CallbackFunctions {
        // SAFETY: same ABI for calls without variadic arguments (x86-64 SysV).
        logger: Some(unsafe {
            std::mem::transmute::<
                extern "C" fn(*mut c_void, *const c_char, fmi2Status, *const c_char, *const c_char),
                fmi2CallbackLogger,
            >(logger)
        }),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: ptr::null_mut(),
    }));
    let c = unsafe {
        crate::ffi::instantiate::<S>(
            name.as_ptr(),
            fmi2CoSimulation,
            guid.as_ptr(),
            ptr::null(),
            callbacks,
            0,
            0,
        )
    };
    assert!(!c.is_null());
    c
}

/// Whether an error message containing `s` was logged.
pub fn logged(s: &str) -> bool {
    LOG.lock()
        .unwrap()
        .iter()
        .any(|(st, m)| *st == fmi2Error && m.contains(s))
}
