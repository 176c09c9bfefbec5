//! Time derivatives of the outputs (docs/model.md §5) at a state, orders 0
//! to 2, for hosts that extrapolate outputs between communication points.
//!
//! Every output is a function of `(t, theta, omega)` through
//! `phi = |theta|`, `s = sgn theta` and the ground input
//! `ag(t) = ag + dag (t - t0)` (linear within a step, `ag'' = 0`). Each one
//! is carried as a jet `[x, dx/dt, d²x/dt²]`:
//!
//! - functions of `phi` (`af`, `a`, the levers `hW`, `hg` and the inertia
//!   `I` of docs/model.md §3) from their `phi`-derivatives by the chain rule,
//!   `d/dt F(phi) = F' s omega`, `d²/dt² F(phi) = F'' omega² + F' s theta''`;
//! - `theta''` from the equation of motion (docs/model.md §3),
//!   `theta'' = N / I`, `N = -s W hW - m ag hg - (1/2) s I' omega²`
//!   (`shiftingPivot`; `costa` and the rigid law without the `I'` term),
//!   differentiated as a quotient of jets; `theta'''` and `theta''''` by
//!   feeding the jet of `theta` back in (Taylor's method);
//! - the support forces `Fx = m (ag + xG'')`, `Fz = m (g + zG'')` with
//!   `xG'' = hg theta'' + s hg' omega²`, `zG'' = s hW theta'' + hW' omega²`
//!   (G moving as a rotation about the shifted pivot, docs/model.md §5).
//!
//! The `phi`-derivatives of `af` are analytic up to `af''`
//! ([`Interface::second_derivatives`](crate::interface::Interface::second_derivatives));
//! `af'''` (needed by `theta''''` and the second derivatives of `Fx`, `Fz`)
//! is a central difference of the analytic `af''` with step `1e-4 phi`,
//! one-sided (three points on the side of the current regime) within two
//! steps of a kink of the right-hand side. Across a kink (`thetaJo`,
//! `thetaC`, a flange corner) the derivatives jump; the values here are
//! those of the regime the state is in (docs/dynamics.md, "Output
//! derivatives", for the measured accuracy).
//!
//! A body at rest has constant outputs, except `Fx = m ag` whose derivative
//! is `m dag`.
//!
//! Under a vertical input `av + dav (t - t0)` (docs/model.md §6) the rigid
//! law's outputs carry the jet of `N = W + m av`, `[N, m dav, 0]`, in place
//! of the weight (its levers do not depend on N); `Fz = m (g + av + zG'')`.
//! The flexible laws' contact depends on N as well: their rates under `av`
//! carry partial derivatives in `phi` and `N` (`loaded_rates`).

use crate::interface::{Law, Regime};
use crate::model::Formulation;

use super::eom::{side_of, Eom};
use super::{GroundInput, Simulator, State, VerticalInput};

/// `[x, dx/dt, d²x/dt²]` of one output, in its unit per s^order.
pub type Jet = [f64; 3];

/// Every real output of docs/model.md §5 (except `thetaOverAlpha`, which is
/// `theta / alpha`) with its first and second time derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutputRates {
    /// rad.
    pub theta: Jet,
    /// rad/s.
    pub omega: Jet,
    /// rad/s².
    pub theta_dd: Jet,
    /// m.
    pub af: Jet,
    /// m.
    pub contact_length: Jet,
    /// N m.
    pub mr: Jet,
    /// N.
    pub fx: Jet,
    /// N.
    pub fz: Jet,
    /// The apparent weight `N = W + m av`, N (docs/model.md §6.1).
    pub apparent_weight: Jet,
}

impl OutputRates {
    /// `|Fx| / Fz` with its time derivatives (docs/model.md §5, "Friction
    /// demand"): the quotient of the force jets, its sign taken from the
    /// first non-zero order of `Fx / Fz`; `+inf` in every order when
    /// `Fz <= 0`.
    pub fn friction_demand(&self) -> Jet {
        if self.fz[0] <= 0.0 {
            return [f64::INFINITY; 3];
        }
        let q = jet_div(self.fx, self.fz);
        let sign = q.iter().find(|x| **x != 0.0).map_or(1.0, |x| x.signum());
        jet_scale(sign, q)
    }
}

/// The jet of `N = W + m (av + dav t)`, N (the weight without `av`).
pub(super) fn apparent_weight(b: &crate::Body, v: VerticalInput) -> Jet {
    if v.av == 0.0 && v.dav == 0.0 {
        [b.weight, 0.0, 0.0]
    } else {
        [b.weight + b.mass * v.av, b.mass * v.dav, 0.0]
    }
}

/// Relative step of the central difference that gives `af'''`.
const AF3_STEP: f64 = 1e-4;

/// `phi`-derivatives of orders 0 to 3 of a function of `phi`.
type PhiDerivs = [f64; 4];

