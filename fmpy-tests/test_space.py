"""`rocking space` and rocking.round_body: a round body in space through RoundBody.fmu, against
independent references: a rotated input turns the response (the pair's rotation, the FMU's
rotation invariance: theta the same, psi shifted by the angle), free rocking in a plane
through the other FMU (RockingBlock.fmu), the
Dharahara page's table (computed by the Rust example from the physics without the FMU), the
planar runs' path of the top on a flexible bed against a closed form in full contact and the
rim's in the stiff limit, and bad input in one line."""

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rocking import groundmotion as gm
from rocking import paths
from rocking.cases import dharahara_cases
from rocking.fmu import RockingFMU
from rocking.round_body import RoundBodyFMU

REPO = Path(__file__).resolve().parents[1]
DFHS = paths.data_dir() / "geonet-darfield-2010" / "3366146_DFHS_HN_20.090"
LOMA = paths.data_dir() / "usgs-lomaprieta-1989" / "0111a.smc"
DRUM = {"shape": "solidCircle", "Ro": 0.5, "massModel": "prism", "H": 3.0, "rho": 2000.0}


def rocking(*args):
    return subprocess.run([sys.executable, "-m", "rocking", *map(str, args)], capture_output=True, text=True)


@pytest.fixture(scope="module")
def fmu():
    with RoundBodyFMU() as f:
        yield f


@pytest.fixture(scope="module")
def loma():
    return gm.pair_of(LOMA)


def test_a_rotated_record_turns_the_response(fmu, loma):
    base = fmu.simulate(DRUM, pair=loma, scale=5.0, stop_time=20.0, rtol=1e-11)
    turned = fmu.simulate(DRUM, pair=loma, scale=5.0, azimuth=40.0, stop_time=20.0, rtol=1e-11)
    assert base.peak_theta_over_alpha > 0.05, "the record must rock the drum"
    assert np.max(np.abs(base.result["theta"] - turned.result["theta"])) <= 1e-9
    # the frame turned by +40 degrees: the lean's azimuth in it is 40 degrees less
    moving = base.result["theta"] > 1e-3
    dpsi = np.angle(np.exp(1j * (base.result["psi"][moving] - turned.result["psi"][moving] - math.radians(40.0))))
    assert np.max(np.abs(dpsi)) <= 1e-6
    assert base.impacts == turned.impacts


def planar_pair(rec):
    """`rec` along x and nothing along y."""
    return gm.HorizontalPair.from_records(rec, rec.scaled(0.0), bearings=None)


@pytest.mark.parametrize("restitution", ["housner", "given"])
def test_in_a_plane_the_round_body_is_the_planar_rigid_fmu(fmu, restitution):
    """Free rocking from a tilt in the x-z plane through both FMUs (RockingBlock.fmu's rigid
    circle and RoundBody.fmu): the tilt, signed along x, to 1e-10 rad, the same impacts."""
    params = {**DRUM, "restitution": restitution, "eta": 0.8}
    quiet = gm.Record.from_samples(np.zeros(801), 0.005)
    space = fmu.simulate({**params, "theta0": 0.2}, pair=planar_pair(quiet), stop_time=4.0, rtol=1e-12)
    with RockingFMU() as rfmu:
        planar = rfmu.simulate({**params, "interface": "rigid", "theta": 0.2}, record=quiet, stop_time=4.0,
                               rtol=1e-12)
    assert planar.impacts >= 5
    signed = np.arcsin(space.result["ex"])
    assert np.max(np.abs(signed - planar.result["theta"])) <= 1e-10
    assert np.max(np.abs(space.result["ey"])) == 0.0
    assert space.impacts == planar.impacts


