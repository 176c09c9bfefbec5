//! Output derivatives of a flexible law under a vertical input (docs/model.md
//! §6, docs/dynamics.md "Output derivatives"): the contact depends on
//! `phi` and on the apparent weight `N(t) = W + m (av + dav t)`, so every
//! function of the contact is carried with its partial derivatives in both
//! ([`Biv`]) and composed with the jets of `phi` and `N` (`N'' = 0`).
//!
//! The partials of `af` and `a` up to order 2 are analytic
//! ([`Interface::loaded_second_derivatives`](crate::interface::Interface::loaded_second_derivatives));
//! those of order 3 of `af` (which `theta''''` needs) are differences of
//! the analytic ones with steps `1e-4 phi` and `1e-4 N`, central, or
//! one-sided on the state's side where a moving threshold (docs/model.md
//! §6.4) lies within two steps, as `af'''` is without `av`.

use crate::interface::{Contact, LoadedCurvature, Regime};
use crate::model::Formulation;

use super::eom::{side_of, Eom};
use super::output_rates::{
    apparent_weight, jet_add, jet_div, jet_mul, jet_scale, theta_jet, Jet, Motion, OutputRates,
};
use super::{GroundInput, Simulator, State, VerticalInput};

/// Relative step of the differences that give the third partials.
const STEP: f64 = 1e-4;

/// `[i][j]`: `d^(i+j) F / dphi^i dN^j` of a function `F(phi, N)` at one
/// point, for `i + j <= 3` (the other entries 0).
#[derive(Clone, Copy, Debug, Default)]
struct Biv([[f64; 4]; 4]);

/// `C(i, a)` for `i <= 3`.
const BINOMIAL: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [1.0, 1.0, 0.0, 0.0],
    [1.0, 2.0, 1.0, 0.0],
    [1.0, 3.0, 3.0, 1.0],
];

// Leibniz's rule and the shifts index by `i - a`, `j + 1`: the ranges are the
// formulas.
#[allow(clippy::needless_range_loop)]
impl Biv {
    /// A function of `phi` alone from its derivatives of orders 0 to 3.
    fn of_phi(d: [f64; 4]) -> Biv {
        let mut u = Biv::default();
        for (i, x) in d.into_iter().enumerate() {
            u.0[i][0] = x;
        }
        u
    }

    fn add(self, v: Biv) -> Biv {
        let mut w = self;
        for i in 0..4 {
            for j in 0..4 - i {
                w.0[i][j] += v.0[i][j];
            }
        }
        w
    }

    fn scale(self, c: f64) -> Biv {
        let mut w = self;
        for row in &mut w.0 {
            for x in row {
                *x *= c;
            }
        }
        w
    }

    /// Leibniz's rule in both variables.
    fn mul(self, v: Biv) -> Biv {
        let mut w = Biv::default();
        for i in 0..4 {
            for j in 0..4 - i {
                let mut sum = 0.0;
                for a in 0..=i {
                    for b in 0..=j {
                        sum += BINOMIAL[i][a] * BINOMIAL[j][b] * self.0[a][b] * v.0[i - a][j - b];
                    }
                }
                w.0[i][j] = sum;
            }
        }
        w
    }

    /// `dF/dphi` (its order-3 partials unknown, 0).
    fn d_phi(self) -> Biv {
        let mut w = Biv::default();
        for i in 0..3 {
            for j in 0..3 - i {
                w.0[i][j] = self.0[i + 1][j];
            }
        }
        w
    }

    /// `dF/dN` (its order-3 partials unknown, 0).
    fn d_n(self) -> Biv {
        let mut w = Biv::default();
        for i in 0..3 {
            for j in 0..3 - i {
                w.0[i][j] = self.0[i][j + 1];
            }
        }
        w
    }

    /// `F(phi(t), N(t))` as a jet in time from the jets of `phi` and `N`.
    fn compose(&self, p: Jet, n: Jet) -> Jet {
        let u = &self.0;
        [
            u[0][0],
            u[1][0] * p[1] + u[0][1] * n[1],
            u[2][0] * p[1] * p[1]
                + 2.0 * u[1][1] * p[1] * n[1]
                + u[0][2] * n[1] * n[1]
                + u[1][0] * p[2]
                + u[0][1] * n[2],
        ]
    }
}

