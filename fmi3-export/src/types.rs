//! The FMI 3.0 C types this layer needs, declared once (`std::ffi`). The
//! status codes are FMI 2.0's (`fmi3OK` = 0 ... `fmi3Fatal` = 4).

#![allow(non_camel_case_types)]

use std::ffi::{c_char, c_void};

pub use fmi2_export::types::{fmi2Status as fmi3Status, fmi3LogMessageCallback};

pub type fmi3Instance = *mut c_void;
pub type fmi3InstanceEnvironment = *mut c_void;
pub type fmi3FMUState = *mut c_void;
pub type fmi3ValueReference = u32;
pub type fmi3Boolean = bool;
pub type fmi3String = *const c_char;
pub type fmi3Byte = u8;
pub type fmi3Float64 = f64;
/// `fmi3IntermediateUpdateCallback`: never called (no intermediate update).
pub type fmi3IntermediateUpdateCallback = *const c_void;
