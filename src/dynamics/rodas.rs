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

use super::erk::{Start, StepOut, Tol};

const GAMMA: f64 = 0.25;
/// The stage times `c_i` of stages 1..5 (stage 6 at `c = 1` too).
const NODES: [f64; 5] = [0.0, 0.386, 0.21, 0.63, 1.0];
/// `gamma_i`, the weights of `df/dt` in stages 1..4 (0 in stages 5, 6).
const D: [f64; 4] = [0.25, -0.1043, 0.1035, -0.0362];

/// `a_ij`: stage `i` is evaluated at `y0 + sum_j a_ij u_j`.
const A: [[f64; 4]; 5] = [
    [0.0; 4],
    [1.544, 0.0, 0.0, 0.0],
    [0.9466785280815826, 0.2557011698983284, 0.0, 0.0],
    [
        3.314825187068521,
        2.896124015972201,
        0.9986419139977817,
        0.0,
    ],
    [
        1.221224509226641,
        6.019134481288629,
        12.53708332932087,
        -0.687886036105895,
    ],
];

/// `c_ij`: stage `i` solves for `u_i` with `sum_j (c_ij / h) u_j` added.
const C: [[f64; 5]; 6] = [
    [0.0; 5],
    [-5.6688, 0.0, 0.0, 0.0, 0.0],
    [-2.430093356833875, -0.2063599157091915, 0.0, 0.0, 0.0],
    [
        -0.1073529058151375,
        -9.594562251023355,
        -20.47028614809616,
        0.0,
        0.0,
    ],
    [
        7.496443313967647,
        -10.24680431464352,
        -33.99990352819905,
        11.7089089320616,
        0.0,
    ],
    [
        8.083246795921522,
        -7.981132988064893,
        -31.52159432874371,
        16.31930543123136,
        -6.058818238834054,
    ],
];

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

/// Differences for the Jacobian at the step start `s` over a time scale
/// `h`; `scales` (rad, rad/s) set the increments of `theta` and `omega`;
/// `hint` the warm start of the contact solves.
pub(crate) fn jacobian(s: &Start, h: f64, mut hint: f64, scales: [f64; 2]) -> Jac {
    let (t, y0, a0) = (s.t, s.y0, s.a0);
    let sq = f64::EPSILON.sqrt();
    // theta increment away from 0 (the side does not change)
    let dth = sq * y0[0].abs().max(scales[0]);
    let dth = if y0[0] < 0.0 || (y0[0] == 0.0 && s.side < 0.0) {
        -dth
    } else {
        dth
    };
    let a_th = s.accel(t, [y0[0] + dth, y0[1]], &mut hint);
    let dom = sq * y0[1].abs().max(scales[1]);
    let a_om = s.accel(t, [y0[0], y0[1] + dom], &mut hint);
    let a_tt = s.accel(t + h, y0, &mut hint);
    Jac {
        a_theta: (a_th - a0) / dth,
        a_omega: (a_om - a0) / dom,
        a_t: (a_tt - a0) / h,
    }
}

/// `sum_j k_j u_j` over the `u` given.
#[inline(always)]
fn comb(k: &[f64], u: &[[f64; 2]]) -> [f64; 2] {
    let mut s = [0.0; 2];
    for (k, u) in k.iter().zip(u) {
        s[0] += k * u[0];
        s[1] += k * u[1];
    }
    s
}

#[inline(always)]
fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

/// One RODAS step of `h` from `s` with Jacobian `j`.
pub(crate) fn step(s: &Start, j: &Jac, h: f64, hint: &mut f64, tol: &Tol) -> StepOut {
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
    let hi = 1.0 / h;
    // `sum_j (c_ij / h) u_j` of stage `i` over the stages before it
    let c_sum = |i: usize, u: &[[f64; 2]]| -> [f64; 2] {
        let k: [f64; 5] = C[i].map(|c| c * hi);
        comb(&k[..i], u)
    };

    let mut u = [[0.0; 2]; 6];
    u[0] = solve([s.y0[1], s.a0 + h * D[0] * fx]);
    let mut y = s.y0;
    for i in 1..5 {
        y = add(s.y0, comb(&A[i][..i], &u[..i]));
        let fi = [y[1], s.accel(s.t + NODES[i] * h, y, hint)];
        let g = c_sum(i, &u[..i]);
        let g = if i < D.len() {
            add(g, [0.0, h * D[i] * fx])
        } else {
            g
        };
        u[i] = solve(add(fi, g));
    }
    // embedded (order 3) solution, then the last stage is the correction
    let y6 = add(y, u[4]);
    let f6 = [y6[1], s.accel(s.t + h, y6, hint)];
    u[5] = solve(add(f6, c_sum(5, &u[..5])));
    let y1 = add(y6, u[5]);
    let a1 = s.accel(s.t + h, y1, hint);
    let sc = tol.scales(s.y0, y1);
    let e0 = u[5][0] / sc[0];
    let e1 = u[5][1] / sc[1];
    StepOut {
        y: y1,
        accel: a1,
        err: (0.5 * (e0 * e0 + e1 * e1)).sqrt(),
        rho: j.rho(),
    }
}
