//! The corner specimen: block sizes, material and the extent of both walls.

use serde::{Deserialize, Serialize};

use crate::error::{err, CornerError};

/// Gravitational acceleration used by the specimen (m/s2), as in the paper.
pub const G: f64 = 9.81;

/// The corner: block sizes, material and extent of both walls.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Specimen {
    /// Block thickness = wall thickness (m).
    pub t: f64,
    /// Block length (m). The running-bond overlap is `v = l/2`.
    pub l: f64,
    /// Block (course) height (m).
    pub h: f64,
    /// Density (kg/m3).
    pub rho: f64,
    /// Dry-joint friction coefficient (-).
    pub mu: f64,
    /// Number of courses; the wall height is `courses * h`.
    pub courses: u32,
    /// Full blocks per course of wall WX, measured from the outer vertex (its length is `blocks_x * l`).
    pub blocks_x: u32,
    /// Full blocks per course of wall WY (its length is `blocks_y * l`).
    pub blocks_y: u32,
    /// Gravitational acceleration (m/s2).
    pub g: f64,
}

impl Specimen {
    /// The paper's 1:4 scaled dry-joint corner (its section 2.1, friction from the tilting tests).
    pub fn paper() -> Self {
        Specimen {
            t: 0.0573,
            l: 0.1149,
            h: 0.0703,
            rho: 1876.0,
            mu: 0.66,
            courses: 9,
            blocks_x: 7,
            blocks_y: 7,
            g: G,
        }
    }

    /// Running-bond overlap, half a block (m).
    pub fn v(&self) -> f64 {
        0.5 * self.l
    }

    /// Wall height (m).
    pub fn height(&self) -> f64 {
        f64::from(self.courses) * self.h
    }

    /// Unit weight `rho g` (N/m3).
    pub fn gamma(&self) -> f64 {
        self.rho * self.g
    }

    /// Length of WX from the outer vertex (m).
    pub fn length_x(&self) -> f64 {
        f64::from(self.blocks_x) * self.l
    }

    /// Length of WY from the outer vertex (m).
    pub fn length_y(&self) -> f64 {
        f64::from(self.blocks_y) * self.l
    }

    /// `tan(alpha_b) = v/h`: the natural stepped crack of running bond, one half block per course \[A2\].
    pub fn tan_alpha_b(&self) -> f64 {
        self.v() / self.h
    }

    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), CornerError> {
        for (name, value) in [
            ("t", self.t),
            ("l", self.l),
            ("h", self.h),
            ("rho", self.rho),
            ("mu", self.mu),
            ("g", self.g),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(err(name, format!("must be finite and > 0, got {value}")));
            }
        }
        if self.courses < 2 {
            return Err(err(
                "courses",
                format!(
                    "must be >= 2 (a hinge needs a course below and above it), got {}",
                    self.courses
                ),
            ));
        }
        for (name, blocks, length) in [
            ("blocks_x", self.blocks_x, self.length_x()),
            ("blocks_y", self.blocks_y, self.length_y()),
        ] {
            if blocks < 1 {
                return Err(err(name, "must be >= 1"));
            }
            if length < self.t {
                return Err(err(name, "the wall is shorter than its thickness t"));
            }
        }
        Ok(())
    }
}

impl Default for Specimen {
    fn default() -> Self {
        Self::paper()
    }
}
