//! The stepping loop of a spatial run (docs/model.md §10.4): steps of
//! DOP853 whose contact side is fixed at their start, cut where the tilt
//! turns a right angle from it (the contact has moved a quarter of the rim,
//! or the tilt has crossed upright) or reaches the overturning limit.
//!
//! A crossing is the base's return to the bed when the tilt there is
//! within [`UPRIGHT`] of the line of its contact side (`strikes`): exactly
//! on it in a plane, and within round-off of it for a planar motion along
//! an oblique azimuth. Off a plane the tilt
//! passes upright at a distance and the contact runs round the rim instead
//! (rolling, without an impact: the rigid model's motion, docs/model.md §10.3).

use nalgebra::Vector3;

use super::eom::{Eom, N};
use super::impact::impact;
use super::step::{dop853, Step};
use super::{PlanInput, Spatial, SpatialState};
use crate::dynamics::controller::{grow, min_step, shrink};
use crate::dynamics::{OutOfRange, Terminal, VerticalInput};

/// A crossing whose tilt is at most this (`sin(theta)`) is the base's
/// return to the bed. Round-off leaves about `1e-16` of the motion's tilt
/// off the plane of a planar motion along an oblique azimuth.
pub const UPRIGHT: f64 = 1e-9;

/// Whether a crossing at the tilt `e` from the contact side `d0` (unit) is
/// the base's return to the bed: the tilt's part off the line of `d0`,
/// `|e x d0|`, is within [`UPRIGHT`]. It is exactly 0 for a planar motion
/// along an axis and round-off along an oblique one, wherever on the line
/// the crossing was located (a Model Exchange host locates it only to its
/// tolerance); at a quarter turn, where `e . d0 = 0`, it is `|e|`.
pub(crate) fn strikes(e: [f64; 2], d0: [f64; 2]) -> bool {
    (e[0] * d0[1] - e[1] * d0[0]).abs() <= UPRIGHT
}

/// The controller's exponent (`-1/8`, the order of DOP853's estimate).
const ERR_EXP: f64 = -1.0 / 8.0;

/// What happened during one `advance`.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct SpatialEvents {
    pub impacts: u32,
    pub uplift: bool,
    pub came_to_rest: bool,
    /// Time of overturning, s, if it happened in this call.
    pub overturned_at: Option<f64>,
    /// Accepted and rejected steps.
    pub steps: u32,
    pub rejected: u32,
    /// The call stopped at [`Spatial::max_steps`] before `t_end`, with the
    /// state consistent at its time.
    pub limited: bool,
    /// Only from [`Spatial::advance_to_event`]: the call stopped at an
    /// uplift, an impact (and coming to rest) or overturning, the state
    /// the one just after it.
    pub stopped_at_event: bool,
    /// The input left the model's range (`g + av <= 0`: the body would leave
    /// the bed): the call ended there and the run is over.
    pub terminal: Option<Terminal>,
}

/// What ends a step early.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Cut {
    /// The tilt turned a right angle from the step's contact side.
    Quarter,
    Overturning,
    /// A flexible bed: a kink of the contact, where the step restarts.
    Kink,
}

impl Spatial {
    /// Integrate from `st.t` to `t_end` (or to overturning) under the
    /// horizontal and vertical inputs.
    pub fn advance(
        &self,
        st: &mut SpatialState,
        t_end: f64,
        input: PlanInput,
        vertical: VerticalInput,
    ) -> SpatialEvents {
        self.run(st, t_end, input, vertical, false)
    }

    /// [`advance`](Self::advance), stopping at the first uplift, impact
    /// (with coming to rest) or overturning inside the call (FMI 3.0's early
    /// return): [`SpatialEvents::stopped_at_event`], the state just after
    /// the event at its time. The contact running on round the rim off a
    /// plane is no event.
    pub fn advance_to_event(
        &self,
        st: &mut SpatialState,
        t_end: f64,
        input: PlanInput,
        vertical: VerticalInput,
    ) -> SpatialEvents {
        self.run(st, t_end, input, vertical, true)
    }

