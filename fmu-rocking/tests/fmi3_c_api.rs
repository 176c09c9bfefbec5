//! Random sequences of FMI 3.0 calls through the exported C functions, on
//! co-simulation instances (with and without event mode and early return)
//! and Model Exchange instances, against an oracle of FMI 3.0's state
//! machine (FMI 3.0 §3.2, §4.2, the state diagrams):
//!
//! - a call the standard forbids in the current state returns `fmi3Error`
//!   (and one line reaches the logger); the instance is then in an error
//!   state where only `fmi3Reset` and `fmi3FreeInstance` lead out;
//! - an allowed call returns `fmi3OK` (or `fmi3Warning`), never `fmi3Fatal`:
//!   no panic crosses the boundary;
//! - `fmi3DoStep`: `lastSuccessfulTime` is in `(t, t + h]`, before `t + h`
//!   exactly when it returns early, which only an instance with
//!   `earlyReturnAllowed` does; `eventHandlingNeeded` only with
//!   `eventModeUsed`;
//! - an FMU state taken, serialized, deserialized and set gives back the
//!   same outputs bit for bit; bad sizes and value references are refused.
//!
//! Fixed seed unless `PROPTEST_RNG_SEED` is set; `PROPTEST_CASES` sets the
//! number of sequences (default 512, about a second in release).

mod fmi3_driver;

use fmi3_driver::*;
use fmu_rocking::description::{vr, ROCKING_BLOCK};
use fmu_rocking::*;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        3 => Just(Op::EnterInit),
        3 => Just(Op::ExitInit),
        8 => (prop::sample::select(vec![1e-3, 0.01, 0.05, 0.2, 4.4e-16]), -6.0..6.0f64)
            .prop_map(|(h, ag)| Op::DoStep { h, ag }),
        2 => Just(Op::EnterEventMode),
        2 => Just(Op::UpdateDiscreteStates),
        2 => Just(Op::EnterStepMode),
        2 => Just(Op::EnterContinuousTime),
        2 => prop::sample::select(vec![0.0, 1e-3, 0.01]).prop_map(|dt| Op::SetTime { dt }),
        2 => Just(Op::CompletedIntegratorStep),
        2 => (0usize..4).prop_map(|n| Op::Derivatives { n }),
        2 => Just(Op::StateRoundTrip),
        2 => (0u32..70).prop_map(|vr| Op::GetFloat64 { vr }),
        1 => Just(Op::SetInt32OnEnumeration),
        3 => (0usize..5, 0usize..3, 0usize..4)
            .prop_map(|(which, value, bad)| Op::SetReal { which, value, bad }),
        1 => (0i32..4, any::<bool>()).prop_map(|(order, mismatch)| Op::OutputDerivative { order, mismatch }),
        1 => (0usize..4, any::<bool>()).prop_map(|(n, nan)| Op::SetStates { n, nan }),
        1 => (10usize..14).prop_map(|n| Op::EventIndicators { n }),
        1 => Just(Op::Terminate),
        1 => Just(Op::Reset),
    ]
}

fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(512);
    let mut c = ProptestConfig {
        cases,
        max_shrink_iters: 256,
        ..ProptestConfig::default()
    };
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = RngSeed::Fixed(0x464d_4933);
    }
    c
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn random_fmi3_call_sequences(me in any::<bool>(), event_mode in any::<bool>(), early in any::<bool>(),
                                  started in any::<bool>(), ops in prop::collection::vec(op(), 0..60)) {
        let mut run = Run::new(me, event_mode, early);
        let prefix = if started { start(me, event_mode) } else { vec![] };
        for o in prefix.iter().chain(&ops) {
            run.apply(o);
        }
    }
}

