"""Simulations through fmpy agree with the Rust engine run directly
(run_direct), for every shape and law, with input arrays with and without
input derivatives; overturning ends the run at the right time."""

import math

import numpy as np
import pytest
from ctypes import c_double, c_int
from fmpy import simulate_fmu
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated

from conftest import size_input_derivative_buffer
from fmu_helpers import COLUMNS, DISCARD, ERROR, OK, Host, fmpy_steps, run_direct, start_values

SHAPES = ["solidRectangle", "hollowRectangle", "solidCircle", "hollowCircle"]
LAWS = ["rigid", "elastic", "elastoPlastic"]
INTERVAL = 0.01
STOP = 3.0


@pytest.fixture(autouse=True)
def fmpy_input_derivative_buffer(monkeypatch):
    """fmpy's buffer of input derivatives sized to the input (conftest.py)."""
    size_input_derivative_buffer(monkeypatch)


def ground_motion(amplitude=4.0, frequency=1.5, dt=0.005, duration=STOP):
    t = np.arange(0.0, duration + dt / 2, dt)
    ag = amplitude * np.sin(2 * math.pi * frequency * t) * np.exp(-0.3 * t)
    signal = np.zeros(len(t), dtype=[("time", np.float64), ("ag", np.float64)])
    signal["time"], signal["ag"] = t, ag
    return signal


def through_fmpy(fmu_path, params, signal, derivatives, stop=STOP):
    return simulate_fmu(
        fmu_path,
        start_values=start_values(params),
        input=signal,
        stop_time=stop,
        output_interval=INTERVAL,
        set_input_derivatives=derivatives,
        output=COLUMNS,
    )


def compare(fmpy_result, direct, rtol=1e-12):
    assert len(fmpy_result) == len(direct["time"])
    np.testing.assert_allclose(fmpy_result["time"], direct["time"], rtol=0, atol=1e-12)
    for c in COLUMNS:
        a = np.asarray(fmpy_result[c], dtype=float)
        b = direct[c]
        scale = max(np.max(np.abs(b)), 1e-300)
        err = np.max(np.abs(a - b)) / scale if len(a) else 0.0
        assert err <= rtol, f"{c}: relative difference {err:.3e}"


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("shape", SHAPES)
def test_fmpy_agrees_with_the_engine(fmu_path, run_direct_path, shape, law):
    params = dict(shape=shape, interface=law, theta=0.01)
    signal = ground_motion()
    result = through_fmpy(fmu_path, params, signal, derivatives=False)
    steps = fmpy_steps(signal["time"], signal["ag"], 0.0, STOP, INTERVAL, derivatives=False)
    direct = run_direct(run_direct_path, params, steps[: len(result) - 1])
    compare(result, direct)
    assert np.max(np.abs(result["theta"])) > 1e-4  # it did rock


@pytest.mark.parametrize("law", LAWS)
def test_input_derivatives_are_used(fmu_path, run_direct_path, law):
    params = dict(interface=law, shape="solidRectangle")
    signal = ground_motion(amplitude=5.0, frequency=2.0, dt=0.0037)  # samples off the grid
    with_d = through_fmpy(fmu_path, params, signal, derivatives=True)
    steps = fmpy_steps(signal["time"], signal["ag"], 0.0, STOP, INTERVAL, derivatives=True)
    assert any(d != 0 for _, _, d in steps)
    compare(with_d, run_direct(run_direct_path, params, steps[: len(with_d) - 1]))
    without = through_fmpy(fmu_path, params, signal, derivatives=False)
    assert not np.array_equal(with_d["theta"], without["theta"])


def test_a_ramp_with_its_derivative_is_exact_whatever_the_step(fmu_path, run_direct_path):
    """A linear ramp given as one segment: with derivatives, the FMU sees the
    exact ground motion, so coarse and fine communication steps agree to the
    integrator tolerance; without, the zero-order hold does not."""
    params = dict(interface="elastic", theta=0.0)
    signal = np.zeros(2, dtype=[("time", np.float64), ("ag", np.float64)])
    # one segment that starts before t = 0 (fmpy gives no slope at the first sample)
    signal["time"], signal["ag"] = [-1.0, 3.0], [-1.5, 4.5]

    def final(interval, derivatives):
        r = simulate_fmu(fmu_path, start_values=start_values(params), input=signal, stop_time=2.0,
                         output_interval=interval, set_input_derivatives=derivatives, output=["theta"])
        return r["theta"][-1]

    fine, coarse = final(0.001, True), final(0.1, True)
    assert coarse == pytest.approx(fine, rel=1e-6, abs=1e-12)
    held = final(0.1, False)
    assert abs(held - fine) > 100 * abs(coarse - fine)


