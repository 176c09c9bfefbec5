#!/usr/bin/env bash
# The main job: build everything the README's commands use (RockingBlock.fmu
# and ShearFrame.fmu with the native stepping loop, the rocking-corner binary)
# and run the Dharahara case study through it, leaving plots and tables in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/venv.sh
tools/cross-deps.sh
cargo xtask fmu
cargo build --release -p corner
.venv/bin/python examples/dharahara.py "$@"
