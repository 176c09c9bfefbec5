//! Equations of motion, impacts, rest and overturning (docs/model.md §3), and the
//! integrator that the FMU calls once per communication step.
//!
//! - Equation of motion (docs/model.md §3), `phi = |theta|`, `s = sgn theta`:
//!   `I(phi) theta'' + (1/2) s I'(phi) omega² = -s W hW(phi) - m ag hg(phi)`
//!   (`shiftingPivot`; `costa` without the `omega²` term; rigid law: `af = 0`,
//!   `I = IO`). See [`eom`].
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

mod dense;
mod eom;
mod erk;
mod free;
mod output_rates;
mod rodas;

pub mod continuous;

pub use output_rates::{Jet, OutputRates};

use crate::interface::{Law, Regime};
use crate::model::Model;
use crate::shape::Shape;

use dense::{first_event, max_abs, Hermite, Hit};
use eom::{side_of, Eom};
use erk::{Dop853, Dp5, Pair, StepOut, Tol};
use free::FreeRigid;
use rodas::Jac;

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
}

/// Output quantities at a state (docs/model.md §5).
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
    /// Kinks of the right-hand side (computed from `model` by `new`: a
    /// changed model needs a new simulator).
    kinks: Kinks,
}

/// Why a step loop stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stop {
    /// Reached `t_end`.
    End,
    /// An event, and the caller wants to see it.
    Event,
}

impl Simulator {
    pub fn new(model: Model, rtol: f64) -> Simulator {
        Simulator::with_method(model, rtol, Method::default())
    }

    /// The same with an explicit Runge-Kutta pair.
    pub fn with_method(model: Model, rtol: f64, method: Method) -> Simulator {
        Simulator {
            kinks: find_kinks(&model),
            model,
            rtol,
            method,
            stiff_mode: true,
        }
    }

    pub fn initial_state(&self, theta0: f64, omega0: f64) -> State {
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
        if self.model.interface.law() == Law::Rigid {
            ag.abs() <= self.uplift_acceleration()
        } else {
            ag == 0.0
        }
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
        let b = &self.model.body;
        let a_min = (b.weight * b.b - b.mass * ag.abs() * b.hg) / b.io;
        if a_min > 0.0 {
            Some((omega.abs(), omega * omega / (2.0 * a_min)))
        } else {
            None
        }
    }

    /// Integrate from `state.t` to `t_end` (or to overturning) under `input`.
    pub fn advance(&self, state: &mut State, t_end: f64, input: GroundInput) -> Events {
        self.run(state, t_end, input, false)
    }

    /// Like [`advance`](Self::advance) but return at the first event (zero crossing,
    /// uplift, rest, overturning) with `state.t` the event's time, or at
    /// `t_end`. The input is `ag + dag (t - t0)` with `t0` the `state.t` of
    /// this call.
    pub fn advance_to_event(&self, state: &mut State, t_end: f64, input: GroundInput) -> Events {
        self.run(state, t_end, input, true)
    }

    /// Integrates in the call's own time `tau = t - t0` (`t0 = state.t` at
    /// the call): a step's resolution is then that of `tau`, not that of the
    /// absolute time, whose last bit at `t = 1e9 s` (1.2e-7 s) is longer
    /// than a passage through the contact zone of a stiff interface.
    fn run(&self, st: &mut State, t_end: f64, input: GroundInput, stop_at_event: bool) -> Events {
        if st.overturned || t_end.is_nan() || t_end <= st.t {
            return Events::default();
        }
        let t0 = st.t;
        let tau_end = t_end - t0;
        st.t = 0.0;
        let mut ev = self.run_local(st, t0, tau_end, input, stop_at_event);
        let to_absolute = move |tau: f64| -> f64 {
            if tau >= tau_end {
                t_end
            } else {
                (t0 + tau).min(t_end)
            }
        };
        ev.overturned_at = ev.overturned_at.map(to_absolute);
        st.t = to_absolute(st.t);
        ev
    }

