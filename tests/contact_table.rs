//! `ContactTable` (src/interface/table.rs) against brute force: the
//! equilibrium solve at every rotation of dense grids (log-spaced and
//! uniform, 40 000 rotations from the first iterative regime to 0.2 rad), for
//! the four shapes and the three laws, crushing starting in partial contact
//! and in full contact, and a stiff interface (the rotations span decades).

use rocking::{ContactTable, Interface, Law, Shape};

const PHI_MAX: f64 = 0.2;

/// (name, shape, weight N, kn Pa/m, fm Pa for crushing in partial contact, fm for crushing in full contact)
fn bodies() -> Vec<(&'static str, Shape, f64, f64, f64, f64)> {
    vec![
        (
            "solid rectangle",
            Shape::SolidRectangle { b: 1.0, l: 1.0 },
            1e5,
            1e8,
            5e5,
            1.5e5,
        ),
        (
            "hollow rectangle",
            Shape::HollowRectangle {
                b: 1.0,
                l: 1.0,
                t: 0.15,
            },
            5e4,
            1e8,
            3e5,
            1.2e5,
        ),
        (
            "solid circle",
            Shape::SolidCircle { ro: 0.5 },
            1e5,
            1e8,
            4e5,
            1.6e5,
        ),
        (
            "hollow circle",
            Shape::HollowCircle { ro: 3.99, ri: 2.12 },
            2.4e7,
            1.7e8,
            5e6,
            1e6,
        ),
        (
            "hollow circle, stiff",
            Shape::HollowCircle { ro: 3.99, ri: 2.12 },
            2.4e7,
            1.5e10,
            2e6,
            1e6,
        ),
    ]
}

fn grid(lo: f64, hi: f64) -> impl Iterator<Item = f64> {
    let n = 20_000;
    let log = (0..=n).map(move |i| lo * (hi / lo).powf(i as f64 / n as f64));
    let uniform = (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64);
    log.chain(uniform)
}

/// Largest relative differences (af, af', a, a') of the table from the
/// solver; a' relative to the largest |a'| within a factor 1.01 of the
/// rotation (it passes through 0 when crushing starts in full contact).
fn worst(it: &Interface, table: &ContactTable) -> [f64; 4] {
    let (lo, hi) = table.range();
    let mut err = [0.0f64; 4];
    let mut served = 0;
    for phi in grid(lo, hi) {
        let Some(t) = table.contact(it, phi) else {
            continue;
        };
        served += 1;
        let c = it.contact(phi);
        assert_eq!(t.regime, c.regime, "regime at {phi}");
        let da_scale = [phi / 1.01, phi, phi * 1.01]
            .iter()
            .map(|&p| it.contact(p).da.abs())
            .fold(0.0, f64::max);
        for (e, (x, y, scale)) in err.iter_mut().zip([
            (t.af, c.af, c.af.abs()),
            (t.daf, c.daf, c.daf.abs()),
            (t.a, c.a, c.a.abs()),
            (t.da, c.da, da_scale),
        ]) {
            *e = e.max((x - y).abs() / scale);
        }
    }
    assert!(
        served > 36_000,
        "the table answered only {served} of 40 002 rotations"
    );
    err
}

#[test]
fn table_agrees_with_the_solve_on_dense_grids() {
    for (name, shape, w, kn, fm_partial, fm_full) in bodies() {
        let rigid = Interface::new(shape, Law::Rigid, w);
        assert!(
            ContactTable::new(&rigid, PHI_MAX).is_none(),
            "{name}: rigid"
        );
        for law in [
            Law::Elastic { kn },
            Law::ElastoPlastic { kn, fm: fm_partial },
            Law::ElastoPlastic { kn, fm: fm_full },
        ] {
            let it = Interface::new(shape, law, w);
            let table = ContactTable::new(&it, PHI_MAX).expect("a table");
            let (lo, hi) = table.range();
            // whole octaves from the first iterative regime, the last one
            // reaching PHI_MAX
            let phi0 = it.theta_jo().min(it.theta_c());
            let octaves = (hi / lo).log2();
            assert!(
                lo == phi0 && hi >= PHI_MAX && hi < 2.0 * PHI_MAX && octaves == octaves.round(),
                "{name} {law:?}: range {lo}..{hi}"
            );
            let (pieces, open) = table.pieces();
            let err = worst(&it, &table);
            println!("{name:22} {law:?}: {pieces} pieces ({open} left to the solver), max rel. error af {:.1e}, af' {:.1e}, a {:.1e}, a' {:.1e}", err[0], err[1], err[2], err[3]);
            assert!(
                err[0] <= 1e-12 && err[2] <= 1e-12,
                "{name} {law:?}: af, a: {err:?}"
            );
            // the solver's own af' is good to 1e-10 (1e-9 beside an inner edge,
            // docs/interface.md), its a' to about 3e-8
            assert!(
                err[1] <= 2e-9 && err[3] <= 3e-7,
                "{name} {law:?}: af', a': {err:?}"
            );
        }
    }
}

