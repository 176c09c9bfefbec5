//! The virtual-work balance of one direction: stabilising and overturning work of the
//! in-plane wedge and the out-of-plane parts, friction along the cracks, shear-torsion at
//! the flexural hinges, and the multiplier lambda = (S + D) / (O + Lambda) (`docs/corner.md`).

use std::f64::consts::FRAC_PI_2;

use serde::{Deserialize, Serialize};

use crate::error::{err, CornerError};
use crate::{
    CornerColumn, CornerModel, CrackRatio, Direction, FrictionJoints, FrictionLever, Geometry,
    InPlaneWedge, Mechanism, WallPart,
};

/// Virtual work per unit rotation of the hinge axis (N m per rad), one direction.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct WorkTerms {
    /// S: work of gravity (stabilising).
    pub stabilising: f64,
    /// O: work of the horizontal load per unit multiplier (overturning).
    pub overturning: f64,
    /// Friction dissipated along the in-plane crack.
    pub friction_ip: f64,
    /// Friction dissipated along the out-of-plane outer crack (m = 0 only).
    pub friction_oop: f64,
    /// Shear-torsion dissipated at the two flexural hinges (m = 1 only), lambda-free part.
    pub torsion: f64,
    /// Lambda: the part of the torsion dissipation proportional to the multiplier (enters the denominator).
    pub torsion_lambda: f64,
    /// D = friction_ip + friction_oop + torsion.
    pub dissipation: f64,
    /// The multiplier (S + D) / (O + Lambda).
    pub lambda: f64,
}

/// Per-part quantities of one wall in one role, reused across the search.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct InPlane {
    pub(crate) weight: f64,
    pub(crate) stabilising: f64,
    pub(crate) overturning: f64,
    pub(crate) friction: f64,
}

#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct OutOfPlane {
    pub(crate) weight_green: f64,
    pub(crate) weight_red: f64,
    pub(crate) stabilising: f64,
    pub(crate) overturning: f64,
    pub(crate) friction: f64,
    pub(crate) torsion: f64,
    pub(crate) torsion_lambda: f64,
    /// Fmax(n) of the red block's hinges (N), for the clamp of the torsion brackets.
    pub(crate) fmax: f64,
}

/// Trapezoid with a vertical edge at s = 0, base `b` at z' = 0, top `a` at z' = d:
/// (area, centroid distance from the edge, centroid height above the base).
fn trapezoid(a: f64, b: f64, d: f64) -> (f64, f64, f64) {
    let area = 0.5 * d * (a + b);
    if a + b <= 0.0 {
        return (0.0, 0.0, 0.0);
    }
    let s_g = (a * a + a * b + b * b) / (3.0 * (a + b));
    let z_g = d * (2.0 * a + b) / (3.0 * (a + b));
    (area, s_g, z_g)
}

/// Mean distance of the points of a t x v rectangle from its centroid (m): the lever of
/// uniform shear-torsion on one overlap contact (paper's Eq. 10).
pub fn torsion_lever(t: f64, v: f64) -> f64 {
    let dp = (v * v + t * t).sqrt();
    (v.powi(3) * ((t + dp) / v).ln() + t.powi(3) * ((v + dp) / t).ln() + 2.0 * t * v * dp)
        / (12.0 * t * v)
}

impl CornerModel {
    fn courses_above(&self, d: f64) -> f64 {
        d / self.specimen.h
    }

    /// Frictional capacity of a crack spanning n courses (N), Eq. 9.
    pub fn fmax(&self, n: f64) -> f64 {
        let sp = &self.specimen;
        let count = match self.options.friction_joints {
            FrictionJoints::Eq9 => 0.5 * n * (n + 1.0),
            FrictionJoints::Inner => 0.5 * n * (n - 1.0),
        };
        sp.mu * sp.gamma() * sp.v() * sp.h * sp.t * count
    }

    /// Work of friction along a crack of horizontal extent `extent` over height d (N m / rad).
    fn crack_friction(&self, extent: f64, d: f64) -> f64 {
        let sp = &self.specimen;
        let n = self.courses_above(d);
        let lever = match self.options.friction_lever {
            FrictionLever::Joints => (n - 1.0) * sp.h / 3.0,
            FrictionLever::Third => d / 3.0,
        };
        let tan_b = sp.tan_alpha_b();
        let tan_c = extent.max(0.0) / d;
        let weight = match self.options.crack_ratio {
            CrackRatio::Angle => 1.0 - tan_c.atan() / tan_b.atan(),
            CrackRatio::Tan => 1.0 - tan_c / tan_b,
        };
        lever * self.fmax(n) * weight.max(0.0)
    }

    /// Top of the in-plane wedge of a wall [A3].
    pub(crate) fn wedge_top(&self, w: WallPart) -> f64 {
        match (self.mechanism, self.options.in_plane_wedge) {
            (Mechanism::Flexural, InPlaneWedge::Green) => w.green,
            _ => w.green + w.red,
        }
    }

    pub(crate) fn in_plane(&self, w: WallPart, d: f64) -> InPlane {
        let sp = &self.specimen;
        let top = self.wedge_top(w);
        let (area, s_g, z_g) = trapezoid(top, w.base, d);
        let weight = sp.gamma() * sp.t * area;
        InPlane {
            weight,
            stabilising: weight * s_g,
            overturning: weight * z_g,
            friction: self.crack_friction(top - w.base, d),
        }
    }