    /// [`run`](Self::run) from `st.t = 0` to `t_end` (call-local times; the
    /// call starts at the absolute time `t0`).
    fn run_local(
        &self,
        st: &mut State,
        t0: f64,
        t_end: f64,
        input: GroundInput,
        stop_at_event: bool,
    ) -> Events {
        let mut ev = Events::default();
        let eom = Eom::new(&self.model, st.t, input);
        let tol = self.tol();
        if st.theta == 0.0 && st.omega == 0.0 {
            st.at_rest = true;
        }
        loop {
            if st.at_rest && !eom.rigid {
                // flexible law: theta = omega = 0 is an equilibrium as long
                // as there is no ground motion
                if self.held_at_rest(eom.ag(st.t)) && eom.dag() == 0.0 {
                    st.t = t_end;
                    return ev;
                }
                st.at_rest = false;
                st.h = 0.0;
            }
            if st.at_rest {
                match self.uplift_time(&eom, st.t, t_end) {
                    None => {
                        st.t = t_end;
                        return ev;
                    }
                    Some(tu) => {
                        st.t = tu;
                        st.at_rest = false;
                        st.theta = 0.0;
                        st.omega = 0.0;
                        st.h = 0.0;
                        ev.uplift = true;
                        // An uplift at the call's start (in absolute time)
                        // is not a stop: the call after an uplift event
                        // starts there at rest (theta = omega = 0) and would
                        // report it again, for ever.
                        if stop_at_event && t0 + tu > t0 {
                            return ev;
                        }
                    }
                }
            }
            let stop = match self.method {
                Method::Dp5 => self.steps::<Dp5>(&eom, &tol, st, t_end, stop_at_event, &mut ev),
                Method::Dop853 => {
                    self.steps::<Dop853>(&eom, &tol, st, t_end, stop_at_event, &mut ev)
                }
            };
            if stop == Stop::Event || st.overturned || !st.at_rest || st.t >= t_end {
                return ev;
            }
        }
    }

    /// When a rigid body at rest at `t` lifts off before `t_end`: the first
    /// time `|ag| > g tan(alpha)` (the input is linear), or `None`.
    fn uplift_time(&self, eom: &Eom, t: f64, t_end: f64) -> Option<f64> {
        let thr = self.uplift_acceleration();
        let ag = eom.ag(t);
        if !self.held_at_rest(ag) {
            return Some(t);
        }
        let dag = eom.dag();
        if dag == 0.0 {
            return None;
        }
        let target = if dag > 0.0 { thr } else { -thr };
        let tu = t + (target - ag) / dag;
        // strictly beyond the threshold: the first representable time after
        let tu = if eom.ag(tu).abs() > thr {
            tu
        } else {
            next_up(tu)
        };
        (tu < t_end).then_some(tu)
    }

