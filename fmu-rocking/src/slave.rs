//! The rocking model as an FMI 2.0 co-simulation slave: parameters from the
//! stored values, outputs from `rocking::dynamics`, one `advance` per step;
//! and as a Model Exchange model (the `model_exchange` module).

mod model_exchange;

use crate::description::{vr, ROCKING_BLOCK};
use fmi2_export::bytes::{ByteReader, ByteWriter, ReadError};
use fmi2_export::model_description::ModelDescription;
use fmi2_export::{EventLog, Inputs, Setup, Slave, StepEnd, Update, Values};
use rocking::dynamics::continuous::Continuous;
use rocking::dynamics::{
    GroundInput, OutOfRange, OutputRates, Outputs, Simulator, State, Terminal, VerticalInput,
    WorkLimit,
};
use rocking::{Params, Regime};

/// Largest |ag| a step accepts, m/s2 (far beyond any ground motion; the
/// arithmetic of the equations of motion overflows around 1e200, and beyond
/// it the integrator could not finish a step on the way to overturning;
/// the check costs microseconds).
pub const MAX_GROUND_ACCELERATION: f64 = 1e100;

/// Layout version of the serialized state (inside the generic envelope):
/// 4 added the Model Exchange toe and last impact speed, 5 the terminal
/// condition and the last step's `av`.
const STATE_VERSION: u32 = 5;

/// Everything an FMU state holds (`fmi2GetFMUstate`, serialized): the
/// motion, and what the next step needs besides it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Saved {
    pub continuous: Continuous,
    /// The input had left the model's range: the run is over.
    pub terminal: Option<Terminal>,
    /// `av` at the end of the last step (the next step's jump starts there).
    pub av_end: Option<f64>,
}

pub struct RockingSlave {
    sim: Simulator,
    state: State,
    /// Model Exchange: the toe (see `rocking::dynamics::continuous`).
    side: f64,
    /// Model Exchange: `|omega|` after the last impact of a rigid body, rad/s.
    left_with: f64,
    /// Outputs at `state` for the inputs `(ag, av, dav/dt)` with these bits.
    cache: Option<([u64; 3], Outputs)>,
    /// Output derivatives at `state` for the ground input `(ag, dag/dt,
    /// av, dav/dt)` with these bits.
    rates: Option<([u64; 4], OutputRates)>,
    /// The input left the model's range (docs/model.md §6.5): `regime` 5.
    terminal: Option<Terminal>,
    /// `av` at the end of the last step (none before the first; an FMU
    /// state keeps it): a host that holds its inputs makes it jump.
    av_end: Option<f64>,
    sliding: SlidingCheck,
    /// Model Exchange: `state.omega` is the host's state `omegaW`, not
    /// `omega` (docs/model-exchange.md, "The state omegaW").
    me: bool,
}

/// The sliding check (docs/model.md §5, "Friction demand"): the base's
/// friction coefficient `mu` (0: no check) and whether the instance has
/// warned already (once per instance: a master that goes back with
/// `fmi2SetFMUstate` is not warned again).
struct SlidingCheck {
    mu: f64,
    warned: bool,
}

/// `regime` once the input has left the model's range (docs/model.md §6.5).
const REGIME_OUT_OF_RANGE: i32 = 5;

/// The physics parameters from the stored values (table: [`crate::params`]).
pub fn params(v: Values<'_>) -> Result<Params, String> {
    crate::params::params(|r| v.real(r), |r| v.integer(r))
}

/// What stands for `+inf` at the FMI boundary, which no non-finite value
/// crosses (hosts such as OMSimulator refuse them): Modelica's
/// `Modelica.Constants.inf`, the convention of the Modelica tools and of
/// their FMI hosts. `thetaC` of a law that never crushes, `frictionDemand`
/// where `Fz <= 0` (docs/model.md §5: "Values that stand for infinity").
pub const UNBOUNDED: f64 = 1e60;

/// `x` as variable `r` reports it: `thetaC` and `frictionDemand` at most
/// [`UNBOUNDED`], their `+inf` included (a NaN stays NaN, an overflow).
fn bounded(r: u32, x: f64) -> f64 {
    if matches!(r, vr::THETA_C | vr::FRICTION_DEMAND) && x > UNBOUNDED {
        UNBOUNDED
    } else {
        x
    }
}

