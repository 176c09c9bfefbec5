//! The interpreter of random FMI 2.0 call sequences, shared by the FMUs'
//! proptest suites (`fmu-rocking/tests/c_api_fuzz.rs`,
//! `fmu-round-body/tests/fmi2_fuzz.rs`) and their libFuzzer targets
//! (`fuzz/fuzz_targets/c_api.rs`, `round_body.rs`). The FMI layer is the
//! same for every model, and so is this driver; each FMU's tests supply what
//! is its own through [`Model`] (its exported functions, value references,
//! inputs, parameters and their validity, the ranges of its outputs).
//!
//! [`decode`] turns arbitrary bytes into a list of [`Op`]s on up to
//! [`Model::SLOTS`] instances; [`Driver::apply`] performs each one through the
//! exported `fmi2*` functions, the way a C host would, and checks after every
//! call:
//!
//! - the status is one of `fmi2OK`, `fmi2Warning`, `fmi2Discard`, `fmi2Error`
//!   (never `fmi2Fatal`, which only a panic in the layer gives, and never
//!   `fmi2Pending`: the FMUs have no asynchronous steps);
//! - no panic happened inside the FMU, not even a caught one (a panic hook
//!   counts them per thread);
//! - a call outside the states where FMI 2.0 allows it returns `fmi2Error`
//!   (the driver follows the state machine while it knows the state);
//! - `fmi2Instantiate` gives an instance exactly for a non-empty name, the
//!   right GUID and an fmuType the model description declares;
//! - `fmi2ExitInitializationMode` succeeds exactly when [`Model::valid`]
//!   says the parameters the driver set (its own copy of the values) make a
//!   valid model, and fails with `fmi2Error` otherwise;
//! - after `fmi2OK` from a getter every value was written; Real outputs,
//!   locals and calculated parameters are finite and within the model's
//!   ranges ([`Model::real_problem`], [`Model::check_reals`],
//!   [`Model::integer_in_range`]), Booleans are 0 or 1;
//! - every non-OK status comes with a logger message of that status; every
//!   message is non-empty UTF-8, names the instance, has a declared category
//!   and no `%` conversion left; OK messages only with debug logging on;
//! - FMU states: a state taken from this instance restores (`fmi2OK`) and
//!   gives back the same outputs bit for bit; serialization of a live state
//!   succeeds with the size the FMU gave; an unmodified buffer deserializes;
//!   serializing the deserialized state gives the same bytes; a shorter
//!   buffer is refused; a corrupted one is refused or restores a state that
//!   serializes back to the same bytes;
//! - with [`Model::STRICT`]: a refused setter, initialization or step names
//!   what it refuses, a refused step leaves the state
//!   ([`Model::STATE_OUTPUTS`]) as it was, and a step discarded because the
//!   run ended reports a last successful time within the step.
//!
//! Only what the standard allows a caller to do is done: pointers passed
//! back are the ones the FMU gave out (instances until they are freed, FMU
//! states until they are freed or their instance is), NULL only where the
//! standard allows it (and NULL instance names), and arrays always have the
//! length passed.

#![allow(non_upper_case_globals)]

use std::cell::Cell;
use std::ffi::{c_int, CStr, CString};
use std::fmt::Debug;
use std::ptr;
use std::sync::Once;

use fmi2_export::bytes;
use fmi2_export::model_description::{BaseType, Causality, LogCategory, Type, Variable};
use fmi2_export::test_host::{Keep, Log, Message};
use fmi2_export::types::*;

mod api;
mod calls;
mod driver;
mod messages;
mod ops;
pub mod rigid_body;
mod states;

pub use api::Fmi2Api;
pub use driver::*;
pub(crate) use messages::*;
pub use messages::{names_a_target, names_one_of};
pub use ops::*;

/// Operations decoded from one input at most.
pub const MAX_OPS: usize = 160;
/// Serialized buffers kept for later deserialization.
pub(crate) const POOL: usize = 6;
/// FMU states kept per instance (the oldest is freed beyond).
pub(crate) const MAX_STATES: usize = 6;
/// Written into output arrays before a getter: still there after fmi2OK
/// means a value was not written.
pub(crate) const SENTINEL: u64 = 0x7ff8_dead_beef_f00d;

