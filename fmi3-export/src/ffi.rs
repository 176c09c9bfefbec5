//! The C side of the FMI 3.0 functions, generic over the model: each maps
//! its arguments onto the instance of `fmi2-export` (stored values, state
//! machine, FMU states, logger) through `fmi2_export::ffi::call`, which
//! checks the instance, catches panics and reports failures by the name of
//! the 3.0 function. [`crate::export_fmi3!`] exports them by their names.

#![allow(clippy::missing_safety_doc, clippy::too_many_arguments)]

use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::ptr;
use std::sync::Mutex;

use fmi2_export::fail::{error, Res};
use fmi2_export::ffi::{c_str, call, category_names, owned_strings, slice, slice_mut};
use fmi2_export::instance::{Inner, Instance, INSTANCE_MAGIC};
use fmi2_export::logging::{Callback, Logger};
use fmi2_export::machine::{mask, Machine};
use fmi2_export::model_description::{BaseType, ModelDescription};

pub use crate::arrays::{get_uint64, set_uint64};
use fmi2_export::types::Status;
use fmi2_export::Slave;

use crate::arrays::scalars;
use crate::types::*;

pub fn get_version() -> *const c_char {
    c"3.0".as_ptr()
}

/// How an instance is created: `fmi3InstantiateModelExchange` or
/// `fmi3InstantiateCoSimulation` with its two flags.
#[derive(Clone, Copy)]
pub struct Kind {
    pub model_exchange: bool,
    pub event_mode_used: bool,
    pub early_return_allowed: bool,
}

/// The host's `instanceName`, `instantiationToken` and `resourcePath`.
pub struct Names {
    pub instance_name: fmi3String,
    pub token: fmi3String,
    pub resource_path: fmi3String,
}

pub unsafe fn instantiate<S: Slave>(
    names: Names,
    kind: Kind,
    logging_on: bool,
    env: fmi3InstanceEnvironment,
    log_message: Option<fmi3LogMessageCallback>,
) -> fmi3Instance {
    catch_unwind(AssertUnwindSafe(|| {
        let md = S::description();
        let name = unsafe { c_str(names.instance_name) };
        let logger = Logger::with(
            md,
            log_message.map(Callback::Fmi3),
            env,
            CString::new(name.clone().unwrap_or_default()).unwrap_or_default(),
            logging_on,
        );
        let function = if kind.model_exchange {
            "fmi3InstantiateModelExchange"
        } else {
            "fmi3InstantiateCoSimulation"
        };
        let refuse = |m: String| {
            logger.status(Status::Error, &format!("{function}: {m}"));
            ptr::null_mut()
        };
        if name.as_deref().is_none_or(str::is_empty) {
            return refuse("instanceName must be a non-empty string".into());
        }
        if kind.model_exchange && md.model_exchange.is_none() {
            return refuse("this FMU has no Model Exchange interface".into());
        }
        let token = unsafe { c_str(names.token) };
        if token.as_deref() != Some(S::guid()) {
            return refuse(format!(
                "instantiationToken = {}: this binary was built for the model description with token {}",
                token.as_deref().unwrap_or("NULL"),
                S::guid()
            ));
        }
        let resource_dir = unsafe { c_str(names.resource_path) }.map(PathBuf::from);
        let mut inner = Inner::<S>::new(logger, resource_dir, kind.model_exchange);
        inner.event_mode_used = kind.event_mode_used && !kind.model_exchange;
        inner.early_return_allowed = kind.early_return_allowed && !kind.model_exchange;
        inner.trace(|| {
            let name = name.as_deref().unwrap_or("");
            format!("{function}: instance {name:?}, token {}", S::guid())
        });
        let inst = Box::new(Instance {
            magic: INSTANCE_MAGIC,
            guid: S::guid(),
            inner: Mutex::new(inner),
        });
        Box::into_raw(inst) as fmi3Instance
    }))
    .unwrap_or(ptr::null_mut())
}

pub unsafe fn set_debug_logging<S: Slave>(
    c: fmi3Instance,
    logging_on: bool,
    n: usize,
    categories: *const fmi3String,
) -> fmi3Status {
    call::<S>(c, "fmi3SetDebugLogging", |i| {
        let names = unsafe { category_names(categories, n) }?;
        i.set_debug_logging(logging_on, &names)
    })
}

pub unsafe fn enter_initialization_mode<S: Slave>(
    c: fmi3Instance,
    tolerance_defined: bool,
    tolerance: f64,
    start_time: f64,
    stop_time_defined: bool,
    stop_time: f64,
) -> fmi3Status {
    call::<S>(c, "fmi3EnterInitializationMode", |i| {
        let tol = tolerance_defined.then_some(tolerance);
        let stop = stop_time_defined.then_some(stop_time);
        i.setup_experiment(tol, start_time, stop)?;
        i.enter_initialization_mode()
    })
}

pub unsafe fn exit_initialization_mode<S: Slave>(c: fmi3Instance) -> fmi3Status {
    call::<S>(c, "fmi3ExitInitializationMode", |i| {
        let s = i.exit_initialization_mode()?;
        if i.event_mode_used {
            i.machine = Machine::EventMode;
        }
        Ok(s)
    })
}

