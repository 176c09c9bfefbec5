//! The driver: what it knows of each instance, and `apply`, which performs
//! one operation.

use crate::*;

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

pub const ANY: &[Machine] = &[
    Machine::Instantiated,
    Machine::Init,
    Machine::StepComplete,
    Machine::StepFailed,
    Machine::Terminated,
    Machine::Error,
    Machine::EventMode,
    Machine::ContinuousTime,
];
pub const NOWHERE: &[Machine] = &[];
pub const INSTANTIATED: &[Machine] = &[Machine::Instantiated];
pub const INIT: &[Machine] = &[Machine::Init];
pub const TERMINATE: &[Machine] = &[
    Machine::StepComplete,
    Machine::StepFailed,
    Machine::EventMode,
    Machine::ContinuousTime,
];
pub const GET: &[Machine] = &[
    Machine::Init,
    Machine::StepComplete,
    Machine::StepFailed,
    Machine::Terminated,
    Machine::Error,
    Machine::EventMode,
    Machine::ContinuousTime,
];
pub const SET: &[Machine] = &[
    Machine::Instantiated,
    Machine::Init,
    Machine::StepComplete,
    Machine::EventMode,
    Machine::ContinuousTime,
];
// Model Exchange (FMI 2.0 §3.2.3)
pub const ME_SET_TIME: &[Machine] = &[Machine::EventMode, Machine::ContinuousTime];
pub const ME_CONTINUOUS: &[Machine] = &[Machine::ContinuousTime];
pub const ME_EVENT: &[Machine] = &[Machine::EventMode];
pub const ME_EVALUATE: &[Machine] = &[
    Machine::Init,
    Machine::EventMode,
    Machine::ContinuousTime,
    Machine::Terminated,
    Machine::Error,
];
pub const OUTPUT_DERIVATIVES: &[Machine] = &[
    Machine::StepComplete,
    Machine::StepFailed,
    Machine::Terminated,
    Machine::Error,
];
pub const DO_STEP: &[Machine] = &[Machine::StepComplete];
pub const STATUS: &[Machine] = &[
    Machine::StepComplete,
    Machine::StepFailed,
    Machine::Terminated,
];

/// The driver's copy of the stored parameters and start values (by value
/// reference; Reals and Integers), or unknown.
#[derive(Clone, Debug, PartialEq)]
pub struct Stored {
    pub real: Vec<f64>,
    pub int: Vec<i32>,
}

