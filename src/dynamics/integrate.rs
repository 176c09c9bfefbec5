//! The integration loop of one call: the call's own time axis, rest and
//! uplift (rigid law), and the step loop that ties the controller, the
//! stiffness switch, the kinks and the events together through a step
//! context ([`StepCx`]).

use super::controller;
use super::dense::{first_event, Hermite, Hit};
use super::eom::Eom;
use super::erk::{Dop853, Dp5, Pair, Start, StepOut, Tol};
use super::rodas::Jac;
use super::stiffness::{self, Kind};
use super::{Events, GroundInput, Limited, Method, Simulator, State, Terminal, VerticalInput};

/// Why a step loop stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Stop {
    /// Reached `t_end`.
    End,
    /// An event, and the caller wants to see it.
    Event,
    /// The call's work limit.
    Limit,
}

impl Simulator {
    /// Integrates in the call's own time `tau = t - t0` (`t0 = state.t` at
    /// the call): a step's resolution is then that of `tau`, not that of the
    /// absolute time, whose last bit at `t = 1e9 s` (1.2e-7 s) is longer
    /// than a passage through the contact zone of a stiff interface.
    pub(super) fn run(
        &self,
        st: &mut State,
        t_end: f64,
        input: GroundInput,
        vertical: VerticalInput,
        stop_at_event: bool,
    ) -> Events {
        if st.overturned || t_end.is_nan() || t_end <= st.t {
            return Events::default();
        }
        let t0 = st.t;
        let tau_end = t_end - t0;
        st.t = 0.0;
        let budget = self.work_limit.map(|w| w.budget(tau_end));
        // docs/model.md §6.5: the call ends where the input leaves the range
        let out = self.out_of_range(vertical, tau_end);
        let tau_stop = out.map_or(tau_end, |(tau, _)| tau);
        let mut ev = if tau_stop > 0.0 {
            self.run_local(st, t0, tau_stop, (input, vertical), stop_at_event, budget)
        } else {
            Events::default()
        };
        let to_absolute = move |tau: f64| -> f64 {
            if tau >= tau_end {
                t_end
            } else {
                (t0 + tau).min(t_end)
            }
        };
        ev.overturned_at = ev.overturned_at.map(to_absolute);
        if let Some((tau, condition)) = out {
            if !st.overturned && ev.limited.is_none() && st.t >= tau {
                ev.terminal = Some(Terminal {
                    t: to_absolute(tau),
                    condition,
                    av: vertical.av + vertical.dav * tau,
                });
            }
        }
        st.t = to_absolute(st.t);
        if let Some(l) = ev.limited.as_mut() {
            l.t = st.t;
        }
        ev
    }

    /// [`run`](Self::run) from `st.t = 0` to `t_end` (call-local times; the
    /// call starts at the absolute time `t0`), at most `budget` units of work.
    fn run_local(
        &self,
        st: &mut State,
        t0: f64,
        t_end: f64,
        (input, vertical): (GroundInput, VerticalInput),
        stop_at_event: bool,
        budget: Option<u64>,
    ) -> Events {
        let mut ev = Events::default();
        let eom = Eom::with_vertical(self, st.t, input, vertical);
        let tol = self.tol();
        let call = Call {
            sim: self,
            eom: &eom,
            tol: &tol,
            t_end,
            stop_at_event,
            budget,
        };
        if st.theta == 0.0 && st.omega == 0.0 {
            st.at_rest = true;
        }
        loop {
            if st.at_rest && !eom.rigid && self.model.restraint.is_none() {
                // flexible law: theta = omega = 0 is an equilibrium as long
                // as there is no ground motion (hW(0, N) = 0 for every N)
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
                            ev.stopped_at_event = true;
                            return ev;
                        }
                    }
                }
            }
            let stop = match self.method {
                Method::Dp5 => StepCx::new::<Dp5>(call, st, &mut ev).steps::<Dp5>(),
                Method::Dop853 => StepCx::new::<Dop853>(call, st, &mut ev).steps::<Dop853>(),
            };
            if stop != Stop::End || st.overturned || !st.at_rest || st.t >= t_end {
                ev.stopped_at_event = stop == Stop::Event;
                return ev;
            }
        }
    }

    /// When a rigid body at rest at `t` lifts off before `t_end`: the first
    /// time `|ag| > g tan(alpha)` (the input is linear), or `None`.
    fn uplift_time(&self, eom: &Eom, t: f64, t_end: f64) -> Option<f64> {
        if eom.vertical || self.model.restraint.is_some() {
            return self.release_time(eom, t, t_end);
        }
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
            tu.next_up()
        };
        (tu < t_end).then_some(tu)
    }
}

