//! `fmi2Get*` and `fmi2Set*`: which variables are stored, which may be set
//! in which state, and the input and output derivatives. The three numeric
//! getters are one generic function over `Readable`.

use std::ffi::CString;

use model_description::{BaseType, Causality, Initial, Type, Variability, Variable};

use crate::fail::{error, Fail, Res};
use crate::instance::Inner;
use crate::machine::{mask, Machine, Mask};
use crate::slave::{Inputs, Scalar, Slave};
use crate::types::*;

use Machine as M;

fn is_stored(v: &Variable) -> bool {
    matches!(v.causality, Causality::Parameter | Causality::Input)
        || v.variability == Variability::Constant
        || matches!(
            v.effective_initial(),
            Some(Initial::Exact | Initial::Approx)
        )
}

fn from_store(v: &Variable) -> bool {
    matches!(v.causality, Causality::Parameter | Causality::Input)
        || v.variability == Variability::Constant
}

/// The value a stored variable starts with (`None`: computed by the model).
pub fn start_value(v: &Variable) -> Option<Scalar> {
    if !is_stored(v) {
        return None;
    }
    Some(match v.ty {
        Type::Real { start, .. } => Scalar::Real(start.unwrap_or(0.0)),
        Type::Integer { start } | Type::Enumeration { start, .. } => {
            Scalar::Integer(start.unwrap_or(0))
        }
        Type::Boolean { start } => Scalar::Boolean(start.unwrap_or(false)),
        Type::String { start } => {
            Scalar::String(CString::new(start.unwrap_or("")).unwrap_or_default())
        }
    })
}

/// Whether `v` may be set in state `m` (FMI 2.0 co-simulation rules).
fn settable(v: &Variable, m: Machine) -> bool {
    let input = v.causality == Causality::Input;
    let not_constant = v.variability != Variability::Constant;
    let init = v.effective_initial();
    match m {
        M::Instantiated => {
            input || (not_constant && matches!(init, Some(Initial::Exact | Initial::Approx)))
        }
        M::InitializationMode => {
            input
                || (v.causality != Causality::Parameter && v.variability == Variability::Tunable)
                || (not_constant && init == Some(Initial::Exact))
        }
        M::StepComplete | M::EventMode => {
            input || (v.causality == Causality::Parameter && v.variability == Variability::Tunable)
        }
        // Model Exchange, continuous-time mode: continuous inputs only
        M::ContinuousTimeMode => input && v.variability == Variability::Continuous,
        _ => false,
    }
}

/// A base type that `fmi2Get<Type>` reads alike: from the store or from the
/// model.
trait Readable: Sized {
    const BASE: BaseType;
    const MASK: Mask;
    fn stored(s: &Scalar) -> Option<Self>;
    fn computed<S: Slave>(slave: &mut S, vr: u32, inputs: Inputs<'_>) -> Result<Self, String>;
}

/// [`Readable`] for `$ty`: stored as `Scalar::$base`, of
/// `BaseType::$base`, read by `fmi2Get$base` (`$mask`), computed by
/// `Slave::$get`.
macro_rules! readable {
    ($ty:ty, $base:ident, $mask:ident, $get:ident) => {
        impl Readable for $ty {
            const BASE: BaseType = BaseType::$base;
            const MASK: Mask = mask::$mask;
            fn stored(s: &Scalar) -> Option<$ty> {
                match s {
                    Scalar::$base(x) => Some(*x),
                    _ => None,
                }
            }
            fn computed<S: Slave>(
                slave: &mut S,
                vr: u32,
                inputs: Inputs<'_>,
            ) -> Result<$ty, String> {
                slave.$get(vr, inputs)
            }
        }
    };
}

readable!(f64, Real, fmi2GetReal, get_real);
readable!(i32, Integer, fmi2GetInteger, get_integer);
readable!(bool, Boolean, fmi2GetBoolean, get_boolean);

impl<S: Slave> Inner<S> {
    /// `fmi2GetReal`, `fmi2GetInteger` and `fmi2GetBoolean`: parameters,
    /// inputs and constants from the store, the rest computed by the model.
    fn get<T: Readable>(&mut self, vrs: &[u32], mut put: impl FnMut(usize, T)) -> Res<Status> {
        self.check_state(T::MASK)?;
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(T::BASE, vr)?;
            let x = if from_store(v) {
                match self.values[i].as_ref().and_then(T::stored) {
                    Some(x) => x,
                    None => return error(format!("{} has no stored value", v.name)),
                }
            } else {
                self.with_inputs(|s, u| T::computed(s, vr, u), v.name)
                    .map_err(|f| Fail {
                        status: f.status,
                        message: format!("cannot evaluate {}: {}", v.name, f.message),
                    })?
            };
            put(k, x);
        }
        Ok(Status::Ok)
    }

