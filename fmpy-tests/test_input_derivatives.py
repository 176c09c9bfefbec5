"""Input derivatives (fmi2SetRealInputDerivatives) with a recorded ground motion.

`fmpy.simulate_fmu(..., set_input_derivatives=True)` fails on this FMU. The
defect is fmpy's (0.3.32), not the FMU's:

1. `fmpy.simulation.Input` keeps the derivatives of the continuous Real inputs
   in a ctypes buffer of a fixed 9 elements and assigns one value per input
   (`derivatives[:] = d`). With any other number of inputs than 9 (this FMU
   has one, `ag`) Python raises "ValueError: Can only assign sequence of same
   size" before fmi2SetRealInputDerivatives is called: the FMU never sees the
   call. The same happens with no FMU at all (a stub instance below).
2. With that buffer sized to the inputs, the FMU accepts every call (order 1,
   the value reference of `ag`), but fmpy passes, at a communication point
   that falls on a sample of the table, the slope of the segment that ENDS
   there in most steps: it finds the segment with `searchsorted` on the
   floating communication time, so which segment it takes depends on a
   rounding of n * interval against the table's times (87 % backward for the
   KATNP stand-in at its own dt), and at t = 0 it passes 0. The FMU then
   extrapolates the previous segment across the step: at h = dt the response
   is 6e-2 off the exact record's, against 8e-2 with no derivatives and 3e-8
   with the record's own slopes (table below).

FMI 2.0, section 4.2.1: fmi2SetRealInputDerivatives sets the n-th time
derivative of the inputs given by `vr` (`order` 1 is the first derivative;
`nvr` is the length of `vr`, `order` and `value`), with the same restrictions
as fmi2SetReal. The FMU declares canInterpolateInputs="true" (the only flag
fmpy's simulation checks; maxOutputDerivativeOrder it only parses).

The workaround: `rocking.RockingFMU.simulate` drives the FMU's C functions
itself and passes at each sample the slope of the segment that starts there,
so the FMU sees the record's piecewise-linear interpolation exactly. Checked
here: the values and slopes it sets are the record's, and its response agrees
with an independent host loop at a 10x finer communication step.

`python fmpy-tests/test_input_derivatives.py` prints the table of what input
derivatives buy (docs/examples.md shows it).
"""

import re
import sys
from ctypes import c_double, c_int, c_uint32
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from fmpy import simulate_fmu, simulation
from fmpy.fmi2 import FMU2Slave

from fmu_helpers import Host, start_values

RECORD = Path(__file__).resolve().parent.parent / "data" / "ground-motions" / "katnp-standin" / "KATNP_NS_standin.csv"
#: A slender block (alpha = 0.149 rad) that rocks under 0.8 x the KATNP stand-in
#: without overturning (peak |theta| / alpha = 0.037, 120 impacts), far enough
#: from overturning that a 1e-6 relative change of the record changes theta by
#: 6e-5 of its peak (at 0.9 x: 2e-3, at 1.0 x a 1 % change overturns it).
CASE = dict(shape="solidRectangle", B=0.3, H=2.0)
SCALE = 0.8
STOP = 80.0


def record():
    """The stand-in record as the file gives it: (time s, acc m/s2), read here
    with numpy, not with the package under test."""
    d = np.loadtxt(RECORD, delimiter=",", comments="#", skiprows=5)
    return d[:, 0], SCALE * d[:, 1]


def host_loop(fmu_path, unzipped, h, derivatives, stop=STOP):
    """theta at the communication points 0, h, 2h, ... of a plain host loop:
    at each point the record's linear interpolation, and (if `derivatives`) the
    slope of the chord to the next point. For h equal to or dividing the
    record's dt that chord is the record's own segment: the FMU then sees the
    piecewise-linear record exactly."""
    t_rec, a_rec = record()
    host = Host(fmu_path, unzipped)
    try:
        host.init(**start_values(CASE))
        f, c = host.fmu._functions, host.fmu.component
        vr_ag, order, val = (c_uint32 * 1)(host.vr["ag"]), (c_int * 1)(1), (c_double * 1)()
        vr_th, buf = (c_uint32 * 1)(host.vr["theta"]), (c_double * 1)()
        n = int(round(stop / h))
        grid = np.arange(n + 1) * h
        u = np.interp(grid, t_rec, a_rec)
        theta = np.empty(n + 1)
        f["fmi2GetReal"](c, vr_th, 1, buf)
        theta[0] = buf[0]
        for k in range(n):
            val[0] = u[k]
            assert f["fmi2SetReal"](c, vr_ag, 1, val) == 0
            if derivatives:
                val[0] = (u[k + 1] - u[k]) / (grid[k + 1] - grid[k])
                assert f["fmi2SetRealInputDerivatives"](c, vr_ag, 1, order, val) == 0
            assert f["fmi2DoStep"](c, grid[k], grid[k + 1] - grid[k], 1) == 0, host.messages[-1:]
            f["fmi2GetReal"](c, vr_th, 1, buf)
            theta[k + 1] = buf[0]
        return grid, theta
    finally:
        host.free()