impl Simulator {
    /// When a body at rest at `t` is no longer held before `t_end`, for a
    /// vertical input or a one-sided body ([`Simulator::held`]): on each side
    /// `s` it may leave to, the push `-s ag(t) - k (g + av(t))` is linear in
    /// `t` (`k = tan(alpha)` rigid, 0 flexible one-sided); the first time it
    /// is positive.
    fn release_time(&self, eom: &Eom, t: f64, t_end: f64) -> Option<f64> {
        let b = &self.model.body;
        let k = if eom.rigid { b.b / b.hg } else { 0.0 };
        let sides: &[f64] = match self.model.restraint {
            Some(ref r) => std::slice::from_ref(&r.side),
            None => &[1.0, -1.0],
        };
        let push = |s: f64, t: f64| -s * eom.ag(t) - k * (b.g + eom.av(t));
        let mut first: Option<f64> = None;
        for &s in sides {
            let f0 = push(s, t);
            let df = -s * eom.dag() - k * eom.dav();
            let tu = if f0 > 0.0 {
                t
            } else if df > 0.0 {
                let x = t - f0 / df;
                if push(s, x) > 0.0 {
                    x
                } else {
                    x.next_up()
                }
            } else {
                continue;
            };
            if tu < t_end && first.is_none_or(|f| tu < f) {
                first = Some(tu);
            }
        }
        first
    }
}

/// The settings of one call, the same for each of its step loops.
#[derive(Clone, Copy)]
pub(super) struct Call<'c, 'm> {
    pub(super) sim: &'c Simulator,
    pub(super) eom: &'c Eom<'m>,
    pub(super) tol: &'c Tol,
    /// The call's end (call-local time), s.
    pub(super) t_end: f64,
    /// Stop at an event for the caller to see it.
    pub(super) stop_at_event: bool,
    /// The most work (steps, rejections and zero crossings) of the call.
    pub(super) budget: Option<u64>,
}

/// One step loop: from the state to `t_end`, an event the caller wants,
/// rest, overturning or the work limit. The fields but `call` change from
/// step to step.
pub(super) struct StepCx<'c, 'm> {
    pub(super) call: Call<'c, 'm>,
    pub(super) st: &'c mut State,
    pub(super) ev: &'c mut Events,
    /// Side of the motion at the step start (see `eom::side_of`).
    pub(super) side: f64,
    /// Warm start of the contact solve at the step start, m.
    pub(super) hint: f64,
    /// `theta''` at the step start, rad/s².
    pub(super) a0: f64,
    /// The step to try next, s.
    pub(super) h: f64,
    /// The last attempt was rejected: the next step may not grow.
    pub(super) rejected: bool,
    /// The Rosenbrock Jacobian at the current step start.
    pub(super) jac: Option<Jac>,
    /// `|theta|` of the overturning event being located, rad: `thetaOv`,
    /// or under a vertical input (flexible laws) the root of `hW(phi, N(t))`
    /// found on the step (docs/model.md §6.4).
    pub(super) ov_level: f64,
    /// `|theta|` of the moving kink being located (docs/model.md §6.4), rad.
    pub(super) kink_level: f64,
}