pub unsafe fn terminate<S: Slave>(c: fmi3Instance) -> fmi3Status {
    call::<S>(c, "fmi3Terminate", |i| i.terminate())
}

pub unsafe fn reset<S: Slave>(c: fmi3Instance) -> fmi3Status {
    call::<S>(c, "fmi3Reset", |i| i.reset())
}

/// What 3.0 adds to the table's variables ([`fmi2_export::model_description::fmi3`]).
enum Added {
    Time,
    EventIndicator(usize),
    /// `der(x)`, by the table index of the input `x`.
    InputDerivative(usize),
}

fn added(md: &ModelDescription, vr: u32) -> Option<Added> {
    if vr == md.fmi3_time_vr() {
        Some(Added::Time)
    } else if let Some(j) = md.fmi3_event_indicator_of(vr) {
        Some(Added::EventIndicator(j))
    } else {
        md.fmi3_input_derivative_of(vr).map(Added::InputDerivative)
    }
}

/// Every `vr` names a variable of the table whose 3.0 type is `ty`.
fn check_types(md: &ModelDescription, vrs: &[u32], what: &str, ty: &str) -> Res<()> {
    for &vr in vrs {
        if !md
            .variables
            .iter()
            .any(|v| v.vr == vr && md.fmi3_type(v) == ty)
        {
            return error(format!("value reference {vr} is no {what} variable"));
        }
    }
    Ok(())
}

/// The 2.0 scalars behind the host's value references, one per value
/// (arrays: [`crate::arrays`]).
fn element_vrs<S: Slave>(i: &Inner<S>, vrs: &[u32], n_values: usize) -> Res<Vec<u32>> {
    if i.md.arrays3.is_none() {
        check_n_values(vrs.len(), n_values)?;
        return Ok(vrs.to_vec());
    }
    Ok(scalars(i, vrs, n_values)?
        .into_iter()
        .map(|(r, _)| r)
        .collect())
}

/// The host's `nValues` for scalars: as many values as value references.
fn check_n_values(n: usize, n_values: usize) -> Res<()> {
    if n == n_values {
        Ok(())
    } else {
        error(format!(
            "nValues = {n_values} but nValueReferences = {n}: every variable is a scalar"
        ))
    }
}

fn float64s<S: Slave>(i: &mut Inner<S>, vrs: &[u32], out: &mut [f64]) -> Res<Status> {
    if vrs.iter().all(|&vr| added(i.md, vr).is_none()) {
        return i.get_real(vrs, out);
    }
    let mut z: Option<Vec<f64>> = None;
    let mut status = Status::Ok;
    for (k, &vr) in vrs.iter().enumerate() {
        out[k] = match added(i.md, vr) {
            Some(Added::Time) => i.time,
            Some(Added::EventIndicator(j)) => {
                if z.is_none() {
                    let mut all = vec![0.0; i.event_indicator_count()];
                    status = status.max(i.event_indicators_as_variables(&mut all)?);
                    z = Some(all);
                }
                z.as_ref().expect("filled above")[j]
            }
            Some(Added::InputDerivative(x)) => {
                i.check_state(mask::fmi2GetReal)?;
                i.derivatives[x]
            }
            None => {
                status = status.max(i.get_real(&[vr], &mut out[k..=k])?);
                out[k]
            }
        };
    }
    Ok(status)
}

pub unsafe fn get_float64<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *mut f64,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetFloat64", |i| {
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let all = element_vrs(i, vr, n_values)?;
        let value = unsafe { slice_mut(value, n_values, "values") }?;
        float64s(i, &all, value)
    })
}

pub unsafe fn set_float64<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *const f64,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3SetFloat64", |i| {
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let all = element_vrs(i, vr, n_values)?;
        let vr = &all[..];
        let value = unsafe { slice(value, n_values, "values") }?;
        let (mut table, mut rates) = ((vec![], vec![]), vec![]);
        for (&v, &x) in vr.iter().zip(value) {
            match added(i.md, v) {
                None => {
                    table.0.push(v);
                    table.1.push(x);
                }
                Some(Added::InputDerivative(k)) => rates.push((i.md.variables[k].vr, x)),
                Some(_) => {
                    return error(format!(
                        "value reference {v} (time or an event indicator) cannot be set"
                    ))
                }
            }
        }
        if rates.is_empty() {
            return i.set_real(vr, value);
        }
        set_with_input_derivatives(i, table, &rates)
    })
}

/// `fmi3SetFloat64` with `der(x)` inputs among the variables: checked first
/// (a refused call changes nothing), then the table's values, then the
/// derivatives. Setting `x` resets `der(x)` to 0 as in 2.0 (a host that
/// knows nothing of `der(x)` gets its input held, never a stale slope),
/// unless `der(x)` is in the same call, in any order.
fn set_with_input_derivatives<S: Slave>(
    i: &mut Inner<S>,
    (vrs, values): (Vec<u32>, Vec<f64>),
    rates: &[(u32, f64)],
) -> Res<Status> {
    if i.model_exchange {
        return error(
            "der(x) inputs are for co-simulation: Model Exchange takes the inputs' values only",
        );
    }
    let staged = i.check_input_derivatives(rates)?;
    let status = if vrs.is_empty() {
        Status::Ok
    } else {
        i.set_real(&vrs, &values)?
    };
    i.store_input_derivatives("fmi3SetFloat64", &staged);
    Ok(status)
}

