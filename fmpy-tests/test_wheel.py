"""The platform wheels of `cargo xtask wheel` (issue 24): installable without the clone.

The Linux wheel is installed into a new venv in a temporary folder outside the
clone, with no Rust toolchain on PATH; a simulate, a corner and a two-case
sweep run there, from the wheel's own FMU, stepping loop, rocking-corner and
sample records. The second host of each answer is the clone itself: the same
commands through the editable install and target/release give the same
numbers. The Windows wheel is checked by its contents and tags (it is not run
here): PE binaries for x86-64, the FMUs' win64 folders, RECORD's hashes
recomputed. The packaging checks `twine check` and `auditwheel show` run on
both.

tools/wheel-check.sh runs this file (tools/test.sh leaves it out: the
helpers' cross builds are 155 s cold, 7 s warm). The FMUs are the ones
`cargo xtask fmu` wrote (`--reuse-fmus`).
"""

import base64
import hashlib
import io
import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import tomllib
import zipfile
from pathlib import Path

import pandas as pd
import pytest

from test_cli import REPO, ok

WHEELS = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
WHEELS = (WHEELS if WHEELS.is_absolute() else REPO / WHEELS) / "wheels"
VENV_BIN = Path(sys.executable).parent


@pytest.fixture(scope="module")
def wheels():
    """{tag: path} of the wheels `cargo xtask wheel --reuse-fmus` writes, and the sdist."""
    proc = subprocess.run(["cargo", "xtask", "wheel", "--reuse-fmus"], cwd=REPO, capture_output=True,
                          text=True, timeout=900)
    assert proc.returncode == 0, proc.stderr[-3000:]
    found = {p.name.split("-")[-1].removesuffix(".whl"): p for p in WHEELS.glob("rocking-*.whl")}
    found["sdist"] = next(WHEELS.glob("rocking-*.tar.gz"))
    return found


@pytest.fixture(scope="module")
def sdist(tmp_path_factory):
    """The sdist as tools/wheel.py writes it (8 s), unpacked into a folder outside the clone."""
    out = tmp_path_factory.mktemp("sdist")
    subprocess.run([sys.executable, REPO / "tools" / "wheel.py", "--sdist", "--out", out], check=True,
                   capture_output=True)
    with tarfile.open(next(out.glob("rocking-*.tar.gz"))) as tar:
        tar.extractall(out / "unpacked", filter="data")
    return next((out / "unpacked").iterdir())


def test_sdist_carries_every_workspace_member(sdist):
    """Each member Cargo.toml names, and every source file cargo builds a target from, is in the sdist."""
    members = tomllib.loads((REPO / "Cargo.toml").read_text())["workspace"]["members"]
    missing = [m for m in members if not (sdist / m / "Cargo.toml").is_file()]
    assert not missing, f"MANIFEST.in leaves out the workspace members {missing}"
    meta = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps", "--offline"], cwd=REPO,
                          capture_output=True, text=True, check=True)
    # the sdist is made of the committed files: a source file not yet added to git is not its concern
    tracked = set(subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True,
                                 check=True).stdout.splitlines())
    sources = {Path(t["src_path"]).relative_to(REPO) for p in json.loads(meta.stdout)["packages"]
               for t in p["targets"]}
    sources = {s for s in sources if s.as_posix() in tracked}
    assert len(sources) > 20
    assert not [s for s in sources if not (sdist / s).is_file()]


def test_sdist_workspace_loads(sdist):
    """cargo reads the unpacked sdist's workspace and resolves it from its lock file as it is (no network)."""
    proc = subprocess.run(["cargo", "tree", "--workspace", "--locked", "--offline", "--target",
                           "x86_64-unknown-linux-gnu", "--edges", "normal,build", "--prefix", "none"], cwd=sdist,
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-2000:]
    names = {line.split()[0] for line in proc.stdout.splitlines() if line.strip()}
    assert {"fmu-rocking", "fmi3-export", "corner", "xtask", "serde"} <= names


def _members(wheel):
    with zipfile.ZipFile(wheel) as z:
        return {i.filename: z.read(i) for i in z.infolist()}


def _dist_info(files, name):
    return next(v for k, v in files.items() if k.endswith(f".dist-info/{name}")).decode()


