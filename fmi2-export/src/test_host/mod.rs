//! The in-process host the tests of an FMU built on this layer share
//! (feature `test-host`): one instance of a model `S` driven through the
//! C functions `export_fmi2!` exports for it (each of which only forwards
//! to the [`crate::ffi`] function this host calls), with a [`Log`] of its
//! own that records every message.
//!
//! The setters, getters and life-cycle calls return the FMI status; the
//! helpers that only make sense when they succeed (`real`, `init`,
//! `get_state`, `serialize`, ...) panic otherwise, with the messages logged.

mod log;

use std::ffi::CString;
use std::marker::PhantomData;
use std::ptr;

pub use log::{Keep, Log, Message};

use crate::ffi;
use crate::model_description::{Causality, Type, Variability};
use crate::slave::Slave;
use crate::types::*;

/// How [`Host::with`] instantiates.
#[derive(Clone, Debug)]
pub struct Options<'a> {
    pub name: &'a str,
    pub fmu_type: fmi2Type,
    /// `loggingOn` (debug logging; non-OK messages reach the logger anyway).
    pub logging_on: bool,
    /// `fmuResourceLocation` (NULL if `None`).
    pub resources: Option<&'a str>,
    pub keep: Keep,
}

impl Default for Options<'_> {
    /// A co-simulation instance named `test`, debug logging off, no
    /// resources, every message kept.
    fn default() -> Self {
        Options {
            name: "test",
            fmu_type: fmi2CoSimulation,
            logging_on: false,
            resources: None,
            keep: Keep::All,
        }
    }
}

/// One instance of `S` with its own log; freed on drop.
pub struct Host<S: Slave> {
    pub c: fmi2Component,
    pub log: Box<Log>,
    _callbacks: Box<fmi2CallbackFunctions>,
    _model: PhantomData<fn() -> S>,
}

// SAFETY: an instance shares nothing with others and may move between
// threads (the layer's promise); the log is Sync.
unsafe impl<S: Slave> Send for Host<S> {}

/// The value reference of `S`'s variable `name` (panics if unknown).
pub fn vr_of<S: Slave>(name: &str) -> u32 {
    S::description()
        .variable(name)
        .unwrap_or_else(|| panic!("no variable {name}"))
        .vr
}

/// `fmi2Instantiate` of `S` with no callbacks (NULL) and `name`, `guid`
/// NULL where `None`, for the tests of refused instantiations: the
/// component, NULL if refused (else the caller frees it).
pub fn bare_instance<S: Slave>(
    name: Option<&str>,
    fmu_type: fmi2Type,
    guid: Option<&str>,
) -> fmi2Component {
    let name = name.map(|n| CString::new(n).unwrap());
    let guid = guid.map(|g| CString::new(g).unwrap());
    let or_null = |s: &Option<CString>| s.as_ref().map_or(ptr::null(), |s| s.as_ptr());
    // SAFETY: valid strings or NULL; NULL callbacks are allowed.
    unsafe {
        ffi::instantiate::<S>(
            or_null(&name),
            fmu_type,
            or_null(&guid),
            ptr::null(),
            ptr::null(),
            fmi2False,
            fmi2False,
        )
    }
}

impl<S: Slave> Host<S> {
    /// An instance as [`Options::default`] says.
    pub fn new() -> Self {
        Self::with(Options::default())
    }

    /// As [`Host::new`] with `loggingOn`.
    pub fn with_logging(on: bool) -> Self {
        Self::instantiate(fmi2CoSimulation, on)
    }

    /// An instance of `fmu_type` (`fmi2CoSimulation` or `fmi2ModelExchange`).
    pub fn instantiate(fmu_type: fmi2Type, logging_on: bool) -> Self {
        Self::with(Options {
            fmu_type,
            logging_on,
            ..Options::default()
        })
    }

    /// A co-simulation instance named `name`.
    pub fn named(name: &str) -> Self {
        Self::with(Options {
            name,
            ..Options::default()
        })
    }

