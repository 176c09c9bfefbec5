//! FMI 3.0's modes: step mode and event mode of co-simulation
//! (`fmi3DoStep`, `fmi3EnterEventMode`, `fmi3UpdateDiscreteStates`,
//! `fmi3EnterStepMode`) and Model Exchange's continuous-time functions, on
//! the instance of `fmi2-export`.

#![allow(clippy::missing_safety_doc, clippy::too_many_arguments)]

use fmi2_export::fail::{error, Res};
use fmi2_export::ffi::{call, out, slice, slice_mut};
use fmi2_export::instance::Inner;
use fmi2_export::logging::LOG_EVENTS;
use fmi2_export::machine::Machine;
use fmi2_export::types::Status;
use fmi2_export::Slave;

use crate::types::*;

/// The host's four results of `fmi3DoStep`.
pub struct StepResults {
    pub event_handling_needed: *mut bool,
    pub terminate_simulation: *mut bool,
    pub early_return: *mut bool,
    pub last_successful_time: *mut f64,
}

pub unsafe fn do_step<S: Slave>(
    c: fmi3Instance,
    t: f64,
    h: f64,
    _no_set_fmu_state_prior_to_current_point: bool,
    results: StepResults,
) -> fmi3Status {
    call::<S>(c, "fmi3DoStep", |i| {
        let event = unsafe { out(results.event_handling_needed, "eventHandlingNeeded") }?;
        let terminate = unsafe { out(results.terminate_simulation, "terminateSimulation") }?;
        let early = unsafe { out(results.early_return, "earlyReturn") }?;
        let last = unsafe { out(results.last_successful_time, "lastSuccessfulTime") }?;
        let result = if i.early_return_allowed {
            i.do_step_to_event(t, h)
        } else {
            i.do_step(t, h).map(|s| (s, false))
        };
        // FMI 3.0 ends a run by terminateSimulation on an OK step, where
        // 2.0 discards the step.
        let result = match result {
            Err(f) if f.status == Status::Discard && i.terminated => {
                i.logger.log(
                    Status::Ok,
                    LOG_EVENTS,
                    &format!("fmi3DoStep: {}", f.message),
                );
                Ok((Status::Ok, i.last_successful_time < t + h))
            }
            r => r,
        };
        *last = i.last_successful_time;
        *terminate = i.terminated;
        let stopped_at_event = matches!(result, Ok((_, true)));
        // An event at t + h itself completes the step (no early return) but
        // still needs event mode: each event is reported once, at the step
        // that applied it.
        *early = stopped_at_event && i.early_return_allowed && *last < t + h;
        *event = stopped_at_event && i.event_mode_used && !i.terminated;
        result.map(|(s, _)| s)
    })
}

fn check_co_simulation<S: Slave>(i: &Inner<S>, from: Machine) -> Res<()> {
    if i.model_exchange {
        return error("only for a co-simulation instance");
    }
    if !i.event_mode_used {
        return error("the instance was created with eventModeUsed = false");
    }
    if i.machine() != from {
        return error(format!("not allowed in state {}", i.machine().name()));
    }
    Ok(())
}

pub unsafe fn enter_event_mode<S: Slave>(c: fmi3Instance) -> fmi3Status {
    call::<S>(c, "fmi3EnterEventMode", |i| {
        if i.model_exchange {
            return i.enter_event_mode();
        }
        check_co_simulation(i, Machine::StepComplete)?;
        i.machine = Machine::EventMode;
        Ok(Status::Ok)
    })
}

pub unsafe fn enter_step_mode<S: Slave>(c: fmi3Instance) -> fmi3Status {
    call::<S>(c, "fmi3EnterStepMode", |i| {
        check_co_simulation(i, Machine::EventMode)?;
        i.machine = Machine::StepComplete;
        Ok(Status::Ok)
    })
}

/// The host's six results of `fmi3UpdateDiscreteStates`.
pub struct UpdateResults {
    pub discrete_states_need_update: *mut bool,
    pub terminate_simulation: *mut bool,
    pub nominals_changed: *mut bool,
    pub values_changed: *mut bool,
    pub next_event_time_defined: *mut bool,
    pub next_event_time: *mut f64,
}

