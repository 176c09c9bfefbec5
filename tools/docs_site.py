"""mkdocs hook of the documentation site (mkdocs.yml): the pages that are generated.

- index.md: README.md, its links into docs/ made site links;
- cli.md: the command reference, from the CLI's own `--help` (argparse's, and
  rocking-corner's for `rocking corner`);
- python-api.md: the Python API, mkdocstrings directives over the package;
- rust-api.md: links to the cargo doc output that tools/docs.sh copies to rust/;
- js/mathjax-config.js: MathJax for pymdownx.arithmatex (generic), served from
  the site (tools/docs.sh unpacks the pinned npm package; no network at view time).

Links from a page to a file of the repository outside docs/ (a crate's README,
an example) become the file's name in code: the site carries docs/ only.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

#: Modules of the Python API page, in order.
API_MODULES = ["rocking", "rocking.fmu", "rocking.parametric", "rocking.groundmotion", "rocking.cases",
               "rocking.presets", "rocking.fragility", "rocking.paths"]
#: Crates of the Rust API page (cargo doc --no-deps, tools/docs.sh).
RUST_CRATES = ["rocking", "model_description", "fmi2_export", "corner"]

_LINK = re.compile(r"\[([^\]]+)\]\(([^)\s]+)\)")

MATHJAX_CONFIG = """window.MathJax = {
  tex: {inlineMath: [["\\\\(", "\\\\)"]], displayMath: [["\\\\[", "\\\\]"]], processEscapes: true},
  options: {ignoreHtmlClass: ".*|", processHtmlClass: "arithmatex"}
};
"""


def _outside_docs(target, page_dir):
    """Whether a relative link from a page in `page_dir` (docs-relative) leaves docs/."""
    if re.match(r"^[a-z]+:|^#|^/", target):
        return False
    path = os.path.normpath(os.path.join(page_dir, target.split("#")[0]))
    return path.startswith("..")


def _rewrite_links(markdown, page_dir, prefix=""):
    """Links into docs/ (given with `prefix`, "docs/" for the README) made site links; links out of
    docs/ made the file's name in code."""
    def one(match):
        text, target = match.groups()
        if prefix and target.startswith(prefix):
            return f"[{text}]({target[len(prefix):]})"
        if prefix and not re.match(r"^[a-z]+:|^#", target):
            return f"{text} (`{target}`)" if text.strip("`") != target else f"`{target}`"
        if not prefix and _outside_docs(target, page_dir):
            name = os.path.normpath(os.path.join(page_dir, target)).lstrip("./")
            return f"{text} (`{name}`)"
        return match.group(0)
    return _LINK.sub(one, markdown)


def _help_of(argv):
    out = subprocess.run([sys.executable, "-m", "rocking", *argv, "--help"], capture_output=True, text=True,
                         cwd=ROOT, env={**os.environ, "COLUMNS": "100", "PYTHONPATH": str(ROOT / "python")})
    return out.stdout if out.returncode == 0 else None


def cli_reference():
    from rocking.cli import COMMANDS
    from rocking.cli.corner import corner_binary
    parts = ["# Command reference", "",
             "Generated from the `rocking` command's own `--help` when the site is built.", "",
             "```text", _help_of([]).rstrip(), "```"]
    for module in COMMANDS:
        command = module.replace("_", "-")  # the module corner_blocks registers `corner-blocks`
        parts += ["", f"## rocking {command}", ""]
        if command == "corner":
            exe = corner_binary()
            if exe is None:
                parts.append("rocking-corner was not built (`cargo build --release -p corner`): its help is missing.")
                continue
            text = subprocess.run([exe, "--help"], capture_output=True, text=True, check=True).stdout
            parts.append("`rocking corner ARGS` hands its arguments to the Rust binary `rocking-corner`:")
            parts.append("")
        else:
            text = _help_of([command])
        parts += ["```text", text.rstrip(), "```"]
    return "\n".join(parts) + "\n"


def python_api():
    parts = ["# Python API", "", "The package `rocking`, from its docstrings.", ""]
    for module in API_MODULES:
        parts += [f"::: {module}", "    options:", "      members_order: source", ""]
    return "\n".join(parts)


def rust_api():
    parts = ["# Rust API", "",
             "The library crates, documented by `cargo doc --no-deps` when the site is built:", ""]
    for crate in RUST_CRATES:
        parts.append(f'- <a href="rust/{crate}/index.html">{crate}</a>')
    return "\n".join(parts) + "\n"


def on_files(files, config):
    readme = _rewrite_links((ROOT / "README.md").read_text(), ".", prefix="docs/")
    for name, content in [("index.md", readme), ("cli.md", cli_reference()), ("python-api.md", python_api()),
                          ("rust-api.md", rust_api()), ("js/mathjax-config.js", MATHJAX_CONFIG)]:
        files.append(File.generated(config, name, content=content))
    return files


def on_page_markdown(markdown, page, config, files):
    if page.file.generated_by is not None:
        return markdown
    return _rewrite_links(markdown, os.path.dirname(page.file.src_uri) or ".")


def on_post_build(config):
    """The vendored MathJax and the cargo doc output, copied where the pages look for them."""
    site = Path(config["site_dir"])
    vendor = ROOT / "target" / "docs-vendor" / "mathjax" / "es5"
    if vendor.is_dir():
        shutil.copytree(vendor, site / "js" / "mathjax", dirs_exist_ok=True)
    rustdoc = ROOT / "target" / "doc"
    if rustdoc.is_dir():
        shutil.copytree(rustdoc, site / "rust", dirs_exist_ok=True)