    fn run(
        &self,
        st: &mut SpatialState,
        t_end: f64,
        input: PlanInput,
        vertical: VerticalInput,
        stop_at_event: bool,
    ) -> SpatialEvents {
        let eom = Eom::new(self, st.t, input, vertical);
        let mut ev = SpatialEvents::default();
        let mut after_rejection = false;
        if st.out_of_range {
            return ev;
        }
        let range_end = self.range_end(&eom, vertical, st.t, t_end);
        let t_end = range_end.map_or(t_end, |(t, _)| t);
        while st.t < t_end && !st.overturned {
            if self.max_steps.is_some_and(|m| ev.steps + ev.rejected >= m) {
                ev.limited = true;
                break;
            }
            if st.at_rest && self.flexible() {
                // docs/model.md §3: any horizontal input moves a body on a
                // flexible bed; the vertical alone keeps it upright
                if input == PlanInput::default() {
                    st.t = t_end;
                } else {
                    let a = eom.ag(st.t);
                    let n = a[0].hypot(a[1]);
                    if n > 0.0 {
                        st.pivot = [-a[0] / n, -a[1] / n];
                    }
                    st.at_rest = false;
                    st.h = 0.0;
                    ev.uplift = true;
                    if stop_at_event {
                        ev.stopped_at_event = true;
                        break;
                    }
                }
                continue;
            }
            if st.at_rest {
                match self.uplift(&eom, st.t, t_end) {
                    None => st.t = t_end,
                    Some((t_up, pivot)) => {
                        *st = SpatialState {
                            t: t_up,
                            pivot,
                            at_rest: false,
                            h: 0.0,
                            ..*st
                        };
                        ev.uplift = true;
                        if stop_at_event {
                            ev.stopped_at_event = true;
                            break;
                        }
                    }
                }
                continue;
            }
            if self.flexible() {
                // on a flexible bed the side is the one the tilt rocks on,
                // kept between steps (`bed`); a tilt that left rest away
                // from the side the input pushed it to has that side
                let [ex, ey] = st.e;
                let s = ex.hypot(ey);
                if ex * st.pivot[0] + ey * st.pivot[1] < 0.0 {
                    st.pivot = [ex / s, ey / s];
                }
            }
            let d0 = if self.flexible() {
                st.pivot
            } else {
                st.contact_direction()
            };
            let y0 = st.to_y();
            let f0 = eom.rates(st.t, &y0, d0);
            let armed = self.flexible().then(|| self.arm(&eom, st.t, &y0, d0));
            if st.h <= 0.0 {
                st.h = self.initial_step(&y0, &f0);
            }
            let remaining = t_end - st.t;
            let hh = if st.h >= remaining { remaining } else { st.h };
            let s = dop853(&eom, st.t, (&y0, &f0), hh, d0, |a, b| self.scales(a, b));
            if (s.err.is_nan() || s.err > 1.0) && hh > min_step(st.t, hh) {
                st.h = hh * shrink(s.err, ERR_EXP);
                ev.rejected += 1;
                after_rejection = true;
                continue;
            }
            ev.steps += 1;
            let next_h = hh * grow(s.err, ERR_EXP, after_rejection);
            after_rejection = false;
            let t1 = if hh == remaining { t_end } else { st.t + hh };
            let cut = match &armed {
                Some(a) => self.past_event(&eom, t1, &s.y, d0, a).then_some(Cut::Kink),
                None => self.cut(&s.y, d0),
            };
            match cut {
                None => {
                    st.set_y(&s.y);
                    st.pivot = d0;
                    st.t = t1;
                    st.h = next_h;
                }
                Some(_) => {
                    let (tau, cut, y) = match &armed {
                        Some(a) => self.locate_on_bed(&eom, st.t, (&y0, &f0), (hh, &s.y), d0, a),
                        None => self.locate(&eom, st.t, (&y0, &f0), hh, d0),
                    };
                    st.set_y(&y);
                    st.pivot = d0;
                    st.t += tau;
                    st.h = next_h.min(hh);
                    let impacts = ev.impacts;
                    self.apply(st, cut, &eom, &mut ev);
                    if stop_at_event && (ev.impacts > impacts || st.overturned) {
                        ev.stopped_at_event = true;
                        break;
                    }
                }
            }
        }
        if let Some((t, condition)) = range_end {
            if st.t == t && !st.overturned && !ev.limited {
                st.out_of_range = true;
                ev.terminal = Some(Terminal {
                    t,
                    condition,
                    av: eom.av(t),
                });
            }
        }
        ev
    }

