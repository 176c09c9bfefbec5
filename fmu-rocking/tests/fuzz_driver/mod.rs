//! The interpreter of random FMI 2.0 call sequences, shared by the proptest
//! suite (`tests/c_api_fuzz.rs`) and the libFuzzer target
//! (`fuzz/fuzz_targets/c_api.rs`, which includes this file with `#[path]`).
//!
//! [`decode`] turns arbitrary bytes into a list of [`Op`]s on up to
//! [`SLOTS`] instances; [`Driver::apply`] performs each one through the
//! exported `fmi2*` functions, the way a C host would, and checks after every
//! call:
//!
//! - the status is one of `fmi2OK`, `fmi2Warning`, `fmi2Discard`, `fmi2Error`
//!   (never `fmi2Fatal`, which only a panic in the layer gives, and never
//!   `fmi2Pending`: this FMU has no asynchronous steps);
//! - no panic happened inside the FMU, not even a caught one (a panic hook
//!   counts them per thread);
//! - a call outside the states where FMI 2.0 allows it returns `fmi2Error`
//!   (the driver follows the state machine while it knows the state);
//! - `fmi2ExitInitializationMode` succeeds exactly when the parameters the
//!   driver set build a valid model (`rocking::Params::build`, fed from the
//!   driver's own copy of the values) and fails with `fmi2Error` otherwise;
//! - after `fmi2OK` from a getter every value was written; Real outputs are
//!   finite, calculated parameters are not NaN (`thetaC` is `+inf` without
//!   crushing), `regime` is 0..=4, `impacts` >= 0, `zeroCrossings` >= 0
//!   and not below `impacts` (every impact is a crossing) when both are
//!   read in one call, Booleans are 0 or 1;
//! - every non-OK status comes with a logger message of that status; every
//!   message is non-empty UTF-8, names the instance, has a declared category
//!   and no `%` conversion left; OK messages only with debug logging on;
//! - FMU states: a state taken from this instance restores (`fmi2OK`) and
//!   gives back the same outputs bit for bit; serialization of a live state
//!   succeeds with the size the FMU gave; an unmodified buffer deserializes;
//!   serializing the deserialized state gives the same bytes; a shorter
//!   buffer is refused.
//!
//! Only what the standard allows a caller to do is done: pointers passed
//! back are the ones the FMU gave out (instances until they are freed, FMU
//! states until they are freed or their instance is), NULL only where the
//! standard allows it (and NULL instance names, which the brief asks for), and
//! arrays always have the length passed.

#![allow(dead_code, non_upper_case_globals)]

use std::cell::Cell;
use std::ffi::{c_int, c_void, CStr, CString};
use std::ptr;
use std::sync::Once;

use fmi2_export::bytes;
use fmi2_export::model_description::{BaseType, Causality, Type, Variable};
use fmi2_export::types::*;
use fmu_rocking as fmu;
use fmu_rocking::description::{enums, vr, LOG_CATEGORIES, VARIABLES};
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Formulation, Params, Restitution};

/// Instances the driver juggles at once.
pub const SLOTS: usize = 4;
/// Operations decoded from one input at most.
pub const MAX_OPS: usize = 160;
/// Serialized buffers kept for later deserialization.
const POOL: usize = 6;
/// FMU states kept per instance (the oldest is freed beyond).
const MAX_STATES: usize = 6;
/// Written into output arrays before a getter: still there after fmi2OK
/// means a value was not written.
const SENTINEL: u64 = 0x7ff8_dead_beef_f00d;

// ----- panic counting ------------------------------------------------------

thread_local! {
    static PANICS: Cell<u64> = const { Cell::new(0) };
}

/// Counts every panic of this thread (caught or not), then calls the hook
/// installed before (libFuzzer's aborts; the default one prints).
pub fn install_panic_counter() {
    static ONCE: Once = Once::new();
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

// ----- the logger ------------------------------------------------------------

/// What the logger saw for one instance (its `componentEnvironment`).
pub struct LogSink {
    /// The instance name the FMU must pass back (lossy UTF-8 of ours).
    name: Vec<u8>,
    /// Messages per status 0..=4.
    by_status: [Cell<u64>; 5],
    /// Whether debug logging is on (OK messages allowed).
    debug: Cell<bool>,
    /// The first broken rule, if any (the logger must not panic: it is
    /// called through C).
    problem: std::cell::RefCell<Option<String>>,
    /// Run the message through a real check of its text (else count only).
    inspect: bool,
}

impl LogSink {
    fn new(name: &[u8], debug: bool, inspect: bool) -> Box<LogSink> {
        Box::new(LogSink {
            name: String::from_utf8_lossy(name).into_owned().into_bytes(),
            by_status: Default::default(),
            debug: Cell::new(debug),
            problem: Default::default(),
            inspect,
        })
    }

    fn complain(&self, m: String) {
        if let Ok(mut p) = self.problem.try_borrow_mut() {
            if p.is_none() {
                *p = Some(m);
            }
        }
    }

    fn counts(&self) -> [u64; 5] {
        std::array::from_fn(|i| self.by_status[i].get())
    }

    fn take_problem(&self) -> Option<String> {
        self.problem.borrow_mut().take()
    }
}

/// The logger as the FMU calls it; declared without the variadic part (the
/// FMU passes no arguments after the message; on x86-64 System V and AArch64
/// Linux a non-variadic callee receives such a call unchanged).
type PlainLogger =
    unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String);

/// `fmi2CallbackFunctions` with the logger declared as [`PlainLogger`].
#[repr(C)]
struct Callbacks {
    logger: Option<PlainLogger>,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>,
    environment: fmi2ComponentEnvironment,
}

unsafe extern "C" fn logger(
    env: fmi2ComponentEnvironment,
    name: fmi2String,
    status: fmi2Status,
    category: fmi2String,
    message: fmi2String,
) {
    if env.is_null() {
        return; // cannot report; the driver notices the missing message
    }
    // SAFETY: env is the LogSink given at instantiation, alive until the
    // instance is freed (kept by the driver).
    let sink = unsafe { &*(env as *const LogSink) };
    if !(0..=4).contains(&status) {
        sink.complain(format!("logger called with status {status}"));
        return;
    }
    sink.by_status[status as usize].set(sink.by_status[status as usize].get() + 1);
    if status == fmi2OK && !sink.debug.get() {
        sink.complain("an fmi2OK message with debug logging off".into());
    }
    if !sink.inspect {
        return;
    }
    if name.is_null() || category.is_null() || message.is_null() {
        sink.complain("logger called with a NULL string".into());
        return;
    }
    // SAFETY: the FMU passes NUL-terminated strings (ASan checks the reads).
    let (name, category, message) = unsafe {
        (
            CStr::from_ptr(name).to_bytes(),
            CStr::from_ptr(category).to_bytes(),
            CStr::from_ptr(message).to_bytes(),
        )
    };
    if name != sink.name.as_slice() {
        sink.complain(format!(
            "instance name {:?}, expected {:?}",
            String::from_utf8_lossy(name),
            String::from_utf8_lossy(&sink.name)
        ));
    }
    let Ok(category) = std::str::from_utf8(category) else {
        sink.complain("category is not UTF-8".into());
        return;
    };
    if !LOG_CATEGORIES.iter().any(|c| c.name == category) {
        sink.complain(format!("undeclared category {category:?}"));
    }
    let expected = match status {
        fmi2Warning | fmi2Discard => Some("logStatusWarning"),
        fmi2Error | fmi2Fatal => Some("logStatusError"),
        _ => None,
    };
    if let Some(e) = expected {
        if category != e {
            sink.complain(format!("status {status} in category {category}"));
        }
    }
    let Ok(text) = std::str::from_utf8(message) else {
        sink.complain("message is not UTF-8".into());
        return;
    };
    if text.is_empty() {
        sink.complain("empty message".into());
    }
    // A printf format with no conversion left: every % doubled.
    let mut run = 0usize;
    for ch in text.chars().chain(std::iter::once('\n')) {
        if ch == '%' {
            run += 1;
        } else {
            if run % 2 == 1 {
                sink.complain(format!("a lone % in the format: {text:?}"));
                break;
            }
            run = 0;
        }
    }
}

// ----- reading the input ---------------------------------------------------------

/// Bytes consumed from the front; zeros once exhausted.
pub struct Bytes<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Bytes<'a> {
    pub fn new(data: &'a [u8]) -> Bytes<'a> {
        Bytes { data, pos: 0 }
    }
    pub fn is_empty(&self) -> bool {
        self.pos >= self.data.len()
    }
    pub fn u8(&mut self) -> u8 {
        let b = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }
    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    fn u64(&mut self) -> u64 {
        (self.u32() as u64) | ((self.u32() as u64) << 32)
    }
    /// 0..n (n <= 256).
    fn below(&mut self, n: usize) -> usize {
        self.u8() as usize % n.max(1)
    }
    /// True with probability k/8.
    fn chance(&mut self, k: u8) -> bool {
        self.u8() % 8 < k
    }
    fn take(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.u8()).collect()
    }
    /// A float from a table of awkward values, or raw bits.
    fn awkward(&mut self) -> f64 {
        const T: [f64; 24] = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            2.2250738585072e-309,
            f64::MAX,
            f64::MIN,
            1e300,
            -1e300,
            1e-300,
            1e-9,
            1e-3,
            0.5,
            2.0,
            10.0,
            1e6,
            1e15,
            -1e15,
        ];
        match self.u8() {
            k @ 0..=199 => T[k as usize % T.len()],
            _ => f64::from_bits(self.u64()),
        }
    }
    /// A value near `start` (a plausible setting) or an awkward one.
    fn near(&mut self, start: f64) -> f64 {
        const F: [f64; 12] = [
            1.0, 0.5, 2.0, 0.9, 1.1, 0.1, 10.0, 0.01, 100.0, -1.0, 0.0, 1e-3,
        ];
        if self.chance(5) {
            let base = if start == 0.0 { 0.01 } else { start };
            base * F[self.below(F.len())]
        } else {
            self.awkward()
        }
    }
    /// A small integer around the valid range, or an awkward one.
    fn int(&mut self) -> i32 {
        match self.u8() {
            k @ 0..=191 => (k % 8) as i32 - 1,
            192..=223 => [i32::MIN, i32::MAX, -1, 0, 5, 100, 1 << 16, -(1 << 20)][self.below(8)],
            _ => self.u32() as i32,
        }
    }
}

