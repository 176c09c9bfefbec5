//! What a model implements to become an FMI 2.0 co-simulation slave.
//!
//! The generic layer keeps the values the master sets (parameters, inputs,
//! start values, input derivatives), enforces the state machine, logs, saves
//! and serializes states, and calls the model only through [`Slave`].

use std::ffi::CString;

use model_description::{BaseType, ModelDescription};

use crate::bytes::{ByteReader, ByteWriter, ReadError};

/// One stored value (of a variable the master can set).
#[derive(Clone, Debug)]
pub enum Scalar {
    Real(f64),
    Integer(i32),
    Boolean(bool),
    String(CString),
}

/// As a log message shows a value: `2e8`, `3`, `true`, `"text"`.
impl std::fmt::Display for Scalar {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Scalar::Real(x) => write!(f, "{x}"),
            Scalar::Integer(n) => write!(f, "{n}"),
            Scalar::Boolean(b) => write!(f, "{b}"),
            Scalar::String(s) => write!(f, "{:?}", s.to_string_lossy()),
        }
    }
}

impl Scalar {
    pub fn base(&self) -> BaseType {
        match self {
            Scalar::Real(_) => BaseType::Real,
            Scalar::Integer(_) => BaseType::Integer,
            Scalar::Boolean(_) => BaseType::Boolean,
            Scalar::String(_) => BaseType::String,
        }
    }

    /// Bit-exact equality (NaN equals itself).
    pub fn same(&self, other: &Scalar) -> bool {
        match (self, other) {
            (Scalar::Real(a), Scalar::Real(b)) => a.to_bits() == b.to_bits(),
            (Scalar::Integer(a), Scalar::Integer(b)) => a == b,
            (Scalar::Boolean(a), Scalar::Boolean(b)) => a == b,
            (Scalar::String(a), Scalar::String(b)) => a == b,
            _ => false,
        }
    }
}

/// Read access to the stored values, by value reference.
#[derive(Clone, Copy)]
pub struct Values<'a> {
    pub(crate) md: &'static ModelDescription,
    pub(crate) values: &'a [Option<Scalar>],
}

impl<'a> Values<'a> {
    fn get(&self, base: BaseType, vr: u32) -> &'a Scalar {
        let (i, v) = self
            .md
            .by_vr(base, vr)
            .unwrap_or_else(|| panic!("no {} variable with value reference {vr}", base.as_str()));
        self.values[i]
            .as_ref()
            .unwrap_or_else(|| panic!("{} is not a stored variable", v.name))
    }

    /// The stored Real `vr` (a parameter, an input or a start value).
    pub fn real(&self, vr: u32) -> f64 {
        match self.get(BaseType::Real, vr) {
            Scalar::Real(x) => *x,
            _ => unreachable!(),
        }
    }

    /// The stored Integer or Enumeration `vr`.
    pub fn integer(&self, vr: u32) -> i32 {
        match self.get(BaseType::Integer, vr) {
            Scalar::Integer(x) => *x,
            _ => unreachable!(),
        }
    }

    pub fn boolean(&self, vr: u32) -> bool {
        match self.get(BaseType::Boolean, vr) {
            Scalar::Boolean(x) => *x,
            _ => unreachable!(),
        }
    }
}

/// The inputs during a step or an evaluation: values and first derivatives.
#[derive(Clone, Copy)]
pub struct Inputs<'a> {
    pub values: Values<'a>,
    pub(crate) derivatives: &'a [f64],
}

impl<'a> Inputs<'a> {
    /// Value of the Real input `vr` at the start of the step (or now).
    pub fn real(&self, vr: u32) -> f64 {
        self.values.real(vr)
    }

    /// First time derivative of the Real input `vr` (0 unless the master set it).
    pub fn derivative(&self, vr: u32) -> f64 {
        let (i, _) = self
            .values
            .md
            .by_vr(BaseType::Real, vr)
            .unwrap_or_else(|| panic!("no Real variable with value reference {vr}"));
        self.derivatives[i]
    }