/// What the driver needs to know of one FMU: its C API and its model. The
/// defaults are those of a model with nothing more to check.
pub trait Model: Sized + 'static {
    /// The FMU's exported functions ([`fmi2_api!`]).
    const API: Fmi2Api;
    /// The FMU's GUID.
    const GUID: &'static str;
    /// Its variables (the model description's).
    const VARIABLES: &'static [Variable];
    /// Its log categories.
    const LOG_CATEGORIES: &'static [LogCategory];
    /// Instances the driver juggles at once.
    const SLOTS: usize;
    /// Whether the model description declares Model Exchange (the driver
    /// then expects `fmi2ModelExchange` instances to be made).
    const MODEL_EXCHANGE: bool;
    /// Continuous states (the length of [`Op::Me`]'s `x`).
    const STATES: usize;
    /// Event indicators (0 without Model Exchange).
    const EVENT_INDICATORS: usize;
    /// The array length most Model Exchange calls are given.
    const ME_LENGTH: usize;
    /// The Real inputs (whose derivatives the driver follows).
    const INPUTS: &'static [u32];
    /// The outputs of the state alone, which a refused step must leave
    /// ([`Model::STRICT`]).
    const STATE_OUTPUTS: &'static [u32] = &[];
    /// What a step refused with `fmi2Error` must name ([`Model::STRICT`]).
    const STEP_REFUSAL_NAMES: &'static [&'static str] = &[];
    /// The stricter checks (see the crate's documentation).
    const STRICT: bool = false;
    /// The physics parameters (for messages).
    type Params: Debug;

    /// The physics parameters of the stored values, mapped independently of
    /// the FMU's binding; `None` for a code that is no item of its
    /// enumeration.
    fn params(stored: &Stored) -> Option<Self::Params>;
    /// Whether the stored values make a model the FMU must accept at
    /// fmi2ExitInitializationMode.
    fn valid(stored: &Stored) -> bool;
    /// [`valid`](Self::valid) for an instance of fmuType
    /// fmi2ModelExchange (`model_exchange`) or co-simulation, where an FMU
    /// accepts less in one of them.
    fn valid_for(stored: &Stored, _model_exchange: bool) -> bool {
        Self::valid(stored)
    }
    /// Operation 40: an input set to a value.
    fn set_input(b: &mut Bytes, slot: u8) -> Op;
    /// Operation 41: an input's derivative set.
    fn set_input_derivative(b: &mut Bytes, slot: u8) -> Op;
    /// What is wrong with the value `x` of the Real `r` read with fmi2OK.
    fn real_problem(_r: u32, _x: f64) -> Option<String> {
        None
    }
    /// Checks between the Reals `r` read together (`x`), panicking.
    fn check_reals(_r: &[u32], _x: &[f64]) {}
    /// Whether the Integer `r`'s value `x` is in its range (`None`: any
    /// value, but one must be written).
    fn integer_in_range(_r: u32, _x: c_int) -> Option<bool> {
        None
    }
    /// Checks between the Integers `r` read together (`x`), panicking.
    fn check_integers(_r: &[u32], _x: &[c_int]) {}
    /// Whether to skip the step on slot `k` (counted by the model in
    /// [`Stats::steps_skipped`]); `forged`: the instance was restored from
    /// a mutated buffer.
    fn skip_step(
        _d: &mut Driver<Self>,
        _k: u8,
        _h: f64,
        _machine: Option<Machine>,
        _forged: bool,
    ) -> bool {
        false
    }
    /// Before a step from `StepComplete` whose state `before` the driver
    /// read ([`Model::STRICT`]): whether a refusal with
    /// [`Model::known_refusal`]'s message is a known finding to let pass.
    fn known_finding(_d: &mut Driver<Self>, _k: u8, _t: f64, _h: f64) -> bool {
        false
    }
    /// Whether the messages of a refused step are the known finding's.
    fn known_refusal(_recent: &[Message]) -> bool {
        false
    }
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

/// Decodes `data` and runs it: the fuzz targets' and the proptests' entry.
pub fn run_bytes<M: Model>(data: &[u8]) -> Stats {
    Driver::<M>::run(&decode::<M>(data))
}

/// For every file of `dir` (sorted by name): its name, its decoded
/// operations and the driver's final statistics, a line each. Two dumps
/// taken before and after a change of the driver are identical when the
/// change keeps its behaviour on those inputs.
pub fn dump_corpus<M: Model>(dir: &std::path::Path) -> String {
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a corpus entry").path())
        .collect();
    paths.sort();
    let mut text = String::new();
    for path in paths {
        let data = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let ops = decode::<M>(&data);
        let mut d = Driver::<M>::new();
        for op in &ops {
            d.apply(op);
        }
        let name = path.file_name().expect("a file name").to_string_lossy();
        text += &format!("{name}\n{ops:?}\n{:?}\n", d.finish());
    }
    text
}
