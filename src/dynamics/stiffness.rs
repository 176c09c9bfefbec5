//! Stiffness switching (flexible laws, docs/dynamics.md §4): the explicit
//! pair while it is held by accuracy, RODAS with a projection on the slow
//! manifold while an explicit method would be held by stability.

use super::erk::{Pair, Start, StepOut, Tol};
use super::rodas::{self, Jac};
use super::Events;

/// Explicit steps with `h rho` above this are taken as held by stability.
const STIFF_ON: f64 = 1.0;
/// RODAS steps with `h rho` below this could be explicit.
const STIFF_OFF: f64 = 0.5;
/// Consecutive steps that decide a switch.
const SWITCH_AFTER: u32 = 15;

/// The method of a step: the explicit pair, or RODAS with its Jacobian.
#[derive(Clone, Copy, Debug)]
pub(super) enum Kind {
    Explicit,
    Rodas(Jac),
}

impl Kind {
    /// The step-size controller's exponent of the method.
    pub(super) fn err_exp<P: Pair>(&self) -> f64 {
        match self {
            Kind::Explicit => P::ERR_EXP,
            Kind::Rodas(_) => rodas::ERR_EXP,
        }
    }
}

/// Hairer's stiffness detection on an accepted step `hh` whose spectral
/// radius estimate is `rho`: explicit steps held at `h rho > STIFF_ON` by
/// stability go to RODAS, RODAS steps that an explicit method could take as
/// well (`h rho < STIFF_OFF`) come back, after `SWITCH_AFTER` consecutive
/// steps that argue for it. Updates `stiff` and `switch_count` (fields of
/// the state).
pub(super) fn switch(stiff: &mut bool, switch_count: &mut u32, hh: f64, rho: f64) {
    let stiff_now = if *stiff {
        hh * rho >= STIFF_OFF
    } else {
        hh * rho > STIFF_ON
    };
    if stiff_now == *stiff {
        *switch_count = 0;
    } else {
        *switch_count += 1;
        if *switch_count >= SWITCH_AFTER {
            *stiff = !*stiff;
            *switch_count = 0;
        }
    }
}

/// One step attempt of `h` from `s` with the current kind of method.
#[inline]
pub(super) fn attempt<P: Pair>(
    s: &Start,
    kind: &Kind,
    h: f64,
    hint: &mut f64,
    tol: &Tol,
    ev: &mut Events,
) -> StepOut {
    match kind {
        Kind::Explicit => {
            ev.stats.evals += P::EVALS;
            P::step(s, h, hint, tol)
        }
        Kind::Rodas(j) => {
            ev.stats.evals += rodas::EVALS - 3;
            // In the stiff mode the floor of the velocity error is that of
            // an oscillation at the Jacobian's frequency whose amplitude is
            // the floor of the rotation error: oscillations of the interface
            // below the floor are not resolved (RODAS damps them).
            let stiff_tol = Tol {
                atol_omega: tol.atol_omega.max(tol.atol_theta * j.rho()),
                ..*tol
            };
            rodas::step(s, j, h, hint, &stiff_tol)
        }
    }
}

/// The Jacobian for RODAS at the step start `s` (three evaluations).
pub(super) fn jacobian(s: &Start, h: f64, hint: f64, tol: &Tol, ev: &mut Events) -> Jac {
    ev.stats.evals += 3;
    let scales = [tol.atol_theta / tol.rtol, tol.atol_omega / tol.rtol];
    rodas::jacobian(s, h, hint, scales)
}

/// The state on the linearised slow manifold near `y0` when the fast
/// oscillation about it is below `floor`, else `None`. With `J` the Jacobian, the slow manifold has
/// `theta'' = 0`: `omega_s = -a_t / a_theta` and
/// `theta_s = theta - (a0 + a_omega (omega_s - omega)) / a_theta`. The
/// fast part is `(theta - theta_s, (omega - omega_s) / rho)` in amplitude.
/// Never across `theta = 0` (that is an impact).
pub(super) fn slow_state(j: &Jac, y0: [f64; 2], a0: f64, floor: f64) -> Option<(f64, f64)> {
    if j.a_theta >= 0.0 {
        return None;
    }
    let rho = (-j.a_theta).sqrt();
    let om = -j.a_t / j.a_theta;
    let th = y0[0] - (a0 + j.a_omega * (om - y0[1])) / j.a_theta;
    let fast = (th - y0[0]).hypot((om - y0[1]) / rho);
    let same_side = th * y0[0] > 0.0;
    (fast <= floor && same_side && th.is_finite() && om.is_finite()).then_some((th, om))
}
