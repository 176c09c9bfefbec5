"""The FMI 2.0 interface: parameters, calculated parameters, validation,
state machine, statuses, logging, many instances."""

import math
import threading
from ctypes import POINTER, byref, c_char_p, c_double, c_int, c_uint, c_void_p

import numpy as np
import pytest
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated, fmi2DoStepStatus, fmi2PendingStatus

from fmu_helpers import DISCARD, ERROR, OK, WARNING, Host


@pytest.fixture
def host(fmu_path, unzipped):
    h = Host(fmu_path, unzipped)
    yield h
    h.free()


def section(shape, B=0.5, L=1.0, t=0.1, Ro=0.5, Ri=0.3):
    """Area, second moment and depth from docs/model.md §1."""
    if shape == "solidRectangle":
        return B * L, L * B**3 / 12, B
    if shape == "hollowRectangle":
        return B * L - (B - 2 * t) * (L - 2 * t), (L * B**3 - (L - 2 * t) * (B - 2 * t) ** 3) / 12, B
    if shape == "solidCircle":
        return math.pi * Ro**2, math.pi * Ro**4 / 4, 2 * Ro
    return math.pi * (Ro**2 - Ri**2), math.pi * (Ro**4 - Ri**4) / 4, 2 * Ro


SHAPES = ["solidRectangle", "hollowRectangle", "solidCircle", "hollowCircle"]


def test_version_and_platform(host):
    assert host.fmu.getVersion() == "2.0"
    assert host.fmu.getTypesPlatform() == "default"


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("mass_model", ["prism", "lumped"])
def test_calculated_parameters_match_closed_forms(host, shape, mass_model):
    p = dict(B=0.6, L=0.9, t=0.12, Ro=0.45, Ri=0.25, H=3.1, rho=2100.0, W=4.0e4, hG=1.7, Ic=9.0e3, g=9.81)
    host.set(shape=shape, massModel=mass_model, **p)
    host.fmu.enterInitializationMode()
    # parameters read back exactly
    for k, x in p.items():
        assert host.get(k) == x, k
    assert host.get("shape") == SHAPES.index(shape) + 1
    A, Is, D = section(shape, p["B"], p["L"], p["t"], p["Ro"], p["Ri"])
    g = p["g"]
    if mass_model == "prism":
        W = p["rho"] * g * A * p["H"]
        m = W / g
        hG = p["H"] / 2
        Ic = m * (p["H"] ** 2 / 12 + Is / A)
    else:
        W, hG, Ic = p["W"], p["hG"], p["Ic"]
        m = W / g
    b = D / 2
    R0 = math.hypot(b, hG)
    alpha = math.atan(b / hG)
    IO = Ic + m * R0**2
    expected = dict(mass=m, weight=W, R0=R0, alpha=alpha, IO=IO, etaHousner=1 - 2 * m * b**2 / IO)

    def check():
        for k, x in expected.items():
            assert host.get(k) == pytest.approx(x, rel=1e-12), k

    check()  # in initialization mode
    host.fmu.exitInitializationMode()
    check()  # and after


def test_thresholds_of_the_solid_rectangle(host):
    host.set(interface="elastoPlastic", kn=5e9, fm=5e6)
    host.fmu.enterInitializationMode()
    W, A, D, L = host.get("weight"), 0.5, 0.5, 1.0
    assert host.get("thetaJo") == pytest.approx(2 * W / (5e9 * A * D), rel=1e-10)
    ac = 2 * W / (5e6 * L)
    assert host.get("thetaC") == pytest.approx(5e6 / (5e9 * ac), rel=1e-10)
    ov = host.get("thetaOv")
    assert 0 < ov < host.get("alpha")


def test_rigid_interface_values(host):
    host.set(interface="rigid")
    host.fmu.enterInitializationMode()
    assert host.get("thetaOv") == host.get("alpha")
    assert host.get("thetaJo") == 0.0
    assert host.get("thetaC") == 1e60  # never crushes: Modelica's inf (docs/model.md §5)