/// `hW`, `hg` and the inertia `I` of docs/model.md §3 as functions of
/// `(phi, N)`.
struct LoadedGeometry {
    hw: Biv,
    hg: Biv,
    inertia: Biv,
}

impl Simulator {
    /// The output derivatives of a flexible law in motion under the
    /// vertical input `v` (see the module doc); the values (order 0) are
    /// those of [`Simulator::outputs_loaded`] to rounding.
    pub(super) fn loaded_rates_in_motion(
        &self,
        state: &State,
        input: GroundInput,
        v: VerticalInput,
    ) -> OutputRates {
        let m = &self.model;
        let b = &m.body;
        let GroundInput { ag, dag } = input;
        let n_jet = apparent_weight(b, v);
        let n = n_jet[0];
        let s = side_of(state.theta, state.omega, ag);
        let phi = state.theta.abs();
        let (c, daf_dn) = m.contact_loaded(phi, n);
        let k = m.interface.loaded_second_derivatives(&c, n);
        let af = self.af_partials(&c, daf_dn, &k, n);
        let g = self.loaded_geometry(phi, af);
        let pivot = m.formulation == Formulation::ShiftingPivot;
        let ag_jet = [ag, dag, 0.0];

        // theta'' = (-s N hW - m ag hg - (1/2) (dI/dt) omega) / I with
        // dI/dt = s I_phi omega + I_N N' (docs/model.md §6.2), from the jet
        // of theta [theta, omega, theta'', theta''', theta'''']
        let accel = |th: &[f64; 5]| -> Jet {
            let p = [s * th[0], s * th[1], s * th[2]];
            let w = [th[1], th[2], th[3]];
            let mut num = jet_add(
                jet_scale(-s, jet_mul(n_jet, g.hw.compose(p, n_jet))),
                jet_scale(-b.mass, jet_mul(ag_jet, g.hg.compose(p, n_jet))),
            );
            if pivot {
                let di = jet_add(
                    jet_scale(s, jet_mul(g.inertia.d_phi().compose(p, n_jet), w)),
                    jet_scale(n_jet[1], g.inertia.d_n().compose(p, n_jet)),
                );
                num = jet_add(num, jet_scale(-0.5, jet_mul(di, w)));
            }
            jet_div(num, g.inertia.compose(p, n_jet))
        };
        let eom = Eom::with_vertical(self, state.t, GroundInput { ag, dag: 0.0 }, v);
        let th = theta_jet(&eom, state, s, accel);
        let Motion { p, w, w2, thdd } = Motion::of(&th, s);
        let contact_length = if c.a < m.interface.depth() {
            a_partials(&c, &k).compose(p, n_jet)
        } else {
            [c.contact_length, 0.0, 0.0]
        };
        let hw = g.hw.compose(p, n_jet);
        let hg = g.hg.compose(p, n_jet);
        // docs/model.md §5: xG'' = hg theta'' + s hg' omega², zG'' = s hW theta'' + hW' omega²
        let xg_dd = jet_add(
            jet_mul(hg, thdd),
            jet_scale(s, jet_mul(g.hg.d_phi().compose(p, n_jet), w2)),
        );
        let zg_dd = jet_add(
            jet_scale(s, jet_mul(hw, thdd)),
            jet_mul(g.hw.d_phi().compose(p, n_jet), w2),
        );
        OutputRates {
            theta: [th[0], th[1], th[2]],
            omega: w,
            theta_dd: thdd,
            af: af.compose(p, n_jet),
            contact_length,
            mr: jet_mul(n_jet, hw),
            fx: jet_scale(b.mass, jet_add(ag_jet, xg_dd)),
            fz: jet_scale(b.mass, jet_add([b.g + v.av, v.dav, 0.0], zg_dd)),
            apparent_weight: n_jet,
        }
    }