pub unsafe fn get_int32<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *mut i32,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetInt32", |i| {
        check_n_values(n, n_values)?;
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let value = unsafe { slice_mut(value, n, "values") }?;
        check_types(i.md, vr, "Int32", "Int32")?;
        i.get_integer(vr, value)
    })
}

pub unsafe fn set_int32<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *const i32,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3SetInt32", |i| {
        check_n_values(n, n_values)?;
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let value = unsafe { slice(value, n, "values") }?;
        check_types(i.md, vr, "Int32", "Int32")?;
        i.set_integer(vr, value)
    })
}

/// Enumerations are `Int64` in FMI 3.0; the table's codes fit an `i32`.
pub unsafe fn get_int64<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *mut i64,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetInt64", |i| {
        check_n_values(n, n_values)?;
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let value = unsafe { slice_mut(value, n, "values") }?;
        check_types(i.md, vr, "Enumeration (Int64)", "Enumeration")?;
        let mut v = vec![0; n];
        let s = i.get_integer(vr, &mut v)?;
        value.iter_mut().zip(v).for_each(|(o, x)| *o = x.into());
        Ok(s)
    })
}

pub unsafe fn set_int64<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *const i64,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3SetInt64", |i| {
        check_n_values(n, n_values)?;
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let value = unsafe { slice(value, n, "values") }?;
        check_types(i.md, vr, "Enumeration (Int64)", "Enumeration")?;
        let mut v = Vec::with_capacity(n);
        for (&r, &x) in vr.iter().zip(value) {
            match i32::try_from(x) {
                Ok(x) => v.push(x),
                Err(_) => return error(format!("value {x} of value reference {r} is no item")),
            }
        }
        i.set_integer(vr, &v)
    })
}

pub unsafe fn get_boolean<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *mut bool,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetBoolean", |i| {
        check_n_values(n, n_values)?;
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let value = unsafe { slice_mut(value, n, "values") }?;
        let mut v = vec![0; n];
        let s = i.get_boolean(vr, &mut v)?;
        value.iter_mut().zip(v).for_each(|(o, x)| *o = x != 0);
        Ok(s)
    })
}

pub unsafe fn set_boolean<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *const bool,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3SetBoolean", |i| {
        check_n_values(n, n_values)?;
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let value = unsafe { slice(value, n, "values") }?;
        let v: Vec<i32> = value.iter().map(|&b| b.into()).collect();
        i.set_boolean(vr, &v)
    })
}

pub unsafe fn get_string<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *mut fmi3String,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetString", |i| {
        check_n_values(n, n_values)?;
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let value = unsafe { slice_mut(value, n, "values") }?;
        i.get_string(vr, value)
    })
}

pub unsafe fn set_string<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *const fmi3String,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3SetString", |i| {
        check_n_values(n, n_values)?;
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let value = unsafe { slice(value, n, "values") }?;
        i.set_string(vr, &unsafe { owned_strings(value) })
    })
}

/// `fmi3Get<T>`/`fmi3Set<T>` of a type no variable of this layer has:
/// nothing to do for no value references, an error otherwise.
pub unsafe fn no_such_type<S: Slave>(
    c: fmi3Instance,
    function: &'static str,
    vr: *const fmi3ValueReference,
    n: usize,
) -> fmi3Status {
    call::<S>(c, function, |i| {
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        match vr.first() {
            None => Ok(Status::Ok),
            Some(&v) => {
                let what =
                    i.md.variables
                        .iter()
                        .find(|x| x.vr == v)
                        .map(|x| x.ty.base());
                error(format!(
                    "value reference {v} is no variable of this type{}",
                    what.map_or(String::new(), |b: BaseType| format!(
                        " (it is a {})",
                        b.as_str()
                    ))
                ))
            }
        }
    })
}

/// A function of FMI 3.0 this layer does not provide (its capability flag
/// is false or absent in the model description).
pub unsafe fn not_provided<S: Slave>(c: fmi3Instance, function: &'static str) -> fmi3Status {
    call::<S>(c, function, |_| {
        error("not provided by this FMU (see its modelDescription.xml)")
    })
}

pub unsafe fn get_output_derivatives<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    order: *const i32,
    value: *mut f64,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetOutputDerivatives", |i| {
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let order = unsafe { slice(order, n, "orders") }?;
        let all = scalars(i, vr, n_values)?;
        let orders: Vec<i32> = all.iter().map(|&(_, k)| order[k]).collect();
        let all: Vec<u32> = all.into_iter().map(|(r, _)| r).collect();
        let value = unsafe { slice_mut(value, n_values, "values") }?;
        i.get_real_output_derivatives(&all, &orders, value)
    })
}