/// Early returns under the oracle: a started co-simulation instance with
/// event mode, the default block under a 2 Hz ground acceleration, returns
/// early at the zero crossings of theta, and the oracle's checks hold at
/// each.
#[test]
fn a_forced_run_returns_early_and_handles_its_events() {
    let mut run = Run::new(false, true, true);
    for o in start(false, true) {
        run.apply(&o);
    }
    let mut early = 0;
    for k in 0..80 {
        let t = run.t;
        let ag = if k < 20 {
            3.0 * (4.0 * std::f64::consts::PI * t).sin()
        } else {
            0.0
        };
        run.apply(&Op::DoStep { h: 0.05, ag });
        if run.mode == Mode::Step && run.t < t + 0.05 {
            early += 1;
            for o in [
                Op::EnterEventMode,
                Op::UpdateDiscreteStates,
                Op::EnterStepMode,
            ] {
                run.apply(&o);
            }
        }
        if run.mode != Mode::Step {
            break;
        }
    }
    assert!(
        early >= 2,
        "{early} early returns, mode {:?} at t = {}",
        run.mode,
        run.t
    );
}

/// A started co-simulation instance with event mode and early return.
fn event_instance() -> Run {
    let mut run = Run::new(false, true, true);
    for o in start(false, true) {
        run.apply(&o);
    }
    run
}

/// The forced run's ground acceleration, held over the step from `t`.
fn forcing(t: f64) -> f64 {
    3.0 * (4.0 * std::f64::consts::PI * t).sin()
}

/// One step of `run` to `end` under the ground acceleration held at `ag`,
/// with the event mode that follows an event: (end time, returned early,
/// zero crossings of theta in the step, eventHandlingNeeded).
fn step_to(run: &mut Run, end: f64, ag: f64) -> (f64, bool, i32, bool) {
    let (c, t) = (run.c, run.t);
    let crossings = || {
        let mut z = 0i32;
        // SAFETY: one value reference, one value.
        assert_eq!(
            unsafe { fmi3GetInt32(c, &vr::ZERO_CROSSINGS, 1, &mut z, 1) },
            OK
        );
        z
    };
    let before = crossings();
    // SAFETY: every pointer is to a live local.
    let (s, event, early, last) = unsafe {
        assert_eq!(fmi3SetFloat64(c, &vr::AG, 1, &ag, 1), OK);
        let (mut event, mut term, mut early, mut last) = (false, false, false, -1.0);
        let s = fmi3DoStep(
            c,
            t,
            end - t,
            false,
            &mut event,
            &mut term,
            &mut early,
            &mut last,
        );
        assert!(!term);
        (s, event, early, last)
    };
    assert_eq!(s, OK);
    assert!(last >= t && last <= end, "{last} outside [{t}, {end}]");
    assert_eq!(
        early,
        last < end,
        "earlyReturn exactly when the step stopped before its end"
    );
    run.t = last;
    if event {
        for o in [
            Op::EnterEventMode,
            Op::UpdateDiscreteStates,
            Op::EnterStepMode,
        ] {
            run.apply(&o);
        }
    }
    (last, early, crossings() - before, event)
}

/// Regression: a zero crossing of theta located at the very end of a step
/// (an impact within the step's last ulp, the event's time rounding to
/// `t + h`) was applied without `eventHandlingNeeded`, so a host never
/// heard of it. Each early return of the forced run is replayed with steps
/// that end at the event's time and up to 3 ulps before it, then steps of
/// one ulp across it: every step that applies a crossing reports exactly
/// one event, and no other step reports one.
#[test]
fn every_zero_crossing_is_reported_once_even_at_a_step_end() {
    let mut first = event_instance();
    // (start of the step that returned early, the event's time)
    let mut events = Vec::new();
    while events.len() < 6 && first.t < 3.0 {
        let t = first.t;
        let (last, early, n, event) = step_to(&mut first, t + 0.05, forcing(t));
        assert_eq!(n, event as i32, "a crossing without its event at {last}");
        if early {
            events.push((t, last));
        }
    }
    assert_eq!(events.len(), 6, "{events:?}");
    let (mut at_end, mut steps) = (0, 0);
    for &(tp, te) in &events {
        for ulps in 0..4 {
            let mut run = event_instance();
            // the forced run's steps (and its earlier early returns) to tp
            while run.t < tp {
                let t = run.t;
                step_to(&mut run, (t + 0.05).min(tp), forcing(t));
            }
            assert_eq!(run.t, tp, "the replay of the forced run");
            let mut end = te;
            for _ in 0..ulps {
                end = end.next_down();
            }
            let (mut crossings, mut reported) = (0, 0);
            let mut next = end;
            while run.t <= te.next_up() {
                let (last, early, n, event) = step_to(&mut run, next, forcing(tp));
                assert!(
                    n <= 1 && n == event as i32,
                    "{n} crossings, event {event} at {last}"
                );
                at_end += (event && !early) as i32;
                (crossings, reported, steps) = (crossings + n, reported + event as i32, steps + 1);
                next = run.t.next_up();
            }
            assert_eq!(
                (crossings, reported),
                (1, 1),
                "event at {te}, {ulps} ulps before"
            );
        }
    }
    // the replays do meet the case: events at a step's very end
    assert!(at_end > 0, "no event at a step's end in {steps} steps");
}