fn regime_name(r: Regime) -> &'static str {
    match r {
        Regime::FullContact => "full contact",
        Regime::Partial => "partial contact",
        Regime::PartialCrushing => "partial contact with crushing",
        Regime::FullCrushing => "full contact with crushing",
        Regime::Overturned => "overturned",
    }
}

impl RockingSlave {
    /// The outputs under `ag`, `av` and `av`'s input derivative `dav`
    /// (`Simulator::outputs_loaded`).
    fn outputs(&mut self, ag: f64, av: f64, dav: f64) -> Outputs {
        let key = [ag, av, dav].map(f64::to_bits);
        match self.cache {
            Some((k, o)) if k == key => o,
            _ => {
                let v = VerticalInput { av, dav };
                let o = self.sim.outputs_loaded(&self.motion(av), ag, v);
                self.cache = Some((key, o));
                o
            }
        }
    }

    fn rates(&mut self, input: GroundInput, v: VerticalInput) -> OutputRates {
        let key = [input.ag, input.dag, v.av, v.dav].map(f64::to_bits);
        match self.rates {
            Some((k, r)) if k == key => r,
            _ => {
                let r = self.sim.output_rates_vertical(&self.motion(v.av), input, v);
                self.rates = Some((key, r));
                r
            }
        }
    }

    /// Why a computed value is not finite.
    fn overflow(&self, x: f64, ag: f64) -> String {
        format!(
            "the value is {x} (floating-point overflow at theta = {} rad, omega = {} rad/s, ag = {ag} m/s2)",
            self.state.theta, self.state.omega
        )
    }

    /// Warns, once, when the friction demand at the current state exceeds
    /// `mu` (checked where the state is: at communication points and at
    /// Model Exchange's completed integrator steps).
    fn check_sliding(&mut self, ag: f64, av: f64, dav: f64, log: &mut EventLog) {
        let SlidingCheck { mu, warned } = self.sliding;
        if mu == 0.0 || warned {
            return;
        }
        let demand = bounded(
            vr::FRICTION_DEMAND,
            self.outputs(ag, av, dav).friction_demand(),
        );
        if demand > mu {
            self.sliding.warned = true;
            log.warn(format!(
                "frictionDemand = {demand} > mu = {mu} at t = {}: the base would slide, which the model does not \
                 represent (it assumes no sliding): the results from here on lie outside its assumptions",
                self.state.t
            ));
        }
    }

    fn regime(&mut self, ag: f64, av: f64, dav: f64) -> Regime {
        if self.state.overturned {
            Regime::Overturned
        } else {
            self.outputs(ag, av, dav).regime
        }
    }

