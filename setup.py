"""setuptools' build hook, for the sdist only (pyproject.toml holds the metadata).

The sdist (`cargo xtask wheel`, tools/wheel.py) carries the whole Rust
workspace beside the Python package. Built into a wheel from it (PKG-INFO and
Cargo.toml side by side), `cargo xtask bundle` builds both FMUs, the native
stepping loop and rocking-corner for this machine into the wheel's
rocking/_bundled: that needs Rust (cargo) and says so when it is missing. A
clone (`pip install -e .`) and the platform wheels (which add their bundle
themselves) are built without it.
"""

import shutil
import subprocess
from pathlib import Path

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

FROM_SDIST = Path("PKG-INFO").is_file() and Path("Cargo.toml").is_file()


class BuildWithRust(build_py):
    def run(self):
        super().run()
        if not FROM_SDIST or self.editable_mode:
            return
        if shutil.which("cargo") is None:
            raise SystemExit("rocking: building from the sdist needs Rust (cargo on PATH, rustup.rs); "
                             "or install a platform wheel")
        bundle = Path(self.build_lib).resolve() / "rocking" / "_bundled"
        subprocess.check_call(["cargo", "run", "--release", "--package", "xtask", "--", "bundle", str(bundle)])


class Platform(Distribution):
    """A wheel built from the sdist carries native code: tagged for this machine, never py3-none-any."""

    def has_ext_modules(self):
        return FROM_SDIST


setup(cmdclass={"build_py": BuildWithRust}, distclass=Platform)