// ----- operations -------------------------------------------------------------

#[derive(Clone, Debug)]
pub enum Name {
    Null,
    Empty,
    Plain,
    /// Any bytes but NUL (invalid UTF-8, `%s`, newlines...).
    Odd(Vec<u8>),
    Long,
}

#[derive(Clone, Debug)]
pub enum Guid {
    Right,
    Wrong,
    Null,
    /// The right one with its last character cut.
    Truncated,
}

#[derive(Clone, Debug)]
pub struct InstSpec {
    pub name: Name,
    pub fmu_type: c_int,
    pub guid: Guid,
    /// None: NULL.
    pub resource: Option<Vec<u8>>,
    /// Pass a logger (else the callback struct has none).
    pub logger: bool,
    /// Look into every message (else count only).
    pub inspect: bool,
    pub logging_on: c_int,
    pub visible: c_int,
}

/// The current time, a time close to it, or any value.
#[derive(Clone, Copy, Debug)]
pub enum Point {
    Matching,
    Offset(f64),
    Raw(f64),
}

/// What is done to a serialized buffer before deserializing it.
#[derive(Clone, Debug)]
pub enum Mutation {
    None,
    /// Flip bit `bit` of byte `pos % len`.
    Flip {
        pos: u16,
        bit: u8,
    },
    Truncate(u16),
    Append(Vec<u8>),
    /// Change payload bytes and recompute the envelope (length, checksum), so
    /// that the payload reader itself is exercised.
    Reseal {
        edits: Vec<(u16, u8)>,
        cut: u16,
        extend: Vec<u8>,
    },
    /// Ignore the pool: these bytes.
    Random(Vec<u8>),
}

/// Which FMU state: the k-th live one of instance `slot`, or NULL.
#[derive(Clone, Copy, Debug)]
pub enum StateRef {
    Null,
    Of { slot: u8, k: u8 },
}

#[derive(Clone, Debug)]
pub enum Op {
    Instantiate(u8, InstSpec),
    Free(u8),
    SetupExperiment {
        slot: u8,
        tolerance_defined: c_int,
        tolerance: f64,
        start: f64,
        stop_defined: c_int,
        stop: f64,
    },
    EnterInit(u8),
    ExitInit(u8),
    /// Setup (defaults), enter and exit initialization mode.
    Init(u8),
    Terminate(u8),
    Reset(u8),
    SetReal(u8, Vec<u32>, Vec<f64>),
    SetInteger(u8, Vec<u32>, Vec<c_int>),
    SetBoolean(u8, Vec<u32>, Vec<c_int>),
    SetString(u8, Vec<u32>, Vec<Vec<u8>>),
    GetReal(u8, Vec<u32>),
    GetInteger(u8, Vec<u32>),
    GetBoolean(u8, Vec<u32>),
    GetString(u8, Vec<u32>),
    /// Every Real, Integer and Boolean output and calculated parameter.
    GetAll(u8),
    SetInputDerivatives(u8, Vec<u32>, Vec<c_int>, Vec<f64>),
    GetOutputDerivatives(u8, Vec<u32>, Vec<c_int>),
    DoStep {
        slot: u8,
        point: Point,
        h: f64,
        no_prior: c_int,
    },
    CancelStep(u8),
    /// `which`: 0 Status, 1 Real, 2 Integer, 3 Boolean, 4 String.
    Status(u8, u8, c_int),
    SetDebugLogging(u8, c_int, Vec<Vec<u8>>),
    /// A new state (`reuse` None) or one of the instance's own overwritten.
    GetState(u8, Option<u8>),
    SetState(u8, StateRef),
    FreeState(u8, StateRef),
    /// Serialize a state; `size`: 0 exact, 1 one short, 2 larger (padding).
    Serialize(u8, StateRef, u8),
    Deserialize(u8, u8, Mutation),
    DirectionalDerivative(u8),
    Platform,
    /// Model Exchange: `which` 0 SetTime, 1 SetContinuousStates, 2
    /// GetContinuousStates, 3 GetDerivatives, 4 GetEventIndicators, 5
    /// GetNominalsOfContinuousStates, 6 EnterEventMode, 7 NewDiscreteStates,
    /// 8 EnterContinuousTimeMode, 9 CompletedIntegratorStep; `x` the time or
    /// the states; `n` the array length passed.
    Me {
        slot: u8,
        which: u8,
        x: [f64; 2],
        n: usize,
    },
}

fn slot(b: &mut Bytes) -> u8 {
    b.below(SLOTS) as u8
}

fn vr_of(b: &mut Bytes, base: BaseType) -> u32 {
    if b.chance(7) {
        let own: Vec<&Variable> = VARIABLES.iter().filter(|v| v.ty.base() == base).collect();
        if own.is_empty() {
            return b.below(48) as u32;
        }
        own[b.below(own.len())].vr
    } else {
        match b.below(4) {
            0 => b.below(48) as u32,
            1 => u32::MAX,
            2 => 41 + b.u8() as u32,
            _ => b.u32(),
        }
    }
}

fn count(b: &mut Bytes) -> usize {
    match b.u8() {
        0..=39 => 0,
        40..=159 => 1,
        160..=239 => 2 + b.below(6),
        _ => 8 + b.below(57),
    }
}

fn vrs(b: &mut Bytes, base: BaseType) -> Vec<u32> {
    let n = count(b);
    (0..n).map(|_| vr_of(b, base)).collect()
}

fn start_real(r: u32) -> f64 {
    match VARIABLES.iter().find(|v| v.vr == r).map(|v| v.ty) {
        Some(Type::Real { start, .. }) => start.unwrap_or(0.0),
        _ => 0.0,
    }
}

fn spec(b: &mut Bytes) -> InstSpec {
    let name = match b.below(16) {
        0 => Name::Null,
        1 => Name::Empty,
        2 => Name::Long,
        3 | 4 => {
            let n = b.below(24);
            Name::Odd(b.take(n).into_iter().map(|c| c.max(1)).collect())
        }
        _ => Name::Plain,
    };
    let guid = match b.below(16) {
        0 => Guid::Wrong,
        1 => Guid::Null,
        2 => Guid::Truncated,
        _ => Guid::Right,
    };
    let fmu_type = match b.below(16) {
        0 | 2..=5 => fmi2ModelExchange,
        1 => b.u32() as c_int,
        _ => fmi2CoSimulation,
    };
    let resource = match b.below(8) {
        0 => None,
        1 => Some(b"file:///tmp/rocking%20fuzz/resources".to_vec()),
        2 => Some(b"http://example.invalid/x".to_vec()),
        3 => Some(b"file:///bad%2".to_vec()),
        4 => {
            let n = b.below(32);
            Some(b.take(n).into_iter().map(|c| c.max(1)).collect())
        }
        _ => Some(b"file:///tmp/resources".to_vec()),
    };
    InstSpec {
        name,
        fmu_type,
        guid,
        resource,
        logger: b.chance(7),
        inspect: b.chance(6),
        logging_on: [fmi2False, fmi2True, 7][b.below(3)],
        visible: b.below(2) as c_int,
    }
}

fn mutation(b: &mut Bytes) -> Mutation {
    match b.below(8) {
        0 | 1 => Mutation::None,
        2 => Mutation::Flip {
            pos: b.u16(),
            bit: b.below(8) as u8,
        },
        3 => Mutation::Truncate(b.u16()),
        4 => {
            let n = 1 + b.below(8);
            Mutation::Append(b.take(n))
        }
        5 | 6 => {
            let k = 1 + b.below(4);
            let edits = (0..k).map(|_| (b.u16(), b.u8())).collect();
            let cut = if b.chance(2) { b.below(16) as u16 } else { 0 };
            let n = if b.chance(1) { b.below(12) } else { 0 };
            Mutation::Reseal {
                edits,
                cut,
                extend: b.take(n),
            }
        }
        _ => {
            let n = b.below(256);
            Mutation::Random(b.take(n))
        }
    }
}

fn state_ref(b: &mut Bytes, own: u8) -> StateRef {
    match b.below(16) {
        0 => StateRef::Null,
        1 => StateRef::Of {
            slot: slot(b),
            k: b.u8() % MAX_STATES as u8,
        },
        _ => StateRef::Of {
            slot: own,
            k: b.u8() % MAX_STATES as u8,
        },
    }
}

/// One operation from the input.
/// Operation codes by weight (64 entries): stepping, getting and recovering
/// often, instantiating and freeing rarely, so that random sequences reach
/// initialized instances and FMU states.
const OP_TABLE: [u8; 64] = [
    0, 3, 4, 5, 6, 7, 7, 7, 7, 10, 11, 11, 11, 12, 12, 40, 40, 40, 15, 15, 17, 18, 19, 19, 19, 21,
    22, 23, 24, 24, 24, 26, 41, 41, 27, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 32,
    33, 33, 34, 35, 42, 42, 42, 42, 37, 38, 38, 39, 39, 42,
];

