//! The flexible interface (docs/model.md §2): where the reaction acts.
//!
//! A Winkler bed of springs `kn` (Pa/m), no tension, plastic at `fm` (Pa).
//! For a rotation `phi >= 0` the closure is `delta(x) = phi (a - x)`; the
//! contact length `a` follows from vertical equilibrium `N(a) = W`, and the
//! reaction acts at `af = M(a) / W` from the toe. One scheme serves every
//! shape and regime: the stress profile is a plastic zone `[0, xp]` at `fm`
//! followed by an elastic zone `[xp, x2]`, `x2 = min(a, D)`, whose force and
//! moment come from the shape's cumulative moments `S_k` (docs/model.md §2).

use crate::shape::Shape;

mod spatial;
mod table;
pub use spatial::{RoundBed, RoundReaction};
pub use table::ContactTable;

/// Interface law (docs/model.md §2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Law {
    /// Rigid contact: the reaction acts at the toe (`af = 0` for `theta != 0`).
    Rigid,
    /// Elastic, no tension: springs of stiffness `kn` (Pa/m).
    Elastic { kn: f64 },
    /// Elastic, no tension, perfectly plastic at `fm` (Pa).
    ElastoPlastic { kn: f64, fm: f64 },
}

/// Contact regime (the FMU's `regime` output, docs/model.md §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(i32)]
pub enum Regime {
    /// The whole base is closed and elastic.
    FullContact = 0,
    /// The heel has opened; the contact is elastic.
    Partial = 1,
    /// The heel has opened and the toe has crushed.
    PartialCrushing = 2,
    /// The whole base is closed and the toe has crushed.
    FullCrushing = 3,
    /// The body has overturned (set by the dynamics, never by the interface).
    Overturned = 4,
}

/// The interface's answer at one rotation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Position of the reaction from the toe, m.
    pub af: f64,
    /// `d af / d phi`, m/rad (never positive).
    pub daf: f64,
    /// Equilibrium parameter `a` of the closure `phi (a - x)`, m. Above `D`
    /// the heel is closed too; infinite at `phi = 0`.
    pub a: f64,
    /// Length of the closed part of the base, `min(a, D)`, m.
    pub contact_length: f64,
    /// The rotation this contact was solved for, rad.
    pub phi: f64,
    /// `da / d phi`, m/rad, to predict the next solve's start.
    pub da: f64,
    /// Which stress profile holds.
    pub regime: Regime,
    /// Newton iterations the equilibrium solve took (0 for closed forms).
    pub iterations: u32,
}

/// An edge of the stress profile reaching a point of the base: the
/// moving thresholds of docs/model.md §6.4, zeros of `N - Nbed(phi)` at a
/// bed resultant explicit in `phi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Threshold {
    /// The contact edge `a` at `x` m from the toe (`x = D`: joint opening).
    Contact(f64),
    /// The plastic edge `xp = a - fm/(kn phi)` at `x` m from the toe
    /// (`x = 0`: crushing onset).
    Plastic(f64),
}

/// The most moving thresholds an interface has: joint opening, crushing
/// onset, and both edges at each of the two breaks of a hollow section's
/// width.
pub const THRESHOLDS: usize = 6;

/// An interface law applied to a base shape carrying a weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interface {
    shape: Shape,
    law: Law,
    weight: f64,
    d: f64,
    area: f64,
    is: f64,
    /// `kn`, Pa/m (infinite for the rigid law).
    kn: f64,
    /// `fm`, Pa (infinite unless elasto-plastic).
    fm: f64,
    /// Full moments `S_k(D)`.
    s_full: [f64; 3],
    theta_jo: f64,
    theta_c: f64,
}

/// Iterations of a loaded solve started in the regime of its hint before
/// the regime is decided from the bed resultants instead
/// ([`Interface::contact_loaded`]): from a nearby contact the solve takes
/// one or two.
const HINTED_MAX_ITER: u32 = 6;

/// The regime of a contact whose heel is `closed` (`a >= D`) and whose toe
/// has `crushed` (`a > a1`).
fn regime_of(closed: bool, crushed: bool) -> Regime {
    match (closed, crushed) {
        (true, false) => Regime::FullContact,
        (false, false) => Regime::Partial,
        (false, true) => Regime::PartialCrushing,
        (true, true) => Regime::FullCrushing,
    }
}

/// Relative tolerance of the equilibrium residual `|N(a) - W| / W`.
const EQUILIBRIUM_RTOL: f64 = 2e-15;
const MAX_ITER: u32 = 200;
/// Below this residual a last Halley step is taken without re-evaluation.
const TAYLOR_RTOL: f64 = 1e-7;

