"""The parametric runner (rocking.run_grid) against direct fmpy runs of the
same FMU, serial against parallel, and physical limits (no ground motion, no
motion)."""

import math
from pathlib import Path

import fmpy
import numpy as np
import pandas as pd
import pytest

from rocking import groundmotion as gm
from rocking import RockingFMU, run_grid
from rocking.cases import dharahara_cases, dharahara_tower

REPO = Path(__file__).resolve().parents[1]

ENUM = {"hollowCircle": 4, "lumped": 2, "rigid": 1, "elastic": 2, "elastoPlastic": 3,
        "costa": 1, "shiftingPivot": 2, "housner": 1}
ALPHA = math.atan(3.99 / (30.44 * math.cos(0.125)))  # docs/model.md §4
G = 9.81


@pytest.fixture(scope="module")
def fmu(unzipped):
    return RockingFMU(unzipdir=unzipped)


@pytest.fixture(scope="module")
def standin():
    return gm.katnp_standin()


def numeric(params):
    """Start values with the enumerations as integers, written out here (docs/model.md §5 order)."""
    return {k: ENUM[v] if isinstance(v, str) else v for k, v in params.items()}


def constant_record(acc, duration, dt=0.01):
    return gm.Record.from_samples(np.full(int(round(duration / dt)) + 1, acc), dt, name="constant")


def direct(unzipped, params, stop_time, output_interval=0.01, signals=None):
    """The same case through fmpy.simulate_fmu, the documented fmpy entry point."""
    return fmpy.simulate_fmu(unzipped, start_values=numeric(params), stop_time=stop_time,
                             output_interval=output_interval, input=signals,
                             output=["theta", "thetaOverAlpha", "impacts", "overturned"])


def test_free_rocking_row_equals_direct_fmpy_run(fmu, unzipped):
    # The tower on a crushing foundation released from rest at theta = 0.5 alpha.
    params = dict(dharahara_cases()["F340_fm5"], theta=0.5 * ALPHA)
    df = run_grid({"free": params}, workers=1, fmu=fmu, stop_time=20.0, output_interval=0.01)
    row = df.iloc[0]
    ref = direct(unzipped, params, 20.0)
    assert row["error"] == ""
    assert not row["overturned"] and not ref["overturned"][-1]
    assert row["peak_theta_over_alpha"] == pytest.approx(np.max(np.abs(ref["thetaOverAlpha"])), rel=1e-9)
    assert row["impacts"] == ref["impacts"][-1] > 0


def test_overturning_time_equals_direct_fmpy_run(fmu, unzipped):
    # Rigid tower at 0.9 alpha moving outward: overturns; fmpy stops at the Discard.
    params = dharahara_tower(theta=0.9 * ALPHA, omega=0.05)
    df = run_grid({"out": params}, workers=1, fmu=fmu, stop_time=10.0, output_interval=0.01)
    ref = direct(unzipped, params, 10.0)
    row = df.iloc[0]
    assert row["overturned"] and ref["overturned"][-1]
    assert ref["time"][-1] < 10.0
    assert row["t_overturn"] == pytest.approx(ref["time"][-1], abs=1e-9)
    assert row["peak_theta_over_alpha"] == pytest.approx(row["thetaOv"] / row["alpha"], rel=1e-6)


def test_constant_ground_motion_equals_direct_fmpy_run(fmu, unzipped):
    # From rest, a constant ag beyond the uplift threshold -g tan(alpha) (toward theta > 0):
    # the rigid tower overturns. With a constant input, fmpy's held input equals ours.
    ag = -1.3 * G * math.tan(ALPHA)
    params = dharahara_tower()
    rec = constant_record(ag, 20.0)
    df = run_grid({"push": params}, records=[rec], workers=1, fmu=fmu, output_interval=0.01)
    signals = np.array([(0.0, ag), (20.0, ag)], dtype=[("time", float), ("ag", float)])
    ref = direct(unzipped, params, 20.0, signals=signals)
    row = df.iloc[0]
    assert row["overturned"] and ref["overturned"][-1]
    assert row["t_overturn"] == pytest.approx(ref["time"][-1], abs=1e-9)
    assert row["impacts"] == ref["impacts"][-1] == 0


def test_parallel_rows_equal_serial_rows(fmu, standin):
    cases = {c: dharahara_cases()[c] for c in ("rigid", "I5_fm5", "F85_fm2")}
    kw = dict(records={"standin": standin}, scales=(0.5, 1.0), fmu=fmu, stop_time=30.0)
    serial = run_grid(cases, workers=1, **kw)
    parallel = run_grid(cases, workers=2, **kw)
    assert list(serial["case"]) == [c for c in cases for _ in (0.5, 1.0)]
    assert list(serial["scale"]) == [0.5, 1.0] * 3
    pd.testing.assert_frame_equal(serial.drop(columns=["wall_s", "cpu_s"]),
                                  parallel.drop(columns=["wall_s", "cpu_s"]))
    assert (serial["error"] == "").all()


def test_zero_scale_gives_no_motion(fmu, standin):
    cases = {c: dharahara_cases()[c] for c in ("F85_elastic", "I1500_fm2", "rigid")}
    df = run_grid(cases, records=[standin], scales=(0.0, 1.0), workers=1, fmu=fmu, stop_time=30.0)
    still = df[df["scale"] == 0.0]
    assert (still["peak_theta_over_alpha"] == 0.0).all()
    assert (still["impacts"] == 0).all() and not still["overturned"].any()
    moving = df[(df["scale"] == 1.0) & (df["case"] != "rigid")]
    assert (moving["peak_theta_over_alpha"] > 1e-3).all()


def test_enumerations_by_name_equal_by_value(fmu, standin):
    by_name = dharahara_cases()["I15_fm2"]
    by_value = numeric(by_name)
    df = run_grid({"name": by_name, "value": by_value}, records=[standin], workers=1, fmu=fmu,
                  stop_time=30.0)
    a, b = df.iloc[0], df.iloc[1]
    assert (a["peak_theta_over_alpha"], a["impacts"], a["overturned"]) == \
        (b["peak_theta_over_alpha"], b["impacts"], b["overturned"])


def test_invalid_case_is_reported_in_its_row(fmu):
    is_ = math.pi * (3.99 ** 4 - 2.12 ** 4) / 4
    t = dharahara_tower()
    bad = dharahara_tower(interface="elastic", kn=0.9 * t["W"] * t["hG"] / is_)
    df = run_grid({"bad": bad, "good": dharahara_tower()}, workers=1, fmu=fmu, stop_time=1.0)
    assert "kn" in df.iloc[0]["error"] and "W*hG" in df.iloc[0]["error"]
    assert df.iloc[1]["error"] == "" and df.iloc[1]["peak_theta_over_alpha"] == 0.0