    /// A step from `t` to `t + h`, or (`to_event`) to the first event in it.
    fn step(
        &mut self,
        t: f64,
        h: f64,
        inputs: Inputs<'_>,
        log: &mut EventLog,
        to_event: bool,
    ) -> Result<StepEnd, String> {
        let (ag, dag) = inputs.line(vr::AG, "ag", "m/s2", h, MAX_GROUND_ACCELERATION)?;
        // docs/model.md §7.4: av is checked like ag
        let (av, dav) = inputs.line(vr::AV, "av", "m/s2", h, MAX_GROUND_ACCELERATION)?;
        let v = VerticalInput { av, dav };
        if self.state.overturned {
            return Ok(StepEnd::Terminated {
                time: self.state.t,
                reason: "the body has already overturned".into(),
            });
        }
        if let Some(term) = self.terminal {
            return Ok(StepEnd::Terminated {
                time: term.t,
                reason: format!(
                    "the run ended at t = {} ({})",
                    term.t,
                    term.condition.name()
                ),
            });
        }
        let before = log.enabled().then(|| self.regime(ag, v.av, v.dav));
        let mut s = self.state;
        if let Some(prev) = self.av_end {
            self.sim.vertical_jump(&mut s, prev, v.av);
        }
        let input = GroundInput { ag, dag };
        let ev = if to_event {
            self.sim.advance_to_event_vertical(&mut s, t + h, input, v)
        } else {
            self.sim.advance_vertical(&mut s, t + h, input, v)
        };
        if !(s.theta.is_finite() && s.omega.is_finite() && s.t.is_finite()) {
            return Err(format!(
                "the integration produced a non-finite state (theta = {}, omega = {}) at t = {}",
                s.theta, s.omega, s.t
            ));
        }
        self.state = s;
        self.av_end = Some(v.av + v.dav * (s.t - t));
        self.cache = None;
        self.rates = None;
        self.check_sliding(ag + dag * h, av + dav * h, dav, log);
        if log.enabled() {
            if ev.uplift {
                log.event(format!(
                    "uplift in ({t}, {}]: the body starts rocking",
                    t + h
                ));
            }
            if ev.zero_crossings > 0 {
                log.event(format!(
                    "{} zero crossing(s) of theta in ({t}, {}], of which {} impact(s) (returns after the joint opened); {} crossings, {} impacts so far",
                    ev.zero_crossings,
                    t + h,
                    ev.impacts,
                    s.zero_crossings,
                    s.impacts
                ));
            }
            if ev.came_to_rest {
                log.event(format!("came to rest in ({t}, {}]", t + h));
            }
            let a_end = ag + dag * h;
            let after = self.regime(a_end, v.av + v.dav * h, v.dav);
            if let Some(b) = before {
                if b != after {
                    log.event(format!(
                        "regime {} ({}) -> {} ({}) in ({t}, {}]",
                        b as i32,
                        regime_name(b),
                        after as i32,
                        regime_name(after),
                        t + h
                    ));
                }
            }
        }
        if let Some(t_ov) = ev.overturned_at {
            log.event(format!(
                "overturned at t = {t_ov}: |theta| reached thetaOv = {} rad",
                self.sim.model.theta_ov
            ));
            return Ok(StepEnd::Terminated {
                time: t_ov,
                reason: format!(
                    "the body overturned (|theta| reached thetaOv = {} rad) at t = {t_ov}",
                    self.sim.model.theta_ov
                ),
            });
        }
        if let Some(term) = ev.terminal {
            self.terminal = Some(term);
            let why = match term.condition {
                OutOfRange::LiftOff => "the apparent weight N = m (g + av) reached 0: the body leaves the ground (free flight is not modelled)",
                OutOfRange::BaseCrushing => "the apparent weight N reached fm A: the whole section crushes",
                OutOfRange::RestUnstable => "N hG reached kn Is: the rest position is unstable",
            };
            return Ok(StepEnd::Terminated {
                time: term.t,
                reason: format!(
                    "{} at t = {}: av = {} m/s2; {why}",
                    term.condition.name(),
                    term.t,
                    term.av
                ),
            });
        }
        if let Some(l) = ev.limited {
            let max_steps = self.sim.work_limit.map_or(0, |w| w.per_call);
            return Ok(StepEnd::Stopped {
                time: l.t,
                reason: format!(
                    "work limit reached after {} in the step of {h} s from t = {t} (budget {}: maxSteps = {max_steps}, \
                     up to 1.5 times that for steps over 1 s)",
                    l.cause(),
                    l.budget
                ),
            });
        }
        // an event at the step's end (within its last ulp) is an event too:
        // the impact is applied, and the host must hear of it
        if to_event && ev.stopped_at_event {
            return Ok(StepEnd::Event { time: s.t });
        }
        Ok(StepEnd::Completed)
    }
}

impl Slave for RockingSlave {
    type State = Saved;

