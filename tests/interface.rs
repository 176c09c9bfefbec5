//! Interface mechanics (docs/model.md §2) against independent references:
//! quadrature of the width function, the solid-rectangle closed forms
//! derived by hand, a brute-force fibre model, and invariants.

mod support;

use rocking::{Interface, Law, Regime, Shape};
use support::base::{self, law, resultants, width, width_breaks};
use support::integrate_pieces;

/// The fixture's bases, a large hollow rectangle, the Dharahara's ring
/// (docs/model.md §4) and a thin ring (its inner chord's square-root points
/// nearly meet the outer one's).
fn shapes() -> Vec<Shape> {
    let mut out: Vec<Shape> = base::shapes().iter().map(|&(_, s)| s).collect();
    out.extend([
        Shape::HollowRectangle {
            b: 3.0,
            l: 2.0,
            t: 0.35,
        },
        Shape::HollowCircle { ro: 3.99, ri: 2.12 },
        Shape::HollowCircle { ro: 1.0, ri: 0.97 },
    ]);
    out
}

#[test]
fn full_moments_match_area_and_second_moment() {
    for shape in shapes() {
        let d = shape.depth();
        let [s0, s1, s2] = shape.moments(d);
        let a = shape.area();
        // centroid at D/2, and Is = S2 - 2 c S1 + c^2 S0 with c = D/2
        let c = d / 2.0;
        let is = s2 - 2.0 * c * s1 + c * c * s0;
        assert!((s0 / a - 1.0).abs() < 1e-14, "{shape:?} area {s0} vs {a}");
        assert!((s1 / (a * c) - 1.0).abs() < 1e-14, "{shape:?} first moment");
        assert!(
            (is / shape.second_moment() - 1.0).abs() < 1e-12,
            "{shape:?} Is {is}"
        );
    }
}

#[test]
fn cumulative_moments_match_quadrature() {
    for shape in shapes() {
        let d = shape.depth();
        let bk = width_breaks(&shape);
        let mut worst: f64 = 0.0;
        for i in 0..=60 {
            // from 1e-7 D to D, geometric, plus the breakpoints themselves
            let x = d * 10f64.powf(-7.0 + 7.0 * i as f64 / 60.0);
            for xs in std::iter::once(x).chain(bk.iter().copied()) {
                let s = shape.moments(xs);
                for (k, &sk) in s.iter().enumerate() {
                    let q = integrate_pieces(
                        &|u| u.powi(k as i32) * width(&shape, u),
                        0.0,
                        xs,
                        &bk,
                        1e-15,
                    );
                    let rel = (sk - q).abs() / q.abs();
                    worst = worst.max(rel);
                    assert!(
                        rel < 1e-12,
                        "{shape:?} S{k}({xs}) = {sk}, quadrature {q}, rel {rel:e}"
                    );
                }
            }
        }
        println!("{shape:?}: worst relative error of S0..S2 {worst:e}");
    }
}

/// Solid rectangle, derived by hand (docs/model.md §2 and, for crushing in full
/// contact, the same equilibrium with a trapezoidal elastic zone):
/// returns (af, a, regime).
fn solid_rectangle_exact(bd: f64, l: f64, w: f64, kn: f64, fm: f64, th: f64) -> (f64, f64, Regime) {
    let area = bd * l;
    let k = kn * th;
    let crush_in_full = fm * area < 2.0 * w;
    let full_contact = (
        bd / 2.0 - k * (l * bd.powi(3) / 12.0) / w,
        w / (k * area) + bd / 2.0,
        Regime::FullContact,
    );
    if crush_in_full {
        let theta_c = 2.0 * (fm - w / area) / (kn * bd);
        let theta_jo = fm * fm * l / (2.0 * kn * (fm * area - w));
        if th <= theta_c {
            return full_contact;
        }
        if th <= theta_jo {
            // elastic zone of length e at the heel: e^2 = 2 (fm A - W)/(k L)
            let e = (2.0 * (fm * area - w) / (k * l)).sqrt();
            let xp = bd - e;
            let m = fm * l * xp * xp / 2.0
                + l * (fm * e * (xp + e / 2.0) - k * e * e / 2.0 * (xp + 2.0 * e / 3.0));
            return (m / w, xp + fm / k, Regime::FullCrushing);
        }
    } else {
        let theta_jo = 2.0 * w / (kn * area * bd);
        let ac = 2.0 * w / (fm * l);
        let theta_c = fm / (kn * ac);
        if th <= theta_jo {
            return full_contact;
        }
        if th <= theta_c {
            let a = (2.0 * w / (k * l)).sqrt();
            return (a / 3.0, a, Regime::Partial);
        }
    }
    let a1 = fm / k;
    let alim = w / (fm * l);
    let a2 = alim - a1 / 2.0;
    let af = (a2 * a2 / 2.0 + (a1 / 2.0) * (a2 + a1 / 3.0)) / (a2 + a1 / 2.0);
    (af, a1 + a2, Regime::PartialCrushing)
}

