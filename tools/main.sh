#!/usr/bin/env bash
# The main job: build RockingBlock.fmu and run the Dharahara case study
# through it, leaving plots and tables in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/venv.sh
tools/cross-deps.sh
cargo xtask rocking-block
.venv/bin/python examples/dharahara.py "$@"
