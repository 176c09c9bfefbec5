//! Support for the physics tests, written independently of the code under
//! test: quadratures (tanh-sinh for integrable endpoint singularities,
//! Gauss-Legendre), model builders, the non-smooth points of the restoring
//! moment and the potential energy; the bases and their width ([`base`]),
//! exact rigid rocking ([`exact`]), a plain RK4 ([`rk4`]), a seeded
//! generator for the random sweeps ([`lcg`]), a sampled ground pulse
//! ([`pulse`]), a body under a constant `av` against reduced gravity
//! ([`reduced_gravity`]), the drum of the spatial tests and its ground
//! motion ([`drum`]), their rotated inputs ([`rotated`]) and a Model
//! Exchange host for them ([`model_exchange`]).
#![allow(dead_code)]

pub mod base;
pub mod drum;
pub mod exact;
pub mod lcg;
pub mod model_exchange;
pub mod pulse;
pub mod reduced_gravity;
pub mod rk4;
pub mod rotated;

use rocking::dynamics::{Jet, OutputRates};
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Model, Params};

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

/// Nodes and weights of the `n`-point Gauss-Legendre rule on [-1, 1]
/// (Newton on the Legendre recurrence).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// Composite Gauss-Legendre (`panels` equal panels of 20 points) of `f` on `[p, q]`.
pub fn quad(f: &dyn Fn(f64) -> f64, p: f64, q: f64, panels: usize) -> f64 {
    let rule = gauss_legendre(20);
    let h = (q - p) / panels as f64;
    let mut sum = 0.0;
    for k in 0..panels {
        let a = p + k as f64 * h;
        let mut s = 0.0;
        for &(x, w) in &rule {
            s += w * f(a + 0.5 * h * (1.0 + x));
        }
        sum += 0.5 * h * s;
    }
    sum
}

/// `quad` refined by doubling the panels until two levels agree to `rtol`.
pub fn quad_adaptive(f: &dyn Fn(f64) -> f64, p: f64, q: f64, rtol: f64) -> f64 {
    let mut panels = 1;
    let mut prev = quad(f, p, q, panels);
    for _ in 0..14 {
        panels *= 2;
        let next = quad(f, p, q, panels);
        if (next - prev).abs() <= rtol * next.abs() {
            return next;
        }
        prev = next;
    }
    prev
}

/// A solid rectangular prism `b x 1 x h` m (2000 kg/m³) on a rigid base.
pub fn rigid_block(b: f64, h: f64) -> Model {
    Params {
        shape: ShapeKind::SolidRectangle,
        b,
        l: 1.0,
        mass_model: MassKind::Prism,
        h,
        rho: 2000.0,
        interface: LawKind::Rigid,
        ..Params::default()
    }
    .build()
    .unwrap()
}

/// The default block on an elasto-plastic interface that crushes early:
/// `kn` = 1e8 Pa/m, `fm` = 2 MPa.
pub fn crushing_block() -> Model {
    Params {
        kn: 1e8,
        fm: 2e6,
        ..Params::default()
    }
    .build()
    .unwrap()
}

/// Rotations in `(0, phi)` where the restoring moment `MR(phi)` is not
/// smooth: the regime thresholds, and where the contact edge `a` or the
/// plastic edge `xp = a - fm / (kn phi)` passes a corner of the width
/// function (hollow sections). Found by bisection on the contact solve.
pub fn moment_breaks(m: &Model, phi: f64) -> Vec<f64> {
    use rocking::Law;
    let mut out = Vec::new();
    for l in [m.interface.theta_jo(), m.interface.theta_c()] {
        if l > 0.0 && l < phi {
            out.push(l);
        }
    }
    let corners = base::width_breaks(m.interface.shape());
    let (kn, fm) = match m.interface.law() {
        Law::Elastic { kn } => (kn, f64::INFINITY),
        Law::ElastoPlastic { kn, fm } => (kn, fm),
        Law::Rigid => return out,
    };
    let edges = |p: f64| {
        let c = m.interface.contact(p);
        [c.a, c.a - fm / (kn * p)]
    };
    // scan geometrically from far below the first threshold
    let lo = 1e-6 * m.interface.theta_jo().min(phi);
    let n = 2000;
    let ratio = (phi / lo).powf(1.0 / n as f64);
    for &x in &corners {
        for k in 0..2 {
            let mut p0 = lo;
            let mut f0 = edges(p0)[k] - x;
            for i in 1..=n {
                let p1 = lo * ratio.powi(i);
                let f1 = edges(p1)[k] - x;
                if f0.is_finite() && f1.is_finite() && f0 * f1 < 0.0 {
                    let (mut a, mut b) = (p0, p1);
                    for _ in 0..200 {
                        let c = 0.5 * (a + b);
                        if (edges(c)[k] - x) * f0 > 0.0 {
                            a = c;
                        } else {
                            b = c;
                        }
                    }
                    out.push(0.5 * (a + b));
                }
                p0 = p1;
                f0 = f1;
            }
        }
    }
    out.sort_by(|a, b| a.partial_cmp(b).unwrap());
    out
}

/// Potential energy `V(phi) = ∫_0^phi W hW`, by Gauss-Legendre between the
/// non-smooth points of the restoring moment.
pub fn potential(m: &Model, phi: f64, breaks: &[f64]) -> f64 {
    let f = |p: f64| m.restoring_moment(p).0;
    let mut pts = vec![0.0];
    pts.extend(breaks.iter().copied().filter(|&b| b > 0.0 && b < phi));
    pts.push(phi);
    pts.windows(2)
        .map(|w| quad_adaptive(&f, w[0], w[1], 1e-14))
        .sum()
}

/// `theta`, `omega`, `theta''`, `af`, `contactLength`, `MR`, `Fx`, `Fz`
/// with their time derivatives, in that order.
pub fn output_jets(r: &OutputRates) -> [Jet; 8] {
    [
        r.theta,
        r.omega,
        r.theta_dd,
        r.af,
        r.contact_length,
        r.mr,
        r.fx,
        r.fz,
    ]
}
