//! Operations: decoded from the input bytes.

use crate::*;

/// Bytes consumed from the front; zeros once exhausted.
pub struct Bytes<'a> {
    pub(crate) data: &'a [u8],
    pub(crate) pos: usize,
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
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    pub fn u64(&mut self) -> u64 {
        (self.u32() as u64) | ((self.u32() as u64) << 32)
    }
    /// 0..n (n <= 256).
    pub fn below(&mut self, n: usize) -> usize {
        self.u8() as usize % n.max(1)
    }
    /// True with probability k/8.
    pub fn chance(&mut self, k: u8) -> bool {
        self.u8() % 8 < k
    }
    pub fn take(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.u8()).collect()
    }
    /// A float from a table of awkward values, or raw bits.
    pub fn awkward(&mut self) -> f64 {
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
    pub fn near(&mut self, start: f64) -> f64 {
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
    pub fn int(&mut self) -> i32 {
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
        x: Vec<f64>,
        n: usize,
    },
}

pub fn slot<M: Model>(b: &mut Bytes) -> u8 {
    b.below(M::SLOTS) as u8
}

pub fn vr_of<M: Model>(b: &mut Bytes, base: BaseType) -> u32 {
    if b.chance(7) {
        let own: Vec<&Variable> = M::VARIABLES
            .iter()
            .filter(|v| v.ty.base() == base)
            .collect();
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

pub fn count(b: &mut Bytes) -> usize {
    match b.u8() {
        0..=39 => 0,
        40..=159 => 1,
        160..=239 => 2 + b.below(6),
        _ => 8 + b.below(57),
    }
}

pub fn vrs<M: Model>(b: &mut Bytes, base: BaseType) -> Vec<u32> {
    let n = count(b);
    (0..n).map(|_| vr_of::<M>(b, base)).collect()
}

pub fn start_real<M: Model>(r: u32) -> f64 {
    match M::VARIABLES.iter().find(|v| v.vr == r).map(|v| v.ty) {
        Some(Type::Real { start, .. }) => start.unwrap_or(0.0),
        _ => 0.0,
    }
}

pub fn spec(b: &mut Bytes) -> InstSpec {
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

pub fn mutation(b: &mut Bytes) -> Mutation {
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

pub fn state_ref<M: Model>(b: &mut Bytes, own: u8) -> StateRef {
    match b.below(16) {
        0 => StateRef::Null,
        1 => StateRef::Of {
            slot: slot::<M>(b),
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
pub(crate) const OP_TABLE: [u8; 64] = [
    0, 3, 4, 5, 6, 7, 7, 7, 7, 10, 11, 11, 11, 12, 12, 40, 40, 40, 15, 15, 17, 18, 19, 19, 19, 21,
    22, 23, 24, 24, 24, 26, 41, 41, 27, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 32,
    33, 33, 34, 35, 42, 42, 42, 42, 37, 38, 38, 39, 39, 42,
];

pub fn decode_op<M: Model>(b: &mut Bytes) -> Op {
    let s = slot::<M>(b);
    match OP_TABLE[b.below(64)] {
        40 => M::set_input(b, s),
        42 => Op::Me {
            slot: s,
            which: b.u8(),
            x: (0..M::STATES)
                .map(|i| if i == 0 { b.near(0.05) } else { b.near(0.0) })
                .collect(),
            n: if b.chance(1) {
                [
                    0,
                    1,
                    3,
                    M::EVENT_INDICATORS.saturating_sub(1),
                    M::EVENT_INDICATORS + 1,
                ][b.below(5)]
            } else {
                [
                    M::ME_LENGTH,
                    M::ME_LENGTH,
                    M::EVENT_INDICATORS,
                    M::EVENT_INDICATORS,
                ][b.below(4)]
            },
        },
        41 => M::set_input_derivative(b, s),
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
            let r = vrs::<M>(b, BaseType::Real);
            let x = r.iter().map(|&r| b.near(start_real::<M>(r))).collect();
            Op::SetReal(s, r, x)
        }
        15 | 16 => {
            let r = vrs::<M>(b, BaseType::Integer);
            let x = r.iter().map(|_| b.int()).collect();
            Op::SetInteger(s, r, x)
        }
        17 => {
            let r = vrs::<M>(b, BaseType::Boolean);
            let x = r.iter().map(|_| b.int()).collect();
            Op::SetBoolean(s, r, x)
        }
        18 => {
            let r = vrs::<M>(b, BaseType::String);
            let x = r
                .iter()
                .map(|_| {
                    let n = b.below(8);
                    b.take(n).into_iter().map(|c| c.max(1)).collect()
                })
                .collect();
            Op::SetString(s, r, x)
        }
        19 | 20 => Op::GetReal(s, vrs::<M>(b, BaseType::Real)),
        21 => Op::GetInteger(s, vrs::<M>(b, BaseType::Integer)),
        22 => Op::GetBoolean(s, vrs::<M>(b, BaseType::Boolean)),
        23 => Op::GetString(s, vrs::<M>(b, BaseType::String)),
        24 | 25 => Op::GetAll(s),
        26 => {
            let r = vrs::<M>(b, BaseType::Real);
            let o = r
                .iter()
                .map(|_| if b.chance(5) { 1 } else { b.int() })
                .collect();
            let x = r.iter().map(|_| b.near(1.0)).collect();
            Op::SetInputDerivatives(s, r, o, x)
        }
        27 => {
            let r = vrs::<M>(b, BaseType::Real);
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
                        M::LOG_CATEGORIES[b.below(M::LOG_CATEGORIES.len())]
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
        36 => Op::SetState(s, state_ref::<M>(b, s)),
        37 => {
            if b.chance(1) {
                Op::FreeState(s, state_ref::<M>(b, s))
            } else {
                Op::DirectionalDerivative(s)
            }
        }
        38 => {
            let r = state_ref::<M>(b, s);
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

/// Instantiate into `slot` a co-simulation instance with the right GUID, a
/// logger whose messages are inspected, debug logging off.
pub fn plain_instance(slot: u8) -> Op {
    Op::Instantiate(
        slot,
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
}

/// `fmi2DoStep` of `h` s on slot `slot` from the instance's own time.
pub fn step(slot: u8, h: f64) -> Op {
    Op::DoStep {
        slot,
        point: Point::Matching,
        h,
        no_prior: 0,
    }
}

/// The operations encoded by `data` (at most [`MAX_OPS`]).
pub fn decode<M: Model>(data: &[u8]) -> Vec<Op> {
    let mut b = Bytes::new(data);
    let mut ops = Vec::new();
    // The first byte: how many instances start instantiated (0, 1) or
    // initialized (2, 4) with default settings, so that short inputs reach
    // running instances.
    if !b.is_empty() {
        match b.u8() % 4 {
            0 => {}
            1 => ops.push(plain_instance(0)),
            n => {
                for k in 0..if n == 2 { 2 } else { 4 } {
                    ops.push(plain_instance(k));
                    ops.push(Op::Init(k));
                }
            }
        }
    }
    while !b.is_empty() && ops.len() < MAX_OPS {
        ops.push(decode_op::<M>(&mut b));
    }
    ops
}
