//! Limit analysis of a dry-joint masonry corner under a horizontal load of any
//! orientation, and the collapsing macroblock as a rocking body.
//!
//! The model is the kinematic (upper-bound) limit analysis of Colombo, Savalle,
//! Mehrotra, Funari and Lourenço (2022), re-derived where the paper's text is
//! incomplete; `docs/corner.md` states it in full, with every reconstruction
//! ([A1]..[A7]) and its effect. Two single-leaf running-bond walls, WX along +x
//! and WY along +y, meet at a right angle at the origin (outer vertex, table
//! level). A macroblock is described by seven lengths ([`Geometry`]); the load
//! multiplier of one load direction comes from the virtual-work balance
//! `lambda = (S + D) / (O + Lambda)` and the orientation `alpha` combines the two
//! directions as `cos^2 lambda_X + sin^2 lambda_Y` over a shared geometry.
//!
//! The search is exhaustive over joint-aligned geometries (every length a
//! multiple of the half block `v`, the hinge on a bed joint), exact and
//! deterministic, and is then refined by a continuous Nelder-Mead (argmin) from
//! the grid optimum, as the paper's optimiser did.
//!
//! No FMI here: [`RockingBody::fmu_parameters`] only names the RockingBlock FMU
//! parameters the body maps to.

use std::f64::consts::FRAC_PI_2;
use std::fmt;

use serde::{Deserialize, Serialize};

mod refine;

/// Gravitational acceleration used by the specimen (m/s2), as in the paper.
pub const G: f64 = 9.81;

/// An input the model refuses, named.
#[derive(Debug, Clone, PartialEq)]
pub struct CornerError {
    /// The offending parameter, by the name the interfaces use (`t`, `mu`, `k`, ...).
    pub parameter: &'static str,
    /// What is wrong with it.
    pub reason: String,
}

impl fmt::Display for CornerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid {}: {}", self.parameter, self.reason)
    }
}

impl std::error::Error for CornerError {}

fn err(parameter: &'static str, reason: impl Into<String>) -> CornerError {
    CornerError {
        parameter,
        reason: reason.into(),
    }
}

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

    /// `tan(alpha_b) = v/h`: the natural stepped crack of running bond, one half block per course [A2].
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

/// Named option sets (`docs/corner.md`, "Presets").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// The readings that reproduce the paper's Table 5 (default).
    Paper,
    /// The literal reading of the printed equations.
    Literal,
}

/// [A3] Which line bounds the in-plane wedge in the flexural mechanism (m = 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InPlaneWedge {
    /// The inner ("green") line O''B'': the red part of the in-plane wall stays at rest.
    Green,
    /// The outer line O''A'' (the literal reading of the paper's Eq. 7).
    Outer,
}

/// [A4] How the corner column `[0,t] x [0,t]` is counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CornerColumn {
    /// In both walls (each wall's trapezoid measured from the outer vertex).
    Both,
    /// Once, in the in-plane wedge; the out-of-plane part starts at the inner face.
    Once,
}

/// [A5] Lever of the frictional resultant along a crack.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FrictionLever {
    /// `(n-1) h / 3`: the exact sum of force x slip over the bed joints.
    Joints,
    /// `d / 3`: the resultant of the triangular distribution.
    Third,
}

/// [A6] The friction weight `1 - alpha_c/alpha_b` (angles, as printed) or `1 - tan/tan`.
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

/// The mechanism family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Mechanism {
    /// m = 0: pure rocking-sliding; each wall moves as one block.
    RockingSliding,
    /// m = 1: horizontal flexure; the out-of-plane wall splits into a green part and a red triangle.
    Flexural,
}

impl Mechanism {
    /// From the paper's flag m (0 or 1).
    pub fn from_m(m: u32) -> Result<Self, CornerError> {
        match m {
            0 => Ok(Mechanism::RockingSliding),
            1 => Ok(Mechanism::Flexural),
            _ => Err(err(
                "m",
                format!("must be 0 (rocking-sliding) or 1 (flexural), got {m}"),
            )),
        }
    }

    pub fn m(self) -> u32 {
        match self {
            Mechanism::RockingSliding => 0,
            Mechanism::Flexural => 1,
        }
    }
}

