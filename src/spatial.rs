//! Round bodies in space on a rigid bed (docs/model.md §10) and on the
//! flexible and crushing bed (§11): rocking, wobbling and rolling under both
//! horizontal components of the ground motion and the vertical one.
//!
//! An axisymmetric body (a solid or hollow circle's base, the planar
//! model's mass models) touches the bed at one point of its rim, rolls
//! there without slip and may turn freely about the vertical there (a point
//! contact carries no moment): three rotational degrees of freedom, the
//! centre of mass following the contact. It reuses the planar model's
//! parameters and validation ([`Params`]), its body values ([`Body`]),
//! its restitution and rest rules and its Runge-Kutta tableau; the state
//! and the loop are its own (`y` has seven components, see `eom`).
//!
//! - `frame`: the tilted body's geometry and the contact on the rim;
//! - `pivot`: on a flexible bed, where the bed's resultant acts and how it
//!   moves (docs/model.md §11.2);
//! - `eom`: the balance of angular momentum about the contact (or the
//!   resultant);
//! - `impact`: the return of the base to the rigid bed;
//! - `bed`: a flexible bed's events (the tilt's minimum, the contact's
//!   kinks, overturning, rest; docs/model.md §11.3);
//! - `run`: the stepping loop, its events (the tilt crossing upright,
//!   overturning) and rest;
//! - [`continuous`]: Model Exchange, the same motion as a host's solver
//!   integrates it (derivatives, event indicators, the event update), on
//!   every bed.
//!
//! [`Body`]: crate::body::Body

mod bed;
pub mod continuous;
mod eom;
mod frame;
mod impact;
mod pivot;
mod run;
mod step;

pub use continuous::SpatialUpdate;
pub use run::{SpatialEvents, UPRIGHT};

use nalgebra::Vector3;

use crate::dynamics::{Simulator, VerticalInput};
use crate::model::{MassKind, Model, ParamError, Params, Restitution, RestraintKind, ShapeKind};
use crate::shape::Shape;

/// The horizontal ground acceleration over one call,
/// `a(t) = a + da (t - t0)` with `t0` the state's time at the call, m/s² and
/// m/s³, components along the ground's `x` and `y`.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct PlanInput {
    pub a: [f64; 2],
    pub da: [f64; 2],
}

/// A round body on its bed (rigid, elastic or elastoPlastic), ready to run.
#[derive(Clone, Debug)]
pub struct Spatial {
    /// The planar model of the same parameters (its body, `eta`, `alpha`).
    pub model: Model,
    pub restitution: Restitution,
    /// Base radius `R`, m.
    pub radius: f64,
    /// Inertia about the body's axis through the centre of mass `C`, kg m².
    pub c_axial: f64,
    /// The most steps (accepted and rejected) one `advance` may take;
    /// `None`: no limit. Past it the call returns early
    /// ([`SpatialEvents::limited`]).
    pub max_steps: Option<u32>,
    /// The planar simulator of the same model: its tolerances and rest bound.
    planar: Simulator,
}