impl Stored {
    pub fn start<M: Model>() -> Stored {
        let n = M::VARIABLES.iter().map(|v| v.vr).max().unwrap_or(0) as usize + 1;
        let mut s = Stored {
            real: vec![0.0; n],
            int: vec![0; n],
        };
        for v in M::VARIABLES {
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
}

/// What the driver knows of an instance or of a saved state.
#[derive(Clone, Debug)]
pub(crate) struct Known {
    pub(crate) machine: Option<Machine>,
    pub(crate) stored: Option<Stored>,
    /// The bits of every Real output (if taken where they are defined).
    pub(crate) outputs: Option<Vec<u64>>,
}

impl Known {
    pub(crate) fn unknown() -> Known {
        Known {
            machine: None,
            stored: None,
            outputs: None,
        }
    }
}

pub(crate) struct FmuState {
    pub(crate) p: fmi2FMUstate,
    /// Taken by fmi2GetFMUstate, or deserialized from unmodified bytes:
    /// restoring it must succeed.
    pub(crate) genuine: bool,
    pub(crate) known: Known,
}

pub(crate) struct Slot {
    pub(crate) c: fmi2Component,
    /// What the logger recorded (the callbacks point at it).
    pub(crate) log: Box<Log>,
    /// Kept alive: the FMU holds a pointer to them.
    #[allow(dead_code)]
    pub(crate) callbacks: Box<fmi2CallbackFunctions>,
    pub(crate) logger: bool,
    /// The instance name the FMU must pass back to the logger.
    pub(crate) name: Vec<u8>,
    /// Whether debug logging is on (OK messages allowed).
    pub(crate) debug: bool,
    pub(crate) machine: Option<Machine>,
    pub(crate) stored: Option<Stored>,
    /// The end of the last step as the driver followed it.
    pub(crate) time: Option<f64>,
    /// Restored from a buffer the driver mutated (the engine's internal
    /// state, e.g. its step size, is then arbitrary).
    pub(crate) forged: bool,
    pub(crate) states: Vec<FmuState>,
    /// Instantiated as fmi2ModelExchange.
    pub(crate) me: bool,
    /// The logger keeps every message (else it counts them).
    pub(crate) inspect: bool,
    /// The messages of the last call (when `inspect`).
    pub(crate) recent: Vec<Message>,
    /// The derivatives of [`Model::INPUTS`] as the driver set them, or
    /// unknown (after restoring an FMU state).
    pub(crate) derivatives: Option<Vec<f64>>,
}

pub(crate) struct Blob {
    pub(crate) bytes: Vec<u8>,
    /// Serialized by an instance of fmuType fmi2ModelExchange.
    pub(crate) me: bool,
    /// What the state was, if it was genuine.
    pub(crate) known: Option<Known>,
}

/// Counters of what a run did (for the report and to see that sequences go
/// deep).
#[derive(Clone, Debug, Default)]
pub struct Stats {
    pub calls: u64,
    pub instantiated: u64,
    pub steps_ok: u64,
    pub steps_discard: u64,
    /// Steps the model let the driver skip ([`Model::skip_step`]).
    pub steps_skipped: u64,
    /// Discarded steps that ended the run (overturning, liftOff).
    pub steps_terminated: u64,
    /// Steps refused with fmi2Error from a state that allows them.
    pub steps_refused: u64,
    /// Steps refused with a known finding ([`Driver::tolerate_known`]).
    pub known_overflow: u64,
    pub exit_init_ok: u64,
    pub exit_init_error: u64,
    pub restores_checked: u64,
    pub deserialized: u64,
    /// Model Exchange calls that returned fmi2OK on an ME instance.
    pub model_exchange_ok: u64,
    pub by_status: [u64; 5],
}

pub struct Driver<M: Model> {
    pub(crate) slots: Vec<Option<Slot>>,
    pub(crate) pool: Vec<Blob>,
    pub stats: Stats,
    /// Let pass what the model documents as known findings
    /// ([`Model::skip_step`], [`Model::known_finding`]), so that the fuzzer
    /// looks for other faults.
    pub tolerate_known: bool,
    model: std::marker::PhantomData<M>,
}

pub(crate) fn real_outputs<M: Model>() -> Vec<u32> {
    M::VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Output && v.ty.base() == BaseType::Real)
        .map(|v| v.vr)
        .collect()
}

pub(crate) fn check_status(s: fmi2Status, what: &str) {
    assert!(
        (fmi2OK..=fmi2Error).contains(&s),
        "{what}: status {s} (only fmi2OK..fmi2Error are expected; fmi2Fatal means a panic in the layer, fmi2Pending never happens)"
    );
}

impl<M: Model> Default for Driver<M> {
    fn default() -> Self {
        Self::new()
    }
}

impl<M: Model> Driver<M> {
    pub fn new() -> Driver<M> {
        install_panic_counter();
        Driver {
            slots: (0..M::SLOTS).map(|_| None).collect(),
            pool: Vec::new(),
            stats: Stats::default(),
            tolerate_known: true,
            model: std::marker::PhantomData,
        }
    }

    /// Runs every operation, then frees what is left.
    pub fn run(ops: &[Op]) -> Stats {
        let mut d = Driver::<M>::new();
        for op in ops {
            d.apply(op);
        }
        d.finish()
    }

    /// Frees every instance (and with them their FMU states).
    pub fn finish(mut self) -> Stats {
        for k in 0..M::SLOTS {
            self.free(k as u8);
        }
        std::mem::take(&mut self.stats)
    }

    pub(crate) fn slot(&mut self, k: u8) -> Option<&mut Slot> {
        self.slots[k as usize % M::SLOTS].as_mut()
    }

