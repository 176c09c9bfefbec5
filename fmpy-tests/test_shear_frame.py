"""The packaged ShearFrame FMU through fmpy, against independent solutions:
the damped oscillator in closed form, modal superposition with SciPy's
generalized eigensolver, the static storey shears, and Newton's second law
for a floor force."""

import math
import zipfile

import numpy as np
import pytest
import scipy.linalg
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from conftest import TARGET
from fmu_helpers import ERROR, Host

SHEAR_FMU = TARGET / "fmu" / "ShearFrame.fmu"
MAX = 20


@pytest.fixture(scope="module")
def shear_fmu() -> str:
    if not SHEAR_FMU.is_file():
        pytest.fail(f"{SHEAR_FMU} not found: run `cargo xtask fmu` first", pytrace=False)
    return str(SHEAR_FMU)


@pytest.fixture(scope="module")
def shear_unzipped(shear_fmu, tmp_path_factory) -> str:
    return extract(shear_fmu, unzipdir=str(tmp_path_factory.mktemp("shear")))


def host(shear_fmu, shear_unzipped):
    return Host(shear_fmu, shear_unzipped, logging_on=True)


def sdof(w, zeta, a0, r, t):
    """u'' + 2 zeta w u' + w^2 u = -(a0 + r t) from rest: (u, u')."""
    p1 = -r / w**2
    p0 = -(a0 + 2 * zeta * w * p1) / w**2
    wd = w * math.sqrt(1 - zeta**2)
    c1 = -p0
    c2 = (-p1 + zeta * w * c1) / wd
    e = np.exp(-zeta * w * t)
    s, c = np.sin(wd * t), np.cos(wd * t)
    u = e * (c1 * c + c2 * s) + p0 + p1 * t
    v = e * ((-zeta * w * c1 + wd * c2) * c + (-zeta * w * c2 - wd * c1) * s) + p1
    return u, v


def test_validates_and_names_the_issue_variables(shear_fmu):
    assert validate_fmu(shear_fmu) == []
    md = read_model_description(shear_fmu)
    assert md.coSimulation.modelIdentifier == "ShearFrame"
    names = {v.name: v for v in md.modelVariables}
    for i in range(1, MAX + 1):
        for base in ("m", "k"):
            assert names[f"{base}[{i}]"].causality == "parameter"
        for base in ("Fx", "Fz"):
            assert names[f"{base}[{i}]"].causality == "input"
        for base in ("u", "v", "a", "drift"):
            assert names[f"{base}[{i}]"].causality == "output"
    for name, causality in [("n", "parameter"), ("zeta", "parameter"), ("ag", "input")]:
        assert names[name].causality == causality
    # a floor's absolute acceleration feeds through its own force only
    out = {u.variable.name: u for u in md.outputs}
    assert [d.name for d in out["a[4]"].dependencies] == ["Fx[4]"]
    assert out["u[4]"].dependencies == []


@pytest.mark.parametrize("damping", ["modal", "rayleigh"])
def test_one_storey_step_of_ground_acceleration_is_the_closed_form(shear_fmu, damping):
    m, k, a0 = 2.0e5, 8.0e7, 1.5
    w = math.sqrt(k / m)
    start = {"n": 1, "m[1]": m, "k[1]": k, "ag": a0}
    if damping == "modal":
        zeta = 0.05
        start["zeta"] = zeta
    else:
        # Rayleigh: the ratio alpha / (2 w) + beta w / 2 of the single mode
        alpha, beta = 0.8, 0.002
        zeta = alpha / (2 * w) + beta * w / 2
        start.update(damping=2, rayleighAlpha=alpha, rayleighBeta=beta, zeta=0.5)
    res = simulate_fmu(shear_fmu, start_values=start,
                       stop_time=3.0, output_interval=0.01, output=["u[1]", "v[1]", "a[1]", "period[1]"])
    u, v = sdof(w, zeta, a0, 0.0, res["time"])
    scale = a0 / w**2
    assert np.max(np.abs(res["u[1]"] - u)) < 1e-10 * scale
    assert np.max(np.abs(res["v[1]"] - v)) < 1e-10 * scale * w
    ud2 = -2 * zeta * w * v - w**2 * u - a0
    assert np.max(np.abs(res["a[1]"] - (ud2 + a0))) < 1e-9 * a0
    assert res["period[1]"][0] == pytest.approx(2 * math.pi / w, rel=1e-14)


