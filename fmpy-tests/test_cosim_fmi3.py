"""The co-simulation master on the FMI 3.0 archives (target/fmu/fmi3/,
docs/cosimulation.md §4b): the same runs as the 2.0 master bit for bit when
the inputs are the same (input rates through the der(x) inputs), and with
early return the communication points put on the block's impacts, checked
against Housner's closed-form impact times and against the monolithic
reference. ~7 s."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rocking.cosim import CoupledFMUs, frame_params, sine_ground
from rocking.cosim.reference import Reference
from rocking.cosim.study import convergence_case, errors
from test_model_exchange import Exact, rigid_block


@pytest.fixture(scope="module")
def fmus2():
    with CoupledFMUs() as f:
        yield f


@pytest.fixture(scope="module")
def fmus3():
    with CoupledFMUs(fmi=3) as f:
        yield f


def short_case(stop_time=1.5):
    case = convergence_case()
    case["stop_time"] = stop_time
    return case


@pytest.fixture(scope="module")
def short_reference():
    return Reference(**short_case())


@pytest.mark.parametrize("scheme", ["jacobi", "gauss-seidel"])
@pytest.mark.parametrize("inputs, ground_input", [("constant", "held"), ("midpoint", "midpoint"),
                                                  ("extrapolate", "chord")])
def test_the_3_0_master_is_the_2_0_master_bit_for_bit(fmus2, fmus3, scheme, inputs, ground_input):
    """The same scheme and ground input: 2.0 and 3.0 runs equal bit for bit, with
    step rejection (FMU states saved and restored at each impact: 47 rejected steps),
    inputs held at the step's start or at their midpoint, or extrapolated with their
    rates (2.0: fmi2SetRealInputDerivatives; 3.0: the der(x) inputs) and the ground's
    chord (the 2.0 master's default scheme)."""
    kw = dict(**short_case(), step=0.005, scheme=scheme, inputs=inputs, ground_input=ground_input)
    a, b = fmus2.run(**kw), fmus3.run(**kw)
    assert a.rejected == b.rejected > 10 and b.early_returns == []
    for name in ("time", "theta", "omega", "a_floor", "Fx", "Fz", "u"):
        assert getattr(a, name).tobytes() == getattr(b, name).tobytes(), name
    assert np.abs(a.theta).max() > 0.1


def test_early_return_puts_communication_points_on_housner_impacts(fmus3):
    """A rigid block released from half its slenderness on a heavy, stiff storey
    (block/floor mass 5e-7, 6 ms period), no ground motion, 50 ms steps: each of the
    first 6 impacts ends a communication step early, at Housner's closed-form impact
    time (to the storey's own small effect), and the run goes on along the grid."""
    ex = Exact(0.25, 1.0)
    exact = np.array(ex.impact_times(0.5 * ex.alpha, 6))
    h, stop = 0.05, exact[-1] + 0.01
    res = fmus3.run(frame=frame_params([1e9], [1e15]), block=rigid_block(), floor=1,
                    ground=lambda t: 0.0 * np.asarray(t), stop_time=stop, step=h, inputs="constant",
                    reject=False, early_return=True)
    got = np.array(res.early_returns)
    assert len(got) == len(exact)
    err = np.abs(got - exact) / exact
    print(f"\nworst relative error of the early returns against Housner: {err.max():.1e}")
    assert err.max() < 1e-6  # measured 3.0e-7; 2.5e-5 on a storey 100 times lighter and softer
    assert np.isin(got, res.time).all()  # communication points
    grid = np.minimum(np.arange(int(np.ceil(stop / h - 1e-9)) + 1) * h, stop)
    assert np.isin(grid, res.time).all() and len(res.time) == len(grid) + len(got)
    assert (np.abs(res.theta[np.isin(res.time, got)]) < 1e-12).all()  # theta = 0 there


def _early_return_errors(fmus, ref, **kw):
    """{h: (error in theta, largest error in the impact times (s))} at 5 and 2.5 ms, the
    elastic block of the convergence case (1.5 s) with early return, each of the
    reference's 3 impacts an early return."""
    out = {}
    for h in (0.005, 0.0025):
        res = fmus.run(**short_case(), step=h, early_return=True, **kw)
        got = np.array(res.early_returns)
        assert len(got) == len(ref.impact_times) == 3
        out[h] = (errors(res, ref)["theta"], np.abs(got - ref.impact_times).max())
    print(f"\nerror in theta, in impact times (s): {out}")
    return out


def test_early_return_converges_to_the_reference_and_its_impact_times(fmus3, short_reference):
    """Inputs held: with early return the run's impacts are communication points, the
    error against the monolithic reference halves with the step (order 1), and so does
    the error in the impact times."""
    out = _early_return_errors(fmus3, short_reference, inputs="constant", reject=False, ground_input="midpoint")
    assert 1.6 < out[0.005][0] / out[0.0025][0] < 2.6
    assert 1.6 < out[0.005][1] / out[0.0025][1] < 2.6
    assert out[0.0025][0] < 0.02 and out[0.0025][1] < 2e-3


def test_early_return_with_input_rates_converges_at_order_2(fmus2, fmus3, short_reference):
    """The 2.0 master's scheme on the 3.0 FMUs (extrapolated inputs with their rates in
    the der(x) inputs, the ground's chord, rejection) with early return: the error in
    theta against the monolithic reference falls 5.2 times from 5 to 2.5 ms (order 2),
    is at 2.5 ms no larger than the 2.0 master's (no early return), and the impacts,
    communication points, are within 8e-6 s of the reference's (the held scheme: 1e-3 s)."""
    out = _early_return_errors(fmus3, short_reference)
    two = errors(fmus2.run(**short_case(), step=0.0025), short_reference)["theta"]
    assert out[0.005][0] / out[0.0025][0] > 3.5  # measured 5.2
    assert out[0.0025][0] < 1.1 * two  # measured 5.1e-5 against 5.3e-5
    assert out[0.0025][1] < 2e-5  # measured 7.5e-6 s (5.2e-5 at 5 ms)


def test_early_return_at_a_rigid_blocks_impacts_is_as_accurate_as_rejection(fmus2, fmus3):
    """A rigid block (its force jumps at uplift and at each impact) on the convergence
    case's frame, 3 s, h = 2 ms: with der(x) inputs and early return, the error in theta
    after 2 s against the 2.0 master at 0.5 ms is that of the 2.0 master (rejection, no
    early return) at 2 ms: 2.75e-5 against 2.79e-5 of the peak. It was 3.1 times that
    (8.6e-5, order 1) when the frame got, over the rest of a step that returned early,
    the block's force for its ag before the jump: the master now settles the algebraic
    loop at an early return."""
    case = convergence_case()
    case["block"] = {"interface": "rigid"}
    ref = fmus2.run(**case, step=5e-4)
    peak = np.abs(ref.theta).max()

    def late_error(res):
        on_grid = (res.time > 2.0) & ~np.isin(res.time, res.early_returns)
        return np.abs(res.theta[on_grid] - np.interp(res.time[on_grid], ref.time, ref.theta)).max() / peak

    early = fmus3.run(**case, step=0.002, early_return=True)
    assert len(early.early_returns) >= 7  # uplift (twice, 2 us apart: the settled ag) and 6 impacts
    assert late_error(early) < 1.3 * late_error(fmus2.run(**case, step=0.002))


def test_options_the_fmus_cannot_take_are_refused(fmus2, fmus3, monkeypatch):
    kw = dict(**short_case(0.1), step=0.01)
    with pytest.raises(ValueError, match="early_return = True needs the FMI 3.0 FMUs"):
        fmus2.run(**kw, early_return=True)
    with pytest.raises(ValueError, match="inputs = 'linear': not one of"):
        fmus3.run(**kw, inputs="linear")
    with pytest.raises(ValueError, match="fmi = 4"):
        CoupledFMUs(fmi=4)
    # a 3.0 frame that declares no der(x) inputs: rates refused, held inputs still run
    monkeypatch.setattr(fmus3.frame, "_rate_of", {})
    with pytest.raises(ValueError, match=r"ground_input = 'chord' needs the input der\(ag\) of .*ShearFrame"):
        fmus3.run(**kw)
    with pytest.raises(ValueError, match=r"inputs = 'extrapolate' needs the input der\(Fx\[3\]\)"):
        fmus3.run(**kw, ground_input="midpoint")
    assert fmus3.run(**kw, inputs="midpoint", ground_input="midpoint").time[-1] == 0.1


def _rocking(*args):
    exe = Path(sys.executable).parent / "rocking"
    return subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, timeout=300)


