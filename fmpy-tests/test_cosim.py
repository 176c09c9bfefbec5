"""The co-simulation master (rocking.cosim, docs/cosimulation.md) against the
monolithic reference, which is itself checked first: its energy balance, and
its one-way limit against RockingBlock.fmu driven by the reference's floor.

Runs in ~1 min: the convergence case of docs/cosimulation.md (3 storeys, block
on the roof, 3 s), the steps of the convergence plot's fine end.
"""

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rocking.cosim import CoupledFMUs, frame_params, sine_ground
from rocking.cosim.reference import Reference
from rocking.cosim.study import convergence_case, errors, slope

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def fmus():
    with CoupledFMUs() as f:
        yield f


@pytest.fixture(scope="module")
def case():
    return convergence_case()


@pytest.fixture(scope="module")
def ref(case):
    return Reference(**case)


# -- the reference -------------------------------------------------------------------

def test_reference_conserves_energy_without_damping_and_losses():
    """No damping, restitution 1, fixed ground, the frame released from a deformed shape:
    the energy of frame plus block (kinetic with the floor's velocity, strain, the block's
    potential by quadrature) is constant, through uplifts and zero crossings. The coupling
    law transfers work without creating or losing any (docs/model.md §5)."""
    r = Reference(frame_params([1e4] * 3, [4e6] * 3, zeta=0.0),
                  {"interface": "elastic", "kn": 1e8, "restitution": "given", "eta": 1.0}, floor=3,
                  ground=lambda t: 0.0 * np.asarray(t), stop_time=1.5, u0=[0.01, 0.02, 0.03])
    assert len(r.impact_times) >= 3 and r.peak("theta") > 10 * r.body.thetaJo  # it rocks
    e = r.energy(np.linspace(0.0, 1.5, 61))
    assert np.max(np.abs(e - e[0])) / e[0] < 1e-9  # measured 1.6e-11 over 3 s


def test_reference_one_way_is_the_fmu_driven_by_the_floor(case):
    """One-way, the block is driven by the frame's floor: RockingBlock.fmu fed that floor
    acceleration (sampled every 0.2 ms, linear in between) gives the reference's theta."""
    from rocking.fmu import RockingFMU
    ref1 = Reference(**case, coupling="one-way")
    t = np.arange(0.0, 3.0 + 1e-4, 2e-4)
    with RockingFMU() as f:
        run = f.simulate(case["block"], ag=(t, ref1.at(t)["a_floor"]), stop_time=3.0, rtol=1e-11)
    th = ref1.at(run.result["time"], accelerations=False)["theta"]
    assert np.max(np.abs(run.result["theta"] - th)) / np.max(np.abs(th)) < 1e-5  # measured 6.5e-7


# -- the master against it -----------------------------------------------------------

STEPS = [0.005, 0.0025, 0.00125]


@pytest.mark.parametrize("scheme", ["jacobi", "gauss-seidel"])
@pytest.mark.parametrize("inputs,order", [("constant", 1.0), ("extrapolate", 2.0)])
def test_order_of_convergence(fmus, case, ref, scheme, inputs, order):
    """Fitted slopes of the error in theta and in the floor's acceleration against the
    step (with step rejection at impacts): 1 for constant inputs, 2 extrapolated."""
    errs = [errors(fmus.run(**case, step=h, scheme=scheme, inputs=inputs, reject=True), ref) for h in STEPS]
    for key in ("theta", "a_floor"):
        fitted = slope(STEPS, [e[key] for e in errs])
        assert abs(fitted - order) < 0.35, f"{key}: slope {fitted:.2f}, expected {order}"


def test_agrees_with_the_reference_at_a_small_step(fmus, case, ref):
    res = fmus.run(**case, step=0.000625, scheme="gauss-seidel", inputs="extrapolate", reject=True)
    e = errors(res, ref)
    assert e["theta"] < 2e-4 and e["a_floor"] < 2e-4, e  # measured 5e-5, 6e-5
    assert e["peak_theta"] < 1e-3 and e["peak_a_floor"] < 1e-3, e


