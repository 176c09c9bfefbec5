//! Random sequences of FMI 2.0 calls through the exported C functions, with
//! the same interpreter as the libFuzzer target `fuzz/fuzz_targets/c_api.rs`
//! (`fmi2-fuzz-driver`: the operations, the invariants it checks after every
//! call, and why; `tests/fuzz_driver/mod.rs`: what is RockingBlock's).
//!
//! - `random_call_sequences`: arbitrary bytes decoded into up to 160
//!   operations on up to 4 instances (the fuzz target's input format);
//! - `random_calls_on_a_running_instance`: the same after a valid start, so
//!   that most calls meet an initialized instance;
//! - `random_serialized_states`: fully random, mutated, truncated and
//!   re-sealed (valid checksum, edited payload) buffers to
//!   `fmi2DeSerializeFMUstate`;
//! - `random_parameter_sets`: valid and invalid parameter sets: exit from
//!   initialization mode succeeds exactly for the valid ones, and the
//!   instance resets, initializes with the defaults and frees cleanly after;
//! - `regression_*`: inputs the fuzzer found (replayed as bytes).
//!
//! The cases are the same on every run (fixed seed) unless
//! `PROPTEST_RNG_SEED` is set. `PROPTEST_CASES` sets the number of cases of every property (the default
//! keeps this file at a few seconds in release: 2048 sequences of each kind, 512 serialized-state cases, 1024 parameter sets).

mod fuzz_driver;

use fmi2_export::model_description::{Causality, Type};
use fmi2_export::types::*;
use fmu_rocking::description::{vr, ROCKING_BLOCK, VARIABLES};
use fuzz_driver::*;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

fn cases(default: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default);
    let mut config = ProptestConfig {
        cases,
        // The driver's checks are assertions inside the run: shrinking many
        // long sequences costs more than it tells.
        max_shrink_iters: 256,
        ..ProptestConfig::default()
    };
    // A fixed seed unless PROPTEST_RNG_SEED is given: the suite runs the
    // same cases every time (a rare stall of fmi2DoStep, not yet explained,
    // must not make CI flaky; the fuzzer and other seeds explore further).
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        config.rng_seed = RngSeed::Fixed(0x524f_434b);
    }
    config
}

/// Runs `ops` in a thread. If it has not finished after 60 s the process
/// exits with the operations printed: an fmi2DoStep that never returns must
/// fail the suite at once, not hang it (nor be shrunk, 60 s per try).
fn run_bounded(ops: Vec<Op>) -> Stats {
    let (tx, rx) = std::sync::mpsc::channel();
    let shown = format!("{ops:?}");
    std::thread::spawn(move || {
        let _ = tx.send(Driver::run(&ops));
    });
    match rx.recv_timeout(std::time::Duration::from_secs(60)) {
        Ok(stats) => stats,
        Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
            eprintln!("no answer after 60 s (stalled), operations: {shown}");
            std::process::exit(3);
        }
        // the driver panicked: its message is printed above
        Err(e) => panic!("the driver failed: {e}"),
    }
}

/// [`plain_instance`] of fmuType fmi2ModelExchange.
fn me_instance(slot: u8) -> Op {
    let Op::Instantiate(_, mut spec) = plain_instance(slot) else {
        unreachable!()
    };
    spec.fmu_type = fmi2ModelExchange;
    Op::Instantiate(slot, spec)
}

proptest! {
    #![proptest_config(cases(2048))]

    #[test]
    fn random_call_sequences(data in prop::collection::vec(any::<u8>(), 0..1500)) {
        run_bounded(decode(&data));
    }

    #[test]
    fn random_calls_on_a_running_instance(data in prop::collection::vec(any::<u8>(), 0..1500)) {
        let mut ops = vec![plain_instance(0), Op::Init(0), plain_instance(1), Op::Init(1)];
        ops.extend([me_instance(2), Op::Init(2)]);
        ops.extend(decode(&data));
        run_bounded(ops);
    }
}

/// A mutation of a serialized state, or random bytes.
fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        Just(Mutation::None),
        (any::<u16>(), 0u8..8).prop_map(|(pos, bit)| Mutation::Flip { pos, bit }),
        any::<u16>().prop_map(Mutation::Truncate),
        prop::collection::vec(any::<u8>(), 1..16).prop_map(Mutation::Append),
        (
            prop::collection::vec((any::<u16>(), any::<u8>()), 1..6),
            0u16..24,
            prop::collection::vec(any::<u8>(), 0..16)
        )
            .prop_map(|(edits, cut, extend)| Mutation::Reseal { edits, cut, extend }),
        prop::collection::vec(any::<u8>(), 0..600).prop_map(Mutation::Random),
    ]
}

