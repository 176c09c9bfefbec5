//! The one definition of an FMU's variables, and what is generated from it.
//!
//! - [`schema`]: FMI 2.0 model-description data (generic: variables, units,
//!   enumeration types, capabilities, default experiment);
//! - [`rocking_block`]: the RockingBlock FMU's description (docs/model.md §5) and
//!   its value references [`rocking_block::vr`];
//! - [`shear_frame`]: the ShearFrame FMU's description (an n-storey shear
//!   building) and its value references [`shear_frame::vr`];
//! - `xml` (feature `xml`): `modelDescription.xml` through serde + quick-xml,
//!   and the GUID derived from its content (SHA-256 of the XML without it);
//! - `html` (feature `xml`): `documentation/index.html` with the variable table.
//!
//! The FMU binary uses the table and the value references; its build script
//! generates the XML and the GUID, so the library embeds exactly the GUID the
//! archive ships.

pub mod common;
pub mod rocking_block;
pub mod schema;
pub mod shear_frame;

#[cfg(feature = "xml")]
pub mod html;
#[cfg(feature = "xml")]
pub mod xml;

pub use schema::*;
