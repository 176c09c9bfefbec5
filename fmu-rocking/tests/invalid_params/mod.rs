//! The table of invalid parameter sets that `params_c_api.rs` drives through
//! the C API: each case, what it sets and what the refusal must say.

use super::host::*;

/// What a case sets and what the refusal must say.
pub(crate) struct Case {
    pub(crate) what: String,
    /// Enumerations (by name) set before the reals; all must be accepted.
    pub(crate) ints: Vec<(&'static str, i32)>,
    /// Reals set in the instantiated state; all must be accepted.
    pub(crate) reals: Vec<(&'static str, f64)>,
    /// Where the refusal comes.
    pub(crate) at: At,
    /// The variable the message names.
    pub(crate) var: &'static str,
    /// Its value as the message prints it (`None`: a derived value, only the
    /// name is checked before ` = `).
    pub(crate) value: Option<f64>,
    /// A piece of the stated condition.
    pub(crate) condition: &'static str,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum At {
    ExitInit,
    /// The enumeration `ints.last()` is refused when set.
    SetInteger,
    /// `fmi2SetupExperiment(tolerance, start, stop)`.
    Setup(Option<f64>, f64, Option<f64>),
}

use enums::*;

pub(crate) const SHAPES: [(i32, &str); 4] = [
    (SOLID_RECTANGLE, "solidRectangle"),
    (HOLLOW_RECTANGLE, "hollowRectangle"),
    (SOLID_CIRCLE, "solidCircle"),
    (HOLLOW_CIRCLE, "hollowCircle"),
];

// Start values (the physics defaults, checked by src/tests.rs).
pub(crate) const B: f64 = 0.5;
pub(crate) const L: f64 = 1.0;
pub(crate) const T: f64 = 0.1;
pub(crate) const RO: f64 = 0.5;
pub(crate) const RI: f64 = 0.3;
pub(crate) const H: f64 = 2.5;
pub(crate) const RHO: f64 = 1800.0;
pub(crate) const G: f64 = 9.81;

/// Area and second moment of the default section of `shape` (docs/model.md §1).
pub(crate) fn section(shape: i32) -> (f64, f64) {
    use std::f64::consts::PI;
    match shape {
        SOLID_RECTANGLE => (B * L, L * B.powi(3) / 12.0),
        HOLLOW_RECTANGLE => (
            B * L - (B - 2.0 * T) * (L - 2.0 * T),
            (L * B.powi(3) - (L - 2.0 * T) * (B - 2.0 * T).powi(3)) / 12.0,
        ),
        SOLID_CIRCLE => (PI * RO * RO, PI * RO.powi(4) / 4.0),
        _ => (
            PI * (RO * RO - RI * RI),
            PI * (RO.powi(4) - RI.powi(4)) / 4.0,
        ),
    }
}

pub(crate) fn case(
    what: impl Into<String>,
    ints: &[(&'static str, i32)],
    reals: &[(&'static str, f64)],
    var: &'static str,
    value: Option<f64>,
    condition: &'static str,
) -> Case {
    Case {
        what: what.into(),
        ints: ints.to_vec(),
        reals: reals.to_vec(),
        at: At::ExitInit,
        var,
        value,
        condition,
    }
}

/// The value `x` set on `var` is refused with that value and `condition`.
pub(crate) fn bad(
    ints: &[(&'static str, i32)],
    var: &'static str,
    x: f64,
    condition: &'static str,
) -> Case {
    case(
        format!("{ints:?} {var} = {x}"),
        ints,
        &[(var, x)],
        var,
        Some(x),
        condition,
    )
}

pub(crate) const POSITIVE: &str = "must be finite and > 0";
pub(crate) const NON_FINITE_OR_NOT_POSITIVE: [f64; 6] =
    [0.0, -0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

/// thetaOv of a valid configuration, read in initialization mode.
pub(crate) fn theta_ov(ints: &[(&'static str, i32)]) -> f64 {
    let h = Host::new();
    for &(n, x) in ints {
        assert_eq!(h.set_integer(n, x), fmi2OK);
    }
    assert_eq!(h.enter_init(), fmi2OK);
    h.real("thetaOv")
}

pub(crate) fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    let rect = [("shape", SOLID_RECTANGLE)];
    let hollow_rect = [("shape", HOLLOW_RECTANGLE)];
    let circle = [("shape", SOLID_CIRCLE)];
    let ring = [("shape", HOLLOW_CIRCLE)];
    let lumped = [("massModel", LUMPED)];
    let elastic = [("interface", ELASTIC)];
    let given = [("restitution", GIVEN)];

    // Sizes and physical constants: zero, negative, NaN, infinite.
    for x in NON_FINITE_OR_NOT_POSITIVE {
        v.push(bad(&[], "g", x, POSITIVE));
        for (ints, var) in [
            (&rect[..], "B"),
            (&rect[..], "L"),
            (&hollow_rect[..], "B"),
            (&hollow_rect[..], "L"),
            (&hollow_rect[..], "t"),
            (&circle[..], "Ro"),
            (&ring[..], "Ro"),
            (&ring[..], "Ri"),
            (&[][..], "H"),
            (&[][..], "rho"),
            (&lumped[..], "W"),
            (&lumped[..], "hG"),
            (&[][..], "kn"),
            (&elastic[..], "kn"),
        ] {
            v.push(bad(ints, var, x, POSITIVE));
        }
    }
    // Ic may be 0 (a point mass), not negative or non-finite.
    for x in [-1.0, -1e-300, f64::NAN, f64::INFINITY] {
        v.push(bad(&lumped, "Ic", x, "must be finite and >= 0"));
    }
    // fm: > 0 (inf: no crushing), not NaN.
    for x in [0.0, -1.0, f64::NAN, f64::NEG_INFINITY] {
        v.push(bad(&[], "fm", x, "must be > 0"));
    }
    // Hollow sections: the wall must leave a hole, the hole must be inside.
    v.push(bad(&hollow_rect, "t", 0.25, "2*t < min(B, L) = 0.5")); // 2t = B
    v.push(bad(&hollow_rect, "t", 0.3, "2*t < min(B, L) = 0.5"));
    for (t, cond) in [
        (0.2, "2*t < min(B, L) = 0.4"),
        (0.35, "2*t < min(B, L) = 0.4"),
    ] {
        // L the smaller side
        v.push(case(
            format!("hollow rectangle B 1 L 0.4 t {t}"),
            &hollow_rect,
            &[("B", 1.0), ("L", 0.4), ("t", t)],
            "t",
            Some(t),
            cond,
        ));
    }
    v.push(bad(&ring, "Ri", RO, "Ri < Ro = 0.5")); // Ri = Ro
    v.push(bad(&ring, "Ri", 0.6, "Ri < Ro = 0.5"));
    v.push(case(
        "ring Ro 0.2 < Ri 0.3",
        &ring,
        &[("Ro", 0.2)],
        "Ri",
        Some(RI),
        "Ri < Ro = 0.2",
    ));
    // The section carries its weight: W < fm*A, on every shape, prism and
    // lumped; equality exactly (lumped W = 1e5 N on A = 0.5 m², fm = 2e5 Pa).
    for (shape, name) in SHAPES {
        let (a, _) = section(shape);
        let w_over_a = RHO * G * H; // prism: W/A = rho g H
        let fm = 0.999 * w_over_a;
        v.push(case(
            format!("{name} prism fm = 0.999 W/A"),
            &[("shape", shape)],
            &[("fm", fm)],
            "fm",
            Some(fm),
            "the section crushes at rest: must satisfy W < fm*A",
        ));
        let fm = 0.5 * 1e5 / a;
        v.push(case(
            format!("{name} lumped W 1e5 fm = 0.5 W/A"),
            &[("shape", shape), ("massModel", LUMPED)],
            &[("fm", fm)],
            "fm",
            Some(fm),
            "the section crushes at rest: must satisfy W < fm*A",
        ));
    }
    v.push(case(
        "W = fm*A exactly",
        &lumped,
        &[("W", 1e5), ("fm", 2e5)],
        "fm",
        Some(2e5),
        "must satisfy W < fm*A, W = 100000 N, fm*A = 100000 N",
    ));
    // The rest position is stable: kn*Is > W*hG, on every shape, elastic and
    // crushing; equality exactly (B 1, L 12: Is = 1 m⁴; W 1e5 N, hG 1 m).
    for (shape, name) in SHAPES {
        let (a, is) = section(shape);
        let w = RHO * G * a * H;
        let kn = 0.5 * w * (H / 2.0) / is;
        for law in [ELASTIC, ELASTO_PLASTIC] {
            v.push(case(
                format!("{name} law {law} kn = 0.5 W hG / Is"),
                &[("shape", shape), ("interface", law)],
                &[("kn", kn)],
                "kn",
                Some(kn),
                "the rest position is unstable: must satisfy kn*Is > W*hG",
            ));
        }
    }
    for law in [ELASTIC, ELASTO_PLASTIC] {
        v.push(case(
            format!("law {law}: kn*Is = W*hG exactly"),
            &[("massModel", LUMPED), ("interface", law)],
            &[
                ("B", 1.0),
                ("L", 12.0),
                ("W", 1e5),
                ("hG", 1.0),
                ("kn", 1e5),
            ],
            "kn",
            Some(1e5),
            "kn*Is = 100000 N m, W*hG = 100000 N m",
        ));
    }
    // eta in [0, 1] when given.
    for x in [
        -0.1,
        1.0 + 1e-15,
        1.5,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        v.push(bad(&given, "eta", x, "must be in [0, 1]"));
    }
    // Initial conditions: finite, |theta| < thetaOv.
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        v.push(bad(&[], "theta", x, "must be finite"));
        v.push(bad(&[], "omega", x, "must be finite"));
    }
    for ints in [
        vec![("interface", RIGID)],
        vec![("interface", ELASTIC)],
        vec![],
        vec![("shape", HOLLOW_CIRCLE), ("massModel", LUMPED)],
    ] {
        let ov = theta_ov(&ints);
        for x in [ov, -ov, 1.0001 * ov, 1.0] {
            v.push(bad(
                &ints,
                "theta",
                x,
                "the initial rotation must satisfy |theta| < thetaOv",
            ));
        }
    }
    // Combinations that pass one by one but overflow or vanish together.
    v.push(case(
        "prism weight overflows",
        &[],
        &[("rho", 1e200), ("H", 1e200)],
        "rho",
        Some(1e200),
        "the weight W = rho*g*A*H = inf N must be finite and > 0",
    ));
    v.push(case(
        "section overflows",
        &lumped,
        &[("B", 1e200), ("L", 1e200)],
        "B",
        Some(1e200),
        "the section's area A = inf m2",
    ));
    v.push(case(
        "second moment vanishes",
        &[],
        &[("B", 1e-200)],
        "B",
        Some(1e-200),
        "second moment Is = 0 m4 must be finite and > 0",
    ));
    v.push(case(
        "hollow rectangle of no area",
        &hollow_rect,
        &[("t", 1e-300)],
        "t",
        Some(1e-300),
        "the section's area A = 0 m2",
    ));
    v.push(case(
        "mass overflows",
        &[("massModel", LUMPED), ("interface", RIGID)],
        &[("W", 1e300), ("g", 1e-300)],
        "mass",
        Some(f64::INFINITY),
        "the mass W/g must be finite and > 0",
    ));
    v.push(case(
        "inertia overflows",
        &[("massModel", LUMPED), ("interface", RIGID)],
        &[("hG", 1e200)],
        "IO",
        Some(f64::INFINITY),
        "the inertia about the toe Ic + m*R0^2 must be finite and > 0",
    ));
    v.push(case(
        "prism inertia overflows",
        &[("interface", RIGID)],
        &[("rho", 1e-300), ("H", 1e200)],
        "IO",
        Some(f64::INFINITY),
        "the inertia about the toe",
    ));
    v.push(case(
        "interface too stiff for the weight",
        &[],
        &[("kn", 1e200)],
        "kn",
        Some(1e200),
        "which must be >= 1e-100 rad: the interface is too stiff",
    ));
    v.push(case(
        "weight too small for the interface",
        &elastic,
        &[("g", 1e-100)],
        "kn",
        Some(5e9),
        "which must be >= 1e-100 rad",
    ));
    // Enumerations: refused when set (the stored value stays valid).
    for (var, bad_values) in [
        ("shape", &[0, 5, -1, i32::MIN, i32::MAX][..]),
        ("massModel", &[0, 3][..]),
        ("interface", &[0, 4][..]),
        ("formulation", &[0, 3][..]),
        ("restitution", &[0, 3][..]),
    ] {
        for &x in bad_values {
            v.push(Case {
                what: format!("{var} = {x}"),
                ints: vec![(var, x)],
                reals: vec![],
                at: At::SetInteger,
                var,
                value: Some(x as f64),
                condition: "not an item of",
            });
        }
    }
    // The experiment: tolerance > 0 and finite, finite start, stop >= start.
    for (tol, start, stop, var, value, cond) in [
        (Some(0.0), 0.0, None, "tolerance", 0.0, POSITIVE),
        (Some(-1e-6), 0.0, None, "tolerance", -1e-6, POSITIVE),
        (Some(f64::NAN), 0.0, None, "tolerance", f64::NAN, POSITIVE),
        (
            Some(f64::INFINITY),
            0.0,
            None,
            "tolerance",
            f64::INFINITY,
            POSITIVE,
        ),
        (
            None,
            f64::NAN,
            None,
            "startTime",
            f64::NAN,
            "must be finite",
        ),
        (
            None,
            f64::NEG_INFINITY,
            None,
            "startTime",
            f64::NEG_INFINITY,
            "must be finite",
        ),
        (
            None,
            1.0,
            Some(0.5),
            "stopTime",
            0.5,
            "must be finite and >= startTime = 1",
        ),
        (
            None,
            0.0,
            Some(f64::NAN),
            "stopTime",
            f64::NAN,
            "must be finite",
        ),
        (
            None,
            0.0,
            Some(f64::INFINITY),
            "stopTime",
            f64::INFINITY,
            "must be finite",
        ),
    ] {
        v.push(Case {
            what: format!("setup {tol:?} {start} {stop:?}"),
            ints: vec![],
            reals: vec![],
            at: At::Setup(tol, start, stop),
            var,
            value: Some(value),
            condition: cond,
        });
    }
    v
}
