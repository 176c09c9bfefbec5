//! Model Exchange: the motion as a host's own solver integrates it
//! (docs/model-exchange.md). The host integrates `(theta, omega)` with
//! [`Simulator::derivatives`], watches [`Simulator::event_indicators`] for sign
//! changes and, at each one, calls [`Simulator::event_update`]; this module
//! only evaluates. The equation of motion is the one `Eom` gives the
//! co-simulation integrator, the impact map and the rest criteria are the
//! co-simulation's (`Simulator::comes_to_rest`, `Simulator::settles`).
//!
//! Event indicators (a state event where one changes sign), in this order:
//!
//! | index | indicator | event |
//! |---|---|---|
//! | 0 | `side theta` | zero crossing (impact): `omega <- eta omega`, the toe switches (docs/model.md §3) |
//! | 1 | `thetaOv - abs(theta)` | overturning: the run ends |
//! | 2 | `g tan(alpha) - abs(ag)` while a rigid body rests, else 1 | uplift from rest |
//! | 3.. | `abs(theta) - level` per kink of `af`, one slot per threshold of [`Interface::moving_thresholds`](crate::interface::Interface::moving_thresholds) in its order ([`KINK_SLOTS`]; a kink not reached below `thetaOv`, or absent, 1) | none: the solver restarts at the kink |
//! | 9 | the smallest relative margin of `N = W + m av` to its limits (1 without `av`) | the input left the model's range (docs/model.md §6.5): the run ends |
//! | 10..15 | `abs(theta) - level` for the kinks of slots 3 to 8 at `N = W` (their levels without `av`) on a flexible law with `shiftingPivot` (else 1) | none: `I(phi, W)`, to which the state `omegaW` is referred, has a kink there |
//!
//! Under a vertical input `av` (docs/model.md §6) the uplift threshold is
//! `(g + av) tan(alpha)`; for a flexible law, indicator 1 is
//! `hW(phi, N)/phi`, positive below `thetaOv(N)`, and the kink slots are
//! the thresholds' margins at N (docs/model.md §6.4). A one-sided body
//! (docs/model.md §7) keeps its toe: the crossing is a restraint impact.
//!
//! `side` (the toe the body rocks about, `±1`) is a discrete state: the
//! crossing indicator is positive on the toe's side, so a body that the
//! impact map leaves exactly at `theta = 0` moving into the other side does
//! not fire again.

use crate::interface::{Law, Threshold, THRESHOLDS};
use crate::model::Formulation;

use super::eom::{side_of, Eom};
use super::events::count_crossing;
use super::output_rates::{compose, jet_div, jet_mul, jet_scale, Jet, OutputRates};
use super::{Events, GroundInput, OutOfRange, Simulator, State, VerticalInput};

/// Event-indicator slots for the kinks of `af` (docs/model.md §2: `thetaJo`,
/// `thetaC`, and the two breaks of a hollow section's width, each passed by
/// the contact edge and by the plastic edge), one per moving threshold.
pub const KINK_SLOTS: usize = THRESHOLDS;
/// Number of event indicators: crossing, overturning, uplift, kinks, the
/// range of the apparent weight (docs/model.md §6.5), and the kinks of the
/// inertia at the weight that the state `omegaW` is referred to.
pub const EVENT_INDICATORS: usize = 4 + 2 * KINK_SLOTS;
/// The slot of the range indicator.
const RANGE: usize = 3 + KINK_SLOTS;
/// The first of the slots for the kinks at N = W under a vertical input
/// ([`Simulator::weight_referral`]).
const REFERRED: usize = RANGE + 1;

/// The state of a run under Model Exchange: the co-simulation [`State`]
/// (its `theta`, `omega` are the continuous states; `t` the host's time;
/// the integrator fields unused) and the toe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Continuous {
    pub state: State,
    /// The toe the body rocks about, `+1` or `-1` (see the module doc).
    pub side: f64,
    /// `|omega|` just after the last impact of a rigid body, rad/s (0: none
    /// since the start or the last uplift): see [`Simulator::event_update`].
    pub left_with: f64,
}

/// What an event update did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct EventUpdate {
    /// `theta` or `omega` were changed (the host must re-read them).
    pub states_changed: bool,
    /// A zero crossing of `theta` was applied (impact map).
    pub crossing: bool,
    /// The body came to rest.
    pub came_to_rest: bool,
    /// A rigid body at rest lifted off.
    pub uplift: bool,
    /// The body overturned: the run is over.
    pub overturned: bool,
    /// The vertical input left the model's range (docs/model.md §6.5): the
    /// run is over.
    pub out_of_range: Option<OutOfRange>,
}

