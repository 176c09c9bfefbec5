//! The round body in space as an FMI co-simulation slave (served in FMI
//! 2.0 and 3.0 by the generic layers): parameters from the stored values,
//! outputs from `rocking::spatial`, one `Spatial::advance` per step (FMI
//! 3.0's early return: `Spatial::advance_to_event`); and as a Model
//! Exchange model, whose derivatives, indicators and event update are
//! `rocking::spatial::continuous`'s. Model Exchange's velocity states are
//! `omegaWX`, `omegaWY`, `omegaWZ` (the angular velocity referred to the
//! weight, docs/model.md §11.5): the slave's `omega` holds them under Model
//! Exchange, and the angular velocity is computed from them under the `av`
//! of the instant; they are `omega` but for `formulation = shiftingPivot`
//! on a flexible bed under a vertical input.

use crate::description::{enums, vr, ROUND_BODY};
use fmi2_export::bytes::{ByteReader, ByteWriter, ReadError};
use fmi2_export::model_description::ModelDescription;
use fmi2_export::{EventLog, Inputs, Setup, Slave, StepEnd, Update, Values};
use rocking::dynamics::VerticalInput;
use rocking::interface::{Regime, RoundBed, RoundReaction};
use rocking::model::{LawKind, MassKind, Num, ShapeKind};
use rocking::spatial::continuous::{EVENT_INDICATORS, STATES};
use rocking::spatial::{PlanInput, Spatial, SpatialState};
use rocking::{Formulation, Params, Restitution};

/// Largest |agx|, |agy|, |av| a step accepts, m/s2 (RockingBlock's bound:
/// far beyond any ground motion, below where the arithmetic overflows).
pub const MAX_GROUND_ACCELERATION: f64 = 1e100;

/// What stands for `+inf` at the FMI boundary (RockingBlock's
/// `UNBOUNDED`, Modelica's `inf`): `frictionDemand` where `Fz <= 0`.
pub const UNBOUNDED: f64 = 1e60;

/// Layout version of the serialized state (inside the generic envelope).
/// Model Exchange's discrete state (the contact side `pivot`, rest, the
/// terminal flags) is the co-simulation state's: the layout is unchanged.
const STATE_VERSION: u32 = 1;

// the model description declares as many indicators as the physics has
const _: () = assert!(crate::description::EVENT_INDICATORS as usize == EVENT_INDICATORS);

pub struct RoundBodySlave {
    body: Spatial,
    /// The state; under Model Exchange its `omega` holds `omegaW`.
    state: SpatialState,
    /// Model Exchange: `state.omega` is `omegaW`.
    me: bool,
    /// The flexible bed's law asked in space (`contactArea`, `af`,
    /// `crushedArea`, `regime`); `None` on the rigid bed.
    bed: Option<RoundBed>,
}

/// The bed's reaction where the apparent weight leaves the law's range.
enum Outside {
    /// `g + av <= 0`: the bed carries nothing (liftOff).
    Unloaded,
    /// `m (g + av) >= fm A`: the whole base crushed (baseCrushing).
    Crushed,
}

