//! Random sequences of FMI 2.0 calls on up to three RoundBody instances,
//! through the exported C functions. The interpreter and its checks are
//! `fmi2-fuzz-driver`, RoundBody's part `fmu-round-body/tests/fuzz_driver/mod.rs`,
//! shared with the proptest suite `fmu-round-body/tests/fmi2_fuzz.rs`. Any panic (even one the FMU
//! catches), a failed check, an out-of-bounds access or a leak
//! (AddressSanitizer, LeakSanitizer) is a finding.

#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../fmu-round-body/tests/fuzz_driver/mod.rs"]
mod fuzz_driver;

fuzz_target!(|data: &[u8]| {
    fuzz_driver::run_bytes(data);
});
