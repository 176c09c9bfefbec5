//! Model Exchange's velocity state `omegaW` for `shiftingPivot` on a
//! flexible bed (docs/model.md §11.5): `omega` referred to the inertia at
//! the weight, so that its rate needs the tilt and `N = m (g + av)` but no
//! `dN/dt`, which a Model Exchange host does not give.
//!
//! In the frame `e1` (toward the lean, in the base's plane), `e2` (across
//! it), `e3` (the body's axis), the inertia about the resultant is
//! `J = [[P, 0, Q], [0, J22, 0], [Q, 0, S]]` with `P = A + m hG²`,
//! `Q = m rho hG`, `S = C + m rho²`, `J22 = A + m (hG² + rho²)` (`A`, `C`
//! the central moments across and about the axis), and the equation's
//! `dN/dt` term is `J omega' = -(d rho/dN)(dN/dt) K omega + ...`,
//! `K = m [[0, 0, hG], [0, rho, 0], [0, 0, rho]]` (from
//! `-m r x (omega x dr/dt)`). `M(rho) = [[1, 0, Q/P], [0, sqrt(J22), 0],
//! [0, 0, sqrt(D)]]`, `D = P S - Q² = P C + m A rho²`, satisfies
//! `dM/drho = M J^-1 K`, so `M omega` has a rate free of `dN/dt`
//! (`d(M omega)/dt`'s `dN/dt` part is `(dM/drho - M J^-1 K) omega (d rho/dN)
//! dN/dt`); `omegaW = M(rho_W)^-1 M(rho) omega` with
//! `rho_W = rho(theta, W)` is that state normalised to `omega` at `N = W`:
//!
//! `omegaW = omega + c13 w3 e1 + (k2 - 1) w2 e2 + (k3 - 1) w3 e3`,
//!
//! `wi = ei . omega`, `k2 = sqrt(J22/J22_W)`, `k3 = sqrt(D/D_W)`,
//! `c13 = m hG (rho - k3 rho_W)/P`. Everything is written with
//! `e2 e2^T = 1 - e1 e1^T - e3 e3^T` and with `c13 = a sin(theta)`,
//! `k2 - 1 = beta sin²(theta)` (`a`, `beta` finite at upright, from the
//! resultant's `q = rho/sin(theta)`), so the transform and its rate are
//! smooth through upright, where `e1` is the contact side's.

use nalgebra::Vector3;

use crate::model::Formulation;
use crate::spatial::{Spatial, SpatialState};

/// The transform between `omega` and `omegaW` at one tilt and apparent
/// weight, and what its rate along the tilt needs.
struct Referral {
    /// The body's axis.
    e3: Vector3<f64>,
    /// Toward the lean in the base's plane, `(cos(theta) u, -sin(theta))`.
    e1: Vector3<f64>,
    /// The lean's direction `u` (the contact side at upright).
    u: [f64; 2],
    /// `sin(theta)`, `cos(theta)`.
    s: f64,
    c: f64,
    m: f64,
    hg: f64,
    /// `A`, `P = A + m hG²`, kg m².
    a_moment: f64,
    p: f64,
    /// `rho`, `d rho/d theta` at `N` and at `W`, m and m/rad.
    rho: f64,
    drho: f64,
    rho_w: f64,
    drho_w: f64,
    /// `J22`, `D` at `N` and at `W`.
    j22: f64,
    j22_w: f64,
    d: f64,
    d_w: f64,
    k2: f64,
    k3: f64,
    /// `c13 / sin(theta)`, 1.
    a: f64,
    /// `(k2 - 1)/sin²(theta)`, 1.
    beta: f64,
}

impl Referral {
    fn c13(&self) -> f64 {
        self.a * self.s
    }

    fn kappa(&self) -> f64 {
        self.beta * self.s * self.s
    }

    /// `omegaW` from `omega`:
    /// `k2 omega + (k3 - k2) w3 e3 + (c13 w3 - (k2 - 1) w1) e1`.
    fn referred(&self, omega: &Vector3<f64>) -> Vector3<f64> {
        let w1 = self.e1.dot(omega);
        let w3 = self.e3.dot(omega);
        self.k2 * omega
            + (self.k3 - self.k2) * w3 * self.e3
            + (self.c13() * w3 - self.kappa() * w1) * self.e1
    }

