//! What FMI 3.0 declares that FMI 2.0 left implicit, derived from the same
//! table: the independent variable `time` (3.0 wants exactly one), the
//! event indicators as variables (3.0 lists them in `ModelStructure` by
//! value reference), and the first derivatives of the continuous inputs as
//! input variables `der(x)` with the `derivative` attribute (3.0 has no
//! `fmi3SetRealInputDerivatives`: a host sets them with `fmi3SetFloat64`).
//! Their value references follow the table's largest, in that order, so the
//! table itself stays the one of FMI 2.0.
//!
//! Arrays ([`Arrays3`]): where a model declares them, the table's scalars
//! `x[1]` ... `x[len]` are one array `x` in 3.0, sized by a structural
//! parameter; the array's value reference is the one of `x[1]`, and its
//! `k`-th element is the scalar of value reference `vr(x[1]) + k - 1`, so
//! the 3.0 layer maps an array access onto the 2.0 scalars by arithmetic.

use crate::schema::{BaseType, Causality, ModelDescription, Type, Variability, Variable};

/// FMI 3.0 arrays over the table's per-element scalars: the array `x` is
/// the table's `x[1]` ... `x[len]` (consecutive value references), with as
/// many elements as the structural parameter `size` says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arrays3 {
    /// An Integer parameter of the table: in 3.0 a `UInt64` structural
    /// parameter (1 to `len`), set in configuration mode.
    pub size: &'static str,
    /// The size's description in 3.0, where it sizes the arrays (the
    /// table's says what 2.0 does with the scalars past it).
    pub size_description: &'static str,
    /// The table's scalars per array: the largest `size`.
    pub len: usize,
    /// Each array: its name and description.
    pub arrays: &'static [(&'static str, &'static str)],
}

/// An array element of FMI 3.0 behind a Float64 value reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ArrayAt {
    /// The array's name (of `x` for an element of `der(x)`).
    pub array: &'static str,
    /// An element of `der(x)`, the input's derivative.
    pub derivative: bool,
    /// 1-based: 1 is the array's own value reference; the others are no
    /// variables in 3.0.
    pub element: usize,
}

/// Name of the independent variable of FMI 3.0.
pub const TIME: &str = "time";

impl ModelDescription {
    fn max_vr(&self) -> u32 {
        self.variables.iter().map(|v| v.vr).max().unwrap_or(0)
    }

    /// Value reference of `time` in FMI 3.0: one past the table's largest.
    pub fn fmi3_time_vr(&self) -> u32 {
        self.max_vr() + 1
    }

    /// Number of event indicators (Model Exchange), 0 without it.
    pub fn event_indicator_count(&self) -> u32 {
        self.model_exchange.map_or(0, |me| me.event_indicators)
    }

    /// Value reference of event indicator `i` (0-based) in FMI 3.0.
    pub fn fmi3_event_indicator_vr(&self, i: u32) -> u32 {
        self.max_vr() + 2 + i
    }

    /// The event indicator (0-based) behind value reference `vr`, if any.
    pub fn fmi3_event_indicator_of(&self, vr: u32) -> Option<usize> {
        let first = self.fmi3_event_indicator_vr(0);
        (vr >= first && vr - first < self.event_indicator_count()).then(|| (vr - first) as usize)
    }

    /// The continuous Real inputs whose first derivative FMI 3.0 declares as
    /// an input `der(x)` (co-simulation, when the FMU interpolates inputs as
    /// 2.0's `canInterpolateInputs` says), with their indices in the table.
    pub fn fmi3_derivative_inputs(&self) -> impl Iterator<Item = (usize, &Variable)> {
        let on = self.co_simulation.can_interpolate_inputs;
        self.variables.iter().enumerate().filter(move |(_, v)| {
            on && v.causality == Causality::Input
                && v.variability == Variability::Continuous
                && v.ty.base() == BaseType::Real
        })
    }

    /// Value reference of the `k`-th (0-based) `der(x)` input in FMI 3.0.
    pub fn fmi3_input_derivative_vr(&self, k: u32) -> u32 {
        self.max_vr() + 2 + self.event_indicator_count() + k
    }

    /// The table index of the input `x` whose `der(x)` has value reference `vr`, if any.
    pub fn fmi3_input_derivative_of(&self, vr: u32) -> Option<usize> {
        let k = vr.checked_sub(self.fmi3_input_derivative_vr(0))?;
        self.fmi3_derivative_inputs()
            .nth(k as usize)
            .map(|(i, _)| i)
    }

    /// The array (name, description) and 1-based element that the table
    /// variable `name` is in FMI 3.0, if any.
    pub fn fmi3_element(&self, name: &str) -> Option<(&'static str, &'static str, usize)> {
        let (base, rest) = name.split_once('[')?;
        let k = rest.strip_suffix(']')?.parse().ok()?;
        let a = self.arrays3?;
        let &(n, d) = a.arrays.iter().find(|(n, _)| *n == base)?;
        (1..=a.len).contains(&k).then_some((n, d, k))
    }

    /// The structural parameter that sizes the arrays, if any.
    pub fn fmi3_size(&self) -> Option<&'static Variable> {
        self.variable(self.arrays3?.size)
    }

    /// The FMI 3.0 value reference of the table variable `name`: the
    /// array's for an element.
    pub fn fmi3_vr(&self, name: &str) -> Option<u32> {
        let v = self.variable(name)?;
        Some(match self.fmi3_element(name) {
            Some((_, _, k)) => v.vr + 1 - k as u32,
            None => v.vr,
        })
    }

    /// The 3.0 element name of a table variable's type (`UInt64` for the
    /// structural parameter, `Enumeration` got and set as `Int64`).
    pub fn fmi3_type(&self, v: &Variable) -> &'static str {
        if self.arrays3.is_some_and(|a| a.size == v.name) {
            return "UInt64";
        }
        match v.ty {
            Type::Real { .. } => "Float64",
            Type::Integer { .. } => "Int32",
            Type::Boolean { .. } => "Boolean",
            Type::Enumeration { .. } => "Enumeration",
            Type::String { .. } => "String",
        }
    }

    /// Whether the Float64 value reference `vr` (of the table or a `der(x)`)
    /// is an array's or another element's, with arrays; `None` for a scalar.
    pub fn fmi3_array_at(&self, vr: u32) -> Option<ArrayAt> {
        self.arrays3?;
        let (name, der) = match self.fmi3_input_derivative_of(vr) {
            Some(i) => (self.variables[i].name, true),
            None => (self.by_vr(BaseType::Real, vr)?.1.name, false),
        };
        let (array, _, element) = self.fmi3_element(name)?;
        Some(ArrayAt {
            array,
            derivative: der,
            element,
        })
    }
}