impl Simulator {
    /// The state at the start of a run from `theta0`, `omega0` (rad, rad/s)
    /// under the ground acceleration `ag` (m/s²).
    pub fn continuous(&self, theta0: f64, omega0: f64, ag: f64) -> Continuous {
        Continuous {
            state: self.initial_state(theta0, omega0),
            side: self.side(theta0, omega0, ag),
            left_with: 0.0,
        }
    }

    /// `[theta', omega']` (rad/s, rad/s²) at `c` under the ground
    /// acceleration `ag` (m/s²): the equation of motion of docs/model.md §3
    /// on the toe `c.side`; zero while a rigid body rests and after
    /// overturning, whatever states the host sets (a solver probing its
    /// Jacobian): rest ends at uplift only, which sets the states to 0.
    pub fn derivatives(&self, c: &Continuous, ag: f64) -> [f64; 2] {
        self.derivatives_vertical(c, ag, 0.0)
    }

    /// [`derivatives`](Self::derivatives) under the vertical ground
    /// acceleration `av` (m/s²) too. The host gives no input derivative,
    /// so the `dI/dN dN/dt` term of docs/model.md §6.2 is left out: under a
    /// constant `av` (or `av = 0`) this is the co-simulation's equation.
    pub fn derivatives_vertical(&self, c: &Continuous, ag: f64, av: f64) -> [f64; 2] {
        let st = &c.state;
        // a one-sided body at rest is held by the restraint (docs/model.md
        // §7.1) until the uplift indicator fires
        let held = self.is_rigid() || self.model.restraint.is_some();
        if st.overturned || (st.at_rest && held) {
            return [0.0, 0.0];
        }
        let eom = Eom::with_vertical(
            self,
            st.t,
            GroundInput { ag, dag: 0.0 },
            VerticalInput { av, dav: 0.0 },
        );
        let mut hint = st.a;
        [
            st.omega,
            eom.accel(st.t, st.theta, st.omega, c.side, &mut hint),
        ]
    }

    /// `sqrt(I(phi, N))` at `theta` under `N = W + m av` (kg^(1/2) m): the
    /// factor between `omega` and the state `q = sqrt(I) omega` of the
    /// power form (docs/model-exchange.md, "A varying `av`").
    pub fn sqrt_inertia(&self, theta: f64, av: f64) -> f64 {
        self.inertia_at(theta, av).0.sqrt()
    }

    /// `(I, dI/dphi)` at `theta` under `N = W + m av`, kg m² and kg m²/rad.
    fn inertia_at(&self, theta: f64, av: f64) -> (f64, f64) {
        let b = &self.model.body;
        let n = b.weight + b.mass * av;
        let phi = theta.abs();
        let l = self.model.levers(phi, &self.model.contact_loaded(phi, n).0);
        (l.inertia, l.dinertia)
    }

    /// `[theta', q']` at `c` under `ag`, `av` (m/s²), with `q = sqrt(I)
    /// omega` (`c.state.omega` is `q / sqrt(I)` at this `av`): the power
    /// form of docs/model.md §6.2 as `theta' = q/sqrt(I)`, `q' = (-s N hW -
    /// m ag hg)/sqrt(I)`, exact for any `av(t)` with no derivative of it
    /// (`dI/dN dN/dt` is in the change of `sqrt(I)`). Computed as
    /// `sqrt(I) omega' + s (dI/dphi) omega²/(2 sqrt(I))` from `omega'` at
    /// `dN/dt = 0`, so `costa` (whose `omega'` has no `dN/dt` term) gets
    /// the term `-(dI/dN)(dN/dt) omega/(2 sqrt(I))` wrong under a varying
    /// `av` instead; the rigid law's `IO` does not depend on N.
    pub fn derivatives_q(&self, c: &Continuous, ag: f64, av: f64) -> [f64; 2] {
        self.derivatives_power(c, ag, av, self.inertia_at(c.state.theta, av))
    }