def test_packaging_tools_accept_the_wheels(wheels):
    twine = subprocess.run([VENV_BIN / "twine", "check", "--strict", wheels["manylinux2014_x86_64"],
                            wheels["win_amd64"], wheels["sdist"]], capture_output=True, text=True)
    assert twine.returncode == 0, twine.stdout + twine.stderr
    audit = subprocess.run([VENV_BIN / "auditwheel", "show", wheels["manylinux2014_x86_64"]],
                           capture_output=True, text=True)
    assert audit.returncode == 0, audit.stderr
    # the stepping loop and rocking-corner link glibc 2.17 at most: the manylinux2014 baseline
    assert '"manylinux_2_17_x86_64"' in " ".join(audit.stdout.split()), audit.stdout
    for tag in ("manylinux2014_x86_64", "win_amd64"):
        meta = _dist_info(_members(wheels[tag]), "METADATA")
        assert "License-Expression: MIT OR Apache-2.0" in meta
        assert "License-File: LICENSE-APACHE" in meta and "Classifier: Topic :: Scientific/Engineering" in meta


def test_record_hashes_every_member(wheels):
    """RECORD lists every member with its sha256 and size, recomputed here."""
    for tag in ("manylinux2014_x86_64", "win_amd64"):
        files = _members(wheels[tag])
        rows = [line.split(",") for line in _dist_info(files, "RECORD").splitlines()]
        listed = {name for name, *_ in rows}
        assert listed == set(files), listed ^ set(files)
        for name, digest, size in rows:
            if name.endswith("RECORD"):
                continue
            want = base64.urlsafe_b64encode(hashlib.sha256(files[name]).digest()).rstrip(b"=").decode()
            assert digest == f"sha256={want}" and int(size) == len(files[name]), name


def test_windows_wheel_contents_and_tags(wheels):
    files = _members(wheels["win_amd64"])
    wheel = _dist_info(files, "WHEEL")
    assert "Tag: py3-none-win_amd64" in wheel and "Root-Is-Purelib: false" in wheel
    bundle = "rocking/_bundled/"
    for exe in ("target/release/fmu_stepper.dll", "target/release/rocking-corner.exe"):
        data = files[bundle + exe]
        pe = int.from_bytes(data[0x3C:0x40], "little")  # the PE header's offset (MS-DOS stub)
        assert data[:2] == b"MZ" and data[pe:pe + 4] == b"PE\0\0", exe
        assert int.from_bytes(data[pe + 4:pe + 6], "little") == 0x8664, f"{exe}: not x86-64"
        # stripped: the COFF header's PointerToSymbolTable and NumberOfSymbols
        assert data[pe + 12:pe + 20] == bytes(8), f"{exe}: a COFF symbol table"
    _check_fmus_and_records(files, bundle)
    assert not any(name.endswith((".so", ".so.1")) for name in files), "a Linux library in the Windows wheel"


def _check_fmus_and_records(files, bundle):
    """Both models in both standards, where `cargo xtask fmu` writes them (paths.target_dir()/fmu and fmu/fmi3)."""
    for model in ("RockingBlock", "ShearFrame"):
        for folder, version, linux, windows in (("", "2.0", "linux64", "win64"),
                                                 ("fmi3/", "3.0", "x86_64-linux", "x86_64-windows")):
            with zipfile.ZipFile(io.BytesIO(files[f"{bundle}target/fmu/{folder}{model}.fmu"])) as fmu:
                names = set(fmu.namelist())
                xml = fmu.read("modelDescription.xml").decode()
            assert {f"binaries/{linux}/{model}.so", f"binaries/{windows}/{model}.dll"} <= names, (model, version)
            assert f'fmiVersion="{version}"' in xml, (model, version)
    for record in ("katnp-standin/KATNP_NS_standin.csv", "usgs-lomaprieta-1989/0111a.smc", "README.md"):
        assert files[f"{bundle}data/ground-motions/{record}"] == (REPO / "data/ground-motions" / record).read_bytes()
    assert "Provenance and terms" in files[f"{bundle}data/ground-motions/README.md"].decode()
    _check_examples(files, bundle)


def _check_examples(files, bundle):
    """The README's study files, as in the clone, and what they name found beside them in the bundle."""
    for name in ("examples/fragility.toml", "examples/sweep.toml", "examples/hazard-illustrative.csv",
                 *(p.relative_to(REPO).as_posix() for p in (REPO / "examples/cosim").glob("*.toml"))):
        assert files.get(bundle + name) == (REPO / name).read_bytes(), name
    study = tomllib.loads(files[bundle + "examples/fragility.toml"].decode())
    for path in [*study["records"], study["hazard"]]:
        resolved = os.path.normpath(f"{bundle}examples/{path}")
        assert any(n == resolved or n.startswith(resolved + "/") for n in files), f"fragility.toml: {path}"