/// The physics parameters of the stored values: the body and the bed
/// (rocking every way) with the initial tilt; `Err` names the variable.
fn params(v: Values<'_>) -> Result<Params, String> {
    let shape = match v.integer(vr::SHAPE) {
        enums::SOLID_CIRCLE => ShapeKind::SolidCircle,
        enums::HOLLOW_CIRCLE => ShapeKind::HollowCircle,
        s => {
            return Err(format!(
                "shape = {s}: a body in space needs a round base, solidCircle ({}) or hollowCircle ({})",
                enums::SOLID_CIRCLE,
                enums::HOLLOW_CIRCLE
            ))
        }
    };
    let mass_model = match v.integer(vr::MASS_MODEL) {
        enums::PRISM => MassKind::Prism,
        enums::LUMPED => MassKind::Lumped,
        m => return Err(format!("massModel = {m}: not an item of MassModelKind")),
    };
    let restitution = match v.integer(vr::RESTITUTION) {
        enums::HOUSNER => Restitution::Housner,
        enums::GIVEN => Restitution::Given,
        r => return Err(format!("restitution = {r}: not an item of RestitutionKind")),
    };
    let interface = match v.integer(vr::INTERFACE) {
        enums::RIGID => LawKind::Rigid,
        enums::ELASTIC => LawKind::Elastic,
        enums::ELASTO_PLASTIC => LawKind::ElastoPlastic,
        i => return Err(format!("interface = {i}: not an item of InterfaceLaw")),
    };
    let formulation = match v.integer(vr::FORMULATION) {
        enums::COSTA => Formulation::Costa,
        enums::SHIFTING_PIVOT => Formulation::ShiftingPivot,
        f => return Err(format!("formulation = {f}: not an item of FormulationKind")),
    };
    Ok(Params {
        shape,
        ro: v.real(vr::RO),
        ri: v.real(vr::RI),
        mass_model,
        h: v.real(vr::H),
        rho: v.real(vr::RHO),
        w: v.real(vr::W),
        hg: v.real(vr::HG),
        ic: v.real(vr::IC),
        interface,
        kn: v.real(vr::KN),
        fm: v.real(vr::FM),
        formulation,
        restitution,
        eta: v.real(vr::ETA),
        g: v.real(vr::G),
        theta0: v.real(vr::THETA0),
        ..Params::default()
    })
}

/// The physics' name of a variable as this FMU names it.
fn public_name(physics: &str) -> &str {
    match physics {
        "theta" => "theta0",
        "icAxial" => "IcAxial",
        other => other,
    }
}

/// The inputs now, checked finite: `([agx, agy], av)`.
fn inputs_now(inputs: &Inputs<'_>) -> Result<([f64; 2], f64), String> {
    let mut x = [0.0; 3];
    for (k, (r, name)) in [(vr::AGX, "agx"), (vr::AGY, "agy"), (vr::AV, "av")]
        .into_iter()
        .enumerate()
    {
        x[k] = inputs.real(r);
        if !x[k].is_finite() {
            return Err(format!("{name} = {}: the input must be finite", x[k]));
        }
    }
    Ok(([x[0], x[1]], x[2]))
}

/// `atan2(y, x)` in `(-pi, pi]`.
fn azimuth(d: [f64; 2]) -> f64 {
    let a = d[1].atan2(d[0]);
    if a == -std::f64::consts::PI {
        std::f64::consts::PI
    } else {
        a
    }
}

/// The inputs now for Model Exchange, checked as in a step: `([agx, agy], av)`.
fn ground(inputs: &Inputs<'_>) -> Result<([f64; 2], f64), String> {
    let (ag, av) = inputs_now(inputs)?;
    for (name, x) in [("agx", ag[0]), ("agy", ag[1]), ("av", av)] {
        if x.abs() > MAX_GROUND_ACCELERATION {
            return Err(format!(
                "{name} = {x}: |{name}| must be <= {MAX_GROUND_ACCELERATION:e} m/s2"
            ));
        }
    }
    Ok((ag, av))
}

impl RoundBodySlave {
    /// The body's state under `av` (m/s²): the angular velocity in `omega`
    /// where Model Exchange's state holds `omegaW`.
    fn motion(&self, av: f64) -> SpatialState {
        if self.me {
            self.body.from_weight_referred(self.state, av)
        } else {
            self.state
        }
    }

    /// The state with `omegaW` in its `omega` under `av` (m/s²): Model
    /// Exchange's own, or computed from co-simulation's angular velocity.
    fn referred(&self, av: f64) -> SpatialState {
        if self.me {
            self.state
        } else {
            self.body.to_weight_referred(self.state, av)
        }
    }

