//! The events of a run on a flexible bed (docs/model.md §11.3): overturning
//! where the weight's lever about the resultant vanishes, the tilt turning
//! a right angle from the side it rocks on (with the heel closed: the
//! planar restitution rule; else the side moves on), the kinks of the
//! contact (restarts), rest after the rule, and leaving rest.
//!
//! Each event is the first zero of a margin, positive before it, checked
//! at a step's end and located on the step itself (as the rigid bed's
//! events, `run`); a margin is armed at a step's start when it is clear of
//! zero there, so that a step that starts on an event does not find it
//! again.

use nalgebra::Vector3;

use super::eom::{Eom, N};
use super::pivot::Resultant;
use super::run::{cubic, illinois, strikes, Cut};
use super::step::dop853;
use super::{Spatial, SpatialEvents, SpatialState};
use crate::interface::{Interface, Law, Threshold, THRESHOLDS};

/// A kink's margin within this of zero at a step's start is the kink the
/// step starts on (as the planar loop, docs/model.md §6.4).
const KINK_ARMED: f64 = 1e-10;

/// Past this fraction of the depth from a kink's point the contact's edge
/// tells the side of the kink ([`Spatial::side`]); closer, its margin.
const SIDE_CLEAR: f64 = 1e-6;

/// The half-width of the bracket around the root of an event's margin
/// along the cubic Hermite through a step's ends, relative to the step
/// ([`Spatial::locate_on_bed`]). Where the cubic misses the root by more,
/// the Illinois method goes on from the side it found. On the Dharahara's
/// crushing beds under Coalinga x3 (`examples/dharahara_space_cost.rs`)
/// 1e-7 and 1e-6 both locate an event in 4.2 trial steps (7.3 from the
/// whole step); 1e-7 keeps a rotated run's response to 5e-13 of the
/// turned one (`tests/spatial_flexible.rs`), 1e-6 to 6e-12.
const GUESS_BRACKET: f64 = 1e-7;

/// The margins armed at a step's start.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Armed {
    /// The tilt is on the side `d0` it rocks on, `e . d0 > 0`.
    across: bool,
    /// Each threshold of the contact and the sign of its margin at the
    /// start (0: not armed).
    kinks: [(Option<Threshold>, f64); THRESHOLDS],
}

impl Spatial {
    /// The apparent weight `N = m (g + av)` at `t` (docs/model.md §6.1), N.
    pub(super) fn weight_at(&self, eom: &Eom, t: f64) -> f64 {
        self.model.body.weight + self.mass() * eom.av(t)
    }

    /// `hW / sin(theta)`, m: the lever of the weight about the resultant,
    /// `rho cos(theta) - hG sin(theta)` (the planar `hW`, docs/model.md §3),
    /// over `sin(theta)`; `kn Is/N - hG > 0` at upright, 0 at overturning.
    pub(super) fn overturn_margin(&self, y: &[f64; N], n: f64) -> f64 {
        self.overturn_margin_of(y, &self.resultant(Self::tilt(y), n))
    }

    /// The tilt `theta = asin(|e|)` of the state `y`, rad.
    fn tilt(y: &[f64; N]) -> f64 {
        (y[0] * y[0] + y[1] * y[1]).sqrt().asin()
    }

    /// [`overturn_margin`](Self::overturn_margin) from the resultant `res`
    /// at the state's tilt.
    fn overturn_margin_of(&self, y: &[f64; N], res: &Resultant) -> f64 {
        let s2 = y[0] * y[0] + y[1] * y[1];
        let s = s2.sqrt();
        // rho = secant theta
        let q = if s > 0.0 { res.rho / s } else { res.secant };
        q * (1.0 - s2).sqrt() - self.model.body.hg
    }

    /// `e . d0`: positive while the tilt is on the side `d0` (unit).
    fn along(y: &[f64; N], d0: [f64; 2]) -> f64 {
        y[0] * d0[0] + y[1] * d0[1]
    }

    /// The relative margin `1 - Nbed/N` of a threshold of the contact
    /// (docs/model.md §6.4): positive while its edge is past its point. At
    /// upright the heel is closed and nothing has crushed.
    fn kink_margin(&self, theta: f64, n: f64, t: Threshold) -> f64 {
        if theta <= 0.0 {
            return match t {
                Threshold::Contact(_) => 1.0,
                Threshold::Plastic(_) => -1.0,
            };
        }
        let it = &self.model.interface;
        Interface::threshold_margin(it.threshold_resultant(theta, t), n)
    }

