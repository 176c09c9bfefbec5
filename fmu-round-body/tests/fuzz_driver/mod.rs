//! The interpreter of random FMI 2.0 call sequences on RoundBody.fmu,
//! shared by the proptest suite (`tests/fmi2_fuzz.rs`) and the libFuzzer
//! target (`fuzz/fuzz_targets/round_body.rs`, which includes this file with
//! `#[path]`). RockingBlock's driver (`fmu-rocking/tests/fuzz_driver`) made
//! for this model: its inputs `agx`, `agy`, `av`, its parameters and its
//! outputs.
//!
//! [`decode`] turns arbitrary bytes into a list of [`Op`]s on up to
//! [`SLOTS`] instances; [`Driver::apply`] performs each one through the
//! exported `fmi2*` functions, the way a C host would, and checks after every
//! call:
//!
//! - the status is one of `fmi2OK`, `fmi2Warning`, `fmi2Discard`, `fmi2Error`
//!   (never `fmi2Fatal`, which only a panic in the layer gives, and never
//!   `fmi2Pending`: this FMU has no asynchronous steps);
//! - no panic happened inside the FMU, not even a caught one (a panic hook
//!   counts them per thread);
//! - a call outside the states where FMI 2.0 allows it returns `fmi2Error`
//!   (the driver follows the state machine while it knows the state);
//! - `fmi2Instantiate` gives an instance exactly for a non-empty name, the
//!   right GUID and an fmuType the model description declares (co-simulation;
//!   Model Exchange once `<ModelExchange>` is there);
//! - `fmi2ExitInitializationMode` succeeds exactly when the parameters the
//!   driver set make a valid round body (docs/round-body.md, "Bad input":
//!   `rocking::Params::build` of the driver's own copy of the values, a
//!   round shape, `IcAxial > 0` for the lumped model, `maxSteps >= 1`,
//!   finite `psi0` and initial angular velocities) and fails with
//!   `fmi2Error` otherwise, the message naming a parameter (`name = value`);
//! - a step refused with `fmi2Error` names an input or the communication
//!   point in its message and leaves the state (theta .. yG) as it was;
//! - after `fmi2OK` from a getter every value was written; Real outputs and
//!   calculated parameters are finite (`frictionDemand` at most 1e60, which
//!   it is where `Fz <= 0`), `theta` in [0, pi/2] equals
//!   `asin(sqrt(ex^2 + ey^2))`, `psi` in (-pi, pi], `regime` is rest (1) or
//!   rocking (2), `impacts` >= 0, Booleans are 0 or 1;
//! - every non-OK status comes with a logger message of that status; every
//!   message is non-empty UTF-8, names the instance, has a declared category
//!   and no `%` conversion left; OK messages only with debug logging on;
//! - FMU states: a state taken from this instance restores (`fmi2OK`) and
//!   gives back the same outputs bit for bit; serialization of a live state
//!   succeeds with the size the FMU gave; an unmodified buffer deserializes;
//!   serializing the deserialized state gives the same bytes; a shorter
//!   buffer is refused; a corrupted one is refused or restores a state that
//!   serializes back to the same bytes.
//!
//! Only what the standard allows a caller to do is done: pointers passed
//! back are the ones the FMU gave out (instances until they are freed, FMU
//! states until they are freed or their instance is), NULL only where the
//! standard allows it (and NULL instance names), and arrays always have the
//! length passed.

#![allow(dead_code, non_upper_case_globals)]

use std::cell::Cell;
use std::ffi::{c_int, CStr, CString};
use std::ptr;
use std::sync::Once;

use fmi2_export::bytes;
use fmi2_export::model_description::{BaseType, Causality, Type, Variable};
use fmi2_export::test_host::{Keep, Log, Message};
use fmi2_export::types::*;
use fmu_round_body as fmu;
use fmu_round_body::description::{enums, vr, LOG_CATEGORIES, ROUND_BODY, VARIABLES};
use rocking::model::{LawKind, MassKind, ShapeKind};
use rocking::{Params, Restitution};

mod calls;
mod driver;
mod messages;
mod ops;
mod states;

pub use driver::*;
pub(crate) use messages::*;
pub use ops::*;

/// Instances the driver juggles at once.
pub const SLOTS: usize = 3;
/// Operations decoded from one input at most.
pub const MAX_OPS: usize = 160;
/// Serialized buffers kept for later deserialization.
pub(crate) const POOL: usize = 6;
/// FMU states kept per instance (the oldest is freed beyond).
pub(crate) const MAX_STATES: usize = 6;
/// Written into output arrays before a getter: still there after fmi2OK
/// means a value was not written.
pub(crate) const SENTINEL: u64 = 0x7ff8_dead_beef_f00d;
/// What stands for `+inf` at the boundary (docs/round-body.md): the most
/// `frictionDemand` may be.
pub const UNBOUNDED: f64 = 1e60;

/// Whether the model description declares Model Exchange (the driver then
/// expects `fmi2ModelExchange` instances to be made).
pub fn model_exchange() -> bool {
    ROUND_BODY.model_exchange.is_some()
}

// ----- panic counting ------------------------------------------------------

thread_local! {
    static PANICS: Cell<u64> = const { Cell::new(0) };
}

/// Counts every panic of this thread (caught or not), then calls the hook
/// installed before (libFuzzer's aborts; the default one prints).
pub fn install_panic_counter() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            PANICS.with(|p| p.set(p.get() + 1));
            previous(info);
        }));
    });
}

pub(crate) fn panics() -> u64 {
    PANICS.with(|p| p.get())
}

/// Decodes `data` and runs it: the fuzz target's and the proptests' entry.
pub fn run_bytes(data: &[u8]) -> Stats {
    Driver::run(&decode(data))
}
