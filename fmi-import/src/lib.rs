//! The exact solution of rigid free rocking (Housner), independent of the
//! FMU and of the `rocking` crate: the reference of `tests/free_rocking.rs`,
//! which imports `RockingBlock.fmu` through the `fmi` crate.
//!
//! A rigid block (weight `W`, inertia `IO` about the toe, `R0` from the toe
//! to the centre of mass at angle `alpha` to the vertical) rocks freely:
//! between impacts the energy per unit inertia
//!
//! ```text
//! e = omega²/2 + V(phi)/IO,   V(phi)/IO = p² (cos(alpha - phi) - cos(alpha)),   p² = W R0 / IO,
//! ```
//!
//! with `phi = |theta|`, is conserved (docs/model.md §3); each impact (theta
//! crossing zero) multiplies `omega` by `eta`, so `e` by `eta²`. The time to
//! fall from a peak `Phi` to `psi` is `∫ dpsi / |omega|`; with
//! `s = sin((alpha - psi)/2)` and `k = sin((alpha - Phi)/2)` it is
//!
//! ```text
//! t = (1/p) ∫_k^s ds / sqrt((s² - k²)(1 - s²)) = F(varphi | m) / p,
//! m = 1 - k²,   sin²(varphi) = (s² - k²) / (s² (1 - k²))
//! ```
//!
//! (Byrd & Friedman 217.00 with `a = 1`, `b = k`), an incomplete elliptic
//! integral of the first kind, evaluated here with Carlson's `R_F`. Energy
//! conservation reads `s² - k² = omega² / (4 p²)`, so everything is computed
//! from a state `(theta, omega)` without cancellation, even next to a peak.
//! The unit tests check the times against a direct quadrature of
//! `dpsi / |omega|`.