    /// `[theta', q']` at `c` (its `omega`) under `ag`, `av`, given `(I,
    /// dI/dphi)` there ([`derivatives_q`](Self::derivatives_q)).
    fn derivatives_power(&self, c: &Continuous, ag: f64, av: f64, (i, di): (f64, f64)) -> [f64; 2] {
        let [theta_dot, omega_dot] = self.derivatives_vertical(c, ag, av);
        if theta_dot == 0.0 && omega_dot == 0.0 {
            return [0.0, 0.0];
        }
        let sq = i.sqrt();
        let omega = c.state.omega;
        [
            theta_dot,
            sq * omega_dot + 0.5 * toe_sign(c) * di * omega * omega / sq,
        ]
    }

    /// `sqrt(I(phi, N)/I(phi, W))` at `theta` under `av` (m/s²): the factor
    /// from `omega` to Model Exchange's velocity state `omegaW` (docs/
    /// model-exchange.md, "The state omegaW"). `None` where the model makes
    /// it 1, so that `omegaW` is `omega` bit for bit: `av = 0`, the rigid
    /// law (`IO` does not depend on N) and `costa` (whose `omega` form has no
    /// `dN/dt` term to carry).
    pub fn weight_referral(&self, theta: f64, av: f64) -> Option<f64> {
        if av == 0.0 || !self.inertia_moves_with_n() {
            return None;
        }
        Some((self.inertia_at(theta, av).0 / self.inertia_at(theta, 0.0).0).sqrt())
    }

    /// The equation's inertia term depends on N: a flexible law with
    /// `shiftingPivot`.
    fn inertia_moves_with_n(&self) -> bool {
        !self.is_rigid() && self.model.formulation == Formulation::ShiftingPivot
    }

    /// `c`, whose `state.omega` is the state `omegaW`, with `omega` there
    /// instead, under `av` (m/s²).
    pub fn from_weight_referred(&self, mut c: Continuous, av: f64) -> Continuous {
        if let Some(r) = self.weight_referral(c.state.theta, av) {
            c.state.omega /= r;
        }
        c
    }

    /// `c`, whose `state.omega` is `omega`, with the state `omegaW` there
    /// instead, under `av` (m/s²).
    pub fn to_weight_referred(&self, mut c: Continuous, av: f64) -> Continuous {
        if let Some(r) = self.weight_referral(c.state.theta, av) {
            c.state.omega *= r;
        }
        c
    }

    /// The jet `[omegaW, omegaW', omegaW'']` (rad/s per s^order) along the
    /// motion at `state` (co-simulation's, with `omega`) whose output rates
    /// under `ag` (m/s²) and `v` are `rates`: `omegaW = omega r`,
    /// `r = sqrt(I(phi, N)/I(phi, W))` (docs/model-exchange.md, "The state
    /// omegaW"), with `I = Ic + m (R0² + af² - 2 R0 af sin(alpha))`
    /// (docs/model.md §3) along `af(phi(t), N(t))` (the rates' `af`) and
    /// along `af(phi(t), W)`. `omega`'s own jet where `r` is 1 at all times
    /// (no vertical input, the rigid law, `costa`) and at rest, where `r`
    /// and `r'` are 1 and 0 (the full contact's `af` does not move with N).
    pub fn omega_w_rates(
        &self,
        state: &State,
        ag: f64,
        v: VerticalInput,
        rates: &OutputRates,
    ) -> Jet {
        let loaded = v.av != 0.0 || v.dav != 0.0;
        if !loaded || !self.inertia_moves_with_n() || state.at_rest {
            return rates.omega;
        }
        let b = &self.model.body;
        let inertia = |af: Jet| -> Jet {
            let lever = 2.0 * (af[0] - b.r0 * b.sin_alpha);
            [
                b.ic + b.mass * (b.r0 * b.r0 + af[0] * af[0] - 2.0 * b.r0 * b.sin_alpha * af[0]),
                b.mass * lever * af[1],
                b.mass * (2.0 * af[1] * af[1] + lever * af[2]),
            ]
        };
        let s = side_of(state.theta, state.omega, ag);
        let p = jet_scale(s, rates.theta);
        let it = &self.model.interface;
        let c = it.contact(p[0]);
        let (af2, _) = it.second_derivatives(&c);
        let af_w = compose(&[c.af, c.daf, af2], p);
        let q = jet_div(inertia(rates.af), inertia(af_w));
        let r0 = q[0].sqrt();
        let r1 = q[1] / (2.0 * r0);
        let r = [r0, r1, (q[2] - 2.0 * r1 * r1) / (2.0 * r0)];
        jet_mul(rates.omega, r)
    }

