//! The exported FMI 2.0 functions of one FMU, as function pointers: each
//! FMU crate exports its own `fmi2*` symbols, and a test binary links the
//! crate it tests, so the driver calls them through this table
//! ([`fmi2_api!`](crate::fmi2_api) fills it from a crate's functions).

#![allow(non_snake_case)]

use std::os::raw::c_char;

use fmi2_export::types::*;

/// The FMI 2.0 C API of one FMU.
pub struct Fmi2Api {
    pub fmi2GetTypesPlatform: extern "C" fn() -> *const c_char,
    pub fmi2GetVersion: extern "C" fn() -> *const c_char,
    pub fmi2SetDebugLogging:
        unsafe extern "C" fn(fmi2Component, fmi2Boolean, usize, *const fmi2String) -> fmi2Status,
    pub fmi2Instantiate: unsafe extern "C" fn(
        fmi2String,
        fmi2Type,
        fmi2String,
        fmi2String,
        *const fmi2CallbackFunctions,
        fmi2Boolean,
        fmi2Boolean,
    ) -> fmi2Component,
    pub fmi2FreeInstance: unsafe extern "C" fn(fmi2Component),
    pub fmi2SetupExperiment: unsafe extern "C" fn(
        fmi2Component,
        fmi2Boolean,
        fmi2Real,
        fmi2Real,
        fmi2Boolean,
        fmi2Real,
    ) -> fmi2Status,
    pub fmi2EnterInitializationMode: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    pub fmi2ExitInitializationMode: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    pub fmi2Terminate: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    pub fmi2Reset: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    pub fmi2GetReal: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *mut fmi2Real,
    ) -> fmi2Status,
    pub fmi2GetInteger: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *mut fmi2Integer,
    ) -> fmi2Status,
    pub fmi2GetBoolean: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *mut fmi2Boolean,
    ) -> fmi2Status,
    pub fmi2GetString: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *mut fmi2String,
    ) -> fmi2Status,
    pub fmi2SetReal: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *const fmi2Real,
    ) -> fmi2Status,
    pub fmi2SetInteger: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *const fmi2Integer,
    ) -> fmi2Status,
    pub fmi2SetBoolean: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *const fmi2Boolean,
    ) -> fmi2Status,
    pub fmi2SetString: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *const fmi2String,
    ) -> fmi2Status,
    pub fmi2GetFMUstate: unsafe extern "C" fn(fmi2Component, *mut fmi2FMUstate) -> fmi2Status,
    pub fmi2SetFMUstate: unsafe extern "C" fn(fmi2Component, fmi2FMUstate) -> fmi2Status,
    pub fmi2FreeFMUstate: unsafe extern "C" fn(fmi2Component, *mut fmi2FMUstate) -> fmi2Status,
    pub fmi2SerializedFMUstateSize:
        unsafe extern "C" fn(fmi2Component, fmi2FMUstate, *mut usize) -> fmi2Status,
    pub fmi2SerializeFMUstate:
        unsafe extern "C" fn(fmi2Component, fmi2FMUstate, *mut fmi2Byte, usize) -> fmi2Status,
    pub fmi2DeSerializeFMUstate: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2Byte,
        usize,
        *mut fmi2FMUstate,
    ) -> fmi2Status,
    pub fmi2GetDirectionalDerivative: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *const fmi2ValueReference,
        usize,
        *const fmi2Real,
        *mut fmi2Real,
    ) -> fmi2Status,
    pub fmi2SetRealInputDerivatives: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *const fmi2Integer,
        *const fmi2Real,
    ) -> fmi2Status,
    pub fmi2GetRealOutputDerivatives: unsafe extern "C" fn(
        fmi2Component,
        *const fmi2ValueReference,
        usize,
        *const fmi2Integer,
        *mut fmi2Real,
    ) -> fmi2Status,
    pub fmi2DoStep:
        unsafe extern "C" fn(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean) -> fmi2Status,
    pub fmi2CancelStep: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    pub fmi2GetStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2Status) -> fmi2Status,
    pub fmi2GetRealStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2Real) -> fmi2Status,
    pub fmi2GetIntegerStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2Integer) -> fmi2Status,
    pub fmi2GetBooleanStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2Boolean) -> fmi2Status,
    pub fmi2GetStringStatus:
        unsafe extern "C" fn(fmi2Component, fmi2StatusKind, *mut fmi2String) -> fmi2Status,
    pub fmi2SetTime: unsafe extern "C" fn(fmi2Component, fmi2Real) -> fmi2Status,
    pub fmi2SetContinuousStates:
        unsafe extern "C" fn(fmi2Component, *const fmi2Real, usize) -> fmi2Status,
    pub fmi2GetContinuousStates:
        unsafe extern "C" fn(fmi2Component, *mut fmi2Real, usize) -> fmi2Status,
    pub fmi2GetNominalsOfContinuousStates:
        unsafe extern "C" fn(fmi2Component, *mut fmi2Real, usize) -> fmi2Status,
    pub fmi2GetDerivatives: unsafe extern "C" fn(fmi2Component, *mut fmi2Real, usize) -> fmi2Status,
    pub fmi2GetEventIndicators:
        unsafe extern "C" fn(fmi2Component, *mut fmi2Real, usize) -> fmi2Status,
    pub fmi2EnterEventMode: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    pub fmi2NewDiscreteStates:
        unsafe extern "C" fn(fmi2Component, *mut fmi2EventInfo) -> fmi2Status,
    pub fmi2EnterContinuousTimeMode: unsafe extern "C" fn(fmi2Component) -> fmi2Status,
    pub fmi2CompletedIntegratorStep: unsafe extern "C" fn(
        fmi2Component,
        fmi2Boolean,
        *mut fmi2Boolean,
        *mut fmi2Boolean,
    ) -> fmi2Status,
}