    /// The margins armed at the state `y` at `t` on the side `d0`.
    pub(crate) fn arm(&self, eom: &Eom, t: f64, y: &[f64; N], d0: [f64; 2]) -> Armed {
        let n = self.weight_at(eom, t);
        let theta = Self::tilt(y);
        let edge = self.resultant_near(theta, n, &eom.memo).edge;
        let kinks = self.model.interface.moving_thresholds().map(|th| match th {
            Some(k) => {
                let sign = match self.side(theta, edge, k) {
                    Some(past) => {
                        if past {
                            1.0
                        } else {
                            -1.0
                        }
                    }
                    None => {
                        let m = self.kink_margin(theta, n, k);
                        if m.abs() > KINK_ARMED {
                            m.signum()
                        } else {
                            0.0
                        }
                    }
                };
                (th, sign)
            }
            None => (None, 0.0),
        });
        Armed {
            across: Self::along(y, d0) > 0.0,
            kinks,
        }
    }

    /// The smallest armed margin at `(t, y)` and its event (overturning is
    /// always armed).
    pub(crate) fn margin(
        &self,
        eom: &Eom,
        t: f64,
        y: &[f64; N],
        d0: [f64; 2],
        armed: &Armed,
    ) -> (f64, Cut) {
        let n = self.weight_at(eom, t);
        let theta = Self::tilt(y);
        let res = self.resultant_near(theta, n, &eom.memo);
        let mut best = (self.overturn_margin_of(y, &res), Cut::Overturning);
        if armed.across {
            let m = Self::along(y, d0);
            if m < best.0 {
                best = (m, Cut::Quarter);
            }
        }
        for (th, sign) in armed.kinks {
            if let (Some(k), true) = (th, sign != 0.0) {
                let m = sign * self.kink_margin(theta, n, k);
                if m < best.0 {
                    best = (m, Cut::Kink);
                }
            }
        }
        best
    }

    /// Whether the state `y` at `t`, a step's end, is past an armed
    /// event: [`margin`](Self::margin)`(..).0 <= 0`, with a kink's sign
    /// read from the contact's edge where it is clear of the kink's point
    /// ([`side`](Self::side)) instead of its margin's bed resultant.
    pub(crate) fn past_event(
        &self,
        eom: &Eom,
        t: f64,
        y: &[f64; N],
        d0: [f64; 2],
        armed: &Armed,
    ) -> bool {
        let n = self.weight_at(eom, t);
        let theta = Self::tilt(y);
        let res = self.resultant_near(theta, n, &eom.memo);
        if self.overturn_margin_of(y, &res) <= 0.0 || (armed.across && Self::along(y, d0) <= 0.0) {
            return true;
        }
        armed
            .kinks
            .iter()
            .any(|&(th, sign)| match (th, sign != 0.0) {
                (Some(k), true) => match self.side(theta, res.edge, k) {
                    Some(past) => past != (sign > 0.0),
                    None => sign * self.kink_margin(theta, n, k) <= 0.0,
                },
                _ => false,
            })
    }

    /// Whether the edge of the threshold `t` is past its point at the tilt
    /// `theta > 0` (rad) from the contact's edge `edge` (m), where that is
    /// clear: more than [`SIDE_CLEAR`] of the depth from the point, far
    /// above the contact's error, so the sign of the kink's margin
    /// (`Nbed` grows with `a`) without its bed resultant. `None` at
    /// upright and within the band.
    fn side(&self, theta: f64, edge: f64, t: Threshold) -> Option<bool> {
        let it = &self.model.interface;
        if theta <= 0.0 || !edge.is_finite() {
            return None;
        }
        let past = match t {
            Threshold::Contact(x) => edge - x,
            Threshold::Plastic(x) => match it.law() {
                Law::ElastoPlastic { kn, fm } => edge - fm / (kn * theta) - x,
                _ => return None,
            },
        };
        (past.abs() > SIDE_CLEAR * it.depth()).then_some(past > 0.0)
    }

