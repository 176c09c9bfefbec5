//! Parameter validation (docs/model.md §5) and the derived body values (§1, §3)
//! against closed forms.

use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Params, Restitution};

fn err_of(p: Params) -> (String, String) {
    let e = p.build().expect_err("should be refused");
    (e.variable.to_string(), e.to_string())
}

#[test]
fn each_invalid_parameter_is_named() {
    let base = Params::default();
    let cases: Vec<(&str, Params)> = vec![
        ("B", Params { b: 0.0, ..base }),
        ("L", Params { l: -1.0, ..base }),
        (
            "B",
            Params {
                b: f64::NAN,
                ..base
            },
        ),
        (
            "t",
            Params {
                shape: ShapeKind::HollowRectangle,
                t: 0.25,
                ..base
            },
        ),
        (
            "t",
            Params {
                shape: ShapeKind::HollowRectangle,
                t: 0.0,
                ..base
            },
        ),
        (
            "Ro",
            Params {
                shape: ShapeKind::SolidCircle,
                ro: 0.0,
                ..base
            },
        ),
        (
            "Ri",
            Params {
                shape: ShapeKind::HollowCircle,
                ro: 0.5,
                ri: 0.5,
                ..base
            },
        ),
        (
            "Ri",
            Params {
                shape: ShapeKind::HollowCircle,
                ri: -0.1,
                ..base
            },
        ),
        ("H", Params { h: 0.0, ..base }),
        (
            "rho",
            Params {
                rho: f64::INFINITY,
                ..base
            },
        ),
        (
            "W",
            Params {
                mass_model: MassKind::Lumped,
                w: 0.0,
                ..base
            },
        ),
        (
            "hG",
            Params {
                mass_model: MassKind::Lumped,
                hg: -2.0,
                ..base
            },
        ),
        (
            "Ic",
            Params {
                mass_model: MassKind::Lumped,
                ic: -1.0,
                ..base
            },
        ),
        ("kn", Params { kn: 0.0, ..base }),
        (
            "kn",
            Params {
                interface: LawKind::Elastic,
                kn: -5.0,
                ..base
            },
        ),
        ("fm", Params { fm: 0.0, ..base }),
        // W = 22 kN on A = 0.5 m²: fm*A <= W crushes at rest
        ("fm", Params { fm: 4.0e4, ..base }),
        // kn Is = kn/96 must exceed W hG = 27.6 kN m
        ("kn", Params { kn: 2.0e6, ..base }),
        (
            "eta",
            Params {
                restitution: Restitution::Given,
                eta: 1.5,
                ..base
            },
        ),
        (
            "eta",
            Params {
                restitution: Restitution::Given,
                eta: -0.1,
                ..base
            },
        ),
        ("g", Params { g: 0.0, ..base }),
        (
            "theta",
            Params {
                theta0: 0.5,
                ..base
            },
        ),
        (
            "omega",
            Params {
                omega0: f64::NAN,
                ..base
            },
        ),
    ];
    for (name, p) in cases {
        let (var, msg) = err_of(p);
        assert_eq!(var, name, "{msg}");
        assert!(msg.starts_with(&format!("{name} = ")), "{msg}");
        assert!(
            msg.contains("must"),
            "the message states the condition: {msg}"
        );
    }
}

#[test]
fn conditions_are_sharp() {
    let base = Params::default();
    let area = 0.5;
    let w = 1800.0 * 9.81 * area * 2.5;
    // just above and below W = fm A
    assert!(Params {
        fm: w / area * 1.000001,
        ..base
    }
    .build()
    .is_ok());
    assert!(Params {
        fm: w / area * 0.999999,
        ..base
    }
    .build()
    .is_err());
    // kn Is = W hG
    let is = 1.0 * 0.5f64.powi(3) / 12.0;
    let kn0 = w * 1.25 / is;
    assert!(Params {
        kn: kn0 * 1.000001,
        fm: f64::INFINITY,
        ..base
    }
    .build()
    .is_ok());
    assert!(Params {
        kn: kn0 * 0.999999,
        fm: f64::INFINITY,
        ..base
    }
    .build()
    .is_err());
    // the rigid law ignores kn and fm
    assert!(Params {
        interface: LawKind::Rigid,
        kn: -1.0,
        fm: 0.0,
        ..base
    }
    .build()
    .is_ok());
}

#[test]
fn derived_body_values_match_closed_forms() {
    // prism: solid block B x L x H
    let p = Params {
        interface: LawKind::Rigid,
        ..Params::default()
    };
    let m = p.build().unwrap();
    let (b, l, h, rho, g) = (p.b, p.l, p.h, p.rho, p.g);
    let mass = rho * b * l * h;
    assert!((m.body.mass / mass - 1.0).abs() < 1e-14);
    assert!((m.body.weight / (mass * g) - 1.0).abs() < 1e-14);
    let r0 = ((b / 2.0).powi(2) + (h / 2.0).powi(2)).sqrt();
    assert!((m.body.r0 / r0 - 1.0).abs() < 1e-14);
    assert!((m.body.alpha - (b / h).atan()).abs() < 1e-15);
    // IO of a block about its toe edge: m (B² + H²) / 3
    assert!((m.body.io / (mass * (b * b + h * h) / 3.0) - 1.0).abs() < 1e-14);
    // Housner, solid block: 1 - 1.5 sin² alpha
    let a = m.body.alpha;
    assert!((m.eta - (1.0 - 1.5 * a.sin().powi(2))).abs() < 1e-14);
    // rigid: thetaOv = alpha
    assert_eq!(m.theta_ov, m.body.alpha);
}

