//! The RoundBody FMU: FMI 2.0 and 3.0 co-simulation and Model Exchange of a round body (a
//! solid or hollow circle's base) rocking, wobbling and rolling in space on
//! a rigid or flexible, crushing bed under both horizontal components of the ground motion and
//! the vertical one.
//!
//! Three parts, each knowing only what it must:
//! - the physics, module [`rocking::spatial`] (knows nothing of FMI);
//! - the generic FMI 2.0 and 3.0 layers, crates [`fmi2_export`] and
//!   [`fmi3_export`];
//! - this crate: [`slave::RoundBodySlave`] joins them, and the export
//!   macros write the C functions.
//!
//! The variables come from [`description`] (one table); `build.rs` compiles
//! the same file and generates the XML and its [`GUID`] from it.

pub mod description;
pub mod slave;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_flexible;
#[cfg(test)]
mod tests_me;

pub use slave::RoundBodySlave;

fmi2_export::generated_files!();

fmi2_export::export_fmi2!(crate::slave::RoundBodySlave);

// FMI 3.0 co-simulation from the same binary (`target/fmu/fmi3/RoundBody.fmu`).
fmi3_export::export_fmi3!(crate::slave::RoundBodySlave);
