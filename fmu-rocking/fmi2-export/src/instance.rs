//! One FMU instance: the state machine of FMI 2.0 co-simulation, the stored
//! values, the model, the FMU states. Safe Rust on slices; `ffi` turns the C
//! calls into these.

#![allow(non_upper_case_globals)] // the FMI constants keep their C names

use std::collections::BTreeSet;
use std::ffi::CString;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::sync::Mutex;

use model_description::{
    BaseType, Causality, Initial, ModelDescription, Type, Variability, Variable,
};

use crate::bytes::{self, ByteReader, ByteWriter, ReadError};
use crate::logging::{Logger, LOG_ALL, LOG_EVENTS, LOG_STATUS_WARNING};
use crate::slave::{EventLog, Inputs, Scalar, Setup, Slave, StepEnd, Values};
use crate::types::*;

/// States of the FMI 2.0 co-simulation state machine (no asynchronous steps:
/// `stepInProgress` and `stepCanceled` never occur).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Machine {
    Instantiated,
    InitializationMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
    Fatal,
}

impl Machine {
    const ALL: [Machine; 7] = [
        Machine::Instantiated,
        Machine::InitializationMode,
        Machine::StepComplete,
        Machine::StepFailed,
        Machine::Terminated,
        Machine::Error,
        Machine::Fatal,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Machine::Instantiated => "instantiated",
            Machine::InitializationMode => "initializationMode",
            Machine::StepComplete => "stepComplete",
            Machine::StepFailed => "stepFailed",
            Machine::Terminated => "terminated",
            Machine::Error => "error",
            Machine::Fatal => "fatal",
        }
    }

    fn code(self) -> u8 {
        Machine::ALL.iter().position(|m| *m == self).unwrap() as u8
    }

    fn from_code(c: u8) -> Option<Machine> {
        Machine::ALL.get(c as usize).copied()
    }
}

use Machine as M;

/// Where each function may be called (FMI 2.0, section 4.2.4 state table).
pub(crate) mod allowed {
    use super::Machine as M;
    pub const ANY_BUT_FATAL: &[M] = &[
        M::Instantiated,
        M::InitializationMode,
        M::StepComplete,
        M::StepFailed,
        M::Terminated,
        M::Error,
    ];
    pub const INSTANTIATED: &[M] = &[M::Instantiated];
    pub const INIT: &[M] = &[M::InitializationMode];
    pub const TERMINATE: &[M] = &[M::StepComplete, M::StepFailed];
    pub const GET: &[M] = &[
        M::InitializationMode,
        M::StepComplete,
        M::StepFailed,
        M::Terminated,
        M::Error,
    ];
    pub const SET: &[M] = &[M::Instantiated, M::InitializationMode, M::StepComplete];
    pub const OUTPUT_DERIVATIVES: &[M] = &[M::StepComplete, M::StepFailed, M::Terminated, M::Error];
    pub const DO_STEP: &[M] = &[M::StepComplete];
    pub const STATUS: &[M] = &[M::StepComplete, M::StepFailed, M::Terminated];
}

/// A failed call: its status (Discard, Error or Fatal) and message.
#[derive(Debug)]
pub struct Fail {
    pub status: Status,
    pub message: String,
}

pub type Res<T> = Result<T, Fail>;

pub fn error<T>(message: impl Into<String>) -> Res<T> {
    Err(Fail {
        status: Status::Error,
        message: message.into(),
    })
}

pub fn discard<T>(message: impl Into<String>) -> Res<T> {
    Err(Fail {
        status: Status::Discard,
        message: message.into(),
    })
}

/// The message of a caught panic.
pub fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic".to_string()
    }
}

/// Runs model code, turning a panic into an error.
fn guarded<T>(what: &str, f: impl FnOnce() -> Result<T, String>) -> Res<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(x)) => Ok(x),
        Ok(Err(m)) => error(m),
        Err(p) => error(format!(
            "internal error in the model during {what}: {}",
            panic_message(&*p)
        )),
    }
}

/// A saved FMU state (`fmi2FMUstate` points to one).
pub struct Snapshot<S: Slave> {
    machine: Machine,
    setup: Setup,
    time: f64,
    last_successful_time: f64,
    terminated: bool,
    values: Vec<Option<Scalar>>,
    derivatives: Vec<f64>,
    slave: Option<S::State>,
}

/// An instance as the host sees it (`fmi2Component`).
#[repr(C)]
pub struct Instance<S: Slave> {
    pub(crate) magic: u64,
    pub(crate) guid: &'static str,
    pub(crate) inner: Mutex<Inner<S>>,
}

pub(crate) const INSTANCE_MAGIC: u64 = u64::from_le_bytes(*b"FMI2INST");

