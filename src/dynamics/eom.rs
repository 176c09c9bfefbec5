//! The right-hand side of the equation of motion (docs/model.md §3).
//!
//! `I(phi) theta'' + (1/2) s I'(phi) omega^2 = -s W hW(phi) - m ag hg(phi)`
//! (`shiftingPivot`; `costa` drops the `omega^2` term; the rigid law has
//! `af = 0`, `I = IO` and both coincide), with `phi = |theta|`, `s = sgn theta`.

use crate::interface::{Contact, Law, Regime};
use crate::model::Formulation;

use super::{GroundInput, Simulator, VerticalInput};

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
    /// A vertical ground acceleration acts (docs/model.md §6); `false`: the
    /// apparent weight is the weight and none of its terms is evaluated.
    pub vertical: bool,
    av0: f64,
    dav: f64,
}

impl<'a> Eom<'a> {
    /// The equation under the vertical input `av(t) = av + dav (t - t0)`
    /// too (`VerticalInput::default()`: none).
    pub fn with_vertical(
        sim: &'a Simulator,
        t0: f64,
        input: GroundInput,
        v: VerticalInput,
    ) -> Eom<'a> {
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
            vertical: v.av != 0.0 || v.dav != 0.0,
            av0: v.av,
            dav: v.dav,
        }
    }

    /// Vertical ground acceleration at `t`, m/s².
    #[inline(always)]
    pub fn av(&self, t: f64) -> f64 {
        self.av0 + self.dav * (t - self.t0)
    }

    /// Apparent weight `N(t) = W + m av(t)` (docs/model.md §6.1), N.
    #[inline(always)]
    pub fn apparent_weight(&self, t: f64) -> f64 {
        if self.vertical {
            self.w + self.mass * self.av(t)
        } else {
            self.w
        }
    }

    /// Slope of the vertical ground acceleration, m/s³.
    #[inline(always)]
    pub fn dav(&self) -> f64 {
        self.dav
    }

    /// `dN/dt = m dav/dt`, N/s.
    #[inline(always)]
    pub fn dn(&self) -> f64 {
        self.mass * self.dav
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
            // docs/model.md §6.2, rigid: the weight becomes N = m (g + av)
            let n = self.apparent_weight(t);
            -(side * n * hw + self.mass * ag * hgl) * self.inv_io
        } else if self.vertical {
            self.accel_loaded(ag, self.apparent_weight(t), theta, omega, side, hint)
        } else {
            self.accel_flexible(ag, theta, omega, side, hint)
        }
    }

    /// `theta''` of a flexible law under the apparent weight `n` (docs/model.md
    /// §6.2, shiftingPivot): `I theta'' + (1/2)(dI/dt) omega = -s N hW - m ag hg`
    /// with `dI/dt = s (dI/dphi) omega + (dI/dN) dN/dt` — the power form
    /// `d/dt(I omega²/2) = (-s N hW - m ag hg) omega`, which balances the
    /// energy against the work of the vertical input (§6.3); costa drops
    /// both terms. The contact at `(phi, N)`: [`contact_loaded`](Self::contact_loaded).
    /// Out of line: inlined, its copy of the contact made `av = 0`'s
    /// evaluations slower (docs/performance.md).
    #[inline(never)]
    fn accel_loaded(
        &self,
        ag: f64,
        n: f64,
        theta: f64,
        omega: f64,
        side: f64,
        hint: &mut f64,
    ) -> f64 {
        let s = toe(theta, side);
        let phi = theta.abs();
        let (c, daf_dn) = self.contact_loaded(phi, n, hint);
        let l = self.sim.model.levers(phi, &c);
        let mut num = -s * n * l.hw - self.mass * ag * l.hg;
        if self.pivot_term {
            // dI/dN = -2 m (b - af) daf/dN, like dI/dphi
            let di_dn = -2.0 * self.mass * (self.b - c.af) * daf_dn;
            num -= 0.5 * (s * l.dinertia * omega + di_dn * self.dn()) * omega;
        }
        num / l.inertia
    }

    /// The contact of a flexible law at `phi = |theta|` under the apparent
    /// weight `n` (N) and `daf/dN` (m/N), from `hint` (the `a` of a nearby
    /// contact, updated). For an elastic bed `a` depends on `phi/N` only,
    /// so the table at the weight answers at `phi W/N`
    /// (`af(phi, N) = af(phi W/N, W)`, `daf/dphi` scaled by `W/N`,
    /// `daf/dN = -(phi/N) daf/dphi`); a crushing bed is solved at N
    /// (docs/model.md §6.1).
    #[inline(always)]
    pub fn contact_loaded(&self, phi: f64, n: f64, hint: &mut f64) -> (Contact, f64) {
        let model = &self.sim.model;
        let r = self.w / n;
        let (c, daf_dn) = if n <= 0.0 {
            // the liftOff instant that ends the run (docs/model.md §6.5): the
            // limit N -> 0+, the contact shrunk to the toe; daf/dN, unbounded
            // there (as N^(-3/5) on a hollow circle's toe) but integrable in
            // time, is left out at this one instant
            model.contact_loaded(phi, n)
        } else if model.interface.is_elastic() {
            let mut c = self.sim.reaction(phi * r, *hint);
            c.daf *= r;
            (c, -phi / n * c.daf)
        } else if let Some(mut c) = self.uncrushed(phi, r, *hint) {
            c.daf *= r;
            (c, -phi / n * c.daf)
        } else {
            let (c, xel) = model.interface.contact_loaded(phi, n, *hint);
            self.sim.threshold_limits.note_solved(phi, n, c.a);
            (c, (xel - c.af) / n)
        };
        if c.a.is_finite() {
            *hint = c.a;
        }
        (c, daf_dn)
    }

    /// The edge `a` (m) of the contact [`contact_loaded`](Self::contact_loaded)
    /// gives at `(phi, n)`, read where the table answers without it: which
    /// side of their points the moving thresholds' edges are on
    /// (docs/model.md §6.4). NaN at `phi <= 0` or `n <= 0`.
    pub fn contact_edge(&self, phi: f64, n: f64, hint: f64) -> f64 {
        if phi <= 0.0 || n <= 0.0 {
            return f64::NAN;
        }
        let it = &self.sim.model.interface;
        // an uncrushed contact at N is the elastic bed's at the weight at
        // phi W/N (docs/model.md §6.1), valid while kn phi a <= fm
        let c = self.sim.contact(phi * self.w / n, hint);
        let uncrushed = match it.law() {
            Law::ElastoPlastic { kn, fm } => {
                matches!(c.regime, Regime::FullContact | Regime::Partial) && kn * phi * c.a <= fm
            }
            _ => true,
        };
        if uncrushed {
            c.a
        } else {
            it.contact_loaded(phi, n, hint).0.a
        }
    }

    /// The contact of a crushing bed at `(phi, N)`, `r = W/N`, where the toe
    /// has not crushed: then the bed is elastic and the contact is the one
    /// at the weight at `phi r` (docs/model.md §6.1), if that one has not
    /// crushed either and its `a` stays below `a1 = fm/(kn phi)`. `None`:
    /// solve at N. `daf` is per radian of `phi r`.
    #[inline(always)]
    fn uncrushed(&self, phi: f64, r: f64, hint: f64) -> Option<Contact> {
        let Law::ElastoPlastic { kn, fm } = self.sim.model.interface.law() else {
            return None;
        };
        let (c, a_max) = self.sim.reaction_bounded(phi * r, hint);
        if !matches!(c.regime, Regime::FullContact | Regime::Partial) {
            return None;
        }
        // N <= W: the toe's stress here, kn phi a, is at most the one of
        // the contact at the weight at phi r, kn (phi r) a (the same a),
        // which has not crushed. Else a bound on a that keeps the toe's
        // stress below fm (a margin far above the table's error) shows it
        // without the contact's a.
        if r >= 1.0 || kn * phi * a_max * (1.0 + 1e-9) <= fm {
            return Some(c);
        }
        let c = self.sim.contact(phi * r, hint);
        (c.a <= fm / (kn * phi)).then_some(c)
    }

    #[inline]
    fn accel_flexible(&self, ag: f64, theta: f64, omega: f64, side: f64, hint: &mut f64) -> f64 {
        let s = toe(theta, side);
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

/// The sign of `theta`, `side` at `theta = 0` (a flexible law's toe).
#[inline(always)]
fn toe(theta: f64, side: f64) -> f64 {
    if theta > 0.0 {
        1.0
    } else if theta < 0.0 {
        -1.0
    } else {
        side
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