/// One attempted step from the context's state.
pub(super) struct Trial {
    /// Start time, s.
    pub(super) t: f64,
    /// `(theta, omega)` at the start.
    pub(super) y0: [f64; 2],
    /// End time (`t_end` on the last step), s.
    pub(super) t_new: f64,
    /// `t_new - t`, s.
    pub(super) hh: f64,
    /// Cut by `t_end`.
    pub(super) last: bool,
    pub(super) kind: Kind,
    pub(super) out: StepOut,
    /// The contact warm start at the end of the step.
    pub(super) hint: f64,
    /// The smallest step from `t`.
    pub(super) min_step: f64,
}

/// What the loop does after an event.
pub(super) enum Flow {
    /// Go on stepping.
    Next,
    /// Return from the loop.
    Stop(Stop),
}

impl<'c, 'm> StepCx<'c, 'm> {
    /// The context at the state's start: `theta''` there and the first step
    /// (the state's suggestion, else Hairer's starting step).
    fn new<P: Pair>(call: Call<'c, 'm>, st: &'c mut State, ev: &'c mut Events) -> StepCx<'c, 'm> {
        let Call { sim, eom, tol, .. } = call;
        let side = sim.side(st.theta, st.omega, eom.ag(st.t));
        let mut hint = st.a;
        let a0 = eom.accel(st.t, st.theta, st.omega, side, &mut hint);
        ev.stats.evals += 1;
        let mut h = st.h;
        if h.is_nan() || h <= 0.0 {
            let start = Start {
                eom,
                t: st.t,
                y0: [st.theta, st.omega],
                a0,
                side,
            };
            h = controller::initial_step(&start, tol, &mut hint, P::ORDER);
            ev.stats.evals += 1;
        }
        if eom.rigid || !sim.stiff_mode {
            st.stiff = false;
        }
        StepCx {
            call,
            st,
            ev,
            side,
            hint,
            a0,
            h,
            rejected: false,
            jac: None,
            ov_level: sim.model.theta_ov,
            kink_level: f64::NAN,
        }
    }

    /// Under a vertical input the thresholds move with `N(t)`
    /// (docs/model.md §6.4): the fixed levels (kinks, `thetaOv` at the
    /// weight) are not used, and overturning is the zero of `hW(phi, N)`.
    fn moving_thresholds(&self) -> bool {
        self.call.eom.vertical && !self.call.eom.rigid
    }

    /// `hW(|theta(tau)|, N(t + tau h))` on the step's interpolant `herm`
    /// (`tau` a fraction of the step `tr`), m.
    fn hw_on_step(&self, tr: &Trial, herm: &Hermite, tau: f64) -> f64 {
        let phi = herm.theta(tau).abs();
        let n = self.call.eom.apparent_weight(tr.t + tau * tr.hh);
        // the contact the equation of motion uses
        let (c, _) = self.call.eom.contact_loaded(phi, n, &mut tr.hint.clone());
        self.call.sim.model.levers(phi, &c).hw
    }

