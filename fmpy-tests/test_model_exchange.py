"""Model Exchange: fmpy integrates RockingBlock's states with its own solvers
(CVode, explicit Euler) and reproduces co-simulation (docs/model-exchange.md):
rigid free rocking against the exact solution, the Dharahara tower's
overturning under the stand-in record, an elastic and a crushing case, and a
rigid block coming to rest after a bounded number of events."""

import math

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu
from scipy.integrate import quad
from scipy.optimize import brentq

from fmu_helpers import start_values
from rocking import RockingFMU
from rocking.cases import dharahara_cases
from rocking.groundmotion.katnp import katnp_standin

def cvode_applies_inputs():
    """fmpy 0.3.32's CVode right-hand side sets the time and the states but not
    the inputs (only its root function applies them), so with a time-varying
    input the derivatives use whatever input the last root-function call set:
    the right-hand side then depends on the call history, and CVode fails its
    error test at tight tolerances. Returns (class, name, replacement) for a
    right-hand side that applies the inputs too."""
    from fmpy.sundials import CVodeSolver

    original = CVodeSolver.f

    def f(self, t, y, ydot, user_data):
        self.input.apply(t)
        return original(self, t, y, ydot, user_data)

    return CVodeSolver, "f", f


@pytest.fixture(autouse=True)
def fmpy_cvode_applies_inputs(monkeypatch):
    monkeypatch.setattr(*cvode_applies_inputs())


OUT = ["theta", "omega", "impacts", "zeroCrossings", "overturned", "regime"]


def rigid_block(b=0.25, h=1.0, theta_over_alpha=0.5):
    alpha = math.atan(b / h)
    return dict(shape="solidRectangle", B=b, L=1.0, massModel="prism", H=h, rho=2000.0,
                interface="rigid", restitution="housner", g=9.81, theta=theta_over_alpha * alpha,
                omega=0.0)


class Exact:
    """Housner's rigid free rocking of a solid rectangular prism, in closed form
    up to quadratures (independent of the FMU): energy conserved between
    impacts, multiplied by eta² at each, V(phi) = W R0 (cos(alpha - phi) - cos alpha)."""

    def __init__(self, b, h, g=9.81):
        self.alpha = math.atan(b / h)
        self.r0 = 0.5 * math.hypot(b, h)
        # per unit mass: IO / m = (4/3) R0², W R0 / m = g R0
        self.io = 4.0 / 3.0 * self.r0 ** 2
        self.wr0 = g * self.r0
        self.eta = 1 - 1.5 * math.sin(self.alpha) ** 2

    def v(self, phi):
        return 2 * self.wr0 * math.sin(phi / 2) * math.sin(self.alpha - phi / 2)

    def fall_time(self, phi):
        # psi = phi sin(u) removes the turning-point singularity
        def f(u):
            psi = phi * math.sin(u)
            # V(phi) - V(psi) without cancellation
            dv = 2 * self.wr0 * math.sin(self.alpha - (phi + psi) / 2) * math.sin((phi - psi) / 2)
            return phi * math.cos(u) / math.sqrt(2 * dv / self.io)
        return quad(f, 0, math.pi / 2, epsabs=0, epsrel=1e-13, limit=200)[0]

    def accumulation_time(self, theta0):
        """When the impacts of a block released from theta0 accumulate: their
        times until the amplitude is 1e-12 alpha, then the geometric tail (the
        half-cycle times of small amplitudes shrink by eta per impact)."""
        t, e = self.fall_time(theta0), self.v(theta0)
        while True:
            e *= self.eta ** 2
            phi = brentq(lambda p: self.v(p) - e, 0, self.alpha, xtol=1e-300, rtol=1e-15)
            half = 2 * self.fall_time(phi)
            if phi < 1e-12 * self.alpha:
                return t + half / (1 - self.eta)
            t += half

    def impact_times(self, theta0, n):
        t, e, out = self.fall_time(theta0), self.v(theta0), []
        for _ in range(n):
            out.append(t)
            e *= self.eta ** 2
            phi = brentq(lambda p: self.v(p) - e, 0, self.alpha, xtol=1e-16, rtol=1e-15)
            t += 2 * self.fall_time(phi)
        return out


def me(fmu_path, params, stop, solver="CVode", rtol=1e-10, interval=0.01, step=None, record=None,
       events=True):
    """fmpy in Model Exchange; its Euler makes one step per output interval, so
    `step` (Euler only) is the output interval."""
    if solver == "Euler":
        interval = step
    kw = {}
    if record is not None:
        t, ag = record
        signal = np.zeros(len(t), dtype=[("time", float), ("ag", float)])
        signal["time"], signal["ag"] = t, ag
        kw["input"] = signal
    return simulate_fmu(fmu_path, fmi_type="ModelExchange", solver=solver, relative_tolerance=rtol,
                        step_size=step, stop_time=stop, output_interval=interval,
                        start_values=start_values(params), output=OUT, record_events=events, **kw)


def cs(fmu_path, params, stop, interval=0.01, record=None):
    """Co-simulation through `rocking.RockingFMU`, which gives the FMU the input
    linear inside each step as Model Exchange interpolates it (fmpy's own
    co-simulation holds it, or with input derivatives takes the slope of the
    segment before the step); returns its result array and the `Run`."""
    run = RockingFMU(fmu_path).simulate(params, ag=record, stop_time=stop, output_interval=interval,
                                        outputs=tuple(OUT))
    return run.result, run


def crossing_times(res):
    """Times of the rows where the zero-crossing count goes up (event rows)."""
    zc = res["zeroCrossings"]
    return res["time"][1:][np.diff(zc) > 0]


