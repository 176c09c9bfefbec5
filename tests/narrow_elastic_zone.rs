//! The contact's slope `af'` and curvature `af''` on the Dharahara's ring
//! (docs/dharahara.md: `Ro = 3.99 m`, `Ri = 2.12 m`, `W = 24 MN`) in
//! partial crushing, where the elastic zone `[xp, a]` is a sliver of 2 to
//! 3 cm just beyond the hole's far edge `Ro + Ri` (`xp - (Ro + Ri)` about
//! 1 % of the depth): against a quadrature of the stress profile written
//! independently of the code (`tests/support/base.rs`).

mod support;

use rocking::{Interface, Law, Regime, Shape};
use support::base::{resultants, width, width_breaks};
use support::integrate_pieces;

const RING: Shape = Shape::HollowCircle { ro: 3.99, ri: 2.12 };
const WEIGHT: f64 = 24.0e6;
const KN: f64 = 5e9;

/// `fm = 1.3 W/A` (Pa): the toe crushes before the heel opens, and the
/// plastic edge settles beyond the hole.
fn fm() -> f64 {
    1.3 * WEIGHT / RING.area()
}

/// `(a, xp, af')` at `phi` (rad) by quadrature: `a` by bisection to the last
/// bit on the force of `tests/support/base.rs` over partial crushing's
/// bracket `[a1, D]`, then `af' = -(kn/W) Jc` (docs/model.md §2) with the
/// elastic zone's second moment `Jc` integrated about its centroid, so
/// that no digits cancel (tanh-sinh, relative error ~1e-15).
fn reference(phi: f64) -> (f64, f64, f64) {
    let (kn, fm) = (KN, fm());
    let a1 = fm / (kn * phi);
    let (mut lo, mut hi) = (a1, RING.depth());
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if resultants(&RING, kn, fm, phi, mid)[0] > WEIGHT {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let a = 0.5 * (lo + hi);
    let xp = a - a1;
    let breaks = width_breaks(&RING);
    let moment = |f: &dyn Fn(f64) -> f64| {
        integrate_pieces(&|x| f(x) * width(&RING, x), xp, a, &breaks, 1e-16)
    };
    let centroid = xp + moment(&|x| x - xp) / moment(&|_| 1.0);
    let jc = moment(&|x| (x - centroid) * (x - centroid));
    (a, xp, -kn * jc / WEIGHT)
}

/// Rotations (rad) across the stretch where the elastic zone is a sliver
/// (`a - xp < 0.05 xp`) within four zone lengths of the hole's edge
/// `Ro + Ri`: there `S_k(a) - S_k(xp)` cancels six digits or more.
fn sliver_rotations() -> Vec<f64> {
    let edge = 3.99 + 2.12;
    let (first, last): (f64, f64) = (4e-3, 8.1e-3);
    let n = 24;
    let out: Vec<f64> = (0..=n)
        .map(|k| first * (last / first).powf(k as f64 / n as f64))
        .filter(|&phi| {
            let (a, xp, _) = reference(phi);
            let zone = a - xp;
            xp > edge && xp - edge < 4.0 * zone && zone < 0.05 * xp
        })
        .collect();
    assert!(
        out.len() > n / 2,
        "only {} rotations on the stretch",
        out.len()
    );
    out
}

/// `af'` to 1e-11 relative. The code's solve stops at `|N - W| <= 2e-15 W`,
/// which leaves `a` up to `2e-15 W / (fm w(xp))`, about 1e-14 m, off; that
/// moves `Jc` (cubic in the zone length `l`) by `3 da / l`, 1.5e-12 for
/// `l = 2 cm`; the reference is good to ~1e-13. Taking the zone's moments
/// as differences of the cumulative ones lost up to 1.5e-7 here.
#[test]
fn af_slope_keeps_full_precision_on_a_sliver_beside_the_rings_hole() {
    let it = Interface::new(RING, Law::ElastoPlastic { kn: KN, fm: fm() }, WEIGHT);
    let mut worst: f64 = 0.0;
    for phi in sliver_rotations() {
        let c = it.contact(phi);
        assert_eq!(c.regime, Regime::PartialCrushing);
        let (_, _, daf) = reference(phi);
        let e = ((c.daf - daf) / daf).abs();
        assert!(e < 1e-11, "phi = {phi:e}: af' {} vs {daf} ({e:.1e})", c.daf);
        worst = worst.max(e);
    }
    println!("af' worst relative error {worst:.1e}");
}

/// `af''` to 1e-9 relative against Richardson-extrapolated 5-point central
/// differences of the reference's `af'`, steps `1e-2 phi` and `5e-3 phi`:
/// the step `5e-3 phi` alone is within 2e-8 of the extrapolation, which
/// removes that O(h^4) term and leaves O(h^6) (~1e-12 here) and the
/// reference's rounding divided by the step (~3e-11).
#[test]
fn af_curvature_matches_differences_of_the_quadrature_on_a_sliver() {
    let it = Interface::new(RING, Law::ElastoPlastic { kn: KN, fm: fm() }, WEIGHT);
    let slope = |phi: f64| reference(phi).2;
    let mut worst: f64 = 0.0;
    for phi in sliver_rotations().into_iter().step_by(3) {
        let diff = |h: f64| {
            (-slope(phi + 2.0 * h) + 8.0 * slope(phi + h) - 8.0 * slope(phi - h)
                + slope(phi - 2.0 * h))
                / (12.0 * h)
        };
        let coarse = diff(1e-2 * phi);
        let fine = diff(5e-3 * phi);
        let exact = (16.0 * fine - coarse) / 15.0;
        let (af2, _) = it.second_derivatives(&it.contact(phi));
        let e = ((af2 - exact) / exact).abs();
        assert!(e < 1e-9, "phi = {phi:e}: af'' {af2} vs {exact} ({e:.1e})");
        worst = worst.max(e);
    }
    println!("af'' worst relative error {worst:.1e}");
}