    /// Under moving thresholds, the overturning on the accepted step `tr`
    /// (docs/model.md §6.4: the first zero of `hW(phi, N)` moving outwards),
    /// as a fraction of the step, located by bisection on the interpolant.
    fn moving_overturn(&mut self, tr: &Trial, herm: &Hermite) -> Option<f64> {
        if self.side * tr.out.y[1] <= 0.0 || self.side * tr.out.y[0] <= 0.0 {
            return None;
        }
        if self.hw_on_step(tr, herm, 1.0) > 0.0 {
            return None;
        }
        // hW(phi, N) has its first root at thetaOv(N): a sign found below
        // that is rounding in the lever of a rotation too small to carry
        // it (a body leaving rest at 1e-75 rad), not overturning.
        let phi_end = tr.out.y[0].abs();
        let n_end = self.call.eom.apparent_weight(tr.t + tr.hh);
        if phi_end < (1.0 - 1e-6) * self.call.sim.model.theta_ov_at(n_end) {
            return None;
        }
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.hw_on_step(tr, herm, mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        self.ov_level = herm.theta(hi).abs();
        Some(hi)
    }

    /// `(|theta(tau)|, N(t + tau h))` at `tau` of the step `tr`
    /// (interpolated by `herm`): where the event functions of
    /// docs/model.md §6.4 are evaluated.
    fn point_on_step(&self, tr: &Trial, herm: &Hermite, tau: f64) -> (f64, f64) {
        let phi = herm.theta(tau).abs();
        (phi, self.call.eom.apparent_weight(tr.t + tau * tr.hh))
    }

    /// Under moving thresholds, the first zero on the step `tr` of a
    /// threshold's function (docs/model.md §6.4: joint opening, crushing
    /// onset, an edge of the stress profile at a break of the width), as a
    /// fraction of the step, located on the interpolant; sets
    /// [`kink_level`](Self::kink_level). A function within `1e-10` of its
    /// zero at the step start is the kink the step starts on.
    fn moving_kink(&mut self, tr: &Trial, herm: &Hermite) -> Option<f64> {
        let edges = if self.call.sim.kinks.sides_from_edge {
            [
                self.edge_at(tr.t, tr.y0[0], self.hint),
                // the time of the step's last stage
                self.edge_at(tr.t + tr.hh, tr.out.y[0], tr.hint),
            ]
        } else {
            [f64::NAN; 2]
        };
        let with_edge = |(phi, n), edge| (phi, n, edge);
        let ends = (
            with_edge(self.point_on_step(tr, herm, 0.0), edges[0]),
            with_edge(self.point_on_step(tr, herm, 1.0), edges[1]),
        );
        let tau = self
            .call
            .sim
            .thresholds_crossed(ends.0, ends.1)
            .map(|(i, m0, m1)| self.margin_zero(tr, herm, i, m0, m1))
            .fold(f64::INFINITY, f64::min);
        if tau > 1.0 {
            return None;
        }
        self.kink_level = herm.theta(tau).abs();
        Some(tau)
    }

    /// The edge `a` of the contact at `(t, theta)` (m,
    /// [`Eom::contact_edge`], the solve warm started from `hint`).
    fn edge_at(&self, t: f64, theta: f64, hint: f64) -> f64 {
        let (phi, n) = (theta.abs(), self.call.eom.apparent_weight(t));
        let eom = self.call.eom;
        self.call
            .sim
            .threshold_limits
            .edge(phi, n, || eom.contact_edge(phi, n, hint))
    }

    /// The zero of the `i`-th margin on the step, bracketed by `f0` at 0 and
    /// `f1` at 1 of opposite signs: the end of the bracket past the zero, to
    /// `1e-12` of the step (Illinois regula falsi: the margin is smooth in
    /// `tau` between kinks of `w`, so a few evaluations).
    fn margin_zero(&self, tr: &Trial, herm: &Hermite, i: usize, mut f0: f64, mut f1: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, 1.0);
        let mut last = 0;
        for _ in 0..60 {
            if hi - lo <= 1e-12 {
                break;
            }
            let mut x = (lo * f1 - hi * f0) / (f1 - f0);
            if !(x > lo && x < hi) {
                x = 0.5 * (lo + hi);
            }
            let (phi, n) = self.point_on_step(tr, herm, x);
            let fx = self.call.sim.threshold_margin(i, phi, n, false);
            if (fx > 0.0) == (f0 > 0.0) {
                lo = x;
                f0 = fx;
                if last == -1 {
                    f1 *= 0.5;
                }
                last = -1;
            } else {
                hi = x;
                f1 = fx;
                if last == 1 {
                    f0 *= 0.5;
                }
                last = 1;
            }
        }
        hi
    }

