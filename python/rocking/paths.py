"""Where the repository's files are: the shipped ground-motion records and the FMU.

The package is meant to be installed editable from the repository
(`pip install -e .`, which `tools/venv.sh` does): then this file sits at
python/rocking/paths.py of the repository and the records of
data/ground-motions and the FMU that `cargo xtask fmu` writes are found
relative to it. Installed any other way (a wheel, non-editable), the package
does not carry the records or the FMU: the repository is then looked for from
the current directory upwards, and where none is found the functions that need
it raise `FileNotFoundError` saying so (pass a record's path and `--fmu`
explicitly instead).
"""

import os
from pathlib import Path


def _is_repo(path):
    return (path / "data" / "ground-motions").is_dir() and (path / "Cargo.toml").is_file()


def _find_repo():
    here = Path(__file__).resolve().parents[2]
    if _is_repo(here):
        return here
    cwd = Path.cwd().resolve()
    for candidate in (cwd, *cwd.parents):
        if _is_repo(candidate):
            return candidate
    return None


#: The repository this package was installed from (editable install), or None.
REPO = _find_repo()

_NOT_IN_REPO = ("this installation of the `rocking` package is not inside the RockingBlock repository "
                "(install it with `pip install -e .` from a clone, or run from the clone)")


def repo():
    """The repository's root; FileNotFoundError if the package is not in one."""
    if REPO is None:
        raise FileNotFoundError(_NOT_IN_REPO)
    return REPO


def data_dir():
    """data/ground-motions of the repository (the shipped records)."""
    return repo() / "data" / "ground-motions"


def target_dir():
    """Cargo's target folder: $CARGO_TARGET_DIR (relative to the repository) or target/."""
    env = os.environ.get("CARGO_TARGET_DIR")
    if env:
        path = Path(env)
        return path if path.is_absolute() else repo() / path
    return repo() / "target"


def default_fmu():
    """target/fmu/RockingBlock.fmu of the repository, where `cargo xtask fmu` writes it."""
    return target_dir() / "fmu" / "RockingBlock.fmu"