    /// `fmi2Instantiate` as `o` says; panics if it returns NULL.
    pub fn with(o: Options<'_>) -> Self {
        let log = Log::new(o.keep);
        let callbacks = Box::new(log.callbacks(true));
        let name = CString::new(o.name).unwrap();
        let guid = CString::new(S::guid()).unwrap();
        let resources = o.resources.map(|r| CString::new(r).unwrap());
        // SAFETY: valid strings and callbacks that outlive the instance.
        let c = unsafe {
            ffi::instantiate::<S>(
                name.as_ptr(),
                o.fmu_type,
                guid.as_ptr(),
                resources.as_ref().map_or(ptr::null(), |r| r.as_ptr()),
                &*callbacks,
                fmi2False,
                o.logging_on as fmi2Boolean,
            )
        };
        assert!(!c.is_null(), "fmi2Instantiate failed: {:?}", log.messages());
        Host {
            c,
            log,
            _callbacks: callbacks,
            _model: PhantomData,
        }
    }

    // ----- log --------------------------------------------------------------

    /// Every message kept so far.
    pub fn messages(&self) -> Vec<Message> {
        self.log.messages()
    }

    /// Every message kept so far, and the log emptied.
    pub fn take_messages(&self) -> Vec<Message> {
        self.log.take()
    }

    /// The texts of the messages with status `fmi2Error`.
    pub fn errors(&self) -> Vec<String> {
        self.messages()
            .into_iter()
            .filter(|m| m.status == fmi2Error)
            .map(|m| m.text)
            .collect()
    }

    /// Whether an error message containing `s` was logged.
    pub fn logged(&self, s: &str) -> bool {
        self.errors().iter().any(|m| m.contains(s))
    }

    pub fn clear_log(&self) {
        self.log.clear();
    }

    /// Panics unless `s` is `fmi2OK`, naming `what` and the last message.
    #[track_caller]
    pub fn check(&self, what: &str, s: fmi2Status) {
        assert_eq!(
            s,
            fmi2OK,
            "{what}: status {s}, last message: {}",
            self.log.last_text()
        );
    }

    // ----- setting ----------------------------------------------------------

    pub fn set_real(&self, name: &str, x: f64) -> fmi2Status {
        self.set_reals(&[(vr_of::<S>(name), x)])
    }

    pub fn set_real_vr(&self, r: u32, x: f64) -> fmi2Status {
        self.set_reals(&[(r, x)])
    }

    /// One `fmi2SetReal` of (value reference, value) pairs.
    pub fn set_reals(&self, pairs: &[(u32, f64)]) -> fmi2Status {
        let (vrs, xs): (Vec<u32>, Vec<f64>) = pairs.iter().copied().unzip();
        // SAFETY: n value references and n values.
        unsafe { ffi::set_real::<S>(self.c, vrs.as_ptr(), vrs.len(), xs.as_ptr()) }
    }

    pub fn set_integer(&self, name: &str, x: i32) -> fmi2Status {
        self.set_integers(&[(vr_of::<S>(name), x)])
    }

    /// One `fmi2SetInteger` of (value reference, value) pairs.
    pub fn set_integers(&self, pairs: &[(u32, i32)]) -> fmi2Status {
        let (vrs, xs): (Vec<u32>, Vec<i32>) = pairs.iter().copied().unzip();
        // SAFETY: n value references and n values.
        unsafe { ffi::set_integer::<S>(self.c, vrs.as_ptr(), vrs.len(), xs.as_ptr()) }
    }

    pub fn set_boolean(&self, name: &str, x: bool) -> fmi2Status {
        let r = vr_of::<S>(name);
        let b = x as fmi2Boolean;
        // SAFETY: one value reference and one value.
        unsafe { ffi::set_boolean::<S>(self.c, &r, 1, &b) }
    }

    /// `fmi2SetRealInputDerivatives` for one variable.
    pub fn set_input_derivative(&self, name: &str, order: i32, x: f64) -> fmi2Status {
        self.set_input_derivative_vr(vr_of::<S>(name), order, x)
    }

