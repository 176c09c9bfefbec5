//! Equations of motion, impacts, rest and overturning (MODEL.md §3).
//!
//! API sketch, to be implemented (issue 3). The FMU calls `advance` once per
//! communication step and `outputs` for its output variables.

use crate::interface::Regime;
use crate::model::Model;

/// Everything that determines the future of a run. `Copy`, plain data, so
/// the FMU can save, restore and serialize it bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    /// Time, s.
    pub t: f64,
    /// Rotation, rad (positive about the +x toe).
    pub theta: f64,
    /// Angular velocity, rad/s.
    pub omega: f64,
    /// Impacts so far.
    pub impacts: u64,
    /// At rest on the base (rigid law): stays there until uplift.
    pub at_rest: bool,
    /// Overturned: |theta| reached thetaOv; the run is over.
    pub overturned: bool,
    /// The integrator's suggested next step, s (0: choose afresh).
    pub h: f64,
}

/// Ground acceleration over one communication step: `ag(t) = ag + dag * (t - t0)`,
/// m/s² and m/s³, with `t0` the step's start.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct GroundInput {
    pub ag: f64,
    pub dag: f64,
}

/// What happened during one `advance`.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Events {
    pub impacts: u32,
    pub uplift: bool,
    pub came_to_rest: bool,
    /// Time of overturning, s, if it happened in this step.
    pub overturned_at: Option<f64>,
}

/// Output quantities at a state (MODEL.md §5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outputs {
    /// Angular acceleration, rad/s².
    pub theta_dd: f64,
    pub af: f64,
    pub contact_length: f64,
    /// Restoring moment W hW, N m.
    pub mr: f64,
    pub regime: Regime,
    /// Forces of the support on the body, N.
    pub fx: f64,
    pub fz: f64,
}

/// The integrator for one model at a relative tolerance.
#[derive(Clone, Debug)]
pub struct Simulator {
    pub model: Model,
    pub rtol: f64,
}

impl Simulator {
    pub fn new(model: Model, rtol: f64) -> Simulator {
        Simulator { model, rtol }
    }

    pub fn initial_state(&self, theta0: f64, omega0: f64) -> State {
        State {
            t: 0.0,
            theta: theta0,
            omega: omega0,
            impacts: 0,
            at_rest: false,
            overturned: false,
            h: 0.0,
        }
    }

    /// Integrate from `state.t` to `t_end` (or to overturning) under `input`.
    pub fn advance(&self, _state: &mut State, _t_end: f64, _input: GroundInput) -> Events {
        unimplemented!("issue 3")
    }

    /// Outputs at `state` under ground acceleration `ag` (m/s²).
    pub fn outputs(&self, _state: &State, _ag: f64) -> Outputs {
        unimplemented!("issue 3")
    }
}
