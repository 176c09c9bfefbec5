"""RoundBody.fmu's Model Exchange on the flexible and crushing beds (both formulations: `costa`, and
`shiftingPivot`, whose Model Exchange state is `omegaW`, docs/model.md §11.5) under a second host,
fmpy's CVode, against the same archive's co-simulation, in FMI 2.0 and 3.0: both horizontal
components and `av` as inputs, the tilt (ex, ey, theta), the regime and the impacts at every output,
the overturning time, and coming to rest. The Rust hosts (fmu-round-body/src/tests_me.rs,
tests/spatial_flexible_me.rs) are the first; only outputs are compared, no state names.

Both runs must see the same input, so it is piecewise linear between knots every KNOT s, and the
host's gaps are closed here, not in the FMU:

- fmpy 0.3.32's CVode right-hand side sets the time and the states but not the inputs (its root
  function does), so the derivatives it sees are those of the input where the last root or output
  evaluation set it; the `input_in_rhs` fixture applies the input there too. Unpatched, CVode at
  rtol 1e-10 stops after 4.4 ms at its 500 steps per output interval (measured).
- fmpy's co-simulation gives at a sample the slope of the segment *before* it (and none at the
  first sample), which the FMU extrapolates over the step; every knot is given twice (an input
  event of fmpy's, after which it takes the segment after), with one sample before t = 0, so that
  each step of KNOT s gets its own segment's slope: `agx`'s derivative through
  fmi2SetRealInputDerivatives in 2.0, the inputs `der(agx)` .. in 3.0. Checked on the elastic
  case: co-simulation's tilt in steps of 5 ms is that in steps of 1 ms to 2.1e-11 rad, of 0.25 ms
  to 6.1e-12 (in 2.0 without the sample before 0, whose first step then gets no slope: 3.2e-4 rad).
"""

import math

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.sundials import CVodeSolver

from conftest import TARGET, size_input_derivative_buffer

FMU2 = TARGET / "fmu" / "RoundBody.fmu"
FMU3 = TARGET / "fmu" / "fmi3" / "RoundBody.fmu"
OUTPUTS = ["theta", "ex", "ey", "regime", "impacts", "overturned"]
INPUTS = ("agx", "agy", "av")
# the inputs' knots, and both hosts' output interval, s
KNOT = 0.005
RTOL = 1e-10
# the default drum (Ro 0.5 m, H 3 m) on a bed of kn = 1e8 Pa/m (thetaJo 1.2e-3 rad), crushing at
# fm = 0.3 MPa on elastoPlastic (3); costa (1) unless a test sets shiftingPivot (2)
BED = {"kn": 1e8, "fm": 3e5, "formulation": 1}
COSTA, SHIFTING_PIVOT = 1, 2
ELASTIC, CRUSHING = 2, 3
# g tan(alpha) of the drum, m/s2
UPLIFT = 9.81 / 3.0


@pytest.fixture(scope="module", params=[FMU2, FMU3], ids=["fmi2", "fmi3"])
def archive(request):
    if not request.param.is_file():
        pytest.fail(f"{request.param} not found: run `cargo xtask fmu` first", pytrace=False)
    return str(request.param)


@pytest.fixture
def input_in_rhs(monkeypatch):
    """CVode's right-hand side applies the input at its time (see the module's docstring); and
    fmpy's buffer of input derivatives, 9 long, sized to the 3 inputs (as test_round_body.py)."""
    rhs = CVodeSolver.f

    def f(self, t, y, ydot, user_data):
        self.input.apply(t)
        return rhs(self, t, y, ydot, user_data)

    monkeypatch.setattr(CVodeSolver, "f", f)
    size_input_derivative_buffer(monkeypatch)


def pulse_train(t):
    """1.6 times the uplift threshold at 1.3 Hz, decaying at 0.25 /s (tests/support/drum.rs), m/s2."""
    return 1.6 * UPLIFT * np.sin(2 * math.pi * 1.3 * t) * np.exp(-0.25 * t)


def rocking(t):
    """Two components off any plane and a vertical one of 2 m/s2 at 3.1 Hz (tests/spatial_flexible_me.rs)."""
    return pulse_train(t), 0.7 * pulse_train(1.37 * t + 0.2), 2.0 * np.sin(2 * math.pi * 3.1 * t)


def oblique(t):
    """The pulse train along the azimuth 0.7 rad (a planar motion, so an impact at each crossing)
    and the vertical of `rocking`."""
    return math.cos(0.7) * pulse_train(t), math.sin(0.7) * pulse_train(t), 2.0 * np.sin(2 * math.pi * 3.1 * t)


def overturning(t):
    """The strong two-component input that overturns the drum on the crushing bed, no av."""
    return 2.2 * pulse_train(t), 1.2 * pulse_train(t + 0.1), 0.0 * t