proptest! {
    #![proptest_config(cases(512))]

    /// Buffers to fmi2DeSerializeFMUstate: genuine (from states taken in
    /// initialization mode, after steps, after an overturn), then mutated,
    /// re-sealed or random; every accepted one restores or is refused
    /// cleanly, and serializes back to the same bytes.
    #[test]
    fn random_serialized_states(
        ag in -30.0f64..30.0,
        steps in 0usize..40,
        mutations in prop::collection::vec((any::<u8>(), mutation()), 1..12),
        restore in any::<bool>(),
    ) {
        let mut ops = vec![
            plain_instance(0),
            Op::EnterInit(0),
            Op::GetState(0, None),
            Op::Serialize(0, StateRef::Of { slot: 0, k: 0 }, 0),
            Op::ExitInit(0),
            Op::SetReal(0, vec![vr::AG], vec![ag]),
        ];
        for _ in 0..steps {
            ops.push(step(0, 0.05));
        }
        ops.push(Op::GetState(0, None));
        ops.push(Op::Serialize(0, StateRef::Of { slot: 0, k: 1 }, 2));
        ops.push(plain_instance(1));
        for (from, m) in mutations {
            ops.push(Op::Deserialize(1, from, m));
            if restore {
                ops.push(Op::SetState(1, StateRef::Of { slot: 1, k: 255 }));
                ops.push(Op::GetAll(1));
                ops.push(step(1, 0.05));
            }
        }
        run_bounded(ops);
    }
}

/// A value for a Real parameter: plausible (a factor of its start value) or
/// awkward (zero, negative, NaN, infinities, denormals, huge).
fn real_value(start: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => (0.2f64..5.0).prop_map(move |f| start * f),
        1 => Just(start),
        1 => prop::sample::select(vec![
            0.0,
            -0.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            5e-324,
            f64::MIN_POSITIVE,
            1e300,
            -1e300,
            f64::MAX,
        ]),
    ]
}

/// Every parameter and start value, each set or left at its start.
fn parameter_set() -> impl Strategy<Value = (Vec<u32>, Vec<f64>, Vec<u32>, Vec<i32>)> {
    let reals: Vec<_> = VARIABLES
        .iter()
        .filter(|v| {
            matches!(v.ty, Type::Real { .. })
                && (v.causality == Causality::Parameter || matches!(v.vr, vr::THETA | vr::OMEGA))
        })
        .map(|v| {
            let start = match v.ty {
                Type::Real { start, .. } => start.unwrap_or(0.0),
                _ => 0.0,
            };
            // theta and omega around small rotations and velocities
            let start = if start == 0.0 { 0.01 } else { start };
            (Just(v.vr), prop::option::weighted(0.7, real_value(start)))
        })
        .collect();
    let enums: Vec<_> = VARIABLES
        .iter()
        .filter(|v| matches!(v.ty, Type::Enumeration { .. }))
        .map(|v| {
            (
                Just(v.vr),
                prop::option::weighted(0.8, prop_oneof![8 => 1i32..=4, 1 => any::<i32>()]),
            )
        })
        .collect();
    (reals, enums).prop_map(|(reals, enums)| {
        let (rv, rx): (Vec<u32>, Vec<f64>) = reals
            .into_iter()
            .filter_map(|(r, x)| x.map(|x| (r, x)))
            .unzip();
        let (iv, ix): (Vec<u32>, Vec<i32>) = enums
            .into_iter()
            .filter_map(|(r, x)| x.map(|x| (r, x)))
            .unzip();
        (rv, rx, iv, ix)
    })
}

