//! A plain fixed-step RK4 with impacts and overturning, written here as an
//! independent reference (benches/dynamics, tests/dynamics_convergence.rs),
//! and `theta''` of docs/model.md §3 written out for it.

use rocking::{Formulation, Model};

/// `theta''` of docs/model.md §3 under ground acceleration `ag` (m/s²),
/// rad/s², from the model's `contact` and `levers`: the toe is the sign of
/// `theta`, `side` at `theta = 0`.
pub fn flexible_accel(m: &Model, ag: f64, theta: f64, omega: f64, side: f64) -> f64 {
    let s = if theta != 0.0 { theta.signum() } else { side };
    let phi = theta.abs();
    let c = m.interface.contact(phi);
    let l = m.levers(phi, &c);
    let b = &m.body;
    let pivot = if m.formulation == Formulation::ShiftingPivot {
        0.5 * s * l.dinertia * omega * omega
    } else {
        0.0
    };
    (-s * b.weight * l.hw - b.mass * ag * l.hg - pivot) / l.inertia
}

/// A fixed-step classical RK4 on `(theta, omega)`, impacts at `theta = 0`
/// (`omega <- eta omega`), peaks and overturning located by bisection on
/// the step length.
pub struct Rk4<'a> {
    /// `theta''(t, theta, omega, side)`, rad/s²: the input is supplied as
    /// its `t`; `side` the toe the body rocks about.
    pub accel: &'a dyn Fn(f64, f64, f64, f64) -> f64,
    /// Coefficient of restitution.
    pub eta: f64,
    /// Overturning rotation, rad.
    pub theta_ov: f64,
    /// Step, s.
    pub h: f64,
    /// Stop after this many impacts.
    pub max_impacts: usize,
}

/// What an RK4 run found.
pub struct Rk4Out {
    /// Impact times, s, and post-impact `omega`, rad/s.
    pub impacts: Vec<(f64, f64)>,
    /// `|theta|` at the turning points, rad.
    pub peaks: Vec<f64>,
    /// Time of overturning, s.
    pub overturn: Option<f64>,
    /// `(theta, omega)` where the run stopped.
    pub end: [f64; 2],
}

impl Rk4<'_> {
    /// From `y0` at `t = 0` on the toe `side0` to `t_end`, overturning or
    /// `max_impacts`.
    pub fn run(&self, y0: [f64; 2], side0: f64, t_end: f64) -> Rk4Out {
        let (accel, eta, theta_ov, h) = (self.accel, self.eta, self.theta_ov, self.h);
        let step = |t: f64, y: [f64; 2], dt: f64, s: f64| {
            let f = |t: f64, y: [f64; 2]| [y[1], accel(t, y[0], y[1], s)];
            let k1 = f(t, y);
            let k2 = f(
                t + dt / 2.0,
                [y[0] + dt / 2.0 * k1[0], y[1] + dt / 2.0 * k1[1]],
            );
            let k3 = f(
                t + dt / 2.0,
                [y[0] + dt / 2.0 * k2[0], y[1] + dt / 2.0 * k2[1]],
            );
            let k4 = f(t + dt, [y[0] + dt * k3[0], y[1] + dt * k3[1]]);
            [
                y[0] + dt / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
                y[1] + dt / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
            ]
        };
        // bisection on the step length for a sign change of g(y(dt))
        let bisect = |t: f64, y: [f64; 2], dt: f64, s: f64, g: &dyn Fn([f64; 2]) -> f64| {
            let g0 = g(y);
            let (mut lo, mut hi) = (0.0, dt);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if g(step(t, y, mid, s)) * g0 > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            hi
        };
        let mut out = Rk4Out {
            impacts: Vec::new(),
            peaks: Vec::new(),
            overturn: None,
            end: y0,
        };
        let (mut t, mut y, mut side) = (0.0, y0, side0);
        let n = (t_end / h).round() as usize;
        for k in 0..n {
            let t_next = (k + 1) as f64 * h;
            while t < t_next {
                let dt = t_next - t;
                let y1 = step(t, y, dt, side);
                // the first of: overturning, impact, peak
                if side * y1[0] >= theta_ov {
                    let d = bisect(t, y, dt, side, &|z| side * z[0] - theta_ov);
                    out.overturn = Some(t + d);
                    out.end = step(t, y, d, side);
                    return out;
                }
                if y[0] != 0.0 && side * y1[0] < 0.0 {
                    let d = bisect(t, y, dt, side, &|z| z[0]);
                    let yc = step(t, y, d, side);
                    if y[1] * yc[1] < 0.0 || (side * y[1] > 0.0) {
                        // a peak before the impact
                        let dp = bisect(t, y, d, side, &|z| z[1]);
                        out.peaks.push(step(t, y, dp, side)[0].abs());
                    }
                    t += d;
                    y = [0.0, eta * yc[1]];
                    side = -side;
                    out.impacts.push((t, y[1]));
                    if out.impacts.len() >= self.max_impacts {
                        out.end = y;
                        return out;
                    }
                    continue;
                }
                if y[1] * y1[1] < 0.0 {
                    let dp = bisect(t, y, dt, side, &|z| z[1]);
                    out.peaks.push(step(t, y, dp, side)[0].abs());
                }
                y = y1;
                t = t_next;
            }
        }
        out.end = y;
        out
    }
}