def deviation(theta, reference):
    """max |theta - reference| / max |reference| over the communication points."""
    return float(np.max(np.abs(theta - reference)) / np.max(np.abs(reference)))


def signal():
    t, a = record()
    s = np.zeros(len(t), dtype=[("time", np.float64), ("ag", np.float64)])
    s["time"], s["ag"] = t, a
    return s


def fmpy_run(fmu, h, derivatives, calls=None):
    return simulate_fmu(fmu, start_values=start_values(CASE), input=signal(), stop_time=STOP,
                        output_interval=h, set_input_derivatives=derivatives, output=["theta"],
                        fmi_call_logger=None if calls is None else calls.append)


def buffer_sized_to_the_inputs(monkeypatch):
    """Patch fmpy 0.3.32's Input so that its derivative buffer has one element per input."""
    original = simulation.Input.__init__

    def init(self, *args, **kwargs):
        original(self, *args, **kwargs)
        self.continuous = [c._replace(derivatives=(c.derivatives._type_ * len(c.vrs))())
                           for c in getattr(self, "continuous", [])]

    monkeypatch.setattr(simulation.Input, "__init__", init)


# -- fmpy's defect -----------------------------------------------------------

def ag_reference(model_description):
    return next(v.valueReference for v in model_description.modelVariables if v.name == "ag")


def test_fmpy_fails_before_the_fmu_sees_an_input_derivative(fmu_path, model_description):
    """The exact error, where it is raised, and the FMI calls before it."""
    ag = ag_reference(model_description)
    calls = []
    with pytest.raises(ValueError, match="Can only assign sequence of same size") as info:
        fmpy_run(fmu_path, 0.01, True, calls)
    last = info.traceback[-1]
    assert Path(str(last.path)).parts[-2:] == ("fmpy", "simulation.py")
    assert last.name == "apply"  # Input.apply: `derivatives[:] = d`
    # fmi2SetReal(ag) in initialization mode went through; the derivative call was never made
    assert any(c.startswith("fmi2SetReal(") and f"vr=[{ag}]" in c and c.endswith("-> OK") for c in calls)
    assert not any("fmi2SetRealInputDerivatives" in c for c in calls)
    bad = [c for c in calls if not (c.endswith("-> OK") or c.startswith("fmi2Instantiate("))]
    assert not bad, bad


@pytest.mark.parametrize("inputs", [1, 2, 9, 10])
def test_fmpy_input_fails_with_no_fmu_unless_there_are_nine_inputs(inputs):
    """fmpy alone: a stub FMU2Slave (no binary loaded) whose FMI functions only
    record their arguments, and a model description with `inputs` continuous
    Real inputs. Input.apply fails for every count but 9."""
    recorded = []
    fmu = FMU2Slave.__new__(FMU2Slave)  # no __init__: nothing is loaded
    fmu.component = None
    fmu.fmi2SetReal = lambda c, vr, n, v: recorded.append(("value", list(vr), list(v)))
    fmu.fmi2SetRealInputDerivatives = lambda c, vr, n, o, v: recorded.append(("derivative", list(vr), list(v)[:n]))
    for name in ("fmi2SetInteger", "fmi2SetBoolean"):
        setattr(fmu, name, lambda *a: None)
    names = [f"u{i}" for i in range(inputs)]
    md = SimpleNamespace(modelVariables=[
        SimpleNamespace(name=n, causality="input", variability="continuous", type="Real", valueReference=i)
        for i, n in enumerate(names)])
    table = np.zeros(2, dtype=[("time", np.float64)] + [(n, np.float64) for n in names])
    table["time"] = [0.0, 1.0]
    for i, n in enumerate(names):
        table[n] = [0.0, i + 1.0]  # slope i + 1
    inp = simulation.Input(fmu, md, table, set_input_derivatives=True)
    assert len(inp.continuous[0].derivatives) == 9  # whatever the number of inputs
    if inputs == 9:
        inp.apply(0.5)
        assert recorded[-1] == ("derivative", list(range(9)), [i + 1.0 for i in range(9)])
    else:
        with pytest.raises(ValueError, match="Can only assign sequence of same size"):
            inp.apply(0.5)
        assert [r[0] for r in recorded] == ["value"]  # the values were set, the derivatives not


