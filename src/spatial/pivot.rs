//! Where the flexible bed's resultant acts under the tilted round body and
//! how it moves (docs/model.md §11.2): the lever `r = G - P` from the
//! resultant `P` to the centre of mass, and its rate `dr/dt`.
//!
//! The reaction at the tilt `theta` under the apparent weight `N` is the
//! planar contact along the lean (docs/model.md §11.1): `P` lies on the
//! base's line toward the lean, `rho = R - af(theta, N)` from the base's
//! centre. The body turns about the material point at `P` (no slip there,
//! the planar kinematics of docs/model.md §3), so `vG = omega x r`.
//!
//! Near upright `rho = (kn Is/N) theta` (elastic full contact, the heel
//! closed), so `P` passes through the centre smoothly: every quantity here
//! is written with `q = rho / sin(theta)`, finite at upright, and the
//! direction of the lean `u = e/|e|` enters only where `rho` multiplies it.

use std::cell::Cell;

use nalgebra::Vector3;

use super::Spatial;
use crate::interface::{Law, Regime};
use crate::model::Formulation;

/// The resultant's distance from the base's centre and its derivatives at
/// one tilt and apparent weight.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Resultant {
    /// `rho = R - af`, m.
    pub rho: f64,
    /// `rho / theta`, m/rad: `kn Is / N` in elastic full contact (exact,
    /// also at `theta = 0`, where `rho` loses its digits to `R - af`).
    pub secant: f64,
    /// `d rho/d theta = -af'` at fixed `N`, m/rad.
    pub drho: f64,
    /// `d rho/d N = -d af/d N` at fixed `theta`, m/N (docs/model.md §6.1).
    pub drho_dn: f64,
    /// The heel is closed (`a >= D`): full contact, crushed or not.
    pub heel_closed: bool,
    /// The contact's edge `a` (docs/model.md §2), m: infinite at upright.
    pub edge: f64,
}

/// Where the next solve at the apparent weight starts: the last one's
/// edge `a` (m) at `theta` (rad) and `da/dtheta` (m/rad) at its `N`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hint {
    theta: f64,
    a: f64,
    da: f64,
}

impl Default for Hint {
    fn default() -> Hint {
        Hint {
            theta: f64::NAN,
            a: f64::NAN,
            da: f64::NAN,
        }
    }
}

impl Hint {
    /// The start at `theta` (rad), m: NaN for none.
    fn at(&self, theta: f64) -> f64 {
        self.a + self.da * (theta - self.theta)
    }
}

/// The resultants one run of evaluations has asked for
/// ([`Spatial::resultant_near`]): the last answer and where the next solve
/// starts. Not shared between calls of `advance`.
#[derive(Clone, Debug, Default)]
pub(crate) struct Memo {
    /// `(theta, N, answer)`.
    last: Cell<Option<(f64, f64, Resultant)>>,
    hint: Cell<Hint>,
}

/// The lever of one state.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lever {
    /// The body's axis, unit.
    pub e3: Vector3<f64>,
    /// `G - P`, m.
    pub r: Vector3<f64>,
    /// `dr/dt` as the equation of motion takes it, m/s: the whole rate for
    /// `shiftingPivot`; `costa` leaves out the resultant sliding along the
    /// base (`d rho/dt`), as the planar `costa` leaves out `dI/dphi`.
    pub rdot: Vector3<f64>,
}

impl Spatial {
    /// The resultant at the tilt `theta` (rad) under the apparent weight `n`
    /// (N): the planar contact of docs/model.md §2 and §6.1. Where the toe
    /// has not crushed at N the bed is elastic and the contact is the one
    /// at the weight at `theta W/N` (the planar simulator's, from its table
    /// where it answers), with `daf/dN = -(theta/N) daf/dtheta`; elsewhere it
    /// is solved at N ([`crate::interface::Interface::contact_loaded`]), as
    /// the planar equation of motion does.
    pub(crate) fn resultant(&self, theta: f64, n: f64) -> Resultant {
        self.resultant_near(theta, n, &Memo::default())
    }

    /// [`resultant`](Self::resultant) remembered in `memo`: the last
    /// answer again at the same `(theta, n)` (a step's end, where the
    /// events are checked, is the next step's start), else a solve at N
    /// that starts from the last one's `a` extrapolated along `da/dtheta`:
    /// the same answer to the solve's tolerance (a rotated run's response
    /// the turned one's to 5e-13, `tests/spatial_flexible.rs`) in two or
    /// three evaluations of the bed's resultants instead of five to eight.
    pub(crate) fn resultant_near(&self, theta: f64, n: f64, memo: &Memo) -> Resultant {
        if let Some((t, w, res)) = memo.last.get() {
            if t == theta && w == n {
                return res;
            }
        }
        let res = self.resultant_from(theta, n, &memo.hint);
        memo.last.set(Some((theta, n, res)));
        res
    }

    fn resultant_from(&self, theta: f64, n: f64, hint: &Cell<Hint>) -> Resultant {
        let m = &self.model;
        let ratio = m.body.weight / n;
        let scaled = self.planar.contact(theta * ratio, f64::NAN);
        let uncrushed = match m.interface.law() {
            Law::ElastoPlastic { kn, fm } => {
                matches!(scaled.regime, Regime::FullContact | Regime::Partial)
                    && kn * theta * scaled.a <= fm
            }
            _ => true,
        };
        let (c, daf_dn) = if n <= 0.0 {
            // the liftOff instant that ends a run (docs/model.md §6.5)
            m.contact_loaded(theta, n)
        } else if uncrushed {
            let daf = scaled.daf * ratio;
            let c = crate::interface::Contact { daf, ..scaled };
            (c, -theta / n * daf)
        } else {
            let (c, xel) = m.interface.contact_loaded(theta, n, hint.get().at(theta));
            if c.a.is_finite() && c.da.is_finite() {
                hint.set(Hint {
                    theta,
                    a: c.a,
                    da: c.da,
                });
            }
            (c, (xel - c.af) / n)
        };
        let secant = match (c.regime, m.interface.law()) {
            (Regime::FullContact, Law::Elastic { kn } | Law::ElastoPlastic { kn, .. }) => {
                kn * m.interface.shape().second_moment() / n
            }
            _ => (self.radius - c.af) / theta,
        };
        Resultant {
            rho: secant * theta,
            secant,
            drho: -c.daf,
            drho_dn: -daf_dn,
            heel_closed: matches!(c.regime, Regime::FullContact | Regime::FullCrushing),
            edge: c.a,
        }
    }