    /// Hairer's starting step (Solving ODEs I, §II.4).
    #[allow(clippy::too_many_arguments)]
    fn initial_step(
        &self,
        eom: &Eom,
        tol: &Tol,
        t: f64,
        y: [f64; 2],
        a0: f64,
        side: f64,
        hint: &mut f64,
        order: u32,
    ) -> f64 {
        let sc = tol.scales(y, y);
        let norm =
            |u: f64, v: f64| ((u / sc[0]).powi(2) + (v / sc[1]).powi(2)).sqrt() / 2f64.sqrt();
        let d0 = norm(y[0], y[1]);
        let d1 = norm(y[1], a0);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        let y1 = [y[0] + h0 * y[1], y[1] + h0 * a0];
        let a1 = eom.accel(t + h0, y1[0], y1[1], side, hint);
        let d2 = norm(y1[1] - y[1], a1 - a0) / h0;
        let dm = d1.max(d2);
        let h1 = if dm <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / dm).powf(1.0 / (order as f64 + 1.0))
        };
        (100.0 * h0).min(h1)
    }

    /// The step loop from `st` to `t_end`, an event the caller wants, rest
    /// or overturning.
    fn steps<P: Pair>(
        &self,
        eom: &Eom,
        tol: &Tol,
        st: &mut State,
        t_end: f64,
        stop_at_event: bool,
        ev: &mut Events,
    ) -> Stop {
        let theta_ov = self.model.theta_ov;
        let kink_levels = self.kinks;
        let kinks = kink_levels.as_slice();
        let theta_jo = self.model.interface.theta_jo();
        let mut side = side_of(st.theta, st.omega, eom.ag(st.t));
        let mut hint = st.a;
        let mut a0 = eom.accel(st.t, st.theta, st.omega, side, &mut hint);
        ev.stats.evals += 1;
        let mut h = st.h;
        if h.is_nan() || h <= 0.0 {
            h = self.initial_step(
                eom,
                tol,
                st.t,
                [st.theta, st.omega],
                a0,
                side,
                &mut hint,
                P::ORDER,
            );
            ev.stats.evals += 1;
        }
        if eom.rigid || !self.stiff_mode {
            st.stiff = false;
        }
        let mut rejected = false;
        // the Rosenbrock Jacobian at the current step start
        let mut jac: Option<Jac> = None;
        while st.t < t_end {
            let t = st.t;
            let y0 = [st.theta, st.omega];
            let last = t + 1.01 * h >= t_end;
            let t_new = if last { t_end } else { t + h };
            let hh = t_new - t;
            let kind = if st.stiff {
                let j = match jac {
                    Some(j) => j,
                    None => {
                        let mut j = self.jacobian(eom, tol, t, hh, y0, a0, side, hint, ev);
                        // In the stiff mode an oscillation about the
                        // quasi-static state below the tolerance at the
                        // rocking scale, rtol thetaOv, is projected away
                        // (onto the linearised slow manifold), so that RODAS
                        // is not held to resolve it.
                        let negligible = tol.rtol * theta_ov;
                        if let Some((th, om)) = slow_state(&j, y0, a0, negligible) {
                            st.theta = th;
                            st.omega = om;
                            a0 = eom.accel(t, th, om, side, &mut hint);
                            ev.stats.evals += 1;
                            j = self.jacobian(eom, tol, t, hh, [th, om], a0, side, hint, ev);
                        }
                        jac = Some(j);
                        j
                    }
                };
                Kind::Rodas(j)
            } else {
                Kind::Explicit
            };
            let y0 = [st.theta, st.omega];
            let mut step_hint = hint;
            let out = attempt::<P>(eom, tol, &kind, t, hh, y0, a0, side, &mut step_hint, ev);
            let err_exp = match kind {
                Kind::Explicit => P::ERR_EXP,
                Kind::Rodas(_) => rodas::ERR_EXP,
            };
            // The smallest step, as the step t + m actually makes once
            // rounded to a representable time: a step rejected down to it
            // is then accepted (compared with the unrounded m, the rounded
            // step could exceed it and be rejected for ever).
            let min_step = {
                let m = 16.0 * f64::EPSILON * t.abs().max(hh);
                ((t + m) - t).max(m)
            };
            let acceptable = out.err <= 1.0; // false for NaN
            if !acceptable && hh > min_step {
                ev.stats.rejected += 1;
                let f = if out.err.is_finite() {
                    (0.9 * out.err.powf(err_exp)).clamp(0.2, 1.0)
                } else {
                    0.2
                };
                h = (hh * f).max(min_step);
                // A step rejected because it ran across a kink of the
                // right-hand side: retry to just past the kink, where the
                // accepted step is then cut.
                if !kinks.is_empty() && !st.stiff && out.err.is_finite() {
                    let herm =
                        Hermite::new(hh, [y0[0], y0[1], a0], [out.y[0], out.y[1], out.accel]);
                    if let Some((Hit::Kink(_), tau)) = first_event(&herm, side, theta_ov, kinks) {
                        h = h.min(1.01 * tau * hh).max(min_step);
                    }
                }
                rejected = true;
                continue;
            }
            ev.stats.steps += 1;
            if st.stiff {
                ev.stats.stiff_steps += 1;
            }
            // next step size
            let mut fac = if out.err == 0.0 {
                10.0
            } else {
                (0.9 * out.err.powf(err_exp)).clamp(0.2, 10.0)
            };
            if rejected {
                fac = fac.min(1.0);
            }
            rejected = false;
            let mut h_next = if last { (hh * fac).max(h) } else { hh * fac };
            h_next = h_next.max(min_step);
            // Flexible laws, approaching theta = 0 in partial contact: the
            // contact varies on the scale of phi itself (af ~ phi^(-1/2)),
            // so the error of a step is a function of r = h |omega / theta|:
            // control r (grown by the same factor as h) and keep it below
            // R_MAX, rather than let h grow into the steep region.
            if !eom.rigid && out.y[0] * out.y[1] < 0.0 && out.y[0].abs() > theta_jo {
                let time_to_zero = (out.y[0] / out.y[1]).abs();
                let r = (hh / time_to_zero * fac).min(R_MAX);
                if r > 0.0 {
                    h_next = h_next.min(r * time_to_zero);
                }
            }
            // Stiffness switch (flexible laws), on steps not cut by t_end:
            // explicit steps held at h rho > STIFF_ON by stability go to
            // RODAS; RODAS steps that an explicit method could take as well
            // (h rho < STIFF_OFF) come back.
            if !eom.rigid && !last && self.stiff_mode {
                let stiff_now = if st.stiff {
                    hh * out.rho >= STIFF_OFF
                } else {
                    hh * out.rho > STIFF_ON
                };
                if stiff_now == st.stiff {
                    st.switch_count = 0;
                } else {
                    st.switch_count += 1;
                    if st.switch_count >= SWITCH_AFTER {
                        st.stiff = !st.stiff;
                        st.switch_count = 0;
                    }
                }
            }
            let herm = Hermite::new(hh, [y0[0], y0[1], a0], [out.y[0], out.y[1], out.accel]);
            jac = None;
            // RODAS steps are not cut at the kinks: its steps are long, and
            // the projection on the slow manifold moves the state off them
            let step_kinks = if st.stiff { &[][..] } else { kinks };
            match first_event(&herm, side, theta_ov, step_kinks) {
                None => {
                    note_opening(st, &herm, 1.0, theta_jo);
                    st.t = t_new;
                    st.theta = out.y[0];
                    st.omega = out.y[1];
                    a0 = out.accel;
                    hint = step_hint;
                    st.a = hint;
                    h = h_next;
                    if !eom.rigid {
                        side = side_of(st.theta, st.omega, eom.ag(st.t));
                    }
                }
                Some((hit, tau)) => {
                    let (t_ev, y_ev, status) = self.step_to_event::<P>(
                        eom,
                        tol,
                        &kind,
                        t,
                        y0,
                        a0,
                        side,
                        hint,
                        hit,
                        tau * hh,
                        hh,
                        ev,
                    );
                    if status == EventStatus::Retry && t_ev - t > min_step {
                        // the step to the event is not accurate enough (a
                        // singular kink, a poor interpolant): retry shorter
                        ev.stats.rejected += 1;
                        h = (0.5 * (t_ev - t)).max(min_step);
                        rejected = true;
                        continue;
                    }
                    h = h_next;
                    if status == EventStatus::Spurious {
                        // no event after all (see step_to_event): the
                        // accepted step stands
                        note_opening(st, &herm, 1.0, theta_jo);
                        st.t = t_new;
                        st.theta = out.y[0];
                        st.omega = out.y[1];
                        a0 = out.accel;
                        hint = step_hint;
                        st.a = hint;
                        if !eom.rigid {
                            side = side_of(st.theta, st.omega, eom.ag(st.t));
                        }
                        continue;
                    }
                    // Put the state exactly on the level: move along the
                    // trajectory by the residual, dt = -r / omega, to first
                    // order (the residual is below 1e-3 of the error scale,
                    // but in the contact zone I'(phi) omega² is large and a
                    // bare shift of theta would change the energy).
                    let level = match hit {
                        Hit::Impact => 0.0,
                        Hit::Overturn => side * theta_ov,
                        Hit::Kink(i) => side * kinks[i],
                    };
                    let shift = if y_ev.y[1] != 0.0 {
                        -(y_ev.y[0] - level) / y_ev.y[1]
                    } else {
                        0.0
                    };
                    let y_ev = StepOut {
                        y: [level, y_ev.y[1] + y_ev.accel * shift],
                        ..y_ev
                    };
                    // the part of the step up to the event (on one side of
                    // theta = 0: the event is the step's first)
                    note_opening(st, &herm, ((t_ev - t) / hh).clamp(0.0, 1.0), theta_jo);
                    let t_ev = t_ev + shift;
                    st.t = t_ev;
                    match hit {
                        Hit::Kink(_) => {
                            // exactly on the level, so that the next step
                            // starts on it and is smooth
                            st.theta = level;
                            st.omega = y_ev.y[1];
                            a0 = eom.accel(st.t, st.theta, st.omega, side, &mut hint);
                            ev.stats.evals += 1;
                            st.a = hint;
                            side = side_of(st.theta, st.omega, eom.ag(st.t));
                        }
                        Hit::Overturn => {
                            st.theta = side * theta_ov;
                            st.omega = y_ev.y[1];
                            st.overturned = true;
                            st.h = h;
                            ev.overturned_at = Some(t_ev);
                            return Stop::Event;
                        }
                        Hit::Impact => {
                            st.theta = 0.0;
                            st.omega = self.model.eta * y_ev.y[1];
                            count_crossing(st, ev);
                            let ag = eom.ag(t_ev);
                            let quiet = ag == 0.0 && eom.dag() == 0.0;
                            let mut rest = if eom.rigid {
                                self.comes_to_rest(st.omega, ag)
                            } else {
                                quiet && self.settles(st.omega)
                            };
                            if eom.rigid && quiet && !rest && !stop_at_event {
                                rest = self.free_half_cycles(st, t_end, ev);
                            }
                            if rest {
                                st.omega = 0.0;
                                st.at_rest = true;
                                ev.came_to_rest = true;
                                st.h = 0.0;
                                return if stop_at_event {
                                    Stop::Event
                                } else {
                                    Stop::End
                                };
                            }
                            side = side_of(0.0, st.omega, ag);
                            hint = st.a;
                            a0 = eom.accel(st.t, 0.0, st.omega, side, &mut hint);
                            ev.stats.evals += 1;
                            if stop_at_event {
                                st.h = h;
                                return Stop::Event;
                            }
                        }
                    }
                }
            }
        }
        st.h = h;
        Stop::End
    }

    /// The Jacobian for RODAS at the start of a step.
    #[allow(clippy::too_many_arguments)]
    fn jacobian(
        &self,
        eom: &Eom,
        tol: &Tol,
        t: f64,
        h: f64,
        y0: [f64; 2],
        a0: f64,
        side: f64,
        hint: f64,
        ev: &mut Events,
    ) -> Jac {
        let mut jh = hint;
        ev.stats.evals += 3;
        rodas::jacobian(
            eom,
            t,
            h,
            y0,
            a0,
            side,
            &mut jh,
            tol.atol_theta / tol.rtol,
            tol.atol_omega / tol.rtol,
        )
    }

    /// Rigid law without ground motion, after an impact: the half-cycles
    /// that end before `t_end` in closed form (see `free`), each with its
    /// impact and the rest test. Returns whether the body came to rest; else
    /// `st` is just after the last impact that fits, and the integrator
    /// takes over (for the partial half-cycle, or overturning).
    fn free_half_cycles(&self, st: &mut State, t_end: f64, ev: &mut Events) -> bool {
        let b = &self.model.body;
        let free = FreeRigid::new(b.weight, b.r0, b.io, b.alpha);
        while let Some(phi) = free.peak(st.omega) {
            let t_next = st.t + 2.0 * free.fall_time(phi);
            if t_next.is_nan() || t_next >= t_end {
                break;
            }
            st.t = t_next;
            st.omega *= -self.model.eta;
            // the half-cycle rose to phi > 0 = thetaJo: an impact
            st.opened = true;
            count_crossing(st, ev);
            if self.comes_to_rest(st.omega, 0.0) {
                return true;
            }
        }
        false
    }

    /// The rest criterion of the flexible laws, under zero ground motion:
    /// after an impact at `theta = 0` with `omega`, the free oscillation in
    /// full contact has the amplitude `|omega| sqrt(I0 / K0)`
    /// (`K0 = kn Is - W hG`, `I0 = Ic + m hG²`, the linearisation at
    /// `theta = 0`). Below `rtol thetaOv` (the error floor) it is set to rest
    /// exactly: it would otherwise cross zero every half period for ever,
    /// decaying by `eta` each time.
    fn settles(&self, omega: f64) -> bool {
        let (kn, is) = match self.model.interface.law() {
            Law::Elastic { kn } | Law::ElastoPlastic { kn, .. } => {
                (kn, self.model.interface.shape().second_moment())
            }
            Law::Rigid => return false,
        };
        let b = &self.model.body;
        let k0 = kn * is - b.weight * b.hg;
        let i0 = b.ic + b.mass * b.hg * b.hg;
        let amp = omega.abs() * (i0 / k0).sqrt();
        amp <= self.effective_rtol() * self.model.theta_ov
    }

    /// Whether a rigid body leaving an impact with `omega` under `ag` is at
    /// rest to the tolerance ([`rest_bound`](Self::rest_bound) below the
    /// step's absolute tolerances).
    fn comes_to_rest(&self, omega: f64, ag: f64) -> bool {
        let rtol = self.effective_rtol();
        let (th, om) = self.scales();
        match self.rest_bound(omega, ag) {
            Some((dw, dth)) => dw <= rtol * om && dth <= rtol * th,
            None => false,
        }
    }

    /// Redo the step from `(t, y0)` so that it ends at the event `t + dt`,
    /// then polish `dt` by Newton on the step itself until the event
    /// function (`theta`, `|theta| - level`) is below a thousandth of the
    /// error scale of the motion. Returns the event time, the step, and the
    /// verdict ([`EventStatus`]).
    #[allow(clippy::too_many_arguments)]
    fn step_to_event<P: Pair>(
        &self,
        eom: &Eom,
        tol: &Tol,
        kind: &Kind,
        t: f64,
        y0: [f64; 2],
        a0: f64,
        side: f64,
        hint: f64,
        hit: Hit,
        mut dt: f64,
        h_max: f64,
        ev: &mut Events,
    ) -> (f64, StepOut, EventStatus) {
        let target = match hit {
            Hit::Impact => 0.0,
            Hit::Overturn => side * self.model.theta_ov,
            Hit::Kink(i) => side * self.kinks.as_slice()[i],
        };
        let mut out = StepOut {
            y: y0,
            accel: a0,
            err: 0.0,
            rho: 0.0,
        };
        let mut converged = false;
        for _ in 0..4 {
            if dt > 0.0 {
                let mut hh = hint;
                out = attempt::<P>(eom, tol, kind, t, dt, y0, a0, side, &mut hh, ev);
                ev.stats.steps += 1;
            }
            // relative to the size of the motion itself, not to the error
            // floor: the state is set exactly on the level, and a
            // displacement at the floor would feed a spurious oscillation
            let r = out.y[0] - target;
            let sc = tol.rtol * tol.amp(out.y);
            if r.abs() <= 1e-3 * sc {
                converged = true;
                break;
            }
            // stay inside the step that was accepted
            let next = dt - r / out.y[1];
            if !next.is_finite() || next <= 0.0 || next > h_max || next == dt {
                break;
            }
            dt = next;
        }
        let moving = side * out.y[1];
        let direction = match hit {
            Hit::Impact => moving < 0.0,
            Hit::Overturn => moving > 0.0,
            Hit::Kink(_) => true,
        };
        let status = if t + dt <= t || !direction {
            EventStatus::Spurious
        } else if converged && out.err <= 1.0 {
            EventStatus::Confirmed
        } else {
            EventStatus::Retry
        };
        (t + dt, out, status)
    }

    /// Outputs at `state` under ground acceleration `ag` (m/s²).
    ///
    /// A body at rest that this `ag` sets moving (see
    /// [`held_at_rest`](Self::held_at_rest)) gets the equation of motion's
    /// `theta''`, `Fx`, `Fz` at `theta = omega = 0` on the side `ag` pushes
    /// it to (the motion starts there); its contact outputs stay those at
    /// rest.
    ///
    /// The support forces (docs/model.md §5) follow from the velocity of G
    /// that the equation of motion implies, G turning about the interface
    /// resultant: `xG' = hg omega`, `zG' = s hW omega`, so
    /// `xG'' = hg theta'' + s hg' omega²`, `zG'' = s hW theta'' + hW' omega²`,
    /// `Fx = m (ag + xG'')`, `Fz = m (g + zG'')`. With `I = Ic + m (hg² +
    /// hW²)` these make the energy of a block on a moving support balance
    /// the work of `Fx`; for the rigid law they are G turning rigidly about
    /// the toe.
    pub fn outputs(&self, state: &State, ag: f64) -> Outputs {
        if !state.at_rest {
            return self.outputs_in_motion(state, ag);
        }
        let b = &self.model.body;
        // The contact of a body at rest is the whole base, whatever ag: the
        // contact outputs do not depend on ag (docs/model.md §5 declares
        // only angularAcceleration, Fx, Fz as depending on it).
        let c = self.model.interface.contact(0.0);
        let rest = Outputs {
            theta_dd: 0.0,
            af: c.af,
            contact_length: c.contact_length,
            mr: 0.0,
            regime: c.regime,
            fx: b.mass * ag,
            fz: b.weight,
        };
        if self.held_at_rest(ag) {
            return rest;
        }
        let start = self.outputs_in_motion(state, ag);
        Outputs {
            theta_dd: start.theta_dd,
            fx: start.fx,
            fz: start.fz,
            ..rest
        }
    }

    /// [`outputs`](Self::outputs) from the equation of motion at `state`.
    fn outputs_in_motion(&self, state: &State, ag: f64) -> Outputs {
        let m = &self.model;
        let b = &m.body;
        let side = side_of(state.theta, state.omega, ag);
        let eom = Eom::new(
            m,
            state.t,
            GroundInput {
                ag,
                ..Default::default()
            },
        );
        let mut hint = state.a;
        let theta_dd = eom.accel(state.t, state.theta, state.omega, side, &mut hint);
        let phi = state.theta.abs();
        // rigid law in motion: the reaction is at the toe even at theta = 0
        let c = if eom.rigid {
            m.interface.contact(phi.max(f64::MIN_POSITIVE))
        } else {
            m.interface.contact_near(phi, state.a)
        };
        let l = m.levers(phi, &c);
        let w2 = state.omega * state.omega;
        let xg_dd = l.hg * theta_dd + side * l.dhg * w2;
        let zg_dd = side * l.hw * theta_dd + l.dhw * w2;
        Outputs {
            theta_dd,
            af: c.af,
            contact_length: c.contact_length,
            mr: b.weight * l.hw,
            regime: if state.overturned {
                Regime::Overturned
            } else {
                c.regime
            },
            fx: b.mass * (ag + xg_dd),
            fz: b.mass * (b.g + zg_dd),
        }
    }
}