    /// The loop: attempt, reject or accept, then take the step or the event
    /// found on its dense output.
    fn steps<P: Pair>(mut self) -> Stop {
        while self.st.t < self.call.t_end {
            if self.over_budget() {
                self.st.h = self.h;
                return Stop::Limit;
            }
            let tr = self.attempt::<P>();
            let acceptable = tr.out.err <= 1.0; // false for NaN
            if !acceptable && tr.hh > tr.min_step {
                self.reject::<P>(&tr);
                continue;
            }
            let h_next = self.accept::<P>(&tr);
            let herm = Hermite::new(
                tr.hh,
                [tr.y0[0], tr.y0[1], self.a0],
                [tr.out.y[0], tr.out.y[1], tr.out.accel],
            );
            self.jac = None;
            // RODAS steps are not cut at the kinks: its steps are long, and
            // the projection on the slow manifold moves the state off them
            let moving = self.moving_thresholds();
            let kinks = if self.st.stiff || moving {
                &[][..]
            } else {
                self.call.sim.kinks.as_slice()
            };
            let theta_ov = if moving {
                f64::INFINITY
            } else {
                self.call.sim.model.theta_ov
            };
            let found = match first_event(&herm, self.side, theta_ov, kinks) {
                None if moving => self
                    .moving_overturn(&tr, &herm)
                    .map(|tau| (Hit::Overturn, tau))
                    .or_else(|| {
                        // not in the stiff mode, as the fixed kinks
                        (!self.st.stiff)
                            .then(|| self.moving_kink(&tr, &herm))
                            .flatten()
                            .map(|tau| (Hit::MovingKink, tau))
                    }),
                f => f,
            };
            match found {
                None => {
                    self.take(&tr, &herm);
                    self.h = h_next;
                }
                Some((hit, tau)) => match self.event::<P>(&tr, &herm, hit, tau, h_next) {
                    Flow::Next => {}
                    Flow::Stop(s) => return s,
                },
            }
        }
        self.st.h = self.h;
        Stop::End
    }

    /// Whether the call has used its work budget.
    fn over_budget(&mut self) -> bool {
        let Some(budget) = self.call.budget else {
            return false;
        };
        let work = self.ev.work();
        if work < budget {
            return false;
        }
        self.ev.limited = Some(Limited::at(self.ev, self.st, budget, self.h));
        true
    }

    /// A step of `self.h` (cut at `t_end`) from the state, with the kind of
    /// method of the mode (projecting the state on the slow manifold first
    /// in the stiff mode, see `stiffness::slow_state`).
    fn attempt<P: Pair>(&mut self) -> Trial {
        let t = self.st.t;
        let last = t + 1.01 * self.h >= self.call.t_end;
        let t_new = if last { self.call.t_end } else { t + self.h };
        let hh = t_new - t;
        let kind = if self.st.stiff {
            Kind::Rodas(self.stiff_jacobian(hh))
        } else {
            Kind::Explicit
        };
        let start = self.start();
        let mut hint = self.hint;
        let out = stiffness::attempt::<P>(&start, &kind, hh, &mut hint, self.call.tol, self.ev);
        Trial {
            t,
            y0: start.y0,
            t_new,
            hh,
            last,
            kind,
            out,
            hint,
            min_step: controller::min_step(t, hh),
        }
    }

    /// The Jacobian at the step start, computed once per step start. In the
    /// stiff mode an oscillation about the quasi-static state below the
    /// tolerance at the rocking scale, `rtol thetaOv`, is projected away
    /// (onto the linearised slow manifold), so that RODAS is not held to
    /// resolve it.
    fn stiff_jacobian(&mut self, hh: f64) -> Jac {
        if let Some(j) = self.jac {
            return j;
        }
        let tol = self.call.tol;
        let start = self.start();
        let mut j = stiffness::jacobian(&start, hh, self.hint, tol, self.ev);
        let negligible = tol.rtol * self.call.sim.model.theta_ov;
        if let Some((th, om)) = stiffness::slow_state(&j, start.y0, start.a0, negligible) {
            self.st.theta = th;
            self.st.omega = om;
            self.a0 = start.accel(start.t, [th, om], &mut self.hint);
            self.ev.stats.evals += 1;
            j = stiffness::jacobian(&self.start(), hh, self.hint, tol, self.ev);
        }
        self.jac = Some(j);
        j
    }

