//! The driver: what it knows of each instance, and `apply`, which performs
//! one operation.

use super::*;

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

pub(crate) const ANY: &[M] = &[
    M::Instantiated,
    M::Init,
    M::StepComplete,
    M::StepFailed,
    M::Terminated,
    M::Error,
    M::EventMode,
    M::ContinuousTime,
];
pub(crate) const NOWHERE: &[M] = &[];
pub(crate) const INSTANTIATED: &[M] = &[M::Instantiated];
pub(crate) const INIT: &[M] = &[M::Init];
pub(crate) const TERMINATE: &[M] = &[
    M::StepComplete,
    M::StepFailed,
    M::EventMode,
    M::ContinuousTime,
];
pub(crate) const GET: &[M] = &[
    M::Init,
    M::StepComplete,
    M::StepFailed,
    M::Terminated,
    M::Error,
    M::EventMode,
    M::ContinuousTime,
];
pub(crate) const SET: &[M] = &[
    M::Instantiated,
    M::Init,
    M::StepComplete,
    M::EventMode,
    M::ContinuousTime,
];
// Model Exchange (FMI 2.0 §3.2.3)
pub(crate) const ME_SET_TIME: &[M] = &[M::EventMode, M::ContinuousTime];
pub(crate) const ME_CONTINUOUS: &[M] = &[M::ContinuousTime];
pub(crate) const ME_EVENT: &[M] = &[M::EventMode];
pub(crate) const ME_EVALUATE: &[M] = &[
    M::Init,
    M::EventMode,
    M::ContinuousTime,
    M::Terminated,
    M::Error,
];
pub(crate) const OUTPUT_DERIVATIVES: &[M] =
    &[M::StepComplete, M::StepFailed, M::Terminated, M::Error];
pub(crate) const DO_STEP: &[M] = &[M::StepComplete];
pub(crate) const STATUS: &[M] = &[M::StepComplete, M::StepFailed, M::Terminated];

/// The driver's copy of the stored parameters and start values (by value
/// reference; Reals and Integers), or unknown.
#[derive(Clone, Debug, PartialEq)]
pub struct Stored {
    pub(crate) real: Vec<f64>,
    pub(crate) int: Vec<i32>,
}

impl Stored {
    pub(crate) fn start() -> Stored {
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
            restraint: match i(vr::RESTRAINT) {
                NONE => RestraintKind::None,
                ONE_SIDED => RestraintKind::OneSided,
                _ => return None,
            },
            side: i(vr::SIDE),
            e_restraint: r(vr::E_RESTRAINT),
        })
    }

    pub(crate) fn valid(&self) -> bool {
        // maxSteps >= 1, mu >= 0 and not NaN (docs/model.md §5)
        let mu = self.real[vr::MU as usize];
        self.int[vr::MAX_STEPS as usize] >= 1
            && mu >= 0.0
            && self.params().is_some_and(|p| p.build().is_ok())
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
    pub(crate) slots: Vec<Option<Slot>>,
    pub(crate) pool: Vec<Blob>,
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

pub(crate) fn real_outputs() -> Vec<u32> {
    VARIABLES
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

    pub(crate) fn slot(&mut self, k: u8) -> Option<&mut Slot> {
        self.slots[k as usize % SLOTS].as_mut()
    }

    /// Performs one FMI call on slot `k`: counts, checks the status, that no
    /// panic happened, the logger's findings, the state machine; returns the
    /// status (None when the slot is empty: nothing called).
    pub(crate) fn call(
        &mut self,
        k: u8,
        what: &str,
        allowed: &[Machine],
        f: impl FnOnce(fmi2Component) -> fmi2Status,
    ) -> Option<fmi2Status> {
        let s = self.slots[k as usize % SLOTS].as_mut()?;
        let before = s.log.counts();
        let p0 = panics();
        let status = f(s.c);
        self.stats.calls += 1;
        assert_eq!(panics(), p0, "{what}: the FMU panicked (caught or not)");
        check_status(status, what);
        self.stats.by_status[status as usize] += 1;
        if let Some(p) = problem(&s.log, before, &s.name, s.debug) {
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
            s.machine = Some(M::Error);
        }
        Some(status)
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
}