pub fn decode_op(b: &mut Bytes) -> Op {
    let s = slot(b);
    match OP_TABLE[b.below(64)] {
        40 => Op::SetReal(s, vec![vr::AG], vec![b.int() as f64 * 2.5]),
        42 => Op::Me {
            slot: s,
            which: b.u8(),
            x: [b.near(0.05), b.near(0.0)],
            n: if b.chance(1) {
                [0, 1, 3, 8, 10][b.below(5)]
            } else {
                [2, 2, 9, 9][b.below(4)]
            },
        },
        41 => Op::SetInputDerivatives(s, vec![vr::AG], vec![1], vec![b.int() as f64 * 10.0]),
        0..=2 => Op::Instantiate(s, spec(b)),
        3 => Op::Free(s),
        4 => {
            let tolerance = if b.chance(6) {
                [1e-6, 1e-9, 1e-4, 1e-12][b.below(4)]
            } else {
                b.awkward()
            };
            let start = if b.chance(6) { 0.0 } else { b.awkward() };
            let stop = if b.chance(4) { 1e6 } else { b.awkward() };
            Op::SetupExperiment {
                slot: s,
                tolerance_defined: [fmi2True, fmi2False, 2][b.below(3)],
                tolerance,
                start,
                stop_defined: [fmi2False, fmi2True, -1][b.below(3)],
                stop,
            }
        }
        5 => Op::EnterInit(s),
        6 => Op::ExitInit(s),
        7..=9 => Op::Init(s),
        10 => Op::Terminate(s),
        11 => Op::Reset(s),
        12..=14 => {
            let r = vrs(b, BaseType::Real);
            let x = r.iter().map(|&r| b.near(start_real(r))).collect();
            Op::SetReal(s, r, x)
        }
        15 | 16 => {
            let r = vrs(b, BaseType::Integer);
            let x = r.iter().map(|_| b.int()).collect();
            Op::SetInteger(s, r, x)
        }
        17 => {
            let r = vrs(b, BaseType::Boolean);
            let x = r.iter().map(|_| b.int()).collect();
            Op::SetBoolean(s, r, x)
        }
        18 => {
            let r = vrs(b, BaseType::String);
            let x = r
                .iter()
                .map(|_| {
                    let n = b.below(8);
                    b.take(n).into_iter().map(|c| c.max(1)).collect()
                })
                .collect();
            Op::SetString(s, r, x)
        }
        19 | 20 => Op::GetReal(s, vrs(b, BaseType::Real)),
        21 => Op::GetInteger(s, vrs(b, BaseType::Integer)),
        22 => Op::GetBoolean(s, vrs(b, BaseType::Boolean)),
        23 => Op::GetString(s, vrs(b, BaseType::String)),
        24 | 25 => Op::GetAll(s),
        26 => {
            let r = vrs(b, BaseType::Real);
            let o = r
                .iter()
                .map(|_| if b.chance(5) { 1 } else { b.int() })
                .collect();
            let x = r.iter().map(|_| b.near(1.0)).collect();
            Op::SetInputDerivatives(s, r, o, x)
        }
        27 => {
            let r = vrs(b, BaseType::Real);
            let o = r.iter().map(|_| b.int()).collect();
            Op::GetOutputDerivatives(s, r, o)
        }
        28..=31 => {
            let point = match b.below(16) {
                0 => Point::Raw(b.awkward()),
                1 => Point::Offset(b.awkward() * 1e-9),
                _ => Point::Matching,
            };
            let h = match b.below(16) {
                0..=2 => b.awkward(),
                3 => 10.0,
                4 => 1e-7,
                _ => [0.001, 0.01, 0.02, 0.05, 0.1, 0.5, 1.0, 2.0][b.below(8)],
            };
            Op::DoStep {
                slot: s,
                point,
                h,
                no_prior: b.below(2) as c_int,
            }
        }
        32 => Op::CancelStep(s),
        33 => {
            let which = b.below(5) as u8;
            let kind = if b.chance(7) {
                b.below(4) as c_int
            } else {
                b.int()
            };
            Op::Status(s, which, kind)
        }
        34 => {
            let n = count(b).min(6);
            let cats = (0..n)
                .map(|_| {
                    if b.chance(6) {
                        LOG_CATEGORIES[b.below(LOG_CATEGORIES.len())]
                            .name
                            .as_bytes()
                            .to_vec()
                    } else {
                        let n = b.below(12);
                        b.take(n).into_iter().map(|c| c.max(1)).collect()
                    }
                })
                .collect();
            Op::SetDebugLogging(s, [fmi2True, fmi2False, 3][b.below(3)], cats)
        }
        35 => Op::GetState(s, b.chance(2).then(|| b.u8() % MAX_STATES as u8)),
        36 => Op::SetState(s, state_ref(b, s)),
        37 => {
            if b.chance(1) {
                Op::FreeState(s, state_ref(b, s))
            } else {
                Op::DirectionalDerivative(s)
            }
        }
        38 => {
            let r = state_ref(b, s);
            Op::Serialize(s, r, b.below(3) as u8)
        }
        _ => {
            if b.chance(1) {
                Op::Platform
            } else {
                let k = b.u8();
                Op::Deserialize(s, k, mutation(b))
            }
        }
    }
}

/// The operations encoded by `data` (at most [`MAX_OPS`]).
pub fn decode(data: &[u8]) -> Vec<Op> {
    let mut b = Bytes::new(data);
    let mut ops = Vec::new();
    // The first byte: how many instances start instantiated (0, 1) or
    // initialized (2, 4) with default settings, so that short inputs reach
    // running instances.
    if !b.is_empty() {
        let plain = |k: u8| {
            Op::Instantiate(
                k,
                InstSpec {
                    name: Name::Plain,
                    fmu_type: fmi2CoSimulation,
                    guid: Guid::Right,
                    resource: None,
                    logger: true,
                    inspect: true,
                    logging_on: fmi2False,
                    visible: fmi2False,
                },
            )
        };
        match b.u8() % 4 {
            0 => {}
            1 => ops.push(plain(0)),
            n => {
                for k in 0..if n == 2 { 2 } else { 4 } {
                    ops.push(plain(k));
                    ops.push(Op::Init(k));
                }
            }
        }
    }
    while !b.is_empty() && ops.len() < MAX_OPS {
        ops.push(decode_op(&mut b));
    }
    ops
}

// ----- the driver -------------------------------------------------------------

/// The FMI 2.0 co-simulation states the driver follows (fatal never occurs:
/// it is checked).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Machine {
    Instantiated,
    Init,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
    /// Model Exchange.
    EventMode,
    ContinuousTime,
}

use Machine as M;

const ANY: &[M] = &[
    M::Instantiated,
    M::Init,
    M::StepComplete,
    M::StepFailed,
    M::Terminated,
    M::Error,
    M::EventMode,
    M::ContinuousTime,
];
const NOWHERE: &[M] = &[];
const INSTANTIATED: &[M] = &[M::Instantiated];
const INIT: &[M] = &[M::Init];
const TERMINATE: &[M] = &[
    M::StepComplete,
    M::StepFailed,
    M::EventMode,
    M::ContinuousTime,
];
const GET: &[M] = &[
    M::Init,
    M::StepComplete,
    M::StepFailed,
    M::Terminated,
    M::Error,
    M::EventMode,
    M::ContinuousTime,
];
const SET: &[M] = &[
    M::Instantiated,
    M::Init,
    M::StepComplete,
    M::EventMode,
    M::ContinuousTime,
];
// Model Exchange (FMI 2.0 §3.2.3)
const ME_SET_TIME: &[M] = &[M::EventMode, M::ContinuousTime];
const ME_CONTINUOUS: &[M] = &[M::ContinuousTime];
const ME_EVENT: &[M] = &[M::EventMode];
const ME_EVALUATE: &[M] = &[
    M::Init,
    M::EventMode,
    M::ContinuousTime,
    M::Terminated,
    M::Error,
];
const OUTPUT_DERIVATIVES: &[M] = &[M::StepComplete, M::StepFailed, M::Terminated, M::Error];
const DO_STEP: &[M] = &[M::StepComplete];
const STATUS: &[M] = &[M::StepComplete, M::StepFailed, M::Terminated];

/// The driver's copy of the stored parameters and start values (by value
/// reference; Reals and Integers), or unknown.
#[derive(Clone, Debug, PartialEq)]
pub struct Stored {
    real: Vec<f64>,
    int: Vec<i32>,
}

impl Stored {
    fn start() -> Stored {
        let n = VARIABLES.iter().map(|v| v.vr).max().unwrap_or(0) as usize + 1;
        let mut s = Stored {
            real: vec![0.0; n],
            int: vec![0; n],
        };
        for v in VARIABLES {
            match v.ty {
                Type::Real { start, .. } => s.real[v.vr as usize] = start.unwrap_or(0.0),
                Type::Integer { start } | Type::Enumeration { start, .. } => {
                    s.int[v.vr as usize] = start.unwrap_or(0)
                }
                _ => {}
            }
        }
        s
    }

