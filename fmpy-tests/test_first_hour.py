"""A wheel user's first hour (issue 33): `rocking examples`, the README's "From the wheel"
commands, folder scans over a bundle with pip's caches, help texts that hold without a clone.

The installed wheel is stood in for by a copy of the package whose rocking/_bundled is laid
out as `cargo xtask wheel` stages it: BUILD.json, the clone's FMUs and stepping loop, the
record folders xtask/src/wheel.rs names in RECORDS (with the generator's .pyc that pip's
install writes beside it), and examples/. That copy goes first on PYTHONPATH under the venv's
`rocking` command, so paths.py takes the bundle as it does in a wheel (checked through
`rocking --version`, which names the bundle's commit). The wheel itself is tested by
test_wheel.py.

What the outputs are checked against: git's list of the clone's files, the study files'
own paths read with tomllib, the record's header (PGA), and the README's command lines.
"""

import json
import os
import py_compile
import re
import shlex
import shutil
import subprocess
import tomllib
from pathlib import Path

import pandas as pd
import pytest

from test_cli import KATNP, REPO, ok, rocking, rocking_exe

TARGET = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
TARGET = TARGET if TARGET.is_absolute() else REPO / TARGET
COMMIT = "first-hour-bundle"  # BUILD.json's commit in the stand-in, so --version shows the bundle is used


def _wheel_list(name):
    """The entries of xtask/src/wheel.rs's `const NAME: [&str; N] = [...]`, or None without one."""
    text = (REPO / "xtask" / "src" / "wheel.rs").read_text()
    found = re.search(rf"const {name}: \[&str; \d+\] = \[([^\]]*)\];", text)
    return re.findall(r'"([^"]+)"', found.group(1)) if found else None


def wheel_records():
    """The entries of data/ground-motions a wheel carries."""
    found = _wheel_list("RECORDS")
    assert found, "xtask/src/wheel.rs: no `const RECORDS` list of the wheel's record folders"
    return found


@pytest.fixture(scope="module")
def bundled(tmp_path_factory):
    """(environment running the package as a wheel installs it, its _bundled folder)."""
    fmu = TARGET / "fmu" / "RockingBlock.fmu"
    if not fmu.is_file():
        pytest.fail(f"{fmu} not found: run `cargo xtask fmu` first", pytrace=False)
    site = tmp_path_factory.mktemp("site")
    shutil.copytree(REPO / "python" / "rocking", site / "rocking",
                    ignore=shutil.ignore_patterns("__pycache__", "_bundled"))
    bundle = site / "rocking" / "_bundled"
    (bundle / "target" / "release").mkdir(parents=True)
    (bundle / "BUILD.json").write_text(json.dumps({"commit": COMMIT}))
    (bundle / "target" / "fmu").symlink_to(TARGET / "fmu", target_is_directory=True)
    for helper in ("libfmu_stepper.so", "rocking-corner"):
        if (TARGET / "release" / helper).is_file():
            (bundle / "target" / "release" / helper).symlink_to(TARGET / "release" / helper)
    for entry in wheel_records():
        src, dst = REPO / "data" / "ground-motions" / entry, bundle / "data" / "ground-motions" / entry
        dst.parent.mkdir(parents=True, exist_ok=True)
        (shutil.copytree if src.is_dir() else shutil.copy)(src, dst)
    for script in (bundle / "data").rglob("*.py"):  # pip compiles every .py it installs
        py_compile.compile(str(script), doraise=True)
    assert list((bundle / "data").rglob("__pycache__/*.pyc")), "the stand-in lacks pip's compiled cache"
    examples = _wheel_list("EXAMPLES") or [p.name for p in (REPO / "examples").iterdir()]
    for entry in examples:
        src, dst = REPO / "examples" / entry, bundle / "examples" / entry
        dst.parent.mkdir(parents=True, exist_ok=True)
        (shutil.copytree if src.is_dir() else shutil.copy)(src, dst)
    env = {k: v for k, v in os.environ.items() if k not in ("CARGO_TARGET_DIR", "ROCKING_STEPPER")}
    env["PYTHONPATH"] = str(site)
    version = ok("--version", env=env, cwd=site).stdout
    assert COMMIT in version and str(bundle) in version, version
    return env, bundle


