//! Events (docs/model.md §3): zero crossings of `theta` (impacts, with the
//! restitution rule), overturning at `|theta| = thetaOv`, rest, and the
//! kinks where steps are cut; located on a step's dense output, then the
//! step is redone to end exactly there.

use super::dense::{max_abs, Hermite, Hit};
use super::erk::{Pair, StepOut, Tol};
use super::free::FreeRigid;
use super::integrate::{Flow, StepCx, Stop, Trial};
use super::stiffness;
use super::{Events, Simulator, State};
use crate::interface::Law;

/// The verdict on an event found on the dense output (see
/// [`StepCx::step_to_event`]).
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

impl StepCx<'_, '_> {
    /// The level of `theta` of an event on the side `side`.
    fn level(&self, hit: Hit) -> f64 {
        match hit {
            Hit::Impact => 0.0,
            Hit::Overturn => self.side * self.ov_level,
            Hit::Kink(i) => self.side * self.call.sim.kinks.as_slice()[i],
            Hit::MovingKink => self.side * self.kink_level,
        }
    }

    /// An event found at `tau` (a fraction of the step) on the dense output
    /// `herm` of the accepted step `tr`: the step is redone to end there and
    /// the event applied, or the step retried shorter, or (spurious) taken
    /// as it is. `h_next` is the controller's next step.
    pub(super) fn event<P: Pair>(
        &mut self,
        tr: &Trial,
        herm: &Hermite,
        hit: Hit,
        tau: f64,
        h_next: f64,
    ) -> Flow {
        let (t_ev, y_ev, status) = self.step_to_event::<P>(tr, hit, tau * tr.hh);
        if status == EventStatus::Retry && t_ev - tr.t > tr.min_step {
            // the step to the event is not accurate enough (a singular
            // kink, a poor interpolant): retry shorter
            self.ev.stats.rejected += 1;
            self.h = (0.5 * (t_ev - tr.t)).max(tr.min_step);
            self.rejected = true;
            return Flow::Next;
        }
        self.h = h_next;
        if status == EventStatus::Spurious {
            // no event after all (see step_to_event): the accepted step stands
            self.take(tr, herm);
            return Flow::Next;
        }
        // Put the state exactly on the level: move along the trajectory by
        // the residual, dt = -r / omega, to first order (the residual is
        // below 1e-3 of the error scale, but in the contact zone
        // I'(phi) omega² is large and a bare shift of theta would change the
        // energy).
        let level = self.level(hit);
        let shift = if y_ev.y[1] != 0.0 {
            -(y_ev.y[0] - level) / y_ev.y[1]
        } else {
            0.0
        };
        let omega = y_ev.y[1] + y_ev.accel * shift;
        // the part of the step up to the event (on one side of theta = 0:
        // the event is the step's first)
        self.note_opening(herm, ((t_ev - tr.t) / tr.hh).clamp(0.0, 1.0));
        let t_ev = t_ev + shift;
        self.st.t = t_ev;
        match hit {
            Hit::Kink(_) | Hit::MovingKink => {
                self.on_kink(level, omega);
                Flow::Next
            }
            Hit::Overturn => {
                self.overturn(level, omega, t_ev);
                Flow::Stop(Stop::Event)
            }
            Hit::Impact => self.impact(omega, t_ev),
        }
    }

    /// Exactly on the level of a kink, so that the next step starts on it
    /// and is smooth.
    fn on_kink(&mut self, level: f64, omega: f64) {
        self.st.theta = level;
        self.st.omega = omega;
        self.a0 = self.call.eom.accel(
            self.st.t,
            self.st.theta,
            self.st.omega,
            self.side,
            &mut self.hint,
        );
        self.ev.stats.evals += 1;
        self.st.a = self.hint;
        self.side = self
            .call
            .sim
            .side(self.st.theta, self.st.omega, self.call.eom.ag(self.st.t));
    }

    /// `|theta|` reached `thetaOv` at `t_ev`: the run is over.
    fn overturn(&mut self, level: f64, omega: f64, t_ev: f64) {
        self.st.theta = level;
        self.st.omega = omega;
        self.st.overturned = true;
        self.st.h = self.h;
        self.ev.overturned_at = Some(t_ev);
    }

