//! The interpreter of FMI 3.0 call sequences on RoundBody.fmu with its
//! oracle of the standard's state machine, shared by the proptest suite
//! (`tests/fmi3_fuzz.rs`) and the libFuzzer target
//! (`fuzz/fuzz_targets/round_body3.rs`, which includes this file with
//! `#[path]`): RockingBlock's (`fmu-rocking/tests/fmi3_driver`) made for
//! this model. [`Run::apply`] performs one [`Op`] through the exported
//! `fmi3*` functions and checks its status, messages (one for every
//! refusal, none naming FMI 2.0) and results, and that no panic happened
//! in the FMU, not even a caught one; [`decode`] turns arbitrary bytes into
//! an instance kind and a list of `Op`s: co-simulation with and without
//! event mode and early return (at uplift, impacts, rest, overturning), and
//! Model Exchange (seven states, four event indicators; refused at
//! instantiation if the model description has none, the run then going on
//! with a co-simulation instance).

#![allow(dead_code)] // each includer uses a part

use std::ffi::{c_char, c_void, CStr};
use std::ptr;

use fmi2_export::model_description::BaseType;
use fmu_round_body::description::{vr, ROUND_BODY};
use fmu_round_body::*;

pub const OK: i32 = 0;
pub const WARNING: i32 = 1;
pub const DISCARD: i32 = 2;
pub const ERROR: i32 = 3;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
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
pub enum Op {
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

/// `SetReal`'s value references: the inputs, `der(agx)`, `der(av)`,
/// unknown.
pub fn set_real_vrs() -> [u32; 5] {
    [
        vr::AGX,
        vr::AV,
        ROUND_BODY.fmi3_input_derivative_vr(0),
        ROUND_BODY.fmi3_input_derivative_vr(2),
        9999,
    ]
}
/// `SetReal`'s values: plausible, not finite, huge (1e12 m/s2: far beyond
/// any ground motion, below where a step overflows, see
/// `tests/fmi2_fuzz.rs`, `finding_*`).
pub const SET_REAL_VALUES: [f64; 4] = [0.5, f64::NAN, f64::INFINITY, 1e12];

thread_local! {
    static PANICS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// Counts every panic of this thread (caught or not), then calls the hook
/// installed before.
pub fn install_panic_counter() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            PANICS.with(|p| p.set(p.get() + 1));
            previous(info);
        }));
    });
}

fn panics() -> u64 {
    PANICS.with(|p| p.get())
}

/// Continuous states of Model Exchange (variables with a derivative).
pub fn nx() -> usize {
    ROUND_BODY
        .variables
        .iter()
        .filter(|v| v.derivative.is_some())
        .count()
}

/// Event indicators of Model Exchange.
pub fn nz() -> usize {
    ROUND_BODY
        .model_exchange
        .map_or(0, |m| m.event_indicators as usize)
}

/// A message of a 3.0 instance that names something of FMI 2.0 (the
/// callback cannot panic across the C boundary: [`Run::apply`] checks).
static STRAY: std::sync::Mutex<Option<String>> = std::sync::Mutex::new(None);

unsafe extern "C" fn count_messages(
    env: *mut c_void,
    _s: i32,
    _c: *const c_char,
    m: *const c_char,
) {
    // SAFETY: env is the counter this test passed; m a C string from the FMU.
    unsafe {
        let text = CStr::from_ptr(m).to_string_lossy();
        assert!(!text.is_empty());
        if text.contains("fmi2") {
            *STRAY.lock().unwrap_or_else(|p| p.into_inner()) = Some(text.into_owned());
        }
        *(env as *mut usize) += 1;
    }
}

pub struct Run {
    pub c: *mut c_void,
    pub me: bool,
    pub event_mode: bool,
    pub early: bool,
    pub mode: Mode,
    pub t: f64,
    pub messages: Box<usize>,
    /// Messages logged before the current call.
    pub before: usize,
}

