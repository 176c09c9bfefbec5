//! Equations of motion, impacts, rest and overturning (docs/model.md §3), and the
//! integrator that the FMU calls once per communication step.
//!
//! - Equation of motion (docs/model.md §3), `phi = |theta|`, `s = sgn theta`:
//!   `I(phi) theta'' + (1/2) s I'(phi) omega² = -s W hW(phi) - m ag hg(phi)`
//!   (`shiftingPivot`; `costa` without the `omega²` term; rigid law: `af = 0`,
//!   `I = IO`). See `eom`.
//! - Sign of the ground input: `ag` is the ground acceleration along `+x`, the
//!   direction of the `theta > 0` toe. A positive `ag` pushes the body back,
//!   onto its `-x` toe: from rest, `ag < -g tan(alpha)` lifts it toward
//!   `theta > 0` and `ag > g tan(alpha)` toward `theta < 0`.
//! - Integrator: adaptive embedded Runge-Kutta ([`Method`]): Dormand-Prince
//!   8(5,3) by default, 5(4) available; every call ends exactly at `t_end`;
//!   the ground input is linear inside the call, so its kinks at call
//!   boundaries are never stepped over.
//! - Events: zero crossings of `theta` (impacts, `omega <- eta omega`, for every
//!   law: docs/model.md applies the rule at each crossing) and `|theta| = thetaOv`
//!   (overturning, the run ends) are located on the step's dense output (a
//!   quintic Hermite interpolant), the step is redone to end exactly at the
//!   event and polished by Newton on the step itself.
//! - Counts: every crossing is a zero crossing; it is an impact (a return
//!   after an uplift) if `|theta|` exceeded `thetaJo` since the previous one,
//!   peaks inside a step included (turning points on the dense output).
//! - Rest (rigid law): an impact after which the chattering that remains is
//!   below the tolerance ends the motion ([`Simulator::rest_bound`]); a body at
//!   rest costs O(1) per call until `|ag| > g tan(alpha)` (uplift, found in
//!   closed form on the linear input).
//!
//! See `docs/dynamics.md` for the measurements behind these choices.

// The integrator, one concern a file: `integrate` (the loop of one call and
// its step context), `controller` (step sizes), `stiffness` (explicit pair
// or RODAS), `kinks` (where steps are cut), `events` (impacts, overturning,
// rest), `dense` (the interpolant events are located on), `erk` and `rodas`
// (the methods), `eom` (the right-hand side), `outputs` and `output_rates`.
pub(crate) mod controller;
mod dense;
mod eom;
pub(crate) mod erk;
mod events;
mod free;
mod integrate;
mod kinks;
mod loaded_rates;
mod output_rates;
mod outputs;
mod rodas;
mod stiffness;
mod thresholds;
mod work;

pub mod continuous;

pub use output_rates::{Jet, OutputRates};
pub use work::{Limited, WorkLimit};

use crate::interface::{Contact, ContactTable, Law, Regime};
use crate::model::Model;
use std::sync::Arc;

use erk::Tol;
use kinks::Kinks;

/// Relative tolerance used when the caller gives none (or a non-positive
/// one): `1e-9` (global errors of impact times and amplitudes
/// measured at about half of it, docs/dynamics.md).
pub const DEFAULT_RTOL: f64 = 1e-9;
/// Tolerances are clamped to `[MIN_RTOL, MAX_RTOL]`.
pub const MIN_RTOL: f64 = 1e-13;
pub const MAX_RTOL: f64 = 1e-2;

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
    /// Impacts so far: returns to `theta = 0` after an uplift, the zero
    /// crossings after which `|theta|` had exceeded `thetaJo` (the joint
    /// had opened) since the previous crossing or the start. Rigid law
    /// (`thetaJo = 0`): every zero crossing.
    pub impacts: u64,
    /// Zero crossings of `theta` so far (each applies the restitution rule).
    pub zero_crossings: u64,
    /// `|theta|` has exceeded `thetaJo` since the last zero crossing (or the
    /// start): the next crossing is an impact.
    pub opened: bool,
    /// At rest on the base (rigid law): stays there until uplift.
    pub at_rest: bool,
    /// Overturned: |theta| reached thetaOv; the run is over.
    pub overturned: bool,
    /// The integrator's suggested next step, s (0: choose afresh).
    pub h: f64,
    /// Contact length parameter `a` of the last contact solve, m: the warm
    /// start of the next one (0: none). Part of the state so that a restored
    /// run repeats the same iterations.
    pub a: f64,
    /// The integrator is in its stiff mode (RODAS; flexible laws only).
    pub stiff: bool,
    /// Consecutive steps that argued for switching the mode.
    pub switch_count: u32,
}