impl Spatial {
    /// The body of `params` (a solid or hollow circle on any of the three
    /// beds, rocking both ways) with the relative tolerance `rtol` (as
    /// [`Simulator::new`]). `ic_axial` (kg m²) is the inertia about the
    /// axis, required for the lumped mass model; a prism's is
    /// `m (Is_polar / A)` of its section.
    pub fn new(params: &Params, ic_axial: Option<f64>, rtol: f64) -> Result<Spatial, ParamError> {
        let model = params.build()?;
        let radius = match *model.interface.shape() {
            Shape::SolidCircle { ro } | Shape::HollowCircle { ro, .. } => ro,
            _ => {
                return Err(error(
                    "shape",
                    params.shape as i32 as f64,
                    "a body in space needs a round base (solidCircle or hollowCircle)",
                ))
            }
        };
        if params.restraint != RestraintKind::None {
            return Err(error("restraint", 1.0, "a body in space rocks every way"));
        }
        let mass = model.body.mass;
        let c_axial = match (params.mass_model, ic_axial) {
            (_, Some(c)) if c.is_finite() && c > 0.0 => c,
            (_, Some(c)) => return Err(error("icAxial", c, "must be finite and > 0")),
            // the section's polar moment is twice its second moment for a circle
            (MassKind::Prism, None) => {
                let s = model.interface.shape();
                mass * 2.0 * s.second_moment() / s.area()
            }
            (MassKind::Lumped, None) => {
                return Err(error(
                    "icAxial",
                    f64::NAN,
                    "the lumped mass model needs the inertia about the axis",
                ))
            }
        };
        debug_assert!(matches!(
            params.shape,
            ShapeKind::SolidCircle | ShapeKind::HollowCircle
        ));
        Ok(Spatial {
            model,
            restitution: params.restitution,
            radius,
            c_axial,
            max_steps: None,
            planar: Simulator::new(model, rtol),
        })
    }

    /// Whether the bed is flexible (`elastic` or `elastoPlastic`,
    /// docs/model.md §11): the body turns about the bed's resultant.
    pub fn flexible(&self) -> bool {
        self.model.interface.law() != crate::interface::Law::Rigid
    }

    /// Mass, kg.
    pub fn mass(&self) -> f64 {
        self.model.body.mass
    }

    /// Kinetic plus potential energy in a still ground frame, J:
    /// `omega^T J omega / 2 + W zG` with `zG` the centre of mass's height
    /// (on a flexible bed, its rise from upright rest, `J` about the bed's
    /// resultant).
    pub fn energy(&self, st: &SpatialState) -> f64 {
        if self.flexible() {
            return self.energy_on_bed(st);
        }
        let f = frame::Frame::at(
            st.e,
            st.contact_direction(),
            self.radius,
            self.model.body.hg,
        );
        let (a, c) = (self.model.body.ic, self.c_axial);
        let ig = nalgebra::Matrix3::identity() * a + (c - a) * f.e3 * f.e3.transpose();
        let j = impact::inertia_about(&ig, self.mass(), &f.r);
        let w = Vector3::from(st.omega);
        0.5 * w.dot(&(j * w)) + self.model.body.weight * f.height()
    }

    /// [`energy`](Self::energy) on a flexible bed: the inertia about the
    /// resultant, and the centre of mass's rise from upright rest
    /// `∫ hW dtheta` at the weight (docs/model.md §11.2), J.
    fn energy_on_bed(&self, st: &SpatialState) -> f64 {
        let w = Vector3::from(st.omega);
        let n = self.model.body.weight;
        let l = self.lever(st.e, &w, (n, 0.0), st.contact_direction());
        let (a, c) = (self.model.body.ic, self.c_axial);
        let ig = nalgebra::Matrix3::identity() * a + (c - a) * l.e3 * l.e3.transpose();
        let j = impact::inertia_about(&ig, self.mass(), &l.r);
        let rise = self.lean(st.theta()).1;
        0.5 * w.dot(&(j * w)) + n * rise
    }

    /// The bed's force on the body at the state (N, ground axes), under
    /// the ground accelerations `ag` (horizontal) and `av` (vertical), m/s².
    pub fn contact_force(&self, st: &SpatialState, ag: [f64; 2], av: f64) -> [f64; 3] {
        if st.at_rest {
            let b = &self.model.body;
            return [-b.mass * ag[0], -b.mass * ag[1], b.mass * (b.g + av)];
        }
        let input = PlanInput {
            a: ag,
            da: [0.0; 2],
        };
        let vertical = VerticalInput { av, dav: 0.0 };
        let eom = eom::Eom::new(self, st.t, input, vertical);
        let f = eom
            .rates_and_force(st.t, &st.to_y(), st.contact_direction())
            .force;
        [f.x, f.y, f.z]
    }
}

