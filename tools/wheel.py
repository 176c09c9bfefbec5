"""The Python package's platform wheels and sdist (run by `cargo xtask wheel`).

    wheel.py --bundle DIR --plat TAG --out DIR   setuptools' wheel of python/rocking with DIR
                                                 added as rocking/_bundled, tagged py3-none-TAG
    wheel.py --sdist --out DIR                   the sdist: the git-tracked tree (the Rust
                                                 workspace included), built into a wheel where
                                                 Rust is present (setup.py)

The pure wheel is built by setuptools (pyproject.toml's metadata) from a copy of
the sources in a temporary folder, so that the clone gets no build/ or egg-info.
The platform wheel is that archive with the bundle added, `Root-Is-Purelib:
false`, its tag, and RECORD written again; entries sorted, with fixed times.
The bundle's licence file of the crates in its binaries (THIRD-PARTY-LICENSES.txt)
also goes where a wheel's licence files are (.dist-info/licenses, named by a
License-File line of METADATA).
"""

import argparse
import base64
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: What setuptools needs to build the pure wheel.
SOURCES = ["pyproject.toml", "setup.py", "README.md", "LICENSE-MIT", "LICENSE-APACHE", "python"]
EPOCH = (1980, 1, 1, 0, 0, 0)
#: The bundle's third-party licence file (xtask/src/licences.rs).
THIRD_PARTY = "THIRD-PARTY-LICENSES.txt"


def build(kind, into):
    """setuptools' build_wheel or build_sdist run on a copy of SOURCES; the file it wrote."""
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "src"
        src.mkdir()
        for name in SOURCES if kind == "wheel" else tracked():
            path = ROOT / name
            if path.is_dir():
                shutil.copytree(path, src / name, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
            else:
                (src / name).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(path, src / name)
        code = f"from setuptools import build_meta; print(build_meta.build_{kind}({str(into)!r}))"
        out = subprocess.run([sys.executable, "-c", code], cwd=src, capture_output=True, text=True,
                             env={**os.environ, "SOURCE_DATE_EPOCH": "315532800"})
        if out.returncode != 0:
            sys.exit(f"wheel.py: setuptools build_{kind} failed:\n{out.stderr[-3000:]}")
        return Path(into) / out.stdout.strip().splitlines()[-1]


def tracked():
    """The clone's files under version control (as they are in the work tree): the sdist's candidates."""
    out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True)
    return [name for name in out.stdout.decode().split("\0") if name and (ROOT / name).is_file()]


def record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def platform_wheel(pure, bundle, tag, out):
    """`pure` (py3-none-any) with `bundle` as rocking/_bundled, tagged py3-none-`tag`; its path."""
    with zipfile.ZipFile(pure) as z:
        files = {i.filename: (z.read(i), i.external_attr >> 16) for i in z.infolist()}
    dist_info = next(n.split("/")[0] for n in files if n.endswith(".dist-info/WHEEL"))
    wheel_text = files[f"{dist_info}/WHEEL"][0].decode()
    lines = [ln for ln in wheel_text.splitlines() if not ln.startswith(("Root-Is-Purelib:", "Tag:"))]
    lines += ["Root-Is-Purelib: false", f"Tag: py3-none-{tag}"]
    files[f"{dist_info}/WHEEL"] = (("\n".join(lines) + "\n").encode(), 0o644)
    third_party = Path(bundle) / THIRD_PARTY
    if third_party.is_file():
        files[f"{dist_info}/licenses/{THIRD_PARTY}"] = (third_party.read_bytes(), 0o644)
        meta = files[f"{dist_info}/METADATA"][0].decode()
        head, sep, body = meta.partition("\n\n")
        files[f"{dist_info}/METADATA"] = ((head + f"\nLicense-File: {THIRD_PARTY}" + sep + body).encode(), 0o644)
    for path in sorted(Path(bundle).rglob("*")):
        if path.is_file():
            name = "rocking/_bundled/" + path.relative_to(bundle).as_posix()
            executable = path.suffix in ("", ".so", ".exe", ".dll") and path.name != "README.md"
            files[name] = (path.read_bytes(), 0o755 if executable else 0o644)
    record = f"{dist_info}/RECORD"
    files.pop(record, None)
    names = sorted(n for n in files if not n.startswith(dist_info)) + sorted(n for n in files if n.startswith(dist_info))
    text = "".join(record_line(n, files[n][0]) + "\n" for n in names) + f"{record},,\n"
    target = Path(out) / f"{dist_info.removesuffix('.dist-info')}-py3-none-{tag}.whl"
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as z:
        for name in [*names, record]:
            data, mode = files[name] if name != record else (text.encode(), 0o644)
            info = zipfile.ZipInfo(name, EPOCH)
            info.external_attr = (0o100000 | (mode or 0o644)) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, data)
    return target


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bundle", help="the staged rocking/_bundled folder")
    parser.add_argument("--plat", help="platform tag: manylinux2014_x86_64, win_amd64")
    parser.add_argument("--sdist", action="store_true", help="write the sdist instead")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.sdist:
        path = build("sdist", out)
    else:
        if not (args.bundle and args.plat):
            parser.error("--bundle and --plat, or --sdist")
        with tempfile.TemporaryDirectory() as tmp:
            path = platform_wheel(build("wheel", tmp), args.bundle, args.plat, out)
    print(f"{path} ({path.stat().st_size} bytes)")


if __name__ == "__main__":
    main()
