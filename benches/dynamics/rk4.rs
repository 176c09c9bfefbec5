//! A plain fixed-step RK4 with impacts and overturning, written here as an
//! independent reference, and the quadrature of the exact rigid solution.

use super::support::gauss_legendre;

/// The integral of `f` over `[p, q]` by 30-point Gauss-Legendre panels,
/// doubled until two levels agree to 1e-15.
pub fn quad(f: &dyn Fn(f64) -> f64, p: f64, q: f64) -> f64 {
    let rule = gauss_legendre(30);
    let mut prev = f64::NAN;
    let mut panels = 1;
    loop {
        let h = (q - p) / panels as f64;
        let mut sum = 0.0;
        for k in 0..panels {
            let a = p + k as f64 * h;
            for &(x, w) in &rule {
                sum += 0.5 * h * w * f(a + 0.5 * h * (1.0 + x));
            }
        }
        if (sum - prev).abs() <= 1e-15 * sum.abs() || panels > 1 << 12 {
            return sum;
        }
        prev = sum;
        panels *= 2;
    }
}

/// A fixed-step classical RK4 on `(theta, omega)` with `accel(t, theta,
/// omega, side)`, impacts at `theta = 0` (`omega <- eta omega`), peaks and
/// overturning located by bisection on the step length. Stops at `t_end`
/// or overturning. The input is supplied as `accel`'s `t`.
pub struct Rk4Out {
    pub impacts: Vec<(f64, f64)>,
    pub peaks: Vec<f64>,
    pub overturn: Option<f64>,
}

#[allow(clippy::too_many_arguments)]
pub fn rk4(
    accel: &dyn Fn(f64, f64, f64, f64) -> f64,
    y0: [f64; 2],
    side0: f64,
    eta: f64,
    theta_ov: f64,
    h: f64,
    t_end: f64,
    max_impacts: usize,
) -> Rk4Out {
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
                if out.impacts.len() >= max_impacts {
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
    out
}