fn error(variable: &'static str, value: f64, condition: &str) -> ParamError {
    ParamError {
        variable,
        value,
        condition: condition.into(),
    }
}

/// Everything that determines the future of a spatial run; plain data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpatialState {
    /// Time, s.
    pub t: f64,
    /// The tilt: the horizontal part of the body's axis, `sin(theta)` times
    /// the direction the body leans (and its contact lies) in.
    pub e: [f64; 2],
    /// Angular velocity, rad/s, ground axes.
    pub omega: [f64; 3],
    /// Horizontal position of the centre of mass, m (0 at rest at the start).
    pub xg: [f64; 2],
    /// Direction of the contact (unit): kept when the body is upright, where
    /// the tilt does not tell it.
    pub pivot: [f64; 2],
    /// Impacts so far: returns of the base to the bed. On a flexible bed,
    /// each application of the restitution rule at the tilt's minimum
    /// (docs/model.md §11.3): the planar model's `zeroCrossings`.
    pub impacts: u64,
    pub at_rest: bool,
    /// The tilt reached the overturning limit; the run is over.
    pub overturned: bool,
    /// The input left the model's range (`g + av <= 0`); the run is over.
    pub out_of_range: bool,
    /// The integrator's next step, s (0: choose afresh).
    pub h: f64,
}

impl SpatialState {
    /// At rest upright at `t = 0`.
    pub fn at_rest() -> SpatialState {
        SpatialState {
            t: 0.0,
            e: [0.0; 2],
            omega: [0.0; 3],
            xg: [0.0; 2],
            pivot: [1.0, 0.0],
            impacts: 0,
            at_rest: true,
            overturned: false,
            out_of_range: false,
            h: 0.0,
        }
    }

    /// Tilted by `theta` (rad, > 0) toward the azimuth `psi` (rad from `+x`
    /// toward `+y`) about its rim, moving with `omega` (rad/s, ground axes):
    /// the centre of mass where a tilt from upright about that rim point puts
    /// it. `theta < 0` leans toward `psi + pi`, as the planar model's sign.
    pub fn tilted(body: &Spatial, theta: f64, psi: f64, omega: [f64; 3]) -> SpatialState {
        let (s, c) = theta.sin_cos();
        let (sp, cp) = psi.sin_cos();
        let d = if theta >= 0.0 { [cp, sp] } else { [-cp, -sp] };
        let lean = if body.flexible() {
            body.lean(theta.abs()).0
        } else {
            body.radius * (1.0 - c) + body.model.body.hg * s.abs()
        };
        SpatialState {
            e: [s * cp, s * sp],
            omega,
            xg: [lean * d[0], lean * d[1]],
            pivot: d,
            at_rest: theta == 0.0 && omega == [0.0; 3],
            ..SpatialState::at_rest()
        }
    }

    /// Tilt `theta = asin(|e|)`, rad.
    pub fn theta(&self) -> f64 {
        self.e[0].hypot(self.e[1]).asin()
    }

    /// Direction of the contact (unit): the tilt's, or within
    /// [`UPRIGHT`] of upright the contact's direction kept from before
    /// (round-off decides the tilt's direction there).
    pub fn contact_direction(&self) -> [f64; 2] {
        let s = self.e[0].hypot(self.e[1]);
        if s > run::UPRIGHT {
            [self.e[0] / s, self.e[1] / s]
        } else {
            self.pivot
        }
    }

    fn to_y(self) -> [f64; eom::N] {
        let [ex, ey] = self.e;
        let [wx, wy, wz] = self.omega;
        [ex, ey, wx, wy, wz, self.xg[0], self.xg[1]]
    }

    fn set_y(&mut self, y: &[f64; eom::N]) {
        self.e = [y[0], y[1]];
        self.omega = [y[2], y[3], y[4]];
        self.xg = [y[5], y[6]];
    }
}