/// Leibniz's rule for `(u v)^(k)`, `k <= 3`.
fn phi_mul(u: PhiDerivs, v: PhiDerivs) -> PhiDerivs {
    [
        u[0] * v[0],
        u[1] * v[0] + u[0] * v[1],
        u[2] * v[0] + 2.0 * u[1] * v[1] + u[0] * v[2],
        u[3] * v[0] + 3.0 * u[2] * v[1] + 3.0 * u[1] * v[2] + u[0] * v[3],
    ]
}

pub(super) fn jet_add(u: Jet, v: Jet) -> Jet {
    [u[0] + v[0], u[1] + v[1], u[2] + v[2]]
}

pub(super) fn jet_scale(c: f64, u: Jet) -> Jet {
    [c * u[0], c * u[1], c * u[2]]
}

pub(super) fn jet_mul(u: Jet, v: Jet) -> Jet {
    [
        u[0] * v[0],
        u[1] * v[0] + u[0] * v[1],
        u[2] * v[0] + 2.0 * u[1] * v[1] + u[0] * v[2],
    ]
}

pub(super) fn jet_div(u: Jet, v: Jet) -> Jet {
    let w0 = u[0] / v[0];
    let w1 = (u[1] - w0 * v[1]) / v[0];
    let w2 = (u[2] - 2.0 * w1 * v[1] - w0 * v[2]) / v[0];
    [w0, w1, w2]
}

/// `[theta, omega, theta'', theta''', theta'''']` at `state` on the toe
/// `s`: `theta''` as `eom` gives it (the outputs' value to the bit), then
/// one more derivative per pass of `accel`, the equation of motion as a jet
/// in time of the jet of theta (Taylor's method: the k-th derivative of
/// `theta''` needs theta up to order k + 1).
pub(super) fn theta_jet(
    eom: &Eom,
    state: &State,
    s: f64,
    accel: impl Fn(&[f64; 5]) -> Jet,
) -> [f64; 5] {
    let mut hint = state.a;
    let theta_dd = eom.accel(state.t, state.theta, state.omega, s, &mut hint);
    let mut th = [state.theta, state.omega, theta_dd, 0.0, 0.0];
    th[3] = accel(&th)[1];
    th[4] = accel(&th)[2];
    th
}

/// The jets of the motion from the jet of theta on the toe `s`: `phi = s
/// theta`, `omega`, `omega²`, `theta''`.
pub(super) struct Motion {
    pub p: Jet,
    pub w: Jet,
    pub w2: Jet,
    pub thdd: Jet,
}

impl Motion {
    pub(super) fn of(th: &[f64; 5], s: f64) -> Motion {
        let w = [th[1], th[2], th[3]];
        Motion {
            p: [s * th[0], s * th[1], s * th[2]],
            w,
            w2: jet_mul(w, w),
            thdd: [th[2], th[3], th[4]],
        }
    }
}

/// `F(phi(t))` from `F, F', F''` at `phi(t0)` and the jet of `phi`.
pub(super) fn compose(f: &[f64], p: Jet) -> Jet {
    [f[0], f[1] * p[1], f[2] * p[1] * p[1] + f[1] * p[2]]
}

/// The levers and the inertia of docs/model.md §3 with their
/// `phi`-derivatives up to order 3.
struct Geometry {
    hw: PhiDerivs,
    hg: PhiDerivs,
    inertia: PhiDerivs,
}

impl Simulator {
    /// The outputs at `state` with their first and second time derivatives,
    /// under the ground input `ag + dag (t - state.t)` (m/s², m/s³).
    /// The values (order 0) are those of [`Simulator::outputs`].
    pub fn output_rates(&self, state: &State, input: GroundInput) -> OutputRates {
        self.rates_under(state, input, VerticalInput::default())
    }

    /// [`output_rates`](Self::output_rates) under the vertical input
    /// `av + dav (t - state.t)` too (m/s², m/s³); the values are those of
    /// [`Simulator::outputs_loaded`] (a flexible law's to rounding: its
    /// contact moves with N, see `loaded_rates`).
    pub fn output_rates_vertical(
        &self,
        state: &State,
        input: GroundInput,
        v: VerticalInput,
    ) -> OutputRates {
        self.rates_under(state, input, v)
    }

