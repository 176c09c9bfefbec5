//! `fmi2DoStep` and the status functions of co-simulation.

#![allow(non_upper_case_globals)] // the FMI constants keep their C names

use std::panic::{catch_unwind, AssertUnwindSafe};

use model_description::Causality;

use crate::fail::{discard, error, guarded, Fail, Res};
use crate::instance::Inner;
use crate::logging::LOG_EVENTS;
use crate::machine::{mask, Machine};
use crate::slave::{EventLog, Scalar, Slave, StepEnd};
use crate::types::*;

use Machine as M;

impl<S: Slave> Inner<S> {
    /// Relative tolerance for comparing communication points.
    const TIME_RTOL: f64 = 1e-9;

    pub fn do_step(&mut self, t: f64, h: f64) -> Res<Status> {
        self.step(t, h, false).map(|(s, _)| s)
    }

    /// `do_step` that may stop at the model's first event in the step (FMI
    /// 3.0's early return): `true` with the status if it did, the FMU's time
    /// then being the event's.
    pub fn do_step_to_event(&mut self, t: f64, h: f64) -> Res<(Status, bool)> {
        self.step(t, h, true)
    }

    fn step(&mut self, t: f64, h: f64, to_event: bool) -> Res<(Status, bool)> {
        self.check_state(mask::fmi2DoStep)?;
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
        let events_on = self.logger.wants(Status::Ok, LOG_EVENTS);
        let mut log = EventLog::new(events_on);
        let (slave, inputs) = self.slave_and_inputs()?;
        let before = slave.state();
        let result = guarded("fmi2DoStep", || {
            if to_event {
                slave.do_step_to_event(t, h, inputs, &mut log)
            } else {
                slave.do_step(t, h, inputs, &mut log)
            }
        });
        let status = self.flush(&log);
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
                Ok((status, false))
            }
            Ok(StepEnd::Event { time }) => {
                self.stop_within_step(t, time, false);
                self.machine = M::StepComplete;
                Ok((status, true))
            }
            Ok(StepEnd::Terminated { time, reason }) => {
                self.stop_within_step(t, time, true);
                discard(format!(
                    "{reason}: the simulation ends at t = {time} (fmi2Terminated is true)"
                ))
            }
            Ok(StepEnd::Stopped { time, reason }) => {
                self.stop_within_step(t, time, false);
                discard(format!(
                    "{reason}: the step stopped at t = {time} (fmi2LastSuccessfulTime; fmi2Terminated is false); \
                     restore a state saved before the step (fmi2SetFMUstate) and go on with smaller steps"
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

    /// The model stopped at `time` inside the step from `t`: the inputs
    /// follow their polynomials to `time`, the FMU's time is `time`, and the
    /// state machine is in `stepFailed`.
    fn stop_within_step(&mut self, t: f64, time: f64, terminated: bool) {
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
        self.terminated = terminated;
        self.machine = M::StepFailed;
    }

    pub fn cancel_step(&mut self) -> Res<Status> {
        error(format!(
            "no asynchronous step to cancel: fmi2DoStep never returns fmi2Pending (state {})",
            self.machine.name()
        ))
    }

    pub fn get_status(&mut self, kind: fmi2StatusKind) -> Res<fmi2Status> {
        self.check_state(mask::fmi2GetStatus)?;
        match kind {
            fmi2DoStepStatus => discard(
                "fmi2DoStepStatus is only available after fmi2Pending, which this FMU never returns",
            ),
            _ => other_kind(kind, "an fmi2Status"),
        }
    }

    pub fn get_real_status(&mut self, kind: fmi2StatusKind) -> Res<f64> {
        self.check_state(mask::fmi2GetRealStatus)?;
        match kind {
            fmi2LastSuccessfulTime => Ok(self.last_successful_time),
            _ => other_kind(kind, "a Real"),
        }
    }

    pub fn get_integer_status(&mut self, kind: fmi2StatusKind) -> Res<i32> {
        self.check_state(mask::fmi2GetIntegerStatus)?;
        other_kind(kind, "an Integer")
    }

    pub fn get_boolean_status(&mut self, kind: fmi2StatusKind) -> Res<bool> {
        self.check_state(mask::fmi2GetBooleanStatus)?;
        match kind {
            fmi2Terminated => Ok(self.terminated),
            _ => other_kind(kind, "a Boolean"),
        }
    }

    pub fn get_string_status(&mut self, kind: fmi2StatusKind) -> Res<()> {
        self.check_state(mask::fmi2GetStringStatus)?;
        match kind {
            fmi2PendingStatus => discard("no asynchronous step is pending"),
            _ => other_kind(kind, "a String"),
        }
    }
}

/// A status getter's answer for a kind it has no value of: `fmi2Discard`
/// for a kind of the standard (whose value is of another type, `ty`),
/// `fmi2Error` for an unknown one.
fn other_kind<T>(kind: fmi2StatusKind, ty: &str) -> Res<T> {
    match kind {
        fmi2DoStepStatus | fmi2PendingStatus | fmi2LastSuccessfulTime | fmi2Terminated => {
            discard(format!("status kind {kind} is not {ty}"))
        }
        _ => error(format!("unknown status kind {kind}")),
    }
}