    pub fn set_input_derivative_vr(&self, r: u32, order: i32, x: f64) -> fmi2Status {
        // SAFETY: one value reference, order and value.
        unsafe { ffi::set_real_input_derivatives::<S>(self.c, &r, 1, &order, &x) }
    }

    // ----- getting ----------------------------------------------------------

    /// `fmi2GetReal` of one variable: status and value.
    pub fn get_real(&self, name: &str) -> (fmi2Status, f64) {
        self.get_real_vr(vr_of::<S>(name))
    }

    pub fn get_real_vr(&self, r: u32) -> (fmi2Status, f64) {
        let (s, x) = self.get_reals_vr(&[r]);
        (s, x[0])
    }

    /// One `fmi2GetReal` of several value references.
    pub fn get_reals_vr(&self, vrs: &[u32]) -> (fmi2Status, Vec<f64>) {
        self.get_vr(ffi::get_real::<S>, vrs, f64::NAN)
    }

    /// One call of the getter `get` for several value references; `unset`
    /// stays where it writes nothing.
    fn get_vr<T: Copy>(
        &self,
        get: unsafe fn(fmi2Component, *const fmi2ValueReference, usize, *mut T) -> fmi2Status,
        vrs: &[u32],
        unset: T,
    ) -> (fmi2Status, Vec<T>) {
        let mut x = vec![unset; vrs.len()];
        // SAFETY: n value references and room for n values.
        let s = unsafe { get(self.c, vrs.as_ptr(), vrs.len(), x.as_mut_ptr()) };
        (s, x)
    }

    /// Every Real variable of `S`'s table read with `fmi2GetReal`, one call
    /// each: `(name, status, value)`.
    pub fn every_real(&self) -> Vec<(&'static str, fmi2Status, f64)> {
        S::description()
            .variables
            .iter()
            .filter(|v| matches!(v.ty, Type::Real { .. }))
            .map(|v| {
                let (s, x) = self.get_real_vr(v.vr);
                (v.name, s, x)
            })
            .collect()
    }

    /// Every continuous Real output of `S`'s table with its
    /// `fmi2GetRealOutputDerivatives` of each order from 1 to the declared
    /// `maxOutputDerivativeOrder`, one call each: `(name, order, status,
    /// value)`.
    pub fn every_output_derivative(&self) -> Vec<(&'static str, i32, fmi2Status, f64)> {
        let md = S::description();
        let orders = 1..=md.co_simulation.max_output_derivative_order as i32;
        let outputs = md.variables.iter().filter(|v| {
            v.causality == Causality::Output
                && v.variability == Variability::Continuous
                && matches!(v.ty, Type::Real { .. })
        });
        outputs
            .flat_map(|v| orders.clone().map(move |k| (v, k)))
            .map(|(v, k)| {
                let mut x = f64::NAN;
                // SAFETY: one value reference, one order, room for one value.
                let s =
                    unsafe { ffi::get_real_output_derivatives::<S>(self.c, &v.vr, 1, &k, &mut x) };
                (v.name, k, s, x)
            })
            .collect()
    }

    /// The value of a Real; panics unless `fmi2OK`.
    pub fn real(&self, name: &str) -> f64 {
        self.reals(&[name])[0]
    }

    /// Several Reals in one `fmi2GetReal` call; panics unless `fmi2OK`.
    pub fn reals(&self, names: &[&str]) -> Vec<f64> {
        let vrs: Vec<u32> = names.iter().map(|n| vr_of::<S>(n)).collect();
        let (s, x) = self.get_reals_vr(&vrs);
        assert_eq!(s, fmi2OK, "fmi2GetReal({names:?}): {:?}", self.messages());
        x
    }

    pub fn get_integer(&self, name: &str) -> (fmi2Status, i32) {
        let (s, x) = self.get_integers_vr(&[vr_of::<S>(name)]);
        (s, x[0])
    }

