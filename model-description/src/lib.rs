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
//! - `xml` (feature `xml`): `modelDescription.xml` through serde + quick-xml,
//!   and the GUID derived from its content (SHA-256 of the XML without it);
//! - `html` (feature `xml`): `documentation/index.html` with the variable table;
//! - `build` (feature `xml`): the three files an FMU crate's `build.rs` writes.
//!
//! An FMU binary uses the table and the value references; its build script
//! includes the same `description.rs` and generates the XML and the GUID, so
//! the library embeds exactly the GUID the archive ships.

pub mod common;
pub mod schema;

#[cfg(feature = "xml")]
pub mod build;
#[cfg(feature = "xml")]
pub mod html;
#[cfg(feature = "xml")]
pub mod xml;

pub use schema::*;