    /// Where the out-of-plane part starts along its wall [A4].
    pub(crate) fn oop_start(&self) -> f64 {
        match self.options.corner_column {
            CornerColumn::Both => 0.0,
            CornerColumn::Once => self.specimen.t,
        }
    }

    pub(crate) fn out_of_plane(&self, w: WallPart, d: f64) -> OutOfPlane {
        let sp = &self.specimen;
        let gt = sp.gamma() * sp.t;
        let y0 = self.oop_start();
        let flexural = self.mechanism == Mechanism::Flexural;
        let green_top = if flexural { w.green } else { w.green + w.red };
        let (area_g, _, z_g) = trapezoid(green_top - y0, w.base - y0, d);
        let weight_green = gt * area_g;
        let mut o = OutOfPlane {
            weight_green,
            stabilising: weight_green * 0.5 * sp.t,
            overturning: weight_green * z_g,
            ..OutOfPlane::default()
        };
        let n = self.courses_above(d);
        o.fmax = self.fmax(n);
        if flexural {
            // Red triangle O'A'B': apex at the base point, top width `red`; it turns about the
            // outer line at omega = d / red per unit rotation, so its mean displacement is d/3.
            let weight_red = gt * 0.5 * d * w.red;
            let omega = d / w.red;
            let d0 = torsion_lever(sp.t, sp.v());
            o.weight_red = weight_red;
            o.stabilising += weight_red * 0.5 * sp.t;
            o.overturning += weight_red * d / 3.0;
            o.torsion = 2.0 * self.k * omega * o.fmax * d0;
            o.torsion_lambda = self.k * omega * d0 * weight_red;
        } else {
            o.friction = self.crack_friction(w.green + w.red - w.base, d);
        }
        o
    }

    fn combine(&self, ip: &InPlane, oop: &OutOfPlane) -> WorkTerms {
        let s = ip.stabilising + oop.stabilising;
        let o = ip.overturning + oop.overturning;
        let mut w = WorkTerms {
            stabilising: s,
            overturning: o,
            friction_ip: ip.friction,
            friction_oop: oop.friction,
            torsion: oop.torsion,
            torsion_lambda: oop.torsion_lambda,
            ..WorkTerms::default()
        };
        w.dissipation = w.friction_ip + w.friction_oop + w.torsion;
        w.lambda = (s + w.dissipation) / (o + w.torsion_lambda);
        // [A7] The brackets T0 (1 - F/Fmax), F = lambda W_red / 2 at each hinge, cannot go negative.
        if w.torsion > 0.0 && 0.5 * w.lambda * oop.weight_red > oop.fmax {
            w.torsion = 0.0;
            w.torsion_lambda = 0.0;
            w.dissipation = w.friction_ip + w.friction_oop;
            w.lambda = (s + w.dissipation) / o;
        }
        w
    }

    /// Work terms and multiplier of one direction for a given geometry (not checked).
    pub fn direction_terms(&self, x: &Geometry, dir: Direction) -> WorkTerms {
        let d = self.specimen.height() - x.z1;
        let (ip, oop) = match dir {
            Direction::X => (x.wall_x(), x.wall_y()),
            Direction::Y => (x.wall_y(), x.wall_x()),
        };
        self.combine(&self.in_plane(ip, d), &self.out_of_plane(oop, d))
    }

    /// lambda_alpha of a given geometry, with both directions' terms.
    pub fn evaluate(&self, x: &Geometry, alpha: f64) -> Result<Evaluation, CornerError> {
        let alpha = check_alpha(alpha)?;
        x.check(self, 1e-9)?;
        Ok(self.evaluate_unchecked(x, alpha))
    }

    pub(crate) fn evaluate_unchecked(&self, x: &Geometry, alpha: f64) -> Evaluation {
        let wx = self.direction_terms(x, Direction::X);
        let wy = self.direction_terms(x, Direction::Y);
        let (s, c) = alpha.sin_cos();
        Evaluation {
            alpha,
            lambda_alpha: c * c * wx.lambda + s * s * wy.lambda,
            lambda_x: wx.lambda,
            lambda_y: wy.lambda,
            geometry: *x,
            work_x: wx,
            work_y: wy,
        }
    }
}

/// alpha (rad) checked to lie in [0, pi/2], and clamped there: pi/2 written to 10
/// significant digits (1.570796327) lies 2e-10 above it, so values within 1e-9 of either
/// end count as that end.
pub(crate) fn check_alpha(alpha: f64) -> Result<f64, CornerError> {
    const ROUNDING: f64 = 1e-9;
    if !(alpha.is_finite() && (-ROUNDING..=FRAC_PI_2 + ROUNDING).contains(&alpha)) {
        return Err(err(
            "alpha",
            format!("must be in [0, pi/2] rad, got {alpha}"),
        ));
    }
    Ok(alpha.clamp(0.0, FRAC_PI_2))
}

/// lambda_alpha and its parts for one geometry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Load orientation from the x axis (rad).
    pub alpha: f64,
    pub lambda_alpha: f64,
    #[serde(rename = "lambda_X")]
    pub lambda_x: f64,
    #[serde(rename = "lambda_Y")]
    pub lambda_y: f64,
    pub geometry: Geometry,
    #[serde(rename = "work_X")]
    pub work_x: WorkTerms,
    #[serde(rename = "work_Y")]
    pub work_y: WorkTerms,
}