    /// The state derivatives under the inputs now: `d/dt (ex, ey, omegaW,
    /// xG, yG)`.
    fn rates(&self, inputs: &Inputs<'_>) -> Result<[f64; STATES], String> {
        let (ag, av) = ground(inputs)?;
        let d = self
            .body
            .derivatives_weight_referred(&self.referred(av), ag, av);
        if let Some(x) = d.iter().find(|x| !x.is_finite()) {
            return Err(self.overflow(*x));
        }
        Ok(d)
    }

    fn step(
        &mut self,
        t: f64,
        h: f64,
        inputs: Inputs<'_>,
        log: &mut EventLog,
        to_event: bool,
    ) -> Result<StepEnd, String> {
        let (agx, dagx) = inputs.line(vr::AGX, "agx", "m/s2", h, MAX_GROUND_ACCELERATION)?;
        let (agy, dagy) = inputs.line(vr::AGY, "agy", "m/s2", h, MAX_GROUND_ACCELERATION)?;
        let (av, dav) = inputs.line(vr::AV, "av", "m/s2", h, MAX_GROUND_ACCELERATION)?;
        if self.state.overturned {
            return Ok(StepEnd::Terminated {
                time: self.state.t,
                reason: "the body has already overturned".into(),
            });
        }
        if self.state.out_of_range {
            return Ok(StepEnd::Terminated {
                time: self.state.t,
                reason: "the run ended when g + av reached 0 (liftOff)".into(),
            });
        }
        let plan = PlanInput {
            a: [agx, agy],
            da: [dagx, dagy],
        };
        let mut s = self.state;
        let vertical = VerticalInput { av, dav };
        let ev = if to_event {
            self.body.advance_to_event(&mut s, t + h, plan, vertical)
        } else {
            self.body.advance(&mut s, t + h, plan, vertical)
        };
        let finite = s.t.is_finite()
            && s.e
                .iter()
                .chain(&s.omega)
                .chain(&s.xg)
                .all(|x| x.is_finite());
        if !finite {
            // the inputs named: past a bound of the model's arithmetic, a
            // huge input is what overflows a body already rocking
            return Err(format!(
                "the integration produced a non-finite state (e = {:?}, omega = {:?} rad/s) at t = {} \
                 under agx = {agx}, agy = {agy}, av = {av} m/s2 (slopes {dagx}, {dagy}, {dav} m/s3 \
                 over the step from t = {t}): an input or a parameter beyond what the model's \
                 arithmetic holds",
                s.e, s.omega, s.t
            ));
        }
        self.state = s;
        if log.enabled() {
            if ev.uplift {
                log.event(format!(
                    "uplift in ({t}, {}]: the body starts rocking",
                    t + h
                ));
            }
            if ev.impacts > 0 {
                log.event(format!(
                    "{} impact(s) in ({t}, {}]; {} so far",
                    ev.impacts,
                    t + h,
                    s.impacts
                ));
            }
            if ev.came_to_rest {
                log.event(format!("came to rest in ({t}, {}]", t + h));
            }
        }
        if let Some(t_ov) = ev.overturned_at {
            let theta_ov = self.body.model.theta_ov;
            log.event(format!(
                "overturned at t = {t_ov}: theta reached thetaOv = {theta_ov} rad"
            ));
            return Ok(StepEnd::Terminated {
                time: t_ov,
                reason: format!(
                    "the body overturned (theta reached thetaOv = {theta_ov} rad) at t = {t_ov}"
                ),
            });
        }
        if let Some(term) = ev.terminal {
            log.event(format!("{} at t = {}", term.condition.name(), term.t));
            return Ok(StepEnd::Terminated {
                time: term.t,
                reason: format!(
                    "{} at t = {}: av = {} m/s2; the apparent weight m (g + av) reached 0: the body leaves the bed (free flight is not modelled)",
                    term.condition.name(),
                    term.t,
                    term.av
                ),
            });
        }
        if ev.limited {
            return Ok(StepEnd::Stopped {
                time: s.t,
                reason: format!(
                    "work limit reached after {} integrator steps ({} rejected) in the step of {h} s from t = {t} (maxSteps = {})",
                    ev.steps + ev.rejected,
                    ev.rejected,
                    self.body.max_steps.unwrap_or(0)
                ),
            });
        }
        if ev.stopped_at_event {
            return Ok(StepEnd::Event { time: s.t });
        }
        Ok(StepEnd::Completed)
    }

