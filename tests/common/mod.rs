//! Helpers shared by the integration tests, written independently of the
//! code under test.
#![allow(dead_code)]

/// Tanh-sinh (double exponential) quadrature of `f` over `[p, q]`, refined
/// by halving the step until two levels agree to `rtol` (relative to the
/// integral of |f|). Integrable endpoint singularities (sqrt kinks of a
/// circle's chord) do not slow it down.
pub fn tanh_sinh(f: &dyn Fn(f64) -> f64, p: f64, q: f64, rtol: f64) -> f64 {
    if q <= p {
        return 0.0;
    }
    let r = 0.5 * (q - p);
    let half_pi = std::f64::consts::FRAC_PI_2;
    let tmax = 3.5;
    // Node at parameter t: x = c + r tanh(pi/2 sinh t), distance to the
    // nearer endpoint computed without cancellation.
    let term = |t: f64| -> f64 {
        let u = half_pi * t.sinh();
        let ch = u.cosh();
        let w = half_pi * t.cosh() / (ch * ch);
        // 1 - tanh|u| = 2 / (1 + e^{2|u|})
        let d = r * 2.0 / (1.0 + (2.0 * u.abs()).exp());
        if d <= 0.0 {
            return 0.0;
        }
        let x = if u >= 0.0 { q - d } else { p + d };
        f(x) * w * r
    };
    let mut h = 0.5;
    let mut sum = term(0.0);
    let mut k = 1;
    while k as f64 * h <= tmax {
        let t = k as f64 * h;
        sum += term(t) + term(-t);
        k += 1;
    }
    let mut est = sum * h;
    for _ in 0..12 {
        h *= 0.5;
        let mut k = 1;
        while k as f64 * h <= tmax {
            let t = k as f64 * h;
            sum += term(t) + term(-t);
            k += 2;
        }
        let next = sum * h;
        let done = (next - est).abs() <= rtol * next.abs().max(1e-300);
        est = next;
        if done {
            break;
        }
    }
    est
}

/// Tanh-sinh over the pieces between sorted breakpoints within `[p, q]`.
pub fn integrate_pieces(f: &dyn Fn(f64) -> f64, p: f64, q: f64, breaks: &[f64], rtol: f64) -> f64 {
    let mut pts = vec![p];
    let mut b: Vec<f64> = breaks.iter().copied().filter(|&x| x > p && x < q).collect();
    b.sort_by(|a, b| a.partial_cmp(b).unwrap());
    pts.extend(b);
    pts.push(q);
    pts.windows(2).map(|w| tanh_sinh(f, w[0], w[1], rtol)).sum()
}
