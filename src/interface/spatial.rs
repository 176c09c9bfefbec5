//! The bed's reaction under a round section tilted about any horizontal
//! axis (docs/model.md §11.1): the planar law of §2 along the tilt's
//! direction.
//!
//! # The tilt
//!
//! As in `src/spatial` (docs/model.md §10.1), the tilt is `e`, the
//! horizontal part of the body's axis: `|e| = sin(theta)`, and `e` points
//! where the body leans, `d = e/|e|`. The toe is the rim point on that side,
//! `R d` from the base's centre. The same tilt as a rotation vector (a turn
//! by `theta` about a horizontal axis) is `rho = theta (z x d)`, so
//! `d = rho_hat x z` and `e = sin(|rho|) d`.
//!
//! # Why the planar law
//!
//! The bed is the planar model's: springs `kn` (Pa/m) under each point of the
//! base, no tension, stress capped at `fm` (Pa), holonomic (the stress depends
//! on the present closure alone). With the planar model's kinematics (a
//! small-rotation closure, `theta` for the slope of the base plane) the base
//! point at `p` (m, in the base's plane, from its centre) closes by
//!
//! `delta(p) = theta (a - x)`, `x = R - p . d`,
//!
//! the plane of the tilt: it depends on `x`, the distance from the toe
//! along `d`, and on nothing across it. A disc or a ring is unchanged by any
//! rotation about its centre, so cut into chords across `d` it has at every
//! `x` the planar width `w(x)` (docs/model.md §1), whatever `d` is. Then
//!
//! - the vertical force `∫ sigma dA = ∫ sigma(x) w(x) dx` is the planar `N(a)`,
//!   and equilibrium with the apparent weight fixes the planar `a`;
//! - the moment about the axis across `d` is the planar one, so the
//!   resultant lies at the planar `af` from the toe on the line of `d`;
//! - the moment about `d` itself is `∫ sigma(x) (∫ q dq) dx = 0`: each chord
//!   is symmetric about the line of `d` (`q` across it), whatever the stress
//!   on it.
//!
//! So the reaction is the planar contact at `phi = theta` under `N`, turned
//! to the azimuth of `d`: [`Interface::contact_loaded`], no second law.
//! `tests/spatial_bed.rs` checks it against fibres summed over the disc.

use crate::interface::{Contact, Interface, Law, Regime};
use crate::model::ParamError;
use crate::shape::Shape;

/// The planar interface of a round section, asked in space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoundBed {
    interface: Interface,
    /// Base radius `R`, m.
    radius: f64,
}

/// The bed's reaction at one tilt and apparent weight. Vectors in plan:
/// the base's own plane, on the axes of the ground's `x` and `y` turned with
/// the tilt (the same as the ground's within the small-rotation kinematics
/// of the bed). Moments are the bed's stresses' on the body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoundReaction {
    /// The vertical force, the apparent weight `N`, N.
    pub n: f64,
    /// The tilt `theta = asin(|e|)`, rad (the planar `phi`).
    pub theta: f64,
    /// Direction of the lean and of the toe (unit).
    pub direction: [f64; 2],
    /// The toe, `R d` from the base's centre, m.
    pub toe: [f64; 2],
    /// Where the resultant acts, `(R - af) d` from the base's centre, m:
    /// on the line of the tilt's direction, `af` from the toe.
    pub resultant: [f64; 2],
    /// The moment of the bed's stresses about the base's centre, N m:
    /// `N (c_y, -c_x)` with `c` the [`resultant`](Self::resultant), i.e.
    /// `-N (R - af) (z x d)`: against the tilt, nothing about `d`.
    pub moment: [f64; 2],
    /// `dM/drho` at fixed `N`, N m/rad: the moment's derivative in the
    /// rotation vector `rho = theta (z x d)`, row `i` column `j` for
    /// `dM_i/drho_j`. Along the tilt `N af'` (the planar tangent), across
    /// it `-N (R - af)/theta` (the moment turns with the tilt); both
    /// `-kn Is` at upright on a flexible bed, NaN there for the rigid one
    /// (its moment jumps).
    pub stiffness: [[f64; 2]; 2],
    /// `dM/dN` at fixed tilt, m: `-(R - xel) (z x d)` with `xel` the
    /// centroid of the elastic part of the contact (docs/model.md §6.1).
    pub moment_dn: [f64; 2],
    /// Area of the closed part of the base, `S0(min(a, D))`, m².
    pub contact_area: f64,
    /// Area of the crushed (plastic) part, `S0(xp)`, m².
    pub crushed_area: f64,
    /// The planar contact along `d` (`af`, `af'`, `a`, the contact length,
    /// the regime).
    pub contact: Contact,
}

impl RoundReaction {
    /// The regime of the contact (docs/model.md §2).
    pub fn regime(&self) -> Regime {
        self.contact.regime
    }
}