    /// `[theta', omegaW']` at `cw` (whose `state.omega` is `omegaW`) under
    /// `ag`, `av` (m/s²): Model Exchange's right-hand side, exact for any
    /// `av(t)` with no derivative of it. `omegaW = q/sqrt(J)` with the power
    /// form's `q = sqrt(I) omega` ([`derivatives_q`](Self::derivatives_q))
    /// and `J = I(phi, W)`, which does not depend on `av`, so
    /// `omegaW' = q'/sqrt(J) - omegaW s (dJ/dphi) theta'/(2 J)`. Where
    /// [`weight_referral`](Self::weight_referral) is `None` this is
    /// [`derivatives_vertical`](Self::derivatives_vertical), bit for bit.
    pub fn derivatives_weight_referred(&self, cw: &Continuous, ag: f64, av: f64) -> [f64; 2] {
        if av == 0.0 || !self.inertia_moves_with_n() {
            return self.derivatives_vertical(cw, ag, av);
        }
        // each inertia once: every one is a contact solve at (phi, N)
        let theta = cw.state.theta;
        let (i, di) = self.inertia_at(theta, av);
        let (j, dj) = self.inertia_at(theta, 0.0);
        let mut c = *cw;
        c.state.omega /= (i / j).sqrt();
        let [theta_dot, q_dot] = self.derivatives_power(&c, ag, av, (i, di));
        [
            theta_dot,
            q_dot / j.sqrt() - 0.5 * cw.state.omega * toe_sign(cw) * dj * theta_dot / j,
        ]
    }

    /// The event indicators at `c` under `ag` (see the module doc).
    pub fn event_indicators(&self, c: &Continuous, ag: f64) -> [f64; EVENT_INDICATORS] {
        self.event_indicators_vertical(c, ag, 0.0)
    }

    /// [`event_indicators`](Self::event_indicators) under `av` (m/s²): the
    /// uplift threshold `(g + av) tan(alpha)`; overturning, for a flexible
    /// law, the sign of `hW(phi, N)/phi` (docs/model.md §6.4); and the
    /// range indicator, the smallest relative margin of `N` to its limits.
    pub fn event_indicators_vertical(
        &self,
        c: &Continuous,
        ag: f64,
        av: f64,
    ) -> [f64; EVENT_INDICATORS] {
        let mut z = [1.0; EVENT_INDICATORS];
        let st = &c.state;
        if st.overturned {
            return z;
        }
        let phi = st.theta.abs();
        z[1] = self.model.theta_ov - phi;
        if av != 0.0 {
            z[RANGE] = self.model.range_margin(av);
            if !self.is_rigid() {
                z[1] = self.hw_over_phi(phi, av);
            }
        }
        if st.at_rest && (self.is_rigid() || self.model.restraint.is_some()) {
            z[2] = self.release_margin(ag, av);
            return z;
        }
        z[0] = c.side * st.theta;
        let moving = (av != 0.0 && !self.is_rigid()).then(|| {
            let n = self.model.body.weight + self.model.body.mass * av;
            self.threshold_margins(phi, n)
        });
        let k = &self.kinks;
        for (i, zi) in z[3..3 + KINK_SLOTS].iter_mut().enumerate() {
            let (Some(t), level) = (k.thresholds[i], k.at_weight[i]) else {
                continue;
            };
            *zi = match (moving, level) {
                (None, Some(level)) => phi - level,
                (None, None) => 1.0,
                // the thresholds move with N (docs/model.md §6.4): the
                // margin signed as `phi - level` is (a contact edge passes
                // its point as phi grows, a plastic edge as phi falls), so
                // that `av` leaving 0 flips no indicator; one not reached
                // below thetaOv at the weight signed as that slot's 1 (its
                // edge short of the point, or the toe uncrushed)
                (Some(m), level) => {
                    let contact = matches!(t, Threshold::Contact(_));
                    if contact == level.is_some() {
                        -m[i]
                    } else {
                        m[i]
                    }
                }
            };
        }
        if self.inertia_moves_with_n() {
            // `omegaW`'s inertia I(phi, W) has the kinks of af at the
            // weight, which under av != 0 are no kinks of the motion: the
            // solver restarts there too. At av = 0 these are slots 3 to 8
            // over again (the same values: the same events), so that av
            // leaving 0 flips no indicator.
            for (zi, level) in z[REFERRED..].iter_mut().zip(self.kinks.at_weight) {
                if let Some(level) = level {
                    *zi = phi - level;
                }
            }
        }
        z
    }