/// A validated problem: the corner, the mechanism, the torsion factor and the options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerModel {
    pub specimen: Specimen,
    pub mechanism: Mechanism,
    /// Reduction of the torsional contact at uplifted hinges, in [0, 1] (the paper: 0.3 to 0.6).
    pub k: f64,
    pub options: Options,
}

impl CornerModel {
    pub fn new(specimen: Specimen, m: u32, k: f64, options: Options) -> Result<Self, CornerError> {
        specimen.validate()?;
        let mechanism = Mechanism::from_m(m)?;
        // Each wall must hold at least one joint-aligned part: a base of whole half blocks
        // reaching t, plus one half block of red width under flexure.
        let base_units = (specimen.t / specimen.v() - 1e-9).ceil().max(1.0);
        let least = (base_units + f64::from(mechanism.m())) * specimen.v();
        for (name, length) in [
            ("blocks_x", specimen.length_x()),
            ("blocks_y", specimen.length_y()),
        ] {
            if length < least - 1e-12 {
                return Err(err(
                    name,
                    format!(
                        "the wall ({length} m) cannot hold a macroblock of m = {}: it needs {least} m",
                        mechanism.m()
                    ),
                ));
            }
        }
        if !(k.is_finite() && (0.0..=1.0).contains(&k)) {
            return Err(err("k", format!("must be in [0, 1], got {k}")));
        }
        Ok(CornerModel {
            specimen,
            mechanism,
            k,
            options,
        })
    }

    /// The paper's specimen and preset with the given m and k.
    pub fn paper(m: u32, k: f64) -> Result<Self, CornerError> {
        Self::new(Specimen::paper(), m, k, Options::default())
    }
}

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
struct InPlane {
    weight: f64,
    stabilising: f64,
    overturning: f64,
    friction: f64,
}

#[derive(Debug, Clone, Copy, Default)]
struct OutOfPlane {
    weight_green: f64,
    weight_red: f64,
    stabilising: f64,
    overturning: f64,
    friction: f64,
    torsion: f64,
    torsion_lambda: f64,
    /// Fmax(n) of the red block's hinges (N), for the clamp of the torsion brackets.
    fmax: f64,
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
    fn wedge_top(&self, w: WallPart) -> f64 {
        match (self.mechanism, self.options.in_plane_wedge) {
            (Mechanism::Flexural, InPlaneWedge::Green) => w.green,
            _ => w.green + w.red,
        }
    }

