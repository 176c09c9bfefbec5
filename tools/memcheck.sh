#!/usr/bin/env bash
# Memory checks of the FMU. Logs and reports go to target/memcheck/.
#
#   tools/memcheck.sh [ROUNDS [STEPS]]
#       valgrind memcheck of fmu-rocking/examples/c_api_loop (instantiate,
#       simulate with impacts / a crushing interface / overturning, get, set,
#       serialize and deserialize FMU states, reset, free, and the error
#       paths, with debug logging), built in the release profile (what the FMU
#       ships; ROUNDS x STEPS, default 3 x 1000 steps per case). Fails on any
#       memcheck error or definite/indirect leak. Then the Model Exchange tests (fmu-rocking/tests/model_exchange.rs)
#       under memcheck, and FMI 3.0: an instance's life in a plain C host
#       (co-simulation with early return, Model Exchange) and the 3.0 call
#       sequences (fmu-rocking/tests/fmi3_c_api.rs); then RoundBody.fmu's
#       tests (fmu-round-body: FMI 2.0 and 3.0 through the in-process host,
#       FMU states, random call sequences, beside RockingBlock). This is what
#       tools/test.sh runs (about 2 minutes).
#   tools/memcheck.sh --suites
#       c_api_loop built in the dev profile (no optimisation, debug assertions
#       and overflow checks; DEV_ROUNDS x DEV_STEPS, default 1 x 400: a dev
#       build of the FMU's whole graph, 100 s of CPU, which the test command
#       leaves out), then every test binary of fmu-rocking (fmu_import among
#       them, which dlopens the packaged FMU) and fmi2-export, under memcheck
#       (ci profile, each in its package's directory; PROPTEST_CASES=16;
#       at most SUITE_TIMEOUT=1800 s each; about 6 minutes).
#   tools/memcheck.sh --fmpy
#       the fmpy tests that load the FMU under memcheck with PYTHONMALLOC=malloc;
#       only errors and definite/indirect leaks with a frame of the FMU in a
#       stack count (tools/memcheck_ours.py); CPython/numpy are tallied
#       (about 7 minutes).
#   tools/memcheck.sh --asan
#       AddressSanitizer + LeakSanitizer build (stable toolchain,
#       RUSTC_BOOTSTRAP=1 -Zsanitizer=address, target dir target/asan) of the
#       tests of fmu-rocking and fmi2-export (PROPTEST_CASES=16) and of
#       c_api_loop, run with LeakSanitizer's leak check at exit.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${CARGO_TARGET_DIR:-target}
mkdir -p "$target/memcheck"
out=$(cd "$target/memcheck" && pwd)
supp=tools/memcheck.supp
vg=(valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite,indirect
  --show-leak-kinds=definite,indirect,possible --track-origins=yes)

summary() { # the leak and error summary lines of a valgrind log
  grep -E "ERROR SUMMARY|definitely lost:|indirectly lost:|possibly lost:|still reachable:|suppressed:" "$1" \
    | sed 's/^==[0-9]*== */   /'
}

# Test executables (JSON messages of cargo test --no-run) of the given packages,
# in the ci profile (Cargo.toml: the release profile's optimisation without
# LTO, one codegen unit or line tables): tools/test.sh's Rust stage has built
# them, where a release build of the same tests took minutes more. The FMU's
# own library (c_api_loop, free_rocking3) stays the release build it ships as.
test_binaries() {
  cargo test --profile ci --no-run --message-format=json "$@" 2>/dev/null | python3 -c '
import json, sys
for line in sys.stdin:
    try:
        m = json.loads(line)
    except ValueError:
        continue
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["profile"]["test"]:
        print(m["target"]["name"], m["executable"], m["manifest_path"].rsplit("/", 1)[0])'
}

# c_api_loop PROFILE ROUNDS STEPS: built in PROFILE, under memcheck
c_api_loop() {
  local profile=$1 dir=$1
  [ "$profile" = dev ] && dir=debug
  cargo build --quiet --profile "$profile" -p fmu-rocking --example c_api_loop
  local log="$out/c_api_loop.$profile.log"
  echo "-- memcheck: c_api_loop ($profile profile, $2 rounds x $3 steps)"
  "${vg[@]}" --suppressions="$supp" --log-file="$log" "$target/$dir/examples/c_api_loop" "$2" "$3" | tail -n 1 || status=1
  summary "$log"
}

status=0
case "${1:-}" in
--suites)
  c_api_loop dev "${DEV_ROUNDS:-1}" "${DEV_STEPS:-400}"
  cargo xtask fmu >/dev/null # fmu-rocking/tests/fmu_import.rs loads the packaged FMU
  export PROPTEST_CASES=${PROPTEST_CASES:-16}
  root=$PWD
  while read -r name exe dir; do
    log="$out/suite.$name.log"
    start=$(date +%s)
    # in the package's directory, as cargo test runs it
    if (cd "$dir" && timeout "${SUITE_TIMEOUT:-1800}" "${vg[@]}" --suppressions="$root/$supp" --log-file="$log" "$exe" >"$log.out" 2>&1); then
      verdict=ok
    else
      verdict=FAILED status=1
    fi
    echo "-- $name: $verdict in $(($(date +%s) - start)) s ($(grep -h "test result" "$log.out" | head -1))"
    summary "$log"
  done < <(test_binaries -p fmu-rocking -p fmi2-export)
  ;;