@pytest.mark.parametrize("path, scale", [(DFHS, 2.0), (LOMA, 6.0)])
def test_under_a_record_in_a_plane_the_round_body_is_the_planar_rigid_fmu(fmu, path, scale):
    """A record along 25 degrees and nothing across it, through both FMUs, to the end of the
    record: rocking, then a chatter of hundreds of impacts below 1e-6 rad to rest, and
    rocking again. Before the planar integrator took a crossing at the very start of a step
    as the impact there, the planar FMU lost impacts in such chatters (18 against 122 at
    20.76 s on DFHS x2) and the runs parted by 2.3e-2 rad (tests/chatter.rs)."""
    rec = gm.pair_of(path).along(25.0)
    space = fmu.simulate(DRUM, pair=planar_pair(rec), scale=scale, rtol=1e-12, vertical=False)
    with RockingFMU() as rfmu:
        planar = rfmu.simulate({**DRUM, "interface": "rigid"}, record=rec, scale=scale, rtol=1e-12)
    assert planar.peak_theta_over_alpha > 0.01 and planar.impacts >= 100
    assert np.max(np.abs(np.arcsin(space.result["ex"]) - planar.result["theta"])) <= 1e-10
    assert space.impacts == planar.impacts


def test_the_command_writes_its_files_and_matches_the_dharahara_page(tmp_path):
    out = tmp_path / "dfhs"
    r = rocking("space", DFHS, "--scale", 3, "--preset", "dharahara-rigid", "--compare", "--sweep", 20,
                "--tail", 10, "--rtol", 1e-10, "--out", out)
    assert r.returncode == 0, r.stderr
    s = json.loads((out / "summary.json").read_text())
    history = np.genfromtxt(out / "timehistory.csv", delimiter=",", names=True)
    assert {"agx", "agy", "av", "theta", "psi", "xG", "yG", "Fz", "frictionDemand"} <= set(history.dtype.names)
    assert (out / "plot.png").stat().st_size > 10_000
    assert s["peak_theta_over_alpha"] == pytest.approx(np.max(history["thetaOverAlpha"]))
    # the page's row "Darfield DFHS | 3", computed without the FMU (examples/dharahara_space.rs)
    row = next(line for line in (REPO / "docs" / "dharahara.md").read_text().splitlines()
               if line.startswith("| Darfield DFHS | 3 |"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert f"{s['peak_theta_over_alpha']:.3f} ({s['impacts']})" == cells[2]
    assert cells[4] == f"overturns {s['planar']['x']['t_overturn_s']:.2f} s"
    assert cells[5] == f"{s['planar']['y']['peak_theta_over_alpha']:.3f}"
    assert s["planar"]["worst"]["azimuth_deg"] == 140.0 and s["planar"]["worst"]["overturned"]
    assert "planar along worst (140 deg): overturns at 35.2" in r.stdout


@pytest.mark.parametrize("args, words", [
    (["space", paths.data_dir() / "katnp-standin" / "KATNP_NS_standin.csv"], "horizontal component"),
    (["space", DFHS, "--shape", "solidRectangle"], "not one of solidCircle, hollowCircle"),
    (["space", DFHS, "--preset", "fig15-alpha0.20-costa"], "not one of solidCircle, hollowCircle"),
    (["space", DFHS, "--interface", "soft"], "not one of rigid, elastic, elastoPlastic (interface)"),
    (["space", DFHS, "--preset", "dharahara-F170-fm5", "--kn", "-1"], "kn = -1"),
    (["space", DFHS, "--Ro", "-1"], "Ro"),
    (["space", "no/such/file.090"], "no such record file"),
])
def test_bad_input_is_one_line(tmp_path, args, words):
    r = rocking(*args, "--out", tmp_path / "x")
    assert r.returncode == 2, r.stdout + r.stderr
    lines = [line for line in r.stderr.splitlines() if not line.startswith("rocking space: note")]
    assert len(lines) == 1 and words in lines[0], r.stderr


def flexible_row(case):
    """The cells of `case`'s row in the page's table of the 49 cases under Darfield DFHS x3
    (docs/dharahara.md, "The tower in space on flexible and crushing beds")."""
    text = (REPO / "docs" / "dharahara.md").read_text()
    section = text.split("## The tower in space on flexible and crushing beds", 1)[1]
    row = next(line for line in section.splitlines() if line.startswith(f"| {case} |"))
    return [c.strip() for c in row.strip("|").split("|")]


@pytest.mark.parametrize("case", ["F170_fm5", "I15_elastic"])
def test_the_flexible_table_s_planar_runs_are_the_planar_fmu_s(case):
    """The page's planar runs along x under Darfield DFHS x3 with the vertical (the Rust
    example dharahara_space_flexible, calling the planar Simulator directly) through
    RockingBlock.fmu and its host loop: the same peak to 3 digits and the same
    crossings (the FMU's zeroCrossings), 10 s past the record, rtol 1e-10."""
    pair = gm.pair_of(DFHS)
    rec = pair.along(0.0, with_vertical=True)
    with RockingFMU() as rfmu:
        run = rfmu.simulate(dharahara_cases()[case], record=rec, scale=3.0, rtol=1e-10,
                            stop_time=float(rec.time[-1]) + 10.0)
    assert not run.overturned and run.zero_crossings >= 20, "the case must rock and stand along x"
    assert flexible_row(case)[2] == f"{run.peak_theta_over_alpha:.3f} ({run.zero_crossings})"


def test_the_flexible_table_s_rigid_case_is_the_rigid_study_s():
    """The rigid case of the 49 under Darfield DFHS x3 (examples/dharahara_space_flexible.rs,
    support/space_runs.rs) against the rigid study's row (examples/dharahara_space.rs, its own
    loops): the same peak in space and the same overturning along x."""
    rigid = [c.strip() for c in next(
        line for line in (REPO / "docs" / "dharahara.md").read_text().splitlines()
        if line.startswith("| Darfield DFHS | 3 |")).strip("|").split("|")]
    row = flexible_row("rigid")
    assert row[1] == rigid[2]  # peak (impacts): on the rigid bed the crossings are the impacts
    assert row[2].split(" (")[0] == rigid[4]
    assert row[3].split(" (")[0] == rigid[5]


def test_the_command_runs_a_crushing_bed_and_matches_the_flexible_table(tmp_path):
    """`rocking space --preset dharahara-F170-fm5` (the bed's interface, kn, fm and formulation
    through RoundBody.fmu) under Darfield DFHS x3: the page's run in space (the Rust example,
    Spatial called directly), peak and crossings."""
    out = tmp_path / "f170"
    r = rocking("space", DFHS, "--scale", 3, "--preset", "dharahara-F170-fm5", "--tail", 10, "--rtol", 1e-10,
                "--out", out)
    assert r.returncode == 0, r.stderr
    s = json.loads((out / "summary.json").read_text())
    assert {k: s["parameters"][k] for k in ("interface", "kn", "fm")} == {
        "interface": "elastoPlastic", "kn": 170e6, "fm": 5e6}
    assert not s["overturned"] and s["impacts"] >= 20
    assert flexible_row("F170_fm5")[1] == f"{s['peak_theta_over_alpha']:.3f} ({s['impacts']})"
    assert f"{s['impacts']} crossings" in r.stdout


def test_a_crushing_case_that_overturns_along_x_stands_in_space_through_the_fmu(fmu):
    """I15_fm15 under Darfield DFHS x3 (the page's first figure): through RoundBody.fmu the run
    in space stands with the page's peak and crossings, where the page's planar run along x
    overturns."""
    params = dict(dharahara_cases()["I15_fm15"])
    params["IcAxial"] = params["W"] / params["g"] * (3.99 ** 2 + 2.12 ** 2) / 2
    pair = gm.pair_of(DFHS)
    run = fmu.simulate(params, pair=pair, scale=3.0, rtol=1e-10, stop_time=pair.npts * pair.dt + 10.0)
    row = flexible_row("I15_fm15")
    assert row[2].startswith("overturns")
    assert not run.overturned and row[1] == f"{run.peak_theta_over_alpha:.3f} ({run.impacts})"


def planar_drum_run(rfmu, bed, amplitude, stop=3.0):
    """The drum through RockingBlock.fmu on `bed` under one sine of `amplitude` m/s2 over 0.5 s."""
    t = np.arange(0.0, stop + 1e-9, 0.005)
    acc = np.where(t < 0.5, amplitude * np.sin(2 * math.pi * t / 0.5), 0.0)
    return rfmu.simulate({**DRUM, **bed}, ag=(t, acc), stop_time=stop, rtol=1e-10)


def test_the_planar_top_on_a_soft_bed_is_the_closed_form_not_the_rim_s():
    """`rocking space`'s planar path of the top on an elastic bed soft enough to keep the drum in
    full contact (kn 3e6 Pa/m: thetaJo = 2 W/(kn A D) = 0.039 rad): there the resultant is
    rho = kn Is phi/W from the base's centre (docs/model.md §2's closure), hg = hG cos(phi) +
    rho sin(phi), and the top's displacement xG + hG sin(theta) is, by hand,
    2 hG sin(theta) + (kn Is/W)(sin(theta) - theta cos(theta)); the rim's formula,
    2 hG sin(theta) + Ro (1 - cos(theta)), is off by Ro theta²/2 - (kn Is/W) theta³/3 to leading
    order. Measured at the peak of 0.027 rad: the path 2.5e-9 m from the hand's, the rim 1.65e-4 m."""
    from rocking.cli.space import planar_top

    kn = 3e6
    with RockingFMU() as rfmu:
        run = planar_drum_run(rfmu, {"interface": "elastic", "kn": kn}, 1.6)
    th, c = run.result["theta"], run.calculated
    weight, ro = c["weight"], DRUM["Ro"]
    hg = c["R0"] * math.cos(c["alpha"])
    assert hg == pytest.approx(1.5) and ro == pytest.approx(c["R0"] * math.sin(c["alpha"]))
    assert 0.5 * c["thetaJo"] < np.abs(th).max() < c["thetaJo"], "full contact, well tilted"
    assert (run.result["regime"] == 0).all()
    hand = 2 * hg * np.sin(th) + kn * math.pi * ro ** 4 / 4 / weight * (np.sin(th) - th * np.cos(th))
    rim = 2 * hg * np.sin(th) + ro * np.sign(th) * (1 - np.cos(th))
    top = planar_top(run, flexible=True)
    print(f"peak {np.abs(th).max():.4f} rad, |top - hand| {np.abs(top - hand).max():.2e} m, "
          f"|rim - hand| {np.abs(rim - hand).max():.2e} m")
    assert np.abs(top - hand).max() <= 1e-7
    assert np.abs(rim - hand).max() > 1e-4


def test_the_planar_top_on_a_stiff_bed_tends_to_the_rim_s():
    """A pulse that rocks the drum (peak 0.06 rad, 7 crossings): on the rigid bed the integral of
    hg dtheta (af = 0 off upright) is the rim's closed form to 3.0e-7 m, its trapezoids' error at
    5 ms; on elastic beds the path differs from the rim's formula of the same run by the
    resultant's distance from the toe, af, which shrinks as kn^(-2/5) on a circle's toe
    (docs/model.md §11.2): measured 3.2e-5 m at kn 1e10 Pa/m, 4.2e-6 m at 1e12 (7.6 times less,
    6.3 by the power)."""
    from rocking.cli.space import planar_top

    gaps = []
    with RockingFMU() as rfmu:
        rigid = planar_drum_run(rfmu, {"interface": "rigid"}, 5.0)
        assert rigid.impacts >= 5
        rim = planar_top(rigid, flexible=False)
        assert np.abs(planar_top(rigid, flexible=True) - rim).max() <= 1e-6
        for kn in (1e10, 1e12):
            run = planar_drum_run(rfmu, {"interface": "elastic", "kn": kn}, 5.0)
            assert run.zero_crossings >= 5 and np.abs(run.result["theta"]).max() > 0.05
            gaps.append(np.abs(planar_top(run, flexible=True) - planar_top(run, flexible=False)).max())
    print(f"path - rim at kn 1e10, 1e12: {gaps[0]:.2e}, {gaps[1]:.2e} m")
    assert gaps[1] <= 1e-5 and 4.0 <= gaps[0] / gaps[1] <= 10.0