    /// The physics parameters, mapped independently of the FMU's binding.
    pub fn params(&self) -> Option<Params> {
        use enums::*;
        let r = |k: u32| self.real[k as usize];
        let i = |k: u32| self.int[k as usize];
        Some(Params {
            shape: match i(vr::SHAPE) {
                SOLID_RECTANGLE => ShapeKind::SolidRectangle,
                HOLLOW_RECTANGLE => ShapeKind::HollowRectangle,
                SOLID_CIRCLE => ShapeKind::SolidCircle,
                HOLLOW_CIRCLE => ShapeKind::HollowCircle,
                _ => return None,
            },
            b: r(vr::B),
            l: r(vr::L),
            t: r(vr::T),
            ro: r(vr::RO),
            ri: r(vr::RI),
            mass_model: match i(vr::MASS_MODEL) {
                PRISM => MassKind::Prism,
                LUMPED => MassKind::Lumped,
                _ => return None,
            },
            h: r(vr::H),
            rho: r(vr::RHO),
            w: r(vr::W),
            hg: r(vr::HG),
            ic: r(vr::IC),
            interface: match i(vr::INTERFACE) {
                RIGID => LawKind::Rigid,
                ELASTIC => LawKind::Elastic,
                ELASTO_PLASTIC => LawKind::ElastoPlastic,
                _ => return None,
            },
            kn: r(vr::KN),
            fm: r(vr::FM),
            formulation: match i(vr::FORMULATION) {
                COSTA => Formulation::Costa,
                SHIFTING_PIVOT => Formulation::ShiftingPivot,
                _ => return None,
            },
            restitution: match i(vr::RESTITUTION) {
                HOUSNER => Restitution::Housner,
                GIVEN => Restitution::Given,
                _ => return None,
            },
            eta: r(vr::ETA),
            g: r(vr::G),
            theta0: r(vr::THETA),
            omega0: r(vr::OMEGA),
        })
    }

    fn valid(&self) -> bool {
        self.params().is_some_and(|p| p.build().is_ok())
    }
}

/// What the driver knows of an instance or of a saved state.
#[derive(Clone, Debug)]
struct Known {
    machine: Option<Machine>,
    stored: Option<Stored>,
    /// The bits of every Real output (if taken where they are defined).
    outputs: Option<Vec<u64>>,
}

impl Known {
    fn unknown() -> Known {
        Known {
            machine: None,
            stored: None,
            outputs: None,
        }
    }
}

struct FmuState {
    p: fmi2FMUstate,
    /// Taken by fmi2GetFMUstate, or deserialized from unmodified bytes:
    /// restoring it must succeed.
    genuine: bool,
    known: Known,
}

struct Slot {
    c: fmi2Component,
    sink: Box<LogSink>,
    callbacks: Box<Callbacks>,
    logger: bool,
    machine: Option<Machine>,
    stored: Option<Stored>,
    /// The end of the last step as the driver followed it.
    time: Option<f64>,
    /// Restored from a buffer the driver mutated (the engine's internal
    /// state, e.g. its step size, is then arbitrary).
    forged: bool,
    states: Vec<FmuState>,
    /// Instantiated as fmi2ModelExchange.
    me: bool,
}

struct Blob {
    bytes: Vec<u8>,
    /// Serialized by an instance of fmuType fmi2ModelExchange.
    me: bool,
    /// What the state was, if it was genuine.
    known: Option<Known>,
}

/// Counters of what a run did (for the report and to see that sequences go
/// deep).
#[derive(Clone, Debug, Default)]
pub struct Stats {
    pub calls: u64,
    pub instantiated: u64,
    pub steps_ok: u64,
    pub steps_discard: u64,
    pub steps_skipped: u64,
    pub exit_init_ok: u64,
    pub exit_init_error: u64,
    pub restores_checked: u64,
    pub deserialized: u64,
    /// Model Exchange calls that returned fmi2OK on an ME instance.
    pub model_exchange_ok: u64,
    pub by_status: [u64; 5],
}

pub struct Driver {
    slots: Vec<Option<Slot>>,
    pool: Vec<Blob>,
    pub stats: Stats,
    /// Skip fmi2DoStep for a flexible interface with thetaJo < 1e-8 thetaOv
    /// (kn above about 1e14 Pa/m for the default block, or a body of next
    /// to no weight), where the integrator resolves the contact's time
    /// scale and a step can take minutes to hours, and for a body whose
    /// weight, mass, R0 or IO is outside 1e-30..1e30, where moments overflow
    /// and the step loop may never end, and after restoring a state from a
    /// mutated buffer, whose engine fields (step size, contact hint, stiff
    /// flag) can stall the integrator (known, reported; not what this
    /// driver looks for).
    pub skip_extreme_stiffness: bool,
}

/// thetaJo / thetaOv below which [`Driver::skip_extreme_stiffness`] applies.
pub const EXTREME_STIFFNESS: f64 = 1e-8;

/// Finite communication steps longer than this are not taken (counted in
/// [`Stats::steps_skipped`]): the FMU integrates whatever it is asked to, and
/// a body rocking or held by ag below uplift for 1e300 s is 1e300 s of work
/// (there is no work limit per step: reported, not what this driver looks
/// for). Non-finite, zero and negative steps are always passed.
pub const MAX_STEP: f64 = 10.0;

fn real_outputs() -> Vec<u32> {
    VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Output && v.ty.base() == BaseType::Real)
        .map(|v| v.vr)
        .collect()
}

fn check_status(s: fmi2Status, what: &str) {
    assert!(
        (fmi2OK..=fmi2Error).contains(&s),
        "{what}: status {s} (only fmi2OK..fmi2Error are expected; fmi2Fatal means a panic in the layer, fmi2Pending never happens)"
    );
}

impl Default for Driver {
    fn default() -> Self {
        Self::new()
    }
}

impl Driver {
    pub fn new() -> Driver {
        install_panic_counter();
        Driver {
            slots: (0..SLOTS).map(|_| None).collect(),
            pool: Vec::new(),
            stats: Stats::default(),
            skip_extreme_stiffness: true,
        }
    }

    /// Runs every operation, then frees what is left.
    pub fn run(ops: &[Op]) -> Stats {
        let mut d = Driver::new();
        for op in ops {
            d.apply(op);
        }
        d.finish()
    }

    /// Frees every instance (and with them their FMU states).
    pub fn finish(mut self) -> Stats {
        for k in 0..SLOTS {
            self.free(k as u8);
        }
        std::mem::take(&mut self.stats)
    }

    fn slot(&mut self, k: u8) -> Option<&mut Slot> {
        self.slots[k as usize % SLOTS].as_mut()
    }

    /// Performs one FMI call on slot `k`: counts, checks the status, that no
    /// panic happened, the logger's findings, the state machine; returns the
    /// status (None when the slot is empty: nothing called).
    fn call(
        &mut self,
        k: u8,
        what: &str,
        allowed: &[Machine],
        f: impl FnOnce(fmi2Component) -> fmi2Status,
    ) -> Option<fmi2Status> {
        let s = self.slots[k as usize % SLOTS].as_mut()?;
        let before = s.sink.counts();
        let p0 = panics();
        let status = f(s.c);
        self.stats.calls += 1;
        assert_eq!(panics(), p0, "{what}: the FMU panicked (caught or not)");
        check_status(status, what);
        self.stats.by_status[status as usize] += 1;
        if let Some(p) = s.sink.take_problem() {
            panic!("{what}: logger: {p}");
        }
        if status != fmi2OK && s.logger {
            let after = s.sink.counts();
            assert!(
                after[status as usize] > before[status as usize],
                "{what}: status {status} without a message of that status"
            );
        }
        if let Some(m) = s.machine {
            if !allowed.contains(&m) {
                assert_eq!(status, fmi2Error, "{what} in state {m:?} must be refused");
            }
        }
        if status == fmi2Error {
            s.machine = Some(M::Error);
        }
        Some(status)
    }

    fn set_machine(&mut self, k: u8, m: Option<Machine>) {
        if let Some(s) = self.slot(k) {
            s.machine = m;
        }
    }