impl Interface {
    /// The interface of `shape` under `weight` (N) with the given `law`.
    /// The caller has validated the parameters (see [`crate::model::Params`]):
    /// positive sizes, `kn > 0`, `W < fm A`.
    pub fn new(shape: Shape, law: Law, weight: f64) -> Interface {
        let (kn, fm) = match law {
            Law::Rigid => (f64::INFINITY, f64::INFINITY),
            Law::Elastic { kn } => (kn, f64::INFINITY),
            Law::ElastoPlastic { kn, fm } => (kn, fm),
        };
        let d = shape.depth();
        let mut it = Interface {
            shape,
            law,
            weight,
            d,
            area: shape.area(),
            is: shape.second_moment(),
            kn,
            fm,
            s_full: shape.moments(d),
            theta_jo: 0.0,
            theta_c: f64::INFINITY,
        };
        if law != Law::Rigid {
            let (jo, c) = it.thresholds();
            it.theta_jo = jo;
            it.theta_c = c;
        }
        it
    }

    pub fn shape(&self) -> &Shape {
        &self.shape
    }
    pub fn law(&self) -> Law {
        self.law
    }
    /// Elastic without crushing: the contact depends on `phi / N` only.
    pub fn is_elastic(&self) -> bool {
        matches!(self.law, Law::Elastic { .. })
    }
    /// Base depth `D`, m.
    pub fn depth(&self) -> f64 {
        self.d
    }
    /// Rotation at which the heel opens, rad (0 for the rigid law).
    pub fn theta_jo(&self) -> f64 {
        self.theta_jo
    }
    /// Rotation at which the toe starts to crush, rad (infinite without crushing).
    pub fn theta_c(&self) -> f64 {
        self.theta_c
    }
    /// Plastic limit of `af` for large rotations, `alim / 2` where the whole
    /// weight is carried at `fm` over `[0, alim]`: `S0(alim) = W / fm`, m
    /// (0 without crushing).
    pub fn af_limit(&self) -> f64 {
        if !self.fm.is_finite() {
            return 0.0;
        }
        let target = self.weight / self.fm;
        let alim = solve_increasing(|x| self.shape.moments(x)[0] - target, 0.0, self.d);
        let [s0, s1, _] = self.shape.moments(alim);
        s1 / s0
    }

    /// Thresholds `(thetaJo, thetaC)` (docs/model.md §2, "Regimes and thresholds").
    fn thresholds(&self) -> (f64, f64) {
        let (w, kn, fm, a_sec, d) = (self.weight, self.kn, self.fm, self.area, self.d);
        // Heel opening while the toe is elastic: N(D) = kn theta A D / 2 = W.
        let jo_elastic = 2.0 * w / (kn * a_sec * d);
        if !fm.is_finite() {
            return (jo_elastic, f64::INFINITY);
        }
        if fm * a_sec / 2.0 >= w {
            // Crushing starts in partial contact: solve N(ac) = W with
            // theta = fm / (kn ac), i.e. fm (S0(ac) - S1(ac)/ac) = W.
            let ac = solve_increasing(
                |a| {
                    let [s0, s1, _] = self.shape.moments(a);
                    fm * (s0 - s1 / a) - w
                },
                0.0,
                d,
            );
            (jo_elastic, fm / (kn * ac))
        } else {
            // Crushing starts in full contact: toe stress W/A + kn theta D/2 = fm.
            let theta_c = 2.0 * (fm - w / a_sec) / (kn * d);
            // The heel opens later, at N(a = D) = W with a plastic zone
            // [0, xp], kn theta = fm / (D - xp).
            let [_, s1d, _] = self.s_full;
            let xp = solve_increasing(
                |xp| {
                    let [s0, s1, _] = self.shape.moments(xp);
                    fm * s0 + fm / (d - xp) * (d * (a_sec - s0) - (s1d - s1)) - w
                },
                0.0,
                d,
            );
            (fm / (kn * (d - xp)), theta_c)
        }
    }

    /// The regime at rotation `phi >= 0` for a flexible law.
    fn regime_at(&self, phi: f64) -> Regime {
        let closed = phi <= self.theta_jo;
        let crushed = phi > self.theta_c;
        match (closed, crushed) {
            (true, false) => Regime::FullContact,
            (false, false) => Regime::Partial,
            (false, true) => Regime::PartialCrushing,
            (true, true) => Regime::FullCrushing,
        }
    }

    /// The contact at rotation `phi = |theta|` (rad).
    #[inline]
    pub fn contact(&self, phi: f64) -> Contact {
        self.contact_near(phi, f64::NAN)
    }

