//! The equations of motion of a round body rolling on its rim without slip
//! on a rigid bed (docs/model.md §10.2).
//!
//! With `r = G - P` from the contact to the centre of mass, no slip gives
//! `vG = omega x r`, and the balance of angular momentum about the contact
//! (Newton's law for the centre of mass eliminating the contact force) is
//!
//! `J omega' = m r x g_eff - omega x (IG omega) - m r x (omega x (Omega x r))`
//!
//! with `J = IG + m (|r|² 1 - r r^T)` the inertia about the contact,
//! `IG = A 1 + (C - A) e3 e3^T`, `g_eff = (-agx, -agy, -(g + av))` the
//! gravity and the ground's inertia force per unit mass, and `Omega` the
//! frame's rate (`dr/dt = Omega x r`, see [`Frame::frame_rate`]).
//!
//! On a flexible bed (docs/model.md §11.2) the same balance is taken about
//! the bed's resultant `P`, which carries the whole reaction: `r` and
//! `dr/dt` are `pivot`'s.

use nalgebra::{Matrix3, Vector3};

use super::frame::Frame;
use super::pivot::Memo;
use super::{PlanInput, Spatial};
use crate::dynamics::VerticalInput;

/// Dimension of the state `y = (ex, ey, omega_x, omega_y, omega_z, xG, yG)`:
/// the tilt (the axis's horizontal part), the angular velocity (rad/s) and
/// the centre of mass's horizontal position (m), all in the ground's axes.
pub(crate) const N: usize = 7;

/// The right-hand side under the inputs of one call.
#[derive(Clone, Debug)]
pub(crate) struct Eom<'a> {
    pub body: &'a Spatial,
    t0: f64,
    input: PlanInput,
    vertical: VerticalInput,
    /// The bed's resultants asked for during the call
    /// ([`Spatial::resultant_near`]).
    pub memo: Memo,
}

/// Rates and the contact's force at one point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rates {
    /// `dy/dt`.
    pub dy: [f64; N],
    /// The force of the bed on the body, N.
    pub force: Vector3<f64>,
}

impl<'a> Eom<'a> {
    pub fn new(body: &'a Spatial, t0: f64, input: PlanInput, vertical: VerticalInput) -> Eom<'a> {
        Eom {
            body,
            t0,
            input,
            vertical,
            memo: Memo::default(),
        }
    }

    /// Horizontal ground acceleration at `t`, m/s².
    #[inline]
    pub fn ag(&self, t: f64) -> [f64; 2] {
        let dt = t - self.t0;
        [
            self.input.a[0] + self.input.da[0] * dt,
            self.input.a[1] + self.input.da[1] * dt,
        ]
    }

    /// No ground motion over the call, horizontal or vertical.
    pub fn quiet(&self) -> bool {
        self.input == PlanInput::default() && self.vertical == VerticalInput::default()
    }

    /// Vertical ground acceleration at `t`, m/s².
    #[inline]
    pub fn av(&self, t: f64) -> f64 {
        self.vertical.av + self.vertical.dav * (t - self.t0)
    }

    /// `dy/dt` at `(t, y)` with the contact on the side of `d0`.
    #[inline]
    pub fn rates(&self, t: f64, y: &[f64; N], d0: [f64; 2]) -> [f64; N] {
        self.rates_and_force(t, y, d0).dy
    }

    /// `dy/dt` and the bed's force at `(t, y)`.
    pub fn rates_and_force(&self, t: f64, y: &[f64; N], d0: [f64; 2]) -> Rates {
        let b = self.body;
        let (m, radius, hg) = (b.mass(), b.radius, b.model.body.hg);
        let omega = Vector3::new(y[2], y[3], y[4]);
        let (e3, r, rdot) = if b.flexible() {
            // docs/model.md §11.2: about the bed's resultant
            let n = b.model.body.weight + m * self.av(t);
            let dn = m * self.vertical.dav;
            let l = b.lever_near([y[0], y[1]], &omega, (n, dn), d0, &self.memo);
            (l.e3, l.r, l.rdot)
        } else {
            let f = Frame::at([y[0], y[1]], d0, radius, hg);
            let de3 = omega.cross(&f.e3);
            let big_omega = f.frame_rate(&omega, [de3.x, de3.y]);
            (f.e3, f.r, big_omega.cross(&f.r))
        };
        let de3 = omega.cross(&e3);
        let (a, c) = (b.model.body.ic, b.c_axial);
        let ig = Matrix3::identity() * a + (c - a) * e3 * e3.transpose();
        let j = ig + m * (Matrix3::identity() * r.norm_squared() - r * r.transpose());
        let ag = self.ag(t);
        let g_eff = Vector3::new(-ag[0], -ag[1], -(b.model.body.g + self.av(t)));
        // the centripetal part of the centre of mass's acceleration, omega x dr/dt
        let a_omega = omega.cross(&rdot);
        let rhs = m * r.cross(&g_eff) - omega.cross(&(ig * omega)) - m * r.cross(&a_omega);
        let domega = match j.cholesky() {
            Some(ch) => ch.solve(&rhs),
            None => Vector3::repeat(f64::NAN),
        };
        let vg = omega.cross(&r);
        let a_g = domega.cross(&r) + a_omega;
        Rates {
            dy: [de3.x, de3.y, domega.x, domega.y, domega.z, vg.x, vg.y],
            force: m * (a_g - g_eff),
        }
    }
}
