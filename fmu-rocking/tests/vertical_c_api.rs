//! The vertical input and the one-sided parameters through the C API
//! (docs/model.md §6, §7, §8): the terminal condition `liftOff` is an
//! `fmi2Discard` at the exact time `N = W + m av` reaches 0 (computed here
//! from the FMU's `weight` and `mass`), with `fmi2Terminated`, `regime` 5
//! and a message naming the condition, `av` and the time; a non-finite
//! `av` and bad `side`, `eRestraint` are `fmi2Error` naming the variable;
//! output derivatives under `av`: the rigid law's, a flexible law's refused
//! naming `av`.

mod host;

use host::*;

#[test]
fn lift_off_is_a_discard_at_the_exact_time() {
    let h = Host::new();
    h.init();
    let (w, m) = (h.real("weight"), h.real("mass"));
    let dav = -20.0;
    let dt = 0.1;
    let mut t = 0.0;
    let mut k = 0;
    loop {
        assert_eq!(h.set_real("av", dav * t), fmi2OK);
        assert_eq!(h.set_input_derivative("av", 1, dav), fmi2OK);
        let s = h.do_step(t, dt);
        if s == fmi2Discard {
            break;
        }
        assert_eq!(s, fmi2OK, "{:?}", h.messages());
        assert!((h.real("apparentWeight") - (w + m * dav * (t + dt))).abs() <= 1e-9 * w);
        t += dt;
        k += 1;
        assert!(k < 10, "no discard");
    }
    let (_, t_star) = h.last_successful_time();
    let n = |x: f64| w + m * (dav * t + dav * (x - t));
    assert!(
        n(t_star) <= 0.0 && n(t_star.next_down()) > 0.0,
        "N = {} at {t_star}",
        n(t_star)
    );
    assert_eq!(h.terminated(), (fmi2OK, true));
    assert_eq!(h.integer("regime"), 5);
    let text: Vec<String> = h.messages().into_iter().map(|m| m.text).collect();
    let said = text.iter().any(|m| {
        m.contains("liftOff") && m.contains("av = ") && m.contains(&format!("t = {t_star}"))
    });
    assert!(said, "{text:?}");
}

#[test]
fn non_finite_av_is_an_error_naming_av() {
    for bad in [f64::NAN, f64::INFINITY] {
        let h = Host::new();
        h.init();
        assert_eq!(h.set_real("av", bad), fmi2Error);
        assert!(h.logged("av"), "{:?}", h.errors());
    }
    // finite, but the line av + dav h overflows within the step
    let h = Host::new();
    h.init();
    assert_eq!(h.set_real("av", 1.0), fmi2OK);
    assert_eq!(h.set_input_derivative("av", 1, 1e300), fmi2OK);
    assert_eq!(h.do_step(0.0, 0.01), fmi2Error);
    assert!(h.logged("av = 1"), "{:?}", h.errors());
}

#[test]
fn bad_one_sided_parameters_are_errors_naming_the_variable() {
    let cases: [(&str, i32, f64, f64, &str); 3] = [
        ("side", 0, 0.5, 0.0, "side"),
        ("eRestraint", 1, 1.5, 0.0, "eRestraint"),
        ("theta", 1, 0.5, -0.01, "restraintViolated"),
    ];
    for (what, side, e, theta, word) in cases {
        let h = Host::new();
        assert_eq!(h.setup(None, 0.0, None), fmi2OK);
        assert_eq!(h.set_integer("restraint", enums::ONE_SIDED), fmi2OK);
        assert_eq!(h.set_integer("side", side), fmi2OK);
        assert_eq!(h.set_real("eRestraint", e), fmi2OK);
        assert_eq!(h.set_real("theta", theta), fmi2OK);
        let s = [h.enter_init(), h.exit_init()];
        assert!(s.contains(&fmi2Error), "{what}: {s:?}");
        assert!(h.logged(word), "{what}: {:?}", h.errors());
    }
}

