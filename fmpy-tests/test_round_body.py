"""The packaged RoundBody FMU (target/fmu/RoundBody.fmu and fmi3/RoundBody.fmu)
through fmpy: both archives validate, a run under two horizontal components
goes through simulate_fmu in both standards, and the response to an input
rotated by an angle is the response rotated by it (an invariance of the
physics: the bed and the body are round), against the unrotated run."""

import math

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from conftest import TARGET

FMU2 = TARGET / "fmu" / "RoundBody.fmu"
FMU3 = TARGET / "fmu" / "fmi3" / "RoundBody.fmu"
OUTPUTS = ["theta", "psi", "ex", "ey", "omegaX", "omegaY", "omegaZ", "xG", "yG", "Fx", "Fy", "Fz",
           "frictionDemand", "regime", "impacts", "overturned"]
# g tan(alpha) of the default drum (Ro 0.5 m, H 3 m): the uplift threshold, m/s2
UPLIFT = 9.81 / 3.0
STOP = 4.0


@pytest.fixture(scope="module")
def archives():
    for path in (FMU2, FMU3):
        if not path.is_file():
            pytest.fail(f"{path} not found: run `cargo xtask fmu` first", pytrace=False)
    return str(FMU2), str(FMU3)


def ground(beta=0.0):
    """Two horizontal components that rock the drum off any plane, rotated by beta (rad), and a
    vertical one, every 5 ms."""
    t = np.arange(0.0, STOP + 1e-9, 0.005)
    decay = np.exp(-0.25 * t)
    ax = 1.5 * UPLIFT * np.sin(2 * math.pi * 1.3 * t) * decay
    ay = 1.1 * UPLIFT * np.sin(2 * math.pi * 0.9 * t + 0.4) * decay
    c, s = math.cos(beta), math.sin(beta)
    names = ("time", "agx", "agy", "av")
    signal = np.zeros(len(t), dtype=[(n, np.float64) for n in names])
    signal["time"], signal["agx"], signal["agy"] = t, c * ax - s * ay, s * ax + c * ay
    signal["av"] = 1.5 * np.sin(2 * math.pi * 3.1 * t)
    return signal


def run(path, beta=0.0):
    return simulate_fmu(path, stop_time=STOP, output_interval=0.01, input=ground(beta), output=OUTPUTS)


def test_both_archives_validate(archives):
    for path in archives:
        assert validate_fmu(path) == [], path
    md2, md3 = (read_model_description(p) for p in archives)
    assert md2.coSimulation.modelIdentifier == md3.coSimulation.modelIdentifier == "RoundBody"
    assert md3.instantiationToken == md2.guid
    inputs = {v.name for v in md2.modelVariables if v.causality == "input"}
    assert inputs == {"agx", "agy", "av"}
    assert {f"der({n})" for n in inputs} <= {v.name for v in md3.modelVariables}


def test_two_components_run_in_both_standards(archives):
    r2, r3 = (run(p) for p in archives)
    assert r2["time"][-1] == pytest.approx(STOP) and len(r2) == len(r3)
    moving = r2["theta"] > 0.01
    assert r2["theta"].max() > 0.05 and not r2["overturned"].any()
    # off a plane: the lean's azimuth turns through more than a radian
    assert np.ptp(np.unwrap(r2["psi"][moving])) > 1.0
    # the outputs hang together: theta = asin|e|, and the lean (ex, ey) points along psi
    e = np.hypot(r2["ex"], r2["ey"])
    np.testing.assert_allclose(np.sin(r2["theta"]), e, rtol=0, atol=1e-15)
    np.testing.assert_allclose(np.cos(r2["psi"][moving]) * e[moving], r2["ex"][moving], rtol=0, atol=1e-15)
    # fmpy's 2.0 and 3.0 hosts give each archive the same inputs: the same outputs
    for name in OUTPUTS:
        np.testing.assert_array_equal(r2[name], r3[name], err_msg=name)


@pytest.mark.parametrize("beta", [0.7, 2.5, -1.9])
def test_a_rotated_input_rotates_the_response(archives, beta):
    base, turned = run(archives[0]), run(archives[0], beta)
    moving = base["theta"] > 1e-3
    assert moving.sum() > 100
    np.testing.assert_allclose(turned["theta"], base["theta"], rtol=0, atol=1e-9)
    shift = np.angle(np.exp(1j * (turned["psi"][moving] - base["psi"][moving] - beta)))
    assert np.abs(shift).max() < 1e-9
    c, s = math.cos(beta), math.sin(beta)
    for (x, y) in (("ex", "ey"), ("xG", "yG"), ("omegaX", "omegaY"), ("Fx", "Fy")):
        scale = max(np.abs(base[x]).max(), np.abs(base[y]).max())
        np.testing.assert_allclose(turned[x], c * base[x] - s * base[y], rtol=0, atol=1e-9 * scale, err_msg=x)
        np.testing.assert_allclose(turned[y], s * base[x] + c * base[y], rtol=0, atol=1e-9 * scale, err_msg=y)
    for name in ("omegaZ", "Fz", "impacts", "regime"):
        np.testing.assert_allclose(turned[name], base[name], rtol=0, atol=1e-9 * max(1.0, np.abs(base[name]).max()),
                                   err_msg=name)
