//! `daf/dN` of a crushing bed's contact under an apparent weight `N`
//! (docs/model.md §6.1): [`Interface::contact_loaded`] gives `xel`, the
//! centroid of the elastic part of the contact, for `daf/dN = (xel - af)/N`.
//! Checked against a central difference of `af` in `N` (Richardson
//! extrapolated, its error some 1e-11), from a cold start and from warm
//! starts near the answer, where the solve ends on a Taylor step.

use rocking::{Interface, Law, Shape};

/// The Dharahara's base (a ring of radii 3.99 and 2.12 m under 24.0 MN,
/// `examples/support/dharahara.rs`) on two of its crushing beds, and a
/// solid rectangle and disc of the same weight.
fn beds() -> Vec<(&'static str, Interface)> {
    let w = 24003.94e3;
    let ring = Shape::HollowCircle { ro: 3.99, ri: 2.12 };
    let plastic = |kn: f64, fm: f64| Law::ElastoPlastic { kn, fm };
    vec![
        ("F1350_fm15", Interface::new(ring, plastic(1.35e9, 15e6), w)),
        ("I1500_fm15", Interface::new(ring, plastic(1.5e12, 15e6), w)),
        ("F340_fm5", Interface::new(ring, plastic(3.4e8, 5e6), w)),
        (
            "rectangle",
            Interface::new(
                Shape::SolidRectangle { b: 8.0, l: 4.0 },
                plastic(1e9, 5e6),
                w,
            ),
        ),
        (
            "disc",
            Interface::new(Shape::SolidCircle { ro: 3.99 }, plastic(1e10, 5e6), w),
        ),
    ]
}

/// `daf/dN` by central differences of step `h` and `2h`, Richardson
/// extrapolated, m/N.
fn difference(it: &Interface, phi: f64, n: f64) -> f64 {
    let af = |nn: f64| it.contact_loaded(phi, nn, f64::NAN).0.af;
    let h = 1e-4 * n;
    let d1 = (af(n + h) - af(n - h)) / (2.0 * h);
    let d2 = (af(n + 2.0 * h) - af(n - 2.0 * h)) / (4.0 * h);
    (4.0 * d1 - d2) / 3.0
}

#[test]
fn xel_gives_daf_dn_from_any_start() {
    let mut worst = (0.0f64, String::new());
    let mut crushed = 0;
    for (name, it) in beds() {
        let w = 24003.94e3;
        for phi in [0.005, 0.02, 0.06] {
            for ratio in [0.5, 0.8, 1.0, 1.1] {
                let n = ratio * w;
                let (cold, _) = it.contact_loaded(phi, n, f64::NAN);
                let fd = difference(&it, phi, n);
                // warm starts from 1e-6 to 1e-2 of a away: one to three
                // iterations, the last a Taylor step
                for rel in [0.0, 1e-6, -1e-5, 1e-4, -1e-3, 1e-2] {
                    let hint = if rel == 0.0 {
                        f64::NAN
                    } else {
                        cold.a * (1.0 + rel)
                    };
                    let (c, xel) = it.contact_loaded(phi, n, hint);
                    let exact = (xel - c.af) / n;
                    let err = (exact / fd - 1.0).abs();
                    assert!(
                        err.is_finite(),
                        "{name} phi {phi} N/W {ratio}: {exact} vs {fd}"
                    );
                    if err > worst.0 {
                        worst = (err, format!("{name} phi {phi} N/W {ratio} hint {rel:e}"));
                    }
                }
                crushed += usize::from(matches!(
                    cold.regime,
                    rocking::Regime::PartialCrushing | rocking::Regime::FullCrushing
                ));
            }
        }
    }
    eprintln!(
        "daf/dN = (xel - af)/N against the difference: worst {:.2e} ({}), {crushed} crushed of 60",
        worst.0, worst.1
    );
    assert!(crushed >= 30, "the cases must crush: {crushed}");
    assert!(worst.0 <= 1e-9, "{:e} at {}", worst.0, worst.1);
}
