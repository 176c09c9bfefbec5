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

use std::ffi::{c_char, c_void, CStr};
use std::ptr;

use fmi2_export::model_description::BaseType;
use fmu_rocking::description::{vr, ROCKING_BLOCK};
use fmu_rocking::*;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

const OK: i32 = 0;
const WARNING: i32 = 1;
const DISCARD: i32 = 2;
const ERROR: i32 = 3;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Instantiated,
    Initialization,
    Step,
    Event,
    ContinuousTime,
    /// After `terminateSimulation`: only `fmi3Terminate` goes on.
    Ended,
    Terminated,
    Error,
}

#[derive(Clone, Debug)]
enum Op {
    EnterInit,
    ExitInit,
    DoStep {
        h: f64,
        ag: f64,
    },
    EnterEventMode,
    UpdateDiscreteStates,
    EnterStepMode,
    EnterContinuousTime,
    SetTime {
        dt: f64,
    },
    CompletedIntegratorStep,
    Derivatives {
        n: usize,
    },
    StateRoundTrip,
    GetFloat64 {
        vr: u32,
    },
    SetInt32OnEnumeration,
    /// `fmi3SetFloat64` of one input (`ag`, `av`, `der(ag)`, `der(av)`) or
    /// an unknown value reference, maybe non-finite, maybe with a bad size
    /// or a NULL array.
    SetReal {
        which: usize,
        value: usize,
        bad: usize,
    },
    /// `fmi3GetOutputDerivatives` of theta, order 0..3, maybe nValues wrong.
    OutputDerivative {
        order: i32,
        mismatch: bool,
    },
    /// `fmi3SetContinuousStates` with `n` states, maybe a NaN among them.
    SetStates {
        n: usize,
        nan: bool,
    },
    /// `fmi3GetEventIndicators` into `n` places.
    EventIndicators {
        n: usize,
    },
    Terminate,
    Reset,
}

/// `SetReal`'s value references: the inputs, their derivatives, unknown.
const SET_REAL_VRS: [u32; 5] = [vr::AG, vr::AV, 68, 69, 9999];
const SET_REAL_VALUES: [f64; 3] = [0.5, f64::NAN, f64::INFINITY];

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        3 => Just(Op::EnterInit),
        3 => Just(Op::ExitInit),
        8 => (prop::sample::select(vec![1e-3, 0.01, 0.05, 0.2]), -6.0..6.0f64)
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

unsafe extern "C" fn count_messages(
    env: *mut c_void,
    _s: i32,
    _c: *const c_char,
    m: *const c_char,
) {
    // SAFETY: env is the counter this test passed; m a C string from the FMU.
    unsafe {
        assert!(!CStr::from_ptr(m).to_bytes().is_empty());
        *(env as *mut usize) += 1;
    }
}

struct Run {
    c: *mut c_void,
    me: bool,
    event_mode: bool,
    early: bool,
    mode: Mode,
    t: f64,
    messages: Box<usize>,
    /// Messages logged before the current call.
    before: usize,
}

impl Run {
    fn new(me: bool, event_mode: bool, early: bool) -> Run {
        let mut messages = Box::new(0usize);
        let env = &mut *messages as *mut usize as *mut c_void;
        let guid = std::ffi::CString::new(GUID).unwrap();
        // SAFETY: valid strings and callback; the instance is freed in Drop.
        let c = unsafe {
            if me {
                fmi3InstantiateModelExchange(
                    c"m".as_ptr(),
                    guid.as_ptr(),
                    ptr::null(),
                    false,
                    false,
                    env,
                    Some(count_messages),
                )
            } else {
                fmi3InstantiateCoSimulation(
                    c"c".as_ptr(),
                    guid.as_ptr(),
                    ptr::null(),
                    false,
                    false,
                    event_mode,
                    early,
                    ptr::null(),
                    0,
                    env,
                    Some(count_messages),
                    ptr::null(),
                )
            }
        };
        assert!(!c.is_null());
        Run {
            c,
            me,
            event_mode: event_mode && !me,
            early: early && !me,
            mode: Mode::Instantiated,
            t: 0.0,
            messages,
            before: 0,
        }
    }

    /// In the error state the evaluations and FMU-state functions may
    /// answer (FMI 2.0's masks, which the layer keeps); anything but fatal.
    fn lenient(&mut self, status: i32, what: &Op) {
        assert!(status != 4, "{what:?}: fmi3Fatal");
    }

    /// A well-formed call whose answer depends on the state: never fatal,
    /// refused only with a message (and then in the error state).
    fn settled(&mut self, status: i32, what: &Op) {
        assert!(status != 4, "{what:?}: fmi3Fatal");
        if status == ERROR {
            assert!(
                *self.messages > self.before,
                "{what:?}: refused without a message"
            );
            self.mode = Mode::Error;
        }
    }

