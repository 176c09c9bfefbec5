"""The packaged RoundBody FMU (target/fmu/RoundBody.fmu and fmi3/RoundBody.fmu)
through fmpy: both archives validate, a run under two horizontal components
goes through simulate_fmu in both standards, the response to an input
rotated by an angle is the response rotated by it (an invariance of the
physics: the bed and the body are round), against the unrotated run, and
Model Exchange under fmpy's CVode gives co-simulation's motion and impacts; on
the flexible beds (RockingBlock's interface, kn, fm, formulation) the same in
both standards and under a rotated input (their Model Exchange under CVode:
test_round_body_flexible_me.py)."""

import math

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from conftest import TARGET, size_input_derivative_buffer

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


def run(path, beta=0.0, start=None, outputs=OUTPUTS):
    return simulate_fmu(path, stop_time=STOP, output_interval=0.01, input=ground(beta), output=outputs,
                        start_values=start or {})


# a bed of kn = 1e8 Pa/m under the drum; 3: elastoPlastic, crushing at fm = 0.3 MPa (2: elastic)
BED = {"kn": 1e8, "fm": 3e5}
CONTACT = ["contactArea", "crushedArea", "af"]


def test_both_archives_validate(archives):
    for path in archives:
        assert validate_fmu(path) == [], path
    md2, md3 = (read_model_description(p) for p in archives)
    assert md2.coSimulation.modelIdentifier == md3.coSimulation.modelIdentifier == "RoundBody"
    for md in (md2, md3):
        assert md.modelExchange.modelIdentifier == "RoundBody"
        assert md.numberOfEventIndicators == 4
        # omegaW: omega referred to the weight (docs/model.md §11.5), omega itself but for shiftingPivot
        states = [u.variable.derivative.name for u in md.derivatives]
        assert states == ["ex", "ey", "omegaWX", "omegaWY", "omegaWZ", "xG", "yG"]
    assert md3.coSimulation.hasEventMode and md3.coSimulation.mightReturnEarlyFromDoStep
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


@pytest.fixture
def fmpy_input_derivative_buffer(monkeypatch):
    """fmpy's buffer of input derivatives sized to the three inputs (conftest.py)."""
    size_input_derivative_buffer(monkeypatch)


def me_and_cs(path, start, signal=None, stop=STOP, rtol=1e-10, interval=5e-4):
    """The same run through fmpy's Model Exchange (CVode at `rtol`, its absolute tolerances from the
    FMU's nominals) and its co-simulation (the FMU's own integrator, steps of `interval`, input
    derivatives set)."""
    common = dict(stop_time=stop, output_interval=interval, input=signal, output=OUTPUTS, start_values=start)
    me = simulate_fmu(path, fmi_type="ModelExchange", solver="CVode", relative_tolerance=rtol, **common)
    cs = simulate_fmu(path, fmi_type="CoSimulation", set_input_derivatives=signal is not None, **common)
    return me, cs


@pytest.mark.parametrize("standard", [0, 1])
@pytest.mark.parametrize(
    "start, impacts, tol",
    [
        # free rocking in the plane of azimuth 0.7 rad: every crossing an impact
        ({"theta0": 0.1, "psi0": 0.7}, 14, 1e-9),
        # wobbling off any plane, spun about the vertical: the contact runs round the rim
        ({"theta0": 0.15, "psi0": 0.4, "omegaZ0": 3.0, "omegaX0": 0.2}, 0, 1e-7),
        ({"theta0": 0.1, "psi0": 0.4, "omegaX0": 0.3, "omegaY0": -0.2}, 0, 1e-7),
    ],
)
def test_model_exchange_under_cvode_gives_co_simulations_motion(archives, standard, start, impacts, tol):
    """Free motion (no input, so both interfaces see the same problem exactly): the same impacts,
    and the peak tilt after the first second to `tol` (measured, CVode at rtol 1e-10: 2.7e-10 rad
    after 5 impacts, 6.5e-9 and 1.7e-8 rad wobbling); the azimuth turns through more than a radian
    off a plane."""
    me, cs = me_and_cs(archives[standard], start)
    assert me["impacts"][-1] == cs["impacts"][-1] == impacts
    late = [r["theta"][r["time"] > 1.0].max() for r in (me, cs)]
    assert abs(late[0] - late[1]) <= tol
    assert not me["overturned"].any()
    if impacts == 0:
        assert np.ptp(np.unwrap(me["psi"])) > 1.0