    /// The contact at `phi` near an earlier contact `prev` (the integrator's
    /// previous evaluation). In a partial regime the solve starts from the
    /// mean-width rectangle formula (exact for a solid rectangle) times the
    /// ratio `a / formula` of `prev`, extrapolated to first order; otherwise
    /// from `a` extrapolated along `da/dphi`. Same result to the solver
    /// tolerance, fewer iterations.
    #[inline]
    pub fn contact_after(&self, phi: f64, prev: &Contact) -> Contact {
        let phi = phi.abs();
        let partial = matches!(prev.regime, Regime::Partial | Regime::PartialCrushing);
        let hint = if partial && self.law != Law::Rigid && self.regime_at(phi) == prev.regime {
            let crushing = prev.regime == Regime::PartialCrushing;
            let (g0, dg0) = self.rectangle_formula(prev.phi, crushing);
            let (g1, _) = self.rectangle_formula(phi, crushing);
            let r = prev.a / g0;
            let dr = (prev.da * g0 - prev.a * dg0) / (g0 * g0);
            g1 * (r + dr * (phi - prev.phi))
        } else {
            prev.a + prev.da * (phi - prev.phi)
        };
        self.contact_near(phi, hint)
    }

    /// The contact at `phi`, starting the equilibrium solve from `a_hint`
    /// (the `a` of a nearby rotation; NaN for none). Same result to the
    /// solver tolerance, fewer iterations.
    pub fn contact_near(&self, phi: f64, a_hint: f64) -> Contact {
        let phi = phi.abs();
        self.solve(phi, self.weight, self.regime_at(phi), a_hint).0
    }

    /// The contact at `phi` (rad) under the bed resultant `n` (N) instead of
    /// the weight (docs/model.md §6.1: a vertical ground acceleration makes
    /// the apparent weight `N = m (g + av)`), starting from `a_hint` (m; NaN
    /// for none), and `xel`, the centroid (m from the toe) of the elastic
    /// part of the contact, for `daf/dN = (xel - af)/N`. The regime comes
    /// from the explicit bed resultant `Nbed(a, phi)` (docs/model.md §6.4),
    /// not from the thresholds at the weight. Flexible laws. At `n <= 0`
    /// (only at the `liftOff` instant that ends a run, docs/model.md §6.5)
    /// the limit `n -> 0+`: the contact shrunk to the toe (`af = 0`), or
    /// at `phi = 0` the whole base with `daf = 0`.
    pub fn contact_loaded(&self, phi: f64, n: f64, a_hint: f64) -> (Contact, f64) {
        let phi = phi.abs();
        if n <= 0.0 && self.law != Law::Rigid {
            return if phi == 0.0 {
                let (c, xel) = self.solve(phi, self.weight, Regime::FullContact, a_hint);
                (Contact { daf: 0.0, ..c }, xel)
            } else {
                (toe(phi), 0.0)
            };
        }
        if phi > 0.0 && self.law != Law::Rigid && a_hint > 0.0 && a_hint.is_finite() {
            // The regime of a nearby contact is nearly always this one's:
            // solved there, the solve itself shows it (and the two bed
            // resultants that decide the regime are not evaluated).
            let k = self.kn * phi;
            let regime = regime_of(a_hint >= self.d, a_hint > self.fm / k);
            let (c, xel, inside) = self.solve_in(phi, n, regime, a_hint, HINTED_MAX_ITER);
            if inside {
                return (c, xel);
            }
        }
        let regime = if phi == 0.0 || self.law == Law::Rigid {
            Regime::FullContact
        } else {
            let k = self.kn * phi;
            let a1 = self.fm / k;
            // Nbed grows with a: a >= D iff n >= Nbed(D), xp > 0 iff n > Nbed(a1)
            let closed = n >= self.bed_resultant(k, a1, self.d);
            let crushed = a1.is_finite() && n > self.bed_resultant(k, a1, a1);
            regime_of(closed, crushed)
        };
        self.solve(phi, n, regime, a_hint)
    }

    /// The event functions of docs/model.md §6.4 at `phi` under the bed
    /// resultant `n`, relative to `n`: `1 - Nbed(D, phi)/n`, positive while
    /// the heel is closed (`a > D`), and `1 - Nbed(a1, phi)/n`
    /// (`a1 = fm/(kn phi)`), positive while the toe crushes (`xp > 0`).
    /// At `phi = 0` (and for `phi <= 0`) `[1, -1]`.
    pub fn bed_margins(&self, phi: f64, n: f64) -> [f64; 2] {
        if phi <= 0.0 || self.law == Law::Rigid {
            return [1.0, -1.0];
        }
        let margin = |t| Self::threshold_margin(self.threshold_resultant(phi, t), n);
        let toe = if self.fm.is_finite() {
            margin(Threshold::Plastic(0.0))
        } else {
            -1.0
        };
        [margin(Threshold::Contact(self.d)), toe]
    }

