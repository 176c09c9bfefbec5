//! A macroblock's seven lengths, its constraints, and the load directions.

use serde::{Deserialize, Serialize};

use crate::error::{err, CornerError};
use crate::{CornerModel, Mechanism};

/// The seven lengths of the macroblock (m), with the paper's labels (its Fig. 17).
///
/// Lengths run along each wall from the outer vertex. WX: base `X3` at the hinge
/// level `Z1`, green top `X1`, red top width `X2`. WY: base `Y3`, green top `Y2`,
/// red top width `Y1` (the paper's labels are mirrored between the walls).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Geometry {
    #[serde(rename = "X1")]
    pub x1: f64,
    #[serde(rename = "X2")]
    pub x2: f64,
    #[serde(rename = "X3")]
    pub x3: f64,
    #[serde(rename = "Y1")]
    pub y1: f64,
    #[serde(rename = "Y2")]
    pub y2: f64,
    #[serde(rename = "Y3")]
    pub y3: f64,
    #[serde(rename = "Z1")]
    pub z1: f64,
}

impl Geometry {
    /// The same macroblock with the walls swapped (x <-> y).
    pub fn mirror(&self) -> Geometry {
        Geometry {
            x1: self.y2,
            x2: self.y1,
            x3: self.y3,
            y1: self.x2,
            y2: self.x1,
            y3: self.x3,
            z1: self.z1,
        }
    }

    /// WX as a wall part: (green top, red width, base).
    pub fn wall_x(&self) -> WallPart {
        WallPart {
            green: self.x1,
            red: self.x2,
            base: self.x3,
        }
    }

    /// WY as a wall part: (green top, red width, base).
    pub fn wall_y(&self) -> WallPart {
        WallPart {
            green: self.y2,
            red: self.y1,
            base: self.y3,
        }
    }

    /// Checks the constraints (tolerance `tol`, m); the error names the violated variable.
    pub fn check(&self, model: &CornerModel, tol: f64) -> Result<(), CornerError> {
        let sp = &model.specimen;
        let vals = [
            ("X1", self.x1),
            ("X2", self.x2),
            ("X3", self.x3),
            ("Y1", self.y1),
            ("Y2", self.y2),
            ("Y3", self.y3),
            ("Z1", self.z1),
        ];
        for (name, x) in vals {
            if !x.is_finite() {
                return Err(err(name, "must be finite"));
            }
        }
        if self.z1 < sp.h - tol || self.z1 > sp.height() - sp.h + tol {
            return Err(err("Z1", "must lie in [h, H - h]"));
        }
        let d = sp.height() - self.z1;
        let flexural = model.mechanism == Mechanism::Flexural;
        for (wall, names, len) in [
            (self.wall_x(), ("X1", "X2", "X3"), sp.length_x()),
            (self.wall_y(), ("Y2", "Y1", "Y3"), sp.length_y()),
        ] {
            if wall.base < sp.t - tol || wall.base > wall.green + tol {
                return Err(err(names.2, "base must lie in [t, green top]"));
            }
            if wall.red < -tol || (flexural && wall.red <= 0.0) {
                return Err(err(names.1, "red width must be >= 0 (> 0 for m = 1)"));
            }
            if wall.green + wall.red > len + tol {
                return Err(err(
                    names.0,
                    "the macroblock passes the clamped end of the wall",
                ));
            }
            if wall.green + wall.red - wall.base > d * sp.tan_alpha_b() + tol {
                return Err(err(
                    names.1,
                    "outer crack flatter than the running-bond step alpha_b",
                ));
            }
        }
        Ok(())
    }
}

/// One wall's share of a macroblock: green top, red top width, base (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallPart {
    pub green: f64,
    pub red: f64,
    pub base: f64,
}

/// Load direction of a one-direction mechanism.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Direction {
    /// Load along x: WX in-plane, WY out-of-plane (weight cos^2 alpha).
    X,
    /// Load along y: WY in-plane, WX out-of-plane (weight sin^2 alpha).
    Y,
}