/// The libFuzzer target's decoder (`fuzz/fuzz_targets/c_api3.rs`) on 256
/// pseudo-random inputs (a fixed linear congruential sequence) and on the
/// committed seeds (`fuzz/corpus/c_api3`): every sequence meets the oracle.
#[test]
fn fuzz_decoder_inputs_meet_the_oracle() {
    let mut x = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..256 {
        let len = (x >> 56) as usize;
        let data: Vec<u8> = (0..len)
            .map(|_| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (x >> 33) as u8
            })
            .collect();
        run_bytes(&data);
    }
    let seeds = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/c_api3");
    for entry in std::fs::read_dir(&seeds).expect("fuzz/corpus/c_api3") {
        run_bytes(&std::fs::read(entry.unwrap().path()).unwrap());
    }
}

/// Replays one libFuzzer input, printing its operations:
/// `FUZZ_INPUT=fuzz/artifacts/c_api3/crash-... cargo test --release -p
/// fmu-rocking --test fmi3_c_api -- --ignored --nocapture replay_fuzz_input`.
#[test]
#[ignore]
fn replay_fuzz_input() {
    // the path is relative to the repository's root
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let data = std::fs::read(root.join(std::env::var("FUZZ_INPUT").expect("FUZZ_INPUT")))
        .expect("read FUZZ_INPUT");
    run_bytes_traced(&data, true);
}

/// Regression (found by the c_api3 libFuzzer target): an FMU state taken in
/// a co-simulation instance's event mode (eventModeUsed) serialized, but
/// deserializing it was refused as "a state in state eventMode belongs to
/// an instance of the other fmuType" (2.0 has event mode in Model Exchange
/// only). The round trip (`Op::StateRoundTrip` checks the outputs bit for
/// bit, and ends with a truncated buffer the instance must refuse) after
/// initialization and after an early return's event.
#[test]
fn a_state_taken_in_co_simulation_event_mode_round_trips() {
    let mut run = Run::new(false, true, true);
    for o in [Op::EnterInit, Op::ExitInit, Op::StateRoundTrip] {
        run.apply(&o);
    }
    let mut run = event_instance();
    while run.t < 2.0 {
        let t = run.t;
        run.apply(&Op::DoStep {
            h: 0.05,
            ag: forcing(t),
        });
        if run.t < t + 0.05 {
            run.apply(&Op::EnterEventMode);
            run.apply(&Op::StateRoundTrip);
            return;
        }
    }
    panic!("no early return by t = {}", run.t);
}

/// Regression (found by the c_api3 libFuzzer target): reading an event
/// indicator before initialization builds the model to evaluate it; an FMU
/// state taken then saved that model's state, and deserializing the
/// serialized state was refused ("a model state in state instantiated").
/// Each interface, fresh and after a reset.
#[test]
fn a_state_taken_before_initialization_round_trips() {
    let indicator = ROCKING_BLOCK.fmi3_event_indicator_vr(0);
    for (me, event_mode) in [(false, false), (false, true), (true, false)] {
        let mut run = Run::new(me, event_mode, event_mode);
        for o in [Op::GetFloat64 { vr: indicator }, Op::StateRoundTrip] {
            run.apply(&o);
        }
        let mut run = Run::new(me, event_mode, event_mode);
        for o in start(me, event_mode) {
            run.apply(&o);
        }
        for o in [
            Op::Reset,
            Op::GetFloat64 { vr: indicator },
            Op::StateRoundTrip,
        ] {
            run.apply(&o);
        }
    }
}