#[test]
fn overturning_rotation_is_the_first_root_of_hw() {
    for (law, fm) in [
        (LawKind::Elastic, f64::INFINITY),
        (LawKind::ElastoPlastic, 5e5),
    ] {
        let p = Params {
            interface: law,
            fm,
            ..Params::default()
        };
        let m = p.build().unwrap();
        let ov = m.theta_ov;
        assert!(
            ov > 0.0 && ov < m.body.alpha,
            "thetaOv {ov} alpha {}",
            m.body.alpha
        );
        // MR > 0 on a fine grid below thetaOv, < 0 just above, zero at it
        for i in 1..2000 {
            let phi = ov * i as f64 / 2000.0;
            assert!(
                m.restoring_moment(phi).0 > 0.0,
                "MR <= 0 at {phi} < thetaOv {ov}"
            );
        }
        let (mr, _) = m.restoring_moment(ov);
        assert!(
            mr.abs() < 1e-9 * m.body.weight * m.body.b,
            "MR(thetaOv) = {mr}"
        );
        assert!(m.restoring_moment(ov * 1.001).0 < 0.0);
    }
}

#[test]
fn restoring_moment_derivative_matches_differences() {
    let m = Params::default().build().unwrap();
    for i in 1..100 {
        let phi = m.theta_ov * i as f64 / 100.0;
        let h = 1e-6 * phi;
        let fd = (m.restoring_moment(phi + h).0 - m.restoring_moment(phi - h).0) / (2.0 * h);
        let (_, d) = m.restoring_moment(phi);
        assert!(
            (fd - d).abs() < 1e-5 * d.abs() + 1e-6 * m.body.weight * m.body.b / phi * 1e-6,
            "{phi}: {d} vs {fd}"
        );
    }
}

#[test]
fn lumped_body_values_match_closed_forms() {
    // The Dharahara tower of docs/model.md §4 as a lumped body on a hollow circle.
    let (ro, ri, w, hg, g) = (3.99, 2.12, 24003.94e3, 30.20, 9.81);
    let m_ = w / g;
    let ic = m_ * ((2.0 * hg) * (2.0 * hg) / 12.0 + (ro * ro + ri * ri) / 4.0);
    let p = Params {
        shape: ShapeKind::HollowCircle,
        ro,
        ri,
        mass_model: MassKind::Lumped,
        w,
        hg,
        ic,
        kn: 2e9,
        fm: 2e6,
        ..Params::default()
    };
    let m = p.build().unwrap();
    assert!((m.body.mass / m_ - 1.0).abs() < 1e-15);
    let r0 = (ro * ro + hg * hg).sqrt();
    assert!((m.body.r0 / r0 - 1.0).abs() < 1e-15);
    assert!((m.body.alpha - (ro / hg).atan()).abs() < 1e-15);
    assert!((m.body.io / (ic + m_ * r0 * r0) - 1.0).abs() < 1e-15);
    assert!((m.eta - (1.0 - 2.0 * m_ * ro * ro / (ic + m_ * r0 * r0))).abs() < 1e-15);
    // docs/model.md §4: alpha = atan(3.99/30.20) = 0.131
    assert!((m.body.alpha - 0.131).abs() < 5e-4);
    // hollow circle section
    let a = std::f64::consts::PI * (ro * ro - ri * ri);
    assert!((m.interface.shape().area() / a - 1.0).abs() < 1e-15);
    // thetaJo = 2 W / (kn A D) when crushing starts after opening (fm A / 2 >= W)
    assert!(2e6 * a / 2.0 >= w);
    assert!((m.interface.theta_jo() / (2.0 * w / (2e9 * a * 2.0 * ro)) - 1.0).abs() < 1e-14);
}

/// A value far from 1 is written in exponent form, in the value named and in
/// the condition's numbers: the same rho = 1e300 gave a message of 340
/// characters with a 301-digit weight; ordinary values keep their plain form.
#[test]
fn huge_and_tiny_values_are_written_in_exponent_form() {
    let base = Params::default();
    // W = rho g A H = 1e300 * 9.81 * 0.5 * 2.5 overflows nothing: fm*A is exceeded
    let (var, msg) = err_of(Params { rho: 1e300, ..base });
    assert_eq!(var, "fm", "{msg}");
    assert!(
        msg.contains("W = 1.22625") && msg.contains("e301 N, fm*A = 2500000 N"),
        "{msg}"
    );
    assert!(msg.len() < 120, "{} characters: {msg}", msg.len());
    let (var, msg) = err_of(Params {
        kn: 1e-300,
        fm: f64::INFINITY,
        ..base
    });
    assert_eq!(var, "kn", "{msg}");
    assert!(msg.starts_with("kn = 1e-300: "), "{msg}");
    assert!(msg.contains("kn*Is = 1.0416666666666667e-302 N m"), "{msg}");
    // plain form kept in range: W = 1800 * 9.81 * 0.5 * 2.5
    let (_, msg) = err_of(Params { fm: 1e4, ..base });
    assert!(msg.contains("W = 22072.5 N, fm*A = 5000 N"), "{msg}");
}