#[test]
fn solid_rectangle_matches_closed_forms() {
    let (bd, l) = (0.6, 1.2);
    // (W, kn, fm): crushing after opening; crushing before opening; no crushing
    let cases = [
        (2.0e4, 3.0e9, 4.0e6),
        (2.0e5, 1.0e9, 0.5e6),
        (5.0e4, 8.0e8, f64::INFINITY),
    ];
    for (w, kn, fm) in cases {
        let it = Interface::new(Shape::SolidRectangle { b: bd, l }, law(kn, fm), w);
        let alpha = (bd / 2.0f64).atan2(1.5);
        let mut seen = std::collections::HashSet::new();
        for i in 0..=400 {
            let th = 1e-8 * (alpha / 1e-8).powf(i as f64 / 400.0);
            let c = it.contact(th);
            let (af, a, regime) = solid_rectangle_exact(bd, l, w, kn, fm, th);
            seen.insert(regime);
            assert_eq!(c.regime, regime, "W={w} kn={kn} fm={fm} theta={th}");
            let rel = (c.af - af).abs() / af;
            assert!(
                rel < 1e-12,
                "af at theta={th}: {} vs {af} ({rel:e}), {regime:?}",
                c.af
            );
            let rel_a = (c.a - a).abs() / a;
            assert!(rel_a < 1e-12, "a at theta={th}: {} vs {a} ({rel_a:e})", c.a);
        }
        println!("W={w} fm={fm}: regimes seen {seen:?}");
        let expected = if fm.is_finite() { 3 } else { 2 };
        assert_eq!(
            seen.len(),
            expected,
            "the sweep should cross every regime: {seen:?}"
        );
        if fm.is_finite() {
            let area = bd * l;
            if fm * area >= 2.0 * w {
                let ac = 2.0 * w / (fm * l);
                let tc = fm / (kn * ac);
                assert!(
                    (it.theta_c() / tc - 1.0).abs() < 1e-12,
                    "thetaC {} vs {tc}",
                    it.theta_c()
                );
            } else {
                let tc = 2.0 * (fm - w / area) / (kn * bd);
                let tjo = fm * fm * l / (2.0 * kn * (fm * area - w));
                assert!((it.theta_c() / tc - 1.0).abs() < 1e-12);
                assert!(
                    (it.theta_jo() / tjo - 1.0).abs() < 1e-12,
                    "thetaJo {} vs {tjo}",
                    it.theta_jo()
                );
            }
            // plastic limit alim/2
            assert!((it.af_limit() / (w / (fm * l) / 2.0) - 1.0).abs() < 1e-12);
        } else {
            assert!((it.theta_jo() / (2.0 * w / (kn * bd * l * bd)) - 1.0).abs() < 1e-12);
        }
    }
}

/// Every shape and law: equilibrium and reaction position recomputed by
/// quadrature of the stress profile at the solver's `a`.
fn check_by_quadrature(shape: Shape, w: f64, kn: f64, fm: f64) -> (f64, f64) {
    let it = Interface::new(shape, law(kn, fm), w);
    let d = shape.depth();
    let mut worst_n: f64 = 0.0;
    let mut worst_af: f64 = 0.0;
    for i in 0..=120 {
        let th = 1e-7 * (0.5f64 / 1e-7).powf(i as f64 / 120.0);
        let c = it.contact(th);
        let [n, m] = resultants(&shape, kn, fm, th, c.a);
        let res = (n - w).abs() / w;
        let af = m / w;
        let rel = (c.af - af).abs() / af;
        worst_n = worst_n.max(res);
        worst_af = worst_af.max(rel);
        assert!(
            res < 1e-12,
            "{shape:?} fm={fm}: |N(a)-W|/W = {res:e} at theta={th}"
        );
        assert!(
            rel < 1e-12,
            "{shape:?} fm={fm}: af {} vs quadrature {af} ({rel:e}) at theta={th}",
            c.af
        );
        assert!(c.contact_length <= d && c.af >= 0.0 && c.af <= d / 2.0);
    }
    (worst_n, worst_af)
}