    fn in_plane(&self, w: WallPart, d: f64) -> InPlane {
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
    fn oop_start(&self) -> f64 {
        match self.options.corner_column {
            CornerColumn::Both => 0.0,
            CornerColumn::Once => self.specimen.t,
        }
    }

    fn out_of_plane(&self, w: WallPart, d: f64) -> OutOfPlane {
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
        check_alpha(alpha)?;
        x.check(self, 1e-9)?;
        Ok(self.evaluate_unchecked(x, alpha))
    }

    fn evaluate_unchecked(&self, x: &Geometry, alpha: f64) -> Evaluation {
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

fn check_alpha(alpha: f64) -> Result<(), CornerError> {
    if !(alpha.is_finite() && (-1e-12..=FRAC_PI_2 + 1e-12).contains(&alpha)) {
        return Err(err(
            "alpha",
            format!("must be in [0, pi/2] rad, got {alpha}"),
        ));
    }
    Ok(())
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

/// Result of [`corner_multiplier`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CornerResult {
    /// Load orientation from the x axis (rad).
    pub alpha: f64,
    /// Mechanism flag (0 rocking-sliding, 1 flexural).
    pub m: u32,
    pub k: f64,
    /// The joint-aligned optimum (exact on the grid): the reported multiplier.
    #[serde(flatten)]
    pub grid: Evaluation,
    /// Admissible joint-aligned geometries (the search is exhaustive over these).
    pub candidates: u64,
    /// Of those, the ones evaluated pair by pair; the rest were excluded by a lower bound.
    pub evaluated: u64,
    /// The continuous Nelder-Mead refinement from the grid optimum, when asked for.
    pub refined: Option<Evaluation>,
}

/// The admissible (green, red, base) triples of one wall, in half blocks, for n courses.
fn wall_triples(
    n: u32,
    base_min: u32,
    len_units: u32,
    red_min: u32,
    step_units: u32,
) -> Vec<(u32, u32, u32)> {
    let mut out = Vec::new();
    for base in base_min..=len_units {
        for green in base..=len_units {
            for red in red_min..=(len_units - green) {
                if green + red - base <= step_units.saturating_mul(n) {
                    out.push((green, red, base));
                }
            }
        }
    }
    out
}

/// Minimum of lambda_alpha over the joint-aligned geometries, refined by Nelder-Mead when
/// `options.refine`; `alpha` in rad from the x axis, in [0, pi/2].
pub fn corner_multiplier(model: &CornerModel, alpha: f64) -> Result<CornerResult, CornerError> {
    check_alpha(alpha)?;
    let (grid, counts) = grid_search(model, alpha);
    let refined = if model.options.refine {
        Some(refine::nelder_mead(model, &grid.geometry, alpha))
    } else {
        None
    };
    Ok(CornerResult {
        alpha,
        m: model.mechanism.m(),
        k: model.k,
        grid,
        candidates: counts.candidates,
        evaluated: counts.evaluated,
        refined,
    })
}

/// Exhaustive search over joint-aligned geometries: the hinge on a bed joint `Z1 = j h`, every
/// length a multiple of v, cracks no flatter than the running-bond step. Each wall's triples
/// are reduced once per hinge level to four partial sums (in-plane and out-of-plane numerator
/// and denominator), so a candidate pair costs two divisions.
fn grid_search(model: &CornerModel, alpha: f64) -> (Evaluation, Counts) {
    let sp = &model.specimen;
    let v = sp.v();
    let (s, c) = alpha.sin_cos();
    let (c2, s2) = (c * c, s * s);
    // Smallest number of half blocks that reaches the thickness t (X3, Y3 >= t).
    let base_min = ((sp.t / v) - 1e-9).ceil().max(1.0) as u32;
    let red_min = match model.mechanism {
        Mechanism::Flexural => 1,
        Mechanism::RockingSliding => 0,
    };
    // The crack constraint extent <= d tan(alpha_b) = n v: one half block per course.
    let step_units = 1;
    let mut best: Option<(f64, Geometry)> = None;
    let mut candidates = 0u64;
    let mut evaluated = 0u64;
    for j in 1..sp.courses {
        let z1 = f64::from(j) * sp.h;
        let d = sp.height() - z1;
        let n = sp.courses - j;
        let tx = wall_triples(n, base_min, 2 * sp.blocks_x, red_min, step_units);
        let ty = wall_triples(n, base_min, 2 * sp.blocks_y, red_min, step_units);
        let part = |t: &(u32, u32, u32)| WallPart {
            green: f64::from(t.0) * v,
            red: f64::from(t.1) * v,
            base: f64::from(t.2) * v,
        };
        let px: Vec<(InPlane, OutOfPlane)> = tx
            .iter()
            .map(|t| (model.in_plane(part(t), d), model.out_of_plane(part(t), d)))
            .collect();
        let py: Vec<(InPlane, OutOfPlane)> = ty
            .iter()
            .map(|t| (model.in_plane(part(t), d), model.out_of_plane(part(t), d)))
            .collect();
        // Partial sums: numerator and denominator shares of each wall in each role.
        let sums = |p: &[(InPlane, OutOfPlane)]| -> Vec<[f64; 6]> {
            p.iter()
                .map(|(ip, oop)| {
                    [
                        ip.stabilising + ip.friction,
                        ip.overturning,
                        oop.stabilising + oop.friction + oop.torsion,
                        oop.overturning + oop.torsion_lambda,
                        oop.weight_red,
                        oop.fmax,
                    ]
                })
                .collect()
        };
        let sx = sums(&px);
        let sy = sums(&py);
        candidates += (sx.len() * sy.len()) as u64;
        // Branch and bound. For a WX triple and a set of WY triples, the numerators are
        // smallest and the denominators largest at the set's extremes, so no pair can go below
        //   c2 (a0 + min b2)/(a1 + max b3) + s2 (min b0 + a2)/(max b1 + a3).
        // The formula without the torsion clamp is itself a lower bound (the clamp only raises
        // lambda), and correctly rounded + and / are monotone, so the bound holds in floating
        // point. Rows (WX triples) are visited by increasing bound over all of WY, the WY list in
        // chunks of neighbours (similar triples) with their own bounds; ties are broken by the
        // listing order, so the result is the one the plain double loop gives.
        let extremes = |ys: &[[f64; 6]]| {
            ys.iter()
                .fold([f64::INFINITY, 0.0, f64::INFINITY, 0.0], |e, b| {
                    [
                        e[0].min(b[0]),
                        e[1].max(b[1]),
                        e[2].min(b[2]),
                        e[3].max(b[3]),
                    ]
                })
        };
        let bound = |a: &[f64; 6], e: &[f64; 4]| {
            c2 * ((a[0] + e[2]) / (a[1] + e[3])) + s2 * ((e[0] + a[2]) / (e[1] + a[3]))
        };
        const CHUNK: usize = 16;
        let chunks: Vec<[f64; 4]> = sy.chunks(CHUNK).map(extremes).collect();
        let all = extremes(&sy);
        let mut rows: Vec<(f64, usize)> = sx
            .iter()
            .enumerate()
            .map(|(i, a)| (bound(a, &all), i))
            .collect();
        rows.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1.cmp(&q.1)));
        let global = best.map_or(f64::INFINITY, |b| b.0);
        // Can a candidate of lower bound `lb` still win? Within the level a tie may win on
        // order; against an earlier level it must be strictly lower.
        let open = |lb: f64, level: f64| lb <= level && lb < global;
        let mut level_best = (f64::INFINITY, usize::MAX, usize::MAX);
        for &(row_bound, ix) in &rows {
            if !open(row_bound, level_best.0) {
                break;
            }
            let a = &sx[ix];
            for (ci, e) in chunks.iter().enumerate() {
                if !open(bound(a, e), level_best.0) {
                    continue;
                }
                let start = ci * CHUNK;
                let end = (start + CHUNK).min(sy.len());
                evaluated += (end - start) as u64;
                for (iy, b) in sy.iter().enumerate().take(end).skip(start) {
                    let mut lx = (a[0] + b[2]) / (a[1] + b[3]);
                    let mut ly = (b[0] + a[2]) / (b[1] + a[3]);
                    // The torsion clamp [A7] is rare: redo that direction exactly when it binds.
                    if 0.5 * lx * b[4] > b[5] || 0.5 * ly * a[4] > a[5] {
                        let x = geometry_of(&tx[ix], &ty[iy], v, z1);
                        lx = model.direction_terms(&x, Direction::X).lambda;
                        ly = model.direction_terms(&x, Direction::Y).lambda;
                    }
                    let l = c2 * lx + s2 * ly;
                    if l < level_best.0
                        || (l == level_best.0 && (ix, iy) < (level_best.1, level_best.2))
                    {
                        level_best = (l, ix, iy);
                    }
                }
            }
        }
        if level_best.0 < best.map_or(f64::INFINITY, |b| b.0) {
            let x = geometry_of(&tx[level_best.1], &ty[level_best.2], v, z1);
            best = Some((level_best.0, x));
        }
    }
    let (_, x) = best.expect("a course has at least one admissible geometry");
    (
        model.evaluate_unchecked(&x, alpha),
        Counts {
            candidates,
            evaluated,
        },
    )
}

/// Candidate geometries of a grid search: all admissible ones, and those evaluated after the
/// row bound.
#[derive(Debug, Clone, Copy)]
struct Counts {
    candidates: u64,
    evaluated: u64,
}

fn geometry_of(tx: &(u32, u32, u32), ty: &(u32, u32, u32), v: f64, z1: f64) -> Geometry {
    Geometry {
        x1: f64::from(tx.0) * v,
        x2: f64::from(tx.1) * v,
        x3: f64::from(tx.2) * v,
        y2: f64::from(ty.0) * v,
        y1: f64::from(ty.1) * v,
        y3: f64::from(ty.2) * v,
        z1,
    }
}

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