def _binaries(files):
    """{name: bytes} of every native binary of a wheel: its own and those of the FMUs it carries."""
    found = {}
    for name, data in files.items():
        if data[:4] == b"\x7fELF" or data[:2] == b"MZ":
            found[name] = data
        elif name.endswith(".fmu"):
            with zipfile.ZipFile(io.BytesIO(data)) as fmu:
                found.update({f"{name}:{i}": fmu.read(i) for i in fmu.namelist() if i.startswith("binaries/")})
    return found


def test_binaries_do_not_carry_the_build_folder(wheels):
    """No binary of either wheel (stepping loop, rocking-corner, the FMUs' libraries) names where it was built."""
    folders = {str(REPO).encode(), str(WHEELS.parent).encode()}
    for tag in ("manylinux2014_x86_64", "win_amd64"):
        binaries = _binaries(_members(wheels[tag]))
        # the stepping loop and rocking-corner; three FMUs x two standards x two platforms
        assert len(binaries) == 2 + 3 * 2 * 2, sorted(binaries)
        leaks = {name: sorted(f.decode() for f in folders if f in data) for name, data in binaries.items()}
        assert not {k: v for k, v in leaks.items() if v}, f"{tag}: build folder in {leaks}"


def test_linux_wheel_contents_and_tags(wheels):
    files = _members(wheels["manylinux2014_x86_64"])
    assert "Tag: py3-none-manylinux2014_x86_64" in _dist_info(files, "WHEEL")
    for exe in ("target/release/libfmu_stepper.so", "target/release/rocking-corner"):
        assert files["rocking/_bundled/" + exe][:4] == b"\x7fELF", exe
    _check_fmus_and_records(files, "rocking/_bundled/")