    /// Performs one FMI call on slot `k`: counts, checks the status, that no
    /// panic happened, the logger's findings, the state machine; returns the
    /// status (None when the slot is empty: nothing called).
    pub fn call(
        &mut self,
        k: u8,
        what: &str,
        allowed: &[Machine],
        f: impl FnOnce(fmi2Component) -> fmi2Status,
    ) -> Option<fmi2Status> {
        let s = self.slots[k as usize % M::SLOTS].as_mut()?;
        let before = s.log.counts();
        let p0 = panics();
        let status = f(s.c);
        self.stats.calls += 1;
        assert_eq!(panics(), p0, "{what}: the FMU panicked (caught or not)");
        check_status(status, what);
        self.stats.by_status[status as usize] += 1;
        s.recent = s.log.take();
        if std::env::var_os("FUZZ_DRIVER_TRACE").is_some() {
            let texts: Vec<&str> = s.recent.iter().map(|m| m.text.as_str()).collect();
            eprintln!("  {what} on slot {k}: status {status} {texts:?}");
        }
        if let Some(p) = problem::<M>(&s.log, before, &s.recent, &s.name, s.debug) {
            panic!("{what}: logger: {p}");
        }
        if status != fmi2OK && s.logger {
            let after = s.log.counts();
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
            s.machine = Some(Machine::Error);
        }
        Some(status)
    }

    /// The state the driver follows for slot `k` (None: unknown or empty).
    pub fn machine(&mut self, k: u8) -> Option<Machine> {
        self.slot(k).and_then(|s| s.machine)
    }

    /// A setter refused in a state that allows it (`m`, before the call)
    /// names one of the variables `r` it was given.
    pub(crate) fn refusal_names_a_target(
        &mut self,
        k: u8,
        what: &str,
        m: Option<Machine>,
        st: Option<fmi2Status>,
        r: &[u32],
    ) {
        let Some(s) = self.slot(k) else { return };
        if M::STRICT
            && st == Some(fmi2Error)
            && m.is_some_and(|m| SET.contains(&m))
            && s.inspect
            && s.logger
        {
            assert!(
                names_a_target(&s.recent, r, M::VARIABLES),
                "{what} of {r:?} refused without naming one of them: {:?}",
                s.recent
            );
        }
    }

    /// The driver's copy of slot `k`'s stored values, if it knows them.
    pub fn stored(&self, k: u8) -> Option<&Stored> {
        self.slots[k as usize % M::SLOTS].as_ref()?.stored.as_ref()
    }

    /// The derivatives of [`Model::INPUTS`] on slot `k`, if the driver
    /// knows them.
    pub fn derivatives(&self, k: u8) -> Option<&[f64]> {
        self.slots[k as usize % M::SLOTS]
            .as_ref()?
            .derivatives
            .as_deref()
    }

