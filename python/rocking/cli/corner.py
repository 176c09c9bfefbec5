"""`rocking corner ARGS...`: the arguments forwarded untouched to the Rust binary rocking-corner."""

import os
import shutil
import subprocess

from .. import paths
from .common import CLIError


def corner_binary():
    """target/release/rocking-corner of the repository, else rocking-corner on PATH, else None."""
    if paths.REPO is not None:
        local = paths.target_dir() / "release" / ("rocking-corner" + paths.EXE)
        if local.is_file() and os.access(local, os.X_OK):
            return str(local)
    return shutil.which("rocking-corner")


def forward(argv):
    """Run rocking-corner on argv as given (argparse never sees it); its exit status."""
    exe = corner_binary()
    if exe is None:
        raise CLIError("rocking-corner not found (target/release of the repository, PATH): "
                       "build it with `cargo build --release -p corner`")
    return subprocess.call([exe, *argv])


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    sub.add_parser("corner", help="forward the arguments to the Rust binary rocking-corner", add_help=False)
