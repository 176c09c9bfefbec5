//! The C-facing Model Exchange functions (FMI 2.0 §3.2): pointer checks and
//! panic barriers around [`Inner`](crate::instance::Inner)'s methods, as in
//! [`ffi`](crate::ffi). Each takes the pointers the standard gives it: an
//! instance from `fmi2Instantiate` and arrays of the length passed.

#![allow(clippy::missing_safety_doc)]

use crate::ffi::{call, slice, slice_mut};
use crate::slave::Slave;
use crate::types::*;

pub unsafe fn set_time<S: Slave>(c: fmi2Component, time: fmi2Real) -> fmi2Status {
    call::<S>(c, "fmi2SetTime", |i| {
        i.trace(|| format!("fmi2SetTime(time = {time})"));
        i.set_time(time)
    })
}

pub unsafe fn set_continuous_states<S: Slave>(
    c: fmi2Component,
    x: *const fmi2Real,
    nx: usize,
) -> fmi2Status {
    call::<S>(c, "fmi2SetContinuousStates", |i| {
        let x = unsafe { slice(x, nx, "x") }?;
        i.set_continuous_states(x)
    })
}

/// A getter (`$function`) that fills the host's array of `n` Reals
/// (`$what` in the messages) by `Inner`'s method of the same name.
macro_rules! reals_fn {
    ($name:ident, $function:literal, $what:literal) => {
        pub unsafe fn $name<S: Slave>(c: fmi2Component, x: *mut fmi2Real, n: usize) -> fmi2Status {
            call::<S>(c, $function, |i| {
                let x = unsafe { slice_mut(x, n, $what) }?;
                i.$name(x)
            })
        }
    };
}

reals_fn!(get_continuous_states, "fmi2GetContinuousStates", "x");
reals_fn!(
    get_nominals_of_continuous_states,
    "fmi2GetNominalsOfContinuousStates",
    "x_nominal"
);
reals_fn!(get_derivatives, "fmi2GetDerivatives", "derivatives");
reals_fn!(
    get_event_indicators,
    "fmi2GetEventIndicators",
    "eventIndicators"
);

pub unsafe fn enter_event_mode<S: Slave>(c: fmi2Component) -> fmi2Status {
    call::<S>(c, "fmi2EnterEventMode", |i| i.enter_event_mode())
}

pub unsafe fn new_discrete_states<S: Slave>(
    c: fmi2Component,
    info: *mut fmi2EventInfo,
) -> fmi2Status {
    call::<S>(c, "fmi2NewDiscreteStates", |i| {
        let info = unsafe { slice_mut(info, 1, "fmi2eventInfo") }?;
        let (status, e) = i.new_discrete_states()?;
        info[0] = fmi2EventInfo {
            newDiscreteStatesNeeded: fmi2False,
            terminateSimulation: e.terminate_simulation as fmi2Boolean,
            nominalsOfContinuousStatesChanged: fmi2False,
            valuesOfContinuousStatesChanged: e.values_of_continuous_states_changed as fmi2Boolean,
            nextEventTimeDefined: fmi2False,
            nextEventTime: 0.0,
        };
        Ok(status)
    })
}

pub unsafe fn enter_continuous_time_mode<S: Slave>(c: fmi2Component) -> fmi2Status {
    call::<S>(c, "fmi2EnterContinuousTimeMode", |i| {
        i.enter_continuous_time_mode()
    })
}

pub unsafe fn completed_integrator_step<S: Slave>(
    c: fmi2Component,
    _no_set_fmu_state_prior_to_current_point: fmi2Boolean,
    enter_event_mode: *mut fmi2Boolean,
    terminate_simulation: *mut fmi2Boolean,
) -> fmi2Status {
    call::<S>(c, "fmi2CompletedIntegratorStep", |i| {
        let e = unsafe { slice_mut(enter_event_mode, 1, "enterEventMode") }?;
        let t = unsafe { slice_mut(terminate_simulation, 1, "terminateSimulation") }?;
        let (status, enter, terminate) = i.completed_integrator_step()?;
        e[0] = enter as fmi2Boolean;
        t[0] = terminate as fmi2Boolean;
        Ok(status)
    })
}