    /// The step start at the state.
    fn start(&self) -> Start<'c> {
        self.start_at(self.st.t, [self.st.theta, self.st.omega])
    }

    /// The step start at `(t, y0)` with the context's `theta''` and side.
    pub(super) fn start_at(&self, t: f64, y0: [f64; 2]) -> Start<'c> {
        Start {
            eom: self.call.eom,
            t,
            y0,
            a0: self.a0,
            side: self.side,
        }
    }

    /// A rejected step: shorter by the controller, and cut just past a kink
    /// it ran across.
    fn reject<P: Pair>(&mut self, tr: &Trial) {
        self.ev.stats.rejected += 1;
        let f = controller::shrink(tr.out.err, tr.kind.err_exp::<P>());
        self.h = (tr.hh * f).max(tr.min_step);
        let kinks = &self.call.sim.kinks;
        if !kinks.as_slice().is_empty()
            && !self.st.stiff
            && !self.moving_thresholds()
            && tr.out.err.is_finite()
        {
            let herm = Hermite::new(
                tr.hh,
                [tr.y0[0], tr.y0[1], self.a0],
                [tr.out.y[0], tr.out.y[1], tr.out.accel],
            );
            self.h = kinks.retry_past(
                &herm,
                self.side,
                self.call.sim.model.theta_ov,
                tr.hh,
                self.h,
                tr.min_step,
            );
        }
        if self.moving_thresholds() && !self.st.stiff && tr.out.err.is_finite() {
            // cut just past a moving kink the step ran across
            let herm = Hermite::new(
                tr.hh,
                [tr.y0[0], tr.y0[1], self.a0],
                [tr.out.y[0], tr.out.y[1], tr.out.accel],
            );
            if let Some(tau) = self.moving_kink(tr, &herm) {
                self.h = self.h.min(1.01 * tau * tr.hh).max(tr.min_step);
            }
        }
        self.rejected = true;
    }

    /// An accepted step: counted, the mode switched if it argues for it
    /// (steps not cut by `t_end`); returns the next step size.
    fn accept<P: Pair>(&mut self, tr: &Trial) -> f64 {
        self.ev.stats.steps += 1;
        if self.st.stiff {
            self.ev.stats.stiff_steps += 1;
        }
        let fac = controller::grow(tr.out.err, tr.kind.err_exp::<P>(), self.rejected);
        self.rejected = false;
        let mut h_next = if tr.last {
            (tr.hh * fac).max(self.h)
        } else {
            tr.hh * fac
        };
        h_next = h_next.max(tr.min_step);
        if !self.call.eom.rigid {
            h_next = controller::toward_zero(
                h_next,
                tr.hh,
                fac,
                tr.out.y,
                self.call.sim.model.interface.theta_jo(),
            );
        }
        if !self.call.eom.rigid && !tr.last && self.call.sim.stiff_mode {
            stiffness::switch(
                &mut self.st.stiff,
                &mut self.st.switch_count,
                tr.hh,
                tr.out.rho,
            );
        }
        h_next
    }

    /// The state moves to the end of the accepted step.
    pub(super) fn take(&mut self, tr: &Trial, herm: &Hermite) {
        self.note_opening(herm, 1.0);
        self.st.t = tr.t_new;
        self.st.theta = tr.out.y[0];
        self.st.omega = tr.out.y[1];
        self.a0 = tr.out.accel;
        self.hint = tr.hint;
        self.st.a = self.hint;
        if !self.call.eom.rigid {
            self.side =
                self.call
                    .sim
                    .side(self.st.theta, self.st.omega, self.call.eom.ag(self.st.t));
        }
    }
}
