//! A host for the integration tests of `fmu-rocking/tests/`: the exported
//! `fmi2*` functions of the library called in-process through their C
//! signatures, with a capturing logger per instance.
//!
//! Use from a test file with `mod host;` and `use host::*;`. Every instance
//! has its own log (the logger's `componentEnvironment` points at it), so
//! tests running in parallel never see each other's messages.

#![allow(dead_code, unused_imports)] // each test file uses a different part

use std::ffi::{c_char, c_void, CStr, CString};
use std::ptr;
use std::sync::Mutex;

pub use fmi2_export::types::*;
pub use fmu_rocking::description::{enums, vr, ROCKING_BLOCK};
use fmu_rocking::*;

/// One message the FMU sent to the logger.
#[derive(Clone, Debug, PartialEq)]
pub struct Message {
    pub status: fmi2Status,
    pub category: String,
    pub text: String,
}

type Log = Mutex<Vec<Message>>;

fn text(p: *const c_char) -> String {
    if p.is_null() {
        "<NULL>".into()
    } else {
        // SAFETY: the FMU passes NUL-terminated strings that outlive the call.
        unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
    }
}

/// The logger, declared without the variadic part: the FMU formats its
/// messages itself and passes them with `%` doubled and no arguments.
extern "C" fn capture(
    env: *mut c_void,
    _instance: *const c_char,
    status: fmi2Status,
    category: *const c_char,
    message: *const c_char,
) {
    if env.is_null() {
        return;
    }
    // SAFETY: env is the `Log` of the `Host` that owns the instance; the
    // host frees the instance before the log.
    let log = unsafe { &*(env as *const Log) };
    // The FMU doubles `%` so that a printf-style logger prints it once.
    let msg = text(message).replace("%%", "%");
    log.lock().unwrap_or_else(|p| p.into_inner()).push(Message {
        status,
        category: text(category),
        text: msg,
    });
}

/// The value reference of a variable by its public name (panics if unknown).
pub fn vr_of(name: &str) -> u32 {
    ROCKING_BLOCK
        .variable(name)
        .unwrap_or_else(|| panic!("no variable {name}"))
        .vr
}

/// One FMU instance with its own log; freed on drop.
pub struct Host {
    pub c: fmi2Component,
    log: Box<Log>,
    _callbacks: Box<fmi2CallbackFunctions>,
}

impl Host {
    /// A co-simulation instance named `test`, debug logging off (non-OK
    /// messages reach the logger anyway).
    pub fn new() -> Host {
        Host::with_logging(false)
    }

    /// As [`Host::new`] with `loggingOn`.
    pub fn with_logging(on: bool) -> Host {
        Host::instantiate(fmi2CoSimulation, on)
    }

    /// An instance of `fmu_type` (`fmi2CoSimulation` or `fmi2ModelExchange`).
    pub fn instantiate(fmu_type: fmi2Type, on: bool) -> Host {
        let log: Box<Log> = Box::new(Mutex::new(Vec::new()));
        let callbacks = Box::new(fmi2CallbackFunctions {
            // SAFETY: same ABI for calls without variadic arguments (x86-64
            // SysV, AArch64): the FMU never passes any.
            logger: Some(unsafe {
                std::mem::transmute::<
                    extern "C" fn(
                        *mut c_void,
                        *const c_char,
                        fmi2Status,
                        *const c_char,
                        *const c_char,
                    ),
                    fmi2CallbackLogger,
                >(capture)
            }),
            allocateMemory: None,
            freeMemory: None,
            stepFinished: None,
            componentEnvironment: &*log as *const Log as *mut c_void,
        });
        let name = CString::new("test").unwrap();
        let guid = CString::new(GUID).unwrap();
        // SAFETY: valid strings and callbacks that outlive the instance.
        let c = unsafe {
            fmi2Instantiate(
                name.as_ptr(),
                fmu_type,
                guid.as_ptr(),
                ptr::null(),
                &*callbacks,
                fmi2False,
                if on { fmi2True } else { fmi2False },
            )
        };
        assert!(!c.is_null(), "fmi2Instantiate failed");
        Host {
            c,
            log,
            _callbacks: callbacks,
        }
    }

    // ----- log --------------------------------------------------------------

    /// Every message so far.
    pub fn messages(&self) -> Vec<Message> {
        self.log.lock().unwrap().clone()
    }

    /// Every message so far, and the log emptied.
    pub fn take_messages(&self) -> Vec<Message> {
        std::mem::take(&mut *self.log.lock().unwrap())
    }

