//! RODAS, the L-stable, stiffly accurate Rosenbrock method of order 4(3)
//! (Hairer & Wanner, *Solving ODEs II*, §IV.7, code `rodas.f`), for the
//! stiff phases of a flexible interface: a stiff interface (large `kn`)
//! oscillates in full contact at `omega_n ~ sqrt(kn Is / I)`, and an explicit
//! method would be held at `h ~ 1/omega_n` by stability whatever the
//! tolerance.
//!
//! The Jacobian `J = [[0, 1], [da/dtheta, da/domega]]` (`a = theta''`) is
//! formed by differences at the start of each step; `da/dt` likewise (it is
//! exact: `a` is affine in the ground acceleration, which is linear in `t`).
//! Each stage solves the 2x2 system `(I/(h gamma) - J) u = rhs` directly.

use super::eom::Eom;
use super::erk::{StepOut, Tol};

const GAMMA: f64 = 0.25;
const C2: f64 = 0.386;
const C3: f64 = 0.21;
const C4: f64 = 0.63;
const D1: f64 = 0.25;
const D2: f64 = -0.1043;
const D3: f64 = 0.1035;
const D4: f64 = -0.0362;

const A21: f64 = 1.544;
const A31: f64 = 0.9466785280815826;
const A32: f64 = 0.2557011698983284;
const A41: f64 = 3.314825187068521;
const A42: f64 = 2.896124015972201;
const A43: f64 = 0.9986419139977817;
const A51: f64 = 1.221224509226641;
const A52: f64 = 6.019134481288629;
const A53: f64 = 12.53708332932087;
const A54: f64 = -0.687886036105895;

const C21: f64 = -5.6688;
const C31: f64 = -2.430093356833875;
const C32: f64 = -0.2063599157091915;
const C41: f64 = -0.1073529058151375;
const C42: f64 = -9.594562251023355;
const C43: f64 = -20.47028614809616;
const C51: f64 = 7.496443313967647;
const C52: f64 = -10.24680431464352;
const C53: f64 = -33.99990352819905;
const C54: f64 = 11.7089089320616;
const C61: f64 = 8.083246795921522;
const C62: f64 = -7.981132988064893;
const C63: f64 = -31.52159432874371;
const C64: f64 = 16.31930543123136;
const C65: f64 = -6.058818238834054;

/// Order of the error estimate's leading term: `err ~ h^4`.
pub(crate) const ERR_EXP: f64 = -1.0 / 4.0;
/// Right-hand-side evaluations of a step: 5 stages, 3 for the Jacobian and
/// `da/dt`, 1 for `a(y1)`.
pub(crate) const EVALS: u32 = 9;

/// The linearisation at the start of a step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Jac {
    /// `d theta'' / d theta`, 1/s².
    pub a_theta: f64,
    /// `d theta'' / d omega`, 1/s.
    pub a_omega: f64,
    /// `d theta'' / d t`, rad/s³.
    pub a_t: f64,
}

impl Jac {
    /// Spectral radius of `J`: the largest `|lambda|` with
    /// `lambda² - a_omega lambda - a_theta = 0`, bounded above.
    pub fn rho(&self) -> f64 {
        self.a_omega.abs() + self.a_theta.abs().sqrt()
    }
}

/// Differences for the Jacobian at `(t, y0)` where `theta'' = a0`, over a
/// time scale `h`. `theta_scale` sets the increment of `theta`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn jacobian(
    eom: &Eom,
    t: f64,
    h: f64,
    y0: [f64; 2],
    a0: f64,
    side: f64,
    hint: &mut f64,
    theta_scale: f64,
    omega_scale: f64,
) -> Jac {
    let sq = f64::EPSILON.sqrt();
    // theta increment away from 0 (the side does not change)
    let dth = sq * y0[0].abs().max(theta_scale);
    let dth = if y0[0] < 0.0 || (y0[0] == 0.0 && side < 0.0) {
        -dth
    } else {
        dth
    };
    let mut hh = *hint;
    let a_th = eom.accel(t, y0[0] + dth, y0[1], side, &mut hh);
    let dom = sq * y0[1].abs().max(omega_scale);
    let a_om = eom.accel(t, y0[0], y0[1] + dom, side, &mut hh);
    let a_tt = eom.accel(t + h, y0[0], y0[1], side, &mut hh);
    Jac {
        a_theta: (a_th - a0) / dth,
        a_omega: (a_om - a0) / dom,
        a_t: (a_tt - a0) / h,
    }
}

