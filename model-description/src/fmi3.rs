//! What FMI 3.0 declares that FMI 2.0 left implicit, derived from the same
//! table: the independent variable `time` (3.0 wants exactly one), the
//! event indicators as variables (3.0 lists them in `ModelStructure` by
//! value reference), and the first derivatives of the continuous inputs as
//! input variables `der(x)` with the `derivative` attribute (3.0 has no
//! `fmi3SetRealInputDerivatives`: a host sets them with `fmi3SetFloat64`).
//! Their value references follow the table's largest, in that order, so the
//! table itself stays the one of FMI 2.0.

use crate::schema::{BaseType, Causality, ModelDescription, Variability, Variable};

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
}