    /// The texts of the messages with status `fmi2Error`.
    pub fn errors(&self) -> Vec<String> {
        self.messages()
            .into_iter()
            .filter(|m| m.status == fmi2Error)
            .map(|m| m.text)
            .collect()
    }

    pub fn clear_log(&self) {
        self.log.lock().unwrap().clear();
    }

    // ----- setting ----------------------------------------------------------

    pub fn set_real(&self, name: &str, x: f64) -> fmi2Status {
        self.set_real_vr(vr_of(name), x)
    }

    pub fn set_real_vr(&self, r: u32, x: f64) -> fmi2Status {
        // SAFETY: one value reference and one value.
        unsafe { fmi2SetReal(self.c, &r, 1, &x) }
    }

    pub fn set_integer(&self, name: &str, x: i32) -> fmi2Status {
        let r = vr_of(name);
        // SAFETY: one value reference and one value.
        unsafe { fmi2SetInteger(self.c, &r, 1, &x) }
    }

    pub fn set_boolean(&self, name: &str, x: bool) -> fmi2Status {
        let r = vr_of(name);
        let b = if x { fmi2True } else { fmi2False };
        // SAFETY: one value reference and one value.
        unsafe { fmi2SetBoolean(self.c, &r, 1, &b) }
    }

    /// `fmi2SetRealInputDerivatives` for one variable.
    pub fn set_input_derivative(&self, name: &str, order: i32, x: f64) -> fmi2Status {
        let r = vr_of(name);
        // SAFETY: one value reference, order and value.
        unsafe { fmi2SetRealInputDerivatives(self.c, &r, 1, &order, &x) }
    }

    // ----- getting ----------------------------------------------------------

    /// `fmi2GetReal` of one variable: status and value.
    pub fn get_real(&self, name: &str) -> (fmi2Status, f64) {
        self.get_real_vr(vr_of(name))
    }

    pub fn get_real_vr(&self, r: u32) -> (fmi2Status, f64) {
        let mut x = f64::NAN;
        // SAFETY: one value reference and room for one value.
        let s = unsafe { fmi2GetReal(self.c, &r, 1, &mut x) };
        (s, x)
    }

    /// The value of a Real; panics unless `fmi2OK`.
    pub fn real(&self, name: &str) -> f64 {
        let (s, x) = self.get_real(name);
        assert_eq!(s, fmi2OK, "fmi2GetReal({name}): {:?}", self.messages());
        x
    }

    /// Several Reals in one `fmi2GetReal` call; panics unless `fmi2OK`.
    pub fn reals(&self, names: &[&str]) -> Vec<f64> {
        let vrs: Vec<u32> = names.iter().map(|n| vr_of(n)).collect();
        let mut x = vec![f64::NAN; vrs.len()];
        // SAFETY: n value references and room for n values.
        let s = unsafe { fmi2GetReal(self.c, vrs.as_ptr(), vrs.len(), x.as_mut_ptr()) };
        assert_eq!(s, fmi2OK, "fmi2GetReal({names:?}): {:?}", self.messages());
        x
    }

    pub fn get_integer(&self, name: &str) -> (fmi2Status, i32) {
        let r = vr_of(name);
        let mut x = i32::MIN;
        // SAFETY: one value reference and room for one value.
        let s = unsafe { fmi2GetInteger(self.c, &r, 1, &mut x) };
        (s, x)
    }

    pub fn integer(&self, name: &str) -> i32 {
        let (s, x) = self.get_integer(name);
        assert_eq!(s, fmi2OK, "fmi2GetInteger({name}): {:?}", self.messages());
        x
    }

    pub fn get_boolean(&self, name: &str) -> (fmi2Status, bool) {
        let r = vr_of(name);
        let mut x = -1;
        // SAFETY: one value reference and room for one value.
        let s = unsafe { fmi2GetBoolean(self.c, &r, 1, &mut x) };
        (s, x != fmi2False)
    }

    pub fn boolean(&self, name: &str) -> bool {
        let (s, x) = self.get_boolean(name);
        assert_eq!(s, fmi2OK, "fmi2GetBoolean({name}): {:?}", self.messages());
        x
    }

    // ----- life cycle -------------------------------------------------------

