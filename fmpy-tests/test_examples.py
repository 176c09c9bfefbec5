"""The examples (Dharahara case study, Fig. 15 free rocking) against independent
references: a quadrature of the interface stresses written here, an
integration of docs/model.md §3 with scipy, the uplift condition of a rigid body,
and the FMU's own calculated parameters."""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from rocking import groundmotion as gm
from rocking import RockingFMU
from rocking.cases import dharahara_cases, dharahara_tower, fig15_block

REPO = Path(__file__).resolve().parents[1]

RO, RI, W = 3.99, 2.12, 24003.94e3
HG = 30.44 * math.cos(0.125)
ALPHA = math.atan(RO / HG)
R0 = math.hypot(RO, HG)
G = 9.81


@pytest.fixture(scope="module")
def fmu(unzipped):
    return RockingFMU(unzipdir=unzipped)


@pytest.fixture(scope="module")
def mr_csv(tmp_path_factory):
    out = tmp_path_factory.mktemp("mr")
    subprocess.run(["cargo", "run", "--release", "--quiet", "--example", "dharahara_curves", "--", str(out)],
                   cwd=REPO, check=True, capture_output=True)
    curves = pd.read_csv(out / "dharahara_mr_curves.csv", comment="#")
    cases = pd.read_csv(out / "dharahara_mr_cases.csv").set_index("case")
    return curves, cases


# --- moment-rotation curves ---------------------------------------------------

def test_curves_thetaOv_equals_fmu_calculated_thetaOv(fmu, mr_csv):
    _, cases = mr_csv
    params = dharahara_cases()
    assert set(params) == set(cases.index) and len(params) == 49
    for cid, p in params.items():
        calc = fmu.calculated(p)
        assert calc["thetaOv"] == pytest.approx(cases.loc[cid, "thetaOv"], rel=1e-9), cid
        assert calc["alpha"] == pytest.approx(ALPHA, rel=1e-12)
        assert calc["thetaC"] == pytest.approx(cases.loc[cid, "thetaC"], rel=1e-9) or \
            (math.isinf(calc["thetaC"]) and math.isinf(cases.loc[cid, "thetaC"]))


def ring_width(x):
    """w(x) of the hollow circle, x from the toe (docs/model.md §1)."""
    u = x - RO
    outer = 2 * math.sqrt(max(RO * RO - u * u, 0.0))
    inner = 2 * math.sqrt(max(RI * RI - u * u, 0.0))
    return outer - inner


def mr_by_quadrature(theta, kn, fm):
    """MR = W hW from the stress profile sigma = min(kn theta (a - x), fm), N(a) = W solved by brentq."""
    def stress(x, a):
        return min(kn * theta * (a - x), fm) if x < a else 0.0

    def force(a):
        pts = sorted({p for p in (RO - RI, RO + RI, a - fm / (kn * theta)) if 0 < p < min(a, 2 * RO)})
        return quad(lambda x: stress(x, a) * ring_width(x), 0, min(a, 2 * RO), points=pts or None,
                    limit=200, epsabs=1e-3, epsrel=1e-11)[0]

    hi = 1.0
    while force(hi) < W:
        hi *= 2
    a = brentq(lambda a: force(a) - W, 1e-9, hi, xtol=1e-14, rtol=1e-14)
    pts = sorted({p for p in (RO - RI, RO + RI, a - fm / (kn * theta)) if 0 < p < min(a, 2 * RO)})
    moment = quad(lambda x: stress(x, a) * ring_width(x) * x, 0, min(a, 2 * RO), points=pts or None,
                  limit=200, epsabs=1e-3, epsrel=1e-11)[0]
    af = moment / W
    return W * (R0 * math.sin(ALPHA - theta) - af * math.cos(theta))


@pytest.mark.parametrize("cid,kn,fm", [("F85_fm2", 85e6, 2e6), ("F170_fm15", 170e6, 15e6),
                                       ("I2_elastic", 2e9, math.inf)])
def test_curves_against_stress_quadrature(mr_csv, cid, kn, fm):
    curves, _ = mr_csv
    scale = W * R0 * math.sin(ALPHA)
    for i in (130, 300, 600, 900, 1100):
        theta = curves["theta"].iloc[i]
        ref = mr_by_quadrature(theta, kn, fm)
        assert curves[cid].iloc[i] == pytest.approx(ref, abs=1e-7 * scale), (cid, theta)


def test_rigid_curve_is_housner(mr_csv):
    curves, cases = mr_csv
    th = curves["theta"]
    np.testing.assert_allclose(curves["rigid"], W * R0 * np.sin(ALPHA - th), rtol=0, atol=1e-9 * W * R0)
    assert cases.loc["rigid", "thetaOv"] == pytest.approx(ALPHA, rel=1e-12)


# --- time histories -----------------------------------------------------------

def test_rigid_tower_below_uplift_threshold_does_not_rock(fmu):
    rec = gm.katnp_standin()
    threshold = G * math.tan(ALPHA)
    below = fmu.simulate(dharahara_tower(), record=rec, scale=0.98 * threshold / rec.pga, stop_time=40.0)
    above = fmu.simulate(dharahara_tower(), record=rec, scale=1.05 * threshold / rec.pga, stop_time=40.0)
    assert below.peak_theta_over_alpha == 0.0 and below.impacts == 0
    assert above.peak_theta_over_alpha > 0.0


