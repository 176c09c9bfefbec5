//! FMI 2.0 model descriptions, generic: no model lives here. Each FMU crate
//! (`fmu-rocking`, `fmu-shear-frame`) defines its own variables in its
//! `src/description.rs`, one `ModelDescription` from which its value
//! references, the `modelDescription.xml`, the GUID and the documentation
//! come.
//!
//! - [`schema`]: FMI 2.0 model-description data (variables, units,
//!   enumeration types, capabilities, default experiment);
//! - [`common`]: what every FMU of this project declares alike (authors,
//!   licence, the co-simulation capabilities of `fmi2-export`);
//! - [`rigid_body`]: the entries RockingBlock and RoundBody share (the body's
//!   parameters, units, enumerations) and the [`variables!`] table macro;
//! - `xml` (feature `xml`): `modelDescription.xml` through serde + quick-xml,
//!   and the GUID derived from its content (SHA-256 of the XML without it);
//! - `xml3` (feature `xml`): the FMI 3.0 `modelDescription.xml` of the same
//!   table, and [`fmi3`]: the variables 3.0 adds (`time`, event indicators);
//! - `html` (feature `xml`): `documentation/index.html` with the variable table;
//! - `build` (feature `xml`): the three files an FMU crate's `build.rs` writes.
//!
//! An FMU binary uses the table and the value references; its build script
//! includes the same `description.rs` and generates the XML and the GUID, so
//! the library embeds exactly the GUID the archive ships.
//!
//! # Example
//!
//! The table of a gain `y = k u`: one input, one parameter, one output,
//! with value references and 1-based indices as the XML will carry them.
//!
//! ```
//! use model_description::{
//!     common, Causality, DefaultExperiment, Initial, ModelDescription, Type, Variability, Variable,
//! };
//!
//! static VARIABLES: [Variable; 3] = [
//!     Variable { name: "u", vr: 0, description: "input", causality: Causality::Input,
//!                ty: Type::Real { unit: None, display_unit: None, start: Some(0.0), min: None, max: None },
//!                ..Variable::DEFAULT },
//!     Variable { name: "k", vr: 1, description: "gain", causality: Causality::Parameter, variability: Variability::Fixed,
//!                initial: Some(Initial::Exact),
//!                ty: Type::Real { unit: None, display_unit: None, start: Some(2.0), min: None, max: None },
//!                ..Variable::DEFAULT },
//!     Variable { name: "y", vr: 2, description: "output k u", causality: Causality::Output, depends_on: &["u", "k"],
//!                ..Variable::DEFAULT },
//! ];
//! static GAIN: ModelDescription = ModelDescription {
//!     model_name: "Gain",
//!     description: "y = k u",
//!     author: common::AUTHOR,
//!     version: "0.1.0",
//!     copyright: common::COPYRIGHT,
//!     license: common::LICENSE,
//!     generation_tool: common::GENERATION_TOOL,
//!     co_simulation: common::co_simulation("Gain"),
//!     model_exchange: None,
//!     units: &[],
//!     types: &[],
//!     log_categories: &[],
//!     default_experiment: DefaultExperiment { start_time: 0.0, stop_time: 1.0, tolerance: 1e-6, step_size: 1e-3 },
//!     variables: &VARIABLES,
//!     documentation: "",
//!     arrays3: None,
//! };
//!
//! GAIN.check().expect("a consistent description");
//! assert_eq!(GAIN.variable("y").map(|v| v.vr), Some(2));
//! assert_eq!(GAIN.index_of("k"), Some(2));
//! ```

pub mod common;
pub mod fmi3;
pub mod rigid_body;
pub mod schema;

#[cfg(feature = "xml")]
pub mod build;
#[cfg(feature = "xml")]
pub mod html;
#[cfg(feature = "xml")]
pub mod xml;
#[cfg(feature = "xml")]
pub mod xml3;

pub use schema::*;
