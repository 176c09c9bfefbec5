#!/usr/bin/env bash
# The documentation site (mkdocs.yml), built strict into target/site: docs/*.md,
# the command reference from the CLI's --help, the Python API (mkdocstrings),
# the Rust API (cargo doc --no-deps of the workspace, copied to rust/) and
# MathJax served from the site (the pinned npm package, unpacked once into
# target/docs-vendor). `--check` then renders the main pages in Debian's
# headless chromium (tools/docs_browser_check.py; installs it with apt).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/venv.sh
MATHJAX=3.2.2
vendor=target/docs-vendor/mathjax
if [ ! -f "$vendor/es5/tex-chtml.js" ] || [ "$(cat "$vendor/VERSION" 2>/dev/null)" != "$MATHJAX" ]; then
    rm -rf "$vendor" && mkdir -p "$vendor"
    (cd "$vendor" && npm pack "mathjax@$MATHJAX" --silent >/dev/null && tar xzf "mathjax-$MATHJAX.tgz" --strip-components=1 package/es5 && rm "mathjax-$MATHJAX.tgz")
    echo "$MATHJAX" > "$vendor/VERSION"
fi
# the workspace's crates with rustdoc's warnings as errors: the very build of
# the test command's rustdoc stage, so that there it is already done
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --quiet --workspace
NO_MKDOCS_2_WARNING=1 .venv/bin/mkdocs build --strict --quiet
echo "site: target/site/index.html"
if [ "${1:-}" = "--check" ]; then
    .venv/bin/python tools/docs_browser_check.py target/site --install
fi
