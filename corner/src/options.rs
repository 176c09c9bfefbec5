//! The model's options: one switch per reconstruction of `docs/corner.md` (\[A3\]..\[A6\],
//! the joints of Fmax), and the named presets.

use serde::{Deserialize, Serialize};

/// Named option sets (`docs/corner.md`, "Presets").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// The readings that reproduce the paper's Table 5 (default).
    Paper,
    /// The literal reading of the printed equations.
    Literal,
}

/// \[A3\] Which line bounds the in-plane wedge in the flexural mechanism (m = 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InPlaneWedge {
    /// The inner ("green") line O''B'': the red part of the in-plane wall stays at rest.
    Green,
    /// The outer line O''A'' (the literal reading of the paper's Eq. 7).
    Outer,
}

/// \[A4\] How the corner column `[0,t] x [0,t]` is counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CornerColumn {
    /// In both walls (each wall's trapezoid measured from the outer vertex).
    Both,
    /// Once, in the in-plane wedge; the out-of-plane part starts at the inner face.
    Once,
}

/// \[A5\] Lever of the frictional resultant along a crack.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FrictionLever {
    /// `(n-1) h / 3`: the exact sum of force x slip over the bed joints.
    Joints,
    /// `d / 3`: the resultant of the triangular distribution.
    Third,
}

/// \[A6\] The friction weight `1 - alpha_c/alpha_b` (angles, as printed) or `1 - tan/tan`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CrackRatio {
    Angle,
    Tan,
}

/// Which bed joints carry friction in `Fmax`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FrictionJoints {
    /// The paper's Eq. 9: `n (n+1) / 2` course-loads over the `n` joints.
    Eq9,
    /// Only the joints inside the macroblock: `n (n-1) / 2`.
    Inner,
}

/// Options of the model; each field is one reconstruction switched.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Options {
    pub in_plane_wedge: InPlaneWedge,
    pub corner_column: CornerColumn,
    pub friction_lever: FrictionLever,
    pub crack_ratio: CrackRatio,
    pub friction_joints: FrictionJoints,
    /// Run the continuous Nelder-Mead refinement after the grid search.
    pub refine: bool,
}

impl Options {
    pub fn preset(preset: Preset) -> Self {
        match preset {
            Preset::Paper => Options {
                in_plane_wedge: InPlaneWedge::Green,
                corner_column: CornerColumn::Both,
                friction_lever: FrictionLever::Joints,
                crack_ratio: CrackRatio::Angle,
                friction_joints: FrictionJoints::Eq9,
                refine: true,
            },
            Preset::Literal => Options {
                in_plane_wedge: InPlaneWedge::Outer,
                corner_column: CornerColumn::Once,
                friction_lever: FrictionLever::Third,
                crack_ratio: CrackRatio::Angle,
                friction_joints: FrictionJoints::Eq9,
                refine: true,
            },
        }
    }
}

impl Default for Options {
    fn default() -> Self {
        Self::preset(Preset::Paper)
    }
}