    /// The moving thresholds of docs/model.md §6.4 in a fixed order:
    /// joint opening, crushing onset, then at each break of the width
    /// ([`Shape::width_breaks`]) the contact edge and the plastic edge.
    /// `None` where the interface has none: the plastic ones on an elastic
    /// bed, the breaks of a solid section, every one for the rigid law.
    pub fn moving_thresholds(&self) -> [Option<Threshold>; THRESHOLDS] {
        let mut t = [None; THRESHOLDS];
        if self.law == Law::Rigid {
            return t;
        }
        let plastic = self.fm.is_finite();
        t[0] = Some(Threshold::Contact(self.d));
        t[1] = plastic.then_some(Threshold::Plastic(0.0));
        for (i, x) in self.shape.width_breaks().into_iter().flatten().enumerate() {
            t[2 + 2 * i] = Some(Threshold::Contact(x));
            t[3 + 2 * i] = plastic.then_some(Threshold::Plastic(x));
        }
        t
    }

    /// The bed resultant at which the edge of `t` is at its point at
    /// `phi > 0` (a flexible law), N: `Nbed(x, phi)` for the contact edge,
    /// `Nbed(x + fm/(kn phi), phi)` for the plastic one (docs/model.md
    /// §6.4). Under a larger `N` the edge is past the point (`Nbed` grows
    /// with `a`).
    pub fn threshold_resultant(&self, phi: f64, t: Threshold) -> f64 {
        let k = self.kn * phi;
        let a1 = self.fm / k;
        match t {
            Threshold::Contact(x) => self.bed_resultant(k, a1, x),
            Threshold::Plastic(x) => self.bed_resultant(k, a1, x + a1),
        }
    }

    /// Whether the edge of `t` is past its point (the sign of its margin
    /// at the bed resultant `n` the contact was solved for) from the
    /// contact's edge `a` (m) at `phi > 0`: `Nbed` grows strictly with `a`,
    /// so the margin is positive exactly when `a` (or `a - fm/(kn phi)`) is
    /// beyond the point. `None` where `a` is within `1e-8 D` of it (the
    /// contact's own error is some 1e-13 of `a`) or not finite.
    #[inline]
    pub fn threshold_side(&self, phi: f64, a: f64, t: Threshold) -> Option<bool> {
        let edge_past = match t {
            Threshold::Contact(x) => a - x,
            Threshold::Plastic(x) => a - self.fm / (self.kn * phi) - x,
        };
        (edge_past.abs() > 1e-8 * self.d).then_some(edge_past > 0.0)
    }

    /// The relative margin `1 - Nbed/n` of the bed resultant `n` (N) to a
    /// threshold's `limit` ([`threshold_resultant`](Self::threshold_resultant)):
    /// positive while the edge is past its point.
    #[inline]
    pub fn threshold_margin(limit: f64, n: f64) -> f64 {
        1.0 - limit / n
    }

    /// The equilibrium `Nbed(a, phi) = w` in the given regime: the contact
    /// and the elastic zone's centroid `xel` (m from the toe).
    #[inline(always)]
    fn solve(&self, phi: f64, w: f64, regime: Regime, a_hint: f64) -> (Contact, f64) {
        let (c, xel, _) = self.solve_in(phi, w, regime, a_hint, MAX_ITER);
        (c, xel)
    }