def test_model_exchange_is_declared_and_valid(fmu_path, model_description):
    md = model_description
    assert validate_fmu(fmu_path) == []
    assert md.modelExchange.modelIdentifier == md.coSimulation.modelIdentifier == "RockingBlock"
    # docs/model-exchange.md: 9, the range of N under av, six kinks of I(phi, W)
    assert md.numberOfEventIndicators == 16
    states = {d.variable.derivative.name: (d.variable.name, {x.name for x in d.dependencies})
              for d in md.derivatives}
    assert states == {"theta": ("der(theta)", {"theta", "omegaW", "av"}),
                      "omegaW": ("der(omegaW)", {"theta", "omegaW", "ag", "av"})}
    vr = {v.name: v.valueReference for v in md.modelVariables}
    assert vr["der(theta)"] == 43 and vr["der(omegaW)"] == 44 and vr["omegaW"] == 54
    initial = {u.variable.name for u in md.initialUnknowns}
    assert {"der(theta)", "der(omegaW)", "omegaW"} <= initial
    outputs = {u.variable.name: {x.name for x in u.dependencies} for u in md.outputs}
    assert outputs["omega"] == {"av"} and outputs["theta"] == set()


def test_rigid_free_rocking_matches_the_exact_impact_times(fmu_path):
    ex = Exact(0.25, 1.0)
    exact = ex.impact_times(0.5 * ex.alpha, 10)
    res = me(fmu_path, rigid_block(), stop=exact[-1] + 0.05, rtol=1e-10)
    got = crossing_times(res)[:10]
    err = np.abs(got - exact) / np.asarray(exact)
    print(f"\nCVode rtol 1e-10: impact times, worst relative error over 10 impacts {err.max():.1e}")
    assert len(got) == 10 and err.max() < 1e-7
    # explicit Euler, step 1e-4 s: first order, events at step ends
    res = me(fmu_path, rigid_block(), stop=exact[3] + 0.05, solver="Euler", step=1e-4)
    got = crossing_times(res)[:4]
    err = np.abs(got - exact[:4])
    print(f"Euler h 1e-4: impact times, worst absolute error over 4 impacts {err.max():.1e} s")
    assert len(got) == 4 and err.max() < 5e-3


@pytest.mark.parametrize("solver,step", [("CVode", None), ("Euler", 1e-3)])
def test_rigid_block_from_0_9_alpha_comes_to_rest(fmu_path, solver, step):
    ex = Exact(0.25, 1.0)
    res = me(fmu_path, rigid_block(theta_over_alpha=0.9), stop=12.0, solver=solver, step=step,
             rtol=1e-6, interval=0.01)
    t_acc = ex.accumulation_time(0.9 * ex.alpha)
    zc = int(res["zeroCrossings"][-1])
    still = res["time"] > t_acc + 0.5
    print(f"\n{solver}: {zc} impacts, theta = 0 from t = "
          f"{res['time'][np.nonzero(res['theta'])[0][-1] + 1]:.3f} s (exact accumulation {t_acc:.3f} s)")
    # bounded: the count an exact run needs to bring |omega| from its first
    # value down by the factor 1e-9 (the FMU's default tolerance)
    assert zc <= math.ceil(math.log(1e-9) / math.log(ex.eta)) + 2
    assert np.all(res["theta"][still] == 0.0) and np.all(res["omega"][still] == 0.0)


def dharahara(case, stop):
    rec = katnp_standin()
    t, ag = np.asarray(rec.time, float), np.asarray(rec.acc, float)
    keep = t <= stop + 0.01
    return dharahara_cases()[case], (t[keep], ag[keep])


def test_dharahara_overturning_time_matches_co_simulation(fmu_path):
    params, record = dharahara("I15_fm2", 26.0)
    _, ref = cs(fmu_path, params, 26.0, record=record)
    res = me(fmu_path, params, 26.0, rtol=1e-8, record=record)
    # fmpy ends the run at the event that terminates it
    t_me = res["time"][-1]
    print(f"\nDharahara I15_fm2 overturns: CS {ref.t_overturn:.5f} s, ME (CVode rtol 1e-8) {t_me:.5f} s")
    assert ref.overturned and abs(res["theta"][-1]) > 0.99 * abs(ref.result["theta"][-1])
    assert abs(t_me - ref.t_overturn) < 1e-3


@pytest.mark.parametrize("law", ["elastic", "elastoPlastic"])
def test_flexible_interfaces_match_co_simulation(fmu_path, law):
    # a weak joint (fm = 0.3 MPa) that crushes under this pulse
    params = dict(shape="solidRectangle", B=0.5, L=1.0, massModel="prism", H=2.5, rho=1800.0,
                  interface=law, kn=1e8, fm=3e5, g=9.81)
    alpha = math.atan(0.5 / 2.5)
    t = np.arange(0, 3.0001, 0.01)
    ag = np.where(t < 0.5, -1.3 * 9.81 * math.tan(alpha) * np.sin(2 * math.pi * t / 0.5), 0.0)
    ref, _ = cs(fmu_path, params, 3.0, record=(t, ag))
    res = me(fmu_path, params, 3.0, rtol=1e-10, record=(t, ag), events=False)
    diff = np.max(np.abs(res["theta"] - ref["theta"])) / alpha
    print(f"\n{law}: max |theta_ME - theta_CS| / alpha = {diff:.1e}, "
          f"zero crossings CS {ref['zeroCrossings'][-1]} ME {res['zeroCrossings'][-1]}")
    assert ref["zeroCrossings"][-1] >= 1
    assert (2 in set(ref["regime"])) == (law == "elastoPlastic"), "the crushing case crushes"
    assert diff < 1e-5
    assert res["zeroCrossings"][-1] == ref["zeroCrossings"][-1]