    /// A zero crossing at `t_ev` arriving with `omega`: the restitution
    /// rule, the counts, then rest (or, for the rigid law without ground
    /// motion, the half-cycles that fit in closed form).
    fn impact(&mut self, omega: f64, t_ev: f64) -> Flow {
        let (sim, eom) = (self.call.sim, self.call.eom);
        self.st.theta = 0.0;
        self.st.omega = sim.restitution(omega);
        if sim.model.restraint.is_some() {
            // docs/model.md §7.1: every return to the restraint is an impact
            self.st.opened = true;
        }
        count_crossing(self.st, self.ev);
        let ag = eom.ag(t_ev);
        let quiet = ag == 0.0 && eom.dag() == 0.0 && !eom.vertical;
        let n = eom.apparent_weight(t_ev);
        let mut rest = if sim.model.restraint.is_some() {
            sim.rests_on_restraint(self.st.omega, ag, eom.av(t_ev), quiet)
        } else if eom.rigid {
            sim.comes_to_rest_at(self.st.omega, ag, n)
        } else {
            quiet && sim.settles(self.st.omega)
        };
        if eom.rigid && quiet && !rest && !self.call.stop_at_event {
            rest = sim.free_half_cycles(self.st, self.call.t_end, self.ev, self.call.budget);
        }
        if rest {
            self.st.omega = 0.0;
            self.st.at_rest = true;
            self.ev.came_to_rest = true;
            self.st.h = 0.0;
            return Flow::Stop(if self.call.stop_at_event {
                Stop::Event
            } else {
                Stop::End
            });
        }
        self.side = sim.side(0.0, self.st.omega, ag);
        self.hint = self.st.a;
        self.a0 = eom.accel(self.st.t, 0.0, self.st.omega, self.side, &mut self.hint);
        self.ev.stats.evals += 1;
        if self.call.stop_at_event {
            self.st.h = self.h;
            return Flow::Stop(Stop::Event);
        }
        Flow::Next
    }