/// Ground acceleration over one communication step: `ag(t) = ag + dag * (t - t0)`,
/// m/s² and m/s³, with `t0` the step's start (`state.t` when `advance` is called).
/// Positive along `+x`, the direction of the `theta > 0` toe.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct GroundInput {
    pub ag: f64,
    pub dag: f64,
}

/// Vertical ground acceleration over one call: `av(t) = av + dav (t - t0)`,
/// m/s² and m/s³, positive up (docs/model.md §6). Zero: the model of §3.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct VerticalInput {
    pub av: f64,
    pub dav: f64,
}

/// The conditions under which the model stops applying (docs/model.md §6.5);
/// they depend on the input only.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutOfRange {
    /// `N <= 0`: the body leaves the ground (free flight is not modelled).
    LiftOff,
    /// `N >= fm A`: the whole section crushes.
    BaseCrushing,
    /// `N hG >= kn Is`: the rest position is unstable (`thetaOv(N) = 0`).
    RestUnstable,
}

impl OutOfRange {
    /// The public name of the condition.
    pub fn name(self) -> &'static str {
        match self {
            OutOfRange::LiftOff => "liftOff",
            OutOfRange::BaseCrushing => "baseCrushing",
            OutOfRange::RestUnstable => "restUnstable",
        }
    }
}

/// Where and why a run left the model's range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Terminal {
    /// Time, s.
    pub t: f64,
    pub condition: OutOfRange,
    /// The vertical ground acceleration there, m/s².
    pub av: f64,
}

/// Work done by one call.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Stats {
    /// Accepted steps (including the steps redone to end at an event).
    pub steps: u32,
    /// Rejected steps.
    pub rejected: u32,
    /// Right-hand-side evaluations.
    pub evals: u32,
    /// Accepted steps taken in the stiff mode (RODAS).
    pub stiff_steps: u32,
}

/// What happened during one `advance`.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Events {
    /// Impacts (see [`State::impacts`]).
    pub impacts: u32,
    /// Zero crossings of `theta` (see [`State::zero_crossings`]).
    pub zero_crossings: u32,
    pub uplift: bool,
    pub came_to_rest: bool,
    /// Time of overturning, s, if it happened in this step.
    pub overturned_at: Option<f64>,
    /// Integrator work.
    pub stats: Stats,
    /// The call stopped at its work limit ([`Simulator::work_limit`])
    /// before `t_end`: where and why.
    pub limited: Option<Limited>,
    /// The input left the model's range (docs/model.md §6.5): the call
    /// ended there, and the run is over.
    pub terminal: Option<Terminal>,
    /// The call stopped at an event it was asked to stop at
    /// ([`Simulator::advance_to_event`]): `state.t` is the event's time,
    /// which may be `t_end` itself (an event within the last ulp of the
    /// call rounds to it), so `state.t < t_end` does not tell.
    pub stopped_at_event: bool,
}

impl Events {
    /// The work of the call so far: integrator steps, accepted and
    /// rejected, and zero crossings (those found in closed form cost no
    /// step).
    pub fn work(&self) -> u64 {
        self.stats.steps as u64 + self.stats.rejected as u64 + self.zero_crossings as u64
    }
}

