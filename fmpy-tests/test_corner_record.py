"""The corner under a record (rocking.corner_blocks.dynamics, docs/corner-record.md):
the record's integration into the base's driven velocity against closed forms, the
committed DEM results' consistency (each scale bracket: the run below stands, the run
above collapses, as recorded), and the committed single-block DEM run against a fresh
run of the planar rigid rocking FMU. No DEM run here (examples/corner_record.py makes
them, about 1 min CPU each for the corner)."""

import json
import math
import pathlib

import numpy as np
import pytest

from rocking import groundmotion as gm
from rocking.corner_blocks import dynamics

ROOT = pathlib.Path(__file__).resolve().parent.parent
DATA = ROOT / "data" / "corner-blocks" / "record"
G = 9.81


def results():
    return json.loads((DATA / "results.json").read_text())


def run_file(case, scale):
    return json.loads((DATA / "runs" / case / f"s{scale:.4f}.json").read_text())


# --- the record into a driven velocity -------------------------------------------------

def _sine_error(dt, amp=2.0, omega=2 * math.pi * 2.0, length=3.0):
    t = np.arange(0.0, length + dt / 2, dt)
    at = np.linspace(0.0, length, 997)  # mostly between samples
    exact = amp / omega * (1 - np.cos(omega * at))
    return np.max(np.abs(dynamics.velocity(t, amp * np.sin(omega * t), at) - exact)) / (amp / omega)


def test_velocity_of_a_sine_against_its_closed_form():
    """a = A sin(w t) sampled at dt, taken linear between samples: v within 1e-3 of
    A/w (1 - cos w t) at dt = 5 ms, and the error falls as dt^2 (the trapezoid's order)."""
    coarse, fine = _sine_error(0.01), _sine_error(0.005)
    assert fine < 1e-3
    assert coarse / fine == pytest.approx(4.0, rel=0.1)


def test_velocity_is_exact_on_a_piecewise_linear_record():
    """A triangle pulse 0 -> 3 m/s2 at 0.2 s -> 0 at 0.6 s: v = 1.5 t^2 / 0.2 up to 0.2 s,
    0.9 m/s (its area) from 0.6 s on, and 0 before the record."""
    t = np.array([0.0, 0.2, 0.6])
    a = np.array([0.0, 3.0, 0.0])
    at = np.array([-0.1, 0.0, 0.05, 0.2, 0.4, 0.6, 2.0])
    up = 3.0 / 0.2
    expected = [0.0, 0.0, up * 0.05 ** 2 / 2, 0.3, 0.3 + 0.2 * 3.0 - 7.5 * 0.2 ** 2 / 2, 0.9, 0.9]
    assert dynamics.velocity(t, a, at) == pytest.approx(expected, abs=1e-12)


def test_base_table_sign_settling_and_tail():
    """The base is at rest while settling, then moves along the turned x as -scale v(t)
    (a negative ag, which pushes the blocks outwards along -x, drives the base along +x),
    and keeps the record's last velocity over the tail; one row per time step."""
    p = dynamics.Protocol(dt=1e-3, settle=0.1, tail=0.5)
    t = np.array([0.0, 0.2, 0.4])
    a = np.array([0.0, -2.0, 0.0])
    times, v = dynamics.base_table(t, a, 1.5, p)
    assert times[1] - times[0] == pytest.approx(1e-3)
    assert times[-1] == pytest.approx(0.1 + 0.4 + 0.5)
    assert np.all(v[times <= 0.1 + 1e-12] == 0.0)
    assert np.all(v[times > 0.1 + 1e-9] > 0.0)
    assert v[-1] == pytest.approx(1.5 * 0.4, abs=1e-12)  # -1.5 x the area -0.4 m/s
    assert v[np.argmin(np.abs(times - 0.3))] == pytest.approx(1.5 * 2.0 / 0.2 * 0.2 ** 2 / 2, abs=1e-9)


def test_strong_part_starts_at_a_sign_change():
    t = np.arange(0.0, 10.0, 0.01)
    a = np.sin(2 * math.pi * 1.3 * t + 0.4)
    w, acc, t0 = dynamics.strong_part(t, a, 4.0, 2.0)
    k = int(round(t0 / 0.01))
    assert t0 <= 4.0 and a[k] * a[k - 1] <= 0
    assert w[0] == 0.0 and w[-1] == pytest.approx(2.0) and np.array_equal(acc, a[k:k + len(w)])


# --- the committed results ---------------------------------------------------------------

CASES = ("block", "free", "free-restrained", "fixed")