@pytest.fixture(scope="module")
def installed(wheels, tmp_path_factory):
    """A new venv outside the clone with the Linux wheel installed; (its bin folder, a work folder).

    The wheel goes in with --no-deps; its dependencies are the pinned ones of
    the test's own environment, seen through a .pth line (whose folder's own
    .pth files, among them the editable `rocking`, Python does not run)."""
    home = tmp_path_factory.mktemp("wheel-install")
    assert REPO not in home.parents and not (home / ".git").exists()
    venv = home / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", venv], check=True)
    site = subprocess.run([venv / "bin" / "python", "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                          capture_output=True, text=True, check=True).stdout.strip()
    Path(site, "dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    subprocess.run([sys.executable, "-m", "pip", "--python", venv / "bin" / "python", "install", "--quiet",
                    "--no-deps", "--disable-pip-version-check", wheels["manylinux2014_x86_64"]], check=True)
    work = home / "work"
    work.mkdir()
    return venv / "bin", work


def run_installed(installed, *args):
    """`rocking ARGS` of the new venv, from its work folder, with no Rust (cargo) on PATH."""
    bin_dir, work = installed
    env = {k: v for k, v in os.environ.items() if not k.startswith(("CARGO", "RUSTUP", "VIRTUAL_ENV", "PYTHON"))}
    env["PATH"] = f"{bin_dir}{os.pathsep}/usr/bin{os.pathsep}/bin"
    assert shutil.which("cargo", path=env["PATH"]) is None
    proc = subprocess.run([bin_dir / "rocking", *map(str, args)], cwd=work, env=env, capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 0, f"rocking {' '.join(map(str, args))}: {proc.stderr}"
    return proc


def test_installed_wheel_uses_its_own_files(installed):
    bin_dir, _ = installed
    code = ("import rocking, json; from rocking import paths, stepper; "
            "print(json.dumps([rocking.__file__, str(paths.REPO), stepper.library_path()]))")
    out = subprocess.run([bin_dir / "python", "-c", code], cwd=installed[1], capture_output=True, text=True,
                         check=True).stdout
    module, repo, stepper = json.loads(out)
    assert module.startswith(str(bin_dir.parent)) and repo.endswith("rocking/_bundled"), out
    assert stepper.startswith(repo)
    version = run_installed(installed, "--version").stdout
    head = subprocess.run(["git", "-C", REPO, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    assert f"{repo}/target/fmu/RockingBlock.fmu" in version and f"commit {head}" in version, version


def test_installed_wheel_simulates_as_the_clone(installed, tmp_path):
    record = "KATNP_NS_standin.csv"
    bundled = (Path(installed[0]).parent / "lib").glob(f"python*/site-packages/rocking/_bundled/"
                                                       f"data/ground-motions/katnp-standin/{record}")
    run_installed(installed, "simulate", next(bundled), "--preset", "dharahara-F170-fm5", "--out", "sim")
    ok("simulate", REPO / "data/ground-motions/katnp-standin" / record, "--preset", "dharahara-F170-fm5",
       "--out", tmp_path / "sim")
    wheel = json.loads((installed[1] / "sim" / "summary.json").read_text())
    clone = json.loads((tmp_path / "sim" / "summary.json").read_text())
    assert wheel.keys() == clone.keys()
    assert wheel["fmu"] != clone["fmu"] and wheel["guid"] == clone["guid"]
    for key in ("parameters", "rows", "peak_theta_rad", "t_peak_theta_s", "overturned", "t_overturn_s",
                "impacts", "zeroCrossings", "regimes_reached"):
        assert wheel[key] == clone[key], key
    wheel_rows = pd.read_csv(installed[1] / "sim" / "timehistory.csv")
    pd.testing.assert_frame_equal(wheel_rows, pd.read_csv(tmp_path / "sim" / "timehistory.csv"), check_exact=True)


def test_installed_wheel_runs_corner_as_the_clone(installed):
    args = ["--alpha", "1.570796", "--json"]
    wheel = run_installed(installed, "corner", *args).stdout
    clone = subprocess.run([REPO / "target" / "release" / "rocking-corner", *args], capture_output=True,
                           text=True, check=True).stdout
    assert json.loads(wheel) == json.loads(clone)


def test_installed_wheel_sweeps_two_cases(installed):
    (installed[1] / "cases.toml").write_text('[cases.rigid]\npreset = "dharahara-rigid"\n'
                                             '[cases.soft]\npreset = "dharahara-F170-fm5"\n')
    from rocking import paths  # the clone's
    record = "usgs-lomaprieta-1989/0111a.smc"
    bundled = next((Path(installed[0]).parent / "lib").glob("python*/site-packages/rocking/_bundled"))
    run_installed(installed, "sweep", "cases.toml", "--records", bundled / "data/ground-motions" / record,
                  "--scales", "1", "--out", "sweep.csv", "--workers", "2")
    table = pd.read_csv(installed[1] / "sweep.csv")
    assert sorted(table["case"]) == ["rigid", "soft"]
    assert table["error"].isna().all(), table["error"].tolist()
    assert (paths.data_dir() / record).read_bytes() == (bundled / "data/ground-motions" / record).read_bytes()


#: The Rust targets of the shipped binaries (the wheels and FMUs carry both platforms' FMU libraries).
TARGETS = ("x86_64-unknown-linux-gnu", "x86_64-pc-windows-gnu")
#: A phrase of each licence's text, to tell that a crate's attached text is its licence's.
PHRASES = {"MIT": "permission is hereby granted", "Apache-2.0": "apache license", "Zlib": "provided 'as-is'",
           "BSD-2-Clause": "redistribution and use", "BSD-3-Clause": "redistribution and use",
           "Unicode-3.0": "unicode", "Unlicense": "unlicense", "0BSD": "permission to use, copy, modify",
           "ISC": "permission to use, copy, modify", "BSL-1.0": "boost software license"}


def _crate_graph(packages):
    """{(name, version): licence expression} of what `cargo tree` shows under `packages` (normal edges) for
    either shipped target: an independent reading of the graph the licence file must cover, every crate
    of which Cargo.lock lists."""
    locked = {(p["name"], p["version"]) for p in tomllib.loads((REPO / "Cargo.lock").read_text())["package"]}
    graph = {}
    for target in TARGETS:
        args = ["cargo", "tree", "--locked", "--edges", "normal", "--target", target, "--prefix", "none",
                "--format", "{p}|{l}"]
        for package in packages:
            args += ["--package", package]
        out = subprocess.run(args, cwd=REPO, capture_output=True, text=True, check=True).stdout
        for line in filter(str.strip, out.splitlines()):
            package, licence = line.removesuffix(" (*)").split("|", 1)
            name, version = package.split()[:2]
            graph[(name, version.removeprefix("v"))] = licence.strip()
    assert set(graph) <= locked, set(graph) - locked
    return graph


def _check_licences(text, packages, where):
    """Every crate of the graph listed with its expression and at least one attached text of one of its
    licences."""
    rows = re.findall(r"^  (\S+) (\S+): (.*) \[texts ([\d, ]+)\]$", text, re.MULTILINE)
    listed = {(name, version): (expression, [int(k) for k in numbers.split(",")])
              for name, version, expression, numbers in rows}
    parts = re.split(r"^== Text (\d+): .*$", text, flags=re.MULTILINE)
    texts = {int(k): body.lower() for k, body in zip(parts[1::2], parts[2::2])}
    graph = _crate_graph(packages)
    assert set(listed) == set(graph), f"{where}: {set(graph) ^ set(listed)}"
    for crate, licence in graph.items():
        expression, numbers = listed[crate]
        assert expression.startswith(licence), (where, crate, expression, licence)
        ids = set(re.findall(r"[A-Za-z0-9.+-]+", licence)) - {"OR", "AND", "WITH"}
        unknown = ids - PHRASES.keys()
        assert not unknown, f"{where}: {crate} {unknown}: add a phrase of its text to PHRASES"
        bodies = [texts[k] for k in numbers]
        assert any(PHRASES[i] in b and len(b) > 300 for i in ids for b in bodies), \
            f"{where}: {crate}: no text of {licence}"
    return len(listed)


def test_wheels_list_the_licences_of_their_crates(wheels):
    shipped = ["fmu-rocking", "fmu-shear-frame", "fmu-round-body", "fmu-stepper", "corner"]
    for tag in ("manylinux2014_x86_64", "win_amd64"):
        files = _members(wheels[tag])
        text = files["rocking/_bundled/THIRD-PARTY-LICENSES.txt"]
        assert _dist_info(files, "licenses/THIRD-PARTY-LICENSES.txt").encode() == text
        assert "License-File: THIRD-PARTY-LICENSES.txt" in _dist_info(files, "METADATA")
        assert _check_licences(text.decode(), shipped, tag) > 50
        # mingw-w64's runtime is linked into the win64 binaries only (test_model_description.py)
        runtime = "The C runtime of the win64 binaries" in text.decode()
        assert runtime == (tag == "win_amd64"), tag


def test_fmus_list_the_licences_of_their_crates(wheels):
    """Each archive's documentation/licenses/license.txt covers its own library's graph (the wheels
    fixture wrote the FMUs)."""
    for model, package in (("RockingBlock", "fmu-rocking"), ("ShearFrame", "fmu-shear-frame"),
                           ("RoundBody", "fmu-round-body")):
        for folder in ("", "fmi3/"):
            with zipfile.ZipFile(WHEELS.parent / "fmu" / f"{folder}{model}.fmu") as fmu:
                text = fmu.read("documentation/licenses/license.txt").decode()
            # at least the project's own: the FMU crate, fmi2-export, fmi3-export, model-description, the engine
            assert _check_licences(text, [package], f"{folder}{model}.fmu") >= 5


def test_installed_wheel_cosims_fmi3_from_its_example(installed, tmp_path):
    """`cosim --fmi 3` on the wheel's own examples/cosim/roof_block.toml finds the wheel's 3.0 archives
    (paths.target_dir()/fmu/fmi3) and gives the clone's rows."""
    bundled = next((Path(installed[0]).parent / "lib").glob("python*/site-packages/rocking/_bundled"))
    case = bundled / "examples" / "cosim" / "roof_block.toml"
    run_installed(installed, "cosim", case, "--fmi", "3", "--out", "cosim3")
    code = ("from rocking import paths; print(sorted(str(p) for p in (paths.target_dir() / 'fmu' / 'fmi3')"
            ".glob('*.fmu')))")
    found = subprocess.run([installed[0] / "python", "-c", code], cwd=installed[1], capture_output=True,
                           text=True, check=True).stdout
    assert f"{bundled}/target/fmu/fmi3/RockingBlock.fmu" in found and "fmi3/ShearFrame.fmu" in found, found
    ok("cosim", REPO / "examples" / "cosim" / "roof_block.toml", "--fmi", "3", "--out", tmp_path / "cosim3")
    wheel = pd.read_csv(installed[1] / "cosim3" / "timehistory.csv")
    pd.testing.assert_frame_equal(wheel, pd.read_csv(tmp_path / "cosim3" / "timehistory.csv"), check_exact=True)
