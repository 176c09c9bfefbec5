//! The whole life of RockingBlock instances through the exported C functions,
//! for a memory checker (`tools/memcheck.sh` runs it under valgrind
//! memcheck): instantiate, set up, initialise, simulate (a rigid block with
//! impacts, a block on a flexible interface that crushes, a block that
//! overturns), get/set/overwrite FMU states, serialize and deserialize them,
//! terminate, reset and simulate again, free (with FMU states left alive for
//! `fmi2FreeInstance` to free), and the error paths (wrong GUID, calls in the
//! wrong state, invalid parameters, a non-finite input, a corrupted
//! serialized state, another instance's state), with debug logging on.
//!
//! Every result is checked: a replay from a saved or deserialized state, and
//! a run after `fmi2Reset`, equal the first run bit for bit.
//!
//! ```sh
//! cargo run --release -p fmu-rocking --example c_api_loop [-- ROUNDS [STEPS]]
//! ```

#[path = "../tests/host/mod.rs"]
mod host;

use std::ffi::CString;
use std::ptr;
use std::time::Instant;

use fmu_rocking::description::vr;
use fmu_rocking::*;
use host::*;

const ALL_CATEGORIES: [&str; 4] = ["logEvents", "logStatusWarning", "logStatusError", "logAll"];

/// Bits of a run's samples.
fn bits(samples: &[Sample]) -> Vec<[u64; 12]> {
    samples.iter().map(Sample::bits).collect()
}

/// Runs `steps` steps from step `from`; returns the samples (fewer if it
/// overturned) and whether it overturned.
fn run_from(fmu: &Host, case: &Case, from: usize, steps: usize) -> (Vec<Sample>, bool) {
    let mut out = Vec::with_capacity(steps);
    for k in from..from + steps {
        let (a, d) = case.input(k);
        let s = fmu.step(k as f64 * case.h, case.h, a, d);
        if s == fmi2Discard {
            assert_eq!(
                fmu.terminated(),
                (fmi2OK, true),
                "{}: discard without termination",
                case.name
            );
            return (out, true);
        }
        assert_eq!(s, fmi2OK, "{}: step {k}", case.name);
        out.push(fmu.sample());
    }
    (out, false)
}

struct Summary {
    steps: usize,
    impacts: i32,
    regimes: [bool; 5],
    overturned_at: Option<f64>,
}

/// One instance through its whole life on `case`.
fn exercise(case: &Case, round: usize, steps: usize) -> Summary {
    let fmu = long_run_host(&format!("{} #{round}", case.name), true);
    if round.is_multiple_of(2) {
        fmu.check(
            "fmi2SetDebugLogging",
            fmu.debug_logging(true, &ALL_CATEGORIES),
        );
    } else {
        fmu.check(
            "fmi2SetDebugLogging",
            fmu.debug_logging(true, &["logEvents"]),
        );
    }
    fmu.init_case(case);
    // the state is saved at 1.5 s at the latest (before the overturning cases tip over)
    let half = (steps / 2).min(150);

    // first half, then a saved state and its serialized copy
    let (first, over) = run_from(&fmu, case, 0, half);
    assert!(!over, "{}: overturned in the first half", case.name);
    let mut saved = fmu.get_state();
    let bytes = fmu.serialize(saved);

    // second half, three times: straight on, from the saved state, from the
    // deserialized one
    let (a, over_a) = run_from(&fmu, case, half, steps - half);
    let t_over = over_a.then(|| fmu.last_successful_time().1);
    let restored = fmu.deserialize(&bytes);
    for (state, from) in [
        (saved, "the FMU state"),
        (restored, "the deserialized state"),
    ] {
        fmu.check("fmi2SetFMUstate", fmu.set_state(state));
        let (b, over_b) = run_from(&fmu, case, half, steps - half);
        assert_eq!(bits(&a), bits(&b), "{}: replay from {from}", case.name);
        assert_eq!(over_a, over_b);
        if over_b {
            assert_eq!(
                fmu.last_successful_time().1.to_bits(),
                t_over.unwrap().to_bits()
            );
        }
    }

    // overwrite the saved state with the end state, serialize it again
    fmu.check("fmi2GetFMUstate (overwrite)", fmu.update_state(&mut saved));
    let end_bytes = fmu.serialize(saved);
    assert!(!end_bytes.is_empty());
    fmu.check("fmi2FreeFMUstate", fmu.free_state(&mut saved));
    // `restored` stays alive: fmi2FreeInstance frees it

    fmu.check("fmi2Terminate", fmu.terminate());
    fmu.check("fmi2Reset", fmu.reset());
    fmu.init_case(case);
    let (again, _) = run_from(&fmu, case, 0, half);
    assert_eq!(
        bits(&first),
        bits(&again),
        "{}: run after fmi2Reset",
        case.name
    );
    // a state taken in stepComplete, left alive
    let _left = fmu.get_state();

    let all: Vec<&Sample> = first.iter().chain(a.iter()).collect();
    let mut regimes = [false; 5];
    for s in &all {
        regimes[s.ints[0] as usize] = true;
    }
    if over_a {
        regimes[4] = true;
    }
    Summary {
        steps: all.len(),
        impacts: all.last().map_or(0, |s| s.ints[1]),
        regimes,
        overturned_at: t_over,
    }
}

