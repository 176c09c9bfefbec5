//! Bad inputs and communication points through the C API.
//!
//! - A non-finite ground acceleration (NaN, +inf, -inf) through
//!   `fmi2SetReal`, or as a derivative through `fmi2SetRealInputDerivatives`,
//!   or a finite line `ag + dag h` that overflows within the step, is
//!   `fmi2Error` with a message naming `ag`.
//! - A communication point that does not match the instance's time (ahead,
//!   behind, NaN, infinite) or a step size that is not finite and positive
//!   is `fmi2Error` with a message naming both.
//!
//! In every case the instance keeps the last good step: an FMU state taken
//! after the refusal is, byte for byte, the state taken before it except for
//! the state of the FMI state machine (stepComplete before, error after):
//! time, last successful time, stored inputs and their derivatives, theta,
//! omega and the integrator's state are unchanged. FMI 2.0 (section 2.1.3,
//! fmi2Error): the simulation cannot go on with the instance as it is, but
//! it can be restarted from an FMU state saved before (`fmi2SetFMUstate`,
//! canGetAndSetFMUstate is true) or reset (`fmi2Reset`). Both are checked:
//! after `fmi2SetFMUstate` the run continues bit for bit as a run that never
//! saw the bad call; after `fmi2Reset` a new run is bit for bit a fresh
//! instance's.

mod host;

use host::*;

/// Machine-state codes in the first byte of a state payload.
const STEP_COMPLETE: u8 = 2;
const ERROR: u8 = 5;

const DT: f64 = 0.02;
const STEPS: usize = 60;
/// The bad call comes after this many good steps.
const BAD_AT: usize = 25;

/// Ground acceleration of the runs (m/s²): rocks the default block.
fn ag(k: usize) -> f64 {
    let t = k as f64 * DT;
    2.4 * (10.0 * t).sin() * (-0.5 * t).exp()
}

/// The default elasto-plastic block released at 0.03 rad, at start time 0.
fn start(h: &Host) {
    assert_eq!(h.setup(None, 0.0, None), fmi2OK);
    assert_eq!(h.set_real("theta", 0.03), fmi2OK);
    assert_eq!(h.enter_init(), fmi2OK);
    assert_eq!(h.exit_init(), fmi2OK);
}

const OUTPUTS: [&str; 8] = [
    "theta",
    "omega",
    "angularAcceleration",
    "af",
    "MR",
    "Fx",
    "Fz",
    "ag",
];

/// Steps `from..to` with `ag(k)` set before each: bits of the outputs after
/// each step, and the last successful time.
fn steps(h: &Host, from: usize, to: usize) -> Vec<u64> {
    let mut out = Vec::new();
    for k in from..to {
        assert_eq!(h.set_real("ag", ag(k)), fmi2OK);
        assert_eq!(h.do_step(k as f64 * DT, DT), fmi2OK, "{:?}", h.messages());
        out.extend(h.reals(&OUTPUTS).iter().map(|x| x.to_bits()));
        out.push(h.integer("impacts") as u64);
        let (s, t) = h.last_successful_time();
        assert_eq!(s, fmi2OK);
        out.push(t.to_bits());
    }
    out
}

/// The reference: one uninterrupted run.
fn reference() -> Vec<u64> {
    let h = Host::new();
    start(&h);
    let r = steps(&h, 0, STEPS);
    assert!(h.errors().is_empty());
    // it rocks through the bad call: impacts before and after it
    let impacts = |k: usize| r[(k + 1) * (OUTPUTS.len() + 2) - 2];
    assert!(impacts(BAD_AT - 1) >= 1, "no impact before the bad call");
    assert!(
        impacts(STEPS - 1) > impacts(BAD_AT - 1),
        "no impact after the bad call"
    );
    r
}

type Prepare = Box<dyn Fn(&Host)>;

/// A bad call made after `BAD_AT` good steps.
struct Bad {
    what: String,
    /// Good calls made first (part of the state the refusal must keep).
    prepare: Option<Prepare>,
    call: Box<dyn Fn(&Host) -> fmi2Status>,
    /// Pieces the one error message must contain.
    says: Vec<String>,
}