    /// [`solve`](Self::solve) with at most `max_iter` iterations, and
    /// whether the equilibrium lies in `regime`: the residual met its
    /// tolerance strictly inside the regime's range of `a` (`Nbed` grows
    /// with `a` through every regime, so the root is there).
    #[inline(always)]
    fn solve_in(
        &self,
        phi: f64,
        w: f64,
        regime: Regime,
        a_hint: f64,
        max_iter: u32,
    ) -> (Contact, f64, bool) {
        if phi == 0.0 {
            let c = Contact {
                af: self.d / 2.0,
                daf: if self.law == Law::Rigid {
                    0.0
                } else {
                    -self.kn * self.is / w
                },
                a: f64::INFINITY,
                contact_length: self.d,
                phi,
                da: f64::NAN,
                regime: Regime::FullContact,
                iterations: 0,
            };
            return (c, self.d / 2.0, regime == Regime::FullContact);
        }
        if self.law == Law::Rigid {
            return (toe(phi), 0.0, true);
        }
        let d = self.d;
        let k = self.kn * phi; // stress per unit length of closure, Pa/m
        if regime == Regime::FullContact {
            // Closed form (docs/model.md §2): N = k (a A - A D/2) = W.
            let a = w / (k * self.area) + d / 2.0;
            let c = Contact {
                af: d / 2.0 - k * self.is / w,
                daf: -self.kn * self.is / w,
                a,
                contact_length: d,
                phi,
                da: -w / (k * phi * self.area),
                regime,
                iterations: 0,
            };
            // the whole section is elastic: its centroid
            let inside = a >= d && a <= self.fm / k;
            return (c, self.s_full[1] / self.s_full[0], inside);
        }
        // Elastic length a1: the closure at which the stress reaches fm.
        let a1 = self.fm / k;
        let (mut lo, mut hi) = match regime {
            Regime::Partial => (0.0, d.min(a1)),
            Regime::PartialCrushing => (a1, d.min(a1 + d)),
            _ => (d, a1 + d), // FullCrushing
        };
        let mut a = if a_hint > lo && a_hint < hi {
            a_hint
        } else {
            self.first_guess(k, a1, lo, hi)
        };
        let range = (lo, hi);
        let mut converged = false;
        let mut iterations = 0;
        let mut r = self.resultants(k, a1, a);
        loop {
            let f = r.n - w;
            if f.abs() <= EQUILIBRIUM_RTOL * w {
                converged = true;
                break;
            }
            if iterations >= max_iter {
                break;
            }
            if f > 0.0 {
                hi = a;
            } else {
                lo = a;
            }
            // Halley's step (N is smooth inside a regime; N'' is two widths),
            // bisection when it leaves the bracket.
            let newton = f / r.dn_da;
            let mut next = a - newton / (1.0 - 0.5 * newton * r.d2n_da2 / r.dn_da);
            iterations += 1;
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            } else if f.abs() <= TAYLOR_RTOL * w {
                // Close enough that the step's own error, O(step³) for a
                // smooth N and O(step²) across a flange step of the width,
                // is below the equilibrium tolerance: move the resultants
                // along by their Taylor series instead of re-evaluating.
                r.shift(next - a);
                a = next;
                converged = true;
                break;
            }
            if next == a || hi - lo <= 4.0 * f64::EPSILON * hi {
                break;
            }
            a = next;
            r = self.resultants(k, a1, a);
        }
        // docs/model.md §2: af = M/W; d af/d phi = -(kn/W) x (second moment of the
        // elastic zone about its own centroid), the plastic-boundary terms
        // cancelling as in dN/da.
        let c = Contact {
            af: r.m / w,
            daf: -self.kn * r.central / w,
            a,
            contact_length: a.min(d),
            phi,
            // dN/dphi = kn (e L0 - L1) at fixed a, dN/da = k L0
            da: -r.zone_force / (phi * r.zone_area),
            regime,
            iterations,
        };
        let inside = converged && a > range.0 && a < range.1;
        (c, r.xp + r.zone_moment / r.zone_area + r.xel_moved, inside)
    }

    /// Second derivatives in `phi` of a solved contact `c`:
    /// `(d²af/dphi², d²a/dphi²)`, m/rad², for the output derivatives
    /// (docs/dynamics.md, "Output derivatives"). Inside a regime, from the
    /// elastic zone `[xp, x2]` of docs/model.md §2 (moments `L_k` about `xp`,
    /// centroid `xp + c`, `F = ∫ (a - x) w`): `af' = -(kn/W) Jc` with `Jc`
    /// the zone's central second moment, so `af'' = -(kn/W) dJc/dphi`,
    /// `dJc/dphi = w(x2) (x2 - xp - c)² x2' - w(xp) c² xp'`; `a' = -F/(phi L0)`,
    /// so `a'' = -F'/(phi L0) - a' (1/phi + L0'/L0)` with
    /// `F' = a' L0 - (a - xp) w(xp) xp'`, `L0' = w(x2) x2' - w(xp) xp'`,
    /// `x2' = a'` while `a < D` (else 0), `xp' = a' + a1/phi` while the toe
    /// crushes (`a1 = fm/(kn phi)`, else 0). Both are 0 in full contact (af
    /// is linear in `phi` there, `a` is not an output) and for the rigid law.
    pub fn second_derivatives(&self, c: &Contact) -> (f64, f64) {
        let phi = c.phi;
        if self.law == Law::Rigid || phi == 0.0 || c.regime == Regime::FullContact {
            return (0.0, 0.0);
        }
        match self.elastic_zone(c) {
            Some(z) => self.zone_second_derivatives(c, &z, self.weight),
            None => (0.0, 0.0),
        }
    }

    /// [`second_derivatives`](Self::second_derivatives) of `c` from its
    /// elastic zone `z`, under the bed resultant `n` (N).
    fn zone_second_derivatives(&self, c: &Contact, z: &ElasticZone, n: f64) -> (f64, f64) {
        let &ElasticZone { a1, x2, xp, l } = z;
        let phi = c.phi;
        let (d, a) = (self.d, c.a);
        let e = a - xp;
        let f = e * l[0] - l[1];
        let da = -f / (phi * l[0]);
        let (grow, dx2) = if a < d {
            (self.shape.width(x2), da)
        } else {
            (0.0, 0.0)
        };
        let (lose, dxp) = if xp > 0.0 {
            (self.shape.width(xp), da + a1 / phi)
        } else {
            (0.0, 0.0)
        };
        let cz = l[1] / l[0];
        let e2 = x2 - xp;
        let djc = grow * (e2 - cz) * (e2 - cz) * dx2 - lose * cz * cz * dxp;
        let d2af = -self.kn * djc / n;
        let df = da * l[0] - e * lose * dxp;
        let dl0 = grow * dx2 - lose * dxp;
        let d2a = -df / (phi * l[0]) - da * (1.0 / phi + dl0 / l[0]);
        (d2af, d2a)
    }

    /// The second partial derivatives in `phi` and `N` of a contact `c`
    /// solved at `(phi, n)` ([`contact_loaded`](Self::contact_loaded)),
    /// for the output derivatives under a vertical input (docs/dynamics.md,
    /// "Output derivatives"). With the elastic zone `[xp, x2]` of
    /// docs/model.md §2 (area `L0`, centroid `X = xp + L1/L0` from the
    /// toe, `k = kn phi`): `da/dN = 1/(k L0)`, `daf/dN = (X - af)/N`; as `a`
    /// grows the zone gains `w(x2)` at its end (while `a < D`) and loses
    /// `w(xp)` at its start (while the toe crushes), so `dX/da = (w(x2)
    /// (x2 - X) + w(xp) (X - xp))/L0` and `dL0/da = w(x2) - w(xp)`; at fixed
    /// `a` a larger `phi` moves `xp` by `a1/phi` (`a1 = fm/(kn phi)`).
    /// Then `d²af/dN² = (dX/dN - 2 daf/dN)/N`, `d²af/dphi dN = (dX/dphi -
    /// daf/dphi)/N`, `d²a/dN² = -(dL0/da)/(k² L0³)`, `d²a/dphi dN =
    /// -1/(kn phi² L0) - (dL0/dphi)/(kn phi L0²)`; `d²af/dphi²` and
    /// `d²a/dphi²` are [`second_derivatives`](Self::second_derivatives)'
    /// with `N` for the weight. In full contact `af = D/2 - kn phi Is/N`.
    pub fn loaded_second_derivatives(&self, c: &Contact, n: f64) -> LoadedCurvature {
        let phi = c.phi;
        let mut out = LoadedCurvature::default();
        if self.law == Law::Rigid {
            return out;
        }
        if phi == 0.0 || c.regime == Regime::FullContact {
            let k_is = self.kn * self.is;
            out.af_nn = -2.0 * k_is * phi / (n * n * n);
            out.af_pn = k_is / (n * n);
            out.a_n = 1.0 / (self.kn * phi * self.area);
            return out;
        }
        let Some(z) = self.elastic_zone(c) else {
            return out;
        };
        (out.af_pp, out.a_pp) = self.zone_second_derivatives(c, &z, n);
        let ElasticZone { a1, x2, xp, l } = z;
        let (d, a) = (self.d, c.a);
        let k = self.kn * phi;
        let grow = if a < d { self.shape.width(x2) } else { 0.0 };
        let lose = if xp > 0.0 { self.shape.width(xp) } else { 0.0 };
        let cz = l[1] / l[0];
        let x = xp + cz;
        let a_p = -((a - xp) * l[0] - l[1]) / (phi * l[0]);
        let a_n = 1.0 / (k * l[0]);
        let dx_da = (grow * (x2 - x) + lose * cz) / l[0];
        let dxp = if xp > 0.0 { a1 / phi } else { 0.0 };
        let x_n = dx_da * a_n;
        let x_p = dx_da * a_p + lose * cz * dxp / l[0];
        let af_n = (x - c.af) / n;
        out.a_n = a_n;
        out.af_nn = (x_n - 2.0 * af_n) / n;
        out.af_pn = (x_p - c.daf) / n;
        out.a_nn = -(grow - lose) / (k * k * l[0] * l[0] * l[0]);
        let dl0_dphi = grow * if a < d { a_p } else { 0.0 } - lose * (a_p + dxp);
        out.a_pn = -1.0 / (self.kn * phi * phi * l[0]) - dl0_dphi / (self.kn * phi * l[0] * l[0]);
        out
    }

    /// The elastic zone `[xp, x2]` of a solved contact `c` at `phi > 0`
    /// (docs/model.md §2) with its moments about `xp`; `None` where it has
    /// no area.
    fn elastic_zone(&self, c: &Contact) -> Option<ElasticZone> {
        let a = c.a;
        let a1 = self.fm / (self.kn * c.phi);
        let x2 = a.min(self.d);
        let xp = (a - a1).clamp(0.0, x2);
        let l = if xp == 0.0 && a >= self.d {
            self.s_full
        } else {
            self.shape.zone_moments(xp, x2)
        };
        (l[0] > 0.0).then_some(ElasticZone { a1, x2, xp, l })
    }

    /// The solid-rectangle formulas of docs/model.md §2 for `a` in partial
    /// contact, with the section's mean width `A/D`, and their derivative
    /// in `phi`: elastic `a = sqrt(2W/(kn phi wbar))`; crushing
    /// `a = a1 + a2 = alim + a1/2`, `alim = W/(fm wbar)`, `a1 = fm/(kn phi)`.
    fn rectangle_formula(&self, phi: f64, crushing: bool) -> (f64, f64) {
        let wbar = self.area / self.d;
        if crushing {
            let a1 = self.fm / (self.kn * phi);
            (self.weight / (self.fm * wbar) + a1 / 2.0, -a1 / (2.0 * phi))
        } else {
            let a = (2.0 * self.weight / (self.kn * phi * wbar)).sqrt();
            (a, -a / (2.0 * phi))
        }
    }

    /// A starting point for the equilibrium solve without a hint.
    fn first_guess(&self, k: f64, a1: f64, lo: f64, hi: f64) -> f64 {
        let guess = self
            .rectangle_formula(k / self.kn, a1.is_finite() && lo >= a1)
            .0;
        if guess > lo && guess < hi {
            guess
        } else {
            0.5 * (lo + hi)
        }
    }

    /// The zones of the stress profile at `a` with elastic length `a1`
    /// (m): each cumulative moment evaluated once.
    #[inline(always)]
    fn zones(&self, a1: f64, a: f64) -> Zones {
        let x2 = a.min(self.d);
        let xp = (a - a1).clamp(0.0, x2);
        let sp = if xp > 0.0 {
            self.shape.moments(xp)
        } else {
            [0.0; 3]
        };
        let l = if xp == 0.0 && a >= self.d {
            // whole base elastic: the moments about the toe are known
            self.s_full
        } else {
            // moments(D) is s_full
            let sq = || {
                if a >= self.d {
                    self.s_full
                } else {
                    self.shape.moments(x2)
                }
            };
            self.shape.zone_moments_from(xp, x2, || sp, sq)
        };
        Zones {
            xp,
            x2,
            e: a - xp,
            l,
            sp,
        }
    }

    /// The bed resultant `Nbed(a, phi)` with `k = kn phi` and `a1 = fm/k`
    /// (docs/model.md §6.4), N: the `n` of [`resultants`](Self::resultants)
    /// without the rest.
    #[inline]
    fn bed_resultant(&self, k: f64, a1: f64, a: f64) -> f64 {
        let z = self.zones(a1, a);
        z.plastic(self.fm).0 + k * z.force()
    }

    /// Force and moment of the stress profile with closure `k (a - x)`,
    /// capped at `fm`: plastic zone `[0, xp]`, `xp = a - a1`, elastic zone
    /// `[xp, x2]` (docs/model.md §2). The elastic zone's integrals are taken
    /// about its start `xp` so that no digits cancel when it is narrow.
    #[inline]
    fn resultants(&self, k: f64, a1: f64, a: f64) -> Resultants {
        let z = self.zones(a1, a);
        let (x2, xp, l, e) = (z.x2, z.xp, z.l, z.e);
        let (np, mp) = z.plastic(self.fm);
        let f = z.force();
        // ∫ (a - x) x w = xp (e L0 - L1) + e L1 - L2 over the elastic zone
        let mz = xp * f + e * l[1] - l[2];
        // The elastic zone gains w(x2) at its end (while a < D) and loses
        // w(xp) at its start (while crushing) as a grows.
        let grow = if a < self.d {
            self.shape.width(x2)
        } else {
            0.0
        };
        let lose = if xp > 0.0 { self.shape.width(xp) } else { 0.0 };
        let (central, dcentral_da) = if l[0] > 0.0 {
            let c = l[1] / l[0]; // zone centroid, from xp
            let e2 = x2 - xp;
            (
                (l[2] - l[1] * c).max(0.0),
                grow * (e2 - c) * (e2 - c) - lose * c * c,
            )
        } else {
            (0.0, 0.0)
        };
        Resultants {
            xp,
            zone_moment: l[1],
            n: np + k * f, // = bed_resultant(k, a1, a)
            m: mp + k * mz,
            dn_da: k * l[0],
            d2n_da2: k * (grow - lose),
            dm_da: k * (xp * l[0] + l[1]),
            d2m_da2: k * (x2 * grow - xp * lose),
            central,
            dcentral_da,
            zone_force: f,
            zone_area: l[0],
            grow,
            lose,
            x2,
            xel_moved: 0.0,
        }
    }
}

