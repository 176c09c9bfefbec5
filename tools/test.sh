#!/usr/bin/env bash
# Every test of the project, on a fresh machine: Rust unit, integration and
# property tests, the packaged FMU, and the fmpy suite (Python packages pinned
# in requirements.txt, installed into .venv).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
# a stage's header with the minutes:seconds since the start, so that a slow stage shows
stage() { printf '== %s [%d:%02d]\n' "$1" $(((SECONDS - start) / 60)) $(((SECONDS - start) % 60)); }
stage "venv, and the toolchains of the FMU's linux64 and win64 binaries"
tools/venv.sh
tools/cross-deps.sh --test
stage "format and lints"
cargo fmt --all -- --check
cargo clippy --workspace --all-targets --quiet -- -D warnings
stage "Rust tests (profile ci: release optimisation without LTO or one codegen unit, Cargo.toml)"
cargo test --workspace --profile ci
stage "the release binaries the Python tests run: rocking-corner, the Dharahara curves example"
cargo build --release -p corner
cargo build --release -p rocking --example dharahara_curves
stage "rustdoc of every crate without warnings; the library crates as another FMU author gets"
echo "   them: cargo publish --dry-run (packaged, then built from the package; 33 s cold, a few s warm)"
crates="-p rocking -p model-description -p fmi2-export -p corner"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --quiet --workspace
cargo publish --dry-run --allow-dirty --quiet $crates
stage "valgrind memcheck of an instance's whole life through the C API"
tools/memcheck.sh
stage "package the FMU (linux64 against glibc 2.17, win64) and its FMI cross-check artefacts"
cargo xtask crosscheck
stage "the packaged FMU through the fmi crate's FMI 2.0 importer (fmi-import/)"
# fmi-sys runs bindgen at build time: it needs libclang (Debian: libclang-dev)
if ! dpkg -s libclang-dev >/dev/null 2>&1; then
    sudo=""
    if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then sudo="sudo"; fi
    $sudo apt-get update -qq
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libclang-dev
fi
cargo fmt --manifest-path fmi-import/Cargo.toml -- --check
cargo clippy --manifest-path fmi-import/Cargo.toml --release --all-targets --quiet -- -D warnings
cargo test --release --manifest-path fmi-import/Cargo.toml
stage "the documentation site, strict, and its main pages in headless chromium (tools/docs.sh)"
tools/docs.sh --check
stage "fmpy suite, two workers (pytest-xdist), each test file whole on one of them"
# A file's module fixtures (the wheels, a built site, an extracted FMU) are
# built once, on its worker; tests of different files share only the archives
# and binaries built above, which they read (wine is used by one file alone).
.venv/bin/python -m pytest fmpy-tests -q -rs -n 2 --dist loadfile --durations=12
stage "done"