fn bad_calls() -> Vec<Bad> {
    let mut v: Vec<Bad> = Vec::new();
    let t = BAD_AT as f64 * DT;
    // the FMU's time: the end of the last step, as it computes it
    let t_fmu = (BAD_AT - 1) as f64 * DT + DT;
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        v.push(Bad {
            what: format!("fmi2SetReal(ag = {x})"),
            prepare: None,
            call: Box::new(move |h| h.set_real("ag", x)),
            says: vec![format!("fmi2SetReal: ag = {x}: the input must be finite")],
        });
        v.push(Bad {
            what: format!("fmi2SetRealInputDerivatives(ag, 1, {x})"),
            prepare: None,
            call: Box::new(move |h| h.set_input_derivative("ag", 1, x)),
            says: vec![format!(
                "fmi2SetRealInputDerivatives: derivative of ag = {x}: the input derivative must be finite"
            )],
        });
        // a bad value next to a good one in the same call: nothing is taken
        v.push(Bad {
            what: format!("fmi2SetReal(ag = 1, ag = {x}) in one call"),
            prepare: None,
            call: Box::new(move |h| {
                let vrs = [vr_of("ag"), vr_of("ag")];
                let xs = [1.0, x];
                // SAFETY: two value references and two values.
                unsafe { fmu_rocking::fmi2SetReal(h.c, vrs.as_ptr(), 2, xs.as_ptr()) }
            }),
            says: vec![format!("ag = {x}: the input must be finite")],
        });
    }
    // A finite line that overflows within the step: refused at fmi2DoStep.
    v.push(Bad {
        what: "ag 1e308, dag/dt 1e308 over 10 s".into(),
        prepare: Some(Box::new(|h| {
            assert_eq!(h.set_real("ag", 1e308), fmi2OK);
            assert_eq!(h.set_input_derivative("ag", 1, 1e308), fmi2OK);
        })),
        call: Box::new(move |h| h.do_step(t, 10.0)),
        says: vec![format!(
            "fmi2DoStep: ag = {0} + {0} * 10 = inf at the end of the step: the input must be finite",
            1e308
        )],
    });
    // Communication points that do not match the time, or bad step sizes.
    for (tc, h_step) in [
        (t + DT, DT),           // ahead
        (t - DT, DT),           // behind
        (0.0, DT),              // back to the start
        (t * (1.0 + 1e-6), DT), // ahead by 1e-6 relative
        (t + 1e-7, DT),         // ahead by 1e-7 s
    ] {
        v.push(Bad {
            what: format!("fmi2DoStep({tc}, {h_step})"),
            prepare: None,
            call: Box::new(move |h| h.do_step(tc, h_step)),
            says: vec![
                format!("fmi2DoStep: currentCommunicationPoint = {tc} does not match the FMU's time {t_fmu}"),
            ],
        });
    }
    for (tc, h_step) in [
        (f64::NAN, DT),
        (f64::INFINITY, DT),
        (f64::NEG_INFINITY, DT),
        (t, f64::NAN),
        (t, f64::INFINITY),
        (t, 0.0),
        (t, -DT),
        (t, -0.0),
    ] {
        v.push(Bad {
            what: format!("fmi2DoStep({tc}, {h_step})"),
            prepare: None,
            call: Box::new(move |h| h.do_step(tc, h_step)),
            says: vec![format!(
                "fmi2DoStep: currentCommunicationPoint = {tc}, communicationStepSize = {h_step}: need finite values and a step > 0"
            )],
        });
    }
    v
}