pub struct Inner<S: Slave> {
    pub(crate) md: &'static ModelDescription,
    pub(crate) logger: Logger,
    pub(crate) machine: Machine,
    values: Vec<Option<Scalar>>,
    derivatives: Vec<f64>,
    setup: Setup,
    time: f64,
    last_successful_time: f64,
    terminated: bool,
    slave: Option<S>,
    /// The stored values changed since `slave` was built.
    stale: bool,
    /// Live `fmi2FMUstate` pointers handed out by this instance: a membership
    /// registry, ordered rather than hashed, so that the FMU never asks the OS
    /// for random hasher keys (std's `HashSet` seeds its `RandomState` so).
    states: BTreeSet<usize>,
    pub(crate) resource_dir: Option<PathBuf>,
}

// SAFETY: the raw pointers in `Logger` (host environment and callback) are
// only passed back to the host; FMI allows an instance to be used from any
// thread as long as calls on it do not overlap, and the `Mutex` around
// `Inner` serialises them anyway.
unsafe impl<S: Slave> Send for Inner<S> {}

fn is_stored(v: &Variable) -> bool {
    matches!(v.causality, Causality::Parameter | Causality::Input)
        || v.variability == Variability::Constant
        || matches!(
            v.effective_initial(),
            Some(Initial::Exact | Initial::Approx)
        )
}

fn from_store(v: &Variable) -> bool {
    matches!(v.causality, Causality::Parameter | Causality::Input)
        || v.variability == Variability::Constant
}

fn start_value(v: &Variable) -> Option<Scalar> {
    if !is_stored(v) {
        return None;
    }
    Some(match v.ty {
        Type::Real { start, .. } => Scalar::Real(start.unwrap_or(0.0)),
        Type::Integer { start } | Type::Enumeration { start, .. } => {
            Scalar::Integer(start.unwrap_or(0))
        }
        Type::Boolean { start } => Scalar::Boolean(start.unwrap_or(false)),
        Type::String { start } => {
            Scalar::String(CString::new(start.unwrap_or("")).unwrap_or_default())
        }
    })
}

/// Whether `v` may be set in state `m` (FMI 2.0 co-simulation rules).
fn settable(v: &Variable, m: Machine) -> bool {
    let input = v.causality == Causality::Input;
    let not_constant = v.variability != Variability::Constant;
    let init = v.effective_initial();
    match m {
        M::Instantiated => {
            input || (not_constant && matches!(init, Some(Initial::Exact | Initial::Approx)))
        }
        M::InitializationMode => {
            input
                || (v.causality != Causality::Parameter && v.variability == Variability::Tunable)
                || (not_constant && init == Some(Initial::Exact))
        }
        M::StepComplete => {
            input || (v.causality == Causality::Parameter && v.variability == Variability::Tunable)
        }
        _ => false,
    }
}

impl<S: Slave> Inner<S> {
    pub(crate) fn new(logger: Logger, resource_dir: Option<PathBuf>) -> Inner<S> {
        let md = S::description();
        let mut inner = Inner {
            md,
            logger,
            machine: M::Instantiated,
            values: Vec::new(),
            derivatives: Vec::new(),
            setup: Setup {
                tolerance: None,
                start_time: 0.0,
                stop_time: None,
            },
            time: 0.0,
            last_successful_time: 0.0,
            terminated: false,
            slave: None,
            stale: true,
            states: BTreeSet::new(),
            resource_dir,
        };
        inner.reset_values();
        inner
    }

    fn reset_values(&mut self) {
        self.values = self.md.variables.iter().map(start_value).collect();
        self.derivatives = vec![0.0; self.md.variables.len()];
        self.setup = Setup {
            tolerance: None,
            start_time: 0.0,
            stop_time: None,
        };
        self.time = 0.0;
        self.last_successful_time = 0.0;
        self.terminated = false;
        self.slave = None;
        self.stale = true;
    }

    pub fn machine(&self) -> Machine {
        self.machine
    }

    /// Logs a trace of a call (category logAll), formatting only if wanted.
    pub(crate) fn trace(&self, f: impl FnOnce() -> String) {
        if self.logger.wants(Status::Ok, LOG_ALL) {
            self.logger.log(Status::Ok, LOG_ALL, &f());
        }
    }

    /// Reports a failed call and moves to the error state for fmi2Error.
    pub(crate) fn fail(&mut self, function: &str, f: Fail) -> fmi2Status {
        self.logger
            .status(f.status, &format!("{function}: {}", f.message));
        match f.status {
            Status::Error if self.machine != M::Fatal => self.machine = M::Error,
            Status::Fatal => self.machine = M::Fatal,
            _ => {}
        }
        f.status.raw()
    }

    /// The call is allowed in the current state (the function name is
    /// prefixed to the message by `fail`).
    pub(crate) fn check_state(&self, _function: &str, states: &[Machine]) -> Res<()> {
        if states.contains(&self.machine) {
            Ok(())
        } else {
            let names: Vec<&str> = states.iter().map(|m| m.name()).collect();
            error(format!(
                "not allowed in state {} (only in {})",
                self.machine.name(),
                names.join(", ")
            ))
        }
    }