impl Run {
    pub fn new(me: bool, event_mode: bool, early: bool) -> Run {
        install_panic_counter();
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
                    true,
                    env,
                    Some(count_messages),
                )
            } else {
                fmi3InstantiateCoSimulation(
                    c"c".as_ptr(),
                    guid.as_ptr(),
                    ptr::null(),
                    false,
                    true,
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
        if me && ROUND_BODY.model_exchange.is_none() {
            assert!(
                c.is_null(),
                "a Model Exchange instance of a co-simulation FMU"
            );
            assert!(*messages > 0, "Model Exchange refused without a message");
            return Run::new(false, event_mode, early);
        }
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
        let vrs = [vr::THETA, vr::OMEGA_X, vr::FX];
        let mut out = [0.0; 3];
        // SAFETY: 3 value references, 3 values.
        let s = unsafe { fmi3GetFloat64(self.c, vrs.as_ptr(), 3, out.as_mut_ptr(), 3) };
        (s == OK).then(|| out.map(f64::to_bits))
    }

    /// Calls `op` and checks its status, messages and results.
    pub fn apply(&mut self, op: &Op) {
        let p0 = panics();
        self.call(op);
        assert_eq!(panics(), p0, "{op:?}: the FMU panicked (caught or not)");
        let stray = STRAY.lock().unwrap_or_else(|p| p.into_inner()).take();
        assert!(
            stray.is_none(),
            "{op:?}: a 3.0 message names FMI 2.0: {stray:?}"
        );
    }

    fn call(&mut self, op: &Op) {
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
                        // both horizontal components
                        let a = [ag, -0.7 * ag];
                        let vrs = [vr::AGX, vr::AGY];
                        assert_eq!(fmi3SetFloat64(c, vrs.as_ptr(), 2, a.as_ptr(), 2), OK);
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
                            // = t: the run ended at the step's start
                            last >= self.t && last <= self.t + h,
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
                    let mut dx = [0.0; 9];
                    let s = fmi3GetContinuousStateDerivatives(c, dx.as_mut_ptr(), n);
                    if m == M::Error {
                        return self.lenient(s, op);
                    }
                    let ok = self.me
                        && n == nx()
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
                    let md = &ROUND_BODY;
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
                    let r = set_real_vrs()[which];
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
                    if bad > 0 || which == 4 || !SET_REAL_VALUES[value].is_finite() {
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
                    // maxOutputDerivativeOrder = 0: every order is refused
                    let _ = mismatch;
                    self.expect(false, s, m, op);
                }
                Op::SetStates { n, nan } => {
                    let mut x = [0.0; 9];
                    if nan {
                        x[n.saturating_sub(1)] = f64::NAN;
                    }
                    let s = fmi3SetContinuousStates(c, x.as_ptr(), n);
                    if !self.me || n != nx() || nan {
                        self.expect(false, s, m, op);
                    } else {
                        self.settled(s, op);
                    }
                }
                Op::EventIndicators { n } => {
                    let mut z = [0.0; 9];
                    let s = fmi3GetEventIndicators(c, z.as_mut_ptr(), n);
                    if !self.me || n != nz() {
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

/// A start that meets most calls in a running instance.
pub fn start(me: bool, event_mode: bool) -> Vec<Op> {
    let mut v = vec![Op::EnterInit, Op::ExitInit];
    if event_mode && !me {
        v.extend([Op::UpdateDiscreteStates, Op::EnterStepMode]);
    }
    if me {
        v.extend([Op::UpdateDiscreteStates, Op::EnterContinuousTime]);
    }
    v
}

/// Bytes -> one byte per choice, cycling: the instance kind (Model Exchange,
/// event mode, early return, started), then up to 200 operations.
pub fn decode(data: &[u8]) -> (bool, bool, bool, bool, Vec<Op>) {
    let mut it = data.iter().copied();
    let mut next = move || it.next();
    let kind = next().unwrap_or(0);
    let bit = |k: u8| kind & (1 << k) != 0;
    let mut ops = Vec::new();
    while let (Some(code), true) = (next(), ops.len() < 200) {
        let mut arg = || next().unwrap_or(0) as usize;
        ops.push(match code % 19 {
            0 => Op::EnterInit,
            1 => Op::ExitInit,
            2 => Op::DoStep {
                h: [1e-3, 0.01, 0.05, 0.2, 4.4e-16][arg() % 5],
                ag: (arg() as f64 - 128.0) / 20.0,
            },
            3 => Op::EnterEventMode,
            4 => Op::UpdateDiscreteStates,
            5 => Op::EnterStepMode,
            6 => Op::EnterContinuousTime,
            7 => Op::SetTime {
                dt: [0.0, 1e-3, 0.01][arg() % 3],
            },
            8 => Op::CompletedIntegratorStep,
            9 => Op::Derivatives { n: arg() % 9 },
            10 => Op::StateRoundTrip,
            11 => Op::GetFloat64 {
                vr: (arg() % 72) as u32,
            },
            12 => Op::SetInt32OnEnumeration,
            13 => Op::SetReal {
                which: arg() % 5,
                value: arg() % 4,
                bad: arg() % 4,
            },
            14 => Op::OutputDerivative {
                order: (arg() % 4) as i32,
                mismatch: arg() % 2 == 1,
            },
            15 => Op::SetStates {
                n: arg() % 9,
                nan: arg() % 2 == 1,
            },
            16 => Op::EventIndicators { n: arg() % 9 },
            17 => Op::Terminate,
            _ => Op::Reset,
        });
    }
    (bit(0), bit(1), bit(2), bit(3), ops)
}

/// Runs the sequence `data` decodes to on one fresh instance; `trace`
/// prints each operation with the oracle's mode and time before it.
pub fn run_bytes_traced(data: &[u8], trace: bool) {
    let (me, event_mode, early, started, ops) = decode(data);
    if trace {
        println!(
            "me {me}, eventModeUsed {event_mode}, earlyReturnAllowed {early}, started {started}"
        );
    }
    let mut run = Run::new(me, event_mode, early);
    let prefix = if started {
        start(me, event_mode)
    } else {
        vec![]
    };
    for o in prefix.iter().chain(&ops) {
        if trace {
            println!("{o:?} in {:?} at t = {}", run.mode, run.t);
        }
        run.apply(o);
    }
}

/// Runs the sequence `data` decodes to on one fresh instance.
pub fn run_bytes(data: &[u8]) {
    run_bytes_traced(data, false);
}