    /// The flexible bed's reaction at the state under the apparent weight
    /// `m (g + av)` of the input now (`None` on the rigid bed).
    fn reaction(
        &self,
        inputs: &Inputs<'_>,
    ) -> Result<Option<Result<RoundReaction, Outside>>, String> {
        let Some(bed) = &self.bed else {
            return Ok(None);
        };
        let (_, av) = inputs_now(inputs)?;
        let b = &self.body.model.body;
        let n = b.mass * (b.g + av);
        if n <= 0.0 {
            return Ok(Some(Err(Outside::Unloaded)));
        }
        let s = &self.state;
        match bed.reaction_toward(s.theta(), s.contact_direction(), n) {
            Ok(r) => Ok(Some(Ok(r))),
            // the one condition left: n >= fm A
            Err(e) if e.variable == "N" => Ok(Some(Err(Outside::Crushed))),
            Err(e) => Err(format!(
                "the bed's reaction at theta = {} rad under N = {n} N: {} = {}: {}",
                s.theta(),
                e.variable,
                Num(e.value),
                e.condition
            )),
        }
    }

    /// `contactArea`, `crushedArea` and `af`, m², m², m.
    fn contact(&self, inputs: &Inputs<'_>) -> Result<[f64; 3], String> {
        let area = self.body.model.interface.shape().area();
        let ro = self.body.model.interface.shape().depth() / 2.0;
        Ok(match self.reaction(inputs)? {
            // the rigid bed: the whole base upright at rest, else a rim point
            None if self.state.at_rest => [area, 0.0, ro],
            None => [0.0, 0.0, 0.0],
            Some(Ok(r)) => [r.contact_area, r.crushed_area, r.contact.af],
            Some(Err(Outside::Unloaded)) => [0.0, 0.0, 0.0],
            Some(Err(Outside::Crushed)) => [area, area, ro],
        })
    }

    /// `regime` (RegimeKind's code).
    fn regime(&self, inputs: &Inputs<'_>) -> Result<i32, String> {
        if self.bed.is_some() && self.state.out_of_range {
            return Ok(enums::OUT_OF_RANGE);
        }
        Ok(match self.reaction(inputs)? {
            None if self.state.at_rest => enums::REST,
            None => enums::ROCKING,
            Some(Ok(r)) => match r.regime() {
                Regime::FullContact => enums::FULL_CONTACT,
                Regime::Partial => enums::PARTIAL_CONTACT,
                Regime::PartialCrushing => enums::PARTIAL_CRUSHING,
                Regime::FullCrushing => enums::FULL_CRUSHING,
                // set by the planar dynamics, never by the law
                Regime::Overturned => enums::PARTIAL_CONTACT,
            },
            Some(Err(_)) => enums::OUT_OF_RANGE,
        })
    }

    /// The bed's force on the body under the inputs now, N.
    fn force(&self, inputs: &Inputs<'_>) -> Result<[f64; 3], String> {
        let (ag, av) = inputs_now(inputs)?;
        Ok(self.body.contact_force(&self.motion(av), ag, av))
    }

    /// The angular velocity (`omega`) or, with `referred`, `omegaW` under
    /// the input now, rad/s.
    fn angular_velocity(&self, inputs: &Inputs<'_>, referred: bool) -> Result<[f64; 3], String> {
        if !self.me && !referred {
            return Ok(self.state.omega);
        }
        let (_, av) = inputs_now(inputs)?;
        Ok(if referred {
            self.referred(av).omega
        } else {
            self.motion(av).omega
        })
    }

