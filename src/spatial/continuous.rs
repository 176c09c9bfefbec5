//! Model Exchange of the round body in space: the motion as a host's own
//! solver integrates it (docs/round-body.md, "Model Exchange"), on the
//! rigid bed (docs/model.md §10) and on the flexible and crushing beds
//! (§11.5). The host integrates the seven continuous states with
//! [`Spatial::derivatives_weight_referred`], watches [`Spatial::event_indicators`] for sign
//! changes and, at each one, calls [`Spatial::event_update`]; this module
//! only evaluates. The equation of motion is the one the co-simulation
//! integrator steps (`eom`), the events are the co-simulation's
//! (`Spatial::apply`, `upright_pass`, `comes_to_rest`, `lifts_at`).
//!
//! The continuous states are `y = (ex, ey, omegaWX, omegaWY, omegaWZ, xG,
//! yG)` on every bed ([`Spatial::to_weight_referred`], then
//! [`SpatialState::continuous_states`]), `omegaW` the angular velocity
//! referred to the weight (below), `omega` itself but for `shiftingPivot`
//! on a flexible bed under a vertical input; their rates are
//! [`Spatial::derivatives_weight_referred`]. The discrete state is the
//! contact side `pivot`, held between events: the rates are those of the
//! contact on the side of `pivot`, so a tilt that crosses upright goes on
//! about the old contact, smoothly, until the host locates the crossing
//! (co-simulation holds it over one of its steps). Indicators and event
//! updates take the body's state (`omega`, [`Spatial::from_weight_referred`]).
//!
//! Event indicators (a state event where one changes sign), in this order
//! (rigid bed / flexible bed where they differ):
//!
//! | index | indicator | event |
//! |---|---|---|
//! | 0 | `e . pivot` while the body moves, else 1 | the tilt turned a right angle from the contact side. Rigid: an impact if `|e x pivot| <= UPRIGHT` (it crossed upright in a plane), else the contact runs on round the rim (`pivot = e/|e|`). Flexible: the planar restitution rule if the heel is closed there, then rest if it settles (docs/model.md §11.3) |
//! | 1 | rigid `sin²(alpha) - |e|²`; flexible `hW/(hG sin(theta))` at `N = m (g + av)` | overturning: the run ends |
//! | 2 | at rest: rigid `(g + av) tan(alpha) (1 + 1e-12) - |ag|`, flexible `1` while `ag = 0` else `-1`; moving: 1 | uplift / leaving rest: the body tips toward `-ag/|ag|` |
//! | 3 | rigid `N/W = (g + av)/g`; flexible the smallest relative margin of `N` to `liftOff`, `restUnstable`, `baseCrushing` | out of range (docs/model.md §6.5): the run ends |
//!
//! The contact's kinks on a flexible bed (joint opening, crushing onset, a
//! ring's inner edge; the restarts of co-simulation) are no indicators: the
//! derivatives are continuous there (the resultant's distance `rho` and its
//! slope `af'` are; only `af''` jumps), so a host's error control sees a
//! kink in the rates' slope only.
//!
//! Under Model Exchange the host gives no input derivatives: `dN/dt =
//! m dav/dt` is unknown. It enters only `shiftingPivot` on a flexible bed
//! (the resultant sliding along the base as `N` changes, the spatial form
//! of the planar `dI/dN dN/dt`, docs/model.md §6.2), whose velocity state
//! is therefore `omegaW = M(rho_W)^-1 M(rho) omega` (`referral`, docs/
//! model.md §11.5): its rate needs the tilt and `N` only, and it is
//! `omega` where `N = W`. [`Spatial::derivatives`] is the rate of `omega`
//! with `dN/dt` taken as 0; `costa` and the rigid bed have no such term,
//! and there `omegaW` is `omega` bit for bit.
//!
//! After overturning or leaving the range every indicator is 1 and the
//! derivatives are 0; at rest the derivatives are 0 (the states frozen)
//! until uplift.

mod referral;

use super::eom::{Eom, N};
use super::run::Cut;
use super::{PlanInput, Spatial, SpatialEvents, SpatialState};
use crate::dynamics::VerticalInput;

/// Number of continuous states.
pub const STATES: usize = N;
/// Number of event indicators (see the module doc).
pub const EVENT_INDICATORS: usize = 4;

/// The tilt (`sin(theta)`) an impact or an uplift leaves along the new
/// contact side instead of 0, so that indicator 0 starts positive: a
/// repeated or spurious event update there then finds no crossing. Its
/// effect on the motion is below any tolerance (the rates at `|e| <=
/// UPRIGHT` are the upright ones).
const OFF_ZERO: f64 = 1e-300;

