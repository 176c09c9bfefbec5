//! The bed's reaction under a round section tilted about any horizontal
//! axis (docs/model.md §11.1) against fibres summed over the disc or the
//! ring, written here without the planar law's closed forms: a polar grid
//! of springs, each carrying `min(kn delta, fm)` where it is closed, the
//! closure plane turned by a rotation vector about an arbitrary horizontal
//! axis, its offset found by bisection so that the fibres carry `N`.

use rocking::interface::{RoundBed, RoundReaction};
use rocking::{Interface, Law, Regime, Shape};

/// Fibres over a ring `ri <= r <= ro` (`ri = 0`: the disc), at the
/// midpoints of `nr` rings and `nt` sectors turned by `turn` rad off `+x`
/// (so that no tilt below runs along a line of the grid).
struct Fibres {
    x: Vec<f64>,
    y: Vec<f64>,
    area: Vec<f64>,
}

impl Fibres {
    fn new(ro: f64, ri: f64, nr: usize, nt: usize, turn: f64) -> Fibres {
        let (mut x, mut y, mut area) = (vec![], vec![], vec![]);
        let dr = (ro - ri) / nr as f64;
        let dt = std::f64::consts::TAU / nt as f64;
        for i in 0..nr {
            let r = ri + (i as f64 + 0.5) * dr;
            for j in 0..nt {
                let t = turn + (j as f64 + 0.5) * dt;
                x.push(r * t.cos());
                y.push(r * t.sin());
                // the midpoint rule is exact for the ring's area r dr dt
                area.push(r * dr * dt);
            }
        }
        Fibres { x, y, area }
    }

    /// Force (N), moment about the centre (N m, `sum p x (0, 0, f)`), closed
    /// and crushed areas (m²) with the closure `delta0 - (rho x p)_z` (m).
    fn sums(&self, rho: [f64; 2], delta0: f64, kn: f64, fm: f64) -> Sums {
        let mut s = Sums::default();
        for k in 0..self.x.len() {
            let (px, py, da) = (self.x[k], self.y[k], self.area[k]);
            // a small rotation rho moves p down by -(rho x p)_z
            let delta = delta0 - (rho[0] * py - rho[1] * px);
            if delta <= 0.0 {
                continue;
            }
            let elastic = kn * delta;
            let f = elastic.min(fm) * da;
            s.n += f;
            s.m[0] += py * f;
            s.m[1] -= px * f;
            s.closed += da;
            if elastic >= fm {
                s.crushed += da;
            }
        }
        s
    }

