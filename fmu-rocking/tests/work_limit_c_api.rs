//! The work limit of `fmi2DoStep` (parameter `maxSteps`, docs/model.md §5)
//! through the C API: the two calls that would take minutes without it
//! (kn 1e18 Pa/m shaken below uplift over 1 s; an elastic joint under a
//! constant `ag` over a step of 1e300 s) return `fmi2Discard` at the limit,
//! with `fmi2LastSuccessfulTime` the time reached, a message naming the cause
//! and that time, `fmi2Terminated` false, a consistent state there, and the
//! host goes on with smaller steps from the state it saved. The wall time of
//! each call is printed (`--nocapture`), not asserted.

#![allow(non_upper_case_globals)] // the FMI constants keep their C names

mod host;

use std::time::Instant;

use host::*;

fn start(h: &Host, params: &[(&str, f64)], ag: f64) {
    assert_eq!(h.setup(None, 0.0, None), fmi2OK);
    for &(name, x) in params {
        assert_eq!(h.set_real(name, x), fmi2OK, "{name}");
    }
    assert_eq!(h.enter_init(), fmi2OK);
    assert_eq!(h.exit_init(), fmi2OK);
    assert_eq!(h.set_real("ag", ag), fmi2OK);
}

/// One pathological step: discarded at the limit, consistent, and the host
/// goes on from the saved state in steps of 1 ms.
fn discarded_at_the_limit(name: &str, h: &Host, step: f64) {
    let mut saved = h.get_state();
    let wall = Instant::now();
    let status = h.do_step(0.0, step);
    eprintln!(
        "{name}: fmi2DoStep returned {status} in {:.3} s",
        wall.elapsed().as_secs_f64()
    );
    assert_eq!(status, fmi2Discard, "{:?}", h.messages());
    let (st, t_reached) = h.last_successful_time();
    assert_eq!(st, fmi2OK);
    assert!(t_reached > 0.0 && t_reached < step, "{t_reached}");
    assert_eq!(h.terminated(), (fmi2OK, false));
    let msg = h
        .messages()
        .into_iter()
        .rev()
        .find(|m| m.status == fmi2Discard)
        .expect("a message with the discard");
    assert!(
        msg.text.contains("maxSteps = 100000") && msg.text.contains(&format!("t = {t_reached}")),
        "{}",
        msg.text
    );
    // consistent at t_reached: the outputs are those of a finite state below
    // overturning, where the restoring moment W hW(|theta|) is positive
    // (thetaOv is the first root of hW, docs/model.md §3)
    let (theta, omega, mr) = (h.real("theta"), h.real("omega"), h.real("MR"));
    assert!(theta.is_finite() && omega.is_finite() && mr.is_finite());
    assert!(theta.abs() < h.real("thetaOv") && !h.boolean("overturned"));
    assert!(mr > 0.0, "theta {theta}, MR {mr}");
    // no step from stepFailed; back to the saved state and on
    assert_ne!(h.do_step(t_reached, 1e-3), fmi2OK);
    assert_eq!(h.set_state(saved), fmi2OK);
    assert_eq!(h.free_state(&mut saved), fmi2OK);
    for k in 0..5 {
        assert_eq!(
            h.do_step(k as f64 * 1e-3, 1e-3),
            fmi2OK,
            "{:?}",
            h.messages()
        );
    }
    assert!(h.real("theta").is_finite());
}

#[test]
fn a_very_stiff_interface_over_1_s_is_discarded_at_the_work_limit() {
    let h = Host::with_logging(true);
    start(&h, &[("kn", 1e18)], 1.0);
    discarded_at_the_limit("kn 1e18, h = 1 s", &h, 1.0);
    h.free();
}

#[test]
fn a_step_of_1e300_s_is_discarded_at_the_work_limit() {
    let h = Host::with_logging(true);
    assert_eq!(h.set_integer("interface", enums::ELASTIC), fmi2OK);
    start(&h, &[], 1.0);
    discarded_at_the_limit("elastic, h = 1e300 s", &h, 1e300);
    h.free();
}

#[test]
fn max_steps_below_one_is_refused_naming_it() {
    let h = Host::new();
    assert_eq!(h.setup(None, 0.0, None), fmi2OK);
    assert_eq!(h.set_integer("maxSteps", 0), fmi2OK);
    assert_eq!(h.enter_init(), fmi2OK);
    assert_ne!(h.exit_init(), fmi2OK);
    assert!(
        h.errors().iter().any(|e| e.contains("maxSteps = 0")),
        "{:?}",
        h.errors()
    );
    h.free();
}