--fmpy)
  tools/venv.sh
  cargo xtask fmu >/dev/null
  xml="$out/fmpy.xml"
  echo "-- memcheck: fmpy tests that load the FMU (PYTHONMALLOC=malloc)"
  PYTHONMALLOC=malloc OPENBLAS_NUM_THREADS=1 valgrind --leak-check=full \
    --show-leak-kinds=definite,indirect --track-origins=yes --num-callers=40 \
    --xml=yes --xml-file="$xml" --log-file="$out/fmpy.log" \
    .venv/bin/python -m pytest -p no:cacheprovider -q \
    fmpy-tests/test_fmi_calls.py fmpy-tests/test_state.py fmpy-tests/test_simulation.py \
    fmpy-tests/test_model_description.py fmpy-tests/test_crosscheck.py | tail -n 1 || status=1
  python3 tools/memcheck_ours.py "$xml" | tee "$out/fmpy.report" | grep -v "^      at " || status=1
  ;;
--asan)
  export RUSTC_BOOTSTRAP=1 RUSTFLAGS="-Zsanitizer=address" CARGO_TARGET_DIR="$target/asan"
  export ASAN_OPTIONS=fast_unwind_on_malloc=0:detect_stack_use_after_return=1
  export LSAN_OPTIONS=suppressions=$PWD/tools/lsan.supp
  asan=(--target x86_64-unknown-linux-gnu)
  export PROPTEST_CASES=${PROPTEST_CASES:-16}
  echo "-- AddressSanitizer + LeakSanitizer: tests of fmu-rocking and fmi2-export"
  cargo test "${asan[@]}" -p fmu-rocking -p fmi2-export >"$out/asan.tests.out" 2>&1 || status=1
  grep -E "Running|test result|Sanitizer|SUMMARY|leaked|Suppressions used|^ +[0-9]+ +[0-9]+ [a-z_:]+$" "$out/asan.tests.out" || true
  echo "-- AddressSanitizer + LeakSanitizer: c_api_loop (release profile)"
  cargo run --quiet --release "${asan[@]}" -p fmu-rocking --example c_api_loop -- 3 1000 2>&1 | tail -n 3 || status=1
  ;;
*)
  c_api_loop release "${1:-3}" "${2:-1000}"
  # the Model Exchange call sequences (fmu-rocking/tests/model_exchange.rs)
  root=$PWD
  while read -r name exe dir; do
    log="$out/model_exchange.log"
    echo "-- memcheck: the Model Exchange tests (ci profile)"
    (cd "$dir" && "${vg[@]}" --suppressions="$root/$supp" --log-file="$log" "$exe" -q) | tail -n 2 || status=1
    summary "$log"
  done < <(test_binaries -p fmu-rocking --test model_exchange)
  # FMI 3.0: an instance's whole life through the C API in a plain C host
  # (fmu-rocking/tests/c_host/free_rocking3.c: co-simulation with event mode
  # and early return at each impact, Model Exchange with event handling),
  # then the 3.0 call sequences (fmu-rocking/tests/fmi3_c_api.rs: the state
  # machine, bad sizes, NULL arrays, unknown value references, non-finite
  # values), PROPTEST_CASES=64
  cargo build --quiet --release -p fmu-rocking
  [ -f "$target/fmu/RockingBlock.fmu" ] || cargo xtask fmu >/dev/null # the GUID is the archive's
  guid=$(unzip -p "$target/fmu/RockingBlock.fmu" modelDescription.xml | sed -n 's/.*guid="\([^"]*\)".*/\1/p')
  host="$out/free_rocking3"
  cc -O2 -std=c99 -Wall -Wextra -Werror -o "$host" fmu-rocking/tests/c_host/free_rocking3.c -ldl
  # rigid block (interface 1) from theta = 0.1 rad, 300 steps of 0.01 s,
  # tolerance 1e-9 (doubles as hex bits)
  for mode in cs me; do
    log="$out/fmi3_$mode.log"
    echo "-- memcheck: FMI 3.0 $mode life (free_rocking3, release profile)"
    "${vg[@]}" --suppressions="$supp" --log-file="$log" "$host" "$target/release/libfmu_rocking.so" "$mode" \
      "$guid" \
      "$PWD/" 3e112e0be826d695 3f847ae147ae147b 300 12 1 20 3fb999999999999a 21 | grep -c "^event" | sed 's/^/   events: /' || status=1
    summary "$log"
  done
  while read -r name exe dir; do
    log="$out/fmi3_c_api.log"
    echo "-- memcheck: the FMI 3.0 call sequences (ci profile, PROPTEST_CASES=64)"
    (cd "$dir" && PROPTEST_CASES=64 "${vg[@]}" --suppressions="$root/$supp" --log-file="$log" "$exe" -q) | tail -n 2 || status=1
    summary "$log"
  done < <(test_binaries -p fmu-rocking --test fmi3_c_api)
  # RoundBody.fmu: its tests through the in-process host (FMI 2.0 and 3.0,
  # FMU states, bad input, random call sequences) and beside RockingBlock
  # (tests/planar.rs); the fuzz drivers' proptests (fmi2_fuzz, fmi3_fuzz)
  # with PROPTEST_CASES=32 (8 s under memcheck, 24 s at their defaults)
  while read -r name exe dir; do
    log="$out/round_body_$name.log"
    echo "-- memcheck: fmu-round-body's $name tests (ci profile)"
    (cd "$dir" && PROPTEST_CASES=32 "${vg[@]}" --suppressions="$root/$supp" --log-file="$log" "$exe" -q) | tail -n 2 || status=1
    summary "$log"
  done < <(test_binaries -p fmu-round-body)
  ;;
esac
if [ "$status" -ne 0 ]; then
  echo "memcheck FAILED (see $out/)" >&2
fi
exit "$status"