impl RoundBed {
    /// The bed of `interface`, whose section must be a solid or hollow
    /// circle (`shape`).
    pub fn new(interface: Interface) -> Result<RoundBed, ParamError> {
        let radius = match *interface.shape() {
            Shape::SolidCircle { ro } | Shape::HollowCircle { ro, .. } => ro,
            _ => {
                return Err(ParamError {
                    variable: "shape",
                    value: f64::NAN,
                    condition: "the bed in space needs a round base (solidCircle or hollowCircle)"
                        .into(),
                })
            }
        };
        Ok(RoundBed { interface, radius })
    }

    /// The planar interface.
    pub fn interface(&self) -> &Interface {
        &self.interface
    }

    /// Base radius `R`, m.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The reaction at the tilt `e` (the axis's horizontal part, `|e| < 1`)
    /// under the apparent weight `n` (N, `0 < n`, and `n < fm A` on a
    /// crushing bed). At `e = 0` the lean has no direction: the toe is put
    /// on `+x` (use [`reaction_toward`](Self::reaction_toward) to keep one).
    pub fn reaction(&self, e: [f64; 2], n: f64) -> Result<RoundReaction, ParamError> {
        let s = e[0].hypot(e[1]);
        if s.is_nan() || s >= 1.0 {
            return Err(ParamError {
                variable: "e",
                value: s,
                condition: "the tilt |e| = sin(theta) must be finite and < 1".into(),
            });
        }
        let d = if s > 0.0 {
            [e[0] / s, e[1] / s]
        } else {
            [1.0, 0.0]
        };
        self.reaction_toward(s.asin(), d, n)
    }

    /// The reaction at the tilt `theta` (rad, `0 <= theta < pi/2`) toward
    /// the unit direction `d`, under the apparent weight `n` (N).
    pub fn reaction_toward(
        &self,
        theta: f64,
        d: [f64; 2],
        n: f64,
    ) -> Result<RoundReaction, ParamError> {
        if !(0.0..std::f64::consts::FRAC_PI_2).contains(&theta) {
            return Err(ParamError {
                variable: "theta",
                value: theta,
                condition: "the tilt must be in [0, pi/2)".into(),
            });
        }
        let norm = d[0].hypot(d[1]);
        if norm.is_nan() || (norm - 1.0).abs() > 1e-12 {
            return Err(ParamError {
                variable: "d",
                value: norm,
                condition: "the direction of the tilt must be a unit vector".into(),
            });
        }
        let it = &self.interface;
        let (kn, fm) = match it.law() {
            Law::Rigid => (f64::INFINITY, f64::INFINITY),
            Law::Elastic { kn } => (kn, f64::INFINITY),
            Law::ElastoPlastic { kn, fm } => (kn, fm),
        };
        let shape = it.shape();
        let area = shape.area();
        if !(n > 0.0 && n < fm * area) {
            return Err(ParamError {
                variable: "N",
                value: n,
                condition: format!(
                    "the apparent weight must be > 0 and below fm A = {} N (docs/model.md §6.5)",
                    fm * area
                ),
            });
        }
        let (c, xel) = it.contact_loaded(theta, n, f64::NAN);
        let r = self.radius;
        let lever = r - c.af;
        let across = [-d[1], d[0]]; // z x d
        let x2 = c.contact_length;
        // the plastic zone [0, xp], xp = a - fm/(kn theta) (docs/model.md §2)
        let xp = if theta > 0.0 && fm.is_finite() {
            (c.a - fm / (kn * theta)).clamp(0.0, x2)
        } else {
            0.0
        };
        let s0 = |x: f64| if x > 0.0 { shape.moments(x)[0] } else { 0.0 };
        // (R - af)/theta: in elastic full contact af = R - kn theta Is/N, so
        // it is kn Is/N exactly, also at theta = 0
        let secant = if it.law() == Law::Rigid {
            if theta > 0.0 {
                r / theta
            } else {
                f64::NAN
            }
        } else if c.regime == Regime::FullContact {
            kn * shape.second_moment() / n
        } else {
            lever / theta
        };
        let tangent = n * c.daf;
        let stiffness = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let along = across[i] * across[j];
                let unit = if i == j { 1.0 } else { 0.0 };
                -n * secant * (unit - along) + tangent * along
            })
        });
        Ok(RoundReaction {
            n,
            theta,
            direction: d,
            toe: [r * d[0], r * d[1]],
            resultant: [lever * d[0], lever * d[1]],
            moment: [-n * lever * across[0], -n * lever * across[1]],
            stiffness,
            moment_dn: [-(r - xel) * across[0], -(r - xel) * across[1]],
            contact_area: s0(x2),
            crushed_area: s0(xp),
            contact: c,
        })
    }
}