def test_ramp_through_input_derivatives_and_the_output_derivatives(shear_fmu, shear_unzipped):
    m, k, zeta, r = 1.0e5, 4.0e7, 0.02, 2.0
    w = math.sqrt(k / m)
    h = host(shear_fmu, shear_unzipped)
    h.init(n=1, **{"m[1]": m, "k[1]": k}, zeta=zeta)
    vr = h.vr
    step = 0.05
    worst = 0.0
    for j in range(60):
        t = j * step
        # ag = r t: its value at the step start and its slope
        h.fmu.setReal([vr["ag"]], [r * t])
        h.fmu.setRealInputDerivatives([vr["ag"]], [1], [r])
        if j > 0:
            u_ref, v_ref = sdof(w, zeta, 0.0, r, t)
            d = h.fmu.getRealOutputDerivatives([vr["u[1]"], vr["u[1]"], vr["v[1]"]], [1, 2, 1])
            ud2 = -2 * zeta * w * v_ref - w**2 * u_ref - r * t
            assert d[0] == pytest.approx(v_ref, rel=1e-9)
            assert d[1] == pytest.approx(ud2, rel=1e-9)
            assert d[2] == pytest.approx(ud2, rel=1e-9)
            worst = max(worst, abs(h.get("u[1]") - u_ref) / (r * t / w**2))
        h.fmu.doStep(t, step)
    assert worst < 1e-10
    h.free()


@pytest.mark.parametrize("n", [3, 20])
def test_free_vibration_is_scipys_modal_solution(shear_fmu, n):
    rng = np.random.default_rng(n)
    m = rng.uniform(1.0e5, 3.0e5, n)
    kk = rng.uniform(1.0e8, 4.0e8, n)
    zeta = 0.04
    u0 = rng.uniform(-0.02, 0.04, n)
    v0 = rng.uniform(-0.1, 0.1, n)
    start = {"n": n, "zeta": zeta}
    for i in range(n):
        start.update({f"m[{i + 1}]": m[i], f"k[{i + 1}]": kk[i], f"u[{i + 1}]": u0[i], f"v[{i + 1}]": v0[i]})
    res = simulate_fmu(shear_fmu, start_values=start, stop_time=2.0, output_interval=0.004,
                       output=[f"u[{i + 1}]" for i in range(n)] + [f"period[{i + 1}]" for i in range(n)])
    K = np.diag(kk + np.append(kk[1:], 0)) - np.diag(kk[1:], 1) - np.diag(kk[1:], -1)
    lam, phi = scipy.linalg.eigh(K, np.diag(m))  # mass-normalised modes
    w = np.sqrt(lam)
    q0, qd0 = phi.T @ (m * u0), phi.T @ (m * v0)
    wd = w * math.sqrt(1 - zeta**2)
    t = res["time"][:, None]
    q = np.exp(-zeta * w * t) * (q0 * np.cos(wd * t) + (qd0 + zeta * w * q0) / wd * np.sin(wd * t))
    u = q @ phi.T
    scale = np.max(np.abs(u))
    worst = max(np.max(np.abs(res[f"u[{i + 1}]"] - u[:, i])) for i in range(n)) / scale
    assert worst < 1e-10, worst
    for i in range(n):
        assert res[f"period[{i + 1}]"][0] == pytest.approx(2 * math.pi / w[i], rel=1e-12)


def test_changing_step_sizes_stay_exact(shear_fmu, shear_unzipped):
    # more distinct sizes than the FMU keeps maps for, revisited
    m, k, zeta, a0 = 1.5e5, 6.0e7, 0.05, -2.0
    w = math.sqrt(k / m)
    h = host(shear_fmu, shear_unzipped)
    h.init(n=1, **{"m[1]": m, "k[1]": k}, zeta=zeta, ag=a0)
    t = 0.0
    worst = 0.0
    for dt in [0.01, 0.03, 0.007, 0.05, 0.02, 0.011, 0.01, 0.03] * 10:
        h.fmu.doStep(t, dt)
        t += dt
        u, _ = sdof(w, zeta, a0, 0.0, t)
        worst = max(worst, abs(h.get("u[1]") - u) / (abs(a0) / w**2))
    assert worst < 1e-10, worst
    h.free()