@pytest.mark.xfail(strict=True, raises=ValueError, reason=(
    "fmpy 0.3.32: simulation.Input keeps input derivatives in a fixed buffer of 9 "
    "elements; `derivatives[:] = d` raises ValueError for an FMU with one continuous "
    "Real input. Once fmpy sizes the buffer, this test fails by assertion instead "
    "(fmpy then passes backward slopes at the table's samples): revisit both."))
def test_simulate_fmu_with_input_derivatives_agrees_with_the_record(fmu_path, unzipped):
    result = fmpy_run(fmu_path, 0.01, True)
    _, reference = host_loop(fmu_path, unzipped, 0.001, True)
    assert deviation(result["theta"], reference[::10]) < 1e-5


def test_fmpy_with_the_buffer_fixed_passes_backward_slopes(fmu_path, unzipped, model_description, monkeypatch):
    """With the buffer sized (our patch), the FMU accepts every call, order 1
    for ag; the slope fmpy passes at a sample is that of the segment ending
    there in most steps, and the response then stays nearly as far from the
    exact record's as with no derivatives (6e-2 against 8e-2 at h = dt),
    where the record's own slopes bring it to 3e-8."""
    buffer_sized_to_the_inputs(monkeypatch)
    calls = []
    result = fmpy_run(fmu_path, 0.01, True, calls)
    der = [c for c in calls if c.startswith("fmi2SetRealInputDerivatives")]
    ag = ag_reference(model_description)
    assert der and all(f"vr=[{ag}], nvr=1, order=[1]" in c and c.endswith("-> OK") for c in der)
    passed = np.array([float(re.search(r"value=\[([^\]]*)\]", c).group(1)) for c in der])
    t, a = record()
    slope = np.diff(a) / np.diff(t)
    # passed[0] in initialization mode, passed[1 + k] before the step from t_k; at t_0 fmpy
    # gives 0 (it treats time == t[0] as before the table and holds the first sample)
    assert len(passed) == len(t) and passed[0] == passed[1] == 0.0 != slope[0]
    k = np.arange(1, len(t) - 1)
    step = passed[2:]
    backward = np.isclose(step, slope[k - 1], rtol=1e-9, atol=0) & (slope[k - 1] != slope[k])
    forward = np.isclose(step, slope[k], rtol=1e-9, atol=0)
    assert np.all(backward | forward)
    assert backward.mean() > 0.8  # 0.866 measured
    _, reference = host_loop(fmu_path, unzipped, 0.001, True)
    _, sloped = host_loop(fmu_path, unzipped, 0.01, True)
    assert deviation(result["theta"], reference[::10]) > 1e4 * deviation(sloped, reference[::10])


# -- our side and the workaround --------------------------------------------

