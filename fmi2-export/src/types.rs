//! The FMI 2.0 C types (fmi2TypesPlatform.h, fmi2FunctionTypes.h), declared
//! once with `std::ffi` types; `size_t` is `usize`, its size on every target
//! Rust supports (std has no stable `c_size_t`). Enumerations the host passes in are plain `c_int`
//! so that an out-of-range value is an error, never undefined behaviour.

#![allow(non_camel_case_types, non_upper_case_globals, non_snake_case)]

use std::ffi::{c_char, c_double, c_int, c_uint, c_void};

pub type fmi2Component = *mut c_void;
pub type fmi2ComponentEnvironment = *mut c_void;
pub type fmi2FMUstate = *mut c_void;
pub type fmi2ValueReference = c_uint;
pub type fmi2Real = c_double;
pub type fmi2Integer = c_int;
pub type fmi2Boolean = c_int;
pub type fmi2Char = c_char;
pub type fmi2String = *const fmi2Char;
pub type fmi2Byte = c_char;

pub const fmi2True: fmi2Boolean = 1;
pub const fmi2False: fmi2Boolean = 0;

/// A C enumeration of the standard: its type, a `c_int`, and its values.
macro_rules! c_enum {
    ($(#[$doc:meta])* $ty:ident { $($name:ident = $v:literal),* $(,)? }) => {
        $(#[$doc])*
        pub type $ty = c_int;
        $(pub const $name: $ty = $v;)*
    };
}

c_enum! {
    /// `fmi2Status`.
    fmi2Status {
        fmi2OK = 0, fmi2Warning = 1, fmi2Discard = 2, fmi2Error = 3, fmi2Fatal = 4,
        fmi2Pending = 5,
    }
}

c_enum! {
    /// `fmi2Type`.
    fmi2Type { fmi2ModelExchange = 0, fmi2CoSimulation = 1 }
}

c_enum! {
    /// `fmi2StatusKind`.
    fmi2StatusKind {
        fmi2DoStepStatus = 0, fmi2PendingStatus = 1, fmi2LastSuccessfulTime = 2,
        fmi2Terminated = 3,
    }
}

pub type fmi2CallbackLogger = unsafe extern "C" fn(
    componentEnvironment: fmi2ComponentEnvironment,
    instanceName: fmi2String,
    status: fmi2Status,
    category: fmi2String,
    message: fmi2String,
    ...
);
pub type fmi2CallbackAllocateMemory = unsafe extern "C" fn(nobj: usize, size: usize) -> *mut c_void;
pub type fmi2CallbackFreeMemory = unsafe extern "C" fn(obj: *mut c_void);
pub type fmi2StepFinished =
    unsafe extern "C" fn(componentEnvironment: fmi2ComponentEnvironment, status: fmi2Status);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct fmi2CallbackFunctions {
    pub logger: Option<fmi2CallbackLogger>,
    pub allocateMemory: Option<fmi2CallbackAllocateMemory>,
    pub freeMemory: Option<fmi2CallbackFreeMemory>,
    pub stepFinished: Option<fmi2StepFinished>,
    pub componentEnvironment: fmi2ComponentEnvironment,
}

/// `fmi2EventInfo` (Model Exchange, `fmi2NewDiscreteStates`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct fmi2EventInfo {
    pub newDiscreteStatesNeeded: fmi2Boolean,
    pub terminateSimulation: fmi2Boolean,
    pub nominalsOfContinuousStatesChanged: fmi2Boolean,
    pub valuesOfContinuousStatesChanged: fmi2Boolean,
    pub nextEventTimeDefined: fmi2Boolean,
    pub nextEventTime: fmi2Real,
}

/// The status the Rust side works with; `as fmi2Status` for the C side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Status {
    Ok = 0,
    Warning = 1,
    Discard = 2,
    Error = 3,
    Fatal = 4,
}

impl Status {
    pub fn raw(self) -> fmi2Status {
        self as fmi2Status
    }

    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "fmi2OK",
            Status::Warning => "fmi2Warning",
            Status::Discard => "fmi2Discard",
            Status::Error => "fmi2Error",
            Status::Fatal => "fmi2Fatal",
        }
    }
}

/// FMI 3.0's logger: `(instanceEnvironment, status, category, message)`.
pub type fmi3LogMessageCallback = unsafe extern "C" fn(
    env: *mut c_void,
    status: fmi2Status,
    category: fmi2String,
    message: fmi2String,
);