    /// Checks `status` against whether the oracle allows the call, and
    /// moves the oracle to `next` (or to the error state).
    fn expect(&mut self, allowed: bool, status: i32, next: Mode, what: &Op) {
        assert!(status != 4, "{what:?}: fmi3Fatal");
        if allowed {
            assert!(
                status == OK || status == WARNING,
                "{what:?} in {:?}: status {status}",
                self.mode
            );
            self.mode = next;
        } else {
            assert_eq!(status, ERROR, "{what:?} in {:?} must be refused", self.mode);
            assert!(
                *self.messages > self.before,
                "{what:?}: refused without a message"
            );
            self.mode = Mode::Error;
        }
    }

    fn outputs(&self) -> Option<[u64; 3]> {
        let vrs = [vr::THETA, vr::OMEGA, vr::AF];
        let mut out = [0.0; 3];
        // SAFETY: 3 value references, 3 values.
        let s = unsafe { fmi3GetFloat64(self.c, vrs.as_ptr(), 3, out.as_mut_ptr(), 3) };
        (s == OK).then(|| out.map(f64::to_bits))
    }

    fn apply(&mut self, op: &Op) {
        use Mode as M;
        let m = self.mode;
        let c = self.c;
        self.before = *self.messages;
        // SAFETY: every pointer below is to a live local of the right size.
        unsafe {
            match *op {
                Op::EnterInit => {
                    let s = fmi3EnterInitializationMode(c, false, 0.0, 0.0, false, 0.0);
                    self.expect(m == M::Instantiated, s, M::Initialization, op);
                    self.t = 0.0;
                }
                Op::ExitInit => {
                    let s = fmi3ExitInitializationMode(c);
                    let next = if self.me || self.event_mode {
                        M::Event
                    } else {
                        M::Step
                    };
                    self.expect(m == M::Initialization, s, next, op);
                }
                Op::DoStep { h, ag } => {
                    if m == M::Step {
                        assert_eq!(fmi3SetFloat64(c, &vr::AG, 1, &ag, 1), OK);
                    }
                    let (mut event, mut term, mut early, mut last) = (false, false, false, -1.0);
                    let s = fmi3DoStep(
                        c, self.t, h, false, &mut event, &mut term, &mut early, &mut last,
                    );
                    if m == M::Step && s == DISCARD {
                        // the work limit: a step stopped inside, as in 2.0
                        assert!(last >= self.t && last <= self.t + h && !term);
                        self.mode = M::Ended; // stepFailed: only fmi3Terminate goes on
                        return;
                    }
                    self.expect(m == M::Step, s, M::Step, op);
                    if m == M::Step {
                        assert!(
                            last > self.t - 1e-300 && last <= self.t + h,
                            "{last} after {} + {h}",
                            self.t
                        );
                        assert!(!early || self.early, "early return not allowed");
                        assert!(!early || term || last < self.t + h);
                        assert!(
                            !event || self.event_mode,
                            "eventHandlingNeeded without event mode"
                        );
                        if term {
                            self.mode = M::Ended;
                        }
                        self.t = last;
                    }
                }
                Op::EnterEventMode => {
                    let s = fmi3EnterEventMode(c);
                    let ok = if self.me {
                        m == M::Event || m == M::ContinuousTime
                    } else {
                        self.event_mode && m == M::Step
                    };
                    self.expect(ok, s, M::Event, op);
                }
                Op::UpdateDiscreteStates => {
                    let (mut a, mut b, mut d, mut e, mut f, mut g) =
                        (true, true, true, true, true, 1.0);
                    let s =
                        fmi3UpdateDiscreteStates(c, &mut a, &mut b, &mut d, &mut e, &mut f, &mut g);
                    self.expect(m == M::Event, s, M::Event, op);
                    if m == M::Event {
                        assert!(!a && !d && !f, "no discrete update pending, no time event");
                    }
                }
                Op::EnterStepMode => {
                    let s = fmi3EnterStepMode(c);
                    self.expect(!self.me && m == M::Event, s, M::Step, op);
                }
                Op::EnterContinuousTime => {
                    let s = fmi3EnterContinuousTimeMode(c);
                    self.expect(self.me && m == M::Event, s, M::ContinuousTime, op);
                }
                Op::SetTime { dt } => {
                    let s = fmi3SetTime(c, self.t + dt);
                    let ok = self.me && (m == M::Event || m == M::ContinuousTime);
                    self.expect(ok, s, m, op);
                    if ok {
                        self.t += dt;
                    }
                }
                Op::CompletedIntegratorStep => {
                    let (mut e, mut t) = (false, false);
                    let s = fmi3CompletedIntegratorStep(c, true, &mut e, &mut t);
                    self.expect(self.me && m == M::ContinuousTime, s, m, op);
                }
                Op::Derivatives { n } => {
                    let mut dx = [0.0; 4];
                    let s = fmi3GetContinuousStateDerivatives(c, dx.as_mut_ptr(), n);
                    if m == M::Error {
                        return self.lenient(s, op);
                    }
                    let ok = self.me
                        && n == 2
                        && matches!(
                            m,
                            M::Initialization | M::Event | M::ContinuousTime | M::Terminated
                        );
                    self.expect(ok, s, m, op);
                }
                Op::StateRoundTrip => {
                    let mut st = ptr::null_mut();
                    let s = fmi3GetFMUState(c, &mut st);
                    if m == M::Error {
                        return self.lenient(s, op);
                    }
                    self.expect(true, s, m, op);
                    let mut size = 0usize;
                    assert_eq!(fmi3SerializedFMUStateSize(c, st, &mut size), OK);
                    let mut bytes = vec![0u8; size];
                    assert_eq!(fmi3SerializeFMUState(c, st, bytes.as_mut_ptr(), size), OK);
                    assert_eq!(fmi3FreeFMUState(c, &mut st), OK);
                    assert!(st.is_null());
                    let before = self.outputs();
                    let mut back = ptr::null_mut();
                    assert_eq!(
                        fmi3DeserializeFMUState(c, bytes.as_ptr(), size, &mut back),
                        OK
                    );
                    assert_eq!(fmi3SetFMUState(c, back), OK);
                    assert_eq!(fmi3FreeFMUState(c, &mut back), OK);
                    if before.is_some() {
                        assert_eq!(before, self.outputs());
                    }
                    // a truncated buffer is refused
                    let mut none = ptr::null_mut();
                    let s = fmi3DeserializeFMUState(c, bytes.as_ptr(), size - 1, &mut none);
                    self.expect(false, s, m, op);
                }
                Op::GetFloat64 { vr: r } => {
                    let mut x = 0.0;
                    let s = fmi3GetFloat64(c, &r, 1, &mut x, 1);
                    let md = &ROCKING_BLOCK;
                    let known = md
                        .variables
                        .iter()
                        .any(|v| v.vr == r && v.ty.base() == BaseType::Real)
                        || r == md.fmi3_time_vr()
                        || md.fmi3_event_indicator_of(r).is_some()
                        || md.fmi3_input_derivative_of(r).is_some();
                    if !known {
                        self.expect(false, s, m, op);
                    } else if s == ERROR {
                        // a computed value outside a state that evaluates it
                        self.mode = M::Error;
                    } else {
                        self.lenient(s, op);
                    }
                }
                Op::SetInt32OnEnumeration => {
                    let v = 1i32;
                    let s = fmi3SetInt32(c, &vr::SHAPE, 1, &v, 1);
                    self.expect(false, s, m, op);
                }
                Op::SetReal { which, value, bad } => {
                    let r = SET_REAL_VRS[which];
                    let x = [SET_REAL_VALUES[value]; 2];
                    // bad: 1 nValues = 2 for one value reference, 2 a NULL
                    // value reference array, 3 a NULL value array
                    let vrs = if bad == 2 {
                        ptr::null()
                    } else {
                        &r as *const u32
                    };
                    let xs = if bad == 3 { ptr::null() } else { x.as_ptr() };
                    let s = fmi3SetFloat64(c, vrs, 1, xs, if bad == 1 { 2 } else { 1 });
                    if bad > 0 || which == 4 || value > 0 {
                        self.expect(false, s, m, op);
                    } else {
                        self.settled(s, op);
                    }
                }
                Op::OutputDerivative { order, mismatch } => {
                    let mut x = [0.0; 2];
                    let n_values = if mismatch { 2 } else { 1 };
                    let s = fmi3GetOutputDerivatives(
                        c,
                        &vr::THETA,
                        1,
                        &order,
                        x.as_mut_ptr(),
                        n_values,
                    );
                    if mismatch || order == 0 {
                        self.expect(false, s, m, op);
                    } else {
                        self.settled(s, op);
                    }
                }
                Op::SetStates { n, nan } => {
                    let mut x = [0.0; 4];
                    if nan {
                        x[n.saturating_sub(1)] = f64::NAN;
                    }
                    let s = fmi3SetContinuousStates(c, x.as_ptr(), n);
                    if !self.me || n != 2 || nan {
                        self.expect(false, s, m, op);
                    } else {
                        self.settled(s, op);
                    }
                }
                Op::EventIndicators { n } => {
                    let mut z = [0.0; 14];
                    let s = fmi3GetEventIndicators(c, z.as_mut_ptr(), n);
                    if !self.me || n != 12 {
                        self.expect(false, s, m, op);
                    } else {
                        self.settled(s, op);
                    }
                }
                Op::Terminate => {
                    let s = fmi3Terminate(c);
                    let ok = matches!(m, M::Step | M::Event | M::ContinuousTime | M::Ended);
                    self.expect(ok, s, M::Terminated, op);
                }
                Op::Reset => {
                    let s = fmi3Reset(c);
                    self.expect(true, s, M::Instantiated, op);
                    self.t = 0.0;
                }
            }
        }
    }
}

impl Drop for Run {
    fn drop(&mut self) {
        // SAFETY: created by fmi3Instantiate*, freed once.
        unsafe { fmi3FreeInstance(self.c) };
    }
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

/// A start that meets most calls in a running instance.
fn start(me: bool, event_mode: bool) -> Vec<Op> {
    let mut v = vec![Op::EnterInit, Op::ExitInit];
    if event_mode && !me {
        v.extend([Op::UpdateDiscreteStates, Op::EnterStepMode]);
    }
    if me {
        v.extend([Op::UpdateDiscreteStates, Op::EnterContinuousTime]);
    }
    v
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
