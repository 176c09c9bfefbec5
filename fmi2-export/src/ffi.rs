//! The C side of every FMI 2.0 co-simulation function, generic over the
//! model. [`crate::export_fmi2!`] exports them under their standard names.
//!
//! Every function checks its pointers, catches panics (none crosses the
//! boundary: a panic becomes `fmi2Fatal` for that instance, or `NULL` from
//! `fmi2Instantiate`) and reports failures through the host's logger.

#![allow(clippy::missing_safety_doc)]

use std::ffi::{c_char, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::ptr;
use std::sync::Mutex;

use crate::fail::{error, panic_message, Fail, Res};
use crate::instance::{Inner, Instance, INSTANCE_MAGIC};
use crate::logging::{Logger, GENERIC_CATEGORIES};
use crate::machine::Machine;
use crate::slave::Slave;
use crate::types::*;
use crate::uri::decode_file_uri;

/// The instance behind `c`, if it is one of ours (best effort for foreign pointers).
unsafe fn instance<'a, S: Slave>(c: fmi2Component) -> Option<&'a Instance<S>> {
    if c.is_null() || !(c as usize).is_multiple_of(std::mem::align_of::<Instance<S>>()) {
        return None;
    }
    // SAFETY: the host passes back the pointer fmi2Instantiate returned; we
    // check our magic number and GUID before using anything else.
    let inst = unsafe { &*(c as *const Instance<S>) };
    if inst.magic != INSTANCE_MAGIC || inst.guid != S::guid() {
        return None;
    }
    Some(inst)
}

/// Runs `body` on the instance: state, logging, errors and panics handled.
/// Public for `fmi3-export`, which serves FMI 3.0 on the same instances; `c`
/// is only dereferenced after `instance` recognised it as one of ours.
#[allow(clippy::not_unsafe_ptr_arg_deref)]
pub fn call<S: Slave>(
    c: fmi2Component,
    function: &'static str,
    body: impl FnOnce(&mut Inner<S>) -> Res<Status>,
) -> fmi2Status {
    catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: see `instance`.
        let Some(inst) = (unsafe { instance::<S>(c) }) else {
            return fmi2Error;
        };
        let mut guard = inst.inner.lock().unwrap_or_else(|p| p.into_inner());
        let inner = &mut *guard;
        if inner.machine() == Machine::Fatal {
            inner.logger.status(
                Status::Error,
                &format!("{function}: the instance is in state fatal after an internal error; only fmi2FreeInstance is possible"),
            );
            return fmi2Error;
        }
        match catch_unwind(AssertUnwindSafe(|| body(inner))) {
            Ok(Ok(s)) => s.raw(),
            Ok(Err(f)) => inner.fail(function, f),
            Err(p) => inner.fail(
                function,
                Fail {
                    status: Status::Fatal,
                    message: format!("internal error: {}", panic_message(&*p)),
                },
            ),
        }
    }))
    .unwrap_or(fmi2Fatal)
}

pub unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Res<&'a [T]> {
    if n == 0 {
        Ok(&[])
    } else if p.is_null() {
        error(format!("{what} is NULL but n = {n}"))
    } else {
        // SAFETY: the host promises n valid elements at p.
        Ok(unsafe { std::slice::from_raw_parts(p, n) })
    }
}

pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> Res<&'a mut [T]> {
    if n == 0 {
        Ok(&mut [])
    } else if p.is_null() {
        error(format!("{what} is NULL but n = {n}"))
    } else {
        // SAFETY: the host promises n writable elements at p.
        Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
    }
}

pub unsafe fn out<'a, T>(p: *mut T, what: &str) -> Res<&'a mut T> {
    if p.is_null() {
        error(format!("{what} is NULL"))
    } else {
        // SAFETY: non-null, the host promises a writable T.
        Ok(unsafe { &mut *p })
    }
}

pub fn get_types_platform() -> *const c_char {
    c"default".as_ptr()
}

pub fn get_version() -> *const c_char {
    c"2.0".as_ptr()
}