def signals(ground, stop, fmi3):
    """The input at knots every KNOT s, for Model Exchange (interpolated by fmpy) and for
    co-simulation (each knot twice, one knot before 0, the slopes as `der(..)` columns in 3.0)."""
    t = np.arange(0.0, stop + 1.5 * KNOT, KNOT)
    values = dict(zip(INPUTS, ground(t)))
    me = np.zeros(len(t), dtype=[(n, np.float64) for n in ("time",) + INPUTS])
    me["time"] = t
    for name in INPUTS:
        me[name] = values[name]
    names = ("time",) + INPUTS + (tuple(f"der({n})" for n in INPUTS) if fmi3 else ())
    cs = np.zeros(1 + 2 * len(t), dtype=[(n, np.float64) for n in names])
    cs["time"] = np.concatenate([[-KNOT], np.repeat(t, 2)])
    for name in INPUTS:
        v = values[name]
        cs[name] = np.concatenate([[2 * v[0] - v[1]], np.repeat(v, 2)])
        if fmi3:
            # piecewise constant: the segment before a knot, then after it
            slope = np.diff(v) / KNOT
            before = np.concatenate([[slope[0]], slope])
            after = np.concatenate([slope, [slope[-1]]])
            cs[f"der({name})"] = np.concatenate([[slope[0]], np.column_stack([before, after]).ravel()])
    return me, cs


def me_and_cs(path, interface, ground, stop, cs_start=None, formulation=COSTA):
    """Model Exchange (CVode at RTOL) and co-simulation (the FMU's integrator at RTOL, steps of
    KNOT, FMI 3.0's returning early at its events), both as recorded: Model Exchange has extra
    rows at its events, co-simulation at an early return."""
    fmi3 = "fmi3" in path
    me_signal, cs_signal = signals(ground, stop, fmi3)
    start = dict(BED, interface=interface, formulation=formulation)
    common = dict(stop_time=stop, output_interval=KNOT, output=OUTPUTS, relative_tolerance=RTOL)
    me = simulate_fmu(path, fmi_type="ModelExchange", solver="CVode", input=me_signal, start_values=start, **common)
    cs = simulate_fmu(path, fmi_type="CoSimulation", input=cs_signal, set_input_derivatives=not fmi3,
                      early_return_allowed=fmi3, start_values=dict(start, **(cs_start or {})), **common)
    return me, cs


def on_grid(result):
    """The rows at multiples of KNOT, the last of each time (after its events)."""
    k = np.round(result["time"] / KNOT)
    regular = result[np.abs(result["time"] - k * KNOT) < 1e-9]
    k = np.round(regular["time"] / KNOT)
    return regular[np.append(k[1:] != k[:-1], True)]


def tilt_gap(me, cs):
    n = min(len(me), len(cs))
    return max(np.abs(me[k][:n] - cs[k][:n]).max() for k in ("theta", "ex", "ey"))


@pytest.mark.parametrize("formulation", [COSTA, SHIFTING_PIVOT], ids=["costa", "shiftingPivot"])
@pytest.mark.parametrize("interface", [ELASTIC, CRUSHING], ids=["elastic", "crushing"])
@pytest.mark.parametrize("ground", [rocking, oblique], ids=["two components", "oblique plane"])
def test_model_exchange_under_cvode_follows_co_simulation_on_a_flexible_bed(archive, input_in_rhs, interface, ground,
                                                                            formulation):
    """Both components and av from rest: the same impacts (applications of the restitution rule),
    regime and no overturning at every output, and theta, ex, ey to 2e-7 rad. Measured at CVode's
    rtol 1e-10, both archives, elastic / crushing: 6.2e-8 / 2.9e-8 rad off any plane (1 / 0
    impacts), 1.5e-8 / 1.1e-8 in the oblique plane (5 / 5); off a plane at rtol 1e-11 7.9e-9 and
    8.7e-10, so the gap is the host's error. With kn 1e-4 larger in co-simulation only: 8.0e-6
    and 4.9e-6 rad off a plane; with fmpy's own co-simulation input (no doubled knots): 1.4e-3 rad
    and a regime apart. shiftingPivot (Model Exchange integrating omegaW): 5.8e-8 / 8.4e-9 off any
    plane, 2.1e-8 / 1.6e-8 in the oblique plane; its peaks 1-4 % below costa's, so a run of the
    other formulation on one side is 4e-3 rad apart."""
    me, cs = (on_grid(r) for r in me_and_cs(archive, interface, ground, 2.5, formulation=formulation))
    assert len(me) == len(cs) and np.abs(me["time"] - cs["time"]).max() < 1e-9
    gap = tilt_gap(me, cs)
    peak = cs["theta"].max()
    print(f"{archive} interface {interface} formulation {formulation} {ground.__name__}: peak {peak:.4f} rad, impacts {me['impacts'][-1]} / "
          f"{cs['impacts'][-1]}, |d(theta, ex, ey)| {gap:.2e} rad")
    assert peak > 0.05
    azimuth = np.unwrap(np.arctan2(cs["ey"], cs["ex"])[cs["theta"] > 0.01])
    if ground is rocking:
        assert np.ptp(azimuth) > 0.5, "off a plane"
    else:
        assert cs["impacts"][-1] >= 3 and np.abs(np.sin(azimuth - 0.7)).max() < 1e-9, "in the plane"
    np.testing.assert_array_equal(me["impacts"], cs["impacts"])
    np.testing.assert_array_equal(me["regime"], cs["regime"])
    assert not me["overturned"].any() and not cs["overturned"].any()
    if interface == CRUSHING:
        assert (cs["regime"] >= 5).any(), "the base crushes"
    assert gap <= 2e-7