def test_outputs_at_rest(host):
    host.init()
    assert host.get("theta") == 0.0 and host.get("omega") == 0.0
    assert host.get("Fz") == pytest.approx(host.get("weight"), rel=1e-12)
    assert host.get("Fx") == 0.0
    assert host.get("af") == pytest.approx(0.25, rel=1e-12)
    assert host.get("regime") == 0 and host.get("impacts") == 0 and host.get("overturned") is False
    host.fmu.reset()
    host.init(interface="rigid")
    uplift = host.get("g") * math.tan(host.get("alpha"))  # 1.962 m/s2
    host.set(ag=0.9 * uplift)  # direct feedthrough: at rest (below uplift) Fx = m ag, Fz = W
    assert host.get("Fx") == pytest.approx(host.get("mass") * 0.9 * uplift, rel=1e-12)
    assert host.get("Fz") == pytest.approx(host.get("weight"), rel=1e-12)
    assert host.get("angularAcceleration") == 0.0
    # above uplift the body starts rocking on its toe (theta = omega = 0,
    # side s = -sgn(ag)): xG'' = hG theta'', zG'' = s b theta'' (docs/model.md §5)
    host.set(ag=1.1 * uplift)
    dd = host.get("angularAcceleration")
    m, b, hg = host.get("mass"), 0.25, 1.25
    assert dd < 0.0
    assert host.get("Fx") == pytest.approx(m * (1.1 * uplift + hg * dd), rel=1e-12)
    assert host.get("Fz") == pytest.approx(host.get("weight") - m * b * dd, rel=1e-12)


def test_start_values_are_initial_conditions(host):
    host.init(theta=0.01, omega=-0.02)
    assert host.get("theta") == 0.01 and host.get("omega") == -0.02
    assert host.get("thetaOverAlpha") == pytest.approx(0.01 / host.get("alpha"), rel=1e-15)


INVALID = [
    (dict(B=0.0), "B"),
    (dict(B=-1.0), "B"),
    (dict(L=0.0), "L"),
    (dict(B=float("nan")), "B"),
    (dict(shape="hollowRectangle", t=0.3), "t"),
    (dict(shape="hollowRectangle", t=0.0), "t"),
    (dict(shape="solidCircle", Ro=0.0), "Ro"),
    (dict(shape="hollowCircle", Ri=0.6), "Ri"),
    (dict(shape="hollowCircle", Ri=0.5), "Ri"),
    (dict(kn=0.0), "kn"),
    (dict(interface="elastic", kn=-5.0), "kn"),
    (dict(fm=1.0e4), "fm"),
    (dict(fm=0.0), "fm"),
    (dict(kn=1.0e5), "kn"),
    (dict(restitution="given", eta=1.5), "eta"),
    (dict(restitution="given", eta=-0.1), "eta"),
    (dict(H=0.0), "H"),
    (dict(rho=-1.0), "rho"),
    (dict(massModel="lumped", W=0.0), "W"),
    (dict(massModel="lumped", hG=0.0), "hG"),
    (dict(massModel="lumped", Ic=-1.0), "Ic"),
    (dict(g=0.0), "g"),
    (dict(theta=1.0), "theta"),
]


@pytest.mark.parametrize("values, name", INVALID, ids=[f"{n}-{i}" for i, (_, n) in enumerate(INVALID)])
def test_invalid_parameters_are_refused_naming_the_variable(host, values, name):
    host.set(**values)
    host.fmu.enterInitializationMode()
    status = host.raw("fmi2ExitInitializationMode")
    assert status == ERROR
    errors = host.errors()
    assert errors, "no message through the logger"
    msg = errors[-1]
    assert msg.startswith("fmi2ExitInitializationMode: invalid parameters: ")
    assert f"{name} = " in msg, msg
    # the instance is in the error state: only reset/free and diagnosis
    assert host.status(host.fmu.doStep, 0.0, 0.01) == ERROR
    host.fmu.reset()
    host.init()
    host.fmu.doStep(0.0, 0.01)


def test_valid_edge_cases_are_accepted(host):
    host.init(interface="elastoPlastic", fm=float("inf"))  # fm = inf: no crushing
    assert host.get("thetaC") == 1e60
    host.fmu.reset()
    host.init(restitution="given", eta=0.0)
    host.fmu.reset()
    host.init(restitution="given", eta=1.0)


def test_enumeration_values_are_checked_when_set(host):
    assert host.raw("fmi2SetInteger", (c_uint * 1)(host.vr["shape"]), 1, (c_int * 1)(7)) == ERROR
    assert "shape = 7" in host.errors()[-1] and "solidRectangle" in host.errors()[-1]


