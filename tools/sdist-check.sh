#!/usr/bin/env bash
# The sdist installed as a user installs it: tools/wheel.py writes it from a
# local clone of the committed HEAD (work in progress, which may not build,
# stays out); pip installs it into a new venv outside the clone (the
# dependencies at the versions of requirements.txt), which builds the whole
# Rust workspace from it (setup.py: `cargo xtask bundle`, a cold build: 11
# min 33 s wall, 7 min of CPU on 2 cores, so not part of tools/test.sh); the installed
# `rocking --version` must name the FMU the install built into its own
# rocking/_bundled. First the library crates as another FMU author gets
# them from a registry: `cargo publish --dry-run`, packaged and then built
# from the packages (tools/test.sh checks the packages without that build).
#   tools/sdist-check.sh [--keep]   (--keep: leave the work folder and print it)
set -euo pipefail
cd "$(dirname "$0")/.."
tools/venv.sh
cargo publish --dry-run --allow-dirty --quiet -p rocking -p model-description -p fmi2-export -p corner
work=$(mktemp -d "${TMPDIR:-/tmp}/sdist-check.XXXXXX")
if [ "${1:-}" != "--keep" ]; then trap 'rm -rf "$work"' EXIT; fi

git clone --quiet --no-hardlinks . "$work/clone"
.venv/bin/python "$work/clone/tools/wheel.py" --sdist --out "$work"
echo "sdist-check: the sdist of $(git -C "$work/clone" rev-parse --short HEAD)"
sdist=$(ls "$work"/rocking-*.tar.gz)
.venv/bin/python -m venv "$work/venv"
# constraints may not carry extras: dask[distributed]==X becomes dask==X
sed 's/\[[^]]*\]//' requirements.txt > "$work/constraints.txt"

start=$(date +%s)
# a user's environment: no target folder of the clone's, no venv of the clone's
if ! (cd "$work" && env -u CARGO_TARGET_DIR -u VIRTUAL_ENV "$work/venv/bin/python" -m pip install \
        --disable-pip-version-check --constraint "$work/constraints.txt" "$sdist" >"$work/pip.log" 2>&1); then
    tail -n 40 "$work/pip.log"
    echo "sdist-check: pip install $sdist failed (log above; --keep keeps $work)" >&2
    exit 1
fi
seconds=$(( $(date +%s) - start ))

version=$(cd "$work" && env -u CARGO_TARGET_DIR "$work/venv/bin/rocking" --version)
echo "$version"
case "$version" in
    *"$work/venv/"*"rocking/_bundled/target/fmu/RockingBlock.fmu"*) ;;
    *) echo "sdist-check: rocking --version does not name the installed bundle's FMU" >&2; exit 1 ;;
esac
echo "sdist-check: $(basename "$sdist") installed in ${seconds} s (pip install, the Rust build included)"
[ "${1:-}" = "--keep" ] && echo "sdist-check: work folder $work"
exit 0