    /// The Real input `vr` (called `name` in messages, in `unit`) over a
    /// step of `h` s as `(x, dx/dt)`, checked: finite, and `|x| <= max_abs`
    /// at both ends of the step. A model bounds its inputs where its
    /// arithmetic would overflow; the message names the input and the bound.
    pub fn line(
        &self,
        vr: u32,
        name: &str,
        unit: &str,
        h: f64,
        max_abs: f64,
    ) -> Result<(f64, f64), String> {
        let (x, dx) = (self.real(vr), self.derivative(vr));
        if !(x.is_finite() && dx.is_finite()) {
            return Err(format!(
                "{name} = {x}, d{name}/dt = {dx}: the input must be finite"
            ));
        }
        let x_end = x + dx * h;
        if x.abs().max(x_end.abs()) > max_abs {
            return Err(format!(
                "{name} = {x} at the start of the step, {x_end} at its end: |{name}| must be <= {max_abs:e} {unit}"
            ));
        }
        Ok((x, dx))
    }
}

/// Experiment settings from `fmi2SetupExperiment`, and the interface the
/// instance was created for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setup {
    /// Relative tolerance, if the master defined one.
    pub tolerance: Option<f64>,
    pub start_time: f64,
    pub stop_time: Option<f64>,
    /// The instance is of fmuType fmi2ModelExchange (the host's solver
    /// integrates the continuous states).
    pub model_exchange: bool,
}

/// Messages a slave reports during a call: events (category `logEvents`,
/// formatted only when someone listens) and warnings (status
/// `fmi2Warning`, category `logStatusWarning`, always logged; the call then
/// returns `fmi2Warning`).
pub struct EventLog {
    enabled: bool,
    pub(crate) messages: Vec<String>,
    pub(crate) warnings: Vec<String>,
}

impl EventLog {
    pub(crate) fn new(enabled: bool) -> EventLog {
        EventLog {
            enabled,
            messages: Vec::new(),
            warnings: Vec::new(),
        }
    }

    /// Something is not quite right but the computation goes on: the
    /// message is logged with `fmi2Warning` and the call returns
    /// `fmi2Warning`.
    pub fn warn(&mut self, message: impl Into<String>) {
        self.warnings.push(message.into());
    }

    /// Whether anyone listens (to skip formatting otherwise).
    pub fn enabled(&self) -> bool {
        self.enabled
    }

    pub fn event(&mut self, message: impl Into<String>) {
        if self.enabled {
            self.messages.push(message.into());
        }
    }
}

/// How a step ended.
#[derive(Clone, Debug, PartialEq)]
pub enum StepEnd {
    /// The step reached `t + h`.
    Completed,
    /// The model ended the run at `time` (within the step): `fmi2DoStep`
    /// returns `fmi2Discard`, `fmi2LastSuccessfulTime` is `time` and
    /// `fmi2Terminated` is true.
    Terminated { time: f64, reason: String },
    /// The model stopped at `time` (within the step) without ending the run,
    /// for a reason the host can act on (a work limit): `fmi2DoStep` returns
    /// `fmi2Discard`, `fmi2LastSuccessfulTime` is `time`, `fmi2Terminated`
    /// is false, and the state is the model's at `time`. The host goes on
    /// from a state it saved (`fmi2SetFMUstate`) with smaller steps.
    Stopped { time: f64, reason: String },
    /// Only from [`Slave::do_step_to_event`]: the model stopped at an event
    /// (an impact, an uplift...) at `time`, before `t + h` or at it; the
    /// state is the one just after the event. FMI 3.0's early return (at
    /// `t + h`: the step completes, and the event is still reported).
    Event { time: f64 },
}

/// What a Model Exchange event update did (`fmi2NewDiscreteStates`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Update {
    /// The continuous states changed (the host must re-read them).
    pub states_changed: bool,
    /// The model ends the run, and why (`terminateSimulation`).
    pub terminate: Option<String>,
}

/// The answer of a model without Model Exchange.
fn no_model_exchange<T>() -> Result<T, String> {
    Err("this model has no Model Exchange interface".into())
}