/// Output quantities at a state (docs/model.md §5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outputs {
    /// Angular acceleration, rad/s².
    pub theta_dd: f64,
    pub af: f64,
    pub contact_length: f64,
    /// Restoring moment N hW, N m.
    pub mr: f64,
    pub regime: Regime,
    /// Forces of the support on the body, N.
    pub fx: f64,
    pub fz: f64,
    /// Apparent weight `N = m (g + av)`, N (docs/model.md §6.1).
    pub apparent_weight: f64,
}

impl Outputs {
    /// The friction coefficient the no-sliding assumption needs,
    /// `|Fx| / Fz` (docs/model.md §5, "Friction demand"); `+inf` when
    /// `Fz <= 0`, where the support would have to pull the body down.
    pub fn friction_demand(&self) -> f64 {
        friction_demand(self.fx, self.fz)
    }
}

/// `|fx| / fz`, or `+inf` when `fz <= 0` (docs/model.md §5, "Friction demand").
pub fn friction_demand(fx: f64, fz: f64) -> f64 {
    if fz > 0.0 {
        fx.abs() / fz
    } else {
        f64::INFINITY
    }
}

/// The Runge-Kutta pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Method {
    /// Dormand-Prince 5(4), 6 evaluations per step.
    Dp5,
    /// Dormand-Prince 8(5,3), 12 evaluations per step. Default.
    #[default]
    Dop853,
}

/// The integrator for one model at a relative tolerance.
#[derive(Clone, Debug)]
pub struct Simulator {
    pub model: Model,
    /// Relative tolerance (clamped to `[MIN_RTOL, MAX_RTOL]`, `DEFAULT_RTOL`
    /// if not positive and finite).
    pub rtol: f64,
    /// Runge-Kutta pair.
    pub method: Method,
    /// Whether the stiff mode (RODAS, flexible laws) may be entered; `true`
    /// by default, `false` keeps the explicit pair throughout (for
    /// measurements, docs/dynamics.md).
    pub stiff_mode: bool,
    /// The most work one call may do (`None` by default: no limit). Past
    /// it the call returns early with the state consistent at the time
    /// reached and [`Events::limited`] set.
    pub work_limit: Option<WorkLimit>,
    /// Kinks of the right-hand side (computed from `model` by `new`: a
    /// changed model needs a new simulator).
    kinks: Kinks,
    /// The contact solve tabulated up to `thetaOv` (flexible laws, built by
    /// `new`); `None`: every contact is solved.
    table: Option<Arc<ContactTable>>,
    /// The moving thresholds' bed resultants at the last two rotations
    /// asked for.
    threshold_limits: thresholds::LimitCache,
}

impl Simulator {
    pub fn new(model: Model, rtol: f64) -> Simulator {
        Simulator::with_method(model, rtol, Method::default())
    }

    /// The same with an explicit Runge-Kutta pair.
    pub fn with_method(model: Model, rtol: f64, method: Method) -> Simulator {
        Simulator {
            kinks: Kinks::of(&model),
            table: ContactTable::shared(&model.interface, model.theta_ov),
            model,
            rtol,
            method,
            stiff_mode: true,
            work_limit: None,
            threshold_limits: thresholds::LimitCache::default(),
        }
    }

    /// Whether contacts come from the table ([`ContactTable`], within about
    /// 1e-13 of the solve and a few times cheaper) where it answers, or are
    /// all solved (`false`: for measurements and comparisons).
    pub fn set_contact_table(&mut self, on: bool) {
        self.table = if on {
            ContactTable::shared(&self.model.interface, self.model.theta_ov)
        } else {
            None
        };
    }

    /// The table in use, if any.
    pub fn contact_table(&self) -> Option<&ContactTable> {
        self.table.as_deref()
    }

    /// The contact at `phi = |theta|` (rad, docs/model.md §2): from the
    /// table where it answers, else solved starting from `a_hint` (m; NaN
    /// for none).
    #[inline]
    pub fn contact(&self, phi: f64, a_hint: f64) -> Contact {
        let it = &self.model.interface;
        match self.table.as_ref().and_then(|t| t.contact(it, phi)) {
            Some(c) => c,
            None => it.contact_near(phi, a_hint),
        }
    }