/// The error paths, each followed by the way out of the error state.
fn error_paths() {
    // wrong GUID and an unknown fmuType: NULL (no logger to tell)
    assert!(bare_instance(Some("bad"), fmi2CoSimulation, Some("{not-the-guid}")).is_null());
    // neither fmi2ModelExchange (0) nor fmi2CoSimulation (1)
    assert!(bare_instance(Some("bad"), 7, Some(GUID)).is_null());

    let f = long_run_host("errors", true);
    f.check(
        "fmi2SetDebugLogging",
        f.debug_logging(true, &ALL_CATEGORIES),
    );
    unsafe {
        // a step before initialization
        assert_eq!(fmi2DoStep(f.c, 0.0, 0.01, fmi2False), fmi2Error);
        f.check("fmi2Reset", f.reset());
        // an unknown category: a warning
        let cat = CString::new("noSuchCategory").unwrap();
        let p = cat.as_ptr();
        assert_eq!(fmi2SetDebugLogging(f.c, fmi2True, 1, &p), fmi2Warning);
        // invalid parameters: refused at fmi2ExitInitializationMode
        assert_eq!(f.set_reals(&[(vr::FM, 1.0)]), fmi2OK);
        assert_eq!(fmi2EnterInitializationMode(f.c), fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(f.c), fmi2Error);
        f.check("fmi2Reset", f.reset());
        // an unknown value reference, an enumeration value out of range
        assert_eq!(f.set_reals(&[(9999, 1.0)]), fmi2Error);
        f.check("fmi2Reset", f.reset());
        assert_eq!(f.set_integers(&[(vr::SHAPE, 17)]), fmi2Error);
        f.check("fmi2Reset", f.reset());
        assert_eq!(fmi2EnterInitializationMode(f.c), fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(f.c), fmi2OK);
        // a non-finite input
        let nan = f64::NAN;
        assert_eq!(fmi2SetReal(f.c, &vr::AG, 1, &nan), fmi2Error);
        f.check("fmi2Reset", f.reset());
        assert_eq!(fmi2EnterInitializationMode(f.c), fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(f.c), fmi2OK);
        // a mismatched communication point
        assert_eq!(fmi2DoStep(f.c, 5.0, 0.01, fmi2False), fmi2Error);
        f.check("fmi2Reset", f.reset());
        assert_eq!(fmi2EnterInitializationMode(f.c), fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(f.c), fmi2OK);
        assert_eq!(fmi2DoStep(f.c, 0.0, 0.01, fmi2False), fmi2OK);
        // a corrupted serialized state, a truncated one, a padded one
        let st = f.get_state();
        let mut bytes = f.serialize(st);
        let n = bytes.len();
        bytes[n / 2] ^= 0x55;
        let mut out: fmi2FMUstate = ptr::null_mut();
        assert_eq!(
            fmi2DeSerializeFMUstate(f.c, bytes.as_ptr() as *const fmi2Byte, n, &mut out),
            fmi2Error
        );
        assert!(out.is_null());
        f.check("fmi2Reset", f.reset());
        assert_eq!(
            fmi2DeSerializeFMUstate(f.c, bytes.as_ptr() as *const fmi2Byte, n / 3, &mut out),
            fmi2Error
        );
        f.check("fmi2Reset", f.reset());
        let mut padded = f.serialize(st);
        padded.resize(n + 64, 0);
        let s2 = f.deserialize(&padded);
        f.check("fmi2SetFMUstate", f.set_state(s2));
        // a buffer too small for fmi2SerializeFMUstate
        let mut small = vec![0u8; 8];
        assert_eq!(
            fmi2SerializeFMUstate(f.c, st, small.as_mut_ptr() as *mut fmi2Byte, 8),
            fmi2Error
        );
        f.check("fmi2Reset", f.reset());
        // another instance's state, a freed state, a made-up pointer
        let g = long_run_host("other", false);
        let foreign = g.get_state();
        assert_eq!(fmi2SetFMUstate(f.c, foreign), fmi2Error);
        f.check("fmi2Reset", f.reset());
        let mut gone = f.get_state();
        let stale = gone;
        f.check("fmi2FreeFMUstate", f.free_state(&mut gone));
        assert_eq!(fmi2SetFMUstate(f.c, stale), fmi2Error);
        f.check("fmi2Reset", f.reset());
        assert_eq!(fmi2SetFMUstate(f.c, 0x1234_5678 as fmi2FMUstate), fmi2Error);
        f.check("fmi2Reset", f.reset());
        // NULL arguments
        assert_eq!(fmi2GetReal(f.c, ptr::null(), 3, ptr::null_mut()), fmi2Error);
        f.check("fmi2Reset", f.reset());
        assert_eq!(fmi2GetFMUstate(f.c, ptr::null_mut()), fmi2Error);
        drop(g); // `foreign` is freed with its instance
    }
    let counts = f.log.counts();
    assert!(counts[fmi2Error as usize] + counts[fmi2Fatal as usize] >= 10);
}

