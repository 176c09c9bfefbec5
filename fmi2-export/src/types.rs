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

/// `fmi2Status`.
pub type fmi2Status = c_int;
pub const fmi2OK: fmi2Status = 0;
pub const fmi2Warning: fmi2Status = 1;
pub const fmi2Discard: fmi2Status = 2;
pub const fmi2Error: fmi2Status = 3;
pub const fmi2Fatal: fmi2Status = 4;
pub const fmi2Pending: fmi2Status = 5;

/// `fmi2Type`.
pub type fmi2Type = c_int;
pub const fmi2ModelExchange: fmi2Type = 0;
pub const fmi2CoSimulation: fmi2Type = 1;

/// `fmi2StatusKind`.
pub type fmi2StatusKind = c_int;
pub const fmi2DoStepStatus: fmi2StatusKind = 0;
pub const fmi2PendingStatus: fmi2StatusKind = 1;
pub const fmi2LastSuccessfulTime: fmi2StatusKind = 2;
pub const fmi2Terminated: fmi2StatusKind = 3;

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