pub unsafe fn c_str(p: fmi2String) -> Option<String> {
    if p.is_null() {
        None
    } else {
        // SAFETY: non-null NUL-terminated string from the host.
        Some(unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
    }
}

pub unsafe fn instantiate<S: Slave>(
    instance_name: fmi2String,
    fmu_type: fmi2Type,
    guid: fmi2String,
    resource_location: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    catch_unwind(AssertUnwindSafe(|| {
        let md = S::description();
        // SAFETY: the host passes a valid callback struct or NULL.
        let callbacks = unsafe { functions.as_ref() };
        let name = unsafe { c_str(instance_name) };
        let logger = Logger::new(
            md,
            callbacks.and_then(|f| f.logger),
            callbacks.map_or(ptr::null_mut(), |f| f.componentEnvironment),
            CString::new(name.clone().unwrap_or_default()).unwrap_or_default(),
            logging_on != fmi2False,
        );
        let refuse = |m: String| {
            logger.status(Status::Error, &format!("fmi2Instantiate: {m}"));
            ptr::null_mut()
        };
        match &name {
            Some(n) if !n.is_empty() => {}
            _ => return refuse("instanceName must be a non-empty string".into()),
        }
        let model_exchange = match fmu_type {
            t if t == fmi2CoSimulation => false,
            t if t == fmi2ModelExchange && md.model_exchange.is_some() => true,
            _ => {
                let supported = if md.model_exchange.is_some() {
                    "Model Exchange (fmi2ModelExchange = 0) and co-simulation (fmi2CoSimulation = 1)"
                } else {
                    "co-simulation (fmi2CoSimulation = 1) only"
                };
                return refuse(format!("fmuType = {fmu_type}: this FMU supports {supported}"));
            }
        };
        let g = unsafe { c_str(guid) };
        if g.as_deref() != Some(S::guid()) {
            return refuse(format!(
                "fmuGUID = {}: this binary was built for the model description with GUID {}",
                g.as_deref().unwrap_or("NULL"),
                S::guid()
            ));
        }
        for c in GENERIC_CATEGORIES {
            debug_assert!(md.log_categories.iter().any(|x| x.name == c), "{c}");
        }
        let resource = unsafe { c_str(resource_location) };
        let resource_dir = resource.as_deref().and_then(decode_file_uri);
        let inner = Inner::<S>::new(logger, resource_dir, model_exchange);
        if let (Some(r), None) = (&resource, &inner.resource_dir) {
            inner.log_status_warning(&format!(
                "fmi2Instantiate: fmuResourceLocation {r} is no file URI; resources are not used"
            ));
        }
        inner.trace(|| {
            format!(
                "fmi2Instantiate: instance {:?}, GUID {}, resources {}",
                name.as_deref().unwrap_or(""),
                S::guid(),
                inner
                    .resource_dir
                    .as_ref()
                    .map_or("none".into(), |d| d.display().to_string())
            )
        });
        let inst = Box::new(Instance {
            magic: INSTANCE_MAGIC,
            guid: S::guid(),
            inner: Mutex::new(inner),
        });
        Box::into_raw(inst) as fmi2Component
    }))
    .unwrap_or(ptr::null_mut())
}

pub unsafe fn free_instance<S: Slave>(c: fmi2Component) {
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: see `instance`.
        if unsafe { instance::<S>(c) }.is_none() {
            return;
        }
        let p = c as *mut Instance<S>;
        // SAFETY: one of ours, created by Box::into_raw in fmi2Instantiate.
        let mut b = unsafe { Box::from_raw(p) };
        {
            let inner = b.inner.get_mut().unwrap_or_else(|e| e.into_inner());
            inner.trace(|| "fmi2FreeInstance".into());
        }
        // A stale pointer passed again is recognised (best effort) as freed.
        b.magic = 0;
        // SAFETY: writing our own field before the memory is released.
        unsafe { ptr::write_volatile(&mut (*p).magic, 0) };
        drop(b);
    }));
}

pub unsafe fn set_debug_logging<S: Slave>(
    c: fmi2Component,
    logging_on: fmi2Boolean,
    n: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    call::<S>(c, "fmi2SetDebugLogging", |i| {
        let names = unsafe { category_names(categories, n) }?;
        i.set_debug_logging(logging_on != fmi2False, &names)
    })
}

/// The `n` log category names a host passes to `fmiXSetDebugLogging`
/// (FMI 2.0 and 3.0 alike); a NULL name is refused.
///
/// # Safety
/// `categories` points to `n` C strings, or is NULL with `n` = 0.
pub unsafe fn category_names(categories: *const fmi2String, n: usize) -> Res<Vec<String>> {
    let cats = unsafe { slice(categories, n, "categories") }?;
    let mut names = Vec::with_capacity(cats.len());
    for &p in cats {
        match unsafe { c_str(p) } {
            Some(s) => names.push(s),
            None => return error("a category is NULL"),
        }
    }
    Ok(names)
}

pub unsafe fn setup_experiment<S: Slave>(
    c: fmi2Component,
    tolerance_defined: fmi2Boolean,
    tolerance: fmi2Real,
    start_time: fmi2Real,
    stop_time_defined: fmi2Boolean,
    stop_time: fmi2Real,
) -> fmi2Status {
    call::<S>(c, "fmi2SetupExperiment", |i| {
        let tol = (tolerance_defined != fmi2False).then_some(tolerance);
        let stop = (stop_time_defined != fmi2False).then_some(stop_time);
        let shown = |x: Option<f64>| x.map_or("undefined".into(), |x| x.to_string());
        i.trace(|| {
            format!(
                "fmi2SetupExperiment(tolerance = {}, startTime = {start_time}, stopTime = {})",
                shown(tol),
                shown(stop)
            )
        });
        i.setup_experiment(tol, start_time, stop)
    })
}