    pub fn get_real(&mut self, vrs: &[u32], out: &mut [f64]) -> Res<Status> {
        self.get(vrs, |k, x| out[k] = x)
    }

    pub fn get_integer(&mut self, vrs: &[u32], out: &mut [i32]) -> Res<Status> {
        self.get(vrs, |k, x| out[k] = x)
    }

    pub fn get_boolean(&mut self, vrs: &[u32], out: &mut [fmi2Boolean]) -> Res<Status> {
        self.get(vrs, |k, b| out[k] = if b { fmi2True } else { fmi2False })
    }

    /// Pointers into the stored strings: valid until the next set or reset.
    pub fn get_string(&mut self, vrs: &[u32], out: &mut [fmi2String]) -> Res<Status> {
        self.check_state(mask::fmi2GetString)?;
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(BaseType::String, vr)?;
            match &self.values[i] {
                Some(Scalar::String(s)) => out[k] = s.as_ptr(),
                _ => return error(format!("{} has no stored value", v.name)),
            }
        }
        Ok(Status::Ok)
    }

    fn set(
        &mut self,
        function: &str,
        allowed: Mask,
        base: BaseType,
        vrs: &[u32],
        mut make: impl FnMut(usize, &Variable) -> Res<Scalar>,
    ) -> Res<Status> {
        self.check_state(allowed)?;
        // Check everything first: a refused call changes nothing.
        let mut staged = Vec::with_capacity(vrs.len());
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(base, vr)?;
            if !settable(v, self.machine) {
                return error(format!(
                    "{} (causality {}, variability {}) cannot be set in state {}",
                    v.name,
                    v.causality.as_str(),
                    v.variability.as_str(),
                    self.machine.name()
                ));
            }
            staged.push((i, v, make(k, v)?));
        }
        for (i, v, s) in staged {
            self.trace(|| format!("{function}: {} = {s}", v.name));
            self.values[i] = Some(s);
            if v.causality == Causality::Input {
                // A new input value starts a new polynomial: its derivative
                // applies only if set again after the value.
                self.derivatives[i] = 0.0;
            } else {
                self.stale = true;
            }
        }
        Ok(Status::Ok)
    }

    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Res<Status> {
        self.set(
            "fmi2SetReal",
            mask::fmi2SetReal,
            BaseType::Real,
            vrs,
            |k, v| {
                let x = values[k];
                if v.causality == Causality::Input && !x.is_finite() {
                    return error(format!("{} = {x}: the input must be finite", v.name));
                }
                Ok(Scalar::Real(x))
            },
        )
    }

    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Res<Status> {
        let md = self.md;
        self.set(
            "fmi2SetInteger",
            mask::fmi2SetInteger,
            BaseType::Integer,
            vrs,
            |k, v| {
                let x = values[k];
                if let Type::Enumeration { declared_type, .. } = v.ty {
                    if let Some(t) = md.enum_type(declared_type) {
                        if t.item(x).is_none() {
                            let items: Vec<String> = t
                                .items
                                .iter()
                                .map(|i| format!("{} ({})", i.value, i.name))
                                .collect();
                            return error(format!(
                                "{} = {x}: not an item of {declared_type}: {}",
                                v.name,
                                items.join(", ")
                            ));
                        }
                    }
                }
                Ok(Scalar::Integer(x))
            },
        )
    }

    pub fn set_boolean(&mut self, vrs: &[u32], values: &[fmi2Boolean]) -> Res<Status> {
        self.set(
            "fmi2SetBoolean",
            mask::fmi2SetBoolean,
            BaseType::Boolean,
            vrs,
            |k, _| Ok(Scalar::Boolean(values[k] != fmi2False)),
        )
    }

    pub fn set_string(&mut self, vrs: &[u32], values: &[Option<CString>]) -> Res<Status> {
        self.set(
            "fmi2SetString",
            mask::fmi2SetString,
            BaseType::String,
            vrs,
            |k, v| match &values[k] {
                Some(s) => Ok(Scalar::String(s.clone())),
                None => error(format!("{}: NULL string", v.name)),
            },
        )
    }

    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> Res<Status> {
        self.input_derivatives_allowed()?;
        let mut first = Vec::new();
        let mut ignored = Vec::new();
        for (k, &vr) in vrs.iter().enumerate() {
            match orders[k] {
                1 => first.push((vr, values[k])),
                o if o >= 2 => {
                    ignored.push(format!("{} (order {o})", self.continuous_input(vr)?.1.name))
                }
                o => {
                    let name = self.continuous_input(vr)?.1.name;
                    return error(format!("{name}: derivative order {o} must be >= 1"));
                }
            }
        }
        let staged = self.check_input_derivatives(&first)?;
        self.store_input_derivatives("fmi2SetRealInputDerivatives", &staged);
        if ignored.is_empty() {
            Ok(Status::Ok)
        } else {
            self.logger.status(
                Status::Warning,
                &format!(
                    "fmi2SetRealInputDerivatives: only first derivatives are used; ignored {}",
                    ignored.join(", ")
                ),
            );
            Ok(Status::Warning)
        }
    }

    /// Input derivatives may be set now, in this FMU.
    fn input_derivatives_allowed(&self) -> Res<()> {
        self.check_state(mask::fmi2SetRealInputDerivatives)?;
        if !self.md.co_simulation.can_interpolate_inputs {
            return error("canInterpolateInputs is false");
        }
        Ok(())
    }

    /// The continuous Real input `vr`, or the error naming it.
    fn continuous_input(&self, vr: u32) -> Res<(usize, &'static Variable)> {
        let (i, v) = self.lookup(BaseType::Real, vr)?;
        if v.causality != Causality::Input || v.variability != Variability::Continuous {
            return error(format!("{} is no continuous Real input", v.name));
        }
        Ok((i, v))
    }

    /// First derivatives `(input's value reference, d/dt)` checked as
    /// `fmi2SetRealInputDerivatives` checks them (a state where inputs are
    /// set, an FMU that interpolates inputs, continuous Real inputs, finite
    /// values): `(index, value)` to store, or the first problem. Also FMI
    /// 3.0's `der(x)` inputs, checked before anything is set.
    pub fn check_input_derivatives(&self, first: &[(u32, f64)]) -> Res<Vec<(usize, f64)>> {
        self.input_derivatives_allowed()?;
        let mut staged = Vec::with_capacity(first.len());
        for &(vr, x) in first {
            let (i, v) = self.continuous_input(vr)?;
            if !x.is_finite() {
                return error(format!(
                    "derivative of {} = {x}: the input derivative must be finite",
                    v.name
                ));
            }
            staged.push((i, x));
        }
        Ok(staged)
    }

    /// Stores what [`Self::check_input_derivatives`] accepted.
    pub fn store_input_derivatives(&mut self, function: &str, staged: &[(usize, f64)]) {
        for &(i, x) in staged {
            self.trace(|| format!("{function}: d{}/dt = {x}", self.md.variables[i].name));
            self.derivatives[i] = x;
        }
    }

    pub fn get_real_output_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        out: &mut [f64],
    ) -> Res<Status> {
        self.check_state(mask::fmi2GetRealOutputDerivatives)?;
        let max = self.md.co_simulation.max_output_derivative_order as i32;
        for (k, &vr) in vrs.iter().enumerate() {
            let (_, v) = self.lookup(BaseType::Real, vr)?;
            let o = orders[k];
            if v.causality != Causality::Output {
                return error(format!("{} is no output", v.name));
            }
            if o < 1 || o > max {
                return error(format!(
                    "{}: derivative order {o} outside 1..={max} (maxOutputDerivativeOrder)",
                    v.name
                ));
            }
            out[k] = self
                .with_inputs(|s, u| s.output_derivative(vr, o, u), v.name)
                .map_err(|f| Fail {
                    status: f.status,
                    message: format!("derivative of order {o} of {}: {}", v.name, f.message),
                })?;
        }
        Ok(Status::Ok)
    }
}