/// Carlson's symmetric elliptic integral `R_F(x, y, z)` (duplication, then
/// the fifth-order series; DLMF 19.36.1). At most one argument may be zero.
pub fn carlson_rf(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    assert!(x >= 0.0 && y >= 0.0 && z >= 0.0, "R_F({x}, {y}, {z})");
    for _ in 0..100 {
        let mean = (x + y + z) / 3.0;
        let (dx, dy) = (1.0 - x / mean, 1.0 - y / mean);
        let dz = -(dx + dy);
        // the neglected terms are O(d^6): below 1e-17 for |d| < 1e-3
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-3 {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / mean.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
    unreachable!("R_F duplication converges by a factor 4 per iteration")
}

/// A rigid block rocking freely with restitution `eta`.
#[derive(Clone, Copy, Debug)]
pub struct Housner {
    /// `p² = W R0 / IO`, 1/s².
    pub p2: f64,
    /// Slenderness angle, rad.
    pub alpha: f64,
    /// Coefficient of restitution (ratio of angular velocities at an impact).
    pub eta: f64,
}

impl Housner {
    /// Housner's coefficient of a solid rectangular block of depth `b_full`
    /// and height `h`: `eta = 1 - 1.5 sin²(alpha)`, `tan(alpha) = b_full / h`.
    pub fn solid_block_eta(b_full: f64, h: f64) -> f64 {
        1.0 - 1.5 * b_full.atan2(h).sin().powi(2)
    }

    /// Potential energy per unit inertia, `V(phi)/IO`, in the
    /// cancellation-free form `2 p² sin(phi/2) sin(alpha - phi/2)`.
    pub fn potential(&self, phi: f64) -> f64 {
        2.0 * self.p2 * (0.5 * phi).sin() * (self.alpha - 0.5 * phi).sin()
    }

    /// `(s², d, k²)` of the state `(theta, omega)`: `s = sin((alpha - |theta|)/2)`,
    /// `k = sin((alpha - Phi)/2)` with `Phi` the amplitude, and
    /// `d = s² - k² = omega² / (4 p²)` (energy conservation,
    /// `V(Phi) - V(psi) = IO omega²/2` with `cos(alpha - phi) = 1 - 2 sin²((alpha - phi)/2)`):
    /// every quantity below follows from these without cancellation.
    fn s2_d_k2(&self, theta: f64, omega: f64) -> (f64, f64, f64) {
        let s2 = (0.5 * (self.alpha - theta.abs())).sin().powi(2);
        let d = omega * omega / (4.0 * self.p2);
        let k2 = s2 - d;
        assert!(
            k2 > 0.0,
            "({theta}, {omega}) reaches the overturning rotation"
        );
        (s2, d, k2)
    }

    /// The amplitude (peak `|theta|`) of the half-cycle through `(theta, omega)`.
    pub fn amplitude(&self, theta: f64, omega: f64) -> f64 {
        let (_, d, k2) = self.s2_d_k2(theta, omega);
        // Phi = alpha - 2 asin(k) cancels when Phi << alpha: polish the rise
        // delta = Phi - |theta| by Newton on sin(delta/2) sin(c - delta/2) = d, c = alpha - |theta|
        let c = self.alpha - theta.abs();
        let mut delta = c - 2.0 * k2.sqrt().asin();
        for _ in 0..3 {
            let f = (0.5 * delta).sin() * (c - 0.5 * delta).sin() - d;
            delta -= f / (0.5 * (c - delta).sin());
        }
        theta.abs() + delta
    }

    /// Time between the peak and the state `(theta, omega)` of its half-cycle,
    /// `F(varphi | 1 - k²) / p`.
    pub fn time_from_peak(&self, theta: f64, omega: f64) -> f64 {
        let (s2, d, k2) = self.s2_d_k2(theta, omega);
        let sin2 = d / (s2 * (1.0 - k2));
        // cos²(varphi) = k² (1 - s²) / (s² (1 - k²)), 1 - m sin²(varphi) = k² / s²
        let cos2 = k2 * (1.0 - s2) / (s2 * (1.0 - k2));
        sin2.sqrt() * carlson_rf(cos2, k2 / s2, 1.0) / self.p2.sqrt()
    }

    /// Time from the peak to `theta = 0` of the half-cycle through `(theta, omega)`.
    pub fn fall_time(&self, theta: f64, omega: f64) -> f64 {
        let omega0 = (omega * omega + 2.0 * self.potential(theta.abs())).sqrt();
        self.time_from_peak(0.0, omega0)
    }

    /// Time from the state `(theta, omega)` to the next crossing of zero.
    pub fn time_to_impact(&self, theta: f64, omega: f64) -> f64 {
        let (fall, from_peak) = (
            self.fall_time(theta, omega),
            self.time_from_peak(theta, omega),
        );
        if theta * omega < 0.0 {
            fall - from_peak // on the way down
        } else {
            fall + from_peak // on the way up (or at a peak)
        }
    }

    /// Time since the last crossing of zero of the state `(theta, omega)`.
    pub fn time_since_impact(&self, theta: f64, omega: f64) -> f64 {
        // the motion is symmetric in time about each peak
        self.time_to_impact(theta, -omega)
    }

    /// Released from `theta0` at rest: the times of the first `n` impacts
    /// and the amplitudes of the half-cycles after them.
    pub fn impacts(&self, theta0: f64, n: usize) -> Vec<(f64, f64)> {
        let mut t = self.fall_time(theta0, 0.0);
        // |omega| at theta = 0 just before the first impact
        let mut omega = (2.0 * self.potential(theta0)).sqrt();
        let mut out = Vec::with_capacity(n);
        for _ in 0..n {
            omega *= self.eta;
            out.push((t, self.amplitude(0.0, omega)));
            t += 2.0 * self.fall_time(0.0, omega);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 0.5 m x 2.5 m block.
    fn block() -> Housner {
        let (b, h) = (0.25f64, 1.25f64);
        let r0 = b.hypot(h);
        Housner {
            p2: 3.0 * 9.81 / (4.0 * r0),
            alpha: b.atan2(h),
            eta: Housner::solid_block_eta(2.0 * b, 2.0 * h),
        }
    }

    /// `∫ dpsi / |omega|` from `psi1` to the peak `phi_peak`, directly:
    /// `psi = Phi - d u²` (`d = Phi - psi1`) removes the turning point's
    /// square-root singularity; composite Simpson on `u in [0, 1]`.
    fn time_by_quadrature(hb: &Housner, phi_peak: f64, psi1: f64) -> f64 {
        let d = phi_peak - psi1;
        // omega² = 4 p² sin((Phi - psi)/2) sin(alpha - (Phi + psi)/2)
        let f = |u: f64| {
            if u == 0.0 {
                // limit u -> 0: 2 d u / sqrt(2 p² d u² sin(alpha - Phi))
                return 2.0 * d / (2.0 * hb.p2 * d * (hb.alpha - phi_peak).sin()).sqrt();
            }
            let x = d * u * u;
            let w2 = 4.0 * hb.p2 * (0.5 * x).sin() * (hb.alpha - phi_peak + 0.5 * x).sin();
            2.0 * d * u / w2.sqrt()
        };
        let n = 4000;
        let h = 1.0 / n as f64;
        let mut s = f(0.0) + f(1.0);
        for i in 1..n {
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
        }
        s * h / 3.0
    }

    /// `|omega|` at `|theta| = psi` in the half-cycle of amplitude `phi_peak`.
    fn speed(hb: &Housner, phi_peak: f64, psi: f64) -> f64 {
        // 2 (V(Phi) - V(psi)) / IO, without cancellation
        let w2 = 4.0
            * hb.p2
            * (0.5 * (phi_peak - psi)).sin()
            * (hb.alpha - 0.5 * (phi_peak + psi)).sin();
        w2.sqrt()
    }

    #[test]
    fn rf_special_values() {
        // R_F(0, 1, 1) = pi/2 (K(0)); R_F(x, x, x) = 1/sqrt(x); R_F(0, 1, 2) = Gamma(1/4)² / (4 sqrt(2 pi))
        assert!((carlson_rf(0.0, 1.0, 1.0) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!((carlson_rf(4.0, 4.0, 4.0) - 0.5).abs() < 1e-16);
        assert!((carlson_rf(0.0, 1.0, 2.0) - 1.311_028_777_146_06).abs() < 1e-14);
    }

    #[test]
    fn elliptic_times_match_direct_quadrature() {
        let hb = block();
        for frac in [1e-3, 0.1, 0.5, 0.8, 0.99] {
            let phi_peak = frac * hb.alpha;
            for psi_frac in [0.0, 0.3, 0.9, 0.999] {
                let psi = psi_frac * phi_peak;
                let omega = speed(&hb, phi_peak, psi);
                let amp = hb.amplitude(psi, omega);
                assert!(
                    (amp - phi_peak).abs() < 1e-13 * phi_peak,
                    "{amp} vs {phi_peak}"
                );
                let a = hb.time_from_peak(-psi, omega); // signs do not matter
                let b = time_by_quadrature(&hb, phi_peak, psi);
                assert!((a - b).abs() < 1e-12 * b, "{frac} {psi_frac}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn small_amplitudes_approach_the_linearised_solution() {
        // phi'' = p² (alpha - phi) for small angles: fall time acosh(alpha / (alpha - Phi)) / p,
        // with a relative error O(alpha²)
        let hb = block();
        let phi_peak = 0.5 * hb.alpha;
        let linear = (hb.alpha / (hb.alpha - phi_peak)).acosh() / hb.p2.sqrt();
        let exact = hb.fall_time(phi_peak, 0.0);
        assert!(
            (exact - linear).abs() < hb.alpha.powi(2) * linear,
            "{exact} {linear}"
        );
    }

    #[test]
    fn times_to_and_since_impact_partition_the_half_cycle() {
        let hb = block();
        let phi_peak = 0.6 * hb.alpha;
        let theta = 0.2 * hb.alpha;
        let omega = speed(&hb, phi_peak, theta);
        let half = 2.0 * hb.fall_time(phi_peak, 0.0);
        // moving out: since + to = the time between two impacts
        let sum = hb.time_since_impact(theta, omega) + hb.time_to_impact(theta, omega);
        assert!((sum - half).abs() < 1e-14 * half);
        // moving in: the mirror image
        let since_in = hb.time_since_impact(theta, -omega);
        assert!((since_in - hb.time_to_impact(theta, omega)).abs() < 1e-14 * half);
        // at a peak, both are half the interval
        assert!((hb.time_to_impact(-phi_peak, 0.0) - 0.5 * half).abs() < 1e-14 * half);
    }

    #[test]
    fn impacts_decay_by_eta() {
        let hb = block();
        let theta0 = 0.8 * hb.alpha;
        let imp = hb.impacts(theta0, 3);
        // V(Phi_1) = eta² V(theta0), V(Phi_2) = eta² V(Phi_1)
        let r = hb.potential(imp[0].1) / hb.potential(theta0);
        assert!((r - hb.eta * hb.eta).abs() < 1e-14);
        let r = hb.potential(imp[1].1) / hb.potential(imp[0].1);
        assert!((r - hb.eta * hb.eta).abs() < 1e-14);
        let dt = imp[1].0 - imp[0].0;
        assert!((dt - 2.0 * hb.fall_time(imp[0].1, 0.0)).abs() < 1e-14 * dt);
    }
}