    /// The first time in `[t, t_end]` at which the input leaves the model's
    /// range (docs/model.md §6.5), and which limit: `liftOff` on the rigid
    /// bed, also `baseCrushing` and `restUnstable` on a flexible one (the
    /// planar model's limits, the same bed).
    fn range_end(
        &self,
        eom: &Eom,
        vertical: VerticalInput,
        t: f64,
        t_end: f64,
    ) -> Option<(f64, OutOfRange)> {
        if self.flexible() {
            self.planar
                .out_of_range(vertical, t_end - t)
                .map(|(tau, c)| (if tau >= t_end - t { t_end } else { t + tau }, c))
        } else {
            self.lift_off(eom, t, t_end)
                .map(|t| (t, OutOfRange::LiftOff))
        }
    }

    /// The first time in `[t, t_end]` at which the apparent weight
    /// `m (g + av)` reaches zero (docs/model.md §6.5), if it does.
    fn lift_off(&self, eom: &Eom, t: f64, t_end: f64) -> Option<f64> {
        let g = self.model.body.g;
        if g + eom.av(t) <= 0.0 {
            return Some(t);
        }
        let end = g + eom.av(t_end);
        if end.is_nan() || end > 0.0 {
            return None;
        }
        let (mut lo, mut hi) = (t, t_end);
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                return Some(hi);
            }
            if g + eom.av(mid) <= 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
    }

    /// Which event, if any, the end `y` of a step from the side `d0` is past.
    fn cut(&self, y: &[f64; N], d0: [f64; 2]) -> Option<Cut> {
        let s2 = y[0] * y[0] + y[1] * y[1];
        let limit = self.model.body.sin_alpha;
        if s2 >= limit * limit {
            Some(Cut::Overturning)
        } else if y[0] * d0[0] + y[1] * d0[1] < 0.0 {
            Some(Cut::Quarter)
        } else {
            None
        }
    }

    /// The first event of the step `hh` from `(t, y0)`: its offset from `t`,
    /// which, and the state there, by the Illinois method on the step
    /// itself (each trial a step of DOP853 from `y0`).
    fn locate(
        &self,
        eom: &Eom,
        t: f64,
        (y0, f0): (&[f64; N], &[f64; N]),
        hh: f64,
        d0: [f64; 2],
    ) -> (f64, Cut, [f64; N]) {
        let limit2 = self.model.body.sin_alpha.powi(2);
        let trial = |h: f64| dop853(eom, t, (y0, f0), h, d0, |a, b| self.scales(a, b));
        // one function whose first zero is the first event: the smaller
        // margin to each, overturning and the quarter turn
        let g = |s: &Step| {
            let quarter = s.y[0] * d0[0] + s.y[1] * d0[1];
            let over = limit2 - (s.y[0] * s.y[0] + s.y[1] * s.y[1]);
            quarter.min(over)
        };
        let at = |y: &[f64; N]| {
            let quarter = y[0] * d0[0] + y[1] * d0[1];
            quarter.min(limit2 - (y[0] * y[0] + y[1] * y[1]))
        };
        // upright after an impact the margin is 0 and the tilt grows
        let (mut a, mut fa) = (0.0, at(y0).max(f64::MIN_POSITIVE));
        let end = trial(hh);
        let (mut b, mut fb, mut yb) = (hh, g(&end), end.y);
        // a first guess from the cubic through both ends' values and rates,
        // and a bracket 1e-6 of the step around it (else the whole step)
        let f1 = eom.rates(t + hh, &end.y, d0);
        let guess = first_root(|tau| cubic(at, (y0, f0), (&end.y, &f1), hh, tau), hh);
        let delta = 1e-6 * hh;
        for c in [guess, guess + delta, guess - delta] {
            if !(c > a && c < b) {
                continue;
            }
            let s = trial(c);
            let fc = g(&s);
            if fc <= 0.0 {
                (b, fb, yb) = (c, fc, s.y);
            } else {
                (a, fa) = (c, fc);
            }
        }
        let (b, yb) = illinois(t, (a, fa), (b, fb, yb), |c| {
            let s = trial(c);
            (g(&s), s.y)
        });
        let cut = self.cut(&yb, d0).unwrap_or(Cut::Quarter);
        (b, cut, yb)
    }

    /// Apply the event `cut` at the state `st` (at its time), whose `pivot`
    /// is the side `d0` the tilt was measured from: overturning, or at a
    /// crossing the impact ([`strikes`]) with the rest check, else the
    /// contact running on round the rim (`pivot` becomes the tilt's
    /// direction, the motion unchanged).
    pub(crate) fn apply(&self, st: &mut SpatialState, cut: Cut, eom: &Eom, ev: &mut SpatialEvents) {
        match cut {
            Cut::Overturning => {
                st.overturned = true;
                ev.overturned_at = Some(st.t);
            }
            Cut::Kink => {}
            Cut::Quarter if self.flexible() => self.upright_pass(st, eom, ev),
            Cut::Quarter => {
                if !strikes(st.e, st.pivot) {
                    // off a plane: the contact runs on round the rim
                    let s = st.e[0].hypot(st.e[1]);
                    st.pivot = [st.e[0] / s, st.e[1] / s];
                    return;
                }
                let old = st.pivot;
                let out = impact(self, Vector3::from(st.omega), old);
                st.e = [0.0; 2];
                st.omega = out.omega.into();
                st.pivot = out.pivot;
                st.impacts += 1;
                ev.impacts += 1;
                if self.comes_to_rest(st, eom) {
                    st.omega = [0.0; 3];
                    st.at_rest = true;
                    ev.came_to_rest = true;
                }
            }
        }
    }

    /// Whether the body, upright after an impact, is at rest to the
    /// tolerance: the planar rule ([`crate::dynamics::Simulator::rest_bound_at`])
    /// with the horizontal input's magnitude and the whole angular velocity
    /// (the flat base stops the spin too).
    pub(crate) fn comes_to_rest(&self, st: &SpatialState, eom: &Eom) -> bool {
        let ag = eom.ag(st.t);
        let n = self.model.body.weight + self.mass() * eom.av(st.t);
        let w = Vector3::from(st.omega).norm();
        let rtol = self.planar.effective_rtol();
        let (th, om) = self.planar.scales();
        match self.planar.rest_bound_at(w, ag[0].hypot(ag[1]), n) {
            Some((dw, dth)) => dw <= rtol * om && dth <= rtol * th,
            None => false,
        }
    }

    /// The first time in `[t, t_end]` at which the horizontal input lifts
    /// the body at rest, `|ag| > (g + av) tan(alpha)` (both inputs linear:
    /// a quadratic), and the direction it tips toward, `-ag/|ag|`.
    fn uplift(&self, eom: &Eom, t: f64, t_end: f64) -> Option<(f64, [f64; 2])> {
        let q = |tau: f64| self.tipping(eom, t + tau);
        let span = t_end - t;
        let tau = if q(0.0) > 0.0 {
            0.0
        } else {
            first_positive(q, span)?
        };
        // at the threshold the tilting moment is zero to round-off: start
        // where the equation itself tilts the body onto its new contact
        let tilts = |tau: f64| q(tau) > 0.0 && self.tilting(eom, t + tau) > 0.0;
        let tau = if tilts(tau) {
            tau
        } else {
            let mut gap = min_step(t + tau, 0.0);
            while !tilts((tau + gap).min(span)) {
                if tau + gap >= span {
                    return None;
                }
                gap *= 2.0;
            }
            let (mut lo, mut hi) = (tau, (tau + gap).min(span));
            loop {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break hi;
                }
                if tilts(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
        };
        let a = eom.ag(t + tau);
        let n = a[0].hypot(a[1]);
        Some((t + tau, [-a[0] / n, -a[1] / n]))
    }

    /// `|ag|² - ((g + av) tan(alpha))²` at `t`, m²/s⁴: positive where the
    /// horizontal input lifts the body at rest.
    pub(crate) fn tipping(&self, eom: &Eom, t: f64) -> f64 {
        let b = &self.model.body;
        let k2 = (b.b / b.hg).powi(2);
        let a = eom.ag(t);
        a[0] * a[0] + a[1] * a[1] - k2 * (b.g + eom.av(t)).powi(2)
    }

    /// The direction `-ag/|ag|` the body at rest at `t` tips toward, if the
    /// input lifts it there: `uplift`'s test at one instant.
    pub(crate) fn lifts_at(&self, eom: &Eom, t: f64) -> Option<[f64; 2]> {
        if !(self.tipping(eom, t) > 0.0 && self.tilting(eom, t) > 0.0) {
            return None;
        }
        let a = eom.ag(t);
        let n = a[0].hypot(a[1]);
        Some([-a[0] / n, -a[1] / n])
    }

    /// The tilt's acceleration toward `-ag/|ag|` of the body upright at rest
    /// at `t`, rad/s².
    fn tilting(&self, eom: &Eom, t: f64) -> f64 {
        let a = eom.ag(t);
        let n = a[0].hypot(a[1]);
        if n == 0.0 {
            return 0.0;
        }
        let d = [-a[0] / n, -a[1] / n];
        let f = eom.rates(t, &[0.0; N], d);
        // d(de/dt)/dt = (omega' x z)_h . d = omega' . (z x d)
        -f[2] * d[1] + f[3] * d[0]
    }

    /// Error weights of the components of `y` (see `dynamics::erk::Tol`):
    /// the tilt relative to the amplitude `|e| + |omega_h|² / (2 g_eff)`,
    /// the angular velocity to `sqrt(|omega|² + 2 g_eff |e|)`, the centre of
    /// mass's position to `R0` times the tilt's weight.
    pub(crate) fn scales(&self, y0: &[f64; N], y1: &[f64; N]) -> [f64; N] {
        let b = &self.model.body;
        let rtol = self.planar.effective_rtol();
        let (th, om) = self.planar.scales();
        let two_g = 2.0 * b.weight * b.b / b.io;
        let amp = |y: &[f64; N]| y[0].hypot(y[1]) + (y[2] * y[2] + y[3] * y[3]) / two_g;
        let vel = |y: &[f64; N]| {
            (y[2] * y[2] + y[3] * y[3] + y[4] * y[4] + two_g * y[0].hypot(y[1])).sqrt()
        };
        let se = rtol * th * rtol + rtol * amp(y0).max(amp(y1));
        let sw = rtol * om * rtol + rtol * vel(y0).max(vel(y1));
        [se, se, sw, sw, sw, b.r0 * se, b.r0 * se]
    }

    /// A first step: Hairer's `0.01 |y| / |f|` in the error weights, at most
    /// a hundredth of the rocking period's scale `1/p`.
    fn initial_step(&self, y: &[f64; N], f: &[f64; N]) -> f64 {
        let sc = self.scales(y, y);
        let norm = |v: &[f64; N]| {
            (v.iter().zip(&sc).map(|(x, s)| (x / s).powi(2)).sum::<f64>() / N as f64).sqrt()
        };
        let (d0, d1) = (norm(y), norm(f));
        let b = &self.model.body;
        let p = (b.weight * b.r0 / b.io).sqrt();
        let h = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        h.min(0.01 / p)
    }
}