def test_free_rocking_matches_the_engine(fmu_path, run_direct_path):
    params = dict(interface="rigid", theta=0.1, restitution="given", eta=0.9)
    result = simulate_fmu(fmu_path, start_values=start_values(params), stop_time=4.0, output_interval=0.02, output=COLUMNS)
    steps = [((k + 1) * 0.02, 0.0, 0.0) for k in range(200)]
    direct = run_direct(run_direct_path, params, steps)
    compare(result, direct)
    assert result["impacts"][-1] >= 3


@pytest.mark.parametrize("law", LAWS)
def test_overturning_ends_the_run_at_the_right_time(fmu_path, run_direct_path, law):
    params = dict(interface=law, theta=0.02)
    signal = ground_motion(amplitude=9.0, frequency=0.8)
    result = through_fmpy(fmu_path, params, signal, derivatives=True)
    steps = fmpy_steps(signal["time"], signal["ag"], 0.0, STOP, INTERVAL, derivatives=True)
    direct = run_direct(run_direct_path, params, steps)
    assert direct["overturned"][-1] == 1, "the case must overturn"
    t_ov = direct["time"][-1]
    assert result["time"][-1] == pytest.approx(t_ov, abs=1e-12)
    assert result["time"][-1] < STOP
    assert result["overturned"][-1] and result["regime"][-1] == 4
    assert not result["overturned"][-2]
    compare(result, direct)


def test_overturning_statuses(fmu_path, unzipped):
    h = Host(fmu_path, unzipped, logging_on=True)
    h.fmu.setupExperiment(startTime=0.0)
    h.set(interface="rigid", theta=0.1, omega=0.6)
    h.fmu.enterInitializationMode()
    h.fmu.exitInitializationMode()
    t, dt = 0.0, 0.05
    while True:
        st = h.raw("fmi2DoStep", c_double(t), c_double(dt), c_int(1))
        if st != OK:
            break
        t += dt
    assert st == DISCARD
    t_ov = h.fmu.getRealStatus(fmi2LastSuccessfulTime)
    assert t < t_ov < t + dt
    assert h.fmu.getBooleanStatus(fmi2Terminated) is True
    assert h.get("overturned") is True and h.get("regime") == 4
    assert abs(h.get("theta")) == pytest.approx(h.get("thetaOv"), rel=1e-12)
    discards = [(s, c, m) for s, c, m in h.messages if s == DISCARD]
    assert discards and "overturned" in discards[-1][2]
    assert any(c == "logEvents" and "overturned at t =" in m for s, c, m in h.messages)
    # no further steps; terminate is allowed
    assert h.raw("fmi2DoStep", c_double(t_ov), c_double(dt), c_int(1)) == ERROR
    h.fmu.reset()
    h.init(interface="rigid", theta=0.1, omega=0.6)
    for k in range(int(t_ov / dt) + 2):
        if h.raw("fmi2DoStep", c_double(k * dt), c_double(dt), c_int(1)) == DISCARD:
            break
    h.fmu.terminate()
    h.free()


def test_tolerance_from_setup_experiment(fmu_path, run_direct_path):
    params = dict(interface="elastoPlastic", theta=0.05)
    loose = simulate_fmu(fmu_path, start_values=start_values(params), stop_time=2.0, output_interval=0.05,
                         relative_tolerance=1e-5, output=COLUMNS)
    steps = [((k + 1) * 0.05, 0.0, 0.0) for k in range(40)]
    compare(loose, run_direct(run_direct_path, params, steps, tolerance=1e-5))
    tight = run_direct(run_direct_path, params, steps, tolerance=1e-10)
    assert not np.array_equal(loose["theta"], tight["theta"])
    assert np.max(np.abs(loose["theta"] - tight["theta"])) < 1e-3


def test_start_time_is_honoured(fmu_path, run_direct_path):
    params = dict(interface="rigid", theta=0.1)
    r = simulate_fmu(fmu_path, start_values=start_values(params), start_time=5.0, stop_time=6.0, output_interval=0.05, output=COLUMNS)
    steps = [(5.0 + (k + 1) * 0.05, 0.0, 0.0) for k in range(20)]
    compare(r, run_direct(run_direct_path, params, steps, start=5.0))
