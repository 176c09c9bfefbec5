//! The ShearFrame FMU: FMI 2.0 co-simulation of a linear n-storey shear
//! building, the structural side of a coupled run with RockingBlock.
//!
//! Three parts, each knowing only what it must:
//! - the physics, crate [`shear_frame`] (knows nothing of FMI);
//! - the generic FMI 2.0 layer, crate [`fmi2_export`];
//! - this crate: [`slave::ShearFrameSlave`] joins them, and
//!   [`fmi2_export::export_fmi2!`] exports the C functions.
//!
//! The variables come from [`description`] (one table); `build.rs` compiles
//! the same file and generates the XML and its [`GUID`] from it.

pub mod description;
pub mod slave;

#[cfg(test)]
mod tests;

pub use slave::ShearFrameSlave;

fmi2_export::generated_files!();

fmi2_export::export_fmi2!(crate::slave::ShearFrameSlave);

// FMI 3.0 co-simulation from the same binary (`target/fmu/fmi3/ShearFrame.fmu`).
fmi3_export::export_fmi3!(crate::slave::ShearFrameSlave);
