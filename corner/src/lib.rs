//! Limit analysis of a dry-joint masonry corner under a horizontal load of any
//! orientation, and the collapsing macroblock as a rocking body.
//!
//! The model is the kinematic (upper-bound) limit analysis of Colombo, Savalle,
//! Mehrotra, Funari and Lourenço (2022), re-derived where the paper's text is
//! incomplete; `docs/corner.md` states it in full, with every reconstruction
//! (\[A1\]..\[A7\]) and its effect. Two single-leaf running-bond walls, WX along +x
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
//!
//! # Example
//!
//! The paper's specimen loaded along +y (`alpha = pi/2`): the combined
//! multiplier `cos^2 lambda_X + sin^2 lambda_Y` is then `lambda_Y` alone.
//!
//! ```
//! use corner::{corner_multiplier, CornerModel};
//!
//! let model = CornerModel::paper(1, 0.3).expect("the paper's specimen");
//! let result = corner_multiplier(&model, std::f64::consts::FRAC_PI_2).expect("an orientation in 0..pi/2");
//! let grid = &result.grid; // the joint-aligned optimum
//! assert!(grid.lambda_alpha > 0.0);
//! assert!((grid.lambda_alpha - grid.lambda_y).abs() <= 1e-12 * grid.lambda_y);
//! ```

mod body;
mod error;
mod geometry;
mod model;
mod options;
mod refine;
mod search;
mod specimen;
mod virtual_work;

pub use body::{body_direction, rocking_body, BodyKind, ParamValue, RockingBody};
pub use error::CornerError;
pub use geometry::{Direction, Geometry, WallPart};
pub use model::{CornerModel, Mechanism};
pub use options::{
    CornerColumn, CrackRatio, FrictionJoints, FrictionLever, InPlaneWedge, Options, Preset,
};
pub use search::{corner_multiplier, CornerResult};
pub use specimen::{Specimen, G};
pub use virtual_work::{torsion_lever, Evaluation, WorkTerms};
