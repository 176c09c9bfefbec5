//! The collapsing macroblock as a rigid body rocking about its hinge axis, and the
//! RockingBlock FMU parameters of that body.

use serde::{Deserialize, Serialize};

use crate::error::{err, CornerError};
use crate::{CornerModel, Direction, Geometry, Mechanism};

/// Which of the two FMU bodies of a macroblock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BodyKind {
    /// B = 2b: uplift at lambda_rock, overturning at theta_u; no dissipation.
    Geometric,
    /// B = 2 b_eq: uplift at the limit-analysis lambda; overstates the rotation capacity.
    Threshold,
}

/// A one-direction macroblock as a rigid body rocking about its hinge axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RockingBody {
    pub direction: Direction,
    /// Weight of all moving blocks (N).
    #[serde(rename = "W")]
    pub weight: f64,
    /// Mass (kg).
    pub mass: f64,
    /// Work-equivalent height of G above the hinge level, O / W (m).
    #[serde(rename = "hG")]
    pub h_g: f64,
    /// Work-equivalent lever of G from the hinge axis, S / W (m).
    pub b: f64,
    /// Kinetic-energy-consistent inertia about the hinge axis (kg m2).
    #[serde(rename = "IO")]
    pub i_o: f64,
    /// Inertia about G, I_O - mass (b^2 + hG^2) (kg m2).
    #[serde(rename = "Ic")]
    pub i_c: f64,
    /// The limit-analysis multiplier of this direction (with dissipation).
    pub lambda: f64,
    /// S / O = b / hG: the multiplier without dissipation.
    pub lambda_rock: f64,
    /// atan(b / hG): rotation at which gravity's restoring moment vanishes (rad).
    pub theta_u: f64,
    /// lambda hG: the half-depth that puts the FMU's uplift threshold at lambda (m).
    pub b_eq: f64,
    /// Base length of the out-of-plane part along the hinge (X3 or Y3), the FMU's L (m).
    pub base_length: f64,
}

impl RockingBody {
    /// The RockingBlock FMU parameters of this body, as (name, value) with enumerations by item
    /// name: lumped mass, solid rectangle of depth 2b (geometric) or 2 b_eq (threshold), rigid
    /// interface, Housner restitution.
    pub fn fmu_parameters(&self, kind: BodyKind, g: f64) -> Vec<(&'static str, ParamValue)> {
        let half = match kind {
            BodyKind::Geometric => self.b,
            BodyKind::Threshold => self.b_eq,
        };
        vec![
            ("massModel", ParamValue::Enum("lumped")),
            ("W", ParamValue::Real(self.weight)),
            ("hG", ParamValue::Real(self.h_g)),
            ("Ic", ParamValue::Real(self.i_c)),
            ("shape", ParamValue::Enum("solidRectangle")),
            ("B", ParamValue::Real(2.0 * half)),
            ("L", ParamValue::Real(self.base_length)),
            ("interface", ParamValue::Enum("rigid")),
            ("restitution", ParamValue::Enum("housner")),
            ("g", ParamValue::Real(g)),
        ]
    }
}

/// A parameter value for the FMU file: a real or an enumeration item by name.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum ParamValue {
    Real(f64),
    Enum(&'static str),
}

/// Inertia integrals about the hinge axis of the parts (kg m2), see `docs/corner.md`.
fn inertia(model: &CornerModel, x: &Geometry, dir: Direction) -> f64 {
    let sp = &model.specimen;
    let d = sp.height() - x.z1;
    let (ip, oop) = match dir {
        Direction::X => (x.wall_x(), x.wall_y()),
        Direction::Y => (x.wall_y(), x.wall_x()),
    };
    let rho_t = sp.rho * sp.t;
    // In-plane wedge: rho t * integral of (s^2 + z'^2) over the trapezoid.
    let (a, b) = (model.wedge_top(ip), ip.base);
    let i_ip = rho_t * (d * (a + b) * (a * a + b * b) / 12.0 + d.powi(3) * (3.0 * a + b) / 12.0);
    // Out-of-plane green part: rho * integral of (t z'^2 + t^3/3): rotation about the outer edge.
    let y0 = model.oop_start();
    let flexural = model.mechanism == Mechanism::Flexural;
    let top = if flexural {
        oop.green
    } else {
        oop.green + oop.red
    } - y0;
    let base = oop.base - y0;
    let area = 0.5 * d * (top + base);
    let i_green =
        sp.rho * (sp.t * d.powi(3) * (3.0 * top + base) / 12.0 + sp.t.powi(3) / 3.0 * area);
    // Red triangle: turns at omega = d / red about its outer line; rho t omega^2 * integral of xi^2.
    let i_red = if flexural {
        let omega = d / oop.red;
        omega * omega * rho_t * oop.red.powi(3) * d / 12.0
    } else {
        0.0
    };
    i_ip + i_green + i_red
}

/// The macroblock `x` in direction `dir` as a rocking body (section "From macroblock to
/// rocking body" of `docs/corner.md`). Refuses a body whose inertia about G would be negative.
pub fn rocking_body(
    model: &CornerModel,
    x: &Geometry,
    dir: Direction,
) -> Result<RockingBody, CornerError> {
    x.check(model, 1e-9)?;
    let sp = &model.specimen;
    let w = model.direction_terms(x, dir);
    let d = sp.height() - x.z1;
    let (ip, oop) = match dir {
        Direction::X => (x.wall_x(), x.wall_y()),
        Direction::Y => (x.wall_y(), x.wall_x()),
    };
    let pip = model.in_plane(ip, d);
    let poop = model.out_of_plane(oop, d);
    let weight = pip.weight + poop.weight_green + poop.weight_red;
    let mass = weight / sp.g;
    let h_g = w.overturning / weight;
    let b = w.stabilising / weight;
    let i_o = inertia(model, x, dir);
    let i_c = i_o - mass * (b * b + h_g * h_g);
    if i_c < 0.0 {
        return Err(err(
            "geometry",
            format!("the macroblock is not rocking-like: inertia about G would be {i_c} kg m2"),
        ));
    }
    Ok(RockingBody {
        direction: dir,
        weight,
        mass,
        h_g,
        b,
        i_o,
        i_c,
        lambda: w.lambda,
        lambda_rock: b / h_g,
        theta_u: (b / h_g).atan(),
        b_eq: w.lambda * h_g,
        base_length: oop.base,
    })
}

/// The direction whose body represents orientation alpha: the one with the larger weight.
pub fn body_direction(alpha: f64) -> Direction {
    if alpha >= std::f64::consts::FRAC_PI_4 {
        Direction::Y
    } else {
        Direction::X
    }
}