/// A model as an FMI 2.0 co-simulation slave (and, if its description has
/// `<ModelExchange>`, a Model Exchange model: the methods after
/// `read_state`, whose sizes the layer has checked against the description:
/// `nx` states, the variables with a `derivative` attribute in order, and
/// `numberOfEventIndicators` indicators).
///
/// Every method may return `Err(message)`: the FMI function then returns
/// `fmi2Error` with the message through the logger. A panic is caught and
/// reported the same way; the model's state is restored from before the call.
pub trait Slave: Sized + Send + 'static {
    /// Everything that determines the future of a run: saved, restored and
    /// serialized bit for bit.
    type State: Copy + Send + 'static;

    /// The model's variables (value references, causality, start values...).
    fn description() -> &'static ModelDescription;

    /// The GUID of the `modelDescription.xml` the binary was built with.
    fn guid() -> &'static str;

    /// Builds the model from the parameters and start values; `Err` names the
    /// offending variable and the violated condition.
    fn new(values: Values<'_>, setup: &Setup) -> Result<Self, String>;

    /// A Real output, local or calculated parameter at the current state.
    fn get_real(&mut self, vr: u32, inputs: Inputs<'_>) -> Result<f64, String>;

    /// An Integer output, local or calculated parameter.
    fn get_integer(&mut self, vr: u32, _inputs: Inputs<'_>) -> Result<i32, String> {
        Err(format!("no computed Integer with value reference {vr}"))
    }

    /// A Boolean output, local or calculated parameter.
    fn get_boolean(&mut self, vr: u32, _inputs: Inputs<'_>) -> Result<bool, String> {
        Err(format!("no computed Boolean with value reference {vr}"))
    }

    /// The `order`-th time derivative of the Real output `vr`.
    fn output_derivative(&mut self, vr: u32, order: i32, inputs: Inputs<'_>)
        -> Result<f64, String>;

    /// Advances from `t` to `t + h`, the inputs being `value + derivative * (s - t)`.
    fn do_step(
        &mut self,
        t: f64,
        h: f64,
        inputs: Inputs<'_>,
        log: &mut EventLog,
    ) -> Result<StepEnd, String>;

    /// Like [`do_step`](Self::do_step), but may stop at the first event
    /// inside the step ([`StepEnd::Event`]): FMI 3.0's early return. A model
    /// without events keeps this default.
    fn do_step_to_event(
        &mut self,
        t: f64,
        h: f64,
        inputs: Inputs<'_>,
        log: &mut EventLog,
    ) -> Result<StepEnd, String> {
        self.do_step(t, h, inputs, log)
    }

    fn state(&self) -> Self::State;
    fn set_state(&mut self, state: Self::State);
    fn write_state(state: &Self::State, w: &mut ByteWriter);
    /// Reads a state back; must check every field it can.
    fn read_state(r: &mut ByteReader<'_>) -> Result<Self::State, ReadError>;

    /// Model Exchange: the host's time (`fmi2SetTime`), s.
    fn set_time(&mut self, _t: f64) -> Result<(), String> {
        no_model_exchange()
    }

    /// Model Exchange: the continuous states into `x`.
    fn continuous_states(&self, _x: &mut [f64]) -> Result<(), String> {
        no_model_exchange()
    }

    /// Model Exchange: the host's continuous states (finite, checked).
    fn set_continuous_states(&mut self, _x: &[f64]) -> Result<(), String> {
        no_model_exchange()
    }

    /// Model Exchange: the state derivatives at the current time, states and inputs.
    fn derivatives(&mut self, _inputs: Inputs<'_>, _dx: &mut [f64]) -> Result<(), String> {
        no_model_exchange()
    }

    /// Model Exchange: the event indicators.
    fn event_indicators(&mut self, _inputs: Inputs<'_>, _z: &mut [f64]) -> Result<(), String> {
        no_model_exchange()
    }

    /// Model Exchange: the event update at the current time (`fmi2NewDiscreteStates`).
    fn event_update(&mut self, _inputs: Inputs<'_>, _log: &mut EventLog) -> Result<Update, String> {
        no_model_exchange()
    }

    /// Model Exchange: after an accepted integrator step; `true` asks the
    /// host to enter event mode (`enterEventMode`).
    fn completed_integrator_step(
        &mut self,
        _inputs: Inputs<'_>,
        _log: &mut EventLog,
    ) -> Result<bool, String> {
        no_model_exchange()
    }

    /// Model Exchange: nominal values of the continuous states.
    fn nominals(&self, _x: &mut [f64]) -> Result<(), String> {
        no_model_exchange()
    }
}