def test_fig15_first_impact_matches_scipy_integration(fmu):
    """First impact of a solid block released at 0.9 alpha: the FMU's costa and
    shiftingPivot against scipy on docs/model.md §3 with the solid rectangle's closed-form af."""
    kn, r0, rho, L = 340e6, 3.0, 1800.0, 1.0
    for alpha in (0.10, 0.35):
        B, H = 2 * r0 * math.sin(alpha), 2 * r0 * math.cos(alpha)
        m = rho * B * H * L
        w = m * G
        ic = m * (H * H + B * B) / 12
        is_ = L * B ** 3 / 12
        tjo = 2 * w / (kn * B * L * B)

        def af(phi):
            if phi <= tjo:
                return B / 2 - kn * phi * is_ / w, -kn * is_ / w
            a = math.sqrt(2 * w / (kn * phi * L))
            return a / 3, -a / (6 * phi)

        def rhs(form):
            def f(t, y):
                th, om = y
                phi, s = abs(th), math.copysign(1.0, th)
                a, da = af(phi)
                hw = r0 * math.sin(alpha - phi) - a * math.cos(phi)
                inertia = ic + m * (r0 * r0 + a * a - 2 * r0 * a * math.sin(alpha))
                di = -2 * m * (r0 * math.sin(alpha) - a) * da
                extra = 0.5 * s * di * om * om if form == "shiftingPivot" else 0.0
                return [om, (-s * w * hw - extra) / inertia]
            return f

        hit = lambda t, y: y[0]  # noqa: E731
        hit.terminal, hit.direction = True, -1
        times = {}
        for form in ("costa", "shiftingPivot"):
            ref = solve_ivp(rhs(form), (0, 10), [0.9 * alpha, 0.0], events=hit, method="DOP853",
                            rtol=1e-11, atol=1e-14).t_events[0][0]
            run = fmu.simulate(fig15_block(alpha, form), stop_time=ref + 0.05, output_interval=0.0005,
                               outputs=("theta", "thetaOverAlpha", "impacts"), rtol=1e-10)
            t, th = run.result["time"], run.result["theta"]
            i = int(np.nonzero(th <= 0)[0][0])
            t_fmu = t[i - 1] - th[i - 1] * (t[i] - t[i - 1]) / (th[i] - th[i - 1])
            assert t_fmu == pytest.approx(ref, abs=5e-5), (alpha, form)
            assert run.impacts == 1
            times[form] = (t_fmu, ref)
        # costa arrives later; the FMU reproduces the difference itself
        d_fmu = times["costa"][0] - times["shiftingPivot"][0]
        d_ref = times["costa"][1] - times["shiftingPivot"][1]
        assert d_ref > 0 and d_fmu == pytest.approx(d_ref, rel=0.1)


# --- the scripts ----------------------------------------------------------------

def run_script(args):
    return subprocess.run([sys.executable, *args], cwd=REPO, check=True, capture_output=True, text=True).stdout


def test_dharahara_script_labels_the_standin(tmp_path):
    out = tmp_path / "dh"
    stdout = run_script(["examples/dharahara.py", "--out", str(out), "--cases", "rigid,I15_fm2,F85_elastic",
                         "--stop-time", "3", "--workers", "1"])
    for name in ("dharahara_mr_curves.csv", "dharahara_mr_cases.csv", "dharahara_fig17_foundation.png",
                 "dharahara_fig18_interface.png", "dharahara_fig20_interface.png",
                 "dharahara_fig20_foundation.png", "dharahara_summary.csv", "dharahara_time_histories.csv",
                 "dharahara_claims.csv"):
        assert (out / name).is_file(), name
    assert "STAND-IN" in (out / "dharahara_summary.csv").read_text().upper()
    assert "STAND-IN" in (out / "dharahara_time_histories.csv").read_text()[:2000].upper()
    assert "STAND-IN" in stdout.upper() and str(out) in stdout
    summary = pd.read_csv(out / "dharahara_summary.csv", comment="#")
    assert list(summary["case"]) == ["rigid", "I15_fm2", "F85_elastic"]
    assert set(summary.columns) >= {"overturned", "t_overturn", "peak_theta_over_alpha", "impacts", "wall_s"}


def test_dharahara_script_takes_a_real_record(tmp_path):
    out = tmp_path / "rec"
    path = gm.DATA_DIR / "usgs-lomaprieta-1989" / "0111a.smc"
    stdout = run_script(["examples/dharahara.py", "--out", str(out), "--record", str(path), "--cases", "rigid",
                         "--stop-time", "2", "--workers", "1"])
    text = (out / "dharahara_summary.csv").read_text()
    assert "0111a.smc" in text and "STAND-IN" not in text.upper()
    assert "Loma Prieta" in stdout


def test_dharahara_script_runs_again_exactly_when_an_input_or_output_changed(tmp_path):
    out = tmp_path / "dh"
    args = ["examples/dharahara.py", "--out", str(out), "--cases", "rigid", "--stop-time", "1", "--workers", "1",
            "--scales", ""]
    first = run_script(args)
    files = {p.name: p.read_bytes() for p in out.glob("dharahara_*")}
    stamps = {p.name: p.stat().st_mtime_ns for p in out.glob("dharahara_*")}
    # the same inputs: the earlier log, no file written
    again = run_script(args)
    assert "unchanged" in again and again.startswith(first.rstrip("\n"))
    assert {p.name: p.stat().st_mtime_ns for p in out.glob("dharahara_*")} == stamps
    # another argument, an output altered or removed, --force: run (the same bytes where the inputs are)
    assert "unchanged" not in run_script(args[:-2] + ["--scales", "2"])
    assert "unchanged" not in run_script(args)
    (out / "dharahara_claims.csv").write_text("altered")
    assert "unchanged" not in run_script(args)
    (out / "dharahara_results.md").unlink()
    assert "unchanged" not in run_script(args)
    assert "unchanged" not in run_script(args + ["--force"])
    assert "unchanged" in run_script(args)
    timing = ("dharahara_summary.csv", "dharahara_results.md", "dharahara_mr_log.txt")
    assert all((out / n).read_bytes() == b for n, b in files.items() if n not in timing)