/// The elastic zone of a solved contact ([`Interface::elastic_zone`]).
struct ElasticZone {
    /// `fm/(kn phi)`, m.
    a1: f64,
    /// The zone's ends, m from the toe.
    x2: f64,
    xp: f64,
    /// Its moments about `xp`, `[L0, L1, L2]`.
    l: [f64; 3],
}

/// The second partial derivatives of a contact at `(phi, N)`
/// ([`Interface::loaded_second_derivatives`]): `p` for `phi` (rad), `n`
/// for `N` (N). m/rad², m/(rad N), m/N².
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LoadedCurvature {
    /// `da/dN` (the first partial the contact does not carry).
    pub a_n: f64,
    pub af_pp: f64,
    pub af_pn: f64,
    pub af_nn: f64,
    pub a_pp: f64,
    pub a_pn: f64,
    pub a_nn: f64,
}

/// The plastic zone `[0, xp]` and the elastic zone `[xp, x2]` of the
/// stress profile at one `a` (docs/model.md §2).
struct Zones {
    /// End of the plastic zone, m from the toe.
    xp: f64,
    /// End of the elastic zone, `min(a, D)`, m.
    x2: f64,
    /// Closure at `xp`, `a - xp`, m.
    e: f64,
    /// Moments of the elastic zone about `xp`, `[L0, L1, L2]`.
    l: [f64; 3],
    /// Moments of the plastic zone about the toe, `[S0, S1, S2](xp)`
    /// (zero without one).
    sp: [f64; 3],
}

