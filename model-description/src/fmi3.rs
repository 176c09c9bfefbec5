//! What FMI 3.0 declares that FMI 2.0 left implicit, derived from the same
//! table: the independent variable `time` (3.0 wants exactly one) and the
//! event indicators as variables (3.0 lists them in `ModelStructure` by
//! value reference). Their value references follow the table's largest, so
//! the table itself stays the one of FMI 2.0.

use crate::schema::ModelDescription;

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
}