# ---------------------------------------------------------------------------
# rocking examples DIR, in a clone

def _files(folder):
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()}


def _git_files(*patterns):
    out = subprocess.run(["git", "ls-files", "--", *patterns], cwd=REPO, capture_output=True, text=True,
                         check=True).stdout.split()
    return set(out)


def test_examples_in_a_clone_copies_every_record_and_the_study_files(tmp_path):
    dest = tmp_path / "study"
    proc = ok("examples", dest, cwd=tmp_path)
    expected = _git_files("data/ground-motions") | _git_files("examples/*.toml", "examples/*.csv")
    assert any(f.startswith("examples/cosim/") for f in expected)
    assert _files(dest) == expected
    for rel in expected:
        assert (dest / rel).read_bytes() == (REPO / rel).read_bytes(), rel
    # it says what it wrote and what to run, from the folder it wrote
    assert f"{len(expected)} file(s) written to {dest}" in proc.stdout
    assert f"cd {dest}" in proc.stdout and "rocking ida examples/fragility.toml" in proc.stdout


def _study_paths(study):
    """The files and folders a study or case file names, relative to itself."""
    data = tomllib.loads(study.read_text())
    named = data.get("records", [])
    named = [named] if isinstance(named, str) else list(named)
    named += [data[k] for k in ("hazard",) if k in data]
    named += [data.get("ground", {}).get("record")] if "record" in data.get("ground", {}) else []
    return [study.parent / n for n in named]


def test_copied_studies_find_their_records(tmp_path):
    """Every path a copied study names exists in the copy, and the study's suite is the clone's."""
    from rocking.fragility.suite import load_suite
    dest = tmp_path / "study"
    ok("examples", dest, cwd=tmp_path)
    named = [p for study in (dest / "examples").rglob("*.toml") for p in _study_paths(study)]
    assert named, "no study file names a record or a hazard curve"
    missing = [str(p.relative_to(dest)) for p in named if not p.exists()]
    assert not missing
    suite = load_suite(_study_paths(dest / "examples" / "fragility.toml")[:1])
    assert sorted(suite) == sorted(load_suite([REPO / "data" / "ground-motions"]))
    # a README command, run from the copy as written there
    out = ok("sweep", "examples/sweep.toml", "--records", "data/ground-motions/katnp-standin", "--scales", "1",
             "--out", "out/katnp.csv", cwd=dest)
    table = pd.read_csv(dest / "out" / "katnp.csv")
    assert len(table) == len(tomllib.loads((dest / "examples" / "sweep.toml").read_text())["cases"]), out.stderr
    assert (table["error"].fillna("") == "").all()


def test_examples_does_not_overwrite_without_force(tmp_path):
    dest = tmp_path / "study"
    ok("examples", dest, cwd=tmp_path)
    edited, mine = dest / "examples" / "sweep.toml", dest / "examples" / "mine.toml"
    edited.write_text(edited.read_text() + "\n# my change\n")
    mine.write_text("# mine\n")
    before = edited.read_bytes()
    proc = rocking("examples", dest, cwd=tmp_path)
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1
    assert "examples/sweep.toml" in proc.stderr and "--force" in proc.stderr
    assert edited.read_bytes() == before
    again = ok("examples", dest, "--force", cwd=tmp_path)
    assert "1 file(s) written" in again.stdout
    assert edited.read_bytes() == (REPO / "examples" / "sweep.toml").read_bytes()
    assert mine.read_text() == "# mine\n"


# ---------------------------------------------------------------------------
# As a wheel installs it

def test_bundled_record_folders_with_pips_cache_sweep(bundled, tmp_path):
    """The issue's symptom: sweep over the installed records, beside the generator's .pyc."""
    env, bundle = bundled
    cases = tmp_path / "cases.toml"
    cases.write_text('[cases.rigid]\npreset = "dharahara-rigid"\n')
    ok("sweep", cases, "--records", bundle / "data" / "ground-motions", "--scales", "1", "--out", tmp_path / "r.csv",
       env=env, cwd=tmp_path)
    table = pd.read_csv(tmp_path / "r.csv")
    # katnp's NS; Loma Prieta's 360 and 270 (0111b is its vertical), as data/ground-motions/README.md lists
    assert len(table) == 3 and (table["error"].fillna("") == "").all()


