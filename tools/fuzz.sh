#!/usr/bin/env bash
# Fuzzes the FMU's C API with libFuzzer: `tools/fuzz.sh [seconds]` (default
# 600). Not part of tools/test.sh; the same interpreter runs as proptests in
# `cargo test` (fmu-rocking/tests/c_api_fuzz.rs).
#
# The target, fuzz/fuzz_targets/c_api.rs, decodes its input into up to 160
# FMI calls on up to four instances (fmu-rocking/tests/fuzz_driver/mod.rs)
# and checks every status, value, logger message and FMU state; any panic
# (even one the FMU catches), AddressSanitizer or LeakSanitizer report is a
# finding, written to fuzz/artifacts/c_api/.
#
# cargo-fuzz passes nightly flags (-Zsanitizer=address); RUSTC_BOOTSTRAP=1
# lets the stable toolchain accept them. FUZZ_SANITIZER=none runs without
# AddressSanitizer (faster, or where it is not available).
#
# New inputs go to fuzz/target/corpus-c_api (not committed); the committed
# seeds in fuzz/corpus/c_api are only read. To fold new inputs into the
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
if ! cargo fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz --locked
fi
export RUSTC_BOOTSTRAP=1
mkdir -p target/corpus-c_api
cargo fuzz run c_api -s "${FUZZ_SANITIZER:-address}" target/corpus-c_api corpus/c_api -- \
    -max_total_time="$secs" -timeout=30 -max_len=4096 -rss_limit_mb=4096 -print_final_stats=1
