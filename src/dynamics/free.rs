//! Rigid free rocking (`ag = 0`) half-cycle by half-cycle, in closed form.
//!
//! Without ground motion the rigid law conserves `E = IO omega²/2 + V(phi)`,
//! `V(phi) = W R0 (cos(alpha - phi) - cos(alpha)) = 2 W R0 sin(phi/2) sin(alpha - phi/2)`,
//! between impacts (docs/model.md §3). A body leaving `theta = 0` with `omega`
//! rises to the peak `V(phi) = IO omega²/2` and is back at `theta = 0` with
//! `-omega` after `2 T(phi)`, `T(phi) = ∫_0^phi dpsi / omega(psi)`. With
//! `psi = phi sin(u)` and `v = pi/4 - u/2` the integrand is analytic on
//! `[0, pi/2]` (the turning-point singularity cancels) and 20-point
//! Gauss-Legendre gives `T` to about 1e-15: chattering and free rocking in
//! a quiet part of a record then cost one quadrature per impact instead of
//! several integration steps.

/// Positive nodes and weights of the 20-point Gauss-Legendre rule on [-1, 1].
const GL20: [(f64, f64); 10] = [
    (0.07652652113349734, 0.15275338713072628),
    (0.22778585114164507, 0.14917298647260424),
    (0.37370608871541955, 0.1420961093183824),
    (0.5108670019508271, 0.1316886384491769),
    (0.636053680726515, 0.1181945319615186),
    (0.7463319064601508, 0.1019301198172407),
    (0.8391169718222188, 0.08327674157670471),
    (0.912234428251326, 0.06267204833410879),
    (0.9639719272779138, 0.040601429800386446),
    (0.993128599185095, 0.017614007139150893),
];

/// The free motion of a rigid body.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FreeRigid {
    w_r0: f64,
    io: f64,
    alpha: f64,
}

impl FreeRigid {
    pub fn new(weight: f64, r0: f64, io: f64, alpha: f64) -> FreeRigid {
        FreeRigid {
            w_r0: weight * r0,
            io,
            alpha,
        }
    }

    fn v(&self, phi: f64) -> f64 {
        2.0 * self.w_r0 * (0.5 * phi).sin() * (self.alpha - 0.5 * phi).sin()
    }

    /// The peak rotation of a body leaving `theta = 0` with `omega`, or
    /// `None` if it would reach `alpha` (overturning: left to the
    /// integrator).
    pub fn peak(&self, omega: f64) -> Option<f64> {
        let e = 0.5 * self.io * omega * omega;
        if e.is_nan() || e >= 0.999 * self.v(self.alpha) {
            return None;
        }
        let mut phi = (e / (self.w_r0 * self.alpha.sin())).min(self.alpha);
        for _ in 0..60 {
            // V'(phi) = W R0 sin(alpha - phi)
            let d = (self.v(phi) - e) / (self.w_r0 * (self.alpha - phi).sin());
            phi -= d;
            if d.abs() <= 1e-16 * phi {
                break;
            }
        }
        (phi > 0.0 && phi < self.alpha).then_some(phi)
    }

    /// Time from the peak `phi` down to `theta = 0`, s.
    pub fn fall_time(&self, phi: f64) -> f64 {
        let c = 4.0 * self.w_r0 / self.io;
        let f = |u: f64| {
            let v = std::f64::consts::FRAC_PI_4 - 0.5 * u;
            let psi = phi * u.sin();
            // V(phi) - V(psi) = 2 W R0 sin(alpha - (phi+psi)/2) sin(phi sin²v),
            // sin(phi sin²v) = phi sin²v sinc(phi sin²v); d psi = 2 phi sin v cos v du
            let x = phi * v.sin().powi(2);
            let sinc = if x < 1e-4 {
                1.0 - x * x / 6.0
            } else {
                x.sin() / x
            };
            let dv = c * (self.alpha - 0.5 * (phi + psi)).sin() * phi * sinc;
            phi * 2.0 * v.cos() / dv.sqrt()
        };
        let half = std::f64::consts::FRAC_PI_4;
        let mut sum = 0.0;
        for &(x, w) in &GL20 {
            sum += w * (f(half * (1.0 + x)) + f(half * (1.0 - x)));
        }
        half * sum
    }
}
