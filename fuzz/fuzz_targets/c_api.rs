//! Random sequences of FMI 2.0 calls on up to four RockingBlock instances,
//! through the exported C functions. The interpreter and its invariants are
//! `fmi2-fuzz-driver`, RockingBlock's part `fmu-rocking/tests/fuzz_driver/mod.rs`,
//! shared with the proptest suite `fmu-rocking/tests/c_api_fuzz.rs`. Any panic (even one the FMU catches),
//! a failed invariant, an out-of-bounds access or a leak (AddressSanitizer,
//! LeakSanitizer) is a finding.

#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../fmu-rocking/tests/fuzz_driver/mod.rs"]
mod fuzz_driver;

fuzz_target!(|data: &[u8]| {
    fuzz_driver::run_bytes(data);
});