/// The Illinois method on a step from `t`: the margin is `fa > 0` at the
/// offset `a` and `fb <= 0` at `b` (s), with the state `yb` there;
/// `trial(c)` is the margin and the state at the offset `c`. Returns the
/// first offset found with a margin `<= 0` and its state, within a quarter
/// of the least step (docs/model.md §10.4).
pub(crate) fn illinois(
    t: f64,
    (mut a, mut fa): (f64, f64),
    (mut b, mut fb, mut yb): (f64, f64, [f64; N]),
    trial: impl Fn(f64) -> (f64, [f64; N]),
) -> (f64, [f64; N]) {
    let mut side = 0;
    for _ in 0..200 {
        if b - a <= min_step(t, b) * 0.25 {
            break;
        }
        let mut c = b - fb * (b - a) / (fb - fa);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let (fc, y) = trial(c);
        if fc <= 0.0 {
            (b, fb, yb) = (c, fc, y);
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            (a, fa) = (c, fc);
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        }
        if fc == 0.0 {
            break;
        }
    }
    (b, yb)
}

/// The margin `at` of the state that a cubic Hermite in time through the
/// step's ends `(y, dy/dt)` gives at `tau` into the step `hh`.
pub(crate) fn cubic(
    at: impl Fn(&[f64; N]) -> f64,
    (y0, f0): (&[f64; N], &[f64; N]),
    (y1, f1): (&[f64; N], &[f64; N]),
    hh: f64,
    tau: f64,
) -> f64 {
    let s = tau / hh;
    let (s2, s3) = (s * s, s * s * s);
    let (h00, h10, h01, h11) = (
        2.0 * s3 - 3.0 * s2 + 1.0,
        s3 - 2.0 * s2 + s,
        -2.0 * s3 + 3.0 * s2,
        s3 - s2,
    );
    let mut y = [0.0; N];
    for c in 0..N {
        y[c] = h00 * y0[c] + h10 * hh * f0[c] + h01 * y1[c] + h11 * hh * f1[c];
    }
    at(&y)
}