/// How far past the uplift threshold, relative, indicator 2 reaches zero:
/// at the threshold itself the tilting moment is zero to round-off, so an
/// event update where a host located the zero exactly would find the body
/// not yet tilting and leave it at rest, with the indicator then negative
/// and no sign change to come. A relative `1e-12` puts the moment at some
/// `1e4` times its round-off; uplift moves by `1e-12` of the threshold over
/// the rate of `|ag|` (co-simulation lifts at the first float at which the
/// equation tilts the body, docs/model.md §10.4).
const UPLIFT_MARGIN: f64 = 1e-12;

/// What an event update did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SpatialUpdate {
    /// The continuous states changed (the host must re-read them).
    pub states_changed: bool,
    /// An impact was applied (the base returned to the bed).
    pub impact: bool,
    /// The contact ran on round the rim (a quarter turn, or the tilt passing
    /// upright off a plane): `pivot` changed, the states did not.
    pub rolled_on: bool,
    pub came_to_rest: bool,
    pub uplift: bool,
    /// The body overturned: the run is over.
    pub overturned: bool,
    /// `g + av` reached 0 (liftOff): the run is over.
    pub out_of_range: bool,
}

impl SpatialState {
    /// The continuous states `(ex, ey, omegaX, omegaY, omegaZ, xG, yG)`:
    /// 1, 1, rad/s (three), m (two); Model Exchange's where `omega` holds
    /// `omegaW` ([`Spatial::to_weight_referred`]).
    pub fn continuous_states(&self) -> [f64; STATES] {
        self.to_y()
    }

    /// Sets the continuous states (as
    /// [`continuous_states`](Self::continuous_states)); the discrete state
    /// is kept.
    pub fn set_continuous_states(&mut self, y: &[f64; STATES]) {
        self.set_y(y);
    }
}

impl Spatial {
    /// On a flexible bed, the relative lever of the weight about the
    /// resultant, `hW/(hG sin(theta))` at `N = m (g + av)`: 0 at overturning.
    fn overturn_indicator(&self, st: &SpatialState, eom: &Eom) -> f64 {
        let n = self.weight_at(eom, st.t);
        self.overturn_margin(&st.to_y(), n) / self.model.body.hg
    }