    pub fn apply(&mut self, op: &Op) {
        match op {
            Op::Instantiate(k, spec) => self.instantiate(*k, spec),
            Op::Free(k) => self.free(*k),
            &Op::SetupExperiment {
                slot,
                tolerance_defined,
                tolerance,
                start,
                stop_defined,
                stop,
            } => self.setup(
                slot,
                tolerance_defined,
                tolerance,
                start,
                stop_defined,
                stop,
            ),
            Op::EnterInit(k) => self.enter(*k),
            Op::ExitInit(k) => self.exit(*k),
            Op::Init(k) => {
                if self
                    .slot(*k)
                    .is_some_and(|s| s.machine == Some(M::Instantiated))
                {
                    self.setup(*k, fmi2False, 0.0, 0.0, fmi2False, 0.0);
                    self.enter(*k);
                    self.exit(*k);
                }
            }
            Op::Terminate(k) => {
                if let Some(st) = self.call(*k, "fmi2Terminate", TERMINATE, |c| unsafe {
                    fmu::fmi2Terminate(c)
                }) {
                    if st == fmi2OK {
                        self.set_machine(*k, Some(M::Terminated));
                    }
                }
            }
            Op::Reset(k) => {
                if let Some(st) = self.call(*k, "fmi2Reset", ANY, |c| unsafe { fmu::fmi2Reset(c) })
                {
                    assert_eq!(st, fmi2OK, "fmi2Reset must succeed outside fatal");
                    let s = self.slot(*k).expect("called");
                    s.machine = Some(M::Instantiated);
                    s.stored = Some(Stored::start());
                    s.time = Some(0.0);
                    s.forged = false;
                }
            }
            Op::SetReal(k, r, x) => self.set_real(*k, r, x),
            Op::SetInteger(k, r, x) => self.set_integer(*k, r, x),
            Op::SetBoolean(k, r, x) => {
                self.call(*k, "fmi2SetBoolean", SET, |c| unsafe {
                    fmu::fmi2SetBoolean(c, r.as_ptr(), r.len(), x.as_ptr())
                });
            }
            Op::SetString(k, r, x) => {
                let strings: Vec<CString> = x
                    .iter()
                    .map(|b| CString::new(b.clone()).unwrap_or_default())
                    .collect();
                let ptrs: Vec<fmi2String> = strings.iter().map(|s| s.as_ptr()).collect();
                self.call(*k, "fmi2SetString", SET, |c| unsafe {
                    fmu::fmi2SetString(c, r.as_ptr(), r.len(), ptrs.as_ptr())
                });
            }
            Op::GetReal(k, r) => {
                self.get_real(*k, r);
            }
            Op::GetInteger(k, r) => self.get_integer(*k, r),
            Op::GetBoolean(k, r) => self.get_boolean(*k, r),
            Op::GetString(k, r) => {
                let mut out: Vec<fmi2String> = vec![ptr::null(); r.len()];
                if let Some(fmi2OK) = self.call(*k, "fmi2GetString", GET, |c| unsafe {
                    fmu::fmi2GetString(c, r.as_ptr(), r.len(), out.as_mut_ptr())
                }) {
                    for p in out {
                        assert!(!p.is_null(), "fmi2GetString: fmi2OK with a NULL string");
                        // SAFETY: valid until the next call on the instance.
                        let _ = unsafe { CStr::from_ptr(p) }.to_bytes().len();
                    }
                }
            }
            Op::GetAll(k) => self.get_all(*k),
            Op::SetInputDerivatives(k, r, o, x) => {
                self.call(*k, "fmi2SetRealInputDerivatives", SET, |c| unsafe {
                    fmu::fmi2SetRealInputDerivatives(c, r.as_ptr(), r.len(), o.as_ptr(), x.as_ptr())
                });
            }
            Op::GetOutputDerivatives(k, r, o) => {
                let mut out = vec![f64::from_bits(SENTINEL); r.len()];
                if let Some(fmi2OK) = self.call(
                    *k,
                    "fmi2GetRealOutputDerivatives",
                    OUTPUT_DERIVATIVES,
                    |c| unsafe {
                        fmu::fmi2GetRealOutputDerivatives(
                            c,
                            r.as_ptr(),
                            r.len(),
                            o.as_ptr(),
                            out.as_mut_ptr(),
                        )
                    },
                ) {
                    for (r, x) in r.iter().zip(&out) {
                        assert_ne!(x.to_bits(), SENTINEL, "derivative of vr {r} not written");
                        assert!(x.is_finite(), "derivative of vr {r} = {x}");
                    }
                }
            }
            &Op::DoStep {
                slot,
                point,
                h,
                no_prior,
            } => self.do_step(slot, point, h, no_prior),
            Op::CancelStep(k) => {
                self.call(*k, "fmi2CancelStep", NOWHERE, |c| unsafe {
                    fmu::fmi2CancelStep(c)
                });
            }
            &Op::Status(k, which, kind) => self.status(k, which, kind),
            Op::SetDebugLogging(k, on, cats) => {
                let strings: Vec<CString> = cats
                    .iter()
                    .map(|b| CString::new(b.clone()).unwrap_or_default())
                    .collect();
                let ptrs: Vec<fmi2String> = strings.iter().map(|s| s.as_ptr()).collect();
                if let Some(st) = self.call(*k, "fmi2SetDebugLogging", ANY, |c| unsafe {
                    fmu::fmi2SetDebugLogging(c, *on, ptrs.len(), ptrs.as_ptr())
                }) {
                    if st == fmi2OK || st == fmi2Warning {
                        let s = self.slot(*k).expect("called");
                        s.sink.debug.set(*on != fmi2False);
                    }
                }
            }
            &Op::GetState(k, reuse) => self.get_state(k, reuse),
            &Op::SetState(k, r) => self.set_state(k, r),
            &Op::FreeState(k, r) => self.free_state(k, r),
            &Op::Serialize(k, r, size) => self.serialize(k, r, size),
            Op::Deserialize(k, from, m) => self.deserialize(*k, *from, m),
            Op::DirectionalDerivative(k) => {
                self.call(*k, "fmi2GetDirectionalDerivative", NOWHERE, |c| unsafe {
                    let (mut a, mut b) = (0u32, 0u32);
                    let (x, mut y) = (1.0f64, 0.0f64);
                    let _ = (&mut a, &mut b);
                    fmu::fmi2GetDirectionalDerivative(c, &a, 1, &b, 1, &x, &mut y)
                });
            }
            Op::Me { slot, which, x, n } => self.model_exchange(*slot, *which, *x, *n),
            Op::Platform => {
                let p = fmu::fmi2GetTypesPlatform();
                let v = fmu::fmi2GetVersion();
                // SAFETY: static strings of the FMU.
                unsafe {
                    assert_eq!(CStr::from_ptr(p).to_bytes(), b"default");
                    assert_eq!(CStr::from_ptr(v).to_bytes(), b"2.0");
                }
            }
        }
    }

    /// One Model Exchange call; after `fmi2OK` every value written is finite
    /// (the nominals positive), and the driver follows the ME state machine.
    fn model_exchange(&mut self, k: u8, which: u8, x: [f64; 2], n: usize) {
        let mut out = [f64::from_bits(SENTINEL); 16];
        let n = n.min(out.len());
        let (mut enter, mut terminate) = (-1, -1);
        let mut info = fmi2EventInfo {
            newDiscreteStatesNeeded: -1,
            terminateSimulation: -1,
            nominalsOfContinuousStatesChanged: -1,
            valuesOfContinuousStatesChanged: -1,
            nextEventTimeDefined: -1,
            nextEventTime: f64::NAN,
        };
        let p = out.as_mut_ptr();
        // SAFETY (every arm): a live instance and arrays of at least `n` values.
        let (what, allowed, st): (&str, &[M], _) = match which % 10 {
            0 => (
                "fmi2SetTime",
                ME_SET_TIME,
                self.call(k, "fmi2SetTime", ME_SET_TIME, |c| unsafe {
                    fmu::fmi2SetTime(c, x[0])
                }),
            ),
            1 => (
                "fmi2SetContinuousStates",
                ME_CONTINUOUS,
                self.call(k, "fmi2SetContinuousStates", ME_CONTINUOUS, |c| unsafe {
                    fmu::fmi2SetContinuousStates(c, x.as_ptr(), n.min(2))
                }),
            ),
            2 => (
                "fmi2GetContinuousStates",
                ME_EVALUATE,
                self.call(k, "fmi2GetContinuousStates", ME_EVALUATE, |c| unsafe {
                    fmu::fmi2GetContinuousStates(c, p, n)
                }),
            ),
            3 => (
                "fmi2GetDerivatives",
                ME_EVALUATE,
                self.call(k, "fmi2GetDerivatives", ME_EVALUATE, |c| unsafe {
                    fmu::fmi2GetDerivatives(c, p, n)
                }),
            ),
            4 => (
                "fmi2GetEventIndicators",
                ME_EVALUATE,
                self.call(k, "fmi2GetEventIndicators", ME_EVALUATE, |c| unsafe {
                    fmu::fmi2GetEventIndicators(c, p, n)
                }),
            ),
            5 => (
                "fmi2GetNominalsOfContinuousStates",
                ANY,
                self.call(k, "fmi2GetNominalsOfContinuousStates", ANY, |c| unsafe {
                    fmu::fmi2GetNominalsOfContinuousStates(c, p, n)
                }),
            ),
            6 => (
                "fmi2EnterEventMode",
                ME_SET_TIME,
                self.call(k, "fmi2EnterEventMode", ME_SET_TIME, |c| unsafe {
                    fmu::fmi2EnterEventMode(c)
                }),
            ),
            7 => (
                "fmi2NewDiscreteStates",
                ME_EVENT,
                self.call(k, "fmi2NewDiscreteStates", ME_EVENT, |c| unsafe {
                    fmu::fmi2NewDiscreteStates(c, &mut info)
                }),
            ),
            8 => (
                "fmi2EnterContinuousTimeMode",
                ME_EVENT,
                self.call(k, "fmi2EnterContinuousTimeMode", ME_EVENT, |c| unsafe {
                    fmu::fmi2EnterContinuousTimeMode(c)
                }),
            ),
            _ => (
                "fmi2CompletedIntegratorStep",
                ME_CONTINUOUS,
                self.call(
                    k,
                    "fmi2CompletedIntegratorStep",
                    ME_CONTINUOUS,
                    |c| unsafe {
                        fmu::fmi2CompletedIntegratorStep(c, fmi2True, &mut enter, &mut terminate)
                    },
                ),
            ),
        };
        let _ = allowed;
        let Some(st) = st else { return };
        let me = self.slot(k).is_some_and(|s| s.me);
        if !me {
            assert_eq!(st, fmi2Error, "{what} on a co-simulation instance");
            return;
        }
        if st != fmi2OK {
            return;
        }
        self.stats.model_exchange_ok += 1;
        if (2..=5).contains(&(which % 10)) {
            for (i, v) in out[..n].iter().enumerate() {
                assert!(v.is_finite(), "{what}: value {i} = {v} after fmi2OK");
            }
            if which % 10 == 5 {
                assert!(out[..n].iter().all(|v| *v > 0.0), "{what}: {:?}", &out[..n]);
            }
        }
        match which % 10 {
            6 => self.set_machine(k, Some(M::EventMode)),
            7 => {
                for b in [
                    info.newDiscreteStatesNeeded,
                    info.terminateSimulation,
                    info.valuesOfContinuousStatesChanged,
                ] {
                    assert!(b == fmi2True || b == fmi2False, "{what}: fmi2Boolean {b}");
                }
            }
            8 => self.set_machine(k, Some(M::ContinuousTime)),
            9 => assert!(
                [enter, terminate]
                    .iter()
                    .all(|b| *b == fmi2True || *b == fmi2False),
                "{what}: {enter}, {terminate}"
            ),
            _ => {}
        }
    }