def test_one_way_leaves_the_frame_alone(fmus, case):
    """One-way, the frame does not feel the block: its floors move the same, bit for bit,
    under a block ten times heavier (and a bed ten times stiffer: the same rocking);
    two-way they do not."""
    light = fmus.run(**case, step=0.005, coupling="one-way")
    heavy = dict(case, block={**case["block"], "rho": 18000.0, "kn": 1e9})
    one = fmus.run(**heavy, step=0.005, coupling="one-way")
    two = fmus.run(**heavy, step=0.005, coupling="two-way")
    assert np.array_equal(light.u, one.u)
    assert np.max(np.abs(two.u - one.u)) > 1e-3 * np.max(np.abs(one.u))


def test_overturning_ends_the_run_with_the_frame_kept(fmus, case):
    """A stronger shake overturns the block: the run ends at the FMU's overturning time
    (the reference's to 1e-5 s), and the frame's serialized state, restored in a fresh
    instance, is the frame at that time."""
    strong = dict(case, ground=sine_ground(7.0, 2.0, cycles=3))
    ref = Reference(**strong)
    assert ref.overturned
    res = fmus.run(**strong, step=0.001)
    assert res.overturned and res.time[-1] == res.t_overturn < strong["stop_time"]
    assert abs(res.t_overturn - ref.t_overturn) < 1e-5  # measured 4e-6
    assert abs(abs(res.theta[-1]) - ref.body.thetaOv) < 1e-9
    frame = fmus.frame
    frame.instantiate(strong["frame"], 0.0, 3.0)
    try:
        frame.exit_init()
        frame.set_state(frame._slave.deSerializeFMUstate(res.frame_state))
        u = frame.get(frame.refs(["u[1]", "u[2]", "u[3]"]))
        assert u == list(res.u[-1])
        assert frame.do_step(res.t_overturn, 0.01) == 0  # the structure goes on alone
    finally:
        frame.free()
    assert np.max(np.abs(res.u[-1] - ref.at([res.t_overturn])["u"][0])) < 1e-4 * np.max(np.abs(res.u[-1]))


# -- the command ---------------------------------------------------------------------

def _rocking(*args):
    exe = Path(sys.executable).parent / "rocking"
    return subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, timeout=300)


def test_cli_runs_the_example_case(tmp_path, case, ref):
    proc = _rocking("cosim", REPO / "examples" / "cosim" / "roof_block.toml", "--out", tmp_path, "--reference")
    assert proc.returncode == 0, proc.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    # --reference: the command's own check, the same as errors() against our reference
    assert summary["error_against_reference"]["theta"] < 1e-3  # measured 1.4e-4
    assert (tmp_path / "plot.png").stat().st_size > 10_000
    table = np.genfromtxt(tmp_path / "timehistory.csv", delimiter=",", names=True)
    assert summary["peak_theta_rad"] == pytest.approx(np.max(np.abs(table["theta"])), rel=1e-12)
    # theta over alpha (the plot's panel, issue 25): the default 0.5 m x 2.5 m prism, alpha = atan(B/H)
    assert summary["alpha_rad"] == pytest.approx(math.atan(0.5 / 2.5), rel=1e-12)
    assert summary["peak_theta_over_alpha"] == pytest.approx(summary["peak_theta_rad"] / math.atan(0.2), rel=1e-12)
    # the example is the convergence case at h = 2 ms: within 1 % of the reference
    assert summary["peak_theta_rad"] == pytest.approx(ref.peak("theta"), rel=0.01)
    assert summary["peak_a_floor_m_s2"] == pytest.approx(ref.peak("a_floor"), rel=0.01)


def test_cli_names_the_mistake(tmp_path):
    bad = tmp_path / "case.toml"
    bad.write_text("[frame]\nmasses = [1e4]\nstiffnesses = [4e6]\n[ground]\namplitude = 1\nfrequency = 2\n"
                   "[coupling]\nstep = 0.01\n")
    proc = _rocking("cosim", bad, "--out", tmp_path / "out")
    assert proc.returncode == 2
    assert "case.toml" in proc.stderr and "floor" in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
