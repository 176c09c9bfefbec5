//! The rocking model under Model Exchange: the host's solver integrates
//! `(theta, omegaW)` (`omegaW` is `omega` referred to the inertia at the
//! weight: the same number unless a vertical input acts on a flexible
//! law); derivatives, event indicators and the event update come from
//! `rocking::dynamics::continuous` (docs/model-exchange.md).

use fmi2_export::{EventLog, Inputs, Update};
use rocking::dynamics::continuous::{Continuous, EVENT_INDICATORS};
use rocking::dynamics::State;

use super::{RockingSlave, MAX_GROUND_ACCELERATION};
use crate::description::{vr, EVENT_INDICATORS as DECLARED};

// the model description declares as many indicators as the physics has
const _: () = assert!(DECLARED as usize == EVENT_INDICATORS);

impl RockingSlave {
    /// The Model Exchange view of the current state.
    pub(crate) fn continuous(&self) -> Continuous {
        Continuous {
            state: self.state,
            side: self.side,
            left_with: self.left_with,
        }
    }

    /// The motion under `av` (m/s²), with `omega` where Model Exchange's
    /// state holds `omegaW`.
    pub(crate) fn motion(&self, av: f64) -> State {
        if self.me {
            self.sim.from_weight_referred(self.continuous(), av).state
        } else {
            self.state
        }
    }

    /// The state with `omegaW` in place of `omega` under `av` (m/s²):
    /// Model Exchange's own, or computed from co-simulation's `omega`.
    fn referred(&self, av: f64) -> Continuous {
        if self.me {
            self.continuous()
        } else {
            self.sim.to_weight_referred(self.continuous(), av)
        }
    }

    /// `omegaW` under `av` (m/s²).
    pub(crate) fn omega_w(&self, av: f64) -> f64 {
        self.referred(av).state.omega
    }

    pub(crate) fn store(&mut self, c: Continuous) {
        self.state = c.state;
        self.side = c.side;
        self.left_with = c.left_with;
        self.cache = None;
        self.rates = None;
    }

    /// The ground accelerations `(ag, av)` now, checked as in a step.
    fn ground(inputs: &Inputs<'_>) -> Result<(f64, f64), String> {
        let ag = inputs.real(vr::AG);
        let av = inputs.real(vr::AV);
        for (name, x) in [("ag", ag), ("av", av)] {
            if !x.is_finite() || x.abs() > MAX_GROUND_ACCELERATION {
                return Err(format!(
                    "{name} = {x}: the input must be finite and |{name}| <= {MAX_GROUND_ACCELERATION:e} m/s2"
                ));
            }
        }
        Ok((ag, av))
    }

    pub(crate) fn me_set_time(&mut self, t: f64) -> Result<(), String> {
        self.state.t = t;
        Ok(())
    }

    pub(crate) fn me_states(&self, x: &mut [f64]) -> Result<(), String> {
        x.copy_from_slice(&[self.state.theta, self.state.omega]);
        Ok(())
    }

    /// The host's states (kept as given; a rigid body at rest stays at rest
    /// until uplift: `Simulator::derivatives`).
    pub(crate) fn me_set_states(&mut self, x: &[f64]) -> Result<(), String> {
        let mut c = self.continuous();
        c.state.theta = x[0];
        c.state.omega = x[1];
        self.store(c);
        Ok(())
    }

    pub(crate) fn me_derivatives(
        &mut self,
        inputs: Inputs<'_>,
        dx: &mut [f64],
    ) -> Result<(), String> {
        let (ag, av) = Self::ground(&inputs)?;
        let d = self
            .sim
            .derivatives_weight_referred(&self.referred(av), ag, av);
        if let Some(x) = d.iter().find(|x| !x.is_finite()) {
            return Err(self.overflow(*x, ag));
        }
        dx.copy_from_slice(&d);
        Ok(())
    }

    pub(crate) fn me_event_indicators(
        &mut self,
        inputs: Inputs<'_>,
        z: &mut [f64],
    ) -> Result<(), String> {
        let (ag, av) = Self::ground(&inputs)?;
        let c = self.sim.from_weight_referred(self.continuous(), av);
        z.copy_from_slice(&self.sim.event_indicators_vertical(&c, ag, av));
        Ok(())
    }

    pub(crate) fn me_event_update(
        &mut self,
        inputs: Inputs<'_>,
        log: &mut EventLog,
    ) -> Result<Update, String> {
        let (ag, av) = Self::ground(&inputs)?;
        let mut c = self.sim.from_weight_referred(self.continuous(), av);
        let u = self.sim.event_update_vertical(&mut c, ag, av);
        self.store(self.sim.to_weight_referred(c, av));
        let t = c.state.t;
        if u.uplift {
            log.event(format!("uplift at t = {t}: the body starts rocking"));
        }
        if u.crossing {
            log.event(format!(
                "zero crossing of theta at t = {t}; {} crossings, {} impacts so far",
                c.state.zero_crossings, c.state.impacts
            ));
        }
        if u.came_to_rest {
            log.event(format!("came to rest at t = {t}"));
        }
        let mut terminate = u.overturned.then(|| {
            format!(
                "the body overturned (|theta| reached thetaOv = {} rad) at t = {t}",
                self.sim.model.theta_ov
            )
        });
        if let Some(cond) = u.out_of_range {
            self.terminal = Some(rocking::dynamics::Terminal {
                t,
                condition: cond,
                av,
            });
            terminate = Some(format!(
                "{} at t = {t}: av = {av} m/s2 leaves the model's range",
                cond.name()
            ));
        }
        Ok(Update {
            states_changed: u.states_changed,
            terminate,
        })
    }

    /// `true`: the host must enter event mode (a crossing it did not see).
    pub(crate) fn me_completed_step(&mut self) -> Result<bool, String> {
        let mut c = self.continuous();
        let event = self.sim.completed_step(&mut c);
        self.store(c);
        Ok(event)
    }

    pub(crate) fn me_nominals(&self, x: &mut [f64]) -> Result<(), String> {
        x.copy_from_slice(&self.sim.nominals());
        Ok(())
    }

    /// `der(theta)`, `der(omegaW)` (docs/model-exchange.md).
    pub(crate) fn me_derivative(&mut self, r: u32, inputs: Inputs<'_>) -> Result<f64, String> {
        let mut d = [0.0; 2];
        self.me_derivatives(inputs, &mut d)?;
        Ok(if r == vr::DER_THETA { d[0] } else { d[1] })
    }
}