#[test]
fn all_shapes_and_laws_match_quadrature_of_the_stress_profile() {
    for shape in shapes() {
        let a = shape.area();
        // a weight that gives W/A = 0.3 MPa; fm: crushing before and after opening, none
        let w = 0.3e6 * a;
        for fm in [0.5e6, 2.0e6, f64::INFINITY] {
            let (n, af) = check_by_quadrature(shape, w, 1e9, fm);
            println!("{shape:?} fm={fm:e}: worst |N-W|/W {n:e}, worst af {af:e}");
        }
    }
}

/// Brute-force fibre model: the base as a 2-D grid of square springs (cell
/// centres inside the section), equilibrium by bisection on `a`.
struct Fibres {
    x: Vec<f64>,
    area: Vec<f64>,
}

impl Fibres {
    fn new(shape: &Shape, n: usize) -> Fibres {
        let d = shape.depth();
        let half_width = match *shape {
            Shape::SolidRectangle { l, .. } | Shape::HollowRectangle { l, .. } => l / 2.0,
            Shape::SolidCircle { ro } | Shape::HollowCircle { ro, .. } => ro,
        };
        let h = d / n as f64;
        let ny = (2.0 * half_width / h).ceil() as usize;
        let hy = 2.0 * half_width / ny as f64;
        let inside = |x: f64, y: f64| -> bool {
            match *shape {
                Shape::SolidRectangle { .. } => true,
                Shape::HollowRectangle { b, l, t } => {
                    x <= t || x >= b - t || y.abs() >= l / 2.0 - t
                }
                Shape::SolidCircle { ro } => (x - ro).powi(2) + y * y <= ro * ro,
                Shape::HollowCircle { ro, ri } => {
                    let r2 = (x - ro).powi(2) + y * y;
                    r2 <= ro * ro && r2 >= ri * ri
                }
            }
        };
        let mut xs = Vec::with_capacity(n);
        let mut areas = Vec::with_capacity(n);
        for i in 0..n {
            let x = (i as f64 + 0.5) * h;
            let count = (0..ny)
                .filter(|&j| inside(x, -half_width + (j as f64 + 0.5) * hy))
                .count();
            xs.push(x);
            areas.push(count as f64 * h * hy);
        }
        Fibres { x: xs, area: areas }
    }