def test_cli_runs_the_3_0_fmus_with_early_return(tmp_path):
    case = tmp_path / "case.toml"
    case.write_text("[frame]\nmasses = [1e4, 1e4, 1e4]\nstiffnesses = [4e6, 4e6, 4e6]\nzeta = 0.02\n"
                    "[block]\ninterface = \"elastic\"\nkn = 1e8\n"
                    "[ground]\namplitude = 4.0\nfrequency = 2.0\ncycles = 3\n"
                    "[coupling]\nfloor = 3\nstep = 0.005\nstop_time = 1.5\nearly_return = true\n")
    run = _rocking("cosim", case, "--out", tmp_path / "out", "--fmi", "3")
    assert run.returncode == 0, run.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["options"]["fmi"] == 3 and len(summary["early_returns_s"]) == 3
    assert (summary["options"]["inputs"], summary["options"]["ground_input"]) == ("extrapolate", "chord")
    assert "3 early returns" in run.stdout


@pytest.mark.parametrize("early_return", [False, True])
def test_overturning_ends_the_3_0_run_where_the_2_0_run_ends(fmus2, fmus3, early_return):
    """The stronger shake of test_cosim's overturning test, inputs held: the 3.0 block
    ends the run with terminateSimulation at the time the 2.0 block discards, the
    frame brought to that time, bit for bit, with or without early return (the block
    overturns in its first excursion: no impact, no early return before)."""
    strong = dict(short_case(2.0), ground=sine_ground(7.0, 2.0, cycles=3))
    kw = dict(**strong, step=0.002, inputs="constant", reject=False)
    a = fmus2.run(**kw)
    b = fmus3.run(**kw, early_return=early_return)
    assert a.overturned and b.overturned and b.time[-1] == b.t_overturn < 2.0
    assert b.early_returns == []
    assert b.t_overturn == a.t_overturn and b.u.tobytes() == a.u.tobytes()


def test_midpoint_inputs_converge_at_order_2_with_or_without_early_return():
    """inputs="midpoint" with FMI 3.0 (each input held at its extrapolation's mean
    over the step, the ground at its chord's), §4's elastic case (3 s): the error in theta falls 3.7 times from
    5 to 2.5 ms (1.2 times with the FMUs' own output derivatives, which leave out the
    inputs' rates), and early return leaves it as it is (0.91 times at 2.5 ms; 1.9
    times when the part of a step before an impact kept the whole step's midpoint
    inputs). The two regressions this guards."""
    case = convergence_case()
    ref = Reference(**case)
    with CoupledFMUs(fmi=3) as fmus:
        kw = dict(inputs="midpoint", ground_input="midpoint", reject=False)
        e = [errors(fmus.run(**case, step=h, **kw), ref)["theta"] for h in (0.005, 0.0025)]
        early = fmus.run(**case, step=0.0025, early_return=True, **kw)
    assert e[0] / e[1] > 3.0 and e[1] < 1e-3  # measured 3.7 and 6.3e-4
    assert len(early.early_returns) == len(ref.impact_times) == 6
    assert errors(early, ref)["theta"] < 1.3 * e[1]