    pub fn setup(&self, tolerance: Option<f64>, start: f64, stop: Option<f64>) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe {
            fmi2SetupExperiment(
                self.c,
                tolerance.is_some() as fmi2Boolean,
                tolerance.unwrap_or(0.0),
                start,
                stop.is_some() as fmi2Boolean,
                stop.unwrap_or(0.0),
            )
        }
    }

    pub fn enter_init(&self) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { fmi2EnterInitializationMode(self.c) }
    }

    pub fn exit_init(&self) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { fmi2ExitInitializationMode(self.c) }
    }

    /// Setup (no tolerance, start 0, no stop), enter and exit initialization
    /// mode; panics unless every call returns `fmi2OK`.
    pub fn init(&self) {
        assert_eq!(self.setup(None, 0.0, None), fmi2OK);
        assert_eq!(self.enter_init(), fmi2OK);
        assert_eq!(self.exit_init(), fmi2OK, "{:?}", self.messages());
    }

    pub fn do_step(&self, t: f64, h: f64) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { fmi2DoStep(self.c, t, h, fmi2True) }
    }

    pub fn reset(&self) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { fmi2Reset(self.c) }
    }

    pub fn terminate(&self) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { fmi2Terminate(self.c) }
    }

    /// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`.
    pub fn last_successful_time(&self) -> (fmi2Status, f64) {
        let mut x = f64::NAN;
        // SAFETY: a live instance and room for one value.
        let s = unsafe { fmi2GetRealStatus(self.c, fmi2LastSuccessfulTime, &mut x) };
        (s, x)
    }

    /// `fmi2GetBooleanStatus(fmi2Terminated)`.
    pub fn terminated(&self) -> (fmi2Status, bool) {
        let mut x = -1;
        // SAFETY: a live instance and room for one value.
        let s = unsafe { fmi2GetBooleanStatus(self.c, fmi2Terminated, &mut x) };
        (s, x != fmi2False)
    }

    // ----- FMU states -------------------------------------------------------

    /// A new FMU state; panics unless `fmi2OK`.
    pub fn get_state(&self) -> fmi2FMUstate {
        let mut s: fmi2FMUstate = ptr::null_mut();
        // SAFETY: a live instance; *s is NULL: a new state.
        let st = unsafe { fmi2GetFMUstate(self.c, &mut s) };
        assert_eq!(st, fmi2OK, "{:?}", self.messages());
        s
    }

    pub fn set_state(&self, s: fmi2FMUstate) -> fmi2Status {
        // SAFETY: a live instance (the FMU checks the state pointer).
        unsafe { fmi2SetFMUstate(self.c, s) }
    }

    pub fn free_state(&self, mut s: fmi2FMUstate) -> fmi2Status {
        // SAFETY: a live instance (the FMU checks the state pointer).
        unsafe { fmi2FreeFMUstate(self.c, &mut s) }
    }

    /// `fmi2SerializedFMUstateSize` and `fmi2SerializeFMUstate`; panics
    /// unless both return `fmi2OK`.
    pub fn serialize(&self, s: fmi2FMUstate) -> Vec<u8> {
        let mut n = 0usize;
        // SAFETY: a live instance and room for the size.
        let st = unsafe { fmi2SerializedFMUstateSize(self.c, s, &mut n) };
        assert_eq!(st, fmi2OK, "{:?}", self.messages());
        let mut buf = vec![0u8; n];
        // SAFETY: n writable bytes.
        let st = unsafe { fmi2SerializeFMUstate(self.c, s, buf.as_mut_ptr() as *mut fmi2Byte, n) };
        assert_eq!(st, fmi2OK, "{:?}", self.messages());
        buf
    }

    /// The payload of a new FMU state of the instance as it is now
    /// (envelope checked and removed): its first byte is the state of the
    /// FMI state machine (instantiated 0, initializationMode 1, stepComplete
    /// 2, stepFailed 3, terminated 4, error 5), then the experiment, time,
    /// stored values, input derivatives and the model's state.
    pub fn snapshot_payload(&self) -> Vec<u8> {
        let s = self.get_state();
        let bytes = self.serialize(s);
        assert_eq!(self.free_state(s), fmi2OK);
        fmi2_export::bytes::unseal(GUID, &bytes)
            .expect("a state of this FMU")
            .to_vec()
    }

    /// Frees the instance now (what `Drop` does), for tests of freeing.
    pub fn free(mut self) {
        self.free_now();
    }

    /// Frees the instance and returns every message logged, including any
    /// during `fmi2FreeInstance`.
    pub fn free_and_take_log(mut self) -> Vec<Message> {
        self.free_now();
        self.take_messages()
    }

    fn free_now(&mut self) {
        if !self.c.is_null() {
            // SAFETY: ours, freed once.
            unsafe { fmi2FreeInstance(self.c) };
            self.c = ptr::null_mut();
        }
    }
}

impl Default for Host {
    fn default() -> Host {
        Host::new()
    }
}

impl Drop for Host {
    fn drop(&mut self) {
        self.free_now();
    }
}