    /// The event update at `c` under `ag`: overturning, uplift from rest, or
    /// the zero crossing of `theta` (impact map, then the rest criteria),
    /// whichever the state shows; nothing at a kink. The state is examined,
    /// not the indicator that fired, so a repeated or a spurious call
    /// changes nothing.
    ///
    /// Rest of a rigid body (docs/model-exchange.md): at an impact, either
    /// the co-simulation criterion (the remaining chattering is below the
    /// tolerance, [`Simulator::rest_bound`]), or, without ground motion
    /// (`ag = 0` at this impact and the previous one), the host no longer
    /// resolves the chattering: the body came back faster than `1/sqrt(eta)`
    /// times the speed it left the previous impact with. Without ground
    /// motion energy is conserved between impacts, so a resolved excursion
    /// returns at the speed it left with; a host whose error adds per
    /// excursion more than half the energy an impact takes out (a fixed
    /// step near the excursion's duration: explicit Euler settles into
    /// impacts every few steps that never decay) would chatter for ever.
    pub fn event_update(&self, c: &mut Continuous, ag: f64) -> EventUpdate {
        self.event_update_vertical(c, ag, 0.0)
    }

    /// [`event_update`](Self::event_update) under `av` (m/s²): the range of
    /// docs/model.md §6.5 first, the moving overturning level, the
    /// restraint of §7.
    pub fn event_update_vertical(&self, c: &mut Continuous, ag: f64, av: f64) -> EventUpdate {
        let mut u = EventUpdate::default();
        self.completed_step(c);
        let rigid = self.is_rigid();
        if av != 0.0 && !c.state.overturned {
            u.out_of_range = self
                .out_of_range(VerticalInput { av, dav: 0.0 }, 0.0)
                .map(|x| x.1);
            if u.out_of_range.is_some() {
                return u;
            }
        }
        let beyond = if av != 0.0 && !rigid {
            c.state.theta != 0.0 && self.hw_over_phi(c.state.theta.abs(), av) <= 0.0
        } else {
            c.state.theta.abs() >= self.model.theta_ov
        };
        let st = &mut c.state;
        if st.overturned {
            return u;
        }
        if beyond {
            st.overturned = true;
            u.overturned = true;
            return u;
        }
        if st.at_rest {
            if (rigid || self.model.restraint.is_some()) && !self.held(ag, av) {
                st.theta = 0.0;
                st.omega = 0.0;
                st.at_rest = false;
                c.side = self.side(0.0, 0.0, ag);
                c.left_with = 0.0;
                leave_zero(c.side, &mut st.theta);
                u.uplift = true;
                u.states_changed = true;
            }
            return u;
        }
        if !crossed(c.side, st) {
            return u;
        }
        u.crossing = true;
        u.states_changed = true;
        let eta = match self.model.restraint {
            Some(r) => r.e,
            None => self.model.eta,
        };
        let unresolved = rigid
            && eta < 1.0
            && c.left_with > 0.0
            && ag == 0.0
            && st.omega.abs() * eta.sqrt() >= c.left_with;
        if rigid || self.model.restraint.is_some() {
            // docs/model.md §3: for the rigid law every crossing is an
            // impact; §7.1: every return to the restraint is one
            st.opened = true;
        }
        count_crossing(st, &mut Events::default());
        st.omega = self.restitution(st.omega);
        c.left_with = if rigid && ag == 0.0 {
            st.omega.abs()
        } else {
            0.0
        };
        if self.model.restraint.is_none() {
            c.side = -c.side;
        }
        leave_zero(c.side, &mut st.theta);
        let n = self.model.body.weight + self.model.body.mass * av;
        let rest = if self.model.restraint.is_some() {
            unresolved || self.rests_on_restraint(st.omega, ag, av, ag == 0.0 && av == 0.0)
        } else if rigid {
            unresolved || self.comes_to_rest_at(st.omega, ag, n)
        } else {
            ag == 0.0 && av == 0.0 && self.settles(st.omega)
        };
        if rest {
            st.theta = 0.0;
            st.omega = 0.0;
            st.at_rest = true;
            c.left_with = 0.0;
            u.came_to_rest = true;
        } else if st.omega == 0.0 && !self.held(ag, av) {
            // eta = 0: stopped dead above the uplift threshold
            c.side = self.side(0.0, 0.0, ag);
            leave_zero(c.side, &mut st.theta);
        }
        u
    }

