//! The work limit of one call: a bound on the integrator steps (accepted or
//! rejected) and zero crossings, so that no call runs for minutes (a
//! stiff interface held at tiny explicit steps, a communication step of
//! 1e300 s, a vibration crossing zero for ever).

use super::{Events, State};

/// The most work one call may do, scaled with the length of the call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkLimit {
    /// Work (see [`Events::work`]) allowed to a call of up to
    /// [`BASE_SPAN`](Self::BASE_SPAN).
    pub per_call: u64,
}

impl WorkLimit {
    /// Calls up to this long get `per_call`, s.
    pub const BASE_SPAN: f64 = 1.0;
    /// Longer calls get proportionally more, up to this many times `per_call`.
    pub const MAX_FACTOR: f64 = 1.5;
    /// The default `per_call`: above the costliest call of the C-API stress
    /// grid (`fmu-rocking/tests/stress_c_api.rs`: a 0.17 m solid circle at
    /// kn 5e14 Pa/m, 1 s steps, 50 000 steps and crossings in the 0.6 s
    /// before a limit of 50 000 stopped it), and well under a second of
    /// work (about 2-5 µs per step on this machine).
    pub const DEFAULT_PER_CALL: u64 = 100_000;

    /// The budget of a call over `span` seconds: `per_call` up to
    /// [`BASE_SPAN`](Self::BASE_SPAN), proportionally more beyond, at most
    /// [`MAX_FACTOR`](Self::MAX_FACTOR) times as much, at least 1. Shorter
    /// calls get the whole `per_call`, so that a caller stopped by the limit
    /// can go on with shorter calls; longer ones no more than a bounded
    /// multiple, so that no call runs for long.
    pub fn budget(&self, span: f64) -> u64 {
        let factor = (span / Self::BASE_SPAN).clamp(1.0, Self::MAX_FACTOR);
        let factor = if factor.is_nan() { 1.0 } else { factor };
        ((self.per_call as f64 * factor).ceil() as u64).max(1)
    }
}

impl Default for WorkLimit {
    fn default() -> WorkLimit {
        WorkLimit {
            per_call: WorkLimit::DEFAULT_PER_CALL,
        }
    }
}

/// Where and why a call stopped at its work limit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limited {
    /// Time reached, s: the state's time after the call.
    pub t: f64,
    /// The call's budget (see [`WorkLimit::budget`]).
    pub budget: u64,
    /// Integrator steps of the call, accepted and rejected.
    pub steps: u64,
    /// Zero crossings of the call.
    pub zero_crossings: u64,
    /// The step size the integrator was at, s.
    pub h: f64,
    /// The integrator was in its stiff mode (RODAS).
    pub stiff: bool,
}

impl Limited {
    /// The record at the limit (`st.t` call-local: the caller sets the
    /// absolute time).
    pub(super) fn at(ev: &Events, st: &State, budget: u64, h: f64) -> Limited {
        Limited {
            t: st.t,
            budget,
            steps: ev.stats.steps as u64 + ev.stats.rejected as u64,
            zero_crossings: ev.zero_crossings as u64,
            h,
            stiff: st.stiff,
        }
    }

    /// Why the work ran out, in words: mostly zero crossings (the body
    /// vibrating through `theta = 0`) or mostly steps (steps far shorter
    /// than the call).
    pub fn cause(&self) -> String {
        if self.zero_crossings >= self.steps {
            format!(
                "{} zero crossings of theta (impacts or a vibration through theta = 0 that go on through the step)",
                self.zero_crossings
            )
        } else {
            format!(
                "{} integrator steps ({} zero crossings), the last {:e} s long{}",
                self.steps,
                self.zero_crossings,
                self.h,
                if self.stiff {
                    ", in the stiff mode"
                } else {
                    ""
                }
            )
        }
    }
}
