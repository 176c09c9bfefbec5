//! FMI 2.0 Model Exchange (FMI 2.0 §3): the host integrates the model's
//! continuous states with its own solver; this layer keeps the ME state
//! machine (instantiated, initializationMode, eventMode, continuousTimeMode,
//! terminated, error, fatal; the masks are in [`machine`](crate::machine)),
//! checks sizes and values, and calls the model only through the Model
//! Exchange methods of [`Slave`].

use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::fail::{error, guarded, Res};
use crate::instance::Inner;
use crate::logging::LOG_EVENTS;
use crate::machine::{mask, Machine as M, Mask};
use crate::slave::{EventLog, Inputs, Slave, Values};
use crate::types::*;

/// `fmi2EventInfo` as the layer fills it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EventInfo {
    pub terminate_simulation: bool,
    pub values_of_continuous_states_changed: bool,
}

impl<S: Slave> Inner<S> {
    /// Number of continuous states: the variables with a `derivative` attribute.
    pub fn continuous_state_count(&self) -> usize {
        self.md
            .variables
            .iter()
            .filter(|v| v.derivative.is_some())
            .count()
    }

    /// Number of event indicators of the model description.
    pub fn event_indicator_count(&self) -> usize {
        self.md
            .model_exchange
            .map_or(0, |m| m.event_indicators as usize)
    }

    fn check_me(&self, allowed: Mask) -> Res<()> {
        if !self.model_exchange {
            return error("only for an instance of fmuType fmi2ModelExchange");
        }
        self.check_state(allowed)
    }

    fn check_len(&self, what: &str, n: usize, expected: usize) -> Res<()> {
        if n == expected {
            Ok(())
        } else {
            error(format!("{what} = {n}: this model has {expected}"))
        }
    }