/// A rocking state saved between two steps of a zero-order-hold host (no
/// input derivative: `av` jumps between steps) and set into a second
/// instance: the next step, across the jump of `av`, is bit for bit the
/// uninterrupted instance's (the state keeps the last step's `av`, from
/// which the jump `omega+ = omega- sqrt(I-/I+)` is taken). And a state saved
/// after `liftOff` is still over: the next step is refused, `regime` 5.
#[test]
fn fmu_state_keeps_the_last_av_and_the_terminal_condition() {
    let a = Host::new();
    assert_eq!(a.set_real("theta", 0.004), fmi2OK);
    a.init();
    assert_eq!(a.set_real("av", 2.0), fmi2OK);
    assert_eq!(a.do_step(0.0, 0.01), fmi2OK, "{:?}", a.messages());
    let bytes = a.serialize(a.get_state());
    let b = Host::new();
    assert_eq!(b.set_real("theta", 0.004), fmi2OK);
    b.init();
    assert_eq!(b.set_state(b.deserialize(&bytes)), fmi2OK);
    for h in [&a, &b] {
        assert_eq!(h.set_real("av", -3.0), fmi2OK);
        assert_eq!(h.do_step(0.01, 0.01), fmi2OK, "{:?}", h.messages());
    }
    for name in ["theta", "omega"] {
        assert_eq!(
            a.real(name).to_bits(),
            b.real(name).to_bits(),
            "{name}: {} uninterrupted, {} from the saved state",
            a.real(name),
            b.real(name)
        );
    }

    // liftOff at the end of the first step, then the state saved
    let c = Host::new();
    c.init();
    assert_eq!(c.set_real("av", -20.0), fmi2OK);
    assert_eq!(c.do_step(0.0, 0.1), fmi2Discard, "{:?}", c.messages());
    let ended = c.serialize(c.get_state());
    let d = Host::new();
    d.init();
    assert_eq!(d.set_state(d.deserialize(&ended)), fmi2OK);
    assert_eq!(d.integer("regime"), 5);
    assert_ne!(d.do_step(0.1, 0.1), fmi2OK);
}

/// `fmi2GetRealOutputDerivatives` of one variable at `order`.
fn output_derivative(h: &Host, name: &str, order: i32) -> (fmi2Status, f64) {
    let r = vr_of(name);
    let mut out = f64::NAN;
    // SAFETY: one value reference, one order, room for one value.
    let s = unsafe { fmu_rocking::fmi2GetRealOutputDerivatives(h.c, &r, 1, &order, &mut out) };
    (s, out)
}

/// Output derivatives under `av` with its input derivative, for the rigid
/// and a crushing law: `apparentWeight`' = m dav, `theta`' = `omega`, and
/// `omega`' = `angularAcceleration`, which takes `av`'s input derivative
/// (the power form's `dI/dN` term) bit for bit; order 2 finite.
#[test]
fn output_derivatives_under_av_with_its_input_derivative() {
    let dav = -2.0;
    for law in [enums::RIGID, enums::ELASTO_PLASTIC] {
        let h = Host::new();
        assert_eq!(h.set_integer("interface", law), fmi2OK);
        assert_eq!(h.set_real("theta", 0.05), fmi2OK);
        h.init();
        assert_eq!(h.set_real("av", 1.0), fmi2OK);
        assert_eq!(h.set_input_derivative("av", 1, dav), fmi2OK);
        assert_eq!(h.do_step(0.0, 0.01), fmi2OK, "{:?}", h.messages());
        assert_eq!(h.set_real("av", 1.0 + dav * 0.01), fmi2OK);
        assert_eq!(h.set_input_derivative("av", 1, dav), fmi2OK);
        let (s, x) = output_derivative(&h, "apparentWeight", 1);
        assert_eq!((s, x), (fmi2OK, h.real("mass") * dav), "law {law}");
        let (s, d) = output_derivative(&h, "theta", 1);
        assert_eq!((s, d), (fmi2OK, h.real("omega")), "law {law}");
        let (s, d) = output_derivative(&h, "omega", 1);
        assert_eq!((s, d), (fmi2OK, h.real("angularAcceleration")), "law {law}");
        for name in ["MR", "Fx", "Fz", "af", "contactLength"] {
            let (s, d) = output_derivative(&h, name, 2);
            assert!(s == fmi2OK && d.is_finite(), "law {law}, {name}: {s:?} {d}");
        }
    }
}
