"""`rocking corner ARGS...`: the arguments forwarded untouched to the Rust binary rocking-corner
(the macroblock limit analysis, `--method la`, the default). `--method lp` and `--method dem`
run the same specimen block by block instead: `rocking corner-blocks lp|dem` with the other
arguments (docs/corner-blocks.md), e.g. `rocking corner --method dem --ends free --alpha 1.5708`.

The body file the binary writes (`--body FILE`) is then made one-sided on the
macroblock's collapse side (docs/corner.md §10): restraint = oneSided, side = 1
(theta > 0 is the outward rotation) and eRestraint = the body's own Housner
coefficient etaHousner, which the FMU calculates from it.
"""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

from .. import paths
from .common import CLIError


def corner_binary():
    """The wheel's bundled rocking-corner or the clone's target/release/rocking-corner, else
    rocking-corner on PATH, else None."""
    if paths.REPO is not None:
        local = paths.target_dir() / "release" / ("rocking-corner" + paths.EXE)
        if local.is_file() and os.access(local, os.X_OK):
            return str(local)
    return shutil.which("rocking-corner")


METHODS = ("la", "lp", "dem")


def method_of(argv):
    """(the method of `--method M` / `--method=M`, default la; argv without it)."""
    rest, method = [], "la"
    i = 0
    while i < len(argv):
        if argv[i] == "--method":
            if i + 1 >= len(argv):
                raise CLIError("--method: a value is needed (la, lp or dem)")
            method, i = argv[i + 1], i + 2
            continue
        if argv[i].startswith("--method="):
            method = argv[i].split("=", 1)[1]
        else:
            rest.append(argv[i])
        i += 1
    if method not in METHODS:
        raise CLIError(f"invalid --method: la (macroblock), lp (block LP) or dem (LMGC90), got {method}")
    return method, rest


def forward(argv):
    """Run rocking-corner on argv as given (argparse never sees it), or with `--method lp|dem`
    the block-by-block command; its exit status."""
    method, argv = method_of(argv)
    if method != "la":
        from .main import main
        return main(["corner-blocks", method, *argv])
    if any(a == "--ends" or a.startswith("--ends=") for a in argv):
        raise CLIError("invalid --ends: the macroblock analysis (--method la) has its walls clamped at "
                       "their ends; --ends is for --method lp or dem")
    exe = corner_binary()
    if exe is None:
        raise CLIError("rocking-corner not found (neither bundled with this installation nor in a clone's "
                       "target/release, nor on PATH): install a wheel, or in a clone build it with "
                       "`cargo build --release -p corner`")
    status = subprocess.call([exe, *argv])
    body = body_file(argv)
    if status == 0 and body is not None and body.is_file():
        one_sided(body)
    return status


#: The macroblock's collapse side: it rotates outwards only, theta > 0 (docs/corner.md §10).
COLLAPSE_SIDE = 1


def body_file(argv):
    """The FILE of `--body FILE` / `--body=FILE` among argv, or None."""
    for i, arg in enumerate(argv):
        if arg == "--body" and i + 1 < len(argv):
            return Path(argv[i + 1])
        if arg.startswith("--body="):
            return Path(arg.split("=", 1)[1])
    return None


def one_sided(path):
    """Add restraint = oneSided, side = COLLAPSE_SIDE and eRestraint = etaHousner (the FMU's,
    for this body) to the body file at `path`; a note on stderr when the FMU is missing."""
    from ..fmu import RockingFMU
    body = json.loads(Path(path).read_text())
    try:
        with RockingFMU() as fmu:
            eta = fmu.calculated(body)["etaHousner"]
    except (FileNotFoundError, OSError) as exc:
        print(f"rocking corner: note: {path} left two-sided: no FMU to compute etaHousner ({exc})", file=sys.stderr)
        return
    body.update(restraint="oneSided", side=COLLAPSE_SIDE, eRestraint=eta)
    Path(path).write_text(json.dumps(dict(sorted(body.items())), indent=2) + "\n")
    print(f"rocking corner: {path}: one-sided on the collapse side (side = {COLLAPSE_SIDE}), "
          f"eRestraint = etaHousner = {eta:.6g}", file=sys.stderr)


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    sub.add_parser("corner", add_help=False,
                   help="the corner's collapse multiplier: --method la (default; the arguments go to the Rust "
                        "binary rocking-corner), lp or dem (as `corner-blocks lp|dem`)")