    /// [`contact`](Self::contact) for the equation of motion: where the
    /// table answers, only `af` and `af'` (`a`, `a'` and the contact length
    /// are NaN). Always inlined, as is the table's `reaction`: with two
    /// callers (the flexible and the loaded equation of motion) the
    /// compiler left them out of line, a call at every evaluation that cost
    /// the `av = 0` path 5 % (callgrind, docs/performance.md).
    #[inline(always)]
    pub(crate) fn reaction(&self, phi: f64, a_hint: f64) -> Contact {
        let it = &self.model.interface;
        match self.table.as_ref().and_then(|t| t.reaction(it, phi)) {
            Some(c) => c,
            None => it.contact_near(phi, a_hint),
        }
    }

    /// [`reaction`](Self::reaction) and a bound on the contact's `a`, m
    /// ([`ContactTable::reaction_bounded`]; the solver's `a` where the
    /// table does not answer).
    #[inline(always)]
    pub(crate) fn reaction_bounded(&self, phi: f64, a_hint: f64) -> (Contact, f64) {
        let it = &self.model.interface;
        match self
            .table
            .as_ref()
            .and_then(|t| t.reaction_bounded(it, phi))
        {
            Some(found) => found,
            None => {
                let c = it.contact_near(phi, a_hint);
                (c, c.a)
            }
        }
    }

    pub fn initial_state(&self, theta0: f64, omega0: f64) -> State {
        let mut st = self.state_at_start(theta0, omega0);
        // docs/model.md §7.1: at theta = 0 moving into the restraint, a
        // restraint impact at t = 0
        if let Some(r) = self.model.restraint {
            if theta0 == 0.0 && r.side * omega0 < 0.0 {
                st.omega = -r.e * omega0;
                st.zero_crossings = 1;
                st.impacts = 1;
                st.opened = false;
                st.at_rest = st.omega == 0.0;
            }
        }
        st
    }

    fn state_at_start(&self, theta0: f64, omega0: f64) -> State {
        State {
            t: 0.0,
            theta: theta0,
            omega: omega0,
            impacts: 0,
            zero_crossings: 0,
            opened: theta0.abs() > self.model.interface.theta_jo(),
            at_rest: theta0 == 0.0 && omega0 == 0.0,
            overturned: false,
            h: 0.0,
            a: 0.0,
            stiff: false,
            switch_count: 0,
        }
    }

    /// The tolerance in use.
    pub fn effective_rtol(&self) -> f64 {
        if self.rtol.is_finite() && self.rtol > 0.0 {
            self.rtol.clamp(MIN_RTOL, MAX_RTOL)
        } else {
            DEFAULT_RTOL
        }
    }

    /// Scales of the motion: `(theta_ref, omega_ref)` = `(thetaOv, p thetaOv)`
    /// with `p = sqrt(W R0 / IO)` the rocking frequency parameter. The error
    /// of a step is measured relative to `|y| + y_ref`.
    pub fn scales(&self) -> (f64, f64) {
        let b = &self.model.body;
        let p = (b.weight * b.r0 / b.io).sqrt();
        (self.model.theta_ov, p * self.model.theta_ov)
    }

    /// Ground acceleration that uplifts a rigid body at rest, `g tan(alpha)`, m/s².
    pub fn uplift_acceleration(&self) -> f64 {
        let b = &self.model.body;
        b.g * b.b / b.hg
    }

    /// The error weights (see `erk::Tol`): relative to the size of the
    /// motion, down to the floor `atol_theta = rtol theta_floor`,
    /// `atol_omega = rtol p theta_floor`: `theta_floor = rtol thetaOv` for the
    /// rigid law (below that the rest criterion takes over), `theta_floor =
    /// min(thetaOv, thetaJo)` for the flexible laws (the scale on which the
    /// contact changes).
    fn tol(&self) -> Tol {
        let rtol = self.effective_rtol();
        let (th, om) = self.scales();
        let b = &self.model.body;
        let floor = if self.model.interface.law() == Law::Rigid {
            rtol
        } else {
            (self.model.interface.theta_jo() / th).min(1.0)
        };
        Tol {
            rtol,
            atol_theta: rtol * th * floor,
            atol_omega: rtol * om * floor,
            two_g: 2.0 * b.weight * b.b / b.io,
        }
    }