    /// One `fmi2GetInteger` of several value references.
    pub fn get_integers_vr(&self, vrs: &[u32]) -> (fmi2Status, Vec<i32>) {
        self.get_vr(ffi::get_integer::<S>, vrs, i32::MIN)
    }

    pub fn integer(&self, name: &str) -> i32 {
        let (s, x) = self.get_integer(name);
        assert_eq!(s, fmi2OK, "fmi2GetInteger({name}): {:?}", self.messages());
        x
    }

    pub fn get_boolean(&self, name: &str) -> (fmi2Status, bool) {
        self.get_boolean_vr(vr_of::<S>(name))
    }

    pub fn get_boolean_vr(&self, r: u32) -> (fmi2Status, bool) {
        let (s, x) = self.get_vr(ffi::get_boolean::<S>, &[r], -1);
        (s, x[0] != fmi2False)
    }

    pub fn boolean(&self, name: &str) -> bool {
        let (s, x) = self.get_boolean(name);
        assert_eq!(s, fmi2OK, "fmi2GetBoolean({name}): {:?}", self.messages());
        x
    }

    // ----- life cycle -------------------------------------------------------

    /// `fmi2SetDebugLogging` with these categories.
    pub fn debug_logging(&self, on: bool, categories: &[&str]) -> fmi2Status {
        let cs: Vec<CString> = categories
            .iter()
            .map(|c| CString::new(*c).unwrap())
            .collect();
        let ps: Vec<fmi2String> = cs.iter().map(|c| c.as_ptr()).collect();
        // SAFETY: n category strings.
        unsafe { ffi::set_debug_logging::<S>(self.c, on as fmi2Boolean, ps.len(), ps.as_ptr()) }
    }

    pub fn setup(&self, tolerance: Option<f64>, start: f64, stop: Option<f64>) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe {
            ffi::setup_experiment::<S>(
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
        unsafe { ffi::enter_initialization_mode::<S>(self.c) }
    }

    pub fn exit_init(&self) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { ffi::exit_initialization_mode::<S>(self.c) }
    }

    /// Enter and exit initialization mode: the status of the exit.
    pub fn initialize(&self) -> fmi2Status {
        self.check("fmi2EnterInitializationMode", self.enter_init());
        self.exit_init()
    }

    /// Setup (`tolerance`, start 0, no stop), enter and exit initialization
    /// mode; panics unless every call returns `fmi2OK`.
    pub fn init_with(&self, tolerance: Option<f64>) {
        self.check("fmi2SetupExperiment", self.setup(tolerance, 0.0, None));
        self.check("fmi2ExitInitializationMode", self.initialize());
    }

    /// [`Host::init_with`] no tolerance.
    pub fn init(&self) {
        self.init_with(None);
    }

