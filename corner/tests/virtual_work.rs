//! The closed-form work terms against a brute force: the macroblock is cut block by block
//! (running bond, head joints on a half-block grid alternating per course), each block is
//! clipped to each moving part, and weights, centroid displacements and inertia are summed
//! piece by piece with polygon formulas and an exact quadrature. Nothing here uses the
//! trapezoid formulas of the crate.

mod support;

use corner::{
    rocking_body, torsion_lever, CornerColumn, CornerModel, Direction, Geometry, InPlaneWedge,
    Mechanism, Options, Specimen,
};

type P = (f64, f64);

/// Sutherland-Hodgman: `subject` clipped to the convex counter-clockwise polygon `clip`.
fn clip(subject: &[P], clip: &[P]) -> Vec<P> {
    let mut out = subject.to_vec();
    for i in 0..clip.len() {
        let (a, b) = (clip[i], clip[(i + 1) % clip.len()]);
        let side = |p: P| (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
        let input = std::mem::take(&mut out);
        for j in 0..input.len() {
            let (p, q) = (input[j], input[(j + 1) % input.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                out.push((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)));
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}

/// Integral of f over a convex polygon: fan triangles, edge-midpoint rule (exact for degree 2).
fn integrate(poly: &[P], f: &dyn Fn(P) -> f64) -> f64 {
    let mut sum = 0.0;
    for i in 1..poly.len().saturating_sub(1) {
        let (a, b, c) = (poly[0], poly[i], poly[i + 1]);
        let area = 0.5 * ((b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1));
        let mid = |p: P, q: P| ((p.0 + q.0) / 2.0, (p.1 + q.1) / 2.0);
        sum += area / 3.0 * (f(mid(a, b)) + f(mid(b, c)) + f(mid(c, a)));
    }
    sum
}

/// The blocks of one wall (elevation coordinates s along the wall, z up).
fn blocks(sp: &Specimen, length: f64) -> Vec<Vec<P>> {
    let v = sp.v();
    let mut out = Vec::new();
    for c in 0..sp.courses {
        let (z0, z1) = (f64::from(c) * sp.h, f64::from(c + 1) * sp.h);
        // Head joints at even multiples of v in one course, odd in the next.
        let mut edges = vec![0.0];
        let mut s = if c % 2 == 0 { 2.0 * v } else { v };
        while s < length + sp.l {
            edges.push(s);
            s += 2.0 * v;
        }
        for w in edges.windows(2) {
            out.push(vec![(w[0], z0), (w[1], z0), (w[1], z1), (w[0], z1)]);
        }
    }
    out
}

#[derive(Default, Debug)]
struct Sums {
    weight: f64,
    stabilising: f64,
    overturning: f64,
    inertia: f64,
}

/// Brute-force work terms and inertia of one direction, block by block.
fn brute_force(model: &CornerModel, x: &Geometry, dir: Direction) -> Sums {
    let sp = &model.specimen;
    let (gt, rho, t) = (sp.gamma() * sp.t, sp.rho, sp.t);
    let hh = sp.height();
    let z1 = x.z1;
    let d = hh - z1;
    // (green top, red width, base, wall length) of the in-plane and the out-of-plane wall.
    let (ip, oop, len_ip, len_oop) = match dir {
        Direction::X => (
            (x.x1, x.x2, x.x3),
            (x.y2, x.y1, x.y3),
            sp.length_x(),
            sp.length_y(),
        ),
        Direction::Y => (
            (x.y2, x.y1, x.y3),
            (x.x1, x.x2, x.x3),
            sp.length_y(),
            sp.length_x(),
        ),
    };
    let flexural = model.mechanism == Mechanism::Flexural;
    let ip_top = if flexural && model.options.in_plane_wedge == InPlaneWedge::Green {
        ip.0
    } else {
        ip.0 + ip.1
    };
    let y0 = if model.options.corner_column == CornerColumn::Once {
        t
    } else {
        0.0
    };
    let oop_green_top = if flexural { oop.0 } else { oop.0 + oop.1 };
    let wedge = [(0.0, z1), (ip.2, z1), (ip_top, hh), (0.0, hh)];
    let green = [(y0, z1), (oop.2, z1), (oop_green_top, hh), (y0, hh)];
    let red = [(oop.2, z1), (oop.0 + oop.1, hh), (oop.0, hh)];
    let mut s = Sums::default();
    // In-plane wall: a point (s, z) rises by s and moves by (z - Z1) per unit rotation.
    for b in blocks(sp, len_ip) {
        let piece = clip(&b, &wedge);
        let area = integrate(&piece, &|_| 1.0);
        if area <= 0.0 {
            continue;
        }
        let sc = integrate(&piece, &|p| p.0) / area;
        let zc = integrate(&piece, &|p| p.1) / area;
        s.weight += gt * area;
        s.stabilising += gt * area * sc;
        s.overturning += gt * area * (zc - z1);
        s.inertia += rho * t * integrate(&piece, &|p| p.0 * p.0 + (p.1 - z1).powi(2));
    }
    // Out-of-plane wall: it turns about its outer bottom edge; its mid-thickness rises t/2.
    for b in blocks(sp, len_oop) {
        let piece = clip(&b, &green);
        let area = integrate(&piece, &|_| 1.0);
        if area > 0.0 {
            let zc = integrate(&piece, &|p| p.1) / area;
            s.weight += gt * area;
            s.stabilising += gt * area * t / 2.0;
            s.overturning += gt * area * (zc - z1);
            s.inertia += rho * integrate(&piece, &|p| t * (p.1 - z1).powi(2) + t.powi(3) / 3.0);
        }
        if flexural {
            // The red triangle turns about its outer line O'A' at omega = d / red: a point moves
            // by omega * xi, xi its horizontal distance from O'A'.
            let omega = d / oop.1;
            let xi = |p: P| oop.2 + (oop.0 + oop.1 - oop.2) * (p.1 - z1) / d - p.0;
            let piece = clip(&b, &red);
            let area = integrate(&piece, &|_| 1.0);
            if area > 0.0 {
                let xic = integrate(&piece, &|p| xi(p)) / area;
                s.weight += gt * area;
                s.stabilising += gt * area * t / 2.0;
                s.overturning += gt * area * omega * xic;
                s.inertia += omega * omega * rho * t * integrate(&piece, &|p| xi(p).powi(2));
            }
        }
    }
    s
}

fn geometries(model: &CornerModel) -> Vec<Geometry> {
    let v = model.specimen.v();
    let h = model.specimen.h;
    let mut next = support::uniform(99);
    let mut out = vec![
        // The paper's optima at pi/4 and pi/2 on the joint grid.
        Geometry {
            x1: 5.0 * v,
            x2: 4.0 * v,
            x3: v,
            y1: 4.0 * v,
            y2: 5.0 * v,
            y3: v,
            z1: h,
        },
        Geometry {
            x1: 10.0 * v,
            x2: 4.0 * v,
            x3: 10.0 * v,
            y1: v,
            y2: 5.0 * v,
            y3: v,
            z1: h,
        },
    ];
    while out.len() < 40 {
        // Half joint-aligned, half arbitrary continuous values.
        let snap = out.len() % 2 == 0;
        let q = |r: f64, lo: f64, hi: f64| {
            let x = lo + r * (hi - lo);
            if snap {
                (x / v).round() * v
            } else {
                x
            }
        };
        let z1 = if snap {
            h * (1.0 + (7.0 * next()).floor())
        } else {
            h * (1.0 + 7.0 * next())
        };
        let g = support::draw_geometry(&mut next, q, z1, v, 8.0 * v, 12.0 * v, (v, 5.0 * v));
        if g.check(model, 0.0).is_ok() {
            out.push(g);
        }
    }
    out
}

#[test]
fn closed_forms_equal_the_block_by_block_sums() {
    let mut checked = 0;
    for m in [0, 1] {
        for wedge in [InPlaneWedge::Green, InPlaneWedge::Outer] {
            for column in [CornerColumn::Both, CornerColumn::Once] {
                let o = Options {
                    in_plane_wedge: wedge,
                    corner_column: column,
                    ..Options::default()
                };
                let model = CornerModel::new(Specimen::paper(), m, 0.3, o).unwrap();
                for x in geometries(&model) {
                    for dir in [Direction::X, Direction::Y] {
                        let bf = brute_force(&model, &x, dir);
                        let w = model.direction_terms(&x, dir);
                        let body = rocking_body(&model, &x, dir).unwrap();
                        let rel = |a: f64, b: f64| (a - b).abs() / b.abs().max(1e-300);
                        let ctx = format!("m={m} {wedge:?} {column:?} {dir:?} {x:?}");
                        assert!(rel(w.stabilising, bf.stabilising) < 1e-12, "S {ctx}");
                        assert!(rel(w.overturning, bf.overturning) < 1e-12, "O {ctx}");
                        assert!(rel(body.weight, bf.weight) < 1e-12, "W {ctx}");
                        assert!(rel(body.i_o, bf.inertia) < 1e-12, "I_O {ctx}");
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 2 * 2 * 2 * 40 * 2);
}

#[test]
fn friction_lever_is_the_sum_over_the_bed_joints() {
    // Bed joint under course i (from the top) carries i courses: capacity mu gamma v t h i; it
    // slips by its height above the hinge, (n - i) h, per unit rotation; the hinge joint does not.
    let model = CornerModel::paper(1, 0.3).unwrap();
    let sp = model.specimen;
    for j in 1..sp.courses {
        let n = sp.courses - j;
        let joints: f64 = (1..=n)
            .map(|i| {
                let i = f64::from(i);
                sp.mu * sp.gamma() * sp.v() * sp.t * sp.h * i * (f64::from(n) - i) * sp.h
            })
            .sum();
        // A vertical in-plane crack (X1 = X3) has alpha_c = 0: the full capacity works.
        let v = sp.v();
        let x = Geometry {
            x1: 3.0 * v,
            x2: v,
            x3: 3.0 * v,
            y1: v,
            y2: 2.0 * v,
            y3: v,
            z1: f64::from(j) * sp.h,
        };
        let w = model.direction_terms(&x, Direction::X);
        // n = d/h is computed in floating point: a tolerance relative to the largest joint term.
        let scale = model.fmax(f64::from(n)) * sp.height();
        assert!((w.friction_ip - joints).abs() <= 1e-12 * scale, "n={n}");
    }
}

#[test]
fn torsion_lever_is_the_mean_distance_over_the_contact() {
    // Midpoint rule over a t x v rectangle: the mean distance of its points from the centroid.
    let sp = Specimen::paper();
    let (t, v) = (sp.t, sp.v());
    let n = 1500;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = (f64::from(i) + 0.5) / f64::from(n) * t - t / 2.0;
            let y = (f64::from(j) + 0.5) / f64::from(n) * v - v / 2.0;
            sum += x.hypot(y);
        }
    }
    let mean = sum / f64::from(n * n);
    let d0 = torsion_lever(t, v);
    // The midpoint rule converges slowly at the cone point of |r|: 1e-6 is what 1500^2 points give.
    assert!((d0 - mean).abs() < 1e-6 * d0, "{d0} vs {mean}");
    // The paper's value, 21.95 mm.
    assert!((d0 - 0.02195).abs() < 5e-6, "{d0}");
}
