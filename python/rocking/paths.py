"""Where the package's files are: the shipped ground-motion records, the FMUs and the native helpers.

Two layouts, found the same way by every caller (`REPO`, `target_dir()`, `data_dir()`):

- a clone: the package installed editable (`pip install -e .`, which
  `tools/venv.sh` does), so that this file sits at python/rocking/paths.py of
  the repository; the records are data/ground-motions, the FMUs and the native
  helpers what `cargo xtask fmu` and `cargo build --release` write to
  target/fmu and target/release ($CARGO_TARGET_DIR honoured);
- a wheel (`cargo xtask wheel`): the package carries the same files in
  rocking/_bundled/, laid out like a clone's (data/ground-motions, examples,
  target/fmu, target/release) with BUILD.json (the commit it was built from).

Installed any other way (the sdist without Rust, a plain non-editable
install), the package carries neither: the repository is then looked for from
the current directory upwards, and where none is found the functions that need
it raise `FileNotFoundError` saying so (pass a record's path and `--fmu`
explicitly instead).
"""

import json
import os
import sys
from pathlib import Path

#: rocking/_bundled of a wheel (None in a clone or a plain install).
BUNDLE = Path(__file__).resolve().parent / "_bundled"
if not (BUNDLE / "BUILD.json").is_file():
    BUNDLE = None


def _is_repo(path):
    return (path / "data" / "ground-motions").is_dir() and (path / "Cargo.toml").is_file()


def _find_repo():
    if BUNDLE is not None:
        return BUNDLE
    here = Path(__file__).resolve().parents[2]
    if _is_repo(here):
        return here
    cwd = Path.cwd().resolve()
    for candidate in (cwd, *cwd.parents):
        if _is_repo(candidate):
            return candidate
    return None


#: The repository this package was installed from (editable install), the
#: wheel's rocking/_bundled, or None.
REPO = _find_repo()

_NOT_IN_REPO = ("this installation of the `rocking` package is not inside the RockingBlock repository "
                "and carries no FMU (install a wheel, or `pip install -e .` from a clone, or run from the clone)")

#: Executable suffix of the native binaries (rocking-corner).
EXE = ".exe" if sys.platform == "win32" else ""


def repo():
    """The repository's root (or the wheel's bundle); FileNotFoundError if there is neither."""
    if REPO is None:
        raise FileNotFoundError(_NOT_IN_REPO)
    return REPO


def data_dir():
    """data/ground-motions of the repository (the shipped records; a wheel carries a sample of them)."""
    return repo() / "data" / "ground-motions"


def examples_dir():
    """examples/ of the repository (the study files: fragility.toml, sweep.toml, cosim/...; a
    wheel carries them at rocking/_bundled/examples). `rocking examples DIR` copies them."""
    return repo() / "examples"


def target_dir():
    """Cargo's target folder: $CARGO_TARGET_DIR (relative to the repository) or target/; a wheel's own."""
    env = os.environ.get("CARGO_TARGET_DIR")
    if env and BUNDLE is None:
        path = Path(env)
        return path if path.is_absolute() else repo() / path
    return repo() / "target"


def default_fmu():
    """target/fmu/RockingBlock.fmu of the repository, where `cargo xtask fmu` writes it (or the wheel's)."""
    return target_dir() / "fmu" / "RockingBlock.fmu"


def build_info():
    """{"commit": ...} recorded when the wheel was built; in a clone its checked-out commit; else "unknown"."""
    if BUNDLE is not None:
        return json.loads((BUNDLE / "BUILD.json").read_text())
    return {"commit": _git_commit(REPO) if REPO is not None else "unknown"}


def _git_commit(root):
    """The clone's HEAD (with "-dirty" when its tracked files differ from it), or "unknown"."""
    import subprocess
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True,
                              text=True, timeout=10)
        if head.returncode != 0:
            return "unknown"
        dirty = subprocess.run(["git", "-C", str(root), "diff", "--quiet", "HEAD"], timeout=10).returncode
        return head.stdout.strip() + ("-dirty" if dirty == 1 else "")
    except (OSError, subprocess.SubprocessError):
        return "unknown"
