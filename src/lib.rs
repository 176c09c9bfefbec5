//! Rocking of a rigid body on a flexible, no-tension interface that can crush.
//!
//! This crate is the physics of the model of `docs/model.md` and knows nothing of FMI:
//!
//! - [`shape`]: base sections, their width function `w(x)` and closed-form
//!   cumulative moments `S0, S1, S2` (docs/model.md §1, §2);
//! - [`interface`]: the interface law and the contact solve that gives the
//!   reaction position `af(theta)` and its derivative (docs/model.md §2);
//! - [`body`]: mass models and the derived body values `R0, alpha, IO, eta`
//!   (docs/model.md §1, §3);
//! - [`model`]: the full parameter set, its validation, and the assembled
//!   model with `hW, hg, I(phi)`, thresholds and overturning rotation
//!   (docs/model.md §2, §3, §5);
//! - [`dynamics`]: equations of motion, impacts, rest and overturning, and the
//!   integrator (docs/model.md §3).
//!
//! Sign convention: `theta > 0` rotates the body about its `+x` toe; every
//! function of the rotation that is even in theta takes `phi = |theta|`.
//!
//! # Example
//!
//! The default body (a 0.5 m x 1 m x 2.5 m masonry prism on an elastic
//! bed): it overturns past `thetaOv`, which the bed's flexibility brings
//! below the rigid body's slenderness `alpha`; short of it the restoring
//! moment `MR = W hW` holds it back.
//!
//! ```
//! use rocking::Params;
//!
//! let model = Params::default().build().expect("the defaults are valid");
//! let alpha = model.body.alpha; // rad, atan(B/H) of the prism
//! assert!((alpha - (0.5f64 / 2.5).atan()).abs() < 1e-12);
//! assert!(model.theta_ov > 0.0 && model.theta_ov <= alpha);
//! let (mr, _dmr_dphi) = model.restoring_moment(0.5 * model.theta_ov); // N m, N m/rad
//! assert!(mr > 0.0);
//! ```

pub mod body;
pub mod dynamics;
pub mod interface;
pub mod model;
pub mod shape;
pub mod spatial;
mod trig;

pub use body::{Body, MassModel};
pub use interface::{Contact, ContactTable, Interface, Law, Regime};
pub use model::{Formulation, Model, ParamError, Params, Restitution, Restraint, RestraintKind};
pub use shape::Shape;
