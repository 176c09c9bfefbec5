"""The corner macroblock as a rocking body, on a simulated tilting table.

`rocking-corner --body FILE` (the corner crate, docs/corner.md) writes a
macroblock's body as RockingBlock FMU parameters. Given to the packaged FMU on a
rigid interface under a slow ramp of ground acceleration ag(t) (a tilting table:
the tests ran at 0.02 deg/s near collapse), the body must stay at rest until
ag = lambda g and start rotating within 1e-3 g after it, where lambda is the
limit-analysis multiplier the binary reports (for the threshold-matched body) or
the dissipation-free b/hG (for the geometric body). The multipliers come from the
limit analysis; the FMU only sees W, hG, Ic and B: the test checks that the two
links of the chain agree.
"""

import json
import math
import pathlib
import subprocess
import sys

import pytest

from fmu_helpers import Host

ROOT = pathlib.Path(__file__).resolve().parent.parent
G = 9.81
V = 0.1149 / 2  # half block of the paper's specimen (m)
H_COURSE = 0.0703


def rocking_corner(*args):
    """Runs the corner binary (built by cargo if needed); returns (stdout, stderr)."""
    cmd = ["cargo", "run", "--quiet", "--release", "-p", "corner", "--bin", "rocking-corner", "--"]
    out = subprocess.run(cmd + list(args), cwd=ROOT, check=True, capture_output=True, text=True)
    return out.stdout, out.stderr


def body(tmp_path, kind, alpha, extra=()):
    """The FMU parameters of one body and the limit-analysis record of its orientation."""
    path = tmp_path / f"body_{kind}.json"
    stdout, _ = rocking_corner("--alpha", repr(alpha), "--json", "--body", str(path),
                               "--body-kind", kind, *extra)
    record = json.loads(stdout.splitlines()[-1])
    return json.loads(path.read_text()), record


def first_motion(fmu_path, unzipped, params, lam, window=0.01, rate=0.01, dt=0.005):
    """ag/g at the first step whose end shows rotation, on a ramp of `rate` g/s started at
    (lam - window) g; also asserts the body was exactly at rest before."""
    host = Host(fmu_path, unzipped, name="tilting_table")
    try:
        host.init(**params)
        t = 0.0
        ag0 = (lam - window) * G
        steps = int(math.ceil(2 * window / rate / dt))
        for _ in range(steps):
            ag = ag0 + rate * G * t
            host.set(ag=ag)
            host.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=dt)
            t += dt
            if host.get("theta") != 0.0 or host.get("omega") != 0.0:
                return ag / G
        return math.inf
    finally:
        host.free()


def check_onset(fmu_path, unzipped, params, lam):
    onset = first_motion(fmu_path, unzipped, params, lam)
    # At rest up to lambda g, moving within 1e-3 g after it.
    assert lam <= onset <= lam + 1e-3, (onset, lam)
    return onset


def test_pure_rocking_mechanism_starts_at_its_multiplier(fmu_path, unzipped, tmp_path):
    # m = 0, every crack at the running-bond step: no dissipation, lambda = b/hG.
    geometry = ",".join(repr(x) for x in (V, 8 * V, V, 8 * V, V, V, H_COURSE))
    params, record = body(tmp_path, "geometric", math.pi / 2,
                          ("--m", "0", "--geometry", geometry))
    lam = record["lambda_alpha"]
    assert abs(lam - 0.284844) < 1e-6  # the reference implementation
    assert abs(params["B"] / 2 / params["hG"] - lam) < 1e-12
    check_onset(fmu_path, unzipped, params, lam)


@pytest.mark.parametrize("kind", ["threshold", "geometric"])
def test_pi_2_optimum_bodies_start_at_their_thresholds(fmu_path, unzipped, tmp_path, kind):
    params, record = body(tmp_path, kind, math.pi / 2)
    la = record["lambda_Y"]  # at pi/2 the body's direction carries the whole load
    assert abs(record["lambda_alpha"] - la) < 1e-12
    # The geometric body ignores friction and torsion: it uplifts at b/hG < lambda.
    lam = la if kind == "threshold" else params["B"] / 2 / params["hG"]
    if kind == "geometric":
        assert lam < 0.7 * la
    check_onset(fmu_path, unzipped, params, lam)


def run_example(name, *args):
    cmd = [sys.executable, str(ROOT / "examples" / name), *args]
    return subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout


def test_corner_study_example_draws_its_figures(tmp_path):
    out = run_example("corner_study.py", "--out", str(tmp_path), "--beyond")
    rows = [line.split() for line in out.splitlines()[1:6]]
    # The paper's five orientations, the multiplier falling from pi/4 to pi/2.
    lam = [float(r[1]) for r in rows]
    assert len(lam) == 5 and all(b < a for a, b in zip(lam, lam[1:])), out
    for png in ("corner_lambda_alpha.png", "corner_macroblocks.png", "corner_unequal_walls.png"):
        assert (tmp_path / png).stat().st_size > 10_000


def test_corner_rocking_example_overturns_above_the_uplift_threshold(tmp_path):
    out = run_example("corner_rocking.py", "--out", str(tmp_path))
    rows = {line.split()[0]: [float(x) for x in line.split()[1:]]
            for line in out.splitlines() if line.strip().startswith(("geometric", "threshold"))}
    assert set(rows) == {"geometric", "threshold"}, out
    for kind, (uplift, below, above) in rows.items():
        # A rigid block cannot even leave its base before |ag| reaches its threshold, so no
        # record with a smaller peak can overturn it.
        assert below < above and above >= uplift, (kind, uplift, below, above)
    assert rows["geometric"][0] < rows["threshold"][0]
