//! Helpers for the dynamics tests, written independently of the code under
//! test: Gauss-Legendre quadrature and a few model builders.
#![allow(dead_code)]

use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Model, Params};

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