/// The state on the linearised slow manifold near `y0` when the fast
/// oscillation about it is below `floor`, else `None`. With `J` the Jacobian, the slow manifold has
/// `theta'' = 0`: `omega_s = -a_t / a_theta` and
/// `theta_s = theta - (a0 + a_omega (omega_s - omega)) / a_theta`. The
/// fast part is `(theta - theta_s, (omega - omega_s) / rho)` in amplitude.
/// Never across `theta = 0` (that is an impact).
fn slow_state(j: &Jac, y0: [f64; 2], a0: f64, floor: f64) -> Option<(f64, f64)> {
    if j.a_theta >= 0.0 {
        return None;
    }
    let rho = (-j.a_theta).sqrt();
    let om = -j.a_t / j.a_theta;
    let th = y0[0] - (a0 + j.a_omega * (om - y0[1])) / j.a_theta;
    let fast = (th - y0[0]).hypot((om - y0[1]) / rho);
    let same_side = th * y0[0] > 0.0;
    (fast <= floor && same_side && th.is_finite() && om.is_finite()).then_some((th, om))
}

/// A zero crossing of `theta`: an impact too if the joint had opened since
/// the previous one (see [`State::impacts`]).
fn count_crossing(st: &mut State, ev: &mut Events) {
    st.zero_crossings += 1;
    ev.zero_crossings += 1;
    if st.opened {
        st.impacts += 1;
        ev.impacts += 1;
    }
    st.opened = false;
}

