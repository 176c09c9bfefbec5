#!/usr/bin/env bash
# What `cargo xtask fmu` needs for the FMU's binaries beyond the native one,
# installed where missing (idempotent, quiet when done):
# - linux64 against glibc 2.17: cargo-zigbuild and zig, the pinned wheels of
#   tools/requirements-cross.txt, into .venv (run tools/venv.sh first);
# - win64: the Rust target x86_64-pc-windows-gnu (rustup) and the mingw-w64
#   C toolchain for x86-64 (Debian: gcc-mingw-w64-x86-64);
# - with --test, also wine (Debian: wine64, wine), which runs the win64 test
#   host (fmpy-tests/test_platforms.py).
# A Windows part that cannot be installed (no rustup, no apt-get, no root) is
# one line here; `cargo xtask fmu` then leaves win64 out and the tests report
# it as skipped with the reason.
set -euo pipefail
cd "$(dirname "$0")/.."

stamp=.venv/.requirements-cross.sha
want=$(sha256sum tools/requirements-cross.txt | cut -d' ' -f1)
if ! [ -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -r tools/requirements-cross.txt
    echo "$want" > "$stamp"
fi

target=x86_64-pc-windows-gnu
if ! [ -d "$(rustc --print sysroot)/lib/rustlib/$target" ]; then
    if command -v rustup >/dev/null 2>&1; then
        rustup target add "$target" >/dev/null 2>&1 || echo "cross-deps: rustup target add $target failed: no win64 binary"
    else
        echo "cross-deps: no rustup to add the Rust target $target: no win64 binary"
    fi
fi

packages=()
command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 || packages+=(gcc-mingw-w64-x86-64)
if [ "${1:-}" = "--test" ] && ! command -v wine >/dev/null 2>&1; then
    packages+=(wine64 wine)
fi
if [ ${#packages[@]} -gt 0 ]; then
    sudo=""
    if [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1; then sudo="sudo"; fi
    if command -v apt-get >/dev/null 2>&1 \
        && $sudo apt-get update -qq \
        && $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${packages[@]}" >/dev/null; then
        :
    else
        echo "cross-deps: could not install ${packages[*]} (Debian packages): win64 is left out or not tested"
    fi
fi
