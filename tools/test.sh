#!/usr/bin/env bash
# Every test of the project, on a fresh machine: Rust unit, integration and
# property tests, the packaged FMU, and the fmpy suite (Python packages pinned
# in requirements.txt, installed into .venv).
set -euo pipefail
cd "$(dirname "$0")/.."
echo "== venv"
tools/venv.sh
echo "== format and lints"
cargo fmt --all -- --check
cargo clippy --workspace --all-targets --quiet -- -D warnings
echo "== Rust tests"
cargo test --workspace --release
echo "== package the FMU and its FMI cross-check artefacts"
cargo xtask crosscheck
echo "== fmpy suite"
.venv/bin/python -m pytest fmpy-tests -q