    pub(crate) fn set_machine(&mut self, k: u8, m: Option<Machine>) {
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
                    .is_some_and(|s| s.machine == Some(Machine::Instantiated))
                {
                    self.setup(*k, fmi2False, 0.0, 0.0, fmi2False, 0.0);
                    self.enter(*k);
                    self.exit(*k);
                }
            }
            Op::Terminate(k) => {
                if let Some(st) = self.call(*k, "fmi2Terminate", TERMINATE, |c| unsafe {
                    (M::API.fmi2Terminate)(c)
                }) {
                    if st == fmi2OK {
                        self.set_machine(*k, Some(Machine::Terminated));
                    }
                }
            }
            Op::Reset(k) => {
                if let Some(st) =
                    self.call(*k, "fmi2Reset", ANY, |c| unsafe { (M::API.fmi2Reset)(c) })
                {
                    assert_eq!(st, fmi2OK, "fmi2Reset must succeed outside fatal");
                    let s = self.slot(*k).expect("called");
                    s.machine = Some(Machine::Instantiated);
                    s.stored = Some(Stored::start::<M>());
                    s.time = Some(0.0);
                    s.forged = false;
                    s.derivatives = Some(vec![0.0; M::INPUTS.len()]);
                }
            }
            Op::SetReal(k, r, x) => self.set_real(*k, r, x),
            Op::SetInteger(k, r, x) => self.set_integer(*k, r, x),
            Op::SetBoolean(k, r, x) => {
                let m = self.machine(*k);
                let st = self.call(*k, "fmi2SetBoolean", SET, |c| unsafe {
                    (M::API.fmi2SetBoolean)(c, r.as_ptr(), r.len(), x.as_ptr())
                });
                self.refusal_names_a_target(*k, "fmi2SetBoolean", m, st, r);
            }
            Op::SetString(k, r, x) => {
                let strings: Vec<CString> = x
                    .iter()
                    .map(|b| CString::new(b.clone()).unwrap_or_default())
                    .collect();
                let ptrs: Vec<fmi2String> = strings.iter().map(|s| s.as_ptr()).collect();
                let m = self.machine(*k);
                let st = self.call(*k, "fmi2SetString", SET, |c| unsafe {
                    (M::API.fmi2SetString)(c, r.as_ptr(), r.len(), ptrs.as_ptr())
                });
                self.refusal_names_a_target(*k, "fmi2SetString", m, st, r);
            }
            Op::GetReal(k, r) => {
                self.get_real(*k, r);
            }
            Op::GetInteger(k, r) => self.get_integer(*k, r),
            Op::GetBoolean(k, r) => self.get_boolean(*k, r),
            Op::GetString(k, r) => {
                let mut out: Vec<fmi2String> = vec![ptr::null(); r.len()];
                if let Some(fmi2OK) = self.call(*k, "fmi2GetString", GET, |c| unsafe {
                    (M::API.fmi2GetString)(c, r.as_ptr(), r.len(), out.as_mut_ptr())
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
                let m = self.machine(*k);
                let st = self.call(*k, "fmi2SetRealInputDerivatives", SET, |c| unsafe {
                    (M::API.fmi2SetRealInputDerivatives)(
                        c,
                        r.as_ptr(),
                        r.len(),
                        o.as_ptr(),
                        x.as_ptr(),
                    )
                });
                self.refusal_names_a_target(*k, "fmi2SetRealInputDerivatives", m, st, r);
                if st == Some(fmi2OK) {
                    let s = self.slot(*k).expect("called");
                    if let Some(d) = s.derivatives.as_mut() {
                        for ((r, o), x) in r.iter().zip(o).zip(x) {
                            if let (Some(i), 1) = (M::INPUTS.iter().position(|q| q == r), *o) {
                                d[i] = *x;
                            }
                        }
                    }
                }
            }
            Op::GetOutputDerivatives(k, r, o) => {
                let mut out = vec![f64::from_bits(SENTINEL); r.len()];
                if let Some(fmi2OK) = self.call(
                    *k,
                    "fmi2GetRealOutputDerivatives",
                    OUTPUT_DERIVATIVES,
                    |c| unsafe {
                        (M::API.fmi2GetRealOutputDerivatives)(
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
                        // frictionDemand's are 0 where it stands at 1e60
                        // (docs/model.md §5)
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
                    (M::API.fmi2CancelStep)(c)
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
                    (M::API.fmi2SetDebugLogging)(c, *on, ptrs.len(), ptrs.as_ptr())
                }) {
                    if st == fmi2OK || st == fmi2Warning {
                        let s = self.slot(*k).expect("called");
                        s.debug = *on != fmi2False;
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
                    (M::API.fmi2GetDirectionalDerivative)(c, &a, 1, &b, 1, &x, &mut y)
                });
            }
            Op::Me { slot, which, x, n } => self.model_exchange(*slot, *which, x, *n),
            Op::Platform => {
                let p = (M::API.fmi2GetTypesPlatform)();
                let v = (M::API.fmi2GetVersion)();
                // SAFETY: static strings of the FMU.
                unsafe {
                    assert_eq!(CStr::from_ptr(p).to_bytes(), b"default");
                    assert_eq!(CStr::from_ptr(v).to_bytes(), b"2.0");
                }
            }
        }
    }
}
