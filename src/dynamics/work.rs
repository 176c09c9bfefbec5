//! The work limit of one call: a bound on the integrator steps (accepted or
//! rejected) and zero crossings, so that no call runs for minutes (a
//! stiff interface held at tiny explicit steps, a communication step of
//! 1e300 s, a vibration crossing zero for ever).

use super::{Events, State};

/// The most work one call may do, scaled with the length of the call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorkLimit {
    /// Work (see [`Events::work`]) allowed to a call of 1 s or longer.
    pub per_call: u64,
}

impl WorkLimit {
    /// Length of a call that gets all of `per_call`, s.
    pub const FULL_SPAN: f64 = 1.0;
    /// The smallest share of `per_call` a short call gets.
    pub const MIN_SHARE: f64 = 0.01;

    /// The budget of a call over `span` seconds: `per_call` for calls of
    /// [`FULL_SPAN`](Self::FULL_SPAN) or longer, a proportional share for
    /// shorter ones, at least [`MIN_SHARE`](Self::MIN_SHARE) of it and at
    /// least 1. Long calls get no more: the limit is there to bound the
    /// time a call takes.
    pub fn budget(&self, span: f64) -> u64 {
        let share = (span / Self::FULL_SPAN).clamp(Self::MIN_SHARE, 1.0);
        let share = if share.is_nan() { 1.0 } else { share };
        ((self.per_call as f64 * share).ceil() as u64).max(1)
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
                "{} zero crossings of theta (the body vibrates through theta = 0 faster than the step)",
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
