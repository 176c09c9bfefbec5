//! The RockingBlock FMU: FMI 2.0 co-simulation of a masonry body rocking on
//! a flexible, crushing interface.
//!
//! Three parts, each knowing only what it must:
//! - the physics, crate [`rocking`] (knows nothing of FMI);
//! - the generic FMI 2.0 layer, crate [`fmi2_export`] (knows nothing of rocking);
//! - this crate: [`slave::RockingSlave`] joins them in one small file, and
//!   [`fmi2_export::export_fmi2!`] exports the C functions.
//!
//! The variables come from [`description`] (one table); `build.rs` compiles
//! the same file and generates the XML and its [`GUID`] from it.

pub mod description;
pub mod params;
pub mod slave;

pub use slave::RockingSlave;

fmi2_export::generated_files!();

fmi2_export::export_fmi2!(crate::slave::RockingSlave);

// FMI 3.0 from the same binary (`target/fmu/fmi3/RockingBlock.fmu`).
fmi3_export::export_fmi3!(crate::slave::RockingSlave);