    fn instantiate(&mut self, k: u8, spec: &InstSpec) {
        let k = k as usize % SLOTS;
        if self.slots[k].is_some() {
            // Instantiating into a used slot would lose the pointer: free first.
            self.free(k as u8);
        }
        let name: Option<Vec<u8>> = match &spec.name {
            Name::Null => None,
            Name::Empty => Some(Vec::new()),
            Name::Plain => Some(format!("fuzz{k}").into_bytes()),
            Name::Odd(b) => Some(b.clone()),
            Name::Long => Some(vec![b'n'; 5000]),
        };
        let name_c = name
            .as_ref()
            .map(|n| CString::new(n.clone()).expect("no NUL"));
        let guid = match spec.guid {
            Guid::Right => Some(CString::new(fmu::GUID).expect("GUID")),
            Guid::Wrong => Some(c"{00000000-0000-0000-0000-000000000000}".to_owned()),
            Guid::Null => None,
            Guid::Truncated => Some(CString::new(&fmu::GUID[..fmu::GUID.len() - 1]).expect("GUID")),
        };
        let resource = spec
            .resource
            .as_ref()
            .map(|r| CString::new(r.clone()).expect("no NUL"));
        let sink = LogSink::new(
            name.as_deref().unwrap_or(b""),
            spec.logging_on != fmi2False,
            spec.inspect,
        );
        let callbacks = Box::new(Callbacks {
            logger: spec.logger.then_some(logger as PlainLogger),
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            environment: &*sink as *const LogSink as *mut c_void,
        });
        let p0 = panics();
        let c = unsafe {
            fmu::fmi2Instantiate(
                name_c.as_ref().map_or(ptr::null(), |s| s.as_ptr()),
                spec.fmu_type,
                guid.as_ref().map_or(ptr::null(), |s| s.as_ptr()),
                resource.as_ref().map_or(ptr::null(), |s| s.as_ptr()),
                &*callbacks as *const Callbacks as *const fmi2CallbackFunctions,
                spec.visible,
                spec.logging_on,
            )
        };
        self.stats.calls += 1;
        assert_eq!(panics(), p0, "fmi2Instantiate: the FMU panicked");
        if let Some(p) = sink.take_problem() {
            panic!("fmi2Instantiate: logger: {p}");
        }
        let valid = name.as_ref().is_some_and(|n| !n.is_empty())
            && (spec.fmu_type == fmi2CoSimulation || spec.fmu_type == fmi2ModelExchange)
            && matches!(spec.guid, Guid::Right);
        assert_eq!(
            !c.is_null(),
            valid,
            "fmi2Instantiate({spec:?}) returned {c:?}"
        );
        if c.is_null() {
            if spec.logger {
                assert!(
                    sink.counts()[fmi2Error as usize] > 0,
                    "refused without a message"
                );
            }
            return;
        }
        self.stats.instantiated += 1;
        self.slots[k] = Some(Slot {
            c,
            sink,
            callbacks,
            logger: spec.logger,
            machine: Some(M::Instantiated),
            stored: Some(Stored::start()),
            time: Some(0.0),
            forged: false,
            states: Vec::new(),
            me: spec.fmu_type == fmi2ModelExchange,
        });
    }

    fn free(&mut self, k: u8) {
        let k = k as usize % SLOTS;
        if let Some(s) = self.slots[k].take() {
            let p0 = panics();
            // SAFETY: a live instance of ours; its FMU states go with it.
            unsafe { fmu::fmi2FreeInstance(s.c) };
            self.stats.calls += 1;
            assert_eq!(panics(), p0, "fmi2FreeInstance: the FMU panicked");
            if let Some(p) = s.sink.take_problem() {
                panic!("fmi2FreeInstance: logger: {p}");
            }
            drop(s);
        }
    }

    fn setup(&mut self, k: u8, tol_def: c_int, tol: f64, start: f64, stop_def: c_int, stop: f64) {
        let before = self.slot(k).and_then(|s| s.machine);
        if let Some(st) = self.call(k, "fmi2SetupExperiment", INSTANTIATED, |c| unsafe {
            fmu::fmi2SetupExperiment(c, tol_def, tol, start, stop_def, stop)
        }) {
            let tol_ok = tol_def == fmi2False || (tol.is_finite() && tol > 0.0);
            let stop_ok = stop_def == fmi2False || (stop.is_finite() && stop >= start);
            let s = self.slot(k).expect("called");
            if before == Some(M::Instantiated) || st == fmi2OK {
                assert_eq!(
                    st == fmi2OK,
                    tol_ok && start.is_finite() && stop_ok,
                    "fmi2SetupExperiment({tol_def}, {tol}, {start}, {stop_def}, {stop}) = {st}"
                );
            }
            if st == fmi2OK {
                s.time = Some(start);
            }
        }
    }

    fn enter(&mut self, k: u8) {
        if let Some(fmi2OK) =
            self.call(k, "fmi2EnterInitializationMode", INSTANTIATED, |c| unsafe {
                fmu::fmi2EnterInitializationMode(c)
            })
        {
            self.set_machine(k, Some(M::Init));
        }
    }

    fn exit(&mut self, k: u8) {
        let Some(s) = self.slot(k) else { return };
        let expect = (s.machine == Some(M::Init))
            .then(|| s.stored.as_ref().map(Stored::valid))
            .flatten();
        let stored = s.stored.clone();
        let Some(st) = self.call(k, "fmi2ExitInitializationMode", INIT, |c| unsafe {
            fmu::fmi2ExitInitializationMode(c)
        }) else {
            return;
        };
        if let Some(valid) = expect {
            assert_eq!(
                st,
                if valid { fmi2OK } else { fmi2Error },
                "fmi2ExitInitializationMode with parameters {:?}",
                stored.and_then(|s| s.params())
            );
            if valid {
                self.stats.exit_init_ok += 1;
            } else {
                self.stats.exit_init_error += 1;
            }
        }
        if st == fmi2OK {
            let me = self.slot(k).is_some_and(|s| s.me);
            self.set_machine(k, Some(if me { M::EventMode } else { M::StepComplete }));
        }
    }

    fn set_real(&mut self, k: u8, r: &[u32], x: &[f64]) {
        if let Some(fmi2OK) = self.call(k, "fmi2SetReal", SET, |c| unsafe {
            fmu::fmi2SetReal(c, r.as_ptr(), r.len(), x.as_ptr())
        }) {
            let s = self.slot(k).expect("called");
            if let Some(st) = s.stored.as_mut() {
                for (&r, &x) in r.iter().zip(x) {
                    if let Some(v) = st.real.get_mut(r as usize) {
                        *v = x;
                    }
                }
            }
        }
    }

    fn set_integer(&mut self, k: u8, r: &[u32], x: &[c_int]) {
        if let Some(fmi2OK) = self.call(k, "fmi2SetInteger", SET, |c| unsafe {
            fmu::fmi2SetInteger(c, r.as_ptr(), r.len(), x.as_ptr())
        }) {
            let s = self.slot(k).expect("called");
            if let Some(st) = s.stored.as_mut() {
                for (&r, &x) in r.iter().zip(x) {
                    if let Some(v) = st.int.get_mut(r as usize) {
                        *v = x;
                    }
                }
            }
        }
    }