    /// The first event of the step `hh` from `(t, y0)`, whose end is past
    /// one: its offset from `t`, which, and the state just past it, by the
    /// Illinois method on the step itself (each trial a step of DOP853 from
    /// `y0`), started as the rigid bed's (`run`): from the root of the
    /// margin along the cubic Hermite through the step's ends, bracketed
    /// to [`GUESS_BRACKET`] of the step around it.
    pub(crate) fn locate_on_bed(
        &self,
        eom: &Eom,
        t: f64,
        (y0, f0): (&[f64; N], &[f64; N]),
        (hh, end): (f64, &[f64; N]),
        d0: [f64; 2],
        armed: &Armed,
    ) -> (f64, Cut, [f64; N]) {
        let trial = |h: f64| dop853(eom, t, (y0, f0), h, d0, |a, b| self.scales(a, b)).y;
        let g = |h: f64, y: &[f64; N]| self.margin(eom, t + h, y, d0, armed).0;
        let (mut a, mut fa) = (0.0, g(0.0, y0).max(f64::MIN_POSITIVE));
        let (mut b, mut fb, mut yb) = (hh, g(hh, end), *end);
        let f1 = eom.rates(t + hh, end, d0);
        let along = |tau: f64| {
            let m = cubic(|y| g(tau, y), (y0, f0), (end, &f1), hh, tau);
            (m, *end)
        };
        let (guess, _) = illinois(t, (a, fa), (b, fb, *end), along);
        let delta = GUESS_BRACKET * hh;
        for c in [guess - delta, guess + delta] {
            if !(c > a && c < b) {
                continue;
            }
            let y = trial(c);
            let fc = g(c, &y);
            if fc <= 0.0 {
                (b, fb, yb) = (c, fc, y);
                break;
            }
            (a, fa) = (c, fc);
        }
        let (b, yb) = illinois(t, (a, fa), (b, fb, yb), |c| {
            let y = trial(c);
            (g(c, &y), y)
        });
        let cut = self.margin(eom, t + b, &yb, d0, armed).1;

        (b, cut, yb)
    }

    /// The tilt at `st` has turned a right angle from the side `st.pivot`
    /// it rocked on (in a plane: it crossed upright), and the side becomes
    /// the tilt's direction (`-pivot` within [`super::UPRIGHT`] of the
    /// side's line). With the heel closed
    /// there, the planar restitution rule (docs/model.md §3, §11.3) on the
    /// angular velocity across the axis, `omega_perp <- eta omega_perp` (the
    /// spin about the axis kept), then rest if it settles; with the heel
    /// open, nothing more (a wobble whose contact runs round the rim).
    pub(crate) fn upright_pass(&self, st: &mut SpatialState, eom: &Eom, ev: &mut SpatialEvents) {
        let n = self.weight_at(eom, st.t);
        let s = st.e[0].hypot(st.e[1]);
        // within round-off of the side's line (a planar motion along an
        // oblique azimuth, `strikes`) the tilt's direction is round-off's
        st.pivot = if strikes(st.e, st.pivot) {
            [-st.pivot[0], -st.pivot[1]]
        } else {
            [st.e[0] / s, st.e[1] / s]
        };
        if !self.resultant(s.asin(), n).heel_closed {
            return;
        }
        let c = (1.0 - st.e[0] * st.e[0] - st.e[1] * st.e[1]).sqrt();
        let e3 = Vector3::new(st.e[0], st.e[1], c);
        let w = Vector3::from(st.omega);
        let spin = w.dot(&e3) * e3;
        st.omega = (self.model.eta * (w - spin) + spin).into();
        st.impacts += 1;
        ev.impacts += 1;
        if eom.quiet() && self.settles(st) {
            st.e = [0.0; 2];
            st.omega = [0.0; 3];
            st.at_rest = true;
            ev.came_to_rest = true;
        }
    }

    /// The planar flexible rest rule (docs/model.md §3, "Uplift and rest";
    /// `dynamics::Simulator::settles`) without ground motion: the free
    /// oscillation in full contact left after the rule, of amplitude
    /// `|omega| sqrt(I0/K0)` (`K0 = kn Is - W hG`, `I0 = Ic + m hG²`), and the
    /// tilt itself are below `rtol thetaOv`.
    fn settles(&self, st: &SpatialState) -> bool {
        let it = &self.model.interface;
        let kn = match it.law() {
            crate::interface::Law::Elastic { kn }
            | crate::interface::Law::ElastoPlastic { kn, .. } => kn,
            crate::interface::Law::Rigid => return false,
        };
        let b = &self.model.body;
        let k0 = kn * it.shape().second_moment() - b.weight * b.hg;
        let i0 = b.ic + b.mass * b.hg * b.hg;
        let amp = Vector3::from(st.omega).norm() * (i0 / k0).sqrt();
        let floor = self.planar.effective_rtol() * self.model.theta_ov;
        amp <= floor && st.e[0].hypot(st.e[1]) <= floor
    }
}