proptest! {
    #![proptest_config(cases(1024))]

    /// The driver checks at fmi2ExitInitializationMode that the status is
    /// fmi2OK exactly when `rocking::Params::build` accepts the values it
    /// set, fmi2Error otherwise; then the instance must reset (fmi2OK),
    /// initialize with the defaults (fmi2OK) and free cleanly.
    #[test]
    fn random_parameter_sets(
        (rv, rx, iv, ix) in parameter_set(),
        one_by_one in any::<bool>(),
        ag in -20.0f64..20.0,
    ) {
        // An out-of-range enumeration value is refused when set: the
        // instance is then in the error state until the reset.
        let refused_before_init = iv.iter().zip(&ix).any(|(&r, &x)| !enum_item(r, x));
        let mut ops = vec![plain_instance(0)];
        if one_by_one {
            for (r, x) in rv.iter().zip(&rx) {
                ops.push(Op::SetReal(0, vec![*r], vec![*x]));
            }
            for (r, x) in iv.iter().zip(&ix) {
                ops.push(Op::SetInteger(0, vec![*r], vec![*x]));
            }
        } else {
            ops.push(Op::SetReal(0, rv, rx));
            ops.push(Op::SetInteger(0, iv, ix));
        }
        // (No getter before the exit: a calculated value of an invalid set
        // is already fmi2Error, and the exit would then meet the error state.)
        ops.extend([
            Op::EnterInit(0),
            Op::ExitInit(0),
            Op::GetAll(0),
            Op::SetReal(0, vec![vr::AG], vec![ag]),
            step(0, 0.1),
            Op::GetAll(0),
            Op::GetState(0, None),
            Op::Terminate(0),
            Op::Reset(0),
            Op::Init(0),
            step(0, 0.1),
            Op::GetAll(0),
            Op::Free(0),
        ]);
        let stats = run_bounded(ops);
        // Whatever the set, the second initialization (defaults) succeeded;
        // the first was checked unless a refused enumeration value came
        // before it.
        prop_assert!(stats.exit_init_ok >= 1, "{stats:?}");
        let checked = if refused_before_init { 1 } else { 2 };
        prop_assert_eq!(stats.exit_init_ok + stats.exit_init_error, checked, "{:?}", stats);
    }
}

/// Whether `x` is an item of the enumeration `r`.
fn enum_item(r: u32, x: i32) -> bool {
    VARIABLES.iter().any(|v| match v.ty {
        Type::Enumeration { declared_type, .. } if v.vr == r => ROCKING_BLOCK
            .enum_type(declared_type)
            .is_some_and(|t| t.item(x).is_some()),
        _ => false,
    })
}

/// The serialized state of an instance in initialization mode, then
/// `mutation` of it to a second instance; the driver's statistics.
fn deserialize_mutated(mutation: Mutation) -> Stats {
    Driver::run(&[
        plain_instance(0),
        Op::Init(0),
        Op::GetState(0, None),
        Op::Serialize(0, StateRef::Of { slot: 0, k: 0 }, 0),
        plain_instance(1),
        Op::Deserialize(1, 0, mutation),
    ])
}

/// Found by the proptests of this file (the driver's check that an accepted
/// buffer serializes back to the same bytes): a valid envelope followed by
/// anything was accepted, the bytes after it ignored. Now only zero padding
/// (what fmi2SerializeFMUstate writes into a larger buffer) may follow.
#[test]
fn regression_bytes_after_a_serialized_state_are_refused() {
    for tail in [vec![1u8], vec![0, 0, 0, 7], vec![0xff; 64]] {
        let stats = deserialize_mutated(Mutation::Append(tail.clone()));
        assert_eq!(stats.deserialized, 0, "accepted with {tail:?} appended");
    }
    for zeros in [1, 4, 100] {
        let stats = deserialize_mutated(Mutation::Append(vec![0; zeros]));
        assert_eq!(stats.deserialized, 1, "{zeros} zero bytes of padding");
    }
    assert_eq!(deserialize_mutated(Mutation::None).deserialized, 1);
}

/// Found by `random_call_sequences` (the driver's check that calculated
/// parameters are finite): for a body of next to no weight (rho = 1e-300,
/// or a lumped W = 1e-300) thetaJo is subnormal, the overturning scan's
/// ratio overflowed and thetaOv came out +inf (the body could never
/// overturn), and the model was accepted. Such a set is now refused at
/// fmi2ExitInitializationMode (thetaJo >= 1e-100 rad, thetaOv finite); the
/// driver checks that the status agrees with `Params::build` and that no
/// calculated parameter is infinite.
#[test]
fn regression_weightless_body_has_no_infinite_theta_ov() {
    use fmu_rocking::description::enums::LUMPED;
    let cases: [(Vec<u32>, Vec<f64>, Vec<i32>); 3] = [
        (vec![vr::RHO, vr::OMEGA], vec![1e-300, 0.005], vec![]),
        (vec![vr::RHO], vec![1e-305], vec![]),
        (vec![vr::W, vr::IC], vec![1e-300, 1e-300], vec![LUMPED]),
    ];
    for (r, x, mass_model) in cases {
        let mut ops = vec![plain_instance(0), Op::SetReal(0, r, x)];
        if !mass_model.is_empty() {
            ops.push(Op::SetInteger(0, vec![vr::MASS_MODEL], mass_model));
        }
        ops.extend([
            Op::EnterInit(0),
            Op::ExitInit(0),
            Op::GetAll(0),
            Op::Reset(0),
            Op::Init(0),
        ]);
        let stats = Driver::run(&ops);
        assert_eq!(stats.exit_init_ok + stats.exit_init_error, 2, "{stats:?}");
    }
}