    fn description() -> &'static ModelDescription {
        &ROCKING_BLOCK
    }

    fn guid() -> &'static str {
        crate::GUID
    }

    fn new(values: Values<'_>, setup: &Setup) -> Result<Self, String> {
        let p = params(values)?;
        let model = p.build().map_err(|e| e.to_string())?;
        let rtol = setup
            .tolerance
            .unwrap_or(ROCKING_BLOCK.default_experiment.tolerance);
        let max_steps = values.integer(vr::MAX_STEPS);
        if max_steps < 1 {
            return Err(format!(
                "maxSteps = {max_steps}: the work limit must be >= 1"
            ));
        }
        let mu = values.real(vr::MU);
        if mu.is_nan() || mu < 0.0 {
            return Err(format!(
                "mu = {mu}: the friction coefficient must be >= 0 (0: no sliding check)"
            ));
        }
        let mut sim = Simulator::new(model, rtol);
        sim.work_limit = Some(WorkLimit {
            per_call: max_steps as u64,
        });
        let mut c = sim.continuous(p.theta0, p.omega0, values.real(vr::AG));
        c.state.t = setup.start_time;
        if setup.model_exchange {
            c = sim.to_weight_referred(c, values.real(vr::AV));
        }
        Ok(RockingSlave {
            sim,
            state: c.state,
            side: c.side,
            left_with: c.left_with,
            cache: None,
            rates: None,
            terminal: None,
            av_end: None,
            sliding: SlidingCheck { mu, warned: false },
            me: setup.model_exchange,
        })
    }

    fn get_real(&mut self, r: u32, inputs: Inputs<'_>) -> Result<f64, String> {
        let m = &self.sim.model;
        let b = &m.body;
        let ag = inputs.real(vr::AG);
        let av = inputs.real(vr::AV);
        let dav = inputs.derivative(vr::AV);
        let x = match r {
            vr::THETA => self.state.theta,
            vr::OMEGA => self.motion(av).omega,
            vr::OMEGA_W => self.omega_w(av),
            vr::THETA_OVER_ALPHA => self.state.theta / b.alpha,
            vr::MASS => b.mass,
            vr::WEIGHT => b.weight,
            vr::R0 => b.r0,
            vr::ALPHA => b.alpha,
            vr::IO => b.io,
            vr::ETA_HOUSNER => b.eta_housner(),
            vr::THETA_JO => m.interface.theta_jo(),
            vr::THETA_C => m.interface.theta_c(),
            vr::THETA_OV => m.theta_ov,
            vr::ANGULAR_ACCELERATION => self.outputs(ag, av, dav).theta_dd,
            vr::AF => self.outputs(ag, av, dav).af,
            vr::CONTACT_LENGTH => self.outputs(ag, av, dav).contact_length,
            vr::MR => self.outputs(ag, av, dav).mr,
            vr::FX => self.outputs(ag, av, dav).fx,
            vr::FZ => self.outputs(ag, av, dav).fz,
            // the reaction's opposite, exactly (negation rounds nothing)
            vr::FX_SUPPORT => -self.outputs(ag, av, dav).fx,
            vr::FZ_SUPPORT => -self.outputs(ag, av, dav).fz,
            vr::APPARENT_WEIGHT => self.outputs(ag, av, dav).apparent_weight,
            vr::FRICTION_DEMAND => self.outputs(ag, av, dav).friction_demand(),
            vr::DER_THETA | vr::DER_OMEGA_W => self.me_derivative(r, inputs)?,
            _ => return Err(format!("no computed Real with value reference {r}")),
        };
        // thetaC is +inf without crushing, frictionDemand where Fz <= 0:
        // both reported as UNBOUNDED; anything else not finite is an
        // overflow of a finite but absurd start value or input, refused
        // rather than returned as if it were a result.
        let x = bounded(r, x);
        if !x.is_finite() {
            return Err(self.overflow(x, ag));
        }
        Ok(x)
    }

    fn get_integer(&mut self, r: u32, inputs: Inputs<'_>) -> Result<i32, String> {
        match r {
            vr::REGIME if self.terminal.is_some() => Ok(REGIME_OUT_OF_RANGE),
            vr::REGIME => Ok(self.regime(
                inputs.real(vr::AG),
                inputs.real(vr::AV),
                inputs.derivative(vr::AV),
            ) as i32),
            vr::IMPACTS => Ok(i32::try_from(self.state.impacts).unwrap_or(i32::MAX)),
            vr::ZERO_CROSSINGS => Ok(i32::try_from(self.state.zero_crossings).unwrap_or(i32::MAX)),
            _ => Err(format!("no computed Integer with value reference {r}")),
        }
    }

    fn get_boolean(&mut self, r: u32, _inputs: Inputs<'_>) -> Result<bool, String> {
        match r {
            vr::OVERTURNED => Ok(self.state.overturned),
            _ => Err(format!("no computed Boolean with value reference {r}")),
        }
    }

    fn output_derivative(&mut self, r: u32, order: i32, inputs: Inputs<'_>) -> Result<f64, String> {
        let ag = inputs.real(vr::AG);
        let input = GroundInput {
            ag,
            dag: inputs.derivative(vr::AG),
        };
        let v = VerticalInput {
            av: inputs.real(vr::AV),
            dav: inputs.derivative(vr::AV),
        };
        // the FMI layer has checked 1 <= order <= maxOutputDerivativeOrder
        let k = match order {
            1 | 2 => order as usize,
            _ => return Err(format!("derivative order {order} is not 1 or 2")),
        };
        let rates = self.rates(input, v);
        let x = match r {
            vr::THETA => rates.theta[k],
            vr::OMEGA => rates.omega[k],
            vr::THETA_OVER_ALPHA => rates.theta[k] / self.sim.model.body.alpha,
            vr::ANGULAR_ACCELERATION => rates.theta_dd[k],
            vr::AF => rates.af[k],
            vr::CONTACT_LENGTH => rates.contact_length[k],
            vr::MR => rates.mr[k],
            vr::FX => rates.fx[k],
            vr::FZ => rates.fz[k],
            vr::FX_SUPPORT => -rates.fx[k],
            vr::FZ_SUPPORT => -rates.fz[k],
            // constant where the value is UNBOUNDED (Fz <= 0, or beyond)
            vr::FRICTION_DEMAND => match rates.friction_demand() {
                d if bounded(r, d[0]) == UNBOUNDED => 0.0,
                d => d[k],
            },
            vr::APPARENT_WEIGHT => rates.apparent_weight[k],
            vr::OMEGA_W => self.sim.omega_w_rates(&self.motion(v.av), ag, v, &rates)[k],
            _ => return Err(format!("no Real output with value reference {r}")),
        };
        if !x.is_finite() {
            return Err(self.overflow(x, ag));
        }
        Ok(x)
    }

    fn do_step(
        &mut self,
        t: f64,
        h: f64,
        inputs: Inputs<'_>,
        log: &mut EventLog,
    ) -> Result<StepEnd, String> {
        self.step(t, h, inputs, log, false)
    }

    /// Stops at the first zero crossing (an impact of a rigid block),
    /// uplift, rest or overturning the integrator locates in the step.
    fn do_step_to_event(
        &mut self,
        t: f64,
        h: f64,
        inputs: Inputs<'_>,
        log: &mut EventLog,
    ) -> Result<StepEnd, String> {
        self.step(t, h, inputs, log, true)
    }

    fn state(&self) -> Saved {
        Saved {
            continuous: self.continuous(),
            terminal: self.terminal,
            av_end: self.av_end,
        }
    }

    fn set_state(&mut self, saved: Saved) {
        self.terminal = saved.terminal;
        self.av_end = saved.av_end;
        self.store(saved.continuous);
    }

    fn write_state(saved: &Saved, w: &mut ByteWriter) {
        let c = &saved.continuous;
        let s = &c.state;
        // Destructured: a new field in State breaks the build here, not the format.
        let State {
            t,
            theta,
            omega,
            impacts,
            zero_crossings,
            opened,
            at_rest,
            overturned,
            h,
            a,
            stiff,
            switch_count,
        } = *s;
        w.u32(STATE_VERSION);
        w.f64(t);
        w.f64(theta);
        w.f64(omega);
        w.u64(impacts);
        w.u64(zero_crossings);
        w.bool(opened);
        w.bool(at_rest);
        w.bool(overturned);
        w.f64(h);
        w.f64(a);
        w.bool(stiff);
        w.u32(switch_count);
        w.f64(c.side);
        w.f64(c.left_with);
        w.bool(saved.terminal.is_some());
        if let Some(Terminal { t, condition, av }) = saved.terminal {
            w.f64(t);
            w.u8(match condition {
                OutOfRange::LiftOff => 0,
                OutOfRange::BaseCrushing => 1,
                OutOfRange::RestUnstable => 2,
            });
            w.f64(av);
        }
        w.bool(saved.av_end.is_some());
        if let Some(av) = saved.av_end {
            w.f64(av);
        }
    }

    fn read_state(r: &mut ByteReader<'_>) -> Result<Saved, ReadError> {
        let v = r.u32("state version")?;
        if v != STATE_VERSION {
            return Err(format!(
                "rocking state version {v}, this FMU reads version {STATE_VERSION}"
            ));
        }
        let s = State {
            t: r.f64("t")?,
            theta: r.f64("theta")?,
            omega: r.f64("omega")?,
            impacts: r.u64("impacts")?,
            zero_crossings: r.u64("zero_crossings")?,
            opened: r.bool("opened")?,
            at_rest: r.bool("at_rest")?,
            overturned: r.bool("overturned")?,
            h: r.f64("h")?,
            a: r.f64("a")?,
            stiff: r.bool("stiff")?,
            switch_count: r.u32("switch_count")?,
        };
        let (side, left_with) = (r.f64("side")?, r.f64("left_with")?);
        if side != 1.0 && side != -1.0 {
            return Err(format!("side = {side}: must be 1 or -1"));
        }
        if !(left_with.is_finite() && left_with >= 0.0) {
            return Err(format!("left_with = {left_with}: must be finite and >= 0"));
        }
        for (name, x) in [("t", s.t), ("theta", s.theta), ("omega", s.omega)] {
            if !x.is_finite() {
                return Err(format!("{name} = {x} is not finite"));
            }
        }
        if s.impacts > s.zero_crossings {
            return Err(format!(
                "impacts = {} > zero crossings = {}: every impact is a zero crossing",
                s.impacts, s.zero_crossings
            ));
        }
        if !(s.h.is_finite() && s.h >= 0.0 && s.a.is_finite() && s.a >= 0.0) {
            return Err(format!("step h = {}, contact a = {}: invalid", s.h, s.a));
        }
        let terminal = if r.bool("terminal")? {
            Some(read_terminal(r)?)
        } else {
            None
        };
        let av_end = if r.bool("av_end set")? {
            let av = r.f64("av_end")?;
            if !av.is_finite() {
                return Err(format!("av_end = {av} is not finite"));
            }
            Some(av)
        } else {
            None
        };
        Ok(Saved {
            continuous: Continuous {
                state: s,
                side,
                left_with,
            },
            terminal,
            av_end,
        })
    }

    fn set_time(&mut self, t: f64) -> Result<(), String> {
        self.me_set_time(t)
    }

    fn continuous_states(&self, x: &mut [f64]) -> Result<(), String> {
        self.me_states(x)
    }

    fn set_continuous_states(&mut self, x: &[f64]) -> Result<(), String> {
        self.me_set_states(x)
    }

    fn derivatives(&mut self, inputs: Inputs<'_>, dx: &mut [f64]) -> Result<(), String> {
        self.me_derivatives(inputs, dx)
    }

    fn event_indicators(&mut self, inputs: Inputs<'_>, z: &mut [f64]) -> Result<(), String> {
        self.me_event_indicators(inputs, z)
    }

    fn event_update(&mut self, inputs: Inputs<'_>, log: &mut EventLog) -> Result<Update, String> {
        self.me_event_update(inputs, log)
    }

    fn completed_integrator_step(
        &mut self,
        inputs: Inputs<'_>,
        log: &mut EventLog,
    ) -> Result<bool, String> {
        let event = self.me_completed_step()?;
        self.check_sliding(
            inputs.real(vr::AG),
            inputs.real(vr::AV),
            inputs.derivative(vr::AV),
            log,
        );
        Ok(event)
    }

    fn nominals(&self, x: &mut [f64]) -> Result<(), String> {
        self.me_nominals(x)
    }
}

/// The terminal condition of a serialized state (see `write_state`).
fn read_terminal(r: &mut ByteReader<'_>) -> Result<Terminal, ReadError> {
    let t = r.f64("terminal t")?;
    let code = r.u8("terminal condition")?;
    let av = r.f64("terminal av")?;
    let condition = match code {
        0 => OutOfRange::LiftOff,
        1 => OutOfRange::BaseCrushing,
        2 => OutOfRange::RestUnstable,
        _ => return Err(format!("terminal condition {code}: must be 0, 1 or 2")),
    };
    if !(t.is_finite() && av.is_finite()) {
        return Err(format!("terminal at t = {t}, av = {av}: not finite"));
    }
    Ok(Terminal { t, condition, av })
}