    /// `omega` from `omegaW` (the inverse of [`referred`](Self::referred)):
    /// `omegaW/k2 + (1/k3 - 1/k2) v3 e3 + ((k2 - 1) v1/k2 - c13 v3/k3) e1`,
    /// `vi = ei . omegaW`.
    fn omega_of(&self, w: &Vector3<f64>) -> Vector3<f64> {
        let v1 = self.e1.dot(w);
        let v3 = self.e3.dot(w);
        w / self.k2
            + (1.0 / self.k3 - 1.0 / self.k2) * v3 * self.e3
            + (self.kappa() * v1 / self.k2 - self.c13() * v3 / self.k3) * self.e1
    }

    /// `d omegaW/dt` given `omega` and its rate `domega0` at `dN/dt = 0`:
    /// `T domega0` plus the rate of `T` along the tilt at fixed `N`
    /// (`T omega = omegaW`); the `dN/dt` parts of `T` and of `omega'`
    /// cancel (the module doc).
    fn rate(&self, omega: &Vector3<f64>, domega0: &Vector3<f64>) -> Vector3<f64> {
        let (s, c, m) = (self.s, self.c, self.m);
        let e3 = self.e3;
        let e1 = self.e1;
        let de3 = omega.cross(&e3);
        let ds = self.u[0] * de3.x + self.u[1] * de3.y;
        let dtheta = ds / c;
        // the lean turning: sin(theta) du/dt
        let perp = Vector3::new(de3.x - ds * self.u[0], de3.y - ds * self.u[1], 0.0);
        let (rho_t, rho_w_t) = (self.drho * dtheta, self.drho_w * dtheta);
        let k2_t = self.k2 * m * (self.rho * rho_t / self.j22 - self.rho_w * rho_w_t / self.j22_w);
        let k3_t = self.k3
            * m
            * self.a_moment
            * (self.rho * rho_t / self.d - self.rho_w * rho_w_t / self.d_w);
        let c13_t = m * self.hg * (rho_t - self.k3 * rho_w_t - self.rho_w * k3_t) / self.p;
        let (kappa, c13) = (self.kappa(), self.c13());
        let w1 = e1.dot(omega);
        let w3 = e3.dot(omega);
        // d(c13 e1)/dt, with de1/dt = -theta' e3 + cos(theta) du/dt
        let dc13e1 = c13_t * e1 - c13 * dtheta * e3 + self.a * c * perp;
        // d((k2 - 1) w1 e1)/dt at fixed omega
        let dkappa = k2_t * w1 * e1
            + (-kappa * dtheta * w3 + c * self.beta * s * perp.dot(omega)) * e1
            + w1 * (-kappa * dtheta * e3 + c * self.beta * s * perp);
        // w3's rate at fixed omega is omega . (omega x e3) = 0
        self.referred(domega0)
            + k2_t * omega
            + (k3_t - k2_t) * w3 * e3
            + (self.k3 - self.k2) * w3 * de3
            + w3 * dc13e1
            - dkappa
    }
}

impl Spatial {
    /// Whether Model Exchange's velocity state `omegaW` can differ from
    /// `omega`: `shiftingPivot` on a flexible bed (docs/model.md §11.5).
    /// Elsewhere `omegaW` is `omega`, bit for bit: `costa` has no `dN/dt`
    /// in its rates, the rigid bed no `N` in its lever.
    pub fn weight_referred(&self) -> bool {
        self.flexible() && self.model.formulation == Formulation::ShiftingPivot
    }