pub unsafe fn update_discrete_states<S: Slave>(c: fmi3Instance, r: UpdateResults) -> fmi3Status {
    call::<S>(c, "fmi3UpdateDiscreteStates", |i| {
        let need = unsafe { out(r.discrete_states_need_update, "discreteStatesNeedUpdate") }?;
        let terminate = unsafe { out(r.terminate_simulation, "terminateSimulation") }?;
        let nominals = unsafe { out(r.nominals_changed, "nominalsOfContinuousStatesChanged") }?;
        let values = unsafe { out(r.values_changed, "valuesOfContinuousStatesChanged") }?;
        let defined = unsafe { out(r.next_event_time_defined, "nextEventTimeDefined") }?;
        let next = unsafe { out(r.next_event_time, "nextEventTime") }?;
        (*need, *nominals, *defined, *next) = (false, false, false, 0.0);
        if i.model_exchange {
            let (s, e) = i.new_discrete_states()?;
            *terminate = e.terminate_simulation;
            *values = e.values_of_continuous_states_changed;
            return Ok(s);
        }
        // Co-simulation: the step already handled the event (the state is
        // the one after it), so there is nothing left to update.
        check_co_simulation(i, Machine::EventMode)?;
        *terminate = i.terminated;
        *values = false;
        Ok(Status::Ok)
    })
}

pub unsafe fn enter_continuous_time_mode<S: Slave>(c: fmi3Instance) -> fmi3Status {
    call::<S>(c, "fmi3EnterContinuousTimeMode", |i| {
        i.enter_continuous_time_mode()
    })
}

pub unsafe fn completed_integrator_step<S: Slave>(
    c: fmi3Instance,
    _no_set_fmu_state_prior_to_current_point: bool,
    enter_event_mode: *mut bool,
    terminate_simulation: *mut bool,
) -> fmi3Status {
    call::<S>(c, "fmi3CompletedIntegratorStep", |i| {
        let e = unsafe { out(enter_event_mode, "enterEventMode") }?;
        let t = unsafe { out(terminate_simulation, "terminateSimulation") }?;
        let (status, enter, terminate) = i.completed_integrator_step()?;
        (*e, *t) = (enter, terminate);
        Ok(status)
    })
}

pub unsafe fn set_time<S: Slave>(c: fmi3Instance, time: f64) -> fmi3Status {
    call::<S>(c, "fmi3SetTime", |i| i.set_time(time))
}

pub unsafe fn set_continuous_states<S: Slave>(
    c: fmi3Instance,
    x: *const f64,
    n: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3SetContinuousStates", |i| {
        let x = unsafe { slice(x, n, "continuousStates") }?;
        i.set_continuous_states(x)
    })
}

/// `fmi3Get...` of `n` reals into the host's array, by `Inner`'s method.
macro_rules! reals_fn {
    ($name:ident, $method:ident, $function:literal, $what:literal) => {
        pub unsafe fn $name<S: Slave>(c: fmi3Instance, x: *mut f64, n: usize) -> fmi3Status {
            call::<S>(c, $function, |i| {
                let x = unsafe { slice_mut(x, n, $what) }?;
                i.$method(x)
            })
        }
    };
}

reals_fn!(
    get_continuous_states,
    get_continuous_states,
    "fmi3GetContinuousStates",
    "continuousStates"
);
reals_fn!(
    get_nominals_of_continuous_states,
    get_nominals_of_continuous_states,
    "fmi3GetNominalsOfContinuousStates",
    "nominals"
);
reals_fn!(
    get_derivatives,
    get_derivatives,
    "fmi3GetContinuousStateDerivatives",
    "derivatives"
);
reals_fn!(
    get_event_indicators,
    get_event_indicators,
    "fmi3GetEventIndicators",
    "eventIndicators"
);

pub unsafe fn get_number_of_continuous_states<S: Slave>(
    c: fmi3Instance,
    n: *mut usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetNumberOfContinuousStates", |i| {
        *unsafe { out(n, "nContinuousStates") }? = i.continuous_state_count();
        Ok(Status::Ok)
    })
}

pub unsafe fn get_number_of_event_indicators<S: Slave>(
    c: fmi3Instance,
    n: *mut usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetNumberOfEventIndicators", |i| {
        *unsafe { out(n, "nEventIndicators") }? = i.event_indicator_count();
        Ok(Status::Ok)
    })
}
