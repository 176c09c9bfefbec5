//! The bases of the interface tests, written independently of the code
//! under test: one of each kind, the width function of docs/model.md §1
//! written again from its table, the points where it is not smooth, and
//! the resultants of a contact stress profile by quadrature.

use rocking::{Law, Shape};

use super::integrate_pieces;

/// One base of each kind, with its name, about the size of a masonry
/// block: a 0.5 m x 1 m rectangle, a 0.6 m x 1 m hollow rectangle with
/// 0.1 m walls, a circle of radius 0.4 m and a ring of radii 0.5 m and
/// 0.3 m.
pub fn shapes() -> [(&'static str, Shape); 4] {
    [
        ("solid rectangle", Shape::SolidRectangle { b: 0.5, l: 1.0 }),
        (
            "hollow rectangle",
            Shape::HollowRectangle {
                b: 0.6,
                l: 1.0,
                t: 0.1,
            },
        ),
        ("solid circle", Shape::SolidCircle { ro: 0.4 }),
        ("hollow circle", Shape::HollowCircle { ro: 0.5, ri: 0.3 }),
    ]
}

/// The elasto-plastic law, or the elastic one when `fm` is infinite
/// (`kn` in Pa/m, `fm` in Pa).
pub fn law(kn: f64, fm: f64) -> Law {
    if fm.is_finite() {
        Law::ElastoPlastic { kn, fm }
    } else {
        Law::Elastic { kn }
    }
}

/// Width of the base at `x` (m from the toe), m.
pub fn width(shape: &Shape, x: f64) -> f64 {
    // chord of a circle spanning [lo, hi] along x, from the distances to
    // its two ends (no cancellation near the edges)
    let chord = |lo: f64, hi: f64| {
        if x > lo && x < hi {
            2.0 * ((x - lo) * (hi - x)).sqrt()
        } else {
            0.0
        }
    };
    match *shape {
        Shape::SolidRectangle { b, l } => {
            if (0.0..=b).contains(&x) {
                l
            } else {
                0.0
            }
        }
        Shape::HollowRectangle { b, l, t } => {
            if !(0.0..=b).contains(&x) {
                0.0
            } else if x <= t || x >= b - t {
                l
            } else {
                2.0 * t
            }
        }
        Shape::SolidCircle { ro } => chord(0.0, 2.0 * ro),
        Shape::HollowCircle { ro, ri } => chord(0.0, 2.0 * ro) - chord(ro - ri, ro + ri),
    }
}

/// Points inside the base where the width is not smooth (m from the toe):
/// the inner corners of a hollow section.
pub fn width_breaks(shape: &Shape) -> Vec<f64> {
    match *shape {
        Shape::HollowRectangle { b, t, .. } => vec![t, b - t],
        Shape::HollowCircle { ro, ri } => vec![ro - ri, ro + ri],
        _ => vec![],
    }
}

/// `[N, M]`: the normal force (N) and its moment about the toe (N m) of
/// the stress `min(kn theta (a - x), fm)` over the contact `x < a`,
/// by tanh-sinh between the points where the integrand is not smooth
/// (the width's, and the plastic edge `a - fm / (kn theta)`).
pub fn resultants(shape: &Shape, kn: f64, fm: f64, theta: f64, a: f64) -> [f64; 2] {
    let sigma = |x: f64| (kn * theta * (a - x)).clamp(0.0, fm);
    let mut breaks = width_breaks(shape);
    breaks.push(a - fm / (kn * theta));
    let top = a.min(shape.depth());
    let n = integrate_pieces(&|x| sigma(x) * width(shape, x), 0.0, top, &breaks, 1e-15);
    let m = integrate_pieces(
        &|x| sigma(x) * x * width(shape, x),
        0.0,
        top,
        &breaks,
        1e-15,
    );
    [n, m]
}