    fn af(&self, th: f64, w: f64, kn: f64, fm: f64) -> f64 {
        let n_of = |a: f64| -> (f64, f64) {
            let mut n = 0.0;
            let mut m = 0.0;
            for (x, da) in self.x.iter().zip(&self.area) {
                let s = (kn * th * (a - x)).clamp(0.0, fm);
                n += s * da;
                m += s * x * da;
            }
            (n, m)
        };
        let (mut lo, mut hi) = (0.0, 1.0);
        while n_of(hi).0 < w {
            hi *= 2.0;
        }
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if n_of(mid).0 < w {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let (n, m) = n_of(0.5 * (lo + hi));
        m / n
    }
}

#[test]
fn all_shapes_and_laws_match_a_brute_force_fibre_model() {
    // Resolution: 4000 columns along the depth; the contact is kept longer
    // than 200 columns (a > D/20). The fibre model's own error is measured
    // as its change from 2000 to 4000 columns; we require agreement within
    // 4 times that change plus 1e-6 (the cell-counting noise of the circles).
    for shape in shapes() {
        let fine = Fibres::new(&shape, 4000);
        let coarse = Fibres::new(&shape, 2000);
        let d = shape.depth();
        let w = 0.3e6 * shape.area();
        for fm in [0.5e6, 2.0e6, f64::INFINITY] {
            let kn = 1e9;
            let it = Interface::new(shape, law(kn, fm), w);
            let mut worst: f64 = 0.0;
            for i in 0..=24 {
                let th = 1e-6 * (1e-2f64 / 1e-6).powf(i as f64 / 24.0);
                let c = it.contact(th);
                if c.contact_length < d / 20.0 {
                    continue;
                }
                let f = fine.af(th, w, kn, fm);
                let g = coarse.af(th, w, kn, fm);
                let err = (c.af - f).abs() / d;
                let own = (f - g).abs() / d;
                worst = worst.max(err);
                assert!(
                    err < 4.0 * own + 1e-6,
                    "{shape:?} fm={fm}: theta={th} af {} vs fibres {f} (resolution {own:e})",
                    c.af
                );
            }
            println!("{shape:?} fm={fm:e}: worst |af - af_fibre|/D = {worst:e}");
        }
    }
}

#[test]
fn af_is_d_over_2_at_rest_c1_at_the_thresholds_and_non_increasing() {
    for shape in shapes() {
        let w = 0.3e6 * shape.area();
        let d = shape.depth();
        for law in [
            Law::Elastic { kn: 1e9 },
            Law::ElastoPlastic { kn: 1e9, fm: 0.5e6 },
            Law::ElastoPlastic { kn: 1e9, fm: 2e6 },
        ] {
            let it = Interface::new(shape, law, w);
            assert_eq!(it.contact(0.0).af, d / 2.0);
            // C1 at the thresholds: one-sided analytic derivatives agree
            for th in [it.theta_jo(), it.theta_c()] {
                if !th.is_finite() {
                    continue;
                }
                let lo = it.contact(th * (1.0 - 1e-11));
                let hi = it.contact(th * (1.0 + 1e-11));
                assert!(
                    (lo.af - hi.af).abs() <= 1e-9 * d,
                    "{shape:?} {law:?} af jumps at {th}"
                );
                let rel = (lo.daf - hi.daf).abs() / lo.daf.abs();
                assert!(
                    rel < 1e-6,
                    "{shape:?} {law:?}: af' {} vs {} at {th}",
                    lo.daf,
                    hi.daf
                );
            }
            // af' against central differences, af non-increasing
            let mut prev = d / 2.0;
            for i in 0..=200 {
                let th = 1e-7 * (1.0f64 / 1e-7).powf(i as f64 / 200.0);
                let c = it.contact(th);
                assert!(
                    c.af <= prev * (1.0 + 1e-14),
                    "{shape:?} {law:?}: af grows at {th}"
                );
                prev = c.af;
                let h = th * 1e-4;
                let fd = (it.contact(th + h).af - it.contact(th - h).af) / (2.0 * h);
                // FD error: truncation plus af's own rounding (~1e-13 relative) over h
                let tol = 1e-3 * c.daf.abs() + 1e-12 * c.af / h;
                assert!(
                    (fd - c.daf).abs() < tol,
                    "{shape:?} {law:?}: af'({th}) = {} vs FD {fd}",
                    c.daf
                );
            }
            // plastic limit
            if let Law::ElastoPlastic { .. } = law {
                let big = it.contact(1e4);
                let lim = it.af_limit();
                assert!(
                    (big.af / lim - 1.0).abs() < 1e-3,
                    "{shape:?}: af(1e4) = {} vs alim/2 = {lim}",
                    big.af
                );
            } else {
                assert!(it.contact(1e4).af < 1e-3 * d);
            }
        }
        let rigid = Interface::new(shape, Law::Rigid, w);
        assert_eq!(rigid.contact(1e-9).af, 0.0);
        assert_eq!(rigid.contact(0.3).af, 0.0);
    }
}

#[test]
fn warm_started_solves_agree_with_cold_ones() {
    // The integrator's path: each solve starts from the previous contact.
    // The Taylor finish must leave the equilibrium residual below 1e-12 too.
    for shape in shapes() {
        let w = 0.3e6 * shape.area();
        for fm in [0.5e6, 2.0e6, f64::INFINITY] {
            let kn = 1e9;
            let it = Interface::new(shape, law(kn, fm), w);
            let n = 3000;
            let mut prev = it.contact(1e-7);
            let mut worst: f64 = 0.0;
            for i in 0..n {
                let th = 1e-7 * (0.5f64 / 1e-7).powf(i as f64 / (n - 1) as f64);
                let warm = it.contact_after(th, &prev);
                let cold = it.contact(th);
                prev = warm;
                assert!(
                    (warm.af - cold.af).abs() <= 1e-12 * cold.af,
                    "{shape:?} fm={fm} theta={th}: af {} vs {}",
                    warm.af,
                    cold.af
                );
                // af' after a Taylor finish is first order in the last step:
                // measured below 1.2e-10 relative except beside the square-root
                // points of a thin ring's inner edge (1.4e-9).
                let rel = (warm.daf - cold.daf).abs() / cold.daf.abs();
                worst = worst.max(rel);
                assert!(
                    rel <= 1e-8,
                    "{shape:?} fm={fm} theta={th}: af' {} vs {}",
                    warm.daf,
                    cold.daf
                );
                if i % 97 == 0 {
                    let [nq, _] = resultants(&shape, kn, fm, th, warm.a);
                    assert!(
                        (nq - w).abs() < 1e-12 * w,
                        "{shape:?} fm={fm} theta={th}: residual {:e}",
                        (nq - w).abs() / w
                    );
                }
            }
            println!("{shape:?} fm={fm:e}: worst relative af' difference warm/cold {worst:e}");
        }
    }
}