@pytest.mark.parametrize(
    "components, stop, impacts, tol",
    [
        # along x from rest: uplift at 0.09 s, two impacts (measured 1.9e-6 rad of 0.0903)
        ("x", 1.2, 2, 1e-5),
        # both horizontal components: off any plane, no impact (measured 8.3e-6 rad of 0.197)
        ("xy", 2.0, 0, 5e-5),
    ],
)
def test_model_exchange_under_a_ground_motion(archives, fmpy_input_derivative_buffer, components, stop, impacts, tol):
    """The test motion from rest (without av) through Model Exchange (CVode, rtol 1e-9) and
    co-simulation in steps of 0.5 ms: the same impacts, and the peak tilt to `tol`. Part of the
    difference is fmpy's: its input derivative at a sample of the signal (every 5 ms) is the slope of
    the segment before it, which co-simulation extrapolates over the next step; Model Exchange
    interpolates."""
    signal = ground()
    signal["av"] = 0.0
    if components == "x":
        signal["agy"] = 0.0
    me, cs = me_and_cs(archives[0], {}, signal, stop=stop, rtol=1e-9)
    assert me["impacts"][-1] == cs["impacts"][-1] == impacts
    assert me["regime"][-1] == cs["regime"][-1] == 2
    assert me["theta"].max() > 0.05
    assert abs(me["theta"].max() - cs["theta"].max()) <= tol
    if components == "xy":
        assert np.ptp(np.unwrap(me["psi"][me["theta"] > 0.01])) > 1.0


@pytest.mark.parametrize("interface", [2, 3])
def test_flexible_beds_run_in_both_standards_and_turn_with_the_input(archives, interface):
    """On the elastic and the crushing bed: 2.0 and 3.0 give the same outputs; the input rotated
    by 0.7 rad leaves the tilt and the contact unchanged (the bed and the body are round) and
    turns the lean by it; the contact is at most the base, the crushed part at most the contact
    (nothing crushed on the elastic bed)."""
    start = dict(BED, interface=interface)
    outputs = OUTPUTS + CONTACT
    r2, r3 = (run(p, start=start, outputs=outputs) for p in archives)
    for name in outputs:
        np.testing.assert_array_equal(r2[name], r3[name], err_msg=name)
    assert 0.05 < r2["theta"].max() and not r2["overturned"].any()
    area = math.pi * 0.5 ** 2
    assert (r2["contactArea"] <= area * (1 + 1e-15)).all() and r2["contactArea"].min() < 0.5 * area
    assert (r2["crushedArea"] <= r2["contactArea"]).all()
    assert (r2["crushedArea"].max() > 0) == (interface == 3)
    turned = run(archives[0], 0.7, start=start, outputs=outputs)
    np.testing.assert_allclose(turned["theta"], r2["theta"], rtol=0, atol=1e-9)
    moving = r2["theta"] > 1e-3
    shift = np.angle(np.exp(1j * (turned["psi"][moving] - r2["psi"][moving] - 0.7)))
    assert moving.sum() > 100 and np.abs(shift).max() < 1e-9
    for name in CONTACT:
        scale = np.abs(r2[name]).max()
        np.testing.assert_allclose(turned[name], r2[name], rtol=0, atol=1e-9 * scale, err_msg=name)
    np.testing.assert_array_equal(turned["regime"], r2["regime"])