    /// Bookkeeping after an accepted step of the host: whether the joint
    /// opened (for the impact count), and a flexible body that was set to
    /// rest and has moved again. Returns whether the host must enter event
    /// mode: `theta` has crossed zero without a state event (a host whose
    /// solver could not resolve an excursion, which started at the level
    /// of its tolerance, saw no sign change), and the impact map is due.
    pub fn completed_step(&self, c: &mut Continuous) -> bool {
        if !c.state.at_rest && !c.state.overturned && c.side * c.state.theta < 0.0 {
            return true;
        }
        let st = &mut c.state;
        if st.theta.abs() > self.model.interface.theta_jo() {
            st.opened = true;
        }
        let held = self.is_rigid() || self.model.restraint.is_some();
        if st.at_rest && !held && (st.theta != 0.0 || st.omega != 0.0) {
            // a flexible body leaves rest on the side the ground pushed it to
            st.at_rest = false;
            c.side = self.side(st.theta, st.omega, 0.0);
        }
        false
    }

    /// `hW(phi, N)/phi` at `N = W + m av` (docs/model.md §6.4), m/rad:
    /// positive below `thetaOv(N)`; at `phi = 0` its limit `kn Is/N - hG`.
    /// Below `FULL_CONTACT_LIMIT` with the bed closed and uncrushed the limit
    /// is taken too: there `hW` is `phi (kn Is/N - hG)` to O(phi^3), but the
    /// resultant's shift `af - D/2`, of order `phi`, vanishes in rounding
    /// against `D/2` below about 1e-16 rad and the quotient turns to `-hG`,
    /// which would read as overturning at rest.
    fn hw_over_phi(&self, phi: f64, av: f64) -> f64 {
        /// rad; the quotient's rounding there is ~1e-10 relative, its
        /// difference from the limit O(phi^2) ~ 1e-12
        const FULL_CONTACT_LIMIT: f64 = 1e-6;
        let b = &self.model.body;
        let n = b.weight + b.mass * av;
        let full_contact = || {
            let [heel, toe] = self.model.interface.bed_margins(phi, n);
            heel > 0.0 && toe <= 0.0
        };
        if phi == 0.0 || (phi < FULL_CONTACT_LIMIT && full_contact()) {
            let (c, _) = self.model.contact_loaded(0.0, n);
            return -c.daf - b.hg;
        }
        let (c, _) = self.model.contact_loaded(phi, n);
        self.model.levers(phi, &c).hw / phi
    }

    /// How far a body at rest is from leaving it ([`Simulator::held`]),
    /// m/s², positive while held.
    fn release_margin(&self, ag: f64, av: f64) -> f64 {
        let b = &self.model.body;
        let k = if self.is_rigid() { b.b / b.hg } else { 0.0 };
        match self.model.restraint {
            None => (b.g + av) * k - ag.abs(),
            Some(r) => (b.g + av) * k + r.side * ag,
        }
    }

    /// Nominal values of `(theta, omega)`: the scales of the motion
    /// ([`Simulator::scales`]), rad and rad/s.
    pub fn nominals(&self) -> [f64; 2] {
        let (th, om) = self.scales();
        [th, om]
    }

    fn is_rigid(&self) -> bool {
        self.model.interface.law() == Law::Rigid
    }
}

/// `s = sgn(theta)`, the toe's side at `theta = 0`.
fn toe_sign(c: &Continuous) -> f64 {
    if c.state.theta != 0.0 {
        c.state.theta.signum()
    } else {
        c.side
    }
}

/// Puts `theta` strictly on the toe's side after an impact or an uplift, so
/// that the crossing indicator `side theta` starts positive: a host that
/// stopped just short of the crossing left `theta` on the old side, and one
/// that stopped exactly on it left 0, from which a solver that tracks sign
/// changes (CVode, fmpy's Euler) would miss the next crossing if the
/// excursion were shorter than its next step. The mirror image moves `theta`
/// by no more than the host's own error in locating the event.
fn leave_zero(side: f64, theta: &mut f64) {
    *theta = side * theta.abs().max(f64::MIN_POSITIVE);
}

/// `theta` has crossed zero from the toe's side: it is beyond, or exactly
/// on zero and not moving back into the toe's side (a host that located the
/// crossing at the apex of an excursion below its resolution returns
/// `theta = omega = 0`).
fn crossed(side: f64, st: &State) -> bool {
    let s = side * st.theta;
    s < 0.0 || (s == 0.0 && side * st.omega <= 0.0)
}
