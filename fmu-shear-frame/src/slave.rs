//! The shear building as an FMI 2.0 co-simulation slave: the frame from the
//! stored parameters, outputs from its state, one exact step per `fmi2DoStep`.

use crate::description::{enums, vr, MAX_STOREYS, SHEAR_FRAME};
use fmi2_export::bytes::{ByteReader, ByteWriter, ReadError};
use fmi2_export::model_description::ModelDescription;
use fmi2_export::{EventLog, Inputs, Setup, Slave, StepEnd, Values};
use shear_frame::{Damping, Frame, Load, Propagator, State};

/// Layout version of the serialized [`State`] (inside the generic envelope).
const STATE_VERSION: u32 = 1;

/// Propagators kept for reuse: a master alternates between at most a few
/// step sizes (the regular one and a last, shorter one).
const CACHED_STEPS: usize = 4;

pub struct ShearFrameSlave {
    frame: Frame,
    state: State,
    /// Exact maps for the step sizes used so far, most recent first.
    propagators: Vec<Propagator>,
}

fn floors(n: usize) -> impl Iterator<Item = usize> {
    1..=n
}

/// The loads at the start of the step (`value`) or their rates (`rate`).
fn load(inputs: Inputs<'_>, n: usize, rate: bool) -> Load {
    let get = |r: u32| {
        if rate {
            inputs.derivative(r)
        } else {
            inputs.real(r)
        }
    };
    let mut l = Load {
        ag: get(vr::AG),
        ..Load::ZERO
    };
    for i in floors(n) {
        l.fx[i - 1] = get(vr::at(vr::FX, i));
    }
    l
}

impl ShearFrameSlave {
    fn propagator(&mut self, h: f64) -> &Propagator {
        match self
            .propagators
            .iter()
            .position(|p| p.h().to_bits() == h.to_bits())
        {
            Some(k) => {
                let p = self.propagators.remove(k);
                self.propagators.insert(0, p);
            }
            None => {
                self.propagators.truncate(CACHED_STEPS - 1);
                self.propagators.insert(0, self.frame.propagator(h));
            }
        }
        &self.propagators[0]
    }
}

fn finite(name: &str, x: f64) -> Result<f64, String> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("{name} = {x}: must be finite"))
    }
}

impl Slave for ShearFrameSlave {
    type State = State;

