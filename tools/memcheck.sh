#!/usr/bin/env bash
# Valgrind memcheck of the FMU's C API: builds fmu-rocking/examples/c_api_loop
# (instantiate, simulate with impacts / a crushing interface / overturning,
# get, set, serialize and deserialize FMU states, reset, free, and the error
# paths, with debug logging) in the release profile (what the FMU ships) and
# the dev profile (no optimisation, overflow checks; ~10x slower, so 1 round
# of 400 steps), and runs each under memcheck. Fails on any memcheck error or
# definite/indirect leak.
#
#   tools/memcheck.sh [ROUNDS [STEPS]]    (release: default 3 rounds of 1000 steps per case)
#   DEV_ROUNDS=1 DEV_STEPS=400            (dev profile, the defaults)
#
# Logs: target/memcheck/c_api_loop.<profile>.log
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-3}
steps=${2:-1000}
target=${CARGO_TARGET_DIR:-target}
mkdir -p "$target/memcheck"
status=0
for profile in release dev; do
  dir=release
  if [ "$profile" = dev ]; then
    dir=debug rounds=${DEV_ROUNDS:-1} steps=${DEV_STEPS:-400}
  fi
  cargo build --quiet --profile "$profile" -p fmu-rocking --example c_api_loop
  log="$target/memcheck/c_api_loop.$profile.log"
  echo "-- memcheck: c_api_loop ($profile profile, $rounds rounds x $steps steps)"
  if ! valgrind --error-exitcode=1 --leak-check=full \
    --errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect,possible \
    --track-origins=yes --log-file="$log" \
    "$target/$dir/examples/c_api_loop" "$rounds" "$steps" | tail -n 1; then
    status=1
  fi
  grep -E "ERROR SUMMARY|definitely lost|indirectly lost|possibly lost|still reachable" "$log" \
    | sed 's/^==[0-9]*== */   /'
done
if [ "$status" -ne 0 ]; then
  echo "memcheck FAILED (see $target/memcheck/)" >&2
fi
exit "$status"