    fn lookup(&self, base: BaseType, vr: u32) -> Res<(usize, &'static Variable)> {
        match self.md.by_vr(base, vr) {
            Some(x) => Ok(x),
            None => error(format!("unknown {} value reference {vr}", base.as_str())),
        }
    }

    /// Builds the model if it is missing or the stored values changed.
    fn ensure_slave(&mut self) -> Res<()> {
        if self.slave.is_some() && !self.stale {
            return Ok(());
        }
        let values = Values {
            md: self.md,
            values: &self.values,
        };
        let setup = self.setup;
        let slave =
            guarded("the parameter check", || S::new(values, &setup)).map_err(|f| Fail {
                status: f.status,
                message: format!("invalid parameters: {}", f.message),
            })?;
        self.slave = Some(slave);
        self.stale = false;
        Ok(())
    }

    // ----- common functions -------------------------------------------------

    pub fn set_debug_logging(&mut self, on: bool, categories: &[String]) -> Res<Status> {
        let unknown = self.logger.set_debug_logging(on, categories);
        if unknown.is_empty() {
            Ok(Status::Ok)
        } else {
            let known: Vec<&str> = self.md.log_categories.iter().map(|c| c.name).collect();
            self.logger.status(
                Status::Warning,
                &format!(
                    "fmi2SetDebugLogging: unknown log categories {} ignored (known: {})",
                    unknown.join(", "),
                    known.join(", ")
                ),
            );
            Ok(Status::Warning)
        }
    }

    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> Res<Status> {
        self.check_state("fmi2SetupExperiment", allowed::INSTANTIATED)?;
        if let Some(t) = tolerance {
            if !(t.is_finite() && t > 0.0) {
                return error(format!("tolerance = {t}: must be finite and > 0"));
            }
        }
        if !start_time.is_finite() {
            return error(format!("startTime = {start_time}: must be finite"));
        }
        if let Some(s) = stop_time {
            if !(s.is_finite() && s >= start_time) {
                return error(format!(
                    "stopTime = {s}: must be finite and >= startTime = {start_time}"
                ));
            }
        }
        self.setup = Setup {
            tolerance,
            start_time,
            stop_time,
        };
        self.time = start_time;
        self.last_successful_time = start_time;
        self.stale = true;
        Ok(Status::Ok)
    }

    pub fn enter_initialization_mode(&mut self) -> Res<Status> {
        self.check_state("fmi2EnterInitializationMode", allowed::INSTANTIATED)?;
        self.machine = M::InitializationMode;
        Ok(Status::Ok)
    }

    pub fn exit_initialization_mode(&mut self) -> Res<Status> {
        self.check_state("fmi2ExitInitializationMode", allowed::INIT)?;
        self.stale = true;
        self.ensure_slave()?;
        self.time = self.setup.start_time;
        self.last_successful_time = self.time;
        self.terminated = false;
        self.machine = M::StepComplete;
        Ok(Status::Ok)
    }

    pub fn terminate(&mut self) -> Res<Status> {
        self.check_state("fmi2Terminate", allowed::TERMINATE)?;
        self.machine = M::Terminated;
        Ok(Status::Ok)
    }

    pub fn reset(&mut self) -> Res<Status> {
        self.check_state("fmi2Reset", allowed::ANY_BUT_FATAL)?;
        self.reset_values();
        self.machine = M::Instantiated;
        Ok(Status::Ok)
    }

    // ----- getting and setting ----------------------------------------------

    fn with_inputs<T>(
        &mut self,
        f: impl FnOnce(&mut S, Inputs<'_>) -> Result<T, String>,
        what: &str,
    ) -> Res<T> {
        self.ensure_slave()?;
        let inputs = Inputs {
            values: Values {
                md: self.md,
                values: &self.values,
            },
            derivatives: &self.derivatives,
        };
        let slave = self.slave.as_mut().expect("built above");
        guarded(what, || f(slave, inputs))
    }

    pub fn get_real(&mut self, vrs: &[u32], out: &mut [f64]) -> Res<Status> {
        self.check_state("fmi2GetReal", allowed::GET)?;
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(BaseType::Real, vr)?;
            out[k] = if from_store(v) {
                match &self.values[i] {
                    Some(Scalar::Real(x)) => *x,
                    _ => return error(format!("{} has no stored value", v.name)),
                }
            } else {
                self.with_inputs(|s, u| s.get_real(vr, u), v.name)
                    .map_err(|f| Fail {
                        status: f.status,
                        message: format!("cannot evaluate {}: {}", v.name, f.message),
                    })?
            };
        }
        Ok(Status::Ok)
    }