def test_rocking_fmu_sets_the_records_values_and_slopes(fmu_path):
    """rocking.RockingFMU.simulate: before each step, ag = the sample and dag/dt
    = the slope of the segment that starts at it (order 1, ag's value
    reference), recorded by wrapping the FMU's C functions."""
    rocking = pytest.importorskip("rocking")
    t, a = record()
    with rocking.RockingFMU(fmu_path) as fmu:
        slave = fmu._library()
        raw = slave._functions
        seen = {"fmi2SetReal": [], "fmi2SetRealInputDerivatives": []}

        def spy(name):
            inner = raw[name]

            def call(c, vr, n, *rest):
                seen[name].append((list(vr[:n]), [list(x[:n]) for x in rest]))
                return inner(c, vr, n, *rest)
            # fmpy's own wrappers (FMU2Slave.fmi2SetReal) read these
            call.restype, call.argtypes, call.argnames = inner.restype, inner.argtypes, inner.argnames
            return call

        original = {name: raw[name] for name in seen}
        for name in seen:
            raw[name] = spy(name)
        try:
            # the Python loop, whose calls can be spied on (the native loop gives
            # the same outputs bit for bit: test_stepper.py)
            run = fmu.simulate(CASE, ag=(t, a), stop_time=STOP, outputs=("theta",), loop="python")
        finally:
            raw.update(original)
        ag_vr = fmu.variables["ag"].valueReference
    assert not run.overturned
    values = [x[0][0] for vr, x in seen["fmi2SetReal"] if vr == [ag_vr]]
    derivs = seen["fmi2SetRealInputDerivatives"]
    assert all(vr == [ag_vr] and x[0] == [1] for vr, x in derivs)
    slopes = np.array([x[1][0] for _, x in derivs])
    assert len(slopes) == len(t) - 1
    # the first value is set in initialization mode, then one per step
    # (RockingFMU interpolates the record at i * dt, which may differ from the file's times by an ulp)
    np.testing.assert_allclose(values, np.concatenate([[a[0]], a[:-1]]), rtol=0, atol=1e-12 * np.max(np.abs(a)))
    np.testing.assert_allclose(slopes, np.diff(a) / np.diff(t), rtol=1e-9, atol=1e-12)


def test_rocking_fmu_agrees_with_a_finer_independent_loop(fmu_path, unzipped):
    """RockingFMU.simulate at the record's dt against our plain host loop at
    dt / 10 with slopes (the exact piecewise-linear record, to the integrator's
    tolerance): within 1e-5 of max |theta| (3e-8 measured). Without the slopes
    (zero-order hold at dt) the same comparison is off by more than 1 % (8 %)."""
    rocking = pytest.importorskip("rocking")
    t, a = record()
    with rocking.RockingFMU(fmu_path) as fmu:
        run = fmu.simulate(CASE, ag=(t, a), stop_time=STOP, outputs=("theta",))
    _, reference = host_loop(fmu_path, unzipped, 0.001, True)
    reference = reference[::10]
    assert len(run.result) == len(reference)
    assert deviation(run.result["theta"], reference) < 1e-5
    _, same_step = host_loop(fmu_path, unzipped, 0.01, True)
    assert deviation(run.result["theta"], same_step) < 1e-9
    _, held = host_loop(fmu_path, unzipped, 0.01, False)
    assert deviation(held, reference) > 1e-2


# -- what input derivatives buy (prints the table of docs/examples.md) -------

def table(fmu_path, steps=(0.005, 0.01, 0.02)):
    from fmpy import extract

    unzipped = extract(fmu_path)
    mp = pytest.MonkeyPatch()
    buffer_sized_to_the_inputs(mp)
    rows = []
    try:
        for h in steps:
            _, ref = host_loop(fmu_path, unzipped, h / 10, True)
            ref = ref[::10]
            _, held = host_loop(fmu_path, unzipped, h, False)
            _, sloped = host_loop(fmu_path, unzipped, h, True)
            fm = fmpy_run(unzipped, h, True)["theta"]
            fm_held = fmpy_run(unzipped, h, False)["theta"]
            rows.append((h, deviation(held, ref), deviation(fm_held, ref), deviation(sloped, ref),
                         deviation(fm, ref)))
    finally:
        mp.undo()
    print(f"KATNP stand-in x {SCALE}, {CASE}, {STOP:g} s; reference: the loop with slopes at h / 10;")
    print("max |theta - theta_ref| / max |theta_ref| over the communication points")
    print("| h (s) | no derivatives (our loop) | no derivatives (fmpy) | record's slopes (our loop) "
          "| fmpy's slopes (buffer patched) |")
    print("|---|---|---|---|---|")
    for h, a, b, c, d in rows:
        print(f"| {h} | {a:.2e} | {b:.2e} | {c:.2e} | {d:.2e} |")


if __name__ == "__main__":
    table(sys.argv[1] if len(sys.argv) > 1 else str(Path(__file__).resolve().parent.parent
                                                      / "target" / "fmu" / "RockingBlock.fmu"))