def readme_from_the_wheel():
    """The lines of the README's "From the wheel" code block."""
    text = (REPO / "README.md").read_text()
    section = re.search(r"^## From the wheel\n(.*?)^## ", text, re.S | re.M)
    assert section, "README.md: no section `## From the wheel`"
    block = re.search(r"```sh\n(.*?)```", section.group(1), re.S)
    assert block, "README.md, From the wheel: no ```sh block"
    return [line for line in block.group(1).splitlines() if line.strip()]


def test_readme_from_the_wheel_runs_as_written(bundled, tmp_path):
    env, bundle = bundled
    lines = readme_from_the_wheel()
    install = shlex.split(lines[0], comments=True)
    assert install[:2] == ["pip", "install"] and re.fullmatch(r"rocking-[\w.]+-py3-none-manylinux2014_x86_64\.whl",
                                                                install[2]), lines[0]
    # the rest as written, in an empty folder, with the venv's `rocking` first on PATH
    env = {**env, "PATH": f"{Path(rocking_exe()).parent}{os.pathsep}{env['PATH']}"}
    script = "set -e\n" + "\n".join(lines[1:]) + "\n"
    proc = subprocess.run(["bash", "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "Traceback" not in proc.stderr
    cd = [shlex.split(line) for line in lines if line.startswith("cd ")]
    assert len(cd) == 1
    here = tmp_path / cd[0][1]
    # the copy: the wheel's record folders, no cache, the study files
    assert sorted(p.name for p in (here / "data" / "ground-motions").iterdir()) == sorted(wheel_records())
    assert not list(here.rglob("__pycache__")) and not list(here.rglob("*.pyc"))
    assert (here / "examples" / "fragility.toml").is_file()
    # simulate: the bundle's FMU, the record's PGA from its header line "PGA 0.174 g", times --scale 1.5
    summary = json.loads((here / "out" / "sim" / "summary.json").read_text())
    assert Path(summary["fmu"]).parent == bundle / "target" / "fmu"
    header_pga = float(re.search(r"PGA ([\d.]+) g", KATNP.read_text()).group(1))
    assert summary["record"]["scaled_pga_g"] == pytest.approx(1.5 * header_pga, abs=1.5 * 0.0005)
    # sweep: cases x Loma Prieta's two horizontal components (0111b.smc is its vertical, as
    # data/ground-motions/README.md lists) x the 4 scales of 0.5:2:0.5
    sweep = pd.read_parquet(here / "out" / "sweep.parquet")
    n_cases = len(tomllib.loads((here / "examples" / "sweep.toml").read_text())["cases"])
    assert len(sweep) == n_cases * 2 * 4 and (sweep["error"].fillna("") == "").all()
    # ida: the study's bodies over the records the copy holds (katnp's NS, Loma Prieta's 360 and 270)
    study = json.loads((here / "out" / "fragility-ida" / "summary.json").read_text())
    bodies = tomllib.loads((here / "examples" / "fragility.toml").read_text())["bodies"]
    assert set(study["bodies"]) == set(bodies)
    assert len(study["records"]) == 3 and study["failed_runs"] == 0 and study["runs"] > 0


# ---------------------------------------------------------------------------
# Help texts

def _parsers(parser, prefix="rocking"):
    """(command line, parser) of `parser` and of every subcommand under it."""
    import argparse
    yield prefix, parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _parsers(sub, f"{prefix} {name}")


def test_help_texts_hold_for_a_wheel_user():
    """An option's help that names a clone's path (target/, the repository) names the wheel's too."""
    from rocking.cli.main import build_parser
    wrong = []
    for command, parser in _parsers(build_parser()):
        for action in parser._actions:
            text = " ".join(str(action.help or "").split())
            if re.search(r"target/|repositor", text) and "wheel" not in text:
                wrong.append(f"{command} {'/'.join(action.option_strings) or action.dest}: {text}")
    assert not wrong, "\n".join(wrong)