def test_non_finite_input_is_refused_and_the_state_kept(host):
    vr = (c_uint * 1)(host.vr["ag"])
    for bad in (float("nan"), float("inf"), -float("inf")):
        host.fmu.reset()
        host.init(theta=0.05, interface="rigid")
        host.set(ag=0.5)
        host.fmu.doStep(0.0, 0.01)
        theta = host.get("theta")
        assert host.raw("fmi2SetReal", vr, 1, (c_double * 1)(bad)) == ERROR
        assert "ag = " in host.errors()[-1] and "finite" in host.errors()[-1]
        # the value was not taken; the state stays at the last good step
        assert host.get("ag") == 0.5
        assert host.get("theta") == theta
    order = (c_int * 1)(1)
    host.fmu.reset()
    host.init()
    assert host.raw("fmi2SetRealInputDerivatives", vr, 1, order, (c_double * 1)(float("nan"))) == ERROR
    assert "ag" in host.errors()[-1]


def test_input_that_overflows_within_the_step_is_refused(host):
    host.init()
    host.set(ag=1e308)
    host.fmu.setRealInputDerivatives([host.vr["ag"]], [1], [1e308])
    assert host.raw("fmi2DoStep", c_double(0.0), c_double(10.0), c_int(1)) == ERROR
    assert "finite" in host.errors()[-1]
    assert host.get("theta") == 0.0


WRONG_STATE = [
    ("instantiated", "fmi2DoStep", (c_double(0.0), c_double(0.1), c_int(1))),
    ("instantiated", "fmi2ExitInitializationMode", ()),
    ("instantiated", "fmi2Terminate", ()),
    ("instantiated", "fmi2GetReal", ((c_uint * 1)(1), 1, (c_double * 1)())),
    ("init", "fmi2SetupExperiment", (c_int(0), c_double(0), c_double(0), c_int(0), c_double(0))),
    ("init", "fmi2EnterInitializationMode", ()),
    ("init", "fmi2DoStep", (c_double(0.0), c_double(0.1), c_int(1))),
    ("stepping", "fmi2EnterInitializationMode", ()),
    ("stepping", "fmi2ExitInitializationMode", ()),
    ("stepping", "fmi2SetupExperiment", (c_int(0), c_double(0), c_double(0), c_int(0), c_double(0))),
    ("stepping", "fmi2SetReal", ((c_uint * 1)(1), 1, (c_double * 1)(0.4))),  # B is fixed
    ("stepping", "fmi2SetReal", ((c_uint * 1)(20), 1, (c_double * 1)(0.1))),  # theta: only before
    ("stepping", "fmi2SetInteger", ((c_uint * 1)(0), 1, (c_int * 1)(2))),  # shape
    ("stepping", "fmi2CancelStep", ()),
    ("terminated", "fmi2DoStep", (c_double(0.0), c_double(0.1), c_int(1))),
    ("terminated", "fmi2SetReal", ((c_uint * 1)(19), 1, (c_double * 1)(0.1))),
    ("terminated", "fmi2Terminate", ()),
    ("instantiated", "fmi2GetRealStatus", (fmi2LastSuccessfulTime, byref(c_double()))),
    ("init", "fmi2GetBooleanStatus", (fmi2Terminated, byref(c_int()))),
]


@pytest.mark.parametrize("state, function, args", WRONG_STATE, ids=[f"{s}-{f}" for s, f, _ in WRONG_STATE])
def test_calls_in_the_wrong_state_are_refused(host, state, function, args):
    if state in ("init", "stepping", "terminated"):
        host.fmu.setupExperiment(startTime=0.0)
        host.fmu.enterInitializationMode()
    if state in ("stepping", "terminated"):
        host.fmu.exitInitializationMode()
    if state == "terminated":
        host.fmu.terminate()
    assert host.raw(function, *args) == ERROR
    msg = host.errors()[-1]
    assert msg.startswith(function + ":"), msg
    # refused calls change nothing but the state (error): reset recovers
    host.fmu.reset()
    host.init()
    host.fmu.doStep(0.0, 0.01)


def test_outputs_and_calculated_parameters_cannot_be_set(host):
    for name in ("mass", "Fx", "regime"):
        v = host.var[name]
        host.fmu.reset()
        if v.type == "Real":
            st = host.raw("fmi2SetReal", (c_uint * 1)(v.valueReference), 1, (c_double * 1)(1.0))
        else:
            st = host.raw("fmi2SetInteger", (c_uint * 1)(v.valueReference), 1, (c_int * 1)(1))
        assert st == ERROR
        assert f"{name} (causality" in host.errors()[-1]