    /// Whether a body at rest (`theta = omega = 0`) stays at rest under the
    /// ground acceleration `ag` (m/s²): for the flexible laws only without
    /// ground motion (any `ag` moves the body: `theta'' = -m ag hG / I(0)`);
    /// for the rigid law while `|ag| <= g tan(alpha)` (no uplift).
    pub fn held_at_rest(&self, ag: f64) -> bool {
        self.held(ag, 0.0)
    }

    /// [`held_at_rest`](Self::held_at_rest) under the vertical ground
    /// acceleration `av` (m/s²): the rigid threshold is `(g + av) tan(alpha)`
    /// (docs/model.md §6.2). A one-sided body (docs/model.md §7.1) is held
    /// by the restraint against any push toward it: rigid, it leaves only
    /// when `-side ag > (g + av) tan(alpha)`; flexible, as soon as
    /// `side ag < 0`.
    pub fn held(&self, ag: f64, av: f64) -> bool {
        let b = &self.model.body;
        let rigid = self.model.interface.law() == Law::Rigid;
        match (self.model.restraint, rigid) {
            (None, true) => ag.abs() <= (b.g + av) * b.b / b.hg,
            (None, false) => ag == 0.0,
            (Some(r), true) => -r.side * ag <= (b.g + av) * b.b / b.hg,
            (Some(r), false) => r.side * ag >= 0.0,
        }
    }

    /// The toe the body rocks about (see `eom::side_of`); a one-sided body
    /// always rocks on the restraint's side.
    #[inline]
    pub(crate) fn side(&self, theta: f64, omega: f64, ag: f64) -> f64 {
        match self.model.restraint {
            Some(r) => r.side,
            None => eom::side_of(theta, omega, ag),
        }
    }

    /// The first time in `[0, tau_end]` (call-local, s) at which the vertical
    /// input `v` leaves the model's range (docs/model.md §6.5), and which
    /// limit: `N = W + m av` is linear in time over the call.
    pub fn out_of_range(&self, v: VerticalInput, tau_end: f64) -> Option<(f64, OutOfRange)> {
        if v.av == 0.0 && v.dav == 0.0 {
            return None;
        }
        let m = &self.model;
        let b = &m.body;
        let n = |tau: f64| b.weight + b.mass * (v.av + v.dav * tau);
        let dn = b.mass * v.dav;
        // (limit, below: the range is N > limit, else N < limit), in an
        // array: a Vec here was an allocation at every call with av
        let lift = Some((0.0, true, OutOfRange::LiftOff));
        let shape = m.interface.shape();
        let unstable = |kn: f64| {
            Some((
                kn * shape.second_moment() / b.hg,
                false,
                OutOfRange::RestUnstable,
            ))
        };
        let limits = match m.interface.law() {
            Law::Rigid => [lift, None, None],
            Law::Elastic { kn } => [lift, unstable(kn), None],
            Law::ElastoPlastic { kn, fm } => [
                lift,
                Some((fm * shape.area(), false, OutOfRange::BaseCrushing)),
                unstable(kn),
            ],
        };
        let outside =
            |tau: f64, lim: f64, below: bool| if below { n(tau) <= lim } else { n(tau) >= lim };
        let mut first: Option<(f64, OutOfRange)> = None;
        for (lim, below, cond) in limits.into_iter().flatten() {
            let tau = if outside(0.0, lim, below) {
                0.0
            } else if dn != 0.0 && (dn < 0.0) == below && outside(tau_end, lim, below) {
                // the first representable time, as N is computed: N rounded
                // is monotone in tau, and flat over a few ulps of tau near
                // the limit (more the slower it moves), so the closed-form
                // root may be past the first time (the right-hand side was
                // then evaluated at N = 0 before liftOff)
                first_time(|tau| outside(tau, lim, below), tau_end)
            } else {
                continue;
            };
            if tau <= tau_end && first.is_none_or(|(t, _)| tau < t) {
                first = Some((tau, cond));
            }
        }
        first
    }

