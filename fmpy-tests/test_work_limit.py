"""The work limit of fmi2DoStep (parameter maxSteps, docs/model.md §5): a step
that would take minutes (a very stiff interface shaken below uplift, a
communication step of 1e300 s) returns fmi2Discard at the limit with the time
reached as fmi2LastSuccessfulTime, a message naming the cause and that time,
the state consistent there, and the host able to go on with smaller steps
from the state it saved before the step."""

import math
import time
from ctypes import c_double, c_int

import pytest
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated

from fmu_helpers import DISCARD, OK, Host

CASES = [
    # name, parameters, ag (m/s2), communication step (s)
    ("kn 1e18, 1 s step", dict(kn=1e18), 1.0, 1.0),
    ("elastic, 1e300 s step", dict(interface="elastic"), 1.0, 1e300),
]


@pytest.mark.parametrize("name, values, ag, h", CASES, ids=[c[0] for c in CASES])
def test_a_step_past_the_work_limit_is_discarded_where_it_stopped(fmu_path, unzipped, name, values, ag, h):
    host = Host(fmu_path, unzipped, logging_on=True)
    try:
        host.init(**values)
        host.set(ag=ag)
        saved = host.fmu.getFMUstate()
        t0 = time.perf_counter()
        status = host.raw("fmi2DoStep", c_double(0.0), c_double(h), c_int(1))
        wall = time.perf_counter() - t0
        print(f"{name}: fmi2DoStep returned {status} after {wall:.3f} s")
        assert status == DISCARD
        t_reached = host.fmu.getRealStatus(fmi2LastSuccessfulTime)
        assert 0.0 < t_reached < h
        assert not host.fmu.getBooleanStatus(fmi2Terminated)
        message = [m for s, c, m in host.messages if s == DISCARD][-1]
        assert "maxSteps" in message and f"t = {t_reached!r}" in message, message
        assert "integrator steps" in message, message
        # the state there is consistent: finite, below overturning, where the
        # restoring moment W hW(|theta|) is positive (thetaOv is the first
        # root of hW, docs/model.md §3)
        theta, omega, mr = host.get("theta"), host.get("omega"), host.get("MR")
        assert math.isfinite(theta) and math.isfinite(omega) and math.isfinite(mr)
        assert abs(theta) < host.get("thetaOv")
        assert not host.get("overturned")
        assert mr > 0.0
        # the host goes back to the saved state and on with short steps
        assert host.raw("fmi2DoStep", c_double(t_reached), c_double(1e-3), c_int(1)) != OK
        host.fmu.setFMUstate(saved)
        host.fmu.freeFMUstate(saved)
        for k in range(5):
            host.fmu.doStep(k * 1e-3, 1e-3)
        assert math.isfinite(host.get("theta"))
    finally:
        host.free()


def test_max_steps_below_one_is_refused_naming_it(fmu_path, unzipped):
    host = Host(fmu_path, unzipped)
    try:
        host.fmu.setupExperiment(startTime=0.0)
        host.set(maxSteps=0)
        host.fmu.enterInitializationMode()
        assert host.status(host.fmu.exitInitializationMode) != OK
        assert any("maxSteps" in m for m in host.errors()), host.errors()
    finally:
        host.free()
