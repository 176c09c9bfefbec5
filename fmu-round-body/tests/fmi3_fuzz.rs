//! Random sequences of FMI 3.0 calls on RoundBody.fmu through the exported C
//! functions, on co-simulation instances with and without event mode and
//! early return, and on Model Exchange instances,
//! against an oracle of FMI 3.0's state machine (`tests/fmi3_driver`, the
//! interpreter of the libFuzzer target `fuzz/fuzz_targets/round_body3.rs`):
//!
//! - a call the standard forbids in the current state returns `fmi3Error`
//!   with a message; the instance is then in an error state where only
//!   `fmi3Reset` and `fmi3FreeInstance` lead out;
//! - an allowed call returns `fmi3OK` (or `fmi3Warning`), never
//!   `fmi3Fatal`, and no panic happens in the FMU, not even a caught one;
//! - `fmi3DoStep`: `lastSuccessfulTime` in `[t, t + h]`, before `t + h`
//!   only when it returns early, which only an instance with
//!   `earlyReturnAllowed` does; `eventHandlingNeeded` only with
//!   `eventModeUsed`;
//! - an FMU state taken, serialized, deserialized and set gives back the
//!   same outputs bit for bit; bad sizes, NULL arrays, unknown value
//!   references, non-finite inputs and output derivatives are refused.
//!
//! Fixed seed unless `PROPTEST_RNG_SEED` is set; `PROPTEST_CASES` sets the
//! number of sequences (default 512).

mod fmi3_driver;

use fmi3_driver::*;
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
        1 => Just(Op::EnterContinuousTime),
        1 => prop::sample::select(vec![0.0, 1e-3, 0.01]).prop_map(|dt| Op::SetTime { dt }),
        1 => Just(Op::CompletedIntegratorStep),
        1 => (0usize..9).prop_map(|n| Op::Derivatives { n }),
        3 => Just(Op::StateRoundTrip),
        2 => (0u32..60).prop_map(|vr| Op::GetFloat64 { vr }),
        1 => Just(Op::SetInt32OnEnumeration),
        3 => (0usize..5, 0usize..4, 0usize..4)
            .prop_map(|(which, value, bad)| Op::SetReal { which, value, bad }),
        1 => (0i32..4, any::<bool>()).prop_map(|(order, mismatch)| Op::OutputDerivative { order, mismatch }),
        1 => (0usize..9, any::<bool>()).prop_map(|(n, nan)| Op::SetStates { n, nan }),
        1 => (0usize..9).prop_map(|n| Op::EventIndicators { n }),
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
        c.rng_seed = RngSeed::Fixed(0x5242_4633);
    }
    c
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn random_fmi3_call_sequences(me in any::<bool>(), event_mode in any::<bool>(), early in any::<bool>(),
                                  started in any::<bool>(), ops in prop::collection::vec(op(), 0..60)) {
        let mut run = Run::new(me, event_mode, early);
        let prefix = if started { start(run.me, event_mode) } else { vec![] };
        for o in prefix.iter().chain(&ops) {
            run.apply(o);
        }
    }
}

/// A started co-simulation instance with event mode and early return
/// under both components: 100 steps of 0.05 s that rock the drum; after
/// each early return (uplift, impacts) event mode is entered and left, and
/// every tenth step the FMU state round trip; the oracle's checks hold at
/// each, and the run does return early.
#[test]
fn a_forced_run_returns_early_and_handles_its_events() {
    let mut run = Run::new(false, true, true);
    for o in start(false, true) {
        run.apply(&o);
    }
    let mut early = 0;
    for k in 0..100 {
        let t = run.t;
        let ag = 4.0 * (4.0 * std::f64::consts::PI * t).sin();
        run.apply(&Op::DoStep { h: 0.05, ag });
        if run.mode != Mode::Step {
            break;
        }
        if run.t < t + 0.05 {
            early += 1;
            for o in [
                Op::EnterEventMode,
                Op::UpdateDiscreteStates,
                Op::EnterStepMode,
            ] {
                run.apply(&o);
            }
        }
        if k % 10 == 9 {
            run.apply(&Op::StateRoundTrip);
        }
    }
    assert!(
        early >= 2,
        "{early} early returns, mode {:?} at t = {}",
        run.mode,
        run.t
    );
}

/// The libFuzzer target's decoder on 256 pseudo-random inputs (a fixed
/// linear congruential sequence) and on the committed seeds
/// (`fuzz/corpus/round_body3`): every sequence meets the oracle.
#[test]
fn fuzz_decoder_inputs_and_the_committed_seeds_meet_the_oracle() {
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
    let seeds = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/round_body3");
    let mut n = 0;
    for entry in std::fs::read_dir(&seeds).expect("fuzz/corpus/round_body3") {
        run_bytes(&std::fs::read(entry.unwrap().path()).unwrap());
        n += 1;
    }
    assert!(n > 0, "no seeds in {}", seeds.display());
}

/// Replays one libFuzzer input, printing its operations:
/// `FUZZ_INPUT=fuzz/artifacts/round_body3/crash-... cargo test --profile ci
/// -p fmu-round-body --test fmi3_fuzz -- --ignored --nocapture
/// replay_fuzz_input`.
#[test]
#[ignore = "by hand, with FUZZ_INPUT"]
fn replay_fuzz_input() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let data = std::fs::read(root.join(std::env::var("FUZZ_INPUT").expect("FUZZ_INPUT")))
        .expect("read FUZZ_INPUT");
    run_bytes_traced(&data, true);
}