pub unsafe fn enter_initialization_mode<S: Slave>(c: fmi2Component) -> fmi2Status {
    call::<S>(c, "fmi2EnterInitializationMode", |i| {
        i.trace(|| "fmi2EnterInitializationMode".into());
        i.enter_initialization_mode()
    })
}

pub unsafe fn exit_initialization_mode<S: Slave>(c: fmi2Component) -> fmi2Status {
    call::<S>(c, "fmi2ExitInitializationMode", |i| {
        i.trace(|| "fmi2ExitInitializationMode".into());
        i.exit_initialization_mode()
    })
}

pub unsafe fn terminate<S: Slave>(c: fmi2Component) -> fmi2Status {
    call::<S>(c, "fmi2Terminate", |i| {
        i.trace(|| "fmi2Terminate".into());
        i.terminate()
    })
}

pub unsafe fn reset<S: Slave>(c: fmi2Component) -> fmi2Status {
    call::<S>(c, "fmi2Reset", |i| {
        i.trace(|| "fmi2Reset".into());
        i.reset()
    })
}

/// `fmi2Get<Type>` or `fmi2Set<Type>` (`$function`): `n` value references
/// and `n` values (the host's arrays, checked by [`slice`] and `$values`),
/// handed to `Inner`'s method of the same name.
macro_rules! values_fn {
    ($name:ident, $function:literal, $value:ty, $values:ident) => {
        pub unsafe fn $name<S: Slave>(
            c: fmi2Component,
            vr: *const fmi2ValueReference,
            n: usize,
            value: $value,
        ) -> fmi2Status {
            call::<S>(c, $function, |i| {
                let vr = unsafe { slice(vr, n, "vr") }?;
                let value = unsafe { $values(value, n, "value") }?;
                i.$name(vr, value)
            })
        }
    };
}

values_fn!(get_real, "fmi2GetReal", *mut fmi2Real, slice_mut);
values_fn!(get_integer, "fmi2GetInteger", *mut fmi2Integer, slice_mut);
values_fn!(get_boolean, "fmi2GetBoolean", *mut fmi2Boolean, slice_mut);
values_fn!(get_string, "fmi2GetString", *mut fmi2String, slice_mut);
values_fn!(set_real, "fmi2SetReal", *const fmi2Real, slice);
values_fn!(set_integer, "fmi2SetInteger", *const fmi2Integer, slice);
values_fn!(set_boolean, "fmi2SetBoolean", *const fmi2Boolean, slice);

pub unsafe fn set_string<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    value: *const fmi2String,
) -> fmi2Status {
    call::<S>(c, "fmi2SetString", |i| {
        let vr = unsafe { slice(vr, n, "vr") }?;
        let value = unsafe { slice(value, n, "value") }?;
        i.set_string(vr, &unsafe { owned_strings(value) })
    })
}

/// The host's strings, copied (`None` for NULL, which `set_string` refuses).
pub unsafe fn owned_strings(value: &[fmi2String]) -> Vec<Option<CString>> {
    value
        .iter()
        // SAFETY: non-null NUL-terminated strings from the host.
        .map(|&p| (!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_owned()))
        .collect()
}

// The FMU-state functions have the same C shapes in FMI 2.0 and 3.0:
// `function` is the standard's name, for the messages.

pub unsafe fn get_fmu_state<S: Slave>(
    c: fmi2Component,
    state: *mut fmi2FMUstate,
    function: &'static str,
) -> fmi2Status {
    call::<S>(c, function, |i| {
        let state = unsafe { out(state, "FMUstate") }?;
        let p = i.get_fmu_state(*state as usize)?;
        *state = p as fmi2FMUstate;
        i.trace(|| format!("{function} -> {p:#x}"));
        Ok(Status::Ok)
    })
}

pub unsafe fn set_fmu_state<S: Slave>(
    c: fmi2Component,
    state: fmi2FMUstate,
    function: &'static str,
) -> fmi2Status {
    call::<S>(c, function, |i| {
        i.trace(|| format!("{function}({:#x})", state as usize));
        i.set_fmu_state(state as usize)
    })
}

pub unsafe fn free_fmu_state<S: Slave>(
    c: fmi2Component,
    state: *mut fmi2FMUstate,
    function: &'static str,
) -> fmi2Status {
    call::<S>(c, function, |i| {
        let state = unsafe { out(state, "FMUstate") }?;
        i.trace(|| format!("{function}({:#x})", *state as usize));
        let s = i.free_fmu_state(*state as usize)?;
        *state = ptr::null_mut();
        Ok(s)
    })
}

