//! Invalid parameters through the C API (docs/model.md §5), table-driven: every
//! condition, on every shape, mass model and law it applies to, including
//! the combinations (`W >= fm*A`, `kn*Is <= W*hG`, hollow sections with the
//! inner size at or beyond the outer one), non-finite values, zero and
//! negative sizes, values whose derived quantities overflow, and
//! out-of-range enumerations and experiment settings.
//!
//! For each case:
//! - the call that checks it (`fmi2ExitInitializationMode` for parameters,
//!   `fmi2SetInteger` for enumerations, `fmi2SetupExperiment` for the
//!   experiment) returns `fmi2Error`, and the capturing logger receives one
//!   message with status `fmi2Error`, category `logStatusError`, that names
//!   the variable, its value (`name = value`) and the condition;
//! - the instance is then in the error state (`fmi2DoStep` is refused);
//! - (a) one refused instance is freed at once (clean: no message, no crash);
//! - (b) another is `fmi2Reset`, given valid parameters, initialised and run
//!   through 40 steps with a ground motion: every output after every step is
//!   bit for bit that of a fresh instance with the same calls.

mod host;

use host::*;

/// What a case sets and what the refusal must say.
struct Case {
    what: String,
    /// Enumerations (by name) set before the reals; all must be accepted.
    ints: Vec<(&'static str, i32)>,
    /// Reals set in the instantiated state; all must be accepted.
    reals: Vec<(&'static str, f64)>,
    /// Where the refusal comes.
    at: At,
    /// The variable the message names.
    var: &'static str,
    /// Its value as the message prints it (`None`: a derived value, only the
    /// name is checked before ` = `).
    value: Option<f64>,
    /// A piece of the stated condition.
    condition: &'static str,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum At {
    ExitInit,
    /// The enumeration `ints.last()` is refused when set.
    SetInteger,
    /// `fmi2SetupExperiment(tolerance, start, stop)`.
    Setup(Option<f64>, f64, Option<f64>),
}

use enums::*;

const SHAPES: [(i32, &str); 4] = [
    (SOLID_RECTANGLE, "solidRectangle"),
    (HOLLOW_RECTANGLE, "hollowRectangle"),
    (SOLID_CIRCLE, "solidCircle"),
    (HOLLOW_CIRCLE, "hollowCircle"),
];

// Start values (the physics defaults, checked by src/tests.rs).
const B: f64 = 0.5;
const L: f64 = 1.0;
const T: f64 = 0.1;
const RO: f64 = 0.5;
const RI: f64 = 0.3;
const H: f64 = 2.5;
const RHO: f64 = 1800.0;
const G: f64 = 9.81;

/// Area and second moment of the default section of `shape` (docs/model.md §1).
fn section(shape: i32) -> (f64, f64) {
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

fn case(
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
fn bad(ints: &[(&'static str, i32)], var: &'static str, x: f64, condition: &'static str) -> Case {
    case(
        format!("{ints:?} {var} = {x}"),
        ints,
        &[(var, x)],
        var,
        Some(x),
        condition,
    )
}

const POSITIVE: &str = "must be finite and > 0";
const NON_FINITE_OR_NOT_POSITIVE: [f64; 6] =
    [0.0, -0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

/// thetaOv of a valid configuration, read in initialization mode.
fn theta_ov(ints: &[(&'static str, i32)]) -> f64 {
    let h = Host::new();
    for &(n, x) in ints {
        assert_eq!(h.set_integer(n, x), fmi2OK);
    }
    assert_eq!(h.enter_init(), fmi2OK);
    h.real("thetaOv")
}

fn cases() -> Vec<Case> {
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

/// The start value of an enumeration (model description).
fn start_integer(name: &str) -> i32 {
    match ROCKING_BLOCK.variable(name).unwrap().ty {
        fmi2_export::model_description::Type::Enumeration { start, .. } => start.unwrap(),
        _ => panic!("{name} is no enumeration"),
    }
}

/// Drives a case to its refusal; returns the instance (in the error state).
fn refuse(c: &Case) -> Host {
    let h = Host::new();
    match c.at {
        At::Setup(tol, start, stop) => {
            assert_eq!(h.setup(tol, start, stop), fmi2Error, "{}", c.what);
        }
        At::SetInteger => {
            let &(name, x) = c.ints.last().unwrap();
            assert_eq!(h.set_integer(name, x), fmi2Error, "{}", c.what);
            // a refused call changes nothing: the start value is still
            // stored (the getters work in the error state)
            assert_eq!(h.integer(name), start_integer(name), "{}", c.what);
        }
        At::ExitInit => {
            for &(n, x) in &c.ints {
                assert_eq!(h.set_integer(n, x), fmi2OK, "{}: set {n}", c.what);
            }
            for &(n, x) in &c.reals {
                // parameters are checked at fmi2ExitInitializationMode, not
                // when set
                assert_eq!(h.set_real(n, x), fmi2OK, "{}: set {n}", c.what);
            }
            assert_eq!(h.setup(None, 0.0, None), fmi2OK, "{}", c.what);
            assert_eq!(h.enter_init(), fmi2OK, "{}", c.what);
            assert!(h.errors().is_empty(), "{}: {:?}", c.what, h.messages());
            assert_eq!(h.exit_init(), fmi2Error, "{}: accepted", c.what);
            // the parameters can still be read back in the error state
            // (theta and omega are outputs: evaluated by the model, which
            // the refused parameters do not build)
            for &(n, x) in c
                .reals
                .iter()
                .filter(|(n, _)| !["theta", "omega"].contains(n))
            {
                let (s, y) = h.get_real(n);
                assert_eq!(s, fmi2OK, "{}: get {n}", c.what);
                assert_eq!(y.to_bits(), x.to_bits(), "{}: {n}", c.what);
            }
        }
    }
    h
}

/// The one message of the refusal: status, category, name, value, condition.
fn check_message(h: &Host, c: &Case) {
    let msgs = h.messages();
    let errors: Vec<_> = msgs.iter().filter(|m| m.status == fmi2Error).collect();
    assert_eq!(errors.len(), 1, "{}: {msgs:?}", c.what);
    let m = errors[0];
    assert_eq!(m.category, "logStatusError", "{}", c.what);
    let function = match c.at {
        At::ExitInit => "fmi2ExitInitializationMode: invalid parameters: ",
        At::SetInteger => "fmi2SetInteger: ",
        At::Setup(..) => "fmi2SetupExperiment: ",
    };
    let named = match c.value {
        Some(x) if c.at == At::SetInteger => format!("{} = {}: ", c.var, x as i32),
        Some(x) => format!("{} = {x}: ", c.var),
        None => format!("{} = ", c.var),
    };
    assert!(
        m.text.starts_with(&format!("{function}{named}")),
        "{}: expected {function}{named}... got {}",
        c.what,
        m.text
    );
    assert!(
        m.text.contains(c.condition),
        "{}: no condition {:?} in {}",
        c.what,
        c.condition,
        m.text
    );
}

/// The ground motion of the valid runs (m/s²): strong enough to rock
/// every configuration used.
fn ag(k: usize) -> f64 {
    6.0 * (0.9 * k as f64 * 0.02).sin() * (-(k as f64) * 0.01).exp()
}

const RUN_OUTPUTS: [&str; 9] = [
    "theta",
    "omega",
    "angularAcceleration",
    "af",
    "contactLength",
    "MR",
    "Fx",
    "Fz",
    "thetaOv",
];

/// Valid parameters (the enumerations of the case with the start values of
/// the reals, released at 0.02 rad), 40 steps of 0.02 s: every output's
/// bits after every step.
fn valid_run(h: &Host, c: &Case) -> Vec<u64> {
    assert_eq!(h.setup(None, 0.0, None), fmi2OK, "{}", c.what);
    for &(n, x) in &c.ints {
        if c.at != At::SetInteger {
            assert_eq!(h.set_integer(n, x), fmi2OK, "{}", c.what);
        }
    }
    assert_eq!(h.set_real("theta", 0.02), fmi2OK);
    assert_eq!(h.enter_init(), fmi2OK, "{}", c.what);
    assert_eq!(h.exit_init(), fmi2OK, "{}: {:?}", c.what, h.messages());
    let mut out = Vec::new();
    for k in 0..40 {
        assert_eq!(h.set_real("ag", ag(k)), fmi2OK);
        let s = h.do_step(k as f64 * 0.02, 0.02);
        assert!(s == fmi2OK || s == fmi2Discard, "{}: step {k}: {s}", c.what);
        out.extend(h.reals(&RUN_OUTPUTS).iter().map(|x| x.to_bits()));
        out.push(h.integer("regime") as u64);
        out.push(h.integer("impacts") as u64);
        if s == fmi2Discard {
            break;
        }
    }
    out
}

#[test]
fn every_invalid_parameter_is_refused_named_and_recoverable() {
    let cases = cases();
    let mut by_var = std::collections::BTreeMap::<&str, usize>::new();
    for c in &cases {
        *by_var.entry(c.var).or_default() += 1;
        // (a) refused, then freed at once
        let h = refuse(c);
        check_message(&h, c);
        if c.at == At::ExitInit {
            assert_eq!(h.do_step(0.0, 0.01), fmi2Error, "{}", c.what);
            assert!(
                h.errors()
                    .last()
                    .unwrap()
                    .contains("not allowed in state error"),
                "{}",
                c.what
            );
        }
        let before = h.messages();
        let log = h.free_and_take_log();
        assert_eq!(log, before, "{}: messages while freeing", c.what);

        // (b) refused, reset, valid parameters, run: the same as a fresh instance
        let h = refuse(c);
        assert_eq!(h.reset(), fmi2OK, "{}: {:?}", c.what, h.messages());
        h.clear_log();
        let after_reset = valid_run(&h, c);
        assert!(h.errors().is_empty(), "{}: {:?}", c.what, h.messages());
        let fresh = valid_run(&Host::new(), c);
        assert_eq!(
            after_reset, fresh,
            "{}: differs from a fresh instance",
            c.what
        );
        // it rocked: theta moved off its release value
        assert_ne!(after_reset[0], 0.02f64.to_bits(), "{}", c.what);
    }
    eprintln!("{} cases: {by_var:?}", cases.len());
    // every condition of build() is covered
    for var in [
        "g",
        "B",
        "L",
        "t",
        "Ro",
        "Ri",
        "H",
        "rho",
        "W",
        "hG",
        "Ic",
        "kn",
        "fm",
        "eta",
        "theta",
        "omega",
        "mass",
        "IO",
        "shape",
        "massModel",
        "interface",
        "formulation",
        "restitution",
        "tolerance",
        "startTime",
        "stopTime",
    ] {
        assert!(by_var.contains_key(var), "no case for {var}");
    }
}

/// The instance that refused its parameters frees cleanly also with FMU
/// states still alive, and its states taken in the error state restore the
/// refusal (error state, same values), not a half-built model.
#[test]
fn a_refused_instance_with_live_states_frees_and_restores() {
    let h = Host::new();
    assert_eq!(h.set_real("B", -1.0), fmi2OK);
    assert_eq!(h.enter_init(), fmi2OK);
    let in_init = h.get_state();
    assert_eq!(h.exit_init(), fmi2Error);
    let in_error = h.get_state();
    // back to initialization mode, fix B, go on
    assert_eq!(h.set_state(in_init), fmi2OK);
    assert_eq!(h.set_real("B", 0.5), fmi2OK);
    assert_eq!(h.exit_init(), fmi2OK, "{:?}", h.messages());
    assert_eq!(h.do_step(0.0, 0.01), fmi2OK);
    // to the error state again: stepping is refused, B is -1 again
    assert_eq!(h.set_state(in_error), fmi2OK);
    assert_eq!(h.real("B"), -1.0);
    assert_eq!(h.do_step(0.0, 0.01), fmi2Error);
    h.free(); // with two live states
}