def test_unknown_value_references(host):
    host.init()
    assert host.raw("fmi2GetReal", (c_uint * 1)(999), 1, (c_double * 1)()) == ERROR
    assert "unknown Real value reference 999" in host.errors()[-1]
    host.fmu.reset()
    host.init()
    # shape is an Enumeration (Integer), not a Real
    assert host.raw("fmi2GetReal", (c_uint * 1)(host.vr["shape"]), 1, (c_double * 1)()) == ERROR
    host.fmu.reset()
    host.init()
    assert host.raw("fmi2GetString", (c_uint * 1)(0), 1, (c_char_p * 1)()) == ERROR
    host.fmu.reset()
    host.init()
    assert host.raw("fmi2GetReal", None, 0, None) == OK  # nothing asked, nothing to do


def test_communication_point_is_compared_with_a_tolerance(host):
    host.init()
    t = 0.0
    for _ in range(10):
        host.fmu.doStep(t, 0.1)
        t += 0.1  # accumulates rounding: 0.30000000000000004...
    host.fmu.doStep(1.0 + 1e-14, 0.1)
    assert host.raw("fmi2DoStep", c_double(1.2), c_double(0.1), c_int(1)) == ERROR
    assert "does not match" in host.errors()[-1]


def test_step_size_must_be_positive(host):
    host.init()
    assert host.raw("fmi2DoStep", c_double(0.0), c_double(0.0), c_int(1)) == ERROR
    host.fmu.reset()
    host.init()
    assert host.raw("fmi2DoStep", c_double(0.0), c_double(-0.1), c_int(1)) == ERROR


def test_stop_time_is_honoured(host):
    host.init(stop=0.5)
    host.fmu.doStep(0.0, 0.5)
    assert host.raw("fmi2DoStep", c_double(0.5), c_double(0.1), c_int(1)) == ERROR
    assert "stopTime" in host.errors()[-1]


def test_status_getters(host):
    host.init(start=2.0)
    host.fmu.doStep(2.0, 0.25)
    assert host.fmu.getRealStatus(fmi2LastSuccessfulTime) == 2.25
    assert host.fmu.getBooleanStatus(fmi2Terminated) is False
    # no asynchronous steps: the pending/do-step statuses are not available
    assert host.raw("fmi2GetStatus", fmi2DoStepStatus, byref(c_int())) == DISCARD
    assert host.raw("fmi2GetStringStatus", fmi2PendingStatus, byref(c_char_p())) == DISCARD
    assert host.raw("fmi2GetIntegerStatus", fmi2LastSuccessfulTime, byref(c_int())) == DISCARD
    # Discard is no error: the instance goes on
    host.fmu.doStep(2.25, 0.25)
    assert host.raw("fmi2GetRealStatus", 42, byref(c_double())) == ERROR


def test_cancel_step_is_answered(host):
    host.init()
    assert host.raw("fmi2CancelStep") == ERROR
    assert "fmi2CancelStep: no asynchronous step" in host.errors()[-1]


def test_directional_derivatives_are_not_provided(host):
    host.init()
    st = host.raw("fmi2GetDirectionalDerivative", None, 0, None, 0, None, None)
    assert st == ERROR and "providesDirectionalDerivative" in host.errors()[-1]


REAL_OUTPUTS = ["theta", "omega", "thetaOverAlpha", "angularAcceleration", "af", "contactLength", "MR", "Fx", "Fz"]


def test_output_derivatives(host):
    host.init(theta=0.05, interface="rigid")
    host.fmu.doStep(0.0, 0.05)
    vr = host.vr
    d = host.fmu.getRealOutputDerivatives([vr["theta"], vr["theta"], vr["omega"], vr["thetaOverAlpha"]], [1, 2, 1, 1])
    assert d[0] == host.get("omega")
    assert d[1] == host.get("angularAcceleration")
    assert d[2] == host.get("angularAcceleration")
    assert d[3] == pytest.approx(host.get("omega") / host.get("alpha"), rel=1e-15)
    assert host.raw("fmi2GetRealOutputDerivatives", (c_uint * 1)(vr["theta"]), 1, (c_int * 1)(3), (c_double * 1)()) == ERROR
    assert "order 3" in host.errors()[-1]
    host.fmu.reset()
    host.init()
    for name in ["ag", "B"]:
        assert host.raw("fmi2GetRealOutputDerivatives", (c_uint * 1)(vr[name]), 1, (c_int * 1)(1), (c_double * 1)()) == ERROR
        assert f"{name} is no output" in host.errors()[-1]
        host.fmu.reset()
        host.init()