    fn description() -> &'static ModelDescription {
        &SHEAR_FRAME
    }

    fn guid() -> &'static str {
        crate::GUID
    }

    fn new(values: Values<'_>, setup: &Setup) -> Result<Self, String> {
        let n = values.integer(vr::N);
        if !(1..=MAX_STOREYS as i32).contains(&n) {
            return Err(format!(
                "n = {n}: the frame must have 1 to {MAX_STOREYS} storeys"
            ));
        }
        let n = n as usize;
        let m: Vec<f64> = floors(n).map(|i| values.real(vr::at(vr::M, i))).collect();
        let k: Vec<f64> = floors(n).map(|i| values.real(vr::at(vr::K, i))).collect();
        let damping = match values.integer(vr::DAMPING) {
            enums::MODAL => Damping::Modal {
                zeta: values.real(vr::ZETA),
            },
            enums::RAYLEIGH => Damping::Rayleigh {
                alpha: values.real(vr::RAYLEIGH_ALPHA),
                beta: values.real(vr::RAYLEIGH_BETA),
            },
            d => return Err(format!("damping = {d}: not an item of DampingKind")),
        };
        let frame = Frame::new(&m, &k, damping)?;
        let mut state = State::at_rest(setup.start_time);
        for i in 1..=MAX_STOREYS {
            let u = values.real(vr::at(vr::U, i));
            let v = values.real(vr::at(vr::V, i));
            if i <= n {
                state.u[i - 1] = finite(&format!("u[{i}]"), u)?;
                state.v[i - 1] = finite(&format!("v[{i}]"), v)?;
            } else if u != 0.0 || v != 0.0 {
                return Err(format!(
                    "u[{i}] = {u} m, v[{i}] = {v} m/s: the frame has n = {n} floors (the start values past n must be 0)"
                ));
            }
        }
        Ok(ShearFrameSlave {
            frame,
            state,
            propagators: Vec::new(),
        })
    }

    fn get_real(&mut self, r: u32, inputs: Inputs<'_>) -> Result<f64, String> {
        let n = self.frame.n();
        let (base, i) = vr::split(r);
        if !(1..=MAX_STOREYS).contains(&i) {
            return Err(format!("no computed Real with value reference {r}"));
        }
        if i > n {
            return Ok(0.0);
        }
        let x = match base {
            vr::U => self.state.u[i - 1],
            vr::V => self.state.v[i - 1],
            vr::A => self
                .frame
                .absolute_acceleration(&self.state, &load(inputs, n, false))[i - 1],
            vr::DRIFT => self.frame.drifts(&self.state.u)[i - 1],
            vr::PERIOD => self.frame.periods()[i - 1],
            _ => return Err(format!("no computed Real with value reference {r}")),
        };
        if !x.is_finite() {
            return Err(format!("the value is {x} (floating-point overflow)"));
        }
        Ok(x)
    }

    fn output_derivative(&mut self, r: u32, order: i32, inputs: Inputs<'_>) -> Result<f64, String> {
        let n = self.frame.n();
        let k = match order {
            1 | 2 => order as usize - 1,
            _ => return Err(format!("derivative order {order} is not 1 or 2")),
        };
        let (base, i) = vr::split(r);
        if !(1..=MAX_STOREYS).contains(&i) || !matches!(base, vr::U | vr::V | vr::A | vr::DRIFT) {
            return Err(format!("no Real output with value reference {r}"));
        }
        if i > n {
            return Ok(0.0);
        }
        let rates = self
            .frame
            .rates(&self.state, &load(inputs, n, false), &load(inputs, n, true));
        let x = match base {
            vr::U => rates.u[k][i - 1],
            vr::V => rates.v[k][i - 1],
            vr::A => rates.a[k][i - 1],
            _ => rates.u[k][i - 1] - if i > 1 { rates.u[k][i - 2] } else { 0.0 },
        };
        if !x.is_finite() {
            return Err(format!("the value is {x} (floating-point overflow)"));
        }
        Ok(x)
    }

    fn do_step(
        &mut self,
        _t: f64,
        h: f64,
        inputs: Inputs<'_>,
        _log: &mut EventLog,
    ) -> Result<StepEnd, String> {
        let n = self.frame.n();
        for i in n + 1..=MAX_STOREYS {
            let r = vr::at(vr::FX, i);
            let (f, df) = (inputs.real(r), inputs.derivative(r));
            if f != 0.0 || df != 0.0 {
                return Err(format!(
                    "Fx[{i}] = {f} N (derivative {df} N/s): the frame has n = {n} floors"
                ));
            }
        }
        let value = load(inputs, n, false);
        let rate = load(inputs, n, true);
        let mut s = self.state;
        self.propagator(h).step(&mut s, &value, &rate);
        if !(s.u.iter().chain(&s.v).all(|x| x.is_finite()) && s.t.is_finite()) {
            return Err(format!(
                "the step produced a non-finite state at t = {} (inputs too large)",
                s.t
            ));
        }
        self.state = s;
        Ok(StepEnd::Completed)
    }

    fn state(&self) -> State {
        self.state
    }

    fn set_state(&mut self, state: State) {
        self.state = state;
    }

    fn write_state(s: &State, w: &mut ByteWriter) {
        // Destructured: a new field in State breaks the build here, not the format.
        let State { t, u, v } = *s;
        w.u32(STATE_VERSION);
        w.f64(t);
        for x in u.iter().chain(&v) {
            w.f64(*x);
        }
    }

    fn read_state(r: &mut ByteReader<'_>) -> Result<State, ReadError> {
        let version = r.u32("state version")?;
        if version != STATE_VERSION {
            return Err(format!(
                "shear-frame state version {version}, this FMU reads version {STATE_VERSION}"
            ));
        }
        let mut s = State::at_rest(r.f64("t")?);
        for x in s.u.iter_mut() {
            *x = r.f64("u")?;
        }
        for x in s.v.iter_mut() {
            *x = r.f64("v")?;
        }
        if !(s.t.is_finite() && s.u.iter().chain(&s.v).all(|x| x.is_finite())) {
            return Err("a time, displacement or velocity is not finite".into());
        }
        Ok(s)
    }
}
