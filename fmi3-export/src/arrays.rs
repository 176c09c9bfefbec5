//! Arrays sized by a structural parameter (`model_description::fmi3::Arrays3`):
//! the value reference of an array stands for its first `n` elements, the
//! 2.0 scalars `vr`, `vr + 1` ... (their value references are consecutive);
//! `n`, a `UInt64` in 3.0, is set in configuration mode. A model without
//! arrays keeps one value per value reference and has no configuration mode.

#![allow(clippy::missing_safety_doc)]

use fmi2_export::fail::{error, Res};
use fmi2_export::ffi::{call, slice, slice_mut};
use fmi2_export::instance::Inner;
use fmi2_export::machine::Machine;
use fmi2_export::model_description::fmi3::ArrayAt;
use fmi2_export::model_description::BaseType;
use fmi2_export::slave::Scalar;
use fmi2_export::types::Status;
use fmi2_export::values::start_value;
use fmi2_export::Slave;

use crate::types::*;

/// The current size of the arrays (the structural parameter's stored value).
fn size<S: Slave>(i: &Inner<S>) -> Option<usize> {
    let v = i.md.fmi3_size()?;
    let (k, _) = i.md.by_vr(BaseType::Integer, v.vr)?;
    match i.values[k] {
        Some(Scalar::Integer(n)) => usize::try_from(n).ok(),
        _ => None,
    }
}

/// The 2.0 scalars behind one 3.0 value reference: the array's current
/// elements, or the value reference itself.
fn scalars_of<S: Slave>(i: &Inner<S>, vr: u32) -> Res<(std::ops::Range<u32>, Option<ArrayAt>)> {
    match i.md.fmi3_array_at(vr) {
        None => Ok((vr..vr + 1, None)),
        Some(a) if a.element == 1 => {
            let n = size(i).unwrap_or(0) as u32;
            Ok((vr..vr + n, Some(a)))
        }
        Some(a) => error(format!(
            "value reference {vr} is no variable (element {} of {}, whose value reference is {}: arrays are got and set whole)",
            a.element,
            name(&a),
            vr + 1 - a.element as u32
        )),
    }
}

fn name(a: &ArrayAt) -> String {
    if a.derivative {
        format!("der({})", a.array)
    } else {
        a.array.to_string()
    }
}

/// The 2.0 scalars behind the host's value references, as many as its
/// `nValues`, and for each the index of the value reference it comes from.
pub fn scalars<S: Slave>(i: &Inner<S>, vrs: &[u32], n_values: usize) -> Res<Vec<(u32, usize)>> {
    let mut all = Vec::with_capacity(n_values);
    let mut arrays = Vec::new();
    for (k, &vr) in vrs.iter().enumerate() {
        let (range, array) = scalars_of(i, vr)?;
        if let Some(a) = array {
            arrays.push(format!("{} has {}", name(&a), range.len()));
        }
        all.extend(range.map(|r| (r, k)));
    }
    if all.len() == n_values {
        return Ok(all);
    }
    let what = if arrays.is_empty() {
        "every variable is a scalar".to_string()
    } else {
        let n = i.md.fmi3_size().map_or("n", |v| v.name);
        format!(
            "{} elements ({n} = {}), the scalars 1 each",
            arrays.join(", "),
            size(i).unwrap_or(0)
        )
    };
    error(format!(
        "nValues = {n_values} but the {} value references hold {} values: {what}",
        vrs.len(),
        all.len()
    ))
}

/// From state `from` only, to `to`.
fn move_state<S: Slave>(i: &mut Inner<S>, from: Machine, to: Machine) -> Res<Status> {
    if i.machine() != from {
        return error(format!(
            "not allowed in state {} (only in {})",
            i.machine().name(),
            from.name()
        ));
    }
    i.machine = to;
    Ok(Status::Ok)
}

pub unsafe fn enter_configuration_mode<S: Slave>(c: fmi3Instance) -> fmi3Status {
    call::<S>(c, "fmi3EnterConfigurationMode", |i| {
        if i.md.arrays3.is_none() {
            return error("this FMU has no structural parameter (not provided)");
        }
        move_state(i, Machine::Instantiated, Machine::ConfigurationMode)
    })
}

pub unsafe fn exit_configuration_mode<S: Slave>(c: fmi3Instance) -> fmi3Status {
    call::<S>(c, "fmi3ExitConfigurationMode", |i| {
        move_state(i, Machine::ConfigurationMode, Machine::Instantiated)
    })
}

/// Every element of every array back to its start value, its input
/// derivative to 0: a new size invalidates the arrays' values (FMI 3.0,
/// array variables and structural parameters).
fn restart_arrays<S: Slave>(i: &mut Inner<S>) {
    for (k, v) in i.md.variables.iter().enumerate() {
        if i.md.fmi3_element(v.name).is_some() {
            i.values[k] = start_value(v);
            i.derivatives[k] = 0.0;
        }
    }
}

fn check_size_parameter<S: Slave>(i: &Inner<S>, vrs: &[u32], n_values: usize) -> Res<usize> {
    let size = i.md.fmi3_size();
    for &vr in vrs {
        if size.is_none_or(|v| v.vr != vr) {
            return error(format!("value reference {vr} is no UInt64 variable"));
        }
    }
    if vrs.len() != n_values {
        return error(format!(
            "nValues = {n_values} but nValueReferences = {}: a UInt64 is a scalar",
            vrs.len()
        ));
    }
    Ok(size.map_or(0, |v| {
        i.md.by_vr(BaseType::Integer, v.vr).map_or(0, |x| x.0)
    }))
}

pub unsafe fn get_uint64<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *mut u64,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3GetUInt64", |i| {
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        check_size_parameter(i, vr, n_values)?;
        let value = unsafe { slice_mut(value, n, "values") }?;
        if !vr.is_empty() && i.machine() != Machine::ConfigurationMode {
            i.check_state(fmi2_export::machine::mask::fmi2GetInteger)?;
        }
        value.fill(size(i).unwrap_or(0) as u64);
        Ok(Status::Ok)
    })
}

pub unsafe fn set_uint64<S: Slave>(
    c: fmi3Instance,
    vr: *const fmi3ValueReference,
    n: usize,
    value: *const u64,
    n_values: usize,
) -> fmi3Status {
    call::<S>(c, "fmi3SetUInt64", |i| {
        let vr = unsafe { slice(vr, n, "valueReferences") }?;
        let k = check_size_parameter(i, vr, n_values)?;
        let value = unsafe { slice(value, n, "values") }?;
        let (Some(p), Some(a)) = (i.md.fmi3_size(), i.md.arrays3) else {
            return Ok(Status::Ok);
        };
        if i.machine() != Machine::ConfigurationMode {
            return error(format!(
                "{} is a structural parameter: set it in configuration mode (fmi3EnterConfigurationMode), not in state {}",
                p.name,
                i.machine().name()
            ));
        }
        for &x in value {
            if !(1..=a.len as u64).contains(&x) {
                return error(format!("{} = {x}: must be 1 to {}", p.name, a.len));
            }
            if size(i) != Some(x as usize) {
                i.values[k] = Some(Scalar::Integer(x as i32));
                restart_arrays(i);
                i.stale = true;
            }
        }
        Ok(Status::Ok)
    })
}
