//! The host of the C-API tests of `fmu-rocking/tests/` (and of
//! `examples/c_api_loop.rs` and `benches/memory.rs`, which include it with
//! `#[path]`): the generic in-process host of `fmi2-export` (feature
//! `test-host`) for the RockingBlock model, and the rocking cases and runs
//! of [`cases`].
//!
//! Use from a test file with `mod host;` and `use host::*;`.

#![allow(dead_code, unused_imports)] // each test file uses a different part

mod cases;

pub use cases::*;
pub use fmi2_export::test_host::{Keep, Log, Message, Options};
pub use fmi2_export::types::*;
pub use fmu_rocking::description::{enums, vr, ROCKING_BLOCK};

/// One RockingBlock instance with its own log; freed on drop.
pub type Host = fmi2_export::test_host::Host<fmu_rocking::RockingSlave>;

/// The value reference of a variable by its public name (panics if unknown).
pub fn vr_of(name: &str) -> u32 {
    fmi2_export::test_host::vr_of::<fmu_rocking::RockingSlave>(name)
}

/// `fmi2Instantiate` with no callbacks (see `test_host::bare_instance`).
pub fn bare_instance(name: Option<&str>, fmu_type: fmi2Type, guid: Option<&str>) -> fmi2Component {
    fmi2_export::test_host::bare_instance::<fmu_rocking::RockingSlave>(name, fmu_type, guid)
}