#[test]
fn bad_inputs_and_communication_points_keep_the_last_good_step() {
    let reference = reference();
    let per_step = reference.len() / STEPS;
    let bads = bad_calls();
    for b in &bads {
        // --- refused, state kept, restart from a saved FMU state ------------
        let h = Host::new();
        start(&h);
        let first = steps(&h, 0, BAD_AT);
        assert_eq!(first[..], reference[..BAD_AT * per_step], "{}", b.what);
        let mut saved = h.get_state();
        let at_saved = h.snapshot_payload();
        if let Some(p) = &b.prepare {
            p(&h);
        }
        let before = h.snapshot_payload();
        assert_eq!(before[0], STEP_COMPLETE);
        let (theta, omega) = (h.real("theta"), h.real("omega"));
        h.clear_log();

        assert_eq!((b.call)(&h), fmi2Error, "{}", b.what);
        let msgs = h.messages();
        let errors: Vec<_> = msgs.iter().filter(|m| m.status == fmi2Error).collect();
        assert_eq!(errors.len(), 1, "{}: {msgs:?}", b.what);
        assert_eq!(errors[0].category, "logStatusError");
        for s in &b.says {
            assert!(
                errors[0].text.contains(s.as_str()),
                "{}: {:?} not in {:?}",
                b.what,
                s,
                errors[0].text
            );
        }

        // the state after the refusal is the state before it, byte for
        // byte, but for the state machine
        let after = h.snapshot_payload();
        assert_eq!(after[0], ERROR, "{}", b.what);
        assert_eq!(after[1..], before[1..], "{}: the state changed", b.what);
        // theta and omega read in the error state: unchanged, bit for bit
        assert_eq!(h.real("theta").to_bits(), theta.to_bits(), "{}", b.what);
        assert_eq!(h.real("omega").to_bits(), omega.to_bits(), "{}", b.what);
        // stepping is refused in the error state, even at the right time
        assert_eq!(h.do_step(BAD_AT as f64 * DT, DT), fmi2Error, "{}", b.what);

        // restart from the state saved before the bad call: the run goes on
        // as if the call had never been made
        assert_eq!(h.set_state(saved), fmi2OK, "{}", b.what);
        assert_eq!(h.snapshot_payload(), at_saved, "{}", b.what);
        let rest = steps(&h, BAD_AT, STEPS);
        assert_eq!(
            rest[..],
            reference[BAD_AT * per_step..],
            "{}: the continued run differs",
            b.what
        );
        assert_eq!(h.free_state(&mut saved), fmi2OK);
        drop(h);

        // --- refused, then reset: a new run is a fresh instance's ----------
        let h = Host::new();
        start(&h);
        steps(&h, 0, BAD_AT);
        if let Some(p) = &b.prepare {
            p(&h);
        }
        assert_eq!((b.call)(&h), fmi2Error, "{}", b.what);
        assert_eq!(h.reset(), fmi2OK, "{}", b.what);
        h.clear_log();
        start(&h);
        assert_eq!(steps(&h, 0, STEPS), reference, "{}: after reset", b.what);
        assert!(h.errors().is_empty(), "{}: {:?}", b.what, h.messages());
    }
    eprintln!(
        "{} bad calls, each recovered by fmi2SetFMUstate and by fmi2Reset",
        bads.len()
    );
}

/// The tolerance on the communication point: a master that accumulates
/// `t += h` (rounding) is accepted within 1e-9 relative; the step then
/// starts from the FMU's own time, so the run is the same.
#[test]
fn communication_points_within_the_tolerance_are_the_fmus_time() {
    let reference = reference();
    let h = Host::new();
    start(&h);
    let mut t = 0.0;
    let mut out = Vec::new();
    for k in 0..STEPS {
        assert_eq!(h.set_real("ag", ag(k)), fmi2OK);
        // t accumulates rounding, and is off by up to 1e-10 relative
        let tc = t * (1.0 + 1e-10 * if k % 2 == 0 { 1.0 } else { -1.0 });
        assert_eq!(h.do_step(tc, DT), fmi2OK, "{:?}", h.messages());
        t += DT;
        out.extend(h.reals(&OUTPUTS).iter().map(|x| x.to_bits()));
        out.push(h.integer("impacts") as u64);
        out.push(h.last_successful_time().1.to_bits());
    }
    // the same motion; the step ends are the master's t + h, so compare
    // the state to the integrator's tolerance rather than bit for bit
    let per_step = reference.len() / STEPS;
    for k in 0..STEPS {
        let a = f64::from_bits(out[k * per_step]);
        let b = f64::from_bits(reference[k * per_step]);
        assert!((a - b).abs() < 1e-9, "step {k}: theta {a} vs {b}");
    }
}
