//! The rigid body: mass models and derived values (docs/model.md §1, §3).

use crate::shape::Shape;

/// How the body's mass is described (docs/model.md §1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MassModel {
    /// The base section extruded to height `h` (m) with density `rho` (kg/m³).
    Prism { h: f64, rho: f64 },
    /// Weight `w` (N), height of the centre of mass `hg` (m) and inertia about
    /// the centre of mass `ic` (kg m²), given directly.
    Lumped { w: f64, hg: f64, ic: f64 },
}

/// Derived rigid-body values (docs/model.md §1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    /// Gravity, m/s².
    pub g: f64,
    /// Mass `m = W/g`, kg.
    pub mass: f64,
    /// Weight `W`, N.
    pub weight: f64,
    /// Height of the centre of mass above the base, m.
    pub hg: f64,
    /// Inertia about the centre of mass `Ic`, kg m².
    pub ic: f64,
    /// Half depth of the base `b = D/2`, m.
    pub b: f64,
    /// Toe-to-centre-of-mass distance `R0 = sqrt(b² + hG²)`, m.
    pub r0: f64,
    /// Slenderness `alpha = atan(b/hG)`, rad.
    pub alpha: f64,
    /// `sin(alpha)`, `cos(alpha)`, cached.
    pub sin_alpha: f64,
    pub cos_alpha: f64,
    /// Inertia about the toe `IO = Ic + m R0²`, kg m².
    pub io: f64,
}

impl Body {
    /// Body values for a base `shape`, a mass model and gravity `g` (m/s²).
    /// No validation here: see [`crate::model::Params::build`].
    pub fn new(shape: &Shape, mass_model: MassModel, g: f64) -> Body {
        let (weight, hg, ic) = match mass_model {
            MassModel::Prism { h, rho } => {
                let a = shape.area();
                let weight = rho * g * a * h;
                let m = weight / g;
                // docs/model.md §1: Ic = m (H²/12 + Is/A)
                (
                    weight,
                    h / 2.0,
                    m * (h * h / 12.0 + shape.second_moment() / a),
                )
            }
            MassModel::Lumped { w, hg, ic } => (w, hg, ic),
        };
        let mass = weight / g;
        let b = shape.depth() / 2.0;
        let r0 = b.hypot(hg);
        let alpha = b.atan2(hg);
        Body {
            g,
            mass,
            weight,
            hg,
            ic,
            b,
            r0,
            alpha,
            sin_alpha: b / r0,
            cos_alpha: hg / r0,
            io: ic + mass * r0 * r0,
        }
    }

    /// Housner's coefficient of restitution `eta = 1 - 2 m b² / IO` (docs/model.md §3).
    pub fn eta_housner(&self) -> f64 {
        1.0 - 2.0 * self.mass * self.b * self.b / self.io
    }
}