    /// The partials of `af` at the contact `c` solved at `(phi, n)`, whose
    /// `daf/dN` is `daf_dn`.
    fn af_partials(&self, c: &Contact, daf_dn: f64, k: &LoadedCurvature, n: f64) -> Biv {
        let it = &self.model.interface;
        let mut u = Biv::default();
        u.0[0] = [c.af, daf_dn, k.af_nn, 0.0];
        u.0[1][0] = c.daf;
        u.0[1][1] = k.af_pn;
        u.0[2][0] = k.af_pp;
        let phi = c.phi;
        if phi == 0.0 || c.regime == Regime::FullContact {
            // af = D/2 - kn phi Is/N: the only third partials
            u.0[1][2] = -2.0 * k.af_pn / n;
            u.0[0][3] = -3.0 * k.af_nn / n;
            return u;
        }
        let curvature = |phi: f64, n: f64| {
            let (c, _) = self.model.contact_loaded(phi, n);
            it.loaded_second_derivatives(&c, n)
        };
        let (hp, hn) = (STEP * phi, STEP * n);
        let [above_p, below_p] =
            [2.0, -2.0].map(|f| self.threshold_between((phi, n), (phi + f * hp, n)));
        let [above_n, below_n] =
            [2.0, -2.0].map(|f| self.threshold_between((phi, n), (phi, n + f * hn)));
        u.0[3][0] = difference(|x| curvature(x, n).af_pp, phi, hp, above_p, below_p);
        u.0[2][1] = difference(|x| curvature(phi, x).af_pp, n, hn, above_n, below_n);
        u.0[1][2] = difference(|x| curvature(phi, x).af_pn, n, hn, above_n, below_n);
        u.0[0][3] = difference(|x| curvature(phi, x).af_nn, n, hn, above_n, below_n);
        u
    }

    /// Whether a moving threshold (docs/model.md §6.4) lies between two
    /// points `(phi, N)`: one of their margins differs in sign.
    fn threshold_between(&self, (p0, n0): (f64, f64), (p1, n1): (f64, f64)) -> bool {
        let (m0, m1) = (
            self.threshold_margins(p0, n0),
            self.threshold_margins(p1.max(0.0), n1),
        );
        m0.iter().zip(&m1).any(|(a, b)| (*a > 0.0) != (*b > 0.0))
    }

    /// `hW = R0 sin(alpha - phi) - af cos(phi)`, `hg = R0 cos(alpha - phi) -
    /// af sin(phi)`, `I = Ic + m (R0² + af² - 2 R0 af sin(alpha))`
    /// (docs/model.md §3) from the partials of `af`.
    fn loaded_geometry(&self, phi: f64, af: Biv) -> LoadedGeometry {
        let b = &self.model.body;
        let (sp, cp) = crate::trig::sin_cos(phi);
        let sap = b.sin_alpha * cp - b.cos_alpha * sp; // sin(alpha - phi)
        let cap = b.cos_alpha * cp + b.sin_alpha * sp; // cos(alpha - phi)
        let r = b.r0;
        let sin_am = Biv::of_phi([r * sap, -r * cap, -r * sap, r * cap]);
        let cos_am = Biv::of_phi([r * cap, r * sap, -r * cap, -r * sap]);
        let cos_p = Biv::of_phi([cp, -sp, -cp, sp]);
        let sin_p = Biv::of_phi([sp, cp, -sp, -cp]);
        let k = 2.0 * r * b.sin_alpha;
        let mut inertia = af.mul(af).add(af.scale(-k)).scale(b.mass);
        inertia.0[0][0] += b.ic + b.mass * r * r;
        LoadedGeometry {
            hw: sin_am.add(af.mul(cos_p).scale(-1.0)),
            hg: cos_am.add(af.mul(sin_p).scale(-1.0)),
            inertia,
        }
    }
}

/// The partials of `a` up to order 2 at the contact `c` whose second
/// partials are `k`.
fn a_partials(c: &Contact, k: &LoadedCurvature) -> Biv {
    let mut u = Biv::default();
    u.0[0] = [c.a, k.a_n, k.a_nn, 0.0];
    u.0[1][0] = c.da;
    u.0[1][1] = k.a_pn;
    u.0[2][0] = k.a_pp;
    u
}

/// `g'(x)` by a difference of step `h`: central, or on the side away from
/// a kink `above` or `below` `x` within `2 h` (central if both).
fn difference(g: impl Fn(f64) -> f64, x: f64, h: f64, above: bool, below: bool) -> f64 {
    match (above, below) {
        (true, false) => (3.0 * g(x) - 4.0 * g(x - h) + g(x - 2.0 * h)) / (2.0 * h),
        (false, true) => (-3.0 * g(x) + 4.0 * g(x + h) - g(x + 2.0 * h)) / (2.0 * h),
        _ => (g(x + h) - g(x - h)) / (2.0 * h),
    }
}