/// Marks `st.opened` if `|theta|` exceeds `theta_jo` on `[0, tau_end]` of
/// the step interpolated by `p`: the ends, and the turning points inside
/// (a peak above `thetaJo` between two step ends below it, as in a stiff
/// step, or between two ends cut exactly on the level).
fn note_opening(st: &mut State, p: &Hermite, tau_end: f64, theta_jo: f64) {
    // the end first: the turning-point search only while the joint has not
    // opened in this half-cycle
    if !st.opened && (p.theta(tau_end).abs() > theta_jo || max_abs(p, tau_end) > theta_jo) {
        st.opened = true;
    }
}

/// One step attempt with the current kind of method.
#[allow(clippy::too_many_arguments)]
#[inline]
fn attempt<P: Pair>(
    eom: &Eom,
    tol: &Tol,
    kind: &Kind,
    t: f64,
    h: f64,
    y0: [f64; 2],
    a0: f64,
    side: f64,
    hint: &mut f64,
    ev: &mut Events,
) -> StepOut {
    match kind {
        Kind::Explicit => {
            ev.stats.evals += P::EVALS;
            P::step(eom, t, h, y0, a0, side, hint, tol)
        }
        Kind::Rodas(j) => {
            ev.stats.evals += rodas::EVALS - 3;
            // In the stiff mode the floor of the velocity error is that of
            // an oscillation at the Jacobian's frequency whose amplitude is
            // the floor of the rotation error: oscillations of the interface
            // below the floor are not resolved (RODAS damps them).
            let stiff_tol = Tol {
                atol_omega: tol.atol_omega.max(tol.atol_theta * j.rho()),
                ..*tol
            };
            rodas::step(eom, t, h, y0, a0, j, side, hint, &stiff_tol)
        }
    }
}