impl Zones {
    /// `∫ (a - x) w dx` over the elastic zone, `e L0 - L1`, m³.
    #[inline(always)]
    fn force(&self) -> f64 {
        self.e * self.l[0] - self.l[1]
    }

    /// Force and moment about the toe of the plastic zone at stress `fm`
    /// (Pa): N, N m (none without one: `fm` is infinite on an elastic bed).
    #[inline(always)]
    fn plastic(&self, fm: f64) -> (f64, f64) {
        if self.xp > 0.0 {
            (fm * self.sp[0], fm * self.sp[1])
        } else {
            (0.0, 0.0)
        }
    }
}

/// The stress profile's resultants at one `a`, with their `a`-derivatives.
struct Resultants {
    /// Start of the elastic zone (end of the plastic one), m from the toe.
    xp: f64,
    /// First moment of the elastic zone about `xp`, m³.
    zone_moment: f64,
    /// Normal force `N`, N.
    n: f64,
    /// Moment about the toe, N m.
    m: f64,
    /// `dN/da` at fixed rotation, N/m (the plastic-boundary terms cancel).
    dn_da: f64,
    /// `d²N/da²`, N/m².
    d2n_da2: f64,
    /// `dM/da`, `d²M/da²`.
    dm_da: f64,
    d2m_da2: f64,
    /// Second moment of the elastic zone about its centroid, m⁴, and its
    /// `a`-derivative.
    central: f64,
    dcentral_da: f64,
    /// `∫ (a - x) w dx` over the elastic zone, m³ (`dN/dphi = kn` times it).
    zone_force: f64,
    /// Area of the elastic zone, m².
    zone_area: f64,
    /// The widths the elastic zone gains at its end and loses at its
    /// start as `a` grows, m, and its end `min(a, D)`, m.
    grow: f64,
    lose: f64,
    x2: f64,
    /// How far [`shift`](Self::shift) moved the zone's centroid, m.
    xel_moved: f64,
}