    /// The transform at the tilt `e` (`pivot` the side at upright) under
    /// `av` (m/s²); `None` where it is the identity (see
    /// [`weight_referred`](Self::weight_referred); and `N = W`, `av = 0`).
    fn referral(&self, e: [f64; 2], pivot: [f64; 2], av: f64) -> Option<Referral> {
        let body = &self.model.body;
        let n = body.weight + self.mass() * av;
        if !self.weight_referred() || n == body.weight {
            return None;
        }
        let (m, hg, a_moment, c_moment) = (self.mass(), body.hg, body.ic, self.c_axial);
        let s2 = e[0] * e[0] + e[1] * e[1];
        let s = s2.sqrt();
        let c = (1.0 - s2).sqrt();
        let theta = s.asin();
        let u = if s > 0.0 { [e[0] / s, e[1] / s] } else { pivot };
        let at = |n: f64| {
            let r = self.resultant(theta, n);
            // rho / sin(theta), finite at upright (theta / sin(theta) -> 1)
            let q = if s > 0.0 {
                r.secant * theta / s
            } else {
                r.secant
            };
            (r, q)
        };
        let (res, q) = at(n);
        let (res_w, q_w) = at(body.weight);
        let p = a_moment + m * hg * hg;
        let j22 = p + m * res.rho * res.rho;
        let j22_w = p + m * res_w.rho * res_w.rho;
        let d = p * c_moment + m * a_moment * res.rho * res.rho;
        let d_w = p * c_moment + m * a_moment * res_w.rho * res_w.rho;
        let k2 = (j22 / j22_w).sqrt();
        let k3 = (d / d_w).sqrt();
        Some(Referral {
            e3: Vector3::new(e[0], e[1], c),
            e1: Vector3::new(c * u[0], c * u[1], -s),
            u,
            s,
            c,
            m,
            hg,
            a_moment,
            p,
            rho: res.rho,
            drho: res.drho,
            rho_w: res_w.rho,
            drho_w: res_w.drho,
            j22,
            j22_w,
            d,
            d_w,
            k2,
            k3,
            a: m * hg * (q - k3 * q_w) / p,
            // k2 - 1 = (J22 - J22_W)/(J22_W (k2 + 1)), J22 - J22_W = m s² (q² - q_W²)
            beta: m * (q * q - q_w * q_w) / (j22_w * (k2 + 1.0)),
        })
    }

    /// `st` (its `omega` the angular velocity) with Model Exchange's state
    /// `omegaW` in place of `omega` under `av` (m/s²): the same numbers
    /// where [`weight_referred`](Self::weight_referred) is false or `av = 0`.
    pub fn to_weight_referred(&self, mut st: SpatialState, av: f64) -> SpatialState {
        if let Some(t) = self.referral(st.e, st.pivot, av) {
            st.omega = t.referred(&Vector3::from(st.omega)).into();
        }
        st
    }

    /// `st`, whose `omega` holds Model Exchange's `omegaW`, with the angular
    /// velocity there instead, under `av` (m/s²) (the inverse of
    /// [`to_weight_referred`](Self::to_weight_referred)).
    pub fn from_weight_referred(&self, mut st: SpatialState, av: f64) -> SpatialState {
        if let Some(t) = self.referral(st.e, st.pivot, av) {
            st.omega = t.omega_of(&Vector3::from(st.omega)).into();
        }
        st
    }

    /// Model Exchange's right-hand side: `d/dt (ex, ey, omegaW, xG, yG)` at
    /// `sw` (whose `omega` holds `omegaW`) under `ag`, `av` (m/s²), exact for
    /// any `av(t)` with no derivative of it (docs/model.md §11.5). Where
    /// `omegaW` is `omega` ([`to_weight_referred`](Self::to_weight_referred))
    /// this is [`derivatives`](Self::derivatives), bit for bit.
    pub fn derivatives_weight_referred(
        &self,
        sw: &SpatialState,
        ag: [f64; 2],
        av: f64,
    ) -> [f64; super::STATES] {
        let Some(t) = self.referral(sw.e, sw.pivot, av) else {
            return self.derivatives(sw, ag, av);
        };
        let mut st = *sw;
        let omega = t.omega_of(&Vector3::from(sw.omega));
        st.omega = omega.into();
        let mut dy = self.derivatives(&st, ag, av);
        if st.at_rest || st.overturned || st.out_of_range {
            return dy;
        }
        let dw = t.rate(&omega, &Vector3::new(dy[2], dy[3], dy[4]));
        dy[2..5].copy_from_slice(dw.as_slice());
        dy
    }
}