@pytest.mark.parametrize("case", CASES)
def test_each_committed_bracket_stands_below_and_collapses_above(case):
    c = results()["cases"][case]
    lo, hi = c["dem"]["stands"], c["dem"]["collapses"]
    assert lo < hi and hi / lo - 1 <= 0.03 + 1e-9
    below, above = run_file(case, lo), run_file(case, hi)
    assert not below["collapsed"] and above["collapsed"]
    assert max(np.abs(below["rotation_max"]).max(), np.abs(below["rotation_min"]).max()) < dynamics.FALL
    # the record in the summary is the run's
    assert c["dem"]["peak_rotation_stands"] == below["peak_rotation"]
    # every run of the search is in the summary as its file has it: below lo all stood,
    # above hi all collapsed
    for s, r in c["runs"].items():
        assert run_file(case, float(s))["collapsed"] == r["collapsed"]
        assert r["collapsed"] == (float(s) >= hi)
    # the time of collapse: where the tracked blocks' extreme on the fall side last passed
    # theta_ov before the fall, as the committed series show it
    c_side, c_time = dynamics.collapse(above["time"], above["rotation_max"], above["rotation_min"], c["theta_ov"])
    assert c_side == c["dem"]["fall_side"]
    assert c_time == pytest.approx(c["dem"]["t_collapse"], abs=1e-9, nan_ok=True)
    if math.isfinite(c_time):
        extreme = np.array(above["rotation_max"] if c_side > 0 else [-v for v in above["rotation_min"]])
        k = int(np.searchsorted(above["time"], c_time))
        assert extreme[k - 1] < c["theta_ov"] <= extreme[k] and np.all(extreme[k:] >= c["theta_ov"])


def test_the_record_is_the_one_named():
    prov = results()["record"]
    r = gm.read(ROOT / prov["file"], component=prov["component"])
    assert prov["pga_g"] == pytest.approx(np.max(np.abs(r.acc)) / G)
    assert r.time[0] <= prov["window_s"][0] < prov["window_s"][1] <= r.time[-1]


def _window():
    prov = results()["record"]
    r = gm.read(ROOT / prov["file"], component=prov["component"])
    t, a, t0 = dynamics.strong_part(r.time, r.acc, prov["window_s"][0], prov["window_s"][1] - prov["window_s"][0])
    assert t0 == pytest.approx(prov["window_s"][0])
    return t, a


def _fmu_run(fmu, params, scale):
    t, a = _window()
    return fmu.simulate(params, ag=(t, a), scale=scale, stop_time=float(t[-1]) + 1.0, output_interval=0.005)


def test_single_block_dem_against_the_rocking_fmu():
    """The DEM input's check: the free-standing block's committed DEM run (the largest
    scale that stood) against the planar rigid rocking FMU under the same record and
    scale: the first half-cycle (to 4.1 s) within 15 % of the FMU's peak, the first two
    peaks within 10 % and 20 % (the DEM loses more at the first impact) and 0.05 s."""
    from rocking import RockingFMU

    res = results()
    c = res["cases"]["block"]
    dem_run = run_file("block", c["dem"]["stands"])
    with RockingFMU() as fmu:
        run = _fmu_run(fmu, res["bodies"]["block"]["params"], c["dem"]["stands"])
    ft, fth = run.result["time"], run.result["theta"]
    t, th = np.array(dem_run["time"]), np.array(dem_run["rotation"])
    first = t <= 4.1
    fmu_at = np.interp(t, ft, fth)
    peak = np.max(np.abs(fmu_at[first]))
    assert np.max(np.abs(th[first] - fmu_at[first])) < 0.15 * peak
    early = t <= 4.3
    for pick, rel in ((np.argmin, 0.10), (np.argmax, 0.20)):
        kd, kf = pick(th[early]), pick(fmu_at[early])
        assert th[kd] == pytest.approx(fmu_at[kf], rel=rel)
        assert abs(t[kd] - t[kf]) <= 0.05


def test_single_block_collapses_where_and_when_the_rocking_fmu_does():
    """At every scale the DEM block was run at, the FMU's block does the same (stands or
    overturns, on the same side), and overturns within 0.1 s of the DEM's time."""
    from rocking import RockingFMU

    res = results()
    c = res["cases"]["block"]
    with RockingFMU() as fmu:
        for s, r in c["runs"].items():
            run = _fmu_run(fmu, res["bodies"]["block"]["params"], float(s))
            assert run.overturned == r["collapsed"], s
            if r["collapsed"]:
                assert abs(run.t_overturn - r["t_collapse"]) <= 0.1, s
                assert np.sign(run.result["theta"][-1]) == r["fall_side"], s


def test_the_macroblock_body_where_the_mechanism_is_the_macroblocks():
    """Free ends held inwards (WX above the taped course rocks outwards as one, about the
    bed joint: the geometric body's mechanism): the body's overturning scale lies within
    3 % above the DEM's bracket, and where both collapse, within 0.05 s of each other."""
    from rocking import RockingFMU

    res = results()
    c = res["cases"]["free-restrained"]
    body = res["fmu"]["geometric"]
    assert c["dem"]["stands"] < body["collapses"] <= 1.03 * c["dem"]["collapses"]
    both = 0
    with RockingFMU() as fmu:
        assert not _fmu_run(fmu, body["params"], c["dem"]["stands"]).overturned
        for s, r in c["runs"].items():
            run = _fmu_run(fmu, body["params"], float(s))
            if run.overturned and r["collapsed"]:
                both += 1
                assert abs(run.t_overturn - r["t_collapse"]) <= 0.05, s
    assert both >= 3