/// The verdict on an event found on the dense output (see
/// `Simulator::step_to_event`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum EventStatus {
    /// Located to the last bits by a step that passes the error test, with
    /// `theta` moving the right way: applied.
    Confirmed,
    /// `theta` does not move the right way there (the interpolant of a step
    /// whose error is below the floor can cross where the motion does not),
    /// or no time passes: no event, the accepted step stands.
    Spurious,
    /// The step to the event failed the error test or the polish did not
    /// converge: the step is retried shorter.
    Retry,
}

/// The method of a step: the explicit pair, or RODAS with its Jacobian.
#[derive(Clone, Copy, Debug)]
enum Kind {
    Explicit,
    Rodas(Jac),
}

/// Explicit steps with `h rho` above this are taken as held by stability.
const STIFF_ON: f64 = 1.0;
/// RODAS steps with `h rho` below this could be explicit.
const STIFF_OFF: f64 = 0.5;
/// Consecutive steps that decide a switch.
const SWITCH_AFTER: u32 = 15;

/// Largest `h |omega / theta|` of a step toward `theta = 0` in partial
/// contact (flexible laws).
const R_MAX: f64 = 0.5;

/// Kink levels of `|theta|`, at most a few.
#[derive(Clone, Copy, Debug, Default)]
struct Kinks {
    levels: [f64; 8],
    n: usize,
}