    fn rates_under(&self, state: &State, input: GroundInput, v: VerticalInput) -> OutputRates {
        let m = &self.model;
        let b = &m.body;
        let GroundInput { ag, dag } = input;
        let n = apparent_weight(b, v);
        if state.at_rest {
            let c = m.interface.contact(0.0);
            let constant = |x: f64| [x, 0.0, 0.0];
            let rest = OutputRates {
                theta: constant(state.theta),
                omega: constant(state.omega),
                theta_dd: constant(0.0),
                af: constant(c.af),
                contact_length: constant(c.contact_length),
                mr: constant(0.0),
                fx: [b.mass * ag, b.mass * dag, 0.0],
                fz: n,
                apparent_weight: n,
            };
            if self.held(ag, v.av) {
                return rest;
            }
            // ag sets the body moving: the motion's rates, but the contact
            // outputs keep their rest values as `outputs` does (the rigid
            // law's toe contact starts only once the body has lifted).
            let start = self.output_rates_in_motion(state, input, v);
            return OutputRates {
                af: rest.af,
                contact_length: rest.contact_length,
                mr: rest.mr,
                ..start
            };
        }
        self.output_rates_in_motion(state, input, v)
    }

    /// [`output_rates`](Self::output_rates) from the equation of motion at
    /// `state`.
    fn output_rates_in_motion(
        &self,
        state: &State,
        input: GroundInput,
        v: VerticalInput,
    ) -> OutputRates {
        let m = &self.model;
        let vertical = v.av != 0.0 || v.dav != 0.0;
        if vertical && m.interface.law() != Law::Rigid {
            return self.loaded_rates_in_motion(state, input, v);
        }
        let b = &m.body;
        let GroundInput { ag, dag } = input;
        let n_jet = apparent_weight(b, v);
        let rigid = m.interface.law() == Law::Rigid;
        let s = side_of(state.theta, state.omega, ag);
        // the rigid law continues the formulas through theta = 0 (see
        // `Eom::accel`); the flexible laws are even in theta
        let phi = if rigid {
            s * state.theta
        } else {
            state.theta.abs()
        };
        let c = if rigid {
            m.interface.contact(phi.max(f64::MIN_POSITIVE))
        } else {
            self.contact(phi, state.a)
        };
        let (af2, a2) = m.interface.second_derivatives(&c);
        let af3 = if rigid {
            0.0
        } else {
            self.af_third(phi, c.regime)
        };
        let af = [c.af, c.daf, af2, af3];
        let g = self.geometry(phi, af);
        let pivot = !rigid && m.formulation == Formulation::ShiftingPivot;

        // theta'' = N / I as a jet, from the jet of theta [theta, omega,
        // theta'', theta''', theta''''].
        let accel = |th: &[f64; 5]| -> Jet {
            let p = [s * th[0], s * th[1], s * th[2]];
            let w = [th[1], th[2], th[3]];
            let w2 = jet_mul(w, w);
            let ag_jet = [ag, dag, 0.0];
            let weight = if vertical {
                jet_scale(-s, jet_mul(n_jet, compose(&g.hw, p)))
            } else {
                jet_scale(-s * b.weight, compose(&g.hw, p))
            };
            let mut n = jet_add(
                weight,
                jet_scale(-b.mass, jet_mul(ag_jet, compose(&g.hg, p))),
            );
            if pivot {
                n = jet_add(
                    n,
                    jet_scale(-0.5 * s, jet_mul(compose(&g.inertia[1..], p), w2)),
                );
            }
            jet_div(n, compose(&g.inertia, p))
        };
        let eom = Eom::with_vertical(
            self,
            state.t,
            GroundInput { ag, dag: 0.0 },
            VerticalInput { av: v.av, dav: 0.0 },
        );
        let th = theta_jet(&eom, state, s, accel);
        let Motion { p, w, w2, thdd } = Motion::of(&th, s);
        let contact_length = if !rigid && c.a < m.interface.depth() {
            compose(&[c.a, c.da, a2], p)
        } else {
            [c.contact_length, 0.0, 0.0]
        };
        // docs/model.md §5: xG'' = hg theta'' + s hg' omega², zG'' = s hW theta'' + hW' omega²
        let xg_dd = jet_add(
            jet_mul(compose(&g.hg, p), thdd),
            jet_scale(s, jet_mul(compose(&g.hg[1..], p), w2)),
        );
        let zg_dd = jet_add(
            jet_scale(s, jet_mul(compose(&g.hw, p), thdd)),
            jet_mul(compose(&g.hw[1..], p), w2),
        );
        OutputRates {
            theta: [th[0], th[1], th[2]],
            omega: w,
            theta_dd: thdd,
            af: compose(&af, p),
            contact_length,
            mr: if vertical {
                jet_mul(n_jet, compose(&g.hw, p))
            } else {
                jet_scale(b.weight, compose(&g.hw, p))
            },
            fx: jet_scale(b.mass, jet_add([ag, dag, 0.0], xg_dd)),
            // av = 0: b.g + 0.0 is b.g, the same bits
            fz: jet_scale(b.mass, jet_add([b.g + v.av, v.dav, 0.0], zg_dd)),
            apparent_weight: n_jet,
        }
    }

