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

mod invalid_params;

use invalid_params::*;
// the invalid parameters' cases, not host's runs
use invalid_params::Case;

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
        _ => format!("{} = ", c.var),
    };
    assert!(
        m.text.starts_with(&format!("{function}{named}")),
        "{}: expected {function}{named}... got {}",
        c.what,
        m.text
    );
    // a Real is written in whatever form reads back as the value set
    if let (Some(x), false) = (c.value, c.at == At::SetInteger) {
        let rest = &m.text[function.len() + named.len()..];
        let shown = rest.split(": ").next().unwrap_or("");
        let read: f64 = shown.parse().unwrap_or(f64::NAN);
        assert!(
            read == x || (read.is_nan() && x.is_nan()),
            "{}: the value {x} written as {shown:?} in {}",
            c.what,
            m.text
        );
    }
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