pub unsafe fn serialized_fmu_state_size<S: Slave>(
    c: fmi2Component,
    state: fmi2FMUstate,
    size: *mut usize,
    function: &'static str,
) -> fmi2Status {
    call::<S>(c, function, |i| {
        let size = unsafe { out(size, "size") }?;
        *size = i.serialized_size(state as usize)?;
        Ok(Status::Ok)
    })
}

pub unsafe fn serialize_fmu_state<S: Slave>(
    c: fmi2Component,
    state: fmi2FMUstate,
    bytes: *mut u8,
    size: usize,
    function: &'static str,
) -> fmi2Status {
    call::<S>(c, function, |i| {
        let buf = unsafe { slice_mut(bytes, size, "serializedState") }?;
        i.serialize_fmu_state(state as usize, buf)
    })
}

pub unsafe fn deserialize_fmu_state<S: Slave>(
    c: fmi2Component,
    bytes: *const u8,
    size: usize,
    state: *mut fmi2FMUstate,
    function: &'static str,
) -> fmi2Status {
    call::<S>(c, function, |i| {
        let state = unsafe { out(state, "FMUstate") }?;
        let buf = unsafe { slice(bytes, size, "serializedState") }?;
        let p = i.deserialize_fmu_state(buf)?;
        *state = p as fmi2FMUstate;
        Ok(Status::Ok)
    })
}

pub unsafe fn get_directional_derivative<S: Slave>(c: fmi2Component) -> fmi2Status {
    call::<S>(c, "fmi2GetDirectionalDerivative", |_| {
        error("not provided (providesDirectionalDerivative is false)")
    })
}

pub unsafe fn set_real_input_derivatives<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status {
    call::<S>(c, "fmi2SetRealInputDerivatives", |i| {
        let vr = unsafe { slice(vr, n, "vr") }?;
        let order = unsafe { slice(order, n, "order") }?;
        let value = unsafe { slice(value, n, "value") }?;
        i.set_real_input_derivatives(vr, order, value)
    })
}

pub unsafe fn get_real_output_derivatives<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    n: usize,
    order: *const fmi2Integer,
    value: *mut fmi2Real,
) -> fmi2Status {
    call::<S>(c, "fmi2GetRealOutputDerivatives", |i| {
        let vr = unsafe { slice(vr, n, "vr") }?;
        let order = unsafe { slice(order, n, "order") }?;
        let value = unsafe { slice_mut(value, n, "value") }?;
        i.get_real_output_derivatives(vr, order, value)
    })
}

pub unsafe fn do_step<S: Slave>(
    c: fmi2Component,
    current_communication_point: fmi2Real,
    communication_step_size: fmi2Real,
    _no_set_fmu_state_prior_to_current_point: fmi2Boolean,
) -> fmi2Status {
    call::<S>(c, "fmi2DoStep", |i| {
        i.trace(|| {
            format!(
                "fmi2DoStep(currentCommunicationPoint = {current_communication_point}, communicationStepSize = {communication_step_size})"
            )
        });
        i.do_step(current_communication_point, communication_step_size)
    })
}

pub unsafe fn cancel_step<S: Slave>(c: fmi2Component) -> fmi2Status {
    call::<S>(c, "fmi2CancelStep", |i| i.cancel_step())
}

/// `fmi2Get<Type>Status` (`$function`): `Inner`'s method of the same name
/// answers, into the host's `value` (a `bool` as `fmi2True`/`fmi2False`).
macro_rules! status_fn {
    ($name:ident, $function:literal, $value:ty) => {
        pub unsafe fn $name<S: Slave>(
            c: fmi2Component,
            kind: fmi2StatusKind,
            value: *mut $value,
        ) -> fmi2Status {
            call::<S>(c, $function, |i| {
                let value = unsafe { out(value, "value") }?;
                *value = i.$name(kind)?.into();
                Ok(Status::Ok)
            })
        }
    };
}

status_fn!(get_status, "fmi2GetStatus", fmi2Status);
status_fn!(get_real_status, "fmi2GetRealStatus", fmi2Real);
status_fn!(get_integer_status, "fmi2GetIntegerStatus", fmi2Integer);
status_fn!(get_boolean_status, "fmi2GetBooleanStatus", fmi2Boolean);

pub unsafe fn get_string_status<S: Slave>(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2String,
) -> fmi2Status {
    call::<S>(c, "fmi2GetStringStatus", |i| {
        let _ = unsafe { out(value, "value") }?;
        i.get_string_status(kind)?;
        Ok(Status::Ok)
    })
}