fn main() {
    let mut args = std::env::args().skip(1);
    let rounds: usize = args.next().map_or(2, |a| a.parse().expect("ROUNDS"));
    let steps: usize = args.next().map_or(400, |a| a.parse().expect("STEPS"));
    let cases = [
        rigid_case(1.0, 2.0),
        crushing_case(1.0, 2e5, 1.2),
        overturning_case(false),
        overturning_case(true),
    ];
    let t0 = Instant::now();
    for round in 0..rounds {
        for case in &cases {
            let s = exercise(case, round, steps);
            let names = [
                "full",
                "partial",
                "partialCrushing",
                "fullCrushing",
                "overturned",
            ];
            let seen: Vec<&str> = (0..5).filter(|&i| s.regimes[i]).map(|i| names[i]).collect();
            println!(
                "round {round} {:<22} {:>5} steps, {:>3} impacts, regimes {:?}{}",
                case.name,
                s.steps,
                s.impacts,
                seen,
                s.overturned_at
                    .map_or(String::new(), |t| format!(", overturned at t = {t:.4} s"))
            );
        }
        error_paths();
    }
    println!(
        "c_api_loop: {rounds} round(s), {steps} steps per case, all checks passed in {:.2} s",
        t0.elapsed().as_secs_f64()
    );
}