/// The [`Fmi2Api`] of the crate `$fmu` (its exported `fmi2*` functions).
#[macro_export]
macro_rules! fmi2_api {
    ($fmu:path) => {{
        use $fmu as fmu;
        $crate::Fmi2Api {
            fmi2GetTypesPlatform: fmu::fmi2GetTypesPlatform,
            fmi2GetVersion: fmu::fmi2GetVersion,
            fmi2SetDebugLogging: fmu::fmi2SetDebugLogging,
            fmi2Instantiate: fmu::fmi2Instantiate,
            fmi2FreeInstance: fmu::fmi2FreeInstance,
            fmi2SetupExperiment: fmu::fmi2SetupExperiment,
            fmi2EnterInitializationMode: fmu::fmi2EnterInitializationMode,
            fmi2ExitInitializationMode: fmu::fmi2ExitInitializationMode,
            fmi2Terminate: fmu::fmi2Terminate,
            fmi2Reset: fmu::fmi2Reset,
            fmi2GetReal: fmu::fmi2GetReal,
            fmi2GetInteger: fmu::fmi2GetInteger,
            fmi2GetBoolean: fmu::fmi2GetBoolean,
            fmi2GetString: fmu::fmi2GetString,
            fmi2SetReal: fmu::fmi2SetReal,
            fmi2SetInteger: fmu::fmi2SetInteger,
            fmi2SetBoolean: fmu::fmi2SetBoolean,
            fmi2SetString: fmu::fmi2SetString,
            fmi2GetFMUstate: fmu::fmi2GetFMUstate,
            fmi2SetFMUstate: fmu::fmi2SetFMUstate,
            fmi2FreeFMUstate: fmu::fmi2FreeFMUstate,
            fmi2SerializedFMUstateSize: fmu::fmi2SerializedFMUstateSize,
            fmi2SerializeFMUstate: fmu::fmi2SerializeFMUstate,
            fmi2DeSerializeFMUstate: fmu::fmi2DeSerializeFMUstate,
            fmi2GetDirectionalDerivative: fmu::fmi2GetDirectionalDerivative,
            fmi2SetRealInputDerivatives: fmu::fmi2SetRealInputDerivatives,
            fmi2GetRealOutputDerivatives: fmu::fmi2GetRealOutputDerivatives,
            fmi2DoStep: fmu::fmi2DoStep,
            fmi2CancelStep: fmu::fmi2CancelStep,
            fmi2GetStatus: fmu::fmi2GetStatus,
            fmi2GetRealStatus: fmu::fmi2GetRealStatus,
            fmi2GetIntegerStatus: fmu::fmi2GetIntegerStatus,
            fmi2GetBooleanStatus: fmu::fmi2GetBooleanStatus,
            fmi2GetStringStatus: fmu::fmi2GetStringStatus,
            fmi2SetTime: fmu::fmi2SetTime,
            fmi2SetContinuousStates: fmu::fmi2SetContinuousStates,
            fmi2GetContinuousStates: fmu::fmi2GetContinuousStates,
            fmi2GetNominalsOfContinuousStates: fmu::fmi2GetNominalsOfContinuousStates,
            fmi2GetDerivatives: fmu::fmi2GetDerivatives,
            fmi2GetEventIndicators: fmu::fmi2GetEventIndicators,
            fmi2EnterEventMode: fmu::fmi2EnterEventMode,
            fmi2NewDiscreteStates: fmu::fmi2NewDiscreteStates,
            fmi2EnterContinuousTimeMode: fmu::fmi2EnterContinuousTimeMode,
            fmi2CompletedIntegratorStep: fmu::fmi2CompletedIntegratorStep,
        }
    }};
}
