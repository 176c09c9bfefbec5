//! The exact Housner solution of rigid free rocking (docs/model.md §3),
//! written independently of the code under test: between impacts the energy
//! `E = IO omega²/2 + V(phi)` is conserved, each impact multiplies it by
//! `eta²`, and the time from a peak to the next impact is a quadrature.

use super::quad_adaptive;
use rocking::Model;

/// The exact Housner solution of a rigid block released from `theta0` at rest.
pub struct Exact {
    pub w_r0: f64,
    pub io: f64,
    pub alpha: f64,
    pub eta: f64,
}

impl Exact {
    pub fn new(m: &Model) -> Exact {
        let b = &m.body;
        Exact {
            w_r0: b.weight * b.r0,
            io: b.io,
            alpha: b.alpha,
            eta: m.eta,
        }
    }

    /// `V(phi) = 2 W R0 sin(phi/2) sin(alpha - phi/2)`, free of cancellation.
    pub fn v(&self, phi: f64) -> f64 {
        2.0 * self.w_r0 * (0.5 * phi).sin() * (self.alpha - 0.5 * phi).sin()
    }

    /// The amplitude with potential energy `e`: Newton on `V(phi) = e`.
    pub fn amplitude(&self, e: f64) -> f64 {
        let mut phi = e / (self.w_r0 * self.alpha.sin());
        for _ in 0..100 {
            let f = self.v(phi) - e;
            let df = self.w_r0 * (self.alpha - phi).sin();
            let d = f / df;
            phi -= d;
            if d.abs() <= 1e-17 * phi {
                break;
            }
        }
        phi
    }

    /// Time from the peak `phi` to `theta = 0`.
    pub fn fall_time(&self, phi: f64) -> f64 {
        // psi = phi sin(u), v = pi/4 - u/2: phi - psi = 2 phi sin²(v),
        // cos(u) = 2 sin(v) cos(v), V(phi) - V(psi) = 2 W R0 sin(alpha - (phi + psi)/2) sin(phi sin²(v)).
        let f = |u: f64| {
            let v = std::f64::consts::FRAC_PI_4 - 0.5 * u;
            let psi = phi * u.sin();
            // V(phi) - V(psi) = 2 W R0 sin(alpha - (phi+psi)/2) x sin²(v) phi sinc(phi sin²(v))
            let x = phi * v.sin().powi(2);
            let dv_over_sin2 =
                2.0 * self.w_r0 * (self.alpha - 0.5 * (phi + psi)).sin() * phi * sinc(x);
            phi * 2.0 * v.cos() / (2.0 * dv_over_sin2 / self.io).sqrt()
        };
        quad_adaptive(&f, 0.0, std::f64::consts::FRAC_PI_2, 1e-15)
    }

    /// Impact times and post-impact peak amplitudes, `n` impacts.
    pub fn impacts(&self, theta0: f64, n: usize) -> Vec<(f64, f64)> {
        let mut out = Vec::with_capacity(n);
        let mut e = self.v(theta0);
        let mut t = self.fall_time(theta0);
        for _ in 0..n {
            e *= self.eta * self.eta;
            let phi = self.amplitude(e);
            out.push((t, phi));
            t += 2.0 * self.fall_time(phi);
        }
        out
    }
}

/// `sin(x) / x`.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}