    /// Runs `f` on the built model with the inputs at the current time.
    fn me_call<T>(
        &mut self,
        what: &str,
        f: impl FnOnce(&mut S, Inputs<'_>, &mut EventLog) -> Result<T, String>,
    ) -> Res<T> {
        self.me_call_status(what, f).map(|(x, _)| x)
    }

    /// [`me_call`](Self::me_call), with `Status::Warning` if the model
    /// warned during the call.
    fn me_call_status<T>(
        &mut self,
        what: &str,
        f: impl FnOnce(&mut S, Inputs<'_>, &mut EventLog) -> Result<T, String>,
    ) -> Res<(T, Status)> {
        self.ensure_slave()?;
        let mut log = EventLog::new(self.logger.wants(Status::Ok, LOG_EVENTS));
        let inputs = Inputs {
            values: Values {
                md: self.md,
                values: &self.values,
            },
            derivatives: &self.derivatives,
        };
        let slave = self.slave.as_mut().expect("built above");
        let before = slave.state();
        let r = guarded(what, || f(slave, inputs, &mut log));
        let status = self.flush(&log);
        if r.is_err() {
            if let Some(s) = self.slave.as_mut() {
                if catch_unwind(AssertUnwindSafe(|| s.set_state(before))).is_err() {
                    self.slave = None;
                    self.stale = true;
                }
            }
        }
        r.map(|x| (x, status))
    }

    pub fn set_time(&mut self, t: f64) -> Res<Status> {
        self.check_me(mask::fmi2SetTime)?;
        if !t.is_finite() {
            return error(format!("time = {t}: must be finite"));
        }
        self.me_call("fmi2SetTime", |s, _, _| s.set_time(t))?;
        self.time = t;
        Ok(Status::Ok)
    }

    pub fn set_continuous_states(&mut self, x: &[f64]) -> Res<Status> {
        self.check_me(mask::fmi2SetContinuousStates)?;
        self.check_len("nx", x.len(), self.continuous_state_count())?;
        if let Some((i, v)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return error(format!("x[{i}] = {v}: the states must be finite"));
        }
        self.me_call("fmi2SetContinuousStates", |s, _, _| {
            s.set_continuous_states(x)
        })?;
        Ok(Status::Ok)
    }

    pub fn get_continuous_states(&mut self, x: &mut [f64]) -> Res<Status> {
        self.check_me(mask::fmi2GetContinuousStates)?;
        self.check_len("nx", x.len(), self.continuous_state_count())?;
        self.me_call("fmi2GetContinuousStates", |s, _, _| s.continuous_states(x))?;
        Ok(Status::Ok)
    }

    pub fn get_nominals_of_continuous_states(&mut self, x: &mut [f64]) -> Res<Status> {
        self.check_me(mask::fmi2GetNominalsOfContinuousStates)?;
        self.check_len("nx", x.len(), self.continuous_state_count())?;
        if self.machine == M::Instantiated {
            // the parameters may still change: the default nominal
            x.fill(1.0);
            return Ok(Status::Ok);
        }
        self.me_call("fmi2GetNominalsOfContinuousStates", |s, _, _| s.nominals(x))?;
        Ok(Status::Ok)
    }

    pub fn get_derivatives(&mut self, dx: &mut [f64]) -> Res<Status> {
        self.check_me(mask::fmi2GetDerivatives)?;
        self.check_len("nx", dx.len(), self.continuous_state_count())?;
        self.me_call("fmi2GetDerivatives", |s, i, _| s.derivatives(i, dx))?;
        Ok(Status::Ok)
    }

    /// The event indicators read as variables (FMI 3.0 lists them among the
    /// model's variables, which a host may read in a co-simulation instance
    /// too, e.g. to record every `Float64`): the model's indicators at the
    /// current state and inputs, in any interface.
    pub fn event_indicators_as_variables(&mut self, z: &mut [f64]) -> Res<Status> {
        self.indicators("eventIndicator", z)
    }

    pub fn get_event_indicators(&mut self, z: &mut [f64]) -> Res<Status> {
        self.check_me(mask::fmi2GetEventIndicators)?;
        self.indicators("fmi2GetEventIndicators", z)
    }

    fn indicators(&mut self, what: &str, z: &mut [f64]) -> Res<Status> {
        self.check_len("ni", z.len(), self.event_indicator_count())?;
        self.me_call(what, |s, i, _| s.event_indicators(i, z))?;
        Ok(Status::Ok)
    }

    pub fn enter_event_mode(&mut self) -> Res<Status> {
        self.check_me(mask::fmi2EnterEventMode)?;
        self.machine = M::EventMode;
        Ok(Status::Ok)
    }

    pub fn new_discrete_states(&mut self) -> Res<(Status, EventInfo)> {
        self.check_me(mask::fmi2NewDiscreteStates)?;
        if self.terminated {
            return Ok((
                Status::Ok,
                EventInfo {
                    terminate_simulation: true,
                    ..EventInfo::default()
                },
            ));
        }
        let u = self.me_call("fmi2NewDiscreteStates", |s, i, log| s.event_update(i, log))?;
        if let Some(reason) = &u.terminate {
            self.terminated = true;
            self.logger.log(
                Status::Ok,
                LOG_EVENTS,
                &format!("{reason}: terminateSimulation at t = {}", self.time),
            );
        }
        Ok((
            Status::Ok,
            EventInfo {
                terminate_simulation: u.terminate.is_some(),
                values_of_continuous_states_changed: u.states_changed,
            },
        ))
    }

    pub fn enter_continuous_time_mode(&mut self) -> Res<Status> {
        self.check_me(mask::fmi2EnterContinuousTimeMode)?;
        self.machine = M::ContinuousTimeMode;
        Ok(Status::Ok)
    }

    /// Returns `(enterEventMode, terminateSimulation)`.
    pub fn completed_integrator_step(&mut self) -> Res<(Status, bool, bool)> {
        self.check_me(mask::fmi2CompletedIntegratorStep)?;
        let (enter, status) = self.me_call_status("fmi2CompletedIntegratorStep", |s, i, log| {
            s.completed_integrator_step(i, log)
        })?;
        Ok((status, enter, self.terminated))
    }
}