/// The first sign change from positive of `f` on `(0, span]` (32 samples,
/// then bisection), or `span`.
fn first_root(f: impl Fn(f64) -> f64, span: f64) -> f64 {
    let n = 32;
    let mut lo = 0.0;
    for i in 1..=n {
        let hi = span * i as f64 / n as f64;
        if f(hi) <= 0.0 {
            let mut lo = lo;
            let mut hi = hi;
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if f(mid) <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return hi;
        }
        lo = hi;
    }
    span
}

/// The first `tau` in `(0, span]` where the quadratic `q` (negative at 0)
/// turns positive, to the last bit.
fn first_positive(q: impl Fn(f64) -> f64, span: f64) -> Option<f64> {
    // q(tau) = q0 + q1 tau + q2 tau²: its coefficients from three values
    let (q0, qh, q1v) = (q(0.0), q(0.5 * span), q(span));
    let c2 = 2.0 * (q1v - 2.0 * qh + q0) / (span * span);
    let c1 = (4.0 * qh - q1v - 3.0 * q0) / span;
    let roots = quadratic_roots(c2, c1, q0);
    let tau = roots
        .into_iter()
        .flatten()
        .filter(|&r| r > 0.0 && r <= span)
        .fold(f64::INFINITY, f64::min);
    let tau = if tau.is_finite() {
        tau
    } else if q1v > 0.0 {
        // q(0) is zero to round-off and the fitted root at or before 0:
        // the bisection below finds the first float where q > 0
        0.0
    } else {
        return None;
    };
    // the root's float, then the first float past it where q > 0
    let (mut lo, mut hi) = (
        (tau * (1.0 - 1e-9)).max(0.0),
        (tau * (1.0 + 1e-9)).min(span),
    );
    if q(hi) <= 0.0 {
        hi = span;
        if q(hi) <= 0.0 {
            return None;
        }
    }
    if q(lo) > 0.0 {
        lo = 0.0;
    }
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return Some(hi);
        }
        if q(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
}

/// Real roots of `a x² + b x + c`.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    if a == 0.0 {
        return [(b != 0.0).then(|| -c / b), None];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [None, None];
    }
    let qq = -0.5 * (b + b.signum() * disc.sqrt());
    let r1 = qq / a;
    let r2 = if qq != 0.0 { c / qq } else { r1 };
    [Some(r1), Some(r2)]
}
