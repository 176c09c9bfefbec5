//! The right-hand side of the equation of motion (docs/model.md §3).
//!
//! `I(phi) theta'' + (1/2) s I'(phi) omega^2 = -s W hW(phi) - m ag hg(phi)`
//! (`shiftingPivot`; `costa` drops the `omega^2` term; the rigid law has
//! `af = 0`, `I = IO` and both coincide), with `phi = |theta|`, `s = sgn theta`.

use crate::interface::Law;
use crate::model::Formulation;

use super::{GroundInput, Simulator};

/// The equation of motion of one model under the ground input of one
/// `advance` call: `ag(t) = ag + dag (t - t0)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Eom<'a> {
    sim: &'a Simulator,
    pub rigid: bool,
    pivot_term: bool,
    w: f64,
    mass: f64,
    b: f64,
    hg: f64,
    inv_io: f64,
    t0: f64,
    ag0: f64,
    dag: f64,
}

impl<'a> Eom<'a> {
    pub fn new(sim: &'a Simulator, t0: f64, input: GroundInput) -> Eom<'a> {
        let model = &sim.model;
        let rigid = model.interface.law() == Law::Rigid;
        let body = &model.body;
        Eom {
            sim,
            rigid,
            pivot_term: !rigid && model.formulation == Formulation::ShiftingPivot,
            w: body.weight,
            mass: body.mass,
            b: body.b,
            hg: body.hg,
            inv_io: 1.0 / body.io,
            t0,
            ag0: input.ag,
            dag: input.dag,
        }
    }

    /// Ground acceleration at `t`, m/s².
    #[inline(always)]
    pub fn ag(&self, t: f64) -> f64 {
        self.ag0 + self.dag * (t - self.t0)
    }

    /// Slope of the ground acceleration, m/s³.
    #[inline(always)]
    pub fn dag(&self) -> f64 {
        self.dag
    }

    /// `theta''` at `(t, theta, omega)`.
    ///
    /// Rigid law: `side` is the toe the body rocks about during the current
    /// step and the formula is continued analytically through `theta = 0`
    /// (`phi = side theta` may be slightly negative in a stage that overshoots
    /// an impact; the step is then cut at the impact).
    ///
    /// Flexible laws: the right-hand side is continuous through `theta = 0`
    /// (`hW(0) = 0`, `I'(0) = 0`), so the side is the sign of `theta`, and
    /// `side` only decides at `theta = 0` exactly. `hint` carries the contact
    /// length `a` from one evaluation to the next (warm start of the
    /// equilibrium solve).
    #[inline(always)]
    pub fn accel(&self, t: f64, theta: f64, omega: f64, side: f64, hint: &mut f64) -> f64 {
        let ag = self.ag(t);
        if self.rigid {
            let phi = side * theta;
            let (sp, cp) = crate::trig::sin_cos(phi);
            // R0 sin(alpha - phi) = b cos(phi) - hG sin(phi), R0 cos(alpha - phi) = hG cos(phi) + b sin(phi)
            let hw = self.b * cp - self.hg * sp;
            let hgl = self.hg * cp + self.b * sp;
            -(side * self.w * hw + self.mass * ag * hgl) * self.inv_io
        } else {
            self.accel_flexible(ag, theta, omega, side, hint)
        }
    }

    #[inline]
    fn accel_flexible(&self, ag: f64, theta: f64, omega: f64, side: f64, hint: &mut f64) -> f64 {
        let s = if theta > 0.0 {
            1.0
        } else if theta < 0.0 {
            -1.0
        } else {
            side
        };
        let phi = theta.abs();
        let c = self.sim.reaction(phi, *hint);
        if c.a.is_finite() {
            *hint = c.a;
        }
        let l = self.sim.model.levers(phi, &c);
        let mut num = -s * self.w * l.hw - self.mass * ag * l.hg;
        if self.pivot_term {
            num -= 0.5 * s * l.dinertia * omega * omega;
        }
        num / l.inertia
    }
}

/// The toe the body rocks about: the sign of `theta`; at `theta = 0` the
/// sign of `omega` (the side it is moving into); at rest with `omega = 0`
/// the side the ground pushes it to, `-sgn(ag)` (from the equation of motion
/// at `theta = 0+`, `theta'' = -(W hW + m ag hg) / I`: negative `ag` lifts
/// it toward `theta > 0`). `+1` when nothing decides.
#[inline]
pub(crate) fn side_of(theta: f64, omega: f64, ag: f64) -> f64 {
    if theta != 0.0 {
        theta.signum()
    } else if omega != 0.0 {
        omega.signum()
    } else if ag != 0.0 {
        -ag.signum()
    } else {
        1.0
    }
}