@pytest.mark.parametrize("formulation", ["shiftingPivot", "costa"])
@pytest.mark.parametrize("interface", ["rigid", "elastic", "elastoPlastic"])
def test_every_real_output_has_derivatives_of_orders_1_and_2(host, interface, formulation):
    """maxOutputDerivativeOrder = 2 holds for every Real output: after a few
    steps under a ground acceleration with a slope (fmi2SetRealInputDerivatives),
    both orders of all nine are fmi2OK and finite, also at rest."""
    vrs = [host.vr[n] for n in REAL_OUTPUTS]
    for theta in [0.04, 0.0]:
        host.init(theta=theta, interface=interface, formulation=formulation, fm=1e6, ag=0.2)
        host.fmu.setRealInputDerivatives([host.vr["ag"]], [1], [-0.3])
        for k in range(5):
            host.fmu.doStep(k * 0.01, 0.01)
            d1 = host.fmu.getRealOutputDerivatives(vrs, [1] * len(vrs))
            d2 = host.fmu.getRealOutputDerivatives(vrs, [2] * len(vrs))
            assert all(math.isfinite(x) for x in d1 + d2), (d1, d2)
            assert d1[0] == host.get("omega") and d2[0] == d1[1] == host.get("angularAcceleration")
            assert d1[3] == d2[1]
        if theta == 0.0 and interface == "rigid":
            # at rest: every output constant but Fx = m ag, whose slope is m dag/dt
            assert d1[:7] == [0.0] * 7 and d2 == [0.0] * 9
            assert d1[7] == pytest.approx(-0.3 * host.get("mass"), rel=1e-15)
            assert d1[8] == 0.0
        host.fmu.reset()


def test_higher_input_derivatives_are_ignored_with_a_warning(host):
    host.init()
    st = host.raw("fmi2SetRealInputDerivatives", (c_uint * 1)(host.vr["ag"]), 1, (c_int * 1)(2), (c_double * 1)(1.0))
    assert st == WARNING
    assert "ignored" in host.messages[-1][2]
    host.fmu.doStep(0.0, 0.1)  # still fine


def test_input_derivatives_only_for_inputs(host):
    host.init()
    st = host.raw("fmi2SetRealInputDerivatives", (c_uint * 1)(host.vr["B"]), 1, (c_int * 1)(1), (c_double * 1)(1.0))
    assert st == ERROR and "B is no continuous Real input" in host.errors()[-1]


# ----- logging -------------------------------------------------------------

def test_errors_reach_the_logger_even_with_debug_logging_off(fmu_path, unzipped):
    h = Host(fmu_path, unzipped, name="quiet", logging_on=False)
    h.set(B=-1.0)
    h.fmu.enterInitializationMode()
    assert h.raw("fmi2ExitInitializationMode") == ERROR
    status, category, msg = h.messages[-1]
    assert status == ERROR and category == "logStatusError" and "B = -1" in msg
    assert h.names[-1] == "quiet"
    h.free()


def test_instance_name_and_environment_are_passed_back(fmu_path, unzipped):
    h = Host(fmu_path, unzipped, name="pier 7 (50% scale)", environment=0x1234)
    h.set(B=-1.0)
    h.fmu.enterInitializationMode()
    h.raw("fmi2ExitInitializationMode")
    assert h.names[-1] == "pier 7 (50% scale)"
    assert h.environments[-1] == 0x1234
    h.free()


def test_debug_logging_categories(fmu_path, unzipped):
    h = Host(fmu_path, unzipped, logging_on=False)
    h.init(theta=0.1, interface="rigid")
    for k in range(20):
        h.fmu.doStep(0.1 * k, 0.1)
    assert not [m for m in h.messages if m[1] == "logEvents"], "events without debug logging"
    h.fmu.setDebugLogging(True, ["logEvents"])
    for k in range(20, 40):
        h.fmu.doStep(0.1 * k, 0.1)
    events = [m for s, c, m in h.messages if c == "logEvents"]
    assert any("impact" in m for m in events), events
    assert not [m for m in h.messages if m[1] == "logAll"], "call trace without logAll"
    h.fmu.setDebugLogging(True, ["logAll"])
    h.fmu.doStep(4.0, 0.1)
    assert any(c == "logAll" and "fmi2DoStep" in m for s, c, m in h.messages)
    h.fmu.setDebugLogging(False, [])
    n = len(h.messages)
    for k in range(41, 60):
        h.fmu.doStep(0.1 * k, 0.1)
    assert len(h.messages) == n
    h.free()