    /// `hW = R0 sin(alpha - phi) - af cos(phi)`, `hg = R0 cos(alpha - phi) -
    /// af sin(phi)`, `I = Ic + m (R0² + af² - 2 R0 af sin(alpha))`
    /// (docs/model.md §3) and their `phi`-derivatives, from those of `af`.
    fn geometry(&self, phi: f64, af: PhiDerivs) -> Geometry {
        let b = &self.model.body;
        let (sp, cp) = crate::trig::sin_cos(phi);
        let sap = b.sin_alpha * cp - b.cos_alpha * sp; // sin(alpha - phi)
        let cap = b.cos_alpha * cp + b.sin_alpha * sp; // cos(alpha - phi)
        let r = b.r0;
        let sin_am = [r * sap, -r * cap, -r * sap, r * cap];
        let cos_am = [r * cap, r * sap, -r * cap, -r * sap];
        let cos_p = [cp, -sp, -cp, sp];
        let sin_p = [sp, cp, -sp, -cp];
        let acos = phi_mul(af, cos_p);
        let asin = phi_mul(af, sin_p);
        let af_sq = phi_mul(af, af);
        let k = 2.0 * r * b.sin_alpha;
        let mut inertia = [0.0; 4];
        let mut hw = [0.0; 4];
        let mut hg = [0.0; 4];
        for i in 0..4 {
            hw[i] = sin_am[i] - acos[i];
            hg[i] = cos_am[i] - asin[i];
            inertia[i] = b.mass * (af_sq[i] - k * af[i]);
        }
        inertia[0] += b.ic + b.mass * r * r;
        Geometry { hw, hg, inertia }
    }

    /// `d³af/dphi³` (m/rad³): central difference of the analytic `af''` with
    /// step `h = 1e-4 phi`; within `2 h` of a kink of the right-hand side,
    /// the one-sided difference on the side of `regime` (a kink belongs to
    /// the regime below it, as in `Interface::contact`). 0 in full contact,
    /// where `af` is linear.
    fn af_third(&self, phi: f64, regime: Regime) -> f64 {
        if regime == Regime::FullContact || phi == 0.0 {
            return 0.0;
        }
        let it = &self.model.interface;
        let d2 = |x: f64| it.second_derivatives(&it.contact(x)).0;
        let h = AF3_STEP * phi;
        let near = self
            .kinks
            .as_slice()
            .iter()
            .find(|&&k| (k - phi).abs() < 2.0 * h)
            .copied();
        match near {
            // below the kink or on it: backward
            Some(k) if phi <= k => {
                (3.0 * d2(phi) - 4.0 * d2(phi - h) + d2(phi - 2.0 * h)) / (2.0 * h)
            }
            Some(_) => (-3.0 * d2(phi) + 4.0 * d2(phi + h) - d2(phi + 2.0 * h)) / (2.0 * h),
            None => (d2(phi + h) - d2(phi - h)) / (2.0 * h),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::LawKind;
    use crate::Params;

    /// `af'''` (central, and one-sided next to a kink) against the closed
    /// forms of a solid rectangle (docs/model.md §2): elastic partial contact
    /// `af = a/3`, `a = sqrt(2W/(kn phi L))`, so `af''' = -(15/8) af/phi³`;
    /// partial crushing `af = alim/2 + fm L a1²/(24 W)`, `a1 = fm/(kn phi)`,
    /// so `af''' = -fm L a1²/(W phi³)`.
    #[test]
    fn third_derivative_of_af_matches_the_rectangle() {
        let elastic = Params {
            interface: LawKind::Elastic,
            ..Params::default()
        };
        let crushing = Params {
            fm: 1e6,
            ..Params::default()
        };
        let mut worst: f64 = 0.0;
        for p in [elastic, crushing] {
            let sim = Simulator::new(p.build().unwrap(), 1e-9);
            let it = &sim.model.interface;
            let w = sim.model.body.weight;
            let start = if p.interface == LawKind::Elastic {
                it.theta_jo()
            } else {
                it.theta_c()
            };
            // from just past the kink (one-sided) to 20 times it (central)
            for f in [1.0 + 1e-5, 1.0 + 1e-3, 1.5, 3.0, 20.0] {
                let phi = start * f;
                let c = it.contact(phi);
                let exact = if p.interface == LawKind::Elastic {
                    -15.0 / 8.0 * c.af / phi.powi(3)
                } else {
                    let a1 = p.fm / (p.kn * phi);
                    -p.fm * p.l * a1 * a1 / (w * phi.powi(3))
                };
                let e = (sim.af_third(phi, c.regime) - exact).abs() / exact.abs();
                println!("{:?} phi/kink = {f}: {e:.1e}", p.interface);
                worst = worst.max(e);
                assert!(e < 1e-6, "{:?} phi = {phi}: error {e:e}", p.interface);
            }
        }
        println!("af''' worst relative error {worst:.1e}");
    }
}