/// Found when the previous test's parameters were stepped (the proptests
/// hung): for a body of next to no weight (rho = 1e-150) the integrator's
/// error scales were ~1e-167, its starting-step estimate squared a0/scale,
/// overflowed, the first step was 0 and the step loop repeated it for ever
/// (fmi2DoStep never returned). Such bodies are now refused at
/// fmi2ExitInitializationMode; whatever happens, every call must return.
#[test]
fn regression_stepping_a_weightless_body_returns() {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for ag in [3.0, -30.0, 0.0] {
            let mut ops = vec![
                plain_instance(0),
                Op::SetReal(0, vec![vr::RHO, vr::OMEGA], vec![1e-150, 0.005]),
                Op::Init(0),
                Op::SetReal(0, vec![vr::AG], vec![ag]),
            ];
            for _ in 0..20 {
                ops.push(step(0, 0.1));
                ops.push(Op::GetAll(0));
            }
            let mut d = Driver::new();
            d.tolerate_known = false;
            for op in &ops {
                d.apply(op);
            }
            d.finish();
        }
        let _ = tx.send(());
    });
    rx.recv_timeout(std::time::Duration::from_secs(60))
        .expect("fmi2DoStep of a weightless body did not return within 60 s");
}

/// Found by `random_parameter_sets` (the driver's check that outputs read
/// with fmi2OK are finite): a finite but absurd start value omega = 1e300
/// rad/s (theta = 0.002) was accepted and fmi2GetReal returned Fx = NaN
/// (inf - inf) with fmi2OK; ag = 1e300 m/s2 gave Fx = inf. A computed value
/// that is not finite is now fmi2Error naming the variable and the state.
#[test]
fn regression_overflowing_outputs_are_refused_not_returned() {
    let ops = [
        plain_instance(0),
        Op::SetReal(0, vec![vr::THETA, vr::OMEGA], vec![0.002, 1e300]),
        Op::Init(0),
        Op::GetAll(0),
        Op::Reset(0),
        Op::GetOutputDerivatives(0, vec![vr::THETA], vec![2]),
        plain_instance(1),
        Op::Init(1),
        Op::SetReal(1, vec![vr::AG], vec![1e300]),
        Op::GetAll(1),
        Op::GetOutputDerivatives(1, vec![vr::OMEGA], vec![1]),
    ];
    let stats = Driver::run(&ops);
    assert_eq!(stats.exit_init_ok, 2, "{stats:?}");
    // The getters of the overflowing values were refused.
    assert!(stats.by_status[fmi2Error as usize] >= 2, "{stats:?}");
}

/// Found by `random_calls_on_a_running_instance` (PROPTEST_RNG_SEED=2: the
/// 60 s watchdog fired): ag = 1.8e308 m/s2 is finite, so it was accepted,
/// and fmi2DoStep never returned (the equations of motion overflow on the
/// way to overturning; from about 1e200 m/s2). A step now refuses |ag| >
/// 1e100 m/s2 at either end with fmi2Error, the state unchanged.
#[test]
fn regression_absurd_ground_acceleration_is_refused_not_hung() {
    for (ag, dag) in [(f64::MAX, 0.0), (1e200, 0.0), (-1e101, 0.0), (0.0, 1e300)] {
        let stats = run_bounded(vec![
            plain_instance(0),
            Op::Init(0),
            Op::SetReal(0, vec![vr::AG], vec![ag]),
            Op::SetInputDerivatives(0, vec![vr::AG], vec![1], vec![dag]),
            step(0, 0.05),
            Op::Reset(0),
            Op::Init(0),
            Op::SetReal(0, vec![vr::AG], vec![1e100]),
            step(0, 0.05),
        ]);
        assert_eq!(
            stats.steps_ok + stats.steps_discard,
            1,
            "ag {ag}: {stats:?}"
        );
    }
}

/// The engine's slow regime, kn = 1e18 Pa/m under ag = 1 m/s2 (below uplift,
/// explicit steps of ~1e-7 s): one fmi2DoStep of 0.1 s did not return within
/// 60 s before the work limit; now it stops at `maxSteps` with fmi2Discard
/// (the driver checks fmi2LastSuccessfulTime inside the step). The channel's
/// timeout is a watchdog against a hang, not a timing.
#[test]
fn extreme_stiffness_stops_at_the_work_limit() {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut d = Driver::new();
        d.tolerate_known = false;
        for op in [
            plain_instance(0),
            Op::SetReal(0, vec![vr::KN], vec![1e18]),
            Op::Init(0),
            Op::SetReal(0, vec![vr::AG], vec![1.0]),
            step(0, 0.1),
        ] {
            d.apply(&op);
        }
        let _ = tx.send(d.finish());
    });
    let stats = rx
        .recv_timeout(std::time::Duration::from_secs(60))
        .expect("one fmi2DoStep at kn = 1e18 returns");
    assert_eq!((stats.steps_ok, stats.steps_discard), (0, 1), "{stats:?}");
}