    /// fmi2GetReal with the value checks; the values after fmi2OK.
    fn get_real(&mut self, k: u8, r: &[u32]) -> Option<Vec<f64>> {
        let mut out = vec![f64::from_bits(SENTINEL); r.len()];
        let st = self.call(k, "fmi2GetReal", GET, |c| unsafe {
            fmu::fmi2GetReal(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        })?;
        if st != fmi2OK && st != fmi2Warning {
            return None;
        }
        let params = || {
            let s = self.slots[k as usize % SLOTS].as_ref();
            format!(
                "{:?}",
                s.and_then(|s| s.stored.as_ref()).and_then(Stored::params)
            )
        };
        for (&r, &x) in r.iter().zip(&out) {
            assert_ne!(x.to_bits(), SENTINEL, "fmi2GetReal: vr {r} not written");
            let v = VARIABLES.iter().find(|v| v.vr == r).expect("a Real vr");
            let finite = match v.causality {
                Causality::Output => x.is_finite(),
                // thetaC is +inf without crushing
                Causality::CalculatedParameter => {
                    x.is_finite() || (r == vr::THETA_C && x == f64::INFINITY)
                }
                _ => true,
            };
            assert!(finite, "{} = {x} with parameters {}", v.name, params());
        }
        Some(out)
    }

    fn get_integer(&mut self, k: u8, r: &[u32]) {
        let mut out: Vec<c_int> = vec![0x5eed_f00d; r.len()];
        if let Some(fmi2OK) = self.call(k, "fmi2GetInteger", GET, |c| unsafe {
            fmu::fmi2GetInteger(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        }) {
            for (&r, &x) in r.iter().zip(&out) {
                match r {
                    vr::REGIME => assert!((0..=4).contains(&x), "regime = {x}"),
                    vr::IMPACTS => assert!(x >= 0, "impacts = {x}"),
                    vr::ZERO_CROSSINGS => assert!(x >= 0, "zeroCrossings = {x}"),
                    _ => assert_ne!(x, 0x5eed_f00d, "fmi2GetInteger: vr {r} not written"),
                }
            }
            let of = |v: u32| r.iter().position(|&q| q == v).map(|i| out[i]);
            if let (Some(i), Some(z)) = (of(vr::IMPACTS), of(vr::ZERO_CROSSINGS)) {
                assert!(i <= z, "impacts = {i} > zeroCrossings = {z}");
            }
        }
    }

    fn get_boolean(&mut self, k: u8, r: &[u32]) {
        let mut out: Vec<c_int> = vec![-7; r.len()];
        if let Some(fmi2OK) = self.call(k, "fmi2GetBoolean", GET, |c| unsafe {
            fmu::fmi2GetBoolean(c, r.as_ptr(), r.len(), out.as_mut_ptr())
        }) {
            for (&r, &x) in r.iter().zip(&out) {
                assert!(x == fmi2True || x == fmi2False, "Boolean vr {r} = {x}");
            }
        }
    }

    fn get_all(&mut self, k: u8) {
        let of = |base: BaseType| -> Vec<u32> {
            VARIABLES
                .iter()
                .filter(|v| {
                    v.ty.base() == base
                        && matches!(
                            v.causality,
                            Causality::Output | Causality::CalculatedParameter
                        )
                })
                .map(|v| v.vr)
                .collect()
        };
        self.get_real(k, &of(BaseType::Real));
        self.get_integer(k, &of(BaseType::Integer));
        self.get_boolean(k, &of(BaseType::Boolean));
    }

    fn do_step(&mut self, k: u8, point: Point, h: f64, no_prior: c_int) {
        let Some(s) = self.slot(k) else { return };
        let machine = s.machine;
        let forged = s.forged;
        // The FMU's time: asked where it answers, else the driver's own.
        let mut now = s.time;
        if matches!(
            machine,
            Some(M::StepComplete | M::StepFailed | M::Terminated)
        ) {
            let mut t = f64::NAN;
            if let Some(fmi2OK) = self.call(k, "fmi2GetRealStatus", STATUS, |c| unsafe {
                fmu::fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &mut t)
            }) {
                assert!(t.is_finite(), "fmi2LastSuccessfulTime = {t}");
                if let Some(d) = now {
                    assert_eq!(t.to_bits(), d.to_bits(), "fmi2LastSuccessfulTime");
                }
                now = Some(t);
            }
        }
        if h.is_finite() && h > MAX_STEP || (self.skip_extreme_stiffness && forged) {
            self.stats.steps_skipped += 1;
            return;
        }
        if self.skip_extreme_stiffness && machine == Some(M::StepComplete) && self.extreme(k) {
            self.stats.steps_skipped += 1;
            return;
        }
        let base = now.unwrap_or(0.0);
        let t = match point {
            Point::Matching => base,
            Point::Offset(d) => base + d,
            Point::Raw(x) => x,
        };
        if std::env::var_os("FUZZ_DRIVER_TRACE").is_some() {
            let s = self.slots[k as usize % SLOTS].as_ref();
            let params = s.and_then(|s| s.stored.as_ref()).and_then(Stored::params);
            let state = self.get_real(k, &[vr::AG, vr::THETA, vr::OMEGA]);
            eprintln!("fmi2DoStep({t}, {h}) on slot {k}: ag, theta, omega {state:?}, parameters {params:?}");
        }
        let Some(st) = self.call(k, "fmi2DoStep", DO_STEP, |c| unsafe {
            fmu::fmi2DoStep(c, t, h, no_prior)
        }) else {
            return;
        };
        let s = self.slot(k).expect("called");
        if !(t.is_finite() && h.is_finite() && h > 0.0) {
            assert_eq!(st, fmi2Error, "fmi2DoStep({t}, {h})");
        }
        match st {
            fmi2OK => {
                s.machine = Some(M::StepComplete);
                s.time = Some(t + h);
                self.stats.steps_ok += 1;
            }
            fmi2Discard => {
                s.machine = Some(M::StepFailed);
                s.time = None;
                self.stats.steps_discard += 1;
                let mut term = fmi2False;
                if let Some(fmi2OK) = self.call(k, "fmi2GetBooleanStatus", STATUS, |c| unsafe {
                    fmu::fmi2GetBooleanStatus(c, fmi2Terminated, &mut term)
                }) {
                    assert_eq!(
                        term, fmi2True,
                        "fmi2Discard from fmi2DoStep: fmi2Terminated"
                    );
                }
            }
            _ => {}
        }
    }

    /// A model out of the integrator's working range (see
    /// [`Driver::skip_extreme_stiffness`]), read from the FMU itself: a
    /// flexible interface far stiffer than the body's weight, or a body whose
    /// weight, mass, lever or inertia is beyond 1e-30..1e30 (W = 1.8e308 N on
    /// a rigid interface: the moments overflow and the step loop never ends).
    fn extreme(&mut self, k: u8) -> bool {
        let mut law: c_int = 0;
        let Some(fmi2OK) = self.call(k, "fmi2GetInteger", GET, |c| unsafe {
            fmu::fmi2GetInteger(c, &vr::INTERFACE, 1, &mut law)
        }) else {
            return false;
        };
        let Some(x) = self.get_real(
            k,
            &[
                vr::THETA_JO,
                vr::THETA_OV,
                vr::WEIGHT,
                vr::MASS,
                vr::R0,
                vr::IO,
            ],
        ) else {
            return false;
        };
        let body = x[2..].iter().any(|&v| !(1e-30..=1e30).contains(&v));
        body || (law != enums::RIGID && x[0] < EXTREME_STIFFNESS * x[1])
    }

    fn status(&mut self, k: u8, which: u8, kind: c_int) {
        let name = [
            "fmi2GetStatus",
            "fmi2GetRealStatus",
            "fmi2GetIntegerStatus",
            "fmi2GetBooleanStatus",
            "fmi2GetStringStatus",
        ][which as usize % 5];
        let mut st_out: fmi2Status = -1;
        let mut r = f64::NAN;
        let mut i: c_int = -1;
        let mut b: c_int = -1;
        let mut s: fmi2String = ptr::null();
        let Some(st) = self.call(k, name, STATUS, |c| unsafe {
            match which % 5 {
                0 => fmu::fmi2GetStatus(c, kind, &mut st_out),
                1 => fmu::fmi2GetRealStatus(c, kind, &mut r),
                2 => fmu::fmi2GetIntegerStatus(c, kind, &mut i),
                3 => fmu::fmi2GetBooleanStatus(c, kind, &mut b),
                _ => fmu::fmi2GetStringStatus(c, kind, &mut s),
            }
        }) else {
            return;
        };
        if st == fmi2OK {
            match which % 5 {
                0 => check_status(st_out, "fmi2GetStatus value"),
                1 => assert!(r.is_finite(), "{name}({kind}) = {r}"),
                3 => assert!(b == fmi2True || b == fmi2False, "{name}({kind}) = {b}"),
                // SAFETY: a string of the FMU's.
                4 if !s.is_null() => {
                    let _ = unsafe { CStr::from_ptr(s) }.to_bytes().len();
                }
                _ => {}
            }
        }
        if !(0..=3).contains(&kind) {
            assert!(st == fmi2Error, "{name}({kind}) = {st}: unknown kind");
        }
    }

    /// The state `r` names, if it exists: (pointer, owner slot, index).
    fn lookup_state(&self, r: StateRef) -> Option<(fmi2FMUstate, usize, usize)> {
        match r {
            StateRef::Null => Some((ptr::null_mut(), usize::MAX, usize::MAX)),
            StateRef::Of { slot, k } => {
                let owner = slot as usize % SLOTS;
                let s = self.slots[owner].as_ref()?;
                if s.states.is_empty() {
                    return None;
                }
                let i = k as usize % s.states.len();
                Some((s.states[i].p, owner, i))
            }
        }
    }

    /// What the driver knows of slot `k` now, with its outputs read if that
    /// cannot fail (the model exists and its parameters are valid).
    fn know(&mut self, k: u8) -> Known {
        let Some(s) = self.slot(k) else {
            return Known::unknown();
        };
        let outputs = if matches!(
            s.machine,
            Some(M::StepComplete | M::StepFailed | M::Terminated)
        ) {
            self.get_real(k, &real_outputs())
                .map(|v| v.iter().map(|x| x.to_bits()).collect())
        } else {
            None
        };
        let s = self.slot(k).expect("exists");
        Known {
            machine: s.machine,
            stored: s.stored.clone(),
            outputs,
        }
    }

    fn get_state(&mut self, k: u8, reuse: Option<u8>) {
        let Some(s) = self.slot(k) else { return };
        if s.states.len() >= MAX_STATES && reuse.is_none() {
            // Keep the number bounded: free the oldest instead.
            self.free_state(k, StateRef::Of { slot: k, k: 0 });
            return;
        }
        let (mut p, index) = match reuse {
            Some(i) if !s.states.is_empty() => {
                let i = i as usize % s.states.len();
                (s.states[i].p, Some(i))
            }
            _ => (ptr::null_mut(), None),
        };
        let known = self.know(k);
        let Some(st) = self.call(k, "fmi2GetFMUstate", ANY, |c| unsafe {
            fmu::fmi2GetFMUstate(c, &mut p)
        }) else {
            return;
        };
        assert_eq!(st, fmi2OK, "fmi2GetFMUstate");
        assert!(!p.is_null(), "fmi2GetFMUstate gave NULL");
        let s = self.slot(k).expect("called");
        let state = FmuState {
            p,
            genuine: true,
            known,
        };
        match index {
            Some(i) => {
                assert_eq!(p, s.states[i].p, "fmi2GetFMUstate moved a reused state");
                s.states[i] = state;
            }
            None => s.states.push(state),
        }
    }

    fn set_state(&mut self, k: u8, r: StateRef) {
        if self.slot(k).is_none() {
            return;
        }
        let Some((p, owner, i)) = self.lookup_state(r) else {
            return;
        };
        let own = owner == k as usize % SLOTS;
        let state = own.then(|| {
            let s = &self.slots[owner].as_ref().expect("owner").states[i];
            (s.genuine, s.known.clone())
        });
        let Some(st) = self.call(k, "fmi2SetFMUstate", ANY, |c| unsafe {
            fmu::fmi2SetFMUstate(c, p)
        }) else {
            return;
        };
        let Some((genuine, known)) = state else {
            assert_eq!(
                st, fmi2Error,
                "fmi2SetFMUstate with a state not of this instance"
            );
            return;
        };
        if genuine {
            assert_eq!(st, fmi2OK, "fmi2SetFMUstate of a live own state");
        }
        if st != fmi2OK {
            return;
        }
        let s = self.slot(k).expect("called");
        s.machine = known.machine;
        s.stored = known.stored.clone();
        s.time = None;
        s.forged = !genuine;
        if let Some(before) = known.outputs {
            let now = self
                .get_real(k, &real_outputs())
                .expect("outputs after restoring a state where they were read");
            let now: Vec<u64> = now.iter().map(|x| x.to_bits()).collect();
            assert_eq!(
                now, before,
                "outputs after fmi2SetFMUstate differ from when it was taken"
            );
            self.stats.restores_checked += 1;
        }
    }

    fn free_state(&mut self, k: u8, r: StateRef) {
        if self.slot(k).is_none() {
            return;
        }
        let Some((p, owner, i)) = self.lookup_state(r) else {
            return;
        };
        let own = owner == k as usize % SLOTS;
        let mut q = p;
        let Some(st) = self.call(k, "fmi2FreeFMUstate", ANY, |c| unsafe {
            fmu::fmi2FreeFMUstate(c, &mut q)
        }) else {
            return;
        };
        if p.is_null() {
            assert_eq!(st, fmi2OK, "fmi2FreeFMUstate(NULL) is ignored");
        } else if own {
            assert_eq!(st, fmi2OK, "fmi2FreeFMUstate of a live own state");
            assert!(q.is_null(), "fmi2FreeFMUstate leaves the pointer set");
            self.slot(k).expect("called").states.remove(i);
        } else {
            assert_eq!(
                st, fmi2Error,
                "fmi2FreeFMUstate of another instance's state"
            );
            assert_eq!(q, p, "a refused fmi2FreeFMUstate changed the pointer");
        }
    }

    fn serialize(&mut self, k: u8, r: StateRef, size_mode: u8) {
        if self.slot(k).is_none() {
            return;
        }
        let Some((p, owner, i)) = self.lookup_state(r) else {
            return;
        };
        let own = owner == k as usize % SLOTS && !p.is_null();
        let mut size: usize = usize::MAX;
        let Some(st) = self.call(k, "fmi2SerializedFMUstateSize", ANY, |c| unsafe {
            fmu::fmi2SerializedFMUstateSize(c, p, &mut size)
        }) else {
            return;
        };
        if !own {
            assert_eq!(
                st, fmi2Error,
                "fmi2SerializedFMUstateSize of a foreign state"
            );
            return;
        }
        assert_eq!(st, fmi2OK, "fmi2SerializedFMUstateSize of a live own state");
        assert!(size > 0 && size < 1 << 20, "serialized size {size}");
        let len = match size_mode % 3 {
            0 => size,
            1 => size - 1,
            _ => size + 17,
        };
        let mut buf = vec![0xa5u8; len];
        let Some(st) = self.call(k, "fmi2SerializeFMUstate", ANY, |c| unsafe {
            fmu::fmi2SerializeFMUstate(c, p, buf.as_mut_ptr() as *mut fmi2Byte, len)
        }) else {
            return;
        };
        if len < size {
            assert_eq!(
                st, fmi2Error,
                "fmi2SerializeFMUstate into {len} < {size} bytes"
            );
            return;
        }
        assert_eq!(st, fmi2OK, "fmi2SerializeFMUstate of a live own state");
        assert!(buf[size..].iter().all(|&b| b == 0), "padding is zero");
        let s = &self.slots[owner].as_ref().expect("owner").states[i];
        let known = s.genuine.then(|| s.known.clone());
        if self.pool.len() >= POOL {
            self.pool.remove(0);
        }
        let me = self.slots[owner].as_ref().is_some_and(|o| o.me);
        self.pool.push(Blob {
            bytes: buf,
            known,
            me,
        });
    }

    fn deserialize(&mut self, k: u8, from: u8, m: &Mutation) {
        if self.slot(k).is_none() {
            return;
        }
        let (mut bytes, known, source_me) = match m {
            Mutation::Random(b) => (b.clone(), None, false),
            _ if self.pool.is_empty() => (Vec::new(), None, false),
            _ => {
                let blob = &self.pool[from as usize % self.pool.len()];
                (blob.bytes.clone(), blob.known.clone(), blob.me)
            }
        };
        // a state of one fmuType's own states does not restore into an
        // instance of the other (fmu_state.rs)
        let target_me = self.slot(k).is_some_and(|s| s.me);
        let fits = known.as_ref().is_some_and(|kn| match kn.machine {
            Some(M::EventMode | M::ContinuousTime) => target_me,
            Some(M::StepComplete | M::StepFailed) => !target_me,
            Some(_) => true,
            None => source_me == target_me,
        });
        let genuine = fits && matches!(m, Mutation::None);
        match m {
            Mutation::None | Mutation::Random(_) => {}
            Mutation::Flip { pos, bit } => {
                if !bytes.is_empty() {
                    let i = *pos as usize % bytes.len();
                    bytes[i] ^= 1 << (bit % 8);
                }
            }
            Mutation::Truncate(n) => {
                let n = *n as usize % (bytes.len() + 1);
                bytes.truncate(n);
            }
            Mutation::Append(extra) => bytes.extend_from_slice(extra),
            Mutation::Reseal { edits, cut, extend } => {
                let mut payload = match trim(&bytes).and_then(|t| bytes::unseal(fmu::GUID, t).ok())
                {
                    Some(p) => p.to_vec(),
                    None => bytes.clone(),
                };
                if !payload.is_empty() {
                    for &(pos, val) in edits {
                        let i = pos as usize % payload.len();
                        payload[i] = val;
                    }
                }
                let keep = payload.len().saturating_sub(*cut as usize);
                payload.truncate(keep);
                payload.extend_from_slice(extend);
                bytes = bytes::seal(fmu::GUID, &payload);
            }
        }
        let mut p: fmi2FMUstate = ptr::null_mut();
        let Some(st) = self.call(k, "fmi2DeSerializeFMUstate", ANY, |c| unsafe {
            fmu::fmi2DeSerializeFMUstate(c, bytes.as_ptr() as *const fmi2Byte, bytes.len(), &mut p)
        }) else {
            return;
        };
        if genuine {
            assert_eq!(
                st, fmi2OK,
                "fmi2DeSerializeFMUstate of an unmodified buffer"
            );
        }
        if st != fmi2OK {
            assert!(p.is_null(), "a refused buffer gave a state");
            return;
        }
        assert!(!p.is_null());
        self.stats.deserialized += 1;
        let known = if genuine {
            known.expect("genuine")
        } else {
            Known::unknown()
        };
        self.slot(k)
            .expect("called")
            .states
            .push(FmuState { p, genuine, known });
        // Serializing it again gives the same bytes (up to zero padding).
        let mut size = 0usize;
        let st = self.call(k, "fmi2SerializedFMUstateSize", ANY, |c| unsafe {
            fmu::fmi2SerializedFMUstateSize(c, p, &mut size)
        });
        assert_eq!(
            st,
            Some(fmi2OK),
            "fmi2SerializedFMUstateSize of a deserialized state"
        );
        let mut again = vec![0u8; size];
        let st = self.call(k, "fmi2SerializeFMUstate", ANY, |c| unsafe {
            fmu::fmi2SerializeFMUstate(c, p, again.as_mut_ptr() as *mut fmi2Byte, size)
        });
        assert_eq!(
            st,
            Some(fmi2OK),
            "fmi2SerializeFMUstate of a deserialized state"
        );
        let mismatch = (0..size.min(bytes.len())).find(|&i| again[i] != bytes[i]);
        let nonzero_tail = bytes
            .get(size..)
            .map_or(0, |t| t.iter().filter(|&&b| b != 0).count());
        assert!(
            bytes.len() >= size && mismatch.is_none() && nonzero_tail == 0,
            "a deserialized state serializes to other bytes: {} bytes in, {size} out, first difference at {mismatch:?}, {nonzero_tail} non-zero bytes after the envelope",
            bytes.len()
        );
        // Keep the number bounded.
        if self.slot(k).expect("called").states.len() > MAX_STATES {
            self.free_state(k, StateRef::Of { slot: k, k: 0 });
        }
    }
}

/// The envelope without trailing zero padding (by its own length field).
fn trim(buf: &[u8]) -> Option<&[u8]> {
    // magic 8, version 4, GUID length 4 + bytes, payload length 8, payload, CRC 4
    let g = u32::from_le_bytes(buf.get(12..16)?.try_into().ok()?) as usize;
    let at = 16usize.checked_add(g)?;
    let n = u64::from_le_bytes(buf.get(at..at + 8)?.try_into().ok()?) as usize;
    let total = at.checked_add(8)?.checked_add(n)?.checked_add(4)?;
    buf.get(..total)
}

/// Decodes `data` and runs it: the fuzz target's and the proptests' entry.
pub fn run_bytes(data: &[u8]) -> Stats {
    Driver::run(&decode(data))
}
