#!/usr/bin/env bash
# Every test of the project, on a fresh machine: Rust unit, integration and
# property tests, the packaged FMU, and the fmpy suite (Python packages pinned
# in requirements.txt, installed into .venv).
#
# Two jobs run beside the stages in front of them, because each is mostly one
# thread (downloads and unpacking; valgrind, which runs a program on one core)
# and the machines have two cores: the installs beside the lints, the
# memcheck beside the release binaries, rustdoc, the packaging, fmi-import
# and the docs site. A job's output is printed whole when it is waited for;
# its failure fails the command, and an exit stops it.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
# a stage's header with the minutes:seconds since the start, so that a slow stage shows
clock() { printf '%d:%02d' $(((SECONDS - start) / 60)) $(((SECONDS - start) % 60)); }
stage() { printf '== %s [%s]\n' "$1" "$(clock)"; }
logs=target/test-logs
mkdir -p "$logs"
jobs_started=()
# beside NAME CMD...: start CMD in its own process group (setsid), output to $logs/NAME.log
beside() {
  local name=$1
  shift
  printf '== %s: started beside the next stages [%s]\n' "$name" "$(clock)"
  setsid --wait "$@" >"$logs/$name.log" 2>&1 &
  jobs_started+=($!)
  eval "job_$name=$!"
}
# await NAME: wait for the job, print its output, fail with it
await() {
  local name=$1 pid
  eval "pid=\$job_$name"
  local rc=0
  wait "$pid" || rc=$?
  printf '== %s: output (done at %s)\n' "$name" "$(clock)"
  cat "$logs/$name.log"
  if [ "$rc" -ne 0 ]; then
    echo "$name FAILED (exit $rc, log $logs/$name.log)" >&2
    exit "$rc"
  fi
}
stop_jobs() { for pid in "${jobs_started[@]}"; do kill -- "-$pid" 2>/dev/null || true; done; }
trap stop_jobs EXIT
# the Debian packages fmi-import/ needs: fmi-sys runs bindgen at build time,
# which needs libclang
libclang() {
  if ! dpkg -s libclang-dev >/dev/null 2>&1; then
    local sudo=""
    if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then sudo="sudo"; fi
    $sudo apt-get update -qq
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libclang-dev
  fi
}
export -f libclang
beside installs bash -c 'set -euo pipefail
  echo "-- venv (tools/venv.sh), the toolchains of the FMU'"'"'s linux64 and win64 binaries (tools/cross-deps.sh --test), libclang-dev"
  tools/venv.sh
  tools/cross-deps.sh --test
  libclang'
stage "format and lints"
cargo fmt --all -- --check
cargo clippy --workspace --all-targets --quiet -- -D warnings
await installs
stage "Rust tests (profile ci: release optimisation without LTO or one codegen unit, Cargo.toml)"
cargo test --workspace --profile ci
# what it runs the Rust stage has built: the ci profile's test binaries, the
# release FMU library and the archive
beside memcheck tools/memcheck.sh
stage "the release binaries the Python tests run: rocking-corner, the Dharahara curves example"
cargo build --release -p corner
cargo build --release -p rocking --example dharahara_curves
stage "rustdoc of every crate without warnings; the library crates packaged for publishing"
echo "   (cargo publish --dry-run --no-verify: manifests and contents; tools/sdist-check.sh also"
echo "   builds them from the packages, a cold build of their graph)"
crates="-p rocking -p model-description -p fmi2-export -p corner"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --quiet --workspace
cargo publish --dry-run --allow-dirty --quiet --no-verify $crates
stage "package the FMU (linux64 against glibc 2.17, win64) and its FMI cross-check artefacts"
cargo xtask crosscheck
stage "the packaged FMU through the fmi crate's FMI 2.0 importer (fmi-import/)"
cargo fmt --manifest-path fmi-import/Cargo.toml -- --check
cargo clippy --manifest-path fmi-import/Cargo.toml --release --all-targets --quiet -- -D warnings
cargo test --release --manifest-path fmi-import/Cargo.toml
stage "the documentation site, strict, and its main pages in headless chromium (tools/docs.sh)"
tools/docs.sh --check
stage "valgrind memcheck of an instance's whole life through the C API (tools/memcheck.sh)"
await memcheck
stage "fmpy suite, two workers (pytest-xdist), each test file whole on one of them"
# A file's module fixtures (a built site, an extracted FMU) are built once, on
# its worker; tests of different files share only the archives and binaries
# built above, which they read (wine is used by one file alone). The wheels'
# tests cross-build the helpers a wheel carries: tools/wheel-check.sh.
.venv/bin/python -m pytest fmpy-tests -q -rs -n 2 --dist loadfile --durations=12 \
  --ignore=fmpy-tests/test_wheel.py
stage "done"