    /// The lever at the tilt `e` moving with `omega` (rad/s) under the
    /// apparent weight `n` (N) changing at `dn` (N/s); `d0` (unit) is the
    /// lean's direction used at exactly zero tilt, where only `costa`'s
    /// truncated rate depends on it (docs/model.md §11.2).
    pub(crate) fn lever(
        &self,
        e: [f64; 2],
        omega: &Vector3<f64>,
        (n, dn): (f64, f64),
        d0: [f64; 2],
    ) -> Lever {
        self.lever_near(e, omega, (n, dn), d0, &Memo::default())
    }

    /// [`lever`](Self::lever) with the resultant of
    /// [`resultant_near`](Self::resultant_near) in `memo`.
    pub(crate) fn lever_near(
        &self,
        e: [f64; 2],
        omega: &Vector3<f64>,
        (n, dn): (f64, f64),
        d0: [f64; 2],
        memo: &Memo,
    ) -> Lever {
        let hg = self.model.body.hg;
        let s2 = e[0] * e[0] + e[1] * e[1];
        let s = s2.sqrt();
        let c = (1.0 - s2).sqrt();
        let theta = s.asin();
        let res = self.resultant_near(theta, n, memo);
        // theta / sin(theta) -> 1 at upright
        let q = if s > 0.0 {
            res.secant * theta / s
        } else {
            res.secant
        };
        let e3 = Vector3::new(e[0], e[1], c);
        // P - centre = rho e1, e1 = (cos(theta) u, -sin(theta)), u = e/|e|
        let p = Vector3::new(q * c * e[0], q * c * e[1], -q * s2);
        let r = hg * e3 - p;
        // de3/dt = omega x e3; the lean's rates from its horizontal part
        let de3 = omega.cross(&e3);
        let u = if s > 0.0 { [e[0] / s, e[1] / s] } else { d0 };
        let ds = u[0] * de3.x + u[1] * de3.y;
        let dtheta = ds / c;
        // de/dt across u: the lean turning, rho du/dt = q (de/dt)_perp
        let perp = Vector3::new(de3.x - ds * u[0], de3.y - ds * u[1], 0.0);
        let e1 = Vector3::new(c * u[0], c * u[1], -s);
        // rho de1/dt = rho (-theta' e3 + cos(theta) du/dt)
        let mut dp = -res.rho * dtheta * e3 + c * q * perp;
        if self.model.formulation == Formulation::ShiftingPivot {
            // the resultant sliding along the base: d rho/dt e1
            dp += (res.drho * dtheta + res.drho_dn * dn) * e1;
        }
        Lever {
            e3,
            r,
            rdot: hg * de3 - dp,
        }
    }
}

/// Gauss-Legendre nodes and weights of 5 points on `[-1, 1]`.
const GAUSS5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// Panels per smooth piece of the quadrature in [`Spatial::lean`].
const PANELS: usize = 64;

impl Spatial {
    /// How far the centre of mass has moved from upright rest when the body
    /// is tilted by `theta` (rad) in a vertical plane about its resultant at
    /// the weight: `(x, z)` = `(∫ hg, ∫ hW)` over `[0, theta]`, m, with
    /// `hg = hG cos(phi) + rho sin(phi)` and `hW = rho cos(phi) - hG sin(phi)`
    /// (docs/model.md §3: `xG' = hg omega`, `zG' = hW omega`). By Gauss-Legendre
    /// quadrature on pieces split at `thetaJo` and `thetaC`, where `af` has
    /// kinks; other kinks (a ring's inner edge) are left inside a piece.
    pub(crate) fn lean(&self, theta: f64) -> (f64, f64) {
        let it = &self.model.interface;
        let w = self.model.body.weight;
        let hg = self.model.body.hg;
        let mut breaks = [0.0, it.theta_jo(), it.theta_c(), theta];
        breaks[1] = breaks[1].min(theta);
        breaks[2] = breaks[2].clamp(breaks[1], theta);
        let (mut x, mut z) = (0.0, 0.0);
        for piece in breaks.windows(2) {
            let span = piece[1] - piece[0];
            if span <= 0.0 {
                continue;
            }
            // phi = start + span u², u in [0, 1]: past a threshold af
            // grows like a power of (phi - start) (the circle's width is a
            // square root at its edges), which the substitution smooths
            let h = 1.0 / PANELS as f64;
            for k in 0..PANELS {
                let mid = (k as f64 + 0.5) * h;
                for (node, weight) in GAUSS5 {
                    let u = mid + 0.5 * h * node;
                    let phi = piece[0] + span * u * u;
                    let dphi = 0.5 * h * weight * 2.0 * span * u;
                    let rho = self.resultant(phi, w).rho;
                    let (s, c) = phi.sin_cos();
                    x += dphi * (hg * c + rho * s);
                    z += dphi * (rho * c - hg * s);
                }
            }
        }
        (x, z)
    }
}