    /// The rest criterion (rigid law). After an impact at ground acceleration
    /// `ag` with post-impact velocity `omega`, the exact motion is a sequence
    /// of ever smaller excursions (each one a parabola to first order: the
    /// body leaves with `|omega|` against the deceleration
    /// `a_± = (W b ∓ m ag hG) / IO` of its side at `theta = 0`) converging to
    /// rest. Snapping to rest at once changes the solution by at most
    /// `(|omega|, omega² / (2 a_min))` in `(omega, theta)`. Returns those two
    /// bounds, or `None` if rest is impossible (`|ag| >= g tan(alpha)`).
    pub fn rest_bound(&self, omega: f64, ag: f64) -> Option<(f64, f64)> {
        self.rest_bound_at(omega, ag, self.model.body.weight)
    }

    /// [`rest_bound`](Self::rest_bound) under the apparent weight `n` (N).
    pub fn rest_bound_at(&self, omega: f64, ag: f64, n: f64) -> Option<(f64, f64)> {
        let b = &self.model.body;
        let a_min = (n * b.b - b.mass * ag.abs() * b.hg) / b.io;
        if a_min > 0.0 {
            Some((omega.abs(), omega * omega / (2.0 * a_min)))
        } else {
            None
        }
    }

    /// Integrate from `state.t` to `t_end` (or to overturning) under `input`.
    pub fn advance(&self, state: &mut State, t_end: f64, input: GroundInput) -> Events {
        self.run(state, t_end, input, VerticalInput::default(), false)
    }

    /// [`advance`](Self::advance) under a vertical ground acceleration too
    /// (docs/model.md §6). Stops early at overturning or where the input
    /// leaves the model's range ([`Events::terminal`]).
    pub fn advance_vertical(
        &self,
        state: &mut State,
        t_end: f64,
        input: GroundInput,
        vertical: VerticalInput,
    ) -> Events {
        self.run(state, t_end, input, vertical, false)
    }

    /// Like [`advance`](Self::advance) but return at the first event (zero crossing,
    /// uplift, rest, overturning) with `state.t` the event's time, or at
    /// `t_end`. The input is `ag + dag (t - t0)` with `t0` the `state.t` of
    /// this call.
    pub fn advance_to_event(&self, state: &mut State, t_end: f64, input: GroundInput) -> Events {
        self.run(state, t_end, input, VerticalInput::default(), true)
    }

    /// A jump of the vertical input from `av_before` to `av_after` (m/s²)
    /// between two calls (a zero-order-hold host): the apparent weight
    /// jumps, and with it `I(phi, N)`; the kinetic energy `I omega²/2` stays
    /// continuous, `omega+ = omega- sqrt(I(phi, N-)/I(phi, N+))`
    /// (docs/model.md §6.2). The rigid law's `IO` does not depend on N.
    pub fn vertical_jump(&self, st: &mut State, av_before: f64, av_after: f64) {
        let m = &self.model;
        if av_before == av_after || st.at_rest || m.interface.law() == Law::Rigid {
            return;
        }
        let b = &m.body;
        let phi = st.theta.abs();
        let inertia = |av: f64| {
            let (c, _) = m.contact_loaded(phi, b.weight + b.mass * av);
            m.levers(phi, &c).inertia
        };
        st.omega *= (inertia(av_before) / inertia(av_after)).sqrt();
    }

    /// [`advance_to_event`](Self::advance_to_event) under a vertical ground
    /// acceleration too.
    pub fn advance_to_event_vertical(
        &self,
        state: &mut State,
        t_end: f64,
        input: GroundInput,
        vertical: VerticalInput,
    ) -> Events {
        self.run(state, t_end, input, vertical, true)
    }
}

/// The first representable `tau` in `(0, hi]` at which `holds`, which is
/// monotone (false at 0, true at `hi`), by bisection on the floats.
fn first_time(holds: impl Fn(f64) -> bool, hi: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, hi);
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return hi;
        }
        if holds(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
}