    pub fn get_integer(&mut self, vrs: &[u32], out: &mut [i32]) -> Res<Status> {
        self.check_state("fmi2GetInteger", allowed::GET)?;
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(BaseType::Integer, vr)?;
            out[k] = if from_store(v) {
                match &self.values[i] {
                    Some(Scalar::Integer(x)) => *x,
                    _ => return error(format!("{} has no stored value", v.name)),
                }
            } else {
                self.with_inputs(|s, u| s.get_integer(vr, u), v.name)
                    .map_err(|f| Fail {
                        status: f.status,
                        message: format!("cannot evaluate {}: {}", v.name, f.message),
                    })?
            };
        }
        Ok(Status::Ok)
    }

    pub fn get_boolean(&mut self, vrs: &[u32], out: &mut [fmi2Boolean]) -> Res<Status> {
        self.check_state("fmi2GetBoolean", allowed::GET)?;
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(BaseType::Boolean, vr)?;
            let b = if from_store(v) {
                match &self.values[i] {
                    Some(Scalar::Boolean(x)) => *x,
                    _ => return error(format!("{} has no stored value", v.name)),
                }
            } else {
                self.with_inputs(|s, u| s.get_boolean(vr, u), v.name)
                    .map_err(|f| Fail {
                        status: f.status,
                        message: format!("cannot evaluate {}: {}", v.name, f.message),
                    })?
            };
            out[k] = if b { fmi2True } else { fmi2False };
        }
        Ok(Status::Ok)
    }

    /// Pointers into the stored strings: valid until the next set or reset.
    pub fn get_string(&mut self, vrs: &[u32], out: &mut [fmi2String]) -> Res<Status> {
        self.check_state("fmi2GetString", allowed::GET)?;
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(BaseType::String, vr)?;
            match &self.values[i] {
                Some(Scalar::String(s)) => out[k] = s.as_ptr(),
                _ => return error(format!("{} has no stored value", v.name)),
            }
        }
        Ok(Status::Ok)
    }

    fn set(
        &mut self,
        function: &str,
        base: BaseType,
        vrs: &[u32],
        mut make: impl FnMut(usize, &Variable) -> Res<Scalar>,
    ) -> Res<Status> {
        self.check_state(function, allowed::SET)?;
        // Check everything first: a refused call changes nothing.
        let mut staged = Vec::with_capacity(vrs.len());
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(base, vr)?;
            if !settable(v, self.machine) {
                return error(format!(
                    "{} (causality {}, variability {}) cannot be set in state {}",
                    v.name,
                    v.causality.as_str(),
                    v.variability.as_str(),
                    self.machine.name()
                ));
            }
            staged.push((i, v, make(k, v)?));
        }
        for (i, v, s) in staged {
            self.trace(|| format!("{function}: {} = {s:?}", v.name));
            self.values[i] = Some(s);
            if v.causality == Causality::Input {
                // A new input value starts a new polynomial: its derivative
                // applies only if set again after the value.
                self.derivatives[i] = 0.0;
            } else {
                self.stale = true;
            }
        }
        Ok(Status::Ok)
    }

    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Res<Status> {
        self.set("fmi2SetReal", BaseType::Real, vrs, |k, v| {
            let x = values[k];
            if v.causality == Causality::Input && !x.is_finite() {
                return error(format!("{} = {x}: the input must be finite", v.name));
            }
            Ok(Scalar::Real(x))
        })
    }

    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Res<Status> {
        let md = self.md;
        self.set("fmi2SetInteger", BaseType::Integer, vrs, |k, v| {
            let x = values[k];
            if let Type::Enumeration { declared_type, .. } = v.ty {
                if let Some(t) = md.enum_type(declared_type) {
                    if t.item(x).is_none() {
                        let items: Vec<String> = t
                            .items
                            .iter()
                            .map(|i| format!("{} ({})", i.value, i.name))
                            .collect();
                        return error(format!(
                            "{} = {x}: not an item of {declared_type}: {}",
                            v.name,
                            items.join(", ")
                        ));
                    }
                }
            }
            Ok(Scalar::Integer(x))
        })
    }

    pub fn set_boolean(&mut self, vrs: &[u32], values: &[fmi2Boolean]) -> Res<Status> {
        self.set("fmi2SetBoolean", BaseType::Boolean, vrs, |k, _| {
            Ok(Scalar::Boolean(values[k] != fmi2False))
        })
    }

    pub fn set_string(&mut self, vrs: &[u32], values: &[Option<CString>]) -> Res<Status> {
        self.set(
            "fmi2SetString",
            BaseType::String,
            vrs,
            |k, v| match &values[k] {
                Some(s) => Ok(Scalar::String(s.clone())),
                None => error(format!("{}: NULL string", v.name)),
            },
        )
    }

    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> Res<Status> {
        self.check_state("fmi2SetRealInputDerivatives", allowed::SET)?;
        if !self.md.co_simulation.can_interpolate_inputs {
            return error("canInterpolateInputs is false");
        }
        let mut staged = Vec::new();
        let mut ignored = Vec::new();
        for (k, &vr) in vrs.iter().enumerate() {
            let (i, v) = self.lookup(BaseType::Real, vr)?;
            if v.causality != Causality::Input || v.variability != Variability::Continuous {
                return error(format!("{} is no continuous Real input", v.name));
            }
            let x = values[k];
            match orders[k] {
                1 => {
                    if !x.is_finite() {
                        return error(format!(
                            "derivative of {} = {x}: the input derivative must be finite",
                            v.name
                        ));
                    }
                    staged.push((i, v, x));
                }
                o if o >= 2 => ignored.push(format!("{} (order {o})", v.name)),
                o => return error(format!("{}: derivative order {o} must be >= 1", v.name)),
            }
        }
        for (i, v, x) in staged {
            self.trace(|| format!("fmi2SetRealInputDerivatives: d{}/dt = {x}", v.name));
            self.derivatives[i] = x;
        }
        if ignored.is_empty() {
            Ok(Status::Ok)
        } else {
            self.logger.status(
                Status::Warning,
                &format!(
                    "fmi2SetRealInputDerivatives: only first derivatives are used; ignored {}",
                    ignored.join(", ")
                ),
            );
            Ok(Status::Warning)
        }
    }

    pub fn get_real_output_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        out: &mut [f64],
    ) -> Res<Status> {
        self.check_state("fmi2GetRealOutputDerivatives", allowed::OUTPUT_DERIVATIVES)?;
        let max = self.md.co_simulation.max_output_derivative_order as i32;
        for (k, &vr) in vrs.iter().enumerate() {
            let (_, v) = self.lookup(BaseType::Real, vr)?;
            let o = orders[k];
            if v.causality != Causality::Output {
                return error(format!("{} is no output", v.name));
            }
            if o < 1 || o > max {
                return error(format!(
                    "{}: derivative order {o} outside 1..={max} (maxOutputDerivativeOrder)",
                    v.name
                ));
            }
            out[k] = self
                .with_inputs(|s, u| s.output_derivative(vr, o, u), v.name)
                .map_err(|f| Fail {
                    status: f.status,
                    message: format!("derivative of order {o} of {}: {}", v.name, f.message),
                })?;
        }
        Ok(Status::Ok)
    }

    // ----- stepping ---------------------------------------------------------

    /// Relative tolerance for comparing communication points.
    const TIME_RTOL: f64 = 1e-9;

    pub fn do_step(&mut self, t: f64, h: f64) -> Res<Status> {
        self.check_state("fmi2DoStep", allowed::DO_STEP)?;
        if !t.is_finite() || !h.is_finite() || h <= 0.0 {
            return error(format!(
                "currentCommunicationPoint = {t}, communicationStepSize = {h}: need finite values and a step > 0"
            ));
        }
        let scale = self.time.abs().max(h.abs()).max(1.0);
        if (t - self.time).abs() > Self::TIME_RTOL * scale {
            return error(format!(
                "currentCommunicationPoint = {t} does not match the FMU's time {} (the end of the last step)",
                self.time
            ));
        }
        let end = t + h;
        if let Some(stop) = self.setup.stop_time {
            if end > stop + Self::TIME_RTOL * scale {
                return error(format!(
                    "the step to {end} goes past stopTime = {stop} given to fmi2SetupExperiment"
                ));
            }
        }
        for (i, v) in self.md.variables.iter().enumerate() {
            if let (Causality::Input, Some(Scalar::Real(x))) = (v.causality, &self.values[i]) {
                let d = self.derivatives[i];
                let x_end = x + d * h;
                if !x_end.is_finite() {
                    return error(format!(
                        "{} = {x} + {d} * {h} = {x_end} at the end of the step: the input must be finite",
                        v.name
                    ));
                }
            }
        }
        self.ensure_slave()?;
        let events_on = self.logger.wants(Status::Ok, LOG_EVENTS);
        let mut log = EventLog::new(events_on);
        let inputs = Inputs {
            values: Values {
                md: self.md,
                values: &self.values,
            },
            derivatives: &self.derivatives,
        };
        let slave = self.slave.as_mut().expect("built above");
        let before = slave.state();
        let result = guarded("fmi2DoStep", || slave.do_step(t, h, inputs, &mut log));
        for m in &log.messages {
            self.logger.log(Status::Ok, LOG_EVENTS, m);
        }
        match result {
            Ok(StepEnd::Completed) => {
                self.time = end;
                self.last_successful_time = end;
                // The inputs continue along their polynomials.
                for i in 0..self.values.len() {
                    if let Some(Scalar::Real(x)) = &mut self.values[i] {
                        if self.derivatives[i] != 0.0 {
                            *x += self.derivatives[i] * h;
                        }
                    }
                }
                Ok(Status::Ok)
            }
            Ok(StepEnd::Terminated { time, reason }) => {
                let dt = time - t;
                for i in 0..self.values.len() {
                    if let Some(Scalar::Real(x)) = &mut self.values[i] {
                        if self.derivatives[i] != 0.0 {
                            *x += self.derivatives[i] * dt;
                        }
                    }
                }
                self.time = time;
                self.last_successful_time = time;
                self.terminated = true;
                self.machine = M::StepFailed;
                discard(format!(
                    "{reason}: the simulation ends at t = {time} (fmi2Terminated is true)"
                ))
            }
            Err(f) => {
                // Leave the model at the last good step.
                if let Some(s) = self.slave.as_mut() {
                    let restored = catch_unwind(AssertUnwindSafe(|| s.set_state(before)));
                    if restored.is_err() {
                        self.slave = None;
                        self.stale = true;
                    }
                }
                Err(Fail {
                    status: f.status,
                    message: format!("{} (the state stays at t = {})", f.message, self.time),
                })
            }
        }
    }

    pub fn cancel_step(&mut self) -> Res<Status> {
        error(format!(
            "no asynchronous step to cancel: fmi2DoStep never returns fmi2Pending (state {})",
            self.machine.name()
        ))
    }

    pub fn get_status(&mut self, kind: fmi2StatusKind) -> Res<fmi2Status> {
        self.check_state("fmi2GetStatus", allowed::STATUS)?;
        match kind {
            fmi2DoStepStatus => discard(
                "fmi2DoStepStatus is only available after fmi2Pending, which this FMU never returns",
            ),
            fmi2PendingStatus | fmi2LastSuccessfulTime | fmi2Terminated => {
                discard(format!("status kind {kind} is not an fmi2Status"))
            }
            _ => error(format!("unknown status kind {kind}")),
        }
    }

    pub fn get_real_status(&mut self, kind: fmi2StatusKind) -> Res<f64> {
        self.check_state("fmi2GetRealStatus", allowed::STATUS)?;
        match kind {
            fmi2LastSuccessfulTime => Ok(self.last_successful_time),
            fmi2DoStepStatus | fmi2PendingStatus | fmi2Terminated => {
                discard(format!("status kind {kind} is not a Real"))
            }
            _ => error(format!("unknown status kind {kind}")),
        }
    }

    pub fn get_integer_status(&mut self, kind: fmi2StatusKind) -> Res<i32> {
        self.check_state("fmi2GetIntegerStatus", allowed::STATUS)?;
        match kind {
            fmi2DoStepStatus | fmi2PendingStatus | fmi2LastSuccessfulTime | fmi2Terminated => {
                discard(format!("status kind {kind} is not an Integer"))
            }
            _ => error(format!("unknown status kind {kind}")),
        }
    }

    pub fn get_boolean_status(&mut self, kind: fmi2StatusKind) -> Res<bool> {
        self.check_state("fmi2GetBooleanStatus", allowed::STATUS)?;
        match kind {
            fmi2Terminated => Ok(self.terminated),
            fmi2DoStepStatus | fmi2PendingStatus | fmi2LastSuccessfulTime => {
                discard(format!("status kind {kind} is not a Boolean"))
            }
            _ => error(format!("unknown status kind {kind}")),
        }
    }

    pub fn get_string_status(&mut self, kind: fmi2StatusKind) -> Res<()> {
        self.check_state("fmi2GetStringStatus", allowed::STATUS)?;
        match kind {
            fmi2PendingStatus => discard("no asynchronous step is pending"),
            fmi2DoStepStatus | fmi2LastSuccessfulTime | fmi2Terminated => {
                discard(format!("status kind {kind} is not a String"))
            }
            _ => error(format!("unknown status kind {kind}")),
        }
    }

    // ----- FMU states -------------------------------------------------------

    fn snapshot(&self) -> Snapshot<S> {
        Snapshot {
            machine: self.machine,
            setup: self.setup,
            time: self.time,
            last_successful_time: self.last_successful_time,
            terminated: self.terminated,
            values: self.values.clone(),
            derivatives: self.derivatives.clone(),
            slave: match (&self.slave, self.stale) {
                (Some(s), false) => Some(s.state()),
                _ => None,
            },
        }
    }

    /// `fmi2GetFMUstate`: a new state, or `existing` (one of ours) overwritten.
    pub fn get_fmu_state(&mut self, existing: usize) -> Res<usize> {
        self.check_state("fmi2GetFMUstate", allowed::ANY_BUT_FATAL)?;
        let snap = self.snapshot();
        if existing != 0 {
            if !self.states.contains(&existing) {
                return error(format!(
                    "*FMUstate = {existing:#x} is not a live FMU state of this instance"
                ));
            }
            // SAFETY: the pointer is in our registry: we created it with
            // Box::into_raw and it has not been freed.
            unsafe { *(existing as *mut Snapshot<S>) = snap };
            return Ok(existing);
        }
        let p = Box::into_raw(Box::new(snap)) as usize;
        self.states.insert(p);
        Ok(p)
    }

    fn state_ref(&self, p: usize) -> Res<&Snapshot<S>> {
        if p == 0 || !self.states.contains(&p) {
            return error(format!(
                "FMUstate {p:#x} is not a live FMU state of this instance"
            ));
        }
        // SAFETY: registered pointers come from Box::into_raw and are live.
        Ok(unsafe { &*(p as *const Snapshot<S>) })
    }

    pub fn set_fmu_state(&mut self, p: usize) -> Res<Status> {
        self.check_state("fmi2SetFMUstate", allowed::ANY_BUT_FATAL)?;
        let snap = self.state_ref(p)?;
        let (machine, setup, time, lst, terminated, slave_state) = (
            snap.machine,
            snap.setup,
            snap.time,
            snap.last_successful_time,
            snap.terminated,
            snap.slave,
        );
        let (values, derivatives) = (snap.values.clone(), snap.derivatives.clone());
        let same_values = self.slave.is_some()
            && !self.stale
            && self.setup == setup
            && self.values.len() == values.len()
            && self.values.iter().zip(&values).all(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => a.same(b),
                (None, None) => true,
                _ => false,
            });
        self.values = values;
        self.derivatives = derivatives;
        self.setup = setup;
        self.time = time;
        self.last_successful_time = lst;
        self.terminated = terminated;
        match slave_state {
            Some(st) => {
                if !same_values {
                    self.stale = true;
                    self.ensure_slave()?;
                }
                let slave = self.slave.as_mut().expect("built above");
                guarded("fmi2SetFMUstate", || {
                    slave.set_state(st);
                    Ok(())
                })?;
            }
            None => {
                self.slave = None;
                self.stale = true;
            }
        }
        self.machine = machine;
        Ok(Status::Ok)
    }

    pub fn free_fmu_state(&mut self, p: usize) -> Res<Status> {
        self.check_state("fmi2FreeFMUstate", allowed::ANY_BUT_FATAL)?;
        if p == 0 {
            return Ok(Status::Ok);
        }
        self.state_ref(p)?;
        self.states.remove(&p);
        // SAFETY: registered, created by Box::into_raw, now unregistered.
        drop(unsafe { Box::from_raw(p as *mut Snapshot<S>) });
        Ok(Status::Ok)
    }

    fn serialize(&self, snap: &Snapshot<S>) -> Vec<u8> {
        let mut w = ByteWriter::new();
        w.u8(snap.machine.code());
        w.opt_f64(snap.setup.tolerance);
        w.f64(snap.setup.start_time);
        w.opt_f64(snap.setup.stop_time);
        w.f64(snap.time);
        w.f64(snap.last_successful_time);
        w.bool(snap.terminated);
        w.u32(snap.values.len() as u32);
        for v in &snap.values {
            match v {
                None => w.u8(0),
                Some(Scalar::Real(x)) => {
                    w.u8(1);
                    w.f64(*x);
                }
                Some(Scalar::Integer(x)) => {
                    w.u8(2);
                    w.i32(*x);
                }
                Some(Scalar::Boolean(x)) => {
                    w.u8(3);
                    w.bool(*x);
                }
                Some(Scalar::String(s)) => {
                    w.u8(4);
                    w.bytes(s.as_bytes());
                }
            }
        }
        w.u32(snap.derivatives.len() as u32);
        for d in &snap.derivatives {
            w.f64(*d);
        }
        match &snap.slave {
            None => w.u8(0),
            Some(s) => {
                w.u8(1);
                S::write_state(s, &mut w);
            }
        }
        bytes::seal(S::guid(), &w.buf)
    }

    fn deserialize(&self, buf: &[u8]) -> Result<Snapshot<S>, ReadError> {
        let payload = bytes::unseal(S::guid(), buf)?;
        let mut r = ByteReader::new(payload);
        let code = r.u8("machine state")?;
        let machine =
            Machine::from_code(code).ok_or_else(|| format!("invalid machine state {code}"))?;
        if machine == M::Fatal {
            return Err("a state cannot be in state fatal".into());
        }
        let tolerance = r.opt_f64("tolerance")?;
        let start_time = r.f64("start time")?;
        let stop_time = r.opt_f64("stop time")?;
        let time = r.f64("time")?;
        let last_successful_time = r.f64("last successful time")?;
        let terminated = r.bool("terminated")?;
        let n = r.u32("number of values")? as usize;
        if n != self.md.variables.len() {
            return Err(format!(
                "{n} values, the model has {} variables",
                self.md.variables.len()
            ));
        }
        let mut values = Vec::with_capacity(n);
        for v in self.md.variables {
            let tag = r.u8("value tag")?;
            let s = match tag {
                0 => None,
                1 => Some(Scalar::Real(r.f64(v.name)?)),
                2 => Some(Scalar::Integer(r.i32(v.name)?)),
                3 => Some(Scalar::Boolean(r.bool(v.name)?)),
                4 => Some(Scalar::String(
                    CString::new(r.bytes(v.name)?.to_vec())
                        .map_err(|_| format!("{}: NUL in string", v.name))?,
                )),
                t => return Err(format!("{}: invalid value tag {t}", v.name)),
            };
            let expected = start_value(v);
            let ok = match (&s, &expected) {
                (None, None) => true,
                (Some(a), Some(b)) => a.base() == b.base(),
                _ => false,
            };
            if !ok {
                return Err(format!("{}: value of the wrong kind", v.name));
            }
            if let (Some(Scalar::Integer(x)), Type::Enumeration { declared_type, .. }) = (&s, v.ty)
            {
                if self
                    .md
                    .enum_type(declared_type)
                    .is_some_and(|t| t.item(*x).is_none())
                {
                    return Err(format!("{} = {x}: not an item of {declared_type}", v.name));
                }
            }
            values.push(s);
        }
        let nd = r.u32("number of derivatives")? as usize;
        if nd != n {
            return Err(format!("{nd} input derivatives, expected {n}"));
        }
        let mut derivatives = Vec::with_capacity(nd);
        for _ in 0..nd {
            derivatives.push(r.f64("input derivative")?);
        }
        let slave = match r.u8("model state tag")? {
            0 => None,
            1 => Some(S::read_state(&mut r)?),
            t => return Err(format!("invalid model state tag {t}")),
        };
        r.finish("serialized FMU state")?;
        if slave.is_some() && machine == M::Instantiated {
            return Err("a model state in state instantiated".into());
        }
        Ok(Snapshot {
            machine,
            setup: Setup {
                tolerance,
                start_time,
                stop_time,
            },
            time,
            last_successful_time,
            terminated,
            values,
            derivatives,
            slave,
        })
    }

    pub fn serialized_size(&mut self, p: usize) -> Res<usize> {
        self.check_state("fmi2SerializedFMUstateSize", allowed::ANY_BUT_FATAL)?;
        let snap = self.state_ref(p)?;
        Ok(self.serialize(snap).len())
    }

    pub fn serialize_fmu_state(&mut self, p: usize, out: &mut [u8]) -> Res<Status> {
        self.check_state("fmi2SerializeFMUstate", allowed::ANY_BUT_FATAL)?;
        let snap = self.state_ref(p)?;
        let bytes = self.serialize(snap);
        if out.len() < bytes.len() {
            return error(format!(
                "size = {} is too small: the serialized state has {} bytes (fmi2SerializedFMUstateSize)",
                out.len(),
                bytes.len()
            ));
        }
        out[..bytes.len()].copy_from_slice(&bytes);
        out[bytes.len()..].fill(0);
        Ok(Status::Ok)
    }

    /// `fmi2DeSerializeFMUstate`: checks the buffer, returns a new state.
    pub fn deserialize_fmu_state(&mut self, buf: &[u8]) -> Res<usize> {
        self.check_state("fmi2DeSerializeFMUstate", allowed::ANY_BUT_FATAL)?;
        // A buffer may carry trailing zero padding from fmi2SerializeFMUstate
        // with a larger size: the envelope's length field tells the real end.
        let snap = match self.deserialize(buf) {
            Ok(s) => s,
            Err(first) => match trim_padding(buf) {
                Some(t) if t.len() < buf.len() => self.deserialize(t).map_err(|_| first),
                _ => Err(first),
            }
            .or_else(|e| error(format!("refused: {e}")))?,
        };
        let p = Box::into_raw(Box::new(snap)) as usize;
        self.states.insert(p);
        Ok(p)
    }

    /// Frees every FMU state still alive (at fmi2FreeInstance).
    pub(crate) fn free_all_states(&mut self) {
        for p in std::mem::take(&mut self.states) {
            // SAFETY: registered pointers are live boxes created by us.
            drop(unsafe { Box::from_raw(p as *mut Snapshot<S>) });
        }
    }

    pub(crate) fn log_status_warning(&self, message: &str) {
        self.logger
            .log(Status::Warning, LOG_STATUS_WARNING, message);
    }
}

/// The envelope's own length, if the buffer is longer and the rest is zero
/// padding (anything else after the envelope is refused).
fn trim_padding(buf: &[u8]) -> Option<&[u8]> {
    let mut r = ByteReader::new(buf);
    r.u64("magic").ok()?;
    r.u32("version").ok()?;
    let g = r.bytes("guid").ok()?.len();
    let n = r.u64("length").ok()? as usize;
    let total = 8usize
        .checked_add(4)?
        .checked_add(4)?
        .checked_add(g)?
        .checked_add(8)?
        .checked_add(n)?
        .checked_add(4)?;
    let (envelope, rest) = buf.split_at_checked(total)?;
    rest.iter().all(|&b| b == 0).then_some(envelope)
}

impl<S: Slave> Drop for Inner<S> {
    fn drop(&mut self) {
        self.free_all_states();
    }
}