/// Rotations where the right-hand side has a kink (flexible laws), below
/// `thetaOv`: there `af'` (hence `I'`, which the `shiftingPivot` term
/// multiplies by `omega²`) is continuous but its derivative jumps, and a
/// step across would see a low-order error and be rejected several times,
/// so steps are cut there. They are the regime thresholds `thetaJo` and
/// `thetaC`, and the rotations where the contact edge `a` or the plastic
/// edge `xp = a - fm / (kn phi)` passes a corner of the width function:
/// the flanges of a hollow rectangle (`w` jumps), the inner circle of a
/// hollow circle (`w'` is infinite). Found by bisection on the contact
/// solve (`a` decreases with `phi` beyond `thetaJo`, `xp` increases beyond
/// `thetaC`).
fn find_kinks(model: &Model) -> Kinks {
    let mut k = Kinks::default();
    let (kn, fm) = match model.interface.law() {
        Law::Rigid => return k,
        Law::Elastic { kn } => (kn, f64::INFINITY),
        Law::ElastoPlastic { kn, fm } => (kn, fm),
    };
    let ov = model.theta_ov;
    let mut push = |l: f64| {
        if l > 0.0 && l < ov && k.n < k.levels.len() {
            k.levels[k.n] = l;
            k.n += 1;
        }
    };
    let (jo, c) = (model.interface.theta_jo(), model.interface.theta_c());
    push(jo);
    push(c);
    let corners: &[f64] = match *model.interface.shape() {
        Shape::HollowRectangle { b, t, .. } => &[t, b - t],
        Shape::HollowCircle { ro, ri } => &[ro - ri, ro + ri],
        _ => &[],
    };
    let a = |phi: f64| model.interface.contact(phi).a;
    let xp = |phi: f64| a(phi) - fm / (kn * phi);
    for &x in corners {
        // a(phi) = x: a from D at thetaJo down
        if jo < ov && a(ov) < x {
            push(bisect(|p| x - a(p), jo, ov));
        }
        // xp(phi) = x: xp from 0 at thetaC up
        if c < ov && xp(ov) > x {
            push(bisect(|p| xp(p) - x, c, ov));
        }
    }
    k
}

/// Root of a function increasing through 0 on `[lo, hi]`, by bisection.
fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

impl Kinks {
    fn as_slice(&self) -> &[f64] {
        &self.levels[..self.n]
    }
}

/// The next representable number above `x`.
fn next_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let bits = x.to_bits();
    if x > 0.0 {
        f64::from_bits(bits + 1)
    } else {
        f64::from_bits(bits - 1)
    }
}