    fn overflow(&self, x: f64) -> String {
        format!(
            "the value is {x} (floating-point overflow at theta = {} rad, omega = {:?} rad/s)",
            self.state.theta(),
            self.state.omega
        )
    }
}

impl Slave for RoundBodySlave {
    type State = SpatialState;

    fn description() -> &'static ModelDescription {
        &ROUND_BODY
    }

    fn guid() -> &'static str {
        crate::GUID
    }

    fn new(values: Values<'_>, setup: &Setup) -> Result<Self, String> {
        let p = params(values)?;
        let rtol = setup
            .tolerance
            .unwrap_or(ROUND_BODY.default_experiment.tolerance);
        let ic_axial = match p.mass_model {
            MassKind::Lumped => Some(values.real(vr::IC_AXIAL)),
            MassKind::Prism => None,
        };
        let mut body = Spatial::new(&p, ic_axial, rtol).map_err(|e| {
            format!(
                "{} = {}: {}",
                public_name(e.variable),
                Num(e.value),
                e.condition
            )
        })?;
        let max_steps = values.integer(vr::MAX_STEPS);
        if max_steps < 1 {
            return Err(format!(
                "maxSteps = {max_steps}: the work limit must be >= 1"
            ));
        }
        body.max_steps = Some(max_steps as u32);
        let psi0 = values.real(vr::PSI0);
        let mut omega = [0.0; 3];
        for (k, (r, name)) in [
            (vr::PSI0, "psi0"),
            (vr::OMEGA_X0, "omegaX0"),
            (vr::OMEGA_Y0, "omegaY0"),
            (vr::OMEGA_Z0, "omegaZ0"),
        ]
        .into_iter()
        .enumerate()
        {
            let x = values.real(r);
            if !x.is_finite() {
                return Err(format!("{name} = {x}: must be finite"));
            }
            if k > 0 {
                omega[k - 1] = x;
            }
        }
        let mut state = SpatialState::tilted(&body, p.theta0, psi0, omega);
        state.t = setup.start_time;
        if setup.model_exchange {
            state = body.to_weight_referred(state, values.real(vr::AV));
        }
        let bed = match p.interface {
            LawKind::Rigid => None,
            _ => Some(RoundBed::new(body.model.interface).map_err(|e| {
                format!(
                    "{} = {}: {}",
                    public_name(e.variable),
                    Num(e.value),
                    e.condition
                )
            })?),
        };
        Ok(RoundBodySlave {
            body,
            state,
            me: setup.model_exchange,
            bed,
        })
    }

    fn get_real(&mut self, r: u32, inputs: Inputs<'_>) -> Result<f64, String> {
        let b = &self.body.model.body;
        let s = &self.state;
        let x = match r {
            vr::THETA => s.theta(),
            vr::PSI => azimuth(s.contact_direction()),
            vr::THETA_OVER_ALPHA => s.theta() / b.alpha,
            vr::EX => s.e[0],
            vr::EY => s.e[1],
            vr::OMEGA_X..=vr::OMEGA_Z => {
                self.angular_velocity(&inputs, false)?[(r - vr::OMEGA_X) as usize]
            }
            vr::OMEGA_WX..=vr::OMEGA_WZ => {
                self.angular_velocity(&inputs, true)?[(r - vr::OMEGA_WX) as usize]
            }
            vr::XG => s.xg[0],
            vr::YG => s.xg[1],
            vr::FX => self.force(&inputs)?[0],
            vr::FY => self.force(&inputs)?[1],
            vr::FZ => self.force(&inputs)?[2],
            vr::FRICTION_DEMAND => {
                let [fx, fy, fz] = self.force(&inputs)?;
                let d = fx.hypot(fy) / fz;
                // Fz <= 0: no friction holds the base (RockingBlock's rule)
                if fz <= 0.0 || d > UNBOUNDED {
                    UNBOUNDED
                } else {
                    d
                }
            }
            vr::MASS => b.mass,
            vr::WEIGHT => b.weight,
            vr::R0 => b.r0,
            vr::ALPHA => b.alpha,
            vr::IO => b.io,
            vr::ETA_HOUSNER => b.eta_housner(),
            vr::THETA_OV => self.body.model.theta_ov,
            vr::DER_EX..=vr::DER_YG => self.rates(&inputs)?[(r - vr::DER_EX) as usize],
            vr::CONTACT_AREA => self.contact(&inputs)?[0],
            vr::CRUSHED_AREA => self.contact(&inputs)?[1],
            vr::AF => self.contact(&inputs)?[2],
            _ => return Err(format!("no computed Real with value reference {r}")),
        };
        if !x.is_finite() {
            return Err(self.overflow(x));
        }
        Ok(x)
    }

    fn get_integer(&mut self, r: u32, inputs: Inputs<'_>) -> Result<i32, String> {
        match r {
            vr::REGIME => self.regime(&inputs),
            vr::IMPACTS => Ok(i32::try_from(self.state.impacts).unwrap_or(i32::MAX)),
            _ => Err(format!("no computed Integer with value reference {r}")),
        }
    }

    fn get_boolean(&mut self, r: u32, _inputs: Inputs<'_>) -> Result<bool, String> {
        match r {
            vr::OVERTURNED => Ok(self.state.overturned),
            _ => Err(format!("no computed Boolean with value reference {r}")),
        }
    }

    fn output_derivative(
        &mut self,
        r: u32,
        order: i32,
        _inputs: Inputs<'_>,
    ) -> Result<f64, String> {
        // maxOutputDerivativeOrder is 0: the layer refuses every order first
        Err(format!(
            "no output derivatives (value reference {r}, order {order}): maxOutputDerivativeOrder = 0"
        ))
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

    /// Stops at the first uplift, impact (with coming to rest) or
    /// overturning inside the step.
    fn do_step_to_event(
        &mut self,
        t: f64,
        h: f64,
        inputs: Inputs<'_>,
        log: &mut EventLog,
    ) -> Result<StepEnd, String> {
        self.step(t, h, inputs, log, true)
    }

    fn state(&self) -> SpatialState {
        self.state
    }

    fn set_state(&mut self, state: SpatialState) {
        self.state = state;
    }

    fn write_state(s: &SpatialState, w: &mut ByteWriter) {
        // Destructured: a new field in SpatialState breaks the build here, not the format.
        let SpatialState {
            t,
            e,
            omega,
            xg,
            pivot,
            impacts,
            at_rest,
            overturned,
            out_of_range,
            h,
        } = *s;
        w.u32(STATE_VERSION);
        w.f64(t);
        for x in e.iter().chain(&omega).chain(&xg).chain(&pivot) {
            w.f64(*x);
        }
        w.u64(impacts);
        w.bool(at_rest);
        w.bool(overturned);
        w.bool(out_of_range);
        w.f64(h);
    }

    fn read_state(r: &mut ByteReader<'_>) -> Result<SpatialState, ReadError> {
        let version = r.u32("state version")?;
        if version != STATE_VERSION {
            return Err(format!(
                "round-body state version {version}, this FMU reads version {STATE_VERSION}"
            ));
        }
        let t = r.f64("t")?;
        let mut f = [0.0; 9];
        for (x, name) in f.iter_mut().zip([
            "ex", "ey", "omegaX", "omegaY", "omegaZ", "xG", "yG", "pivot x", "pivot y",
        ]) {
            *x = r.f64(name)?;
            if !x.is_finite() {
                return Err(format!("{name} = {x} is not finite"));
            }
        }
        let s = SpatialState {
            t,
            e: [f[0], f[1]],
            omega: [f[2], f[3], f[4]],
            xg: [f[5], f[6]],
            pivot: [f[7], f[8]],
            impacts: r.u64("impacts")?,
            at_rest: r.bool("at_rest")?,
            overturned: r.bool("overturned")?,
            out_of_range: r.bool("out_of_range")?,
            h: r.f64("h")?,
        };
        if !s.t.is_finite() {
            return Err(format!("t = {} is not finite", s.t));
        }
        if s.e[0].hypot(s.e[1]) > 1.0 {
            return Err(format!("e = {:?}: the tilt's sine exceeds 1", s.e));
        }
        if (s.pivot[0].hypot(s.pivot[1]) - 1.0).abs() > 1e-12 {
            return Err(format!("pivot = {:?}: not a unit vector", s.pivot));
        }
        if !(s.h.is_finite() && s.h >= 0.0) {
            return Err(format!("step h = {}: must be finite and >= 0", s.h));
        }
        Ok(s)
    }

    fn set_time(&mut self, t: f64) -> Result<(), String> {
        self.state.t = t;
        Ok(())
    }

    fn continuous_states(&self, x: &mut [f64]) -> Result<(), String> {
        x.copy_from_slice(&self.state.continuous_states());
        Ok(())
    }

    /// The host's states (finite: the layer checked), kept as given; at
    /// rest and after the run's end the derivatives are 0 whatever they are.
    fn set_continuous_states(&mut self, x: &[f64]) -> Result<(), String> {
        let y: [f64; STATES] = x
            .try_into()
            .map_err(|_| format!("nx = {}: this model has {STATES}", x.len()))?;
        if y[0].hypot(y[1]) >= 1.0 {
            return Err(format!(
                "ex = {}, ey = {}: the tilt's sine sqrt(ex^2 + ey^2) must be < 1",
                y[0], y[1]
            ));
        }
        self.state.set_continuous_states(&y);
        Ok(())
    }

    fn derivatives(&mut self, inputs: Inputs<'_>, dx: &mut [f64]) -> Result<(), String> {
        dx.copy_from_slice(&self.rates(&inputs)?);
        Ok(())
    }

    fn event_indicators(&mut self, inputs: Inputs<'_>, z: &mut [f64]) -> Result<(), String> {
        let (ag, av) = ground(&inputs)?;
        z.copy_from_slice(&self.body.event_indicators(&self.motion(av), ag, av));
        Ok(())
    }

    fn event_update(&mut self, inputs: Inputs<'_>, log: &mut EventLog) -> Result<Update, String> {
        let (ag, av) = ground(&inputs)?;
        let mut st = self.motion(av);
        let u = self.body.event_update(&mut st, ag, av);
        self.state = if self.me {
            self.body.to_weight_referred(st, av)
        } else {
            st
        };
        let s = &st;
        let t = s.t;
        if u.uplift {
            log.event(format!(
                "uplift at t = {t}: the body starts rocking toward psi = {}",
                azimuth(s.pivot)
            ));
        }
        if u.impact {
            log.event(format!("impact at t = {t}; {} so far", s.impacts));
        }
        if u.came_to_rest {
            log.event(format!("came to rest at t = {t}"));
        }
        let theta_ov = self.body.model.theta_ov;
        let terminate = if u.overturned {
            Some(format!(
                "the body overturned (theta reached thetaOv = {theta_ov} rad) at t = {t}"
            ))
        } else if u.out_of_range {
            Some(format!(
                "liftOff at t = {t}: av = {av} m/s2; the apparent weight m (g + av) reached 0: the body leaves the bed (free flight is not modelled)"
            ))
        } else {
            None
        };
        Ok(Update {
            states_changed: u.states_changed,
            terminate,
        })
    }

    fn completed_integrator_step(
        &mut self,
        inputs: Inputs<'_>,
        _log: &mut EventLog,
    ) -> Result<bool, String> {
        let (ag, av) = ground(&inputs)?;
        Ok(self.body.completed_step(&self.motion(av), ag, av))
    }

    fn nominals(&self, x: &mut [f64]) -> Result<(), String> {
        x.copy_from_slice(&self.body.nominals());
        Ok(())
    }
}
