//! One FMU instance as the host sees it (`fmi2Component`): the stored
//! values, the model, its life cycle (setup, initialization, terminate,
//! reset). Getting and setting values is in `values`, stepping and status
//! in `step`, FMU states in `fmu_state`; `ffi` turns the C calls into these.

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::Mutex;

use model_description::{BaseType, ModelDescription, Variable};

use crate::fail::{error, guarded, Fail, Res};
use crate::logging::{Logger, LOG_ALL, LOG_EVENTS, LOG_STATUS_WARNING};
use crate::machine::{mask, Machine, Mask};
use crate::slave::{EventLog, Inputs, Scalar, Setup, Slave, Values};
use crate::types::*;
use crate::values::start_value;

use Machine as M;

/// An instance as the host sees it (`fmi2Component`).
#[repr(C)]
pub struct Instance<S: Slave> {
    pub magic: u64,
    pub guid: &'static str,
    pub inner: Mutex<Inner<S>>,
}

pub const INSTANCE_MAGIC: u64 = u64::from_le_bytes(*b"FMI2INST");

pub struct Inner<S: Slave> {
    pub md: &'static ModelDescription,
    pub logger: Logger,
    pub machine: Machine,
    pub values: Vec<Option<Scalar>>,
    pub derivatives: Vec<f64>,
    pub setup: Setup,
    pub time: f64,
    pub last_successful_time: f64,
    pub terminated: bool,
    pub slave: Option<S>,
    /// The stored values changed since `slave` was built.
    pub stale: bool,
    /// The instance is of fmuType fmi2ModelExchange.
    pub model_exchange: bool,
    /// Live `fmi2FMUstate` pointers handed out by this instance: a membership
    /// registry, ordered rather than hashed, so that the FMU never asks the OS
    /// for random hasher keys (std's `HashSet` seeds its `RandomState` so).
    pub states: BTreeSet<usize>,
    pub resource_dir: Option<PathBuf>,
    /// FMI 3.0 co-simulation: the host uses event mode (`eventModeUsed`).
    pub event_mode_used: bool,
    /// FMI 3.0 co-simulation: `fmi3DoStep` may stop at an event
    /// (`earlyReturnAllowed`).
    pub early_return_allowed: bool,
}

// SAFETY: the raw pointers in `Logger` (host environment and callback) are
// only passed back to the host; FMI allows an instance to be used from any
// thread as long as calls on it do not overlap, and the `Mutex` around
// `Inner` serialises them anyway.
unsafe impl<S: Slave> Send for Inner<S> {}

impl<S: Slave> Inner<S> {
    pub fn new(logger: Logger, resource_dir: Option<PathBuf>, model_exchange: bool) -> Inner<S> {
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
                model_exchange,
            },
            time: 0.0,
            last_successful_time: 0.0,
            terminated: false,
            slave: None,
            stale: true,
            model_exchange,
            states: BTreeSet::new(),
            resource_dir,
            event_mode_used: false,
            early_return_allowed: false,
        };
        inner.reset_values();
        inner
    }

    pub fn reset_values(&mut self) {
        self.values = self.md.variables.iter().map(start_value).collect();
        self.derivatives = vec![0.0; self.md.variables.len()];
        self.setup = Setup {
            tolerance: None,
            start_time: 0.0,
            stop_time: None,
            model_exchange: self.model_exchange,
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
    pub fn trace(&self, f: impl FnOnce() -> String) {
        if self.logger.wants(Status::Ok, LOG_ALL) {
            self.logger.log(Status::Ok, LOG_ALL, &f());
        }
    }

    /// Reports a failed call and moves to the error state for fmi2Error.
    pub fn fail(&mut self, function: &str, f: Fail) -> fmi2Status {
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
    pub fn check_state(&self, allowed: Mask) -> Res<()> {
        if allowed.contains(self.machine) {
            Ok(())
        } else {
            let names: Vec<&str> = allowed.states().map(|m| m.name()).collect();
            error(format!(
                "not allowed in state {} (only in {})",
                self.machine.name(),
                names.join(", ")
            ))
        }
    }

    pub fn lookup(&self, base: BaseType, vr: u32) -> Res<(usize, &'static Variable)> {
        match self.md.by_vr(base, vr) {
            Some(x) => Ok(x),
            None => error(format!("unknown {} value reference {vr}", base.as_str())),
        }
    }

    /// Builds the model if it is missing or the stored values changed.
    pub fn ensure_slave(&mut self) -> Res<()> {
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

    /// The model (built if needed) and the inputs it sees.
    pub fn slave_and_inputs(&mut self) -> Res<(&mut S, Inputs<'_>)> {
        self.ensure_slave()?;
        let inputs = Inputs {
            values: Values {
                md: self.md,
                values: &self.values,
            },
            derivatives: &self.derivatives,
        };
        Ok((self.slave.as_mut().expect("built above"), inputs))
    }

    /// Evaluates `f` on the model, a panic becoming an error about `what`.
    pub fn with_inputs<T>(
        &mut self,
        f: impl FnOnce(&mut S, Inputs<'_>) -> Result<T, String>,
        what: &str,
    ) -> Res<T> {
        let (slave, inputs) = self.slave_and_inputs()?;
        guarded(what, || f(slave, inputs))
    }

    // ----- life cycle -------------------------------------------------------

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
        self.check_state(mask::fmi2SetupExperiment)?;
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
            model_exchange: self.model_exchange,
        };
        self.time = start_time;
        self.last_successful_time = start_time;
        self.stale = true;
        Ok(Status::Ok)
    }

    pub fn enter_initialization_mode(&mut self) -> Res<Status> {
        self.check_state(mask::fmi2EnterInitializationMode)?;
        self.machine = M::InitializationMode;
        Ok(Status::Ok)
    }

    pub fn exit_initialization_mode(&mut self) -> Res<Status> {
        self.check_state(mask::fmi2ExitInitializationMode)?;
        self.stale = true;
        self.ensure_slave()?;
        self.time = self.setup.start_time;
        self.last_successful_time = self.time;
        self.terminated = false;
        self.machine = if self.model_exchange {
            M::EventMode
        } else {
            M::StepComplete
        };
        Ok(Status::Ok)
    }

    pub fn terminate(&mut self) -> Res<Status> {
        self.check_state(mask::fmi2Terminate)?;
        self.machine = M::Terminated;
        Ok(Status::Ok)
    }

    pub fn reset(&mut self) -> Res<Status> {
        self.check_state(mask::fmi2Reset)?;
        self.reset_values();
        self.machine = M::Instantiated;
        Ok(Status::Ok)
    }

    pub fn log_status_warning(&self, message: &str) {
        self.logger
            .log(Status::Warning, LOG_STATUS_WARNING, message);
    }

    /// Logs what a slave reported during a call: its events, then its
    /// warnings; `Status::Warning` if it warned, else `Status::Ok`.
    pub fn flush(&self, log: &EventLog) -> Status {
        for m in &log.messages {
            self.logger.log(Status::Ok, LOG_EVENTS, m);
        }
        for m in &log.warnings {
            self.log_status_warning(m);
        }
        if log.warnings.is_empty() {
            Status::Ok
        } else {
            Status::Warning
        }
    }
}

impl<S: Slave> Drop for Inner<S> {
    fn drop(&mut self) {
        self.free_all_states();
    }
}
