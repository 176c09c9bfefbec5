#!/usr/bin/env bash
# Fuzzes the FMU's C API with libFuzzer: `tools/fuzz.sh [seconds [target]]`
# (default 600 s, target c_api). Not part of tools/test.sh; the same
# interpreters run as proptests in `cargo test`.
#
# Targets: c_api (FMI 2.0, fmi2-fuzz-driver with fmu-rocking/tests/fuzz_driver, proptests in
# fmu-rocking/tests/c_api_fuzz.rs) and c_api3 (FMI 3.0: co-simulation with
# and without event mode and early return, Model Exchange, der(ag)/der(av),
# bad sizes, NULL arrays, unknown value references, non-finite values;
# fmu-rocking/tests/fmi3_driver, proptests and a replay of the seeds in
# fmu-rocking/tests/fmi3_c_api.rs: `tools/fuzz.sh 600 c_api3`); for
# RoundBody.fmu, round_body (FMI 2.0 on up to three instances, co-simulation
# and Model Exchange: agx, agy, av and their derivatives incl. non-finite and
# huge values, steps of every size, FMU states incl. corrupted buffers,
# resets; fmi2-fuzz-driver with fmu-round-body/tests/fuzz_driver, proptests and a replay of the
# seeds in fmu-round-body/tests/fmi2_fuzz.rs) and round_body3 (FMI 3.0:
# co-simulation with and without event mode and early return, Model
# Exchange; fmu-round-body/tests/fmi3_driver, fmi3_fuzz.rs):
# `tools/fuzz.sh 600 round_body`, `tools/fuzz.sh 600 round_body3`.
#
# The target, fuzz/fuzz_targets/c_api.rs, decodes its input into up to 160
# FMI calls on up to four instances (fmi2-fuzz-driver/src/ops.rs)
# and checks every status, value, logger message and FMU state; any panic
# (even one the FMU catches), AddressSanitizer or LeakSanitizer report is a
# finding, written to fuzz/artifacts/TARGET/ (the same for the others).
# FUZZ_LEN_CONTROL=0 starts at -max_len at once instead of growing the
# inputs from a few bytes (libFuzzer's -len_control, default 100).
#
# cargo-fuzz passes nightly flags (-Zsanitizer=address); RUSTC_BOOTSTRAP=1
# lets the stable toolchain accept them. FUZZ_SANITIZER=none runs without
# AddressSanitizer (faster, or where it is not available).
#
# New inputs go to fuzz/target/corpus-TARGET (not committed); the committed
# seeds in fuzz/corpus/TARGET are only read. To fold new inputs into the
# committed corpus, minimised (cmin rewrites the directory in place):
#   cd fuzz && cp target/corpus-c_api/* corpus/c_api/ &&
#   RUSTC_BOOTSTRAP=1 cargo fuzz cmin c_api corpus/c_api -- -timeout=30
# To replay one input: cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz run c_api
# artifacts/c_api/crash-..., or with its operations printed:
#   FUZZ_INPUT=fuzz/artifacts/c_api/crash-... cargo test --release \
#     -p fmu-rocking --test c_api_fuzz -- --ignored --nocapture replay_fuzz_input
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
secs="${1:-600}"
target="${2:-c_api}"
if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi
export RUSTC_BOOTSTRAP=1
mkdir -p "target/corpus-$target"
cargo fuzz run "$target" -s "${FUZZ_SANITIZER:-address}" "target/corpus-$target" "corpus/$target" -- \
    -max_total_time="$secs" -timeout=30 -max_len=4096 -rss_limit_mb=4096 -print_final_stats=1 \
    -len_control="${FUZZ_LEN_CONTROL:-100}"
