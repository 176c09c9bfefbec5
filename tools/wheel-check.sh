#!/usr/bin/env bash
# The platform wheels of `cargo xtask wheel` (fmpy-tests/test_wheel.py): the
# Linux wheel installed into a new venv outside the clone and run, the
# Windows wheel checked by its contents and tags, twine and auditwheel on
# both, the licences of their crates. It cross-builds the helpers a wheel
# carries (the stepping loop and rocking-corner for linux64 and win64: 155 s
# cold on 2 cores), so tools/test.sh leaves it to this command, as it leaves
# the sdist to tools/sdist-check.sh.
#   tools/wheel-check.sh [PYTEST ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
tools/venv.sh
tools/cross-deps.sh
cargo xtask fmu >/dev/null
.venv/bin/python -m pytest fmpy-tests/test_wheel.py -q -rs "$@"