    /// Redo the step `tr` so that it ends at the event `t + dt`, then polish
    /// `dt` by Newton on the step itself until the event function (`theta`,
    /// `|theta| - level`) is below a thousandth of the error scale of the
    /// motion. Returns the event time, the step, and the verdict.
    fn step_to_event<P: Pair>(
        &mut self,
        tr: &Trial,
        hit: Hit,
        mut dt: f64,
    ) -> (f64, StepOut, EventStatus) {
        let tol: &Tol = self.call.tol;
        let start = self.start_at(tr.t, tr.y0);
        let target = self.level(hit);
        let h_max = tr.hh;
        let mut out = StepOut {
            y: tr.y0,
            accel: self.a0,
            err: 0.0,
            rho: 0.0,
        };
        let mut converged = false;
        for _ in 0..4 {
            if dt > 0.0 {
                let mut hh = self.hint;
                out = stiffness::attempt::<P>(&start, &tr.kind, dt, &mut hh, tol, self.ev);
                self.ev.stats.steps += 1;
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
        let moving = self.side * out.y[1];
        let direction = match hit {
            Hit::Impact => moving < 0.0,
            Hit::Overturn => moving > 0.0,
            Hit::Kink(_) | Hit::MovingKink => true,
        };
        let t = tr.t;
        // A crossing that the previous step ended a hair short of (theta on
        // the near side by less than the polish's tolerance, moving toward
        // it) lies at the very start of this step, where no time passes: it
        // is the crossing there, not a spurious event (tests/chatter.rs).
        let at_start = t + dt <= t && hit == Hit::Impact && converged;
        let status = if !direction || (t + dt <= t && !at_start) {
            EventStatus::Spurious
        } else if at_start {
            dt = 0.0;
            out = StepOut {
                y: tr.y0,
                accel: self.a0,
                err: 0.0,
                rho: 0.0,
            };
            EventStatus::Confirmed
        } else if converged && out.err <= 1.0 {
            EventStatus::Confirmed
        } else {
            EventStatus::Retry
        };
        (t + dt, out, status)
    }

    /// Marks the joint opened if `|theta|` exceeds `thetaJo` on `[0, tau_end]`
    /// (fractions of the step) of the step interpolated by `p`: the ends, and
    /// the turning points inside (a peak above `thetaJo` between two step
    /// ends below it, as in a stiff step, or between two ends cut exactly on
    /// the level).
    pub(super) fn note_opening(&mut self, p: &Hermite, tau_end: f64) {
        let theta_jo = self.call.sim.model.interface.theta_jo();
        // the end first: the turning-point search only while the joint has
        // not opened in this half-cycle, and only where the step's bounds
        // reach thetaJo
        if self.st.opened {
            return;
        }
        let (lo, hi) = p.bounds();
        if lo.abs().max(hi.abs()) > theta_jo
            && (p.theta(tau_end).abs() > theta_jo || max_abs(p, tau_end) > theta_jo)
        {
            self.st.opened = true;
        }
    }
}

/// A zero crossing of `theta`: an impact too if the joint had opened since
/// the previous one (see [`State::impacts`]).
pub(super) fn count_crossing(st: &mut State, ev: &mut Events) {
    st.zero_crossings += 1;
    ev.zero_crossings += 1;
    if st.opened {
        st.impacts += 1;
        ev.impacts += 1;
    }
    st.opened = false;
}

impl Simulator {
    /// The restitution rule (docs/model.md §3), at every zero crossing: the
    /// angular velocity after the crossing from the one before, rad/s.
    pub(super) fn restitution(&self, omega: f64) -> f64 {
        match self.model.restraint {
            // docs/model.md §7.1: the restraint reverses the motion
            Some(r) => -r.e * omega,
            None => self.model.eta * omega,
        }
    }

    /// Rest against the restraint after an impact that left `omega` (rad/s)
    /// under `ag`, `av` (m/s², docs/model.md §7.1): rigid, when the energy
    /// left is below `1e-13 alpha` of the work to lift the body by a tilt
    /// of alpha, `IO omega²/(2 N b) < 1e-13 alpha`, and the ground cannot
    /// lift it; flexible, when pushed into the restraint (`side ag > 0`) with
    /// `I(0) omega²/(2 m side ag hG) < 1e-13 alpha` (the bounces accumulate),
    /// or stopped dead (`omega = 0`) and not pushed away, or without any
    /// ground motion below the error floor ([`settles`](Self::settles)).
    pub(super) fn rests_on_restraint(&self, omega: f64, ag: f64, av: f64, quiet: bool) -> bool {
        let Some(r) = self.model.restraint else {
            return false;
        };
        let b = &self.model.body;
        let small = 1e-13 * b.alpha;
        if !self.held(ag, av) {
            return false;
        }
        if self.model.interface.law() == Law::Rigid {
            let n = b.weight + b.mass * av;
            return b.io * omega * omega / (2.0 * n * b.b) < small;
        }
        let push = r.side * ag;
        let i0 = b.ic + b.mass * b.hg * b.hg;
        omega == 0.0
            || (push > 0.0 && i0 * omega * omega / (2.0 * b.mass * push * b.hg) < small)
            || (quiet && self.settles(omega))
    }

    /// Rigid law without ground motion, after an impact: the half-cycles
    /// that end before `t_end` in closed form (see `free`), each with its
    /// impact and the rest test, within the call's work `budget`. Returns
    /// whether the body came to rest; else `st` is just after the last
    /// impact that fits, and the integrator takes over (for the partial
    /// half-cycle, overturning, or the work limit).
    fn free_half_cycles(
        &self,
        st: &mut State,
        t_end: f64,
        ev: &mut Events,
        budget: Option<u64>,
    ) -> bool {
        let b = &self.model.body;
        let free = FreeRigid::new(b.weight, b.r0, b.io, b.alpha);
        while let Some(phi) = free.peak(st.omega) {
            let t_next = st.t + 2.0 * free.fall_time(phi);
            if t_next.is_nan() || t_next >= t_end || budget.is_some_and(|n| ev.work() >= n) {
                break;
            }
            st.t = t_next;
            // the body falls back with the velocity it left with
            st.omega = self.restitution(-st.omega);
            // the half-cycle rose to phi > 0 = thetaJo: an impact
            st.opened = true;
            count_crossing(st, ev);
            let rest = if self.model.restraint.is_some() {
                self.rests_on_restraint(st.omega, 0.0, 0.0, true)
            } else {
                self.comes_to_rest(st.omega, 0.0)
            };
            if rest {
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
    pub(super) fn settles(&self, omega: f64) -> bool {
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
    pub(super) fn comes_to_rest(&self, omega: f64, ag: f64) -> bool {
        self.comes_to_rest_at(omega, ag, self.model.body.weight)
    }

    /// [`comes_to_rest`](Self::comes_to_rest) under the apparent weight `n`, N.
    pub(super) fn comes_to_rest_at(&self, omega: f64, ag: f64, n: f64) -> bool {
        let rtol = self.effective_rtol();
        let (th, om) = self.scales();
        match self.rest_bound_at(omega, ag, n) {
            Some((dw, dth)) => dw <= rtol * om && dth <= rtol * th,
            None => false,
        }
    }
}