    pub fn do_step(&self, t: f64, h: f64) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { ffi::do_step::<S>(self.c, t, h, fmi2True) }
    }

    pub fn reset(&self) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { ffi::reset::<S>(self.c) }
    }

    pub fn terminate(&self) -> fmi2Status {
        // SAFETY: a live instance.
        unsafe { ffi::terminate::<S>(self.c) }
    }

    /// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`.
    pub fn last_successful_time(&self) -> (fmi2Status, f64) {
        let mut x = f64::NAN;
        // SAFETY: a live instance and room for one value.
        let s = unsafe { ffi::get_real_status::<S>(self.c, fmi2LastSuccessfulTime, &mut x) };
        (s, x)
    }

    /// `fmi2GetBooleanStatus(fmi2Terminated)`.
    pub fn terminated(&self) -> (fmi2Status, bool) {
        let mut x = -1;
        // SAFETY: a live instance and room for one value.
        let s = unsafe { ffi::get_boolean_status::<S>(self.c, fmi2Terminated, &mut x) };
        (s, x != fmi2False)
    }

    // ----- FMU states -------------------------------------------------------

    /// A new FMU state; panics unless `fmi2OK`.
    pub fn get_state(&self) -> fmi2FMUstate {
        let mut s: fmi2FMUstate = ptr::null_mut();
        self.check("fmi2GetFMUstate", self.update_state(&mut s));
        s
    }

    /// `fmi2GetFMUstate` into `s` (a new state if NULL, else overwritten).
    pub fn update_state(&self, s: &mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: a live instance; *s is NULL or a state of this instance.
        unsafe { ffi::get_fmu_state::<S>(self.c, s, "fmi2GetFMUstate") }
    }

    #[allow(clippy::not_unsafe_ptr_arg_deref)] // the layer refuses pointers it did not give out
    pub fn set_state(&self, s: fmi2FMUstate) -> fmi2Status {
        // SAFETY: a live instance (the FMU checks the state pointer).
        unsafe { ffi::set_fmu_state::<S>(self.c, s, "fmi2SetFMUstate") }
    }

    /// `fmi2FreeFMUstate`, which sets `*s` to NULL.
    pub fn free_state(&self, s: &mut fmi2FMUstate) -> fmi2Status {
        // SAFETY: a live instance (the FMU checks the state pointer).
        let st = unsafe { ffi::free_fmu_state::<S>(self.c, s, "fmi2FreeFMUstate") };
        assert!(
            st != fmi2OK || s.is_null(),
            "fmi2FreeFMUstate left the state"
        );
        st
    }

    /// `fmi2SerializedFMUstateSize` and `fmi2SerializeFMUstate`; panics
    /// unless both return `fmi2OK`.
    #[allow(clippy::not_unsafe_ptr_arg_deref)] // the layer refuses pointers it did not give out
    pub fn serialize(&self, s: fmi2FMUstate) -> Vec<u8> {
        let mut n = 0usize;
        // SAFETY: a live instance and room for the size.
        let st = unsafe {
            ffi::serialized_fmu_state_size::<S>(self.c, s, &mut n, "fmi2SerializedFMUstateSize")
        };
        self.check("fmi2SerializedFMUstateSize", st);
        let mut buf = vec![0u8; n];
        // SAFETY: n writable bytes.
        let st = unsafe {
            ffi::serialize_fmu_state::<S>(self.c, s, buf.as_mut_ptr(), n, "fmi2SerializeFMUstate")
        };
        self.check("fmi2SerializeFMUstate", st);
        buf
    }

    /// `fmi2DeSerializeFMUstate` into a new state; panics unless `fmi2OK`.
    pub fn deserialize(&self, buf: &[u8]) -> fmi2FMUstate {
        let mut s: fmi2FMUstate = ptr::null_mut();
        // SAFETY: buf.len() readable bytes and room for the state.
        let st = unsafe {
            ffi::deserialize_fmu_state::<S>(
                self.c,
                buf.as_ptr(),
                buf.len(),
                &mut s,
                "fmi2DeSerializeFMUstate",
            )
        };
        self.check("fmi2DeSerializeFMUstate", st);
        s
    }

    /// The payload of a new FMU state of the instance as it is now
    /// (envelope checked and removed): its first byte is the state of the
    /// FMI state machine (instantiated 0, initializationMode 1, stepComplete
    /// 2, stepFailed 3, terminated 4, error 5), then the experiment, time,
    /// stored values, input derivatives and the model's state.
    pub fn snapshot_payload(&self) -> Vec<u8> {
        let mut s = self.get_state();
        let bytes = self.serialize(s);
        self.check("fmi2FreeFMUstate", self.free_state(&mut s));
        crate::bytes::unseal(S::guid(), &bytes)
            .expect("a state of this FMU")
            .to_vec()
    }

    // ----- freeing ----------------------------------------------------------

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
            unsafe { ffi::free_instance::<S>(self.c) };
            self.c = ptr::null_mut();
        }
    }
}

impl<S: Slave> Default for Host<S> {
    fn default() -> Self {
        Self::new()
    }
}

impl<S: Slave> Drop for Host<S> {
    fn drop(&mut self) {
        self.free_now();
    }
}