impl Resultants {
    /// Move to `a + d` by Taylor series: second order for `N` and `M`,
    /// first order for the central moment (it enters `af'` only).
    fn shift(&mut self, d: f64) {
        // the elastic zone's centroid X = xp + L1/L0 moves at
        // dX/da = (w(x2) (x2 - X) + w(xp) (X - xp)) / L0: without it
        // `xel` is the start's, and daf/dN = (xel - af)/N off by the step
        // (1e-8 of it on the Dharahara's crushing beds)
        if self.zone_area > 0.0 {
            let c = self.zone_moment / self.zone_area;
            let e2 = self.x2 - self.xp;
            self.xel_moved = d * (self.grow * (e2 - c) + self.lose * c) / self.zone_area;
        }
        self.n += d * (self.dn_da + 0.5 * d * self.d2n_da2);
        self.m += d * (self.dm_da + 0.5 * d * self.d2m_da2);
        self.central += d * self.dcentral_da;
    }
}

/// The contact of the rigid law at `phi > 0`: the reaction at the toe.
fn toe(phi: f64) -> Contact {
    Contact {
        af: 0.0,
        daf: 0.0,
        a: 0.0,
        contact_length: 0.0,
        phi,
        da: 0.0,
        regime: Regime::Partial,
        iterations: 0,
    }
}

/// Root of an increasing function on `[lo, hi]` by bisection to the last
/// bit (used only at initialization).
pub(crate) fn solve_increasing(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..2000 {
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