    /// The closure at the centre (m) at which the fibres carry `n`, by
    /// bisection (the force grows with it), and the sums there.
    fn equilibrium(&self, rho: [f64; 2], n: f64, kn: f64, fm: f64, ro: f64) -> (f64, Sums) {
        let theta = rho[0].hypot(rho[1]);
        let total: f64 = self.area.iter().sum();
        // everything open below, everything closed at N/A or more above
        let (mut lo, mut hi) = (-theta * ro, n / (kn * total) + theta * ro);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.sums(rho, mid, kn, fm).n > n {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let d0 = 0.5 * (lo + hi);
        (d0, self.sums(rho, d0, kn, fm))
    }
}

#[derive(Default, Debug)]
struct Sums {
    n: f64,
    m: [f64; 2],
    closed: f64,
    crushed: f64,
}

/// The errors of one case, relative: the force at the planar law's plane
/// (to N), the moment about the axis across the tilt (the planar one) and
/// about the tilt's direction `d` (zero) (to N R), the closed and crushed
/// areas (to A).
#[derive(Clone, Copy, Debug, Default)]
struct Errors {
    n: f64,
    m_planar: f64,
    m_about_d: f64,
    closed: f64,
    crushed: f64,
}

impl Errors {
    fn max(self, o: Errors) -> Errors {
        Errors {
            n: self.n.max(o.n),
            m_planar: self.m_planar.max(o.m_planar),
            m_about_d: self.m_about_d.max(o.m_about_d),
            closed: self.closed.max(o.closed),
            crushed: self.crushed.max(o.crushed),
        }
    }
}

struct Case {
    shape: Shape,
    law: Law,
    /// Apparent weight, N.
    n: f64,
    /// The tilt as a rotation vector about a horizontal axis, rad.
    rho: [f64; 2],
}

fn compare(case: &Case, fibres: &Fibres) -> (Errors, RoundReaction) {
    let (ro, a_sec) = match case.shape {
        Shape::SolidCircle { ro } => (ro, case.shape.area()),
        Shape::HollowCircle { ro, .. } => (ro, case.shape.area()),
        _ => unreachable!(),
    };
    let (kn, fm) = match case.law {
        Law::Elastic { kn } => (kn, f64::INFINITY),
        Law::ElastoPlastic { kn, fm } => (kn, fm),
        Law::Rigid => unreachable!(),
    };
    // the interface is built at another weight: the reaction is asked at N
    let bed = RoundBed::new(Interface::new(case.shape, case.law, 0.8 * case.n)).unwrap();
    let theta = case.rho[0].hypot(case.rho[1]);
    // the lean: d = rho_hat x z, e = sin(theta) d
    let d = [case.rho[1] / theta, -case.rho[0] / theta];
    let r = bed
        .reaction([theta.sin() * d[0], theta.sin() * d[1]], case.n)
        .unwrap();
    // the force of the fibres at the planar law's plane, delta0 = theta (a - R)
    let at_law = fibres.sums(case.rho, theta * (r.contact.a - ro), kn, fm);
    let (_, s) = fibres.equilibrium(case.rho, case.n, kn, fm, ro);
    let across = [-d[1], d[0]];
    let dot = |u: [f64; 2], v: [f64; 2]| u[0] * v[0] + u[1] * v[1];
    let scale = case.n * ro;
    let errors = Errors {
        n: (at_law.n - case.n).abs() / case.n,
        m_planar: (dot(s.m, across) - dot(r.moment, across)).abs() / scale,
        m_about_d: (dot(s.m, d) - dot(r.moment, d)).abs() / scale,
        closed: (s.closed - r.contact_area).abs() / a_sec,
        crushed: (s.crushed - r.crushed_area).abs() / a_sec,
    };
    (errors, r)
}

/// Tilts about axes all round, from below the heel's opening to far into
/// crushing, under light and heavy apparent weights, on a disc and a ring.
fn cases() -> Vec<Case> {
    let shapes = [
        Shape::SolidCircle { ro: 0.5 },
        Shape::HollowCircle { ro: 3.99, ri: 2.12 },
    ];
    let mut out = vec![];
    let mut k = 0;
    for shape in shapes {
        let (a_sec, d) = (shape.area(), shape.depth());
        let kn = 2e9;
        let fm = 5e6;
        for plastic in [false, true] {
            // N as a fraction of fm A: light (crushing after the heel opens),
            // heavy (fm A < 2 N: the toe crushes with the heel closed)
            for nu in [0.15, 0.4, 0.7] {
                let n = nu * fm * a_sec;
                let law = if plastic {
                    Law::ElastoPlastic { kn, fm }
                } else {
                    Law::Elastic { kn }
                };
                // the heel opens at 2N/(kn A D) while the toe is elastic
                let theta_jo = 2.0 * n / (kn * a_sec * d);
                for mult in [0.5, 1.7, 4.0, 13.0, 50.0] {
                    for _ in 0..2 {
                        // azimuths spread by the golden angle
                        let beta = 0.3 + 2.399_963_229_728_653 * k as f64;
                        k += 1;
                        let theta = mult * theta_jo;
                        out.push(Case {
                            shape,
                            law,
                            n,
                            rho: [theta * beta.cos(), theta * beta.sin()],
                        });
                    }
                }
            }
        }
    }
    out
}

/// The worst errors over the cases with `nr x nt` fibres, and the regimes met.
fn worst(cases: &[Case], nr: usize, nt: usize) -> (Errors, Vec<Regime>) {
    let mut worst = Errors::default();
    let mut regimes = vec![];
    let mut grids: Vec<(Shape, Fibres)> = vec![];
    for c in cases {
        if !grids.iter().any(|(s, _)| *s == c.shape) {
            let (ro, ri) = match c.shape {
                Shape::SolidCircle { ro } => (ro, 0.0),
                Shape::HollowCircle { ro, ri } => (ro, ri),
                _ => unreachable!(),
            };
            grids.push((c.shape, Fibres::new(ro, ri, nr, nt, 0.1)));
        }
        let fibres = &grids.iter().find(|(s, _)| *s == c.shape).unwrap().1;
        let (e, r) = compare(c, fibres);
        worst = worst.max(e);
        if !regimes.contains(&r.regime()) {
            regimes.push(r.regime());
        }
    }
    (worst, regimes)
}

#[test]
fn the_planar_law_along_the_tilt_is_the_fibres_sum() {
    let cases = cases();
    let (coarse, regimes) = worst(&cases, 40, 160);
    let (fine, _) = worst(&cases, 80, 320);
    println!("{} cases, worst relative errors:", cases.len());
    println!("fibres      N        M planar  M about d closed A  crushed A");
    for (name, e) in [("40x160", coarse), ("80x320", fine)] {
        println!(
            "{name:8} {:9.2e} {:9.2e} {:9.2e} {:9.2e} {:9.2e}",
            e.n, e.m_planar, e.m_about_d, e.closed, e.crushed
        );
    }
    for r in [
        Regime::FullContact,
        Regime::Partial,
        Regime::PartialCrushing,
        Regime::FullCrushing,
    ] {
        assert!(regimes.contains(&r), "no case in {r:?}: {regimes:?}");
    }
    // the stress is continuous with kinks along lines (the neutral line,
    // the plastic edge): the midpoint rule's error is second order in the
    // fibre size for the force and the moments; the areas count whole
    // fibres on either side of a line, first order at worst
    let rate = |c: f64, f: f64| (c / f).log2();
    for (what, c, f, tol, order) in [
        ("N", coarse.n, fine.n, 4e-4, 1.8),
        ("M planar", coarse.m_planar, fine.m_planar, 1.5e-4, 1.8),
        ("M about d", coarse.m_about_d, fine.m_about_d, 4e-5, 1.8),
        ("closed area", coarse.closed, fine.closed, 4e-3, 0.9),
        ("crushed area", coarse.crushed, fine.crushed, 2e-3, 0.9),
    ] {
        println!("{what}: order {:.2}", rate(c, f));
        assert!(f <= tol, "{what}: {f:.3e} > {tol:.0e} with 80 x 320 fibres");
        assert!(
            rate(c, f) >= order,
            "{what}: the error fell from {c:.3e} to {f:.3e}, order {:.2} < {order}",
            rate(c, f)
        );
    }
}

/// The moment's derivatives the reaction reports against central
/// differences of the moment itself, along and across the tilt, and in `N`.
#[test]
fn the_stiffness_is_the_moments_derivative() {
    for (shape, law) in [
        (Shape::SolidCircle { ro: 0.5 }, Law::Elastic { kn: 2e9 }),
        (
            Shape::HollowCircle { ro: 3.99, ri: 2.12 },
            Law::ElastoPlastic { kn: 2e9, fm: 5e6 },
        ),
    ] {
        let a_sec = shape.area();
        let n = 0.4 * 5e6 * a_sec;
        let bed = RoundBed::new(Interface::new(shape, law, n)).unwrap();
        let theta_jo = 2.0 * n / (2e9 * a_sec * shape.depth());
        for (k, mult) in [0.3, 2.5, 20.0].into_iter().enumerate() {
            let beta = 1.1 + 2.0 * k as f64;
            let rho = [mult * theta_jo * beta.cos(), mult * theta_jo * beta.sin()];
            let moment = |rho: [f64; 2], n: f64| {
                let t = rho[0].hypot(rho[1]);
                let e = [t.sin() * rho[1] / t, -t.sin() * rho[0] / t];
                bed.reaction(e, n).unwrap().moment
            };
            let r = {
                let t = rho[0].hypot(rho[1]);
                bed.reaction([t.sin() * rho[1] / t, -t.sin() * rho[0] / t], n)
                    .unwrap()
            };
            let h = 1e-6 * r.theta;
            let scale = n * bed.radius() / r.theta;
            for j in 0..2 {
                let mut up = rho;
                let mut down = rho;
                up[j] += h;
                down[j] -= h;
                let (mu, md) = (moment(up, n), moment(down, n));
                for i in 0..2 {
                    let fd = (mu[i] - md[i]) / (2.0 * h);
                    let err = (fd - r.stiffness[i][j]).abs() / scale;
                    assert!(
                        err <= 1e-6,
                        "{shape:?} x{mult}: dM{i}/drho{j} {fd} vs {}",
                        r.stiffness[i][j]
                    );
                }
            }
            let dn = 1e-6 * n;
            let (mu, md) = (moment(rho, n + dn), moment(rho, n - dn));
            for i in 0..2 {
                let fd = (mu[i] - md[i]) / (2.0 * dn);
                assert!(
                    (fd - r.moment_dn[i]).abs() <= 1e-6 * bed.radius(),
                    "{shape:?} x{mult}: dM{i}/dN {fd} vs {}",
                    r.moment_dn[i]
                );
            }
        }
    }
}

/// Upright the bed carries N uniformly: no moment, the whole section
/// closed, the stiffness `-kn Is` every way; the rigid bed puts N at the toe.
#[test]
fn upright_and_rigid() {
    let shape = Shape::HollowCircle { ro: 3.99, ri: 2.12 };
    let kn = 2e9;
    let n = 2e7;
    let bed = RoundBed::new(Interface::new(shape, Law::ElastoPlastic { kn, fm: 5e6 }, n)).unwrap();
    let r = bed.reaction([0.0, 0.0], n).unwrap();
    assert_eq!(r.moment, [0.0, 0.0]);
    assert_eq!(r.regime(), Regime::FullContact);
    assert!((r.contact_area - shape.area()).abs() <= 1e-12 * shape.area());
    let k = kn * shape.second_moment();
    for (i, row) in r.stiffness.iter().enumerate() {
        for (j, &s) in row.iter().enumerate() {
            let expected = if i == j { -k } else { 0.0 };
            assert!(
                (s - expected).abs() <= 1e-12 * k,
                "{i}{j}: {s} vs {expected}"
            );
        }
    }
    let rigid = RoundBed::new(Interface::new(shape, Law::Rigid, n)).unwrap();
    let (t, psi) = (0.01f64, 2.0f64);
    let r = rigid
        .reaction([t.sin() * psi.cos(), t.sin() * psi.sin()], n)
        .unwrap();
    // N at the toe R d: the moment -N R (z x d)
    let expected = [n * 3.99 * psi.sin(), -n * 3.99 * psi.cos()];
    for (i, want) in expected.into_iter().enumerate() {
        assert!((r.moment[i] - want).abs() <= 1e-9 * n * 3.99);
        assert!((r.resultant[i] - r.toe[i]).abs() <= 1e-15 * 3.99);
    }
    assert_eq!(r.contact_area, 0.0);
}

/// The errors name the offending variable.
#[test]
fn errors_name_the_variable() {
    let shape = Shape::SolidCircle { ro: 0.5 };
    let fm = 5e6;
    let n = 0.3 * fm * shape.area();
    let bed = RoundBed::new(Interface::new(shape, Law::ElastoPlastic { kn: 2e9, fm }, n)).unwrap();
    assert_eq!(bed.reaction([0.6, 0.8], n).unwrap_err().variable, "e");
    assert_eq!(bed.reaction([0.01, 0.0], 0.0).unwrap_err().variable, "N");
    assert_eq!(
        bed.reaction([0.01, 0.0], fm * shape.area())
            .unwrap_err()
            .variable,
        "N"
    );
    assert_eq!(
        bed.reaction_toward(0.01, [1.0, 1.0], n)
            .unwrap_err()
            .variable,
        "d"
    );
    let square = Shape::SolidRectangle { b: 1.0, l: 1.0 };
    let err = RoundBed::new(Interface::new(square, Law::Elastic { kn: 2e9 }, n)).unwrap_err();
    assert_eq!(err.variable, "shape");
}