def test_model_exchange_under_cvode_overturns_with_co_simulation(archive, input_in_rhs):
    """The strong input on the crushing bed: both overturn, at the same time to 1e-7 s and the
    same tilt to 2e-7 rad (measured 2e-9 s and 2.65e-9 rad before), after the same impacts and
    regimes. Co-simulation's overturning time is FMI 2.0's lastSuccessfulTime of the discarded
    step, 3.0's early return."""
    stop = 3.0
    me, cs = me_and_cs(archive, CRUSHING, overturning, stop)
    gm, gc = on_grid(me), on_grid(cs)
    n = min(len(gm), len(gc))
    gap = tilt_gap(gm[:n], gc[:n])
    print(f"{archive}: overturned at {me['time'][-1]:.9f} / {cs['time'][-1]:.9f} s, theta {me['theta'][-1]:.9f} / "
          f"{cs['theta'][-1]:.9f} rad, impacts {me['impacts'][-1]} / {cs['impacts'][-1]}, |d(theta, ex, ey)| before "
          f"{gap:.2e} rad")
    # Model Exchange's last row is the host's at the located root, before the event update sets
    # `overturned` and terminates: the run's end before `stop` is its outcome
    assert cs["overturned"][-1] and not cs["overturned"][:-1].any() and not me["overturned"].any()
    assert me["time"][-1] < stop - KNOT
    assert abs(me["time"][-1] - cs["time"][-1]) <= 1e-7
    assert abs(me["theta"][-1] - cs["theta"][-1]) <= 2e-7
    assert me["impacts"][-1] == cs["impacts"][-1]
    np.testing.assert_array_equal(gm["regime"][: n - 1], gc["regime"][: n - 1])
    assert (gc["regime"] >= 5).any(), "the base crushes"
    assert gap <= 2e-7


def test_model_exchange_under_cvode_comes_to_rest_with_co_simulation(archive):
    """Free rocking in full contact on the elastic bed (from 1e-3 rad along 0.7 rad, inside
    thetaJo = 1.2e-3 rad), no input: the restitution rule at each crossing, then rest where the
    amplitude falls below rtol thetaOv (docs/model.md §11.3), after the same number of rules (92)
    and at the same output (14.89 s). fmpy's Model Exchange gives the FMU no tolerance, which then
    takes its default experiment's (1e-9), so co-simulation runs at that one too. The count is
    as fine as the threshold, 3e-10 rad: CVode at rtol 1e-10 gives 91, at 1e-11 93, at 1e-12 92
    (measured; also on the crushing bed, 94, and along 2.0 rad). The counts agree at every output
    but one (14.72 s, 0.17 s before rest: a crossing of the last few, located either side of it).
    With kn 1e-3 larger in co-simulation only: rest at 14.88 s and the counts apart at 36 outputs."""
    from fmpy import read_model_description

    start = dict(BED, interface=ELASTIC, theta0=1e-3, psi0=0.7)
    common = dict(stop_time=20.0, output_interval=0.01, output=OUTPUTS, start_values=start)
    me = simulate_fmu(archive, fmi_type="ModelExchange", solver="CVode", relative_tolerance=1e-12, **common)
    default = read_model_description(archive).defaultExperiment.tolerance
    cs = simulate_fmu(archive, fmi_type="CoSimulation", relative_tolerance=float(default), **common)
    me = on_grid(me)

    def rest(r):
        moving = np.flatnonzero(r["theta"] != 0.0)
        return r["time"][moving[-1] + 1]

    apart = np.flatnonzero(me["impacts"] != cs["impacts"])
    print(f"{archive}: rules {me['impacts'][-1]} / {cs['impacts'][-1]}, rest at {rest(me):.2f} / {rest(cs):.2f} s, "
          f"counts apart at {me['time'][apart]} {me['impacts'][apart]} {cs['impacts'][apart]}")
    assert len(me) == len(cs) and me["impacts"][-1] >= 20
    assert me["impacts"][-1] == cs["impacts"][-1]
    assert rest(me) == rest(cs) < 19.0
    # the counts at every output, but for a crossing just before rest falling either side of one
    assert np.abs(me["impacts"] - cs["impacts"]).max() <= 1 and len(apart) <= 2
