"""The native stepping loop (fmu-stepper, rocking.stepper) against the Python loop it
replaces (RockingFMU.simulate(loop="python"), the reference): the same FMI calls, so
the same outputs bit for bit, the same overturning and the same errors."""

import math

import numpy as np
import pytest

from rocking import RockingFMU, stepper
from rocking import groundmotion as gm
from rocking.cases import dharahara_cases
from rocking.fmu import FMUError

OUTPUTS = ("theta", "omega", "thetaOverAlpha", "af", "contactLength", "MR", "Fx", "Fz", "regime",
           "impacts", "zeroCrossings", "overturned")


@pytest.fixture(scope="module")
def fmu(unzipped):
    if stepper.library() is None:
        pytest.fail(f"{stepper.library_path()} not built: run `cargo xtask fmu` first", pytrace=False)
    return RockingFMU(unzipdir=unzipped)


def bits(result):
    """Every field of a structured result as its raw bytes."""
    return {name: result[name].tobytes() for name in result.dtype.names}


def both(fmu, params, **kw):
    return fmu.simulate(params, loop="python", **kw), fmu.simulate(params, loop="native", **kw)


def assert_same(py, nat):
    assert py.result.dtype == nat.result.dtype
    assert bits(py.result) == bits(nat.result)
    for f in ("overturned", "impacts", "zero_crossings", "calculated", "messages"):
        assert getattr(py, f) == getattr(nat, f), f
    for f in ("t_end", "t_overturn", "peak_theta_over_alpha"):
        a, b = getattr(py, f), getattr(nat, f)
        assert (math.isnan(a) and math.isnan(b)) or a == b, f


CASES = dharahara_cases()


@pytest.mark.parametrize("case", ["rigid", "I2_fm2", "F170_elastic", "I1500_elastic"])
def test_dharahara_cases_bit_for_bit(fmu, case):
    """Under the KATNP stand-in at the case study's tolerance: overturning (I2_fm2),
    standing, rigid with impacts; every output."""
    py, nat = both(fmu, CASES[case], record=gm.katnp_standin(), rtol=1e-11, outputs=OUTPUTS)
    assert_same(py, nat)
    assert len(nat.result) > 100


def test_overturning_row_is_last_successful_time(fmu):
    py, nat = both(fmu, CASES["I2_fm2"], record=gm.katnp_standin(), scale=2.0, outputs=("theta", "regime"))
    assert nat.overturned and py.overturned
    assert_same(py, nat)
    assert nat.t_end < gm.katnp_standin().time[-1]


def test_free_rocking_sampled_every_fifth_step(fmu):
    """No input (no fmi2SetReal in the loop), outputs every 5 communication steps."""
    params = {"shape": "solidRectangle", "B": 0.5, "interface": "rigid", "theta": 0.05}
    py, nat = both(fmu, params, stop_time=3.0, output_interval=0.05, outputs=("theta", "impacts"))
    assert_same(py, nat)
    assert len(nat.result) == 61


def test_stop_time_not_on_the_grid(fmu):
    py, nat = both(fmu, CASES["F170_fm5"], record=gm.katnp_standin(), stop_time=1.234, outputs=("af",))
    assert_same(py, nat)
    assert nat.result["time"][-1] == 1.234


def test_failed_step_raises_the_same_error(fmu):
    """A non-finite input: both loops stop at the same call with the same message."""
    rec = gm.katnp_standin()
    acc = np.array(rec.acc, dtype=float)
    acc[50] = np.inf
    errors = []
    for loop in ("python", "native"):
        with pytest.raises(FMUError) as info:
            fmu.simulate(CASES["rigid"], ag=(rec.time, acc), loop=loop, outputs=("theta",))
        errors.append(str(info.value))
    assert errors[0] == errors[1]
    assert "fmi2SetReal" in errors[0]