def test_floor_forces_settle_at_the_storey_shears_and_fz_is_ignored(shear_fmu):
    kk = [3.0e8, 2.0e8, 1.0e8]
    fx = [0.0, 2.0e5, -5.0e4]
    start = {"n": 3, "zeta": 0.8, "Fz[2]": -1.0e6}
    for i in range(3):
        start.update({f"m[{i + 1}]": 1.0e5, f"k[{i + 1}]": kk[i], f"Fx[{i + 1}]": fx[i]})
    out = [f"drift[{i}]" for i in (1, 2, 3)] + [f"a[{i}]" for i in (1, 2, 3)]
    res = simulate_fmu(shear_fmu, start_values=start, stop_time=20.0, output_interval=0.5, output=out)
    for i in range(3):
        shear = sum(fx[i:])
        assert res[f"drift[{i + 1}]"][-1] == pytest.approx(shear / kk[i], rel=1e-10, abs=1e-15)
        assert abs(res[f"a[{i + 1}]"][-1]) < 1e-8
    del start["Fz[2]"]
    again = simulate_fmu(shear_fmu, start_values=start, stop_time=20.0, output_interval=0.5, output=out)
    for name in out:
        assert np.array_equal(res[name], again[name])


def test_a_floor_force_accelerates_its_floor_by_f_over_m(shear_fmu, shear_unzipped):
    h = host(shear_fmu, shear_unzipped)
    h.init(n=2, **{"m[1]": 2.0e5, "m[2]": 5.0e4, "u[1]": 0.01, "v[2]": 0.1})
    before = [h.get("a[1]"), h.get("a[2]")]
    h.set(**{"Fx[2]": 1.0e4})
    after = [h.get("a[1]"), h.get("a[2]")]
    assert after[0] == before[0]
    assert after[1] - before[1] == pytest.approx(1.0e4 / 5.0e4, rel=1e-12)
    # the ground acceleration moves the floors relative to the ground, not
    # their absolute acceleration at this instant
    h.set(ag=3.0)
    assert [h.get("a[1]"), h.get("a[2]")] == after
    h.free()


@pytest.mark.parametrize("values,name", [
    ({"n": 0}, "n = 0"),
    ({"n": 21}, "n = 21"),
    ({"m[2]": -1.0}, "m[2] = -1"),
    ({"k[3]": 0.0}, "k[3] = 0"),
    ({"zeta": -0.1}, "zeta = -0.1"),
    ({"damping": 2, "rayleighBeta": -1.0}, "rayleighBeta = -1"),
])
def test_bad_parameters_are_errors_naming_the_variable(shear_fmu, shear_unzipped, values, name):
    h = host(shear_fmu, shear_unzipped)
    h.fmu.setupExperiment(startTime=0.0)
    h.set(**values)
    h.fmu.enterInitializationMode()
    assert h.status(h.fmu.exitInitializationMode) == ERROR
    assert any(name in e for e in h.errors()), h.errors()
    h.free()


def test_a_force_on_a_missing_floor_is_an_error(shear_fmu, shear_unzipped):
    h = host(shear_fmu, shear_unzipped)
    h.init(n=3)
    h.set(**{"Fx[5]": 1.0})
    assert h.status(h.fmu.doStep, 0.0, 0.01) == ERROR
    assert any("Fx[5]" in e for e in h.errors()), h.errors()
    h.free()


def test_fmu_state_replays_a_step_bit_for_bit(shear_fmu, shear_unzipped):
    h = host(shear_fmu, shear_unzipped)
    h.init(n=5, ag=1.0)
    h.fmu.doStep(0.0, 0.1)
    state = h.fmu.getFMUstate()
    blob = h.fmu.serializeFMUstate(state)
    h.fmu.doStep(0.1, 0.1)
    first = [h.get(f"u[{i}]") for i in range(1, 6)]
    h.fmu.setFMUstate(h.fmu.deSerializeFMUstate(blob))
    h.fmu.doStep(0.1, 0.1)
    assert [h.get(f"u[{i}]") for i in range(1, 6)] == first
    h.fmu.freeFMUstate(state)
    h.free()


def test_the_archive_ships_the_binary_and_the_documentation(shear_fmu):
    with zipfile.ZipFile(shear_fmu) as z:
        names = set(z.namelist())
    assert {"modelDescription.xml", "documentation/index.html", "binaries/linux64/ShearFrame.so"} <= names