    /// The right-hand side under the inputs at `t` held (the host gives no
    /// input derivatives under Model Exchange).
    fn eom_at(&self, t: f64, ag: [f64; 2], av: f64) -> Eom<'_> {
        Eom::new(
            self,
            t,
            PlanInput {
                a: ag,
                da: [0.0; 2],
            },
            VerticalInput { av, dav: 0.0 },
        )
    }

    /// `dy/dt` at `st` (its time) under the ground accelerations `ag`
    /// (horizontal) and `av` (vertical), m/s²: the equation of motion with
    /// the contact on the side of `st.pivot`; zero at rest, after
    /// overturning and after lift-off, whatever states the host sets.
    pub fn derivatives(&self, st: &SpatialState, ag: [f64; 2], av: f64) -> [f64; STATES] {
        if st.at_rest || st.overturned || st.out_of_range {
            return [0.0; STATES];
        }
        self.eom_at(st.t, ag, av).rates(st.t, &st.to_y(), st.pivot)
    }

    /// The event indicators at `st` under `ag`, `av` (see the module doc).
    pub fn event_indicators(
        &self,
        st: &SpatialState,
        ag: [f64; 2],
        av: f64,
    ) -> [f64; EVENT_INDICATORS] {
        let mut z = [1.0; EVENT_INDICATORS];
        if st.overturned || st.out_of_range {
            return z;
        }
        let b = &self.model.body;
        let [ex, ey] = st.e;
        z[3] = self.model.range_margin(av);
        if self.flexible() {
            // beyond the range N is no bed's: the lever is not evaluated
            if z[3] > 0.0 && !st.at_rest {
                z[1] = self.overturn_indicator(st, &self.eom_at(st.t, ag, av));
            }
            if st.at_rest {
                // any horizontal input moves a body on a flexible bed (§3)
                z[2] = if ag == [0.0; 2] { 1.0 } else { -1.0 };
            } else {
                z[0] = ex * st.pivot[0] + ey * st.pivot[1];
            }
            return z;
        }
        z[1] = b.sin_alpha * b.sin_alpha - (ex * ex + ey * ey);
        if st.at_rest {
            z[2] = (b.g + av) * (b.b / b.hg) * (1.0 + UPLIFT_MARGIN) - ag[0].hypot(ag[1]);
        } else {
            z[0] = ex * st.pivot[0] + ey * st.pivot[1];
        }
        z
    }

    /// The event update at `st` (its time) under `ag`, `av`: lift-off,
    /// overturning, uplift from rest, or the crossing of indicator 0,
    /// whichever the state shows, with co-simulation's rules
    /// (`Spatial::advance`). The state is examined, not the indicator that
    /// fired, so a repeated or a spurious call changes nothing.
    ///
    /// At a crossing the host has located to its tolerance, `e` is not 0:
    /// the impact criterion is `|e x pivot| <= UPRIGHT` (the tilt's part off
    /// the line of the contact side), the one co-simulation uses at its own
    /// crossings.
    pub fn event_update(&self, st: &mut SpatialState, ag: [f64; 2], av: f64) -> SpatialUpdate {
        let mut u = SpatialUpdate::default();
        if st.overturned || st.out_of_range {
            return u;
        }
        if self.model.range_margin(av) <= 0.0 {
            st.out_of_range = true;
            u.out_of_range = true;
            return u;
        }
        let eom = self.eom_at(st.t, ag, av);
        let mut ev = SpatialEvents::default();
        if st.at_rest {
            if let Some(pivot) = self.leaves_rest(&eom, st.t, ag) {
                leave_rest(st, pivot, &mut u);
            }
            return u;
        }
        if self.past_overturning(st, &eom) {
            self.apply(st, Cut::Overturning, &eom, &mut ev);
            u.overturned = true;
            return u;
        }
        if !crossed(st) {
            return u;
        }
        let before = st.pivot;
        if self.flexible() {
            self.upright_pass(st, &eom, &mut ev);
        } else {
            self.apply(st, Cut::Quarter, &eom, &mut ev);
        }
        if ev.impacts == 0 {
            u.rolled_on = st.pivot != before;
            return u;
        }
        u.impact = true;
        u.states_changed = true;
        u.came_to_rest = ev.came_to_rest;
        if !self.flexible() && !st.at_rest {
            // the rigid rule leaves the tilt at 0: started along the new side
            st.e = [OFF_ZERO * st.pivot[0], OFF_ZERO * st.pivot[1]];
        }
        u
    }

    /// After an accepted step of the host at `st` under `ag`, `av`: whether
    /// an event is due that no indicator's sign change showed (a crossing
    /// or an overturning inside one step, or at rest an uplift whose
    /// indicator changed sign where round-off still held the body), so that
    /// the host must enter event mode.
    pub fn completed_step(&self, st: &SpatialState, ag: [f64; 2], av: f64) -> bool {
        if st.overturned || st.out_of_range {
            return false;
        }
        if self.model.range_margin(av) <= 0.0 {
            return true;
        }
        let eom = self.eom_at(st.t, ag, av);
        if st.at_rest {
            return self.leaves_rest(&eom, st.t, ag).is_some();
        }
        self.past_overturning(st, &eom) || crossed(st)
    }

    /// At rest, the side toward which the body leaves it under `ag`, if it
    /// does: on the rigid bed where the uplift condition holds
    /// (`lifts_at`), on a flexible bed under any horizontal input, toward
    /// `-ag/|ag|` (docs/model.md §3).
    fn leaves_rest(&self, eom: &Eom, t: f64, ag: [f64; 2]) -> Option<[f64; 2]> {
        if !self.flexible() {
            return self.lifts_at(eom, t);
        }
        let a = ag[0].hypot(ag[1]);
        (a > 0.0).then(|| [-ag[0] / a, -ag[1] / a])
    }

    /// Whether the moving body at `st` is at or past overturning: on the
    /// rigid bed `|e| >= sin(alpha)`, on a flexible bed the lever of the
    /// weight about the resultant at or below 0.
    fn past_overturning(&self, st: &SpatialState, eom: &Eom) -> bool {
        if self.flexible() {
            return self.overturn_indicator(st, eom) <= 0.0;
        }
        let [ex, ey] = st.e;
        let sin_alpha = self.model.body.sin_alpha;
        ex * ex + ey * ey >= sin_alpha * sin_alpha
    }

    /// Nominal values of the continuous states: the planar model's scales
    /// of the motion, `thetaOv` for the tilt, `p thetaOv` for the angular
    /// velocity and `R0 thetaOv` for the centre of mass (1, rad/s, m).
    pub fn nominals(&self) -> [f64; STATES] {
        let (th, om) = self.planar.scales();
        let x = self.model.body.r0 * th;
        [th, th, om, om, om, x, x]
    }
}

/// The tilt has turned a right angle from the contact side (or crossed
/// upright): `e . pivot <= 0`, not at exactly zero tilt (upright at an
/// impact's own instant, before the host has moved).
fn crossed(st: &SpatialState) -> bool {
    let [ex, ey] = st.e;
    ex * st.pivot[0] + ey * st.pivot[1] <= 0.0 && (ex != 0.0 || ey != 0.0)
}

/// The body leaves rest tipping toward `pivot` (unit, the contact side):
/// still, its tilt a hair off upright on that side.
fn leave_rest(st: &mut SpatialState, pivot: [f64; 2], u: &mut SpatialUpdate) {
    st.at_rest = false;
    st.pivot = pivot;
    st.omega = [0.0; 3];
    st.e = [OFF_ZERO * pivot[0], OFF_ZERO * pivot[1]];
    u.uplift = true;
    u.states_changed = true;
}
