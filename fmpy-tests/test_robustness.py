"""Robustness of the packaged FMU, where test_fmi_calls.py does not reach:
non-finite parameters, the conditions of docs/model.md section 5 on other shapes
and laws, derived values that overflow, every enumeration, large start times
and bad communication points (the state is kept; a saved state restarts the
run). The full tables run in Rust through the C API
(fmu-rocking/tests/params_c_api.rs, inputs.rs, stress_c_api.rs); these check
the same behaviour through fmpy on the packaged binary."""

import math
from ctypes import c_double, c_int, c_uint

import pytest

from fmu_helpers import ENUMS, ERROR, Host

NAN, INF = float("nan"), float("inf")


@pytest.fixture
def host(fmu_path, unzipped):
    h = Host(fmu_path, unzipped)
    yield h
    h.free()


INVALID = [
    (dict(g=NAN), "g"),
    (dict(g=INF), "g"),
    (dict(kn=NAN), "kn"),
    (dict(kn=INF), "kn"),
    (dict(fm=NAN), "fm"),
    (dict(shape="hollowCircle", Ri=NAN), "Ri"),
    (dict(massModel="lumped", W=INF), "W"),
    (dict(massModel="lumped", Ic=NAN), "Ic"),
    (dict(theta=NAN), "theta"),
    (dict(omega=INF), "omega"),
    (dict(restitution="given", eta=NAN), "eta"),
    # W >= fm*A on a circle (A = 0.785 m2), lumped
    (dict(shape="solidCircle", massModel="lumped", W=1e6, fm=1e6), "fm"),
    # kn*Is <= W*hG on a hollow circle, elastic (Is = 0.0427 m4, W hG = 27.7 kN m)
    (dict(shape="hollowCircle", interface="elastic", kn=1e5), "kn"),
    # 2t >= L where L is the smaller side
    (dict(shape="hollowRectangle", B=1.0, L=0.4, t=0.2), "t"),
    # values that pass one by one but overflow or vanish together
    (dict(rho=1e200, H=1e200), "rho"),
    (dict(massModel="lumped", interface="rigid", W=1e300, g=1e-300), "mass"),
    (dict(massModel="lumped", interface="rigid", hG=1e200), "IO"),
    (dict(B=1e-200), "B"),
    # thetaJo = 2W/(kn A D) below 1e-100 rad
    (dict(kn=1e200), "kn"),
]


@pytest.mark.parametrize("values, name", INVALID, ids=[f"{n}-{i}" for i, (_, n) in enumerate(INVALID)])
def test_more_invalid_parameters_are_refused_naming_the_variable(host, values, name):
    host.set(**values)
    host.fmu.enterInitializationMode()
    assert host.raw("fmi2ExitInitializationMode") == ERROR
    errors = host.errors()
    assert len(errors) == 1, errors
    assert errors[0].startswith(f"fmi2ExitInitializationMode: invalid parameters: {name} = "), errors[0]
    assert "must" in errors[0], errors[0]
    host.fmu.reset()
    host.init(theta=0.02)
    host.fmu.doStep(0.0, 0.01)


@pytest.mark.parametrize("name", list(ENUMS))
def test_every_enumeration_is_checked_when_set(host, name):
    for x in (0, len(ENUMS[name]) + 1, -1):
        host.fmu.reset()
        n = len(host.errors())
        st = host.raw("fmi2SetInteger", (c_uint * 1)(host.vr[name]), 1, (c_int * 1)(x))
        assert st == ERROR
        assert len(host.errors()) == n + 1
        assert f"{name} = {x}: not an item of" in host.errors()[-1], host.errors()[-1]
        # the start value is kept
        assert host.get(name) == int(host.var[name].start)


def _theta_after(host, start, n=100, dt=0.02):
    host.init(start=start, theta=0.1)
    for k in range(n):
        host.fmu.doStep(start + k * dt, dt)
    return host.get("theta"), host.get("impacts")


def test_a_large_start_time_gives_the_same_motion(fmu_path, unzipped):
    # regression: fmi2DoStep never returned at startTime 1e9 s (default block)
    ref = Host(fmu_path, unzipped)
    late = Host(fmu_path, unzipped)
    try:
        theta0, impacts0 = _theta_after(ref, 0.0)
        theta1, impacts1 = _theta_after(late, 1e9)
        assert impacts0 == impacts1 == 2
        assert abs(theta1 - theta0) < 1e-9
    finally:
        ref.free()
        late.free()


BAD_POINTS = [(0.5 + 0.02, 0.02), (0.5 - 0.02, 0.02), (NAN, 0.02), (0.5, NAN), (0.5, -0.02), (INF, 0.02)]


@pytest.mark.parametrize("t, h", BAD_POINTS, ids=[f"{t}-{h}" for t, h in BAD_POINTS])
def test_a_bad_communication_point_keeps_the_state(fmu_path, unzipped, t, h):
    ref = Host(fmu_path, unzipped)
    bad = Host(fmu_path, unzipped)
    try:
        for x in (ref, bad):
            x.init(theta=0.05, interface="rigid")
            for k in range(25):
                x.fmu.doStep(k * 0.02, 0.02)
        saved = bad.fmu.getFMUstate()
        theta, omega = bad.get("theta"), bad.get("omega")
        assert bad.raw("fmi2DoStep", c_double(t), c_double(h), c_int(1)) == ERROR
        msg = bad.errors()[-1]
        assert msg.startswith("fmi2DoStep: currentCommunicationPoint = "), msg
        assert bad.get("theta") == theta and bad.get("omega") == omega
        bad.fmu.setFMUstate(saved)
        bad.fmu.freeFMUstate(saved)
        for x in (ref, bad):
            for k in range(25, 50):
                x.fmu.doStep(k * 0.02, 0.02)
        assert bad.get("theta") == ref.get("theta")
        assert bad.get("omega") == ref.get("omega")
        assert bad.get("impacts") == ref.get("impacts")
    finally:
        ref.free()
        bad.free()


def test_non_finite_ag_keeps_omega_and_time(host):
    host.init(theta=0.05, interface="rigid")
    for k in range(10):
        host.set(ag=0.3)
        host.fmu.doStep(k * 0.02, 0.02)
    saved = host.fmu.getFMUstate()
    theta, omega = host.get("theta"), host.get("omega")
    vr = (c_uint * 1)(host.vr["ag"])
    for bad in (NAN, INF, -INF):
        assert host.raw("fmi2SetReal", vr, 1, (c_double * 1)(bad)) == ERROR
        assert host.errors()[-1].startswith(f"fmi2SetReal: ag = {'NaN' if math.isnan(bad) else ('inf' if bad > 0 else '-inf')}")
        assert host.get("theta") == theta and host.get("omega") == omega and host.get("ag") == 0.3
        host.fmu.setFMUstate(saved)
    # the time is kept: the next step starts where the last good one ended
    host.fmu.doStep(10 * 0.02, 0.02)
    host.fmu.freeFMUstate(saved)
