//! Random sequences of FMI 3.0 calls on one RoundBody instance
//! (co-simulation with or without event mode and early return; Model
//! Exchange refused while the FMU has none), through the exported C
//! functions. The interpreter and its oracle are
//! `fmu-round-body/tests/fmi3_driver/mod.rs`, shared with the proptest
//! suite `fmu-round-body/tests/fmi3_fuzz.rs`. Any panic, a failed check, an
//! out-of-bounds access or a leak (AddressSanitizer, LeakSanitizer) is a
//! finding.

#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../fmu-round-body/tests/fmi3_driver/mod.rs"]
mod fmi3_driver;

fuzz_target!(|data: &[u8]| {
    fmi3_driver::run_bytes(data);
});