def test_unknown_category_is_a_warning_and_percent_survives_printf(fmu_path, unzipped):
    h = Host(fmu_path, unzipped, proxy=True)
    st = h.fmu.fmi2SetDebugLogging(h.fmu.component, 1, 1, (c_char_p * 1)(b"100%s_sure %d"))
    assert st == WARNING
    status, category, msg = h.messages[-1]
    assert category == "logStatusWarning"
    assert "100%s_sure %d" in msg  # through C vsnprintf, unchanged
    h.free()


def test_logging_on_at_instantiation_logs_everything(fmu_path, unzipped):
    h = Host(fmu_path, unzipped, logging_on=True)
    h.init(theta=0.1, interface="rigid")
    h.fmu.doStep(0.0, 2.0)
    cats = {c for s, c, m in h.messages}
    assert {"logAll", "logEvents"} <= cats
    assert any("fmi2Instantiate" in m and "resources" in m for s, c, m in h.messages)
    h.free()


def test_resource_location_is_decoded(fmu_path, tmp_path):
    from fmpy import extract

    d = extract(fmu_path, unzipdir=str(tmp_path / "with space %"))
    h = Host(fmu_path, d, logging_on=True)
    trace = [m for s, c, m in h.messages if "fmi2Instantiate" in m][0]
    assert "with space %/resources" in trace, trace
    h.free()


# ----- many instances -------------------------------------------------------

def run(h, theta, n=50, dt=0.02):
    h.init(theta=theta, interface="elastoPlastic")
    out = []
    for k in range(n):
        h.fmu.doStep(k * dt, dt)
        out.append((h.get("theta"), h.get("omega")))
    return out


def test_hundred_instances_in_one_process(fmu_path, unzipped):
    hosts = [Host(fmu_path, unzipped, name=f"i{k}") for k in range(100)]
    for k, h in enumerate(hosts):
        h.fmu.setupExperiment(startTime=0.0)
        h.set(theta=0.001 * (k % 10), B=0.5 + 0.001 * k)
        h.fmu.enterInitializationMode()
        h.fmu.exitInitializationMode()
    for step in range(20):
        for h in hosts:
            h.fmu.doStep(step * 0.01, 0.01)
    for k, h in enumerate(hosts):
        assert h.get("B") == 0.5 + 0.001 * k
    # same parameters, same results; others independent
    ref = Host(fmu_path, unzipped)
    ref.fmu.setupExperiment(startTime=0.0)
    ref.set(theta=0.001 * 7, B=0.5 + 0.001 * 17)
    ref.fmu.enterInitializationMode()
    ref.fmu.exitInitializationMode()
    for step in range(20):
        ref.fmu.doStep(step * 0.01, 0.01)
    assert ref.get("theta") == hosts[17].get("theta")
    assert ref.get("omega") == hosts[17].get("omega")
    for h in hosts + [ref]:
        h.free()


def run_and_free(h, theta):
    try:
        return run(h, theta)
    finally:
        h.free()


def test_instances_in_threads(fmu_path, unzipped):
    serial = run_and_free(Host(fmu_path, unzipped), 0.02)
    results = {}

    def work(k):
        results[k] = run_and_free(Host(fmu_path, unzipped, name=f"t{k}"), 0.02)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(results) == 8
    for k in range(8):
        assert results[k] == serial


def test_reset_restores_the_start_values(host):
    host.init(theta=0.05, B=0.7)
    host.fmu.doStep(0.0, 0.3)
    host.fmu.reset()
    host.fmu.enterInitializationMode()
    assert host.get("B") == 0.5 and host.get("theta") == 0.0


def test_debug_log_shows_values_as_a_reader_writes_them(fmu_path, unzipped):
    """The trace of instantiate, setup and set: numbers, 'undefined', a path; no Rust debug
    forms (Some(..), None, Real(..)) in what a user reads."""
    h = Host(fmu_path, unzipped, logging_on=True)
    try:
        h.init(tolerance=None, kn=2e8, restraint="oneSided", eRestraint=0.5)
        text = "\n".join(m for _, _, m in h.messages)
    finally:
        h.free()
    assert "kn = 200000000" in text and "restraint = 2" in text and "eRestraint = 0.5" in text
    assert "tolerance = undefined" in text and "stopTime = undefined" in text
    for debug_form in ("Some(", "None", "Real(", "Integer("):
        assert debug_form not in text, debug_form