/// What random sequences reach (for the robustness notes, by hand:
/// `cargo test --release -p fmu-rocking --test c_api_fuzz -- --ignored --nocapture what_random_sequences_reach`):
/// the summed driver statistics of 256 inputs of each property's kind.
#[test]
#[ignore = "a report, not a check"]
fn what_random_sequences_reach() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let bytes = prop::collection::vec(any::<u8>(), 0..1500);
    for running in [false, true] {
        let mut total = Stats::default();
        let mut ops_total = 0;
        for _ in 0..256 {
            let data = bytes.new_tree(&mut runner).unwrap().current();
            let mut ops = if running {
                vec![
                    plain_instance(0),
                    Op::Init(0),
                    plain_instance(1),
                    Op::Init(1),
                    me_instance(2),
                    Op::Init(2),
                ]
            } else {
                Vec::new()
            };
            ops.extend(decode(&data));
            ops_total += ops.len();
            let s = Driver::run(&ops);
            total.calls += s.calls;
            total.instantiated += s.instantiated;
            total.steps_ok += s.steps_ok;
            total.model_exchange_ok += s.model_exchange_ok;
            total.steps_discard += s.steps_discard;
            total.steps_skipped += s.steps_skipped;
            total.exit_init_ok += s.exit_init_ok;
            total.exit_init_error += s.exit_init_error;
            total.restores_checked += s.restores_checked;
            total.deserialized += s.deserialized;
            for k in 0..5 {
                total.by_status[k] += s.by_status[k];
            }
        }
        println!("running start {running}: {ops_total} operations, {total:?}");
    }
}

/// Replays one input of the fuzz target, printing its operations and the
/// time of each: `FUZZ_INPUT=fuzz/artifacts/c_api/crash-... cargo test
/// --release -p fmu-rocking --test c_api_fuzz -- --ignored --nocapture replay_fuzz_input`.
#[test]
#[ignore = "by hand, with FUZZ_INPUT"]
fn replay_fuzz_input() {
    let path = std::env::var("FUZZ_INPUT").expect("FUZZ_INPUT=path of an input");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(path);
    let data = std::fs::read(&path).expect("read FUZZ_INPUT");
    let mut d = Driver::new();
    for op in decode(&data) {
        println!("{op:?}");
        let t = std::time::Instant::now();
        d.apply(&op);
        println!("  {:?}", t.elapsed());
    }
    println!("{:?}", d.finish());
}

/// Event indicators the FMU declares.
const NZ: usize = fmu_rocking::description::EVENT_INDICATORS as usize;

/// Model Exchange through the driver: an ME instance, initialized, answers
/// its evaluations and mode changes (the random sequences reach them too:
/// `what_random_sequences_reach` counts `model_exchange_ok`).
#[test]
fn model_exchange_sequence() {
    install_panic_counter();
    let me = |which: u8, n: usize| Op::Me {
        slot: 0,
        which,
        x: vec![0.05, 0.0],
        n,
    };
    let mut ops = vec![me_instance(0)];
    ops.push(Op::Init(0));
    for w in [5, 2, 3, 4, 7, 8, 0, 1, 3, 4, 9, 6, 7, 8, 3] {
        ops.push(me(w, if w == 4 { NZ } else { 2 }));
    }
    let stats = run_bounded(ops);
    assert_eq!(stats.model_exchange_ok, 15, "{stats:?}");
}

/// Writes, for every committed seed of `fuzz/corpus/c_api`, its decoded
/// operations and the driver's final statistics to the file `DUMP_OUT`
/// ([`fmi2_fuzz_driver::dump_corpus`]): `DUMP_OUT=/tmp/a cargo test
/// --profile ci -p PACKAGE --test TEST -- --ignored dump_corpus`.
#[test]
#[ignore = "by hand, with DUMP_OUT"]
fn dump_corpus() {
    let out = std::env::var("DUMP_OUT").expect("DUMP_OUT=path of the dump");
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/c_api");
    std::fs::write(&out, fmi2_fuzz_driver::dump_corpus::<RockingBlock>(&dir))
        .expect("write DUMP_OUT");
}