/// One RODAS step from `(t, y0)`, `theta''(t, y0) = a0`, with Jacobian `j`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn step(
    eom: &Eom,
    t: f64,
    h: f64,
    y0: [f64; 2],
    a0: f64,
    j: &Jac,
    side: f64,
    hint: &mut f64,
    tol: &Tol,
) -> StepOut {
    // E = I/(h gamma) - J = [[f, -1], [-a_theta, f - a_omega]]
    let f = 1.0 / (h * GAMMA);
    let e11 = f;
    let e12 = -1.0;
    let e21 = -j.a_theta;
    let e22 = f - j.a_omega;
    let det = e11 * e22 - e12 * e21;
    let solve = |r: [f64; 2]| -> [f64; 2] {
        [
            (e22 * r[0] - e12 * r[1]) / det,
            (e11 * r[1] - e21 * r[0]) / det,
        ]
    };
    let fx = j.a_t; // d/dt of (omega, theta'') = (0, a_t)
    let rhs = |y: [f64; 2], tt: f64, hint: &mut f64| -> [f64; 2] {
        [y[1], eom.accel(tt, y[0], y[1], side, hint)]
    };
    let comb = |c: &[(f64, [f64; 2])]| -> [f64; 2] {
        let mut s = [0.0; 2];
        for (k, u) in c {
            s[0] += k * u[0];
            s[1] += k * u[1];
        }
        s
    };
    let add = |a: [f64; 2], b: [f64; 2]| [a[0] + b[0], a[1] + b[1]];
    let hi = 1.0 / h;

    let u1 = solve([y0[1], a0 + h * D1 * fx]);

    let y2 = add(y0, comb(&[(A21, u1)]));
    let f2 = rhs(y2, t + C2 * h, hint);
    let u2 = solve(add(f2, add(comb(&[(C21 * hi, u1)]), [0.0, h * D2 * fx])));

    let y3 = add(y0, comb(&[(A31, u1), (A32, u2)]));
    let f3 = rhs(y3, t + C3 * h, hint);
    let u3 = solve(add(
        f3,
        add(comb(&[(C31 * hi, u1), (C32 * hi, u2)]), [0.0, h * D3 * fx]),
    ));

    let y4 = add(y0, comb(&[(A41, u1), (A42, u2), (A43, u3)]));
    let f4 = rhs(y4, t + C4 * h, hint);
    let u4 = solve(add(
        f4,
        add(
            comb(&[(C41 * hi, u1), (C42 * hi, u2), (C43 * hi, u3)]),
            [0.0, h * D4 * fx],
        ),
    ));

    let y5 = add(y0, comb(&[(A51, u1), (A52, u2), (A53, u3), (A54, u4)]));
    let f5 = rhs(y5, t + h, hint);
    let u5 = solve(add(
        f5,
        comb(&[
            (C51 * hi, u1),
            (C52 * hi, u2),
            (C53 * hi, u3),
            (C54 * hi, u4),
        ]),
    ));

    // embedded (order 3) solution, then the last stage is the correction
    let y6 = add(y5, u5);
    let f6 = rhs(y6, t + h, hint);
    let u6 = solve(add(
        f6,
        comb(&[
            (C61 * hi, u1),
            (C62 * hi, u2),
            (C63 * hi, u3),
            (C64 * hi, u4),
            (C65 * hi, u5),
        ]),
    ));
    let y1 = add(y6, u6);
    let a1 = eom.accel(t + h, y1[0], y1[1], side, hint);
    let sc = tol.scales(y0, y1);
    let e0 = u6[0] / sc[0];
    let e1 = u6[1] / sc[1];
    StepOut {
        y: y1,
        accel: a1,
        err: (0.5 * (e0 * e0 + e1 * e1)).sqrt(),
        rho: j.rho(),
    }
}
