"""Rocking spectra of records (rocking.spectra, `rocking spectrum`): docs/spectra.md.

References independent of the code under test: similarity of two rigid blocks of one
slenderness under a record stretched in time by the ratio of their p (built here from the
record's samples); the least overturning scale against runs of the FMU at and below it
(brute force); a rigid block under a rectangular pulse given as a record against the exact
first integral of test_map.py; p = sqrt(3 g / (4 R)) worked by hand."""

import dataclasses
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from rocking.fmu import RockingFMU
from rocking.groundmotion import Record, read_all
from rocking.maps import read_metadata
from rocking.pulses import Pulse
from rocking.spectra import SpectrumOptions, rectangle_family, run_spectrum
from test_map import rectangular_least_amplitude

REPO = pathlib.Path(__file__).resolve().parent.parent
LOMA = REPO / "data" / "ground-motions" / "usgs-lomaprieta-1989" / "0111a.smc"
G = 9.81
ALPHA = 0.2
RIGID = {"interface": "rigid"}


@pytest.fixture(scope="module")
def fmu(fmu_path):
    with RockingFMU(fmu_path) as f:
        yield f


@pytest.fixture(scope="module")
def loma():
    return read_all(LOMA)[0]


def test_family_by_p_and_by_size_by_hand():
    by_p = rectangle_family(RIGID, alpha=ALPHA, p=[2.0, 4.0])
    by_r = rectangle_family(RIGID, alpha=ALPHA, sizes=[3 * G / 16])
    for (_, body), p in zip(by_p, (2.0, 4.0)):
        R = math.hypot(body["B"], body["H"]) / 2
        assert math.sqrt(3 * G / (4 * R)) == pytest.approx(p, rel=1e-12)
        assert math.atan(body["B"] / body["H"]) == pytest.approx(ALPHA, rel=1e-12)
        assert body["interface"] == "rigid" and body["shape"] == "solidRectangle"
    assert by_r[0][1]["B"] == pytest.approx(by_p[0][1]["B"], rel=1e-12)
    assert [label for label, _ in rectangle_family(RIGID, alpha=ALPHA, p=[2.0, 4.0, 2.0])] == ["p=2", "p=4"]
    with pytest.raises(ValueError, match="empty"):
        rectangle_family(RIGID, alpha=ALPHA, p=[])
    with pytest.raises(ValueError, match="sizes: every value must be > 0"):
        rectangle_family(RIGID, alpha=ALPHA, sizes=[1.0, -2.0])
    with pytest.raises(ValueError, match="hollowCircle"):
        rectangle_family(dict(RIGID, shape="hollowCircle"), p=[1.0])


def test_similarity_rigid_blocks_under_a_record_stretched_in_time(fmu, loma):
    """theta'' = -p^2 [sin(alpha - theta) + ag/g cos(alpha - theta)]: in tau = p t two rigid
    blocks of one alpha are one block, so a block of p / k under ag(t / k) has the history of
    the block of p under ag(t). The spectra of both (peak at several scales, the least
    overturning scale's search) must agree."""
    k = 2.5
    slow = dataclasses.replace(loma, time=loma.time * k, dt=loma.dt * k)
    opts = SpectrumOptions(scales=(2.0, 3.0, 4.0), tol=0.01, tail=5.0)
    p = [3.0, 6.0]
    _, fast_sp = run_spectrum(rectangle_family(RIGID, alpha=ALPHA, p=p), loma, fmu, opts, workers=2)
    _, slow_sp = run_spectrum(rectangle_family(RIGID, alpha=ALPHA, p=[x / k for x in p]), slow, fmu,
                              dataclasses.replace(opts, tail=5.0 * k), workers=2)
    assert slow_sp["p"].to_numpy() == pytest.approx(fast_sp["p"].to_numpy() / k, rel=1e-12)
    a, b = fast_sp["peak_theta_over_alpha"].to_numpy(), slow_sp["peak_theta_over_alpha"].to_numpy()
    print("peak theta/alpha, p:", a, "\n                 p/k:", b)
    assert (a > 0.05).sum() >= 3  # the blocks rock: the comparison is not of zeros
    assert list(fast_sp["overturned"]) == list(slow_sp["overturned"])
    assert b == pytest.approx(a, rel=1e-4, abs=1e-6)
    for col in ("least_scale_lo", "least_scale_hi"):
        assert slow_sp[col].to_numpy() == pytest.approx(fast_sp[col].to_numpy(), rel=1e-12)


def test_least_overturning_scale_against_brute_force(fmu, loma):
    """The bracket's runs repeated outside the search (lo stands, hi overturns) and a scan of
    40 scales from the uplift scale up to lo: none overturns (the least is the least)."""
    bodies = (rectangle_family(RIGID, alpha=ALPHA, p=[4.0])
              + rectangle_family({"interface": "elastic", "kn": 1e9}, alpha=ALPHA, p=[4.0]))
    bodies = [("rigid", bodies[0][1]), ("elastic", bodies[1][1])]
    _, sp = run_spectrum(bodies, loma, fmu, SpectrumOptions(scales=(1.0,), tol=1e-3, tail=5.0), workers=2)
    lines = []
    for (label, params), row in zip(bodies, sp.itertuples()):
        assert not row.censored and row.unresolved == ""
        lo, hi = row.least_scale_lo, row.least_scale_hi
        assert hi / lo < 1 + 1e-3 and lo < row.least_scale < hi

        def over(s):
            return fmu.simulate(params, record=loma, scale=s, stop_time=loma.duration + 5.0,
                                outputs=("thetaOverAlpha",)).overturned

        assert over(hi) and not over(lo)
        below = np.geomspace(row.uplift_scale, lo, 40)
        assert not any(over(s) for s in below)
        lines.append(f"{label}: least scale {row.least_scale:.5g} in [{lo:.6g}, {hi:.6g}], 40 runs below stand")
    print("\n".join(lines))


def test_rectangular_pulse_record_against_the_first_integral(fmu):
    """A rigid block under one rectangular pulse of amplitude A0 given as a record: the least
    overturning scale times A0 / (g tan alpha) is the exact least amplitude (test_map's first
    integral), to the search's tolerance."""
    A0, lines = 3.0, []
    for w_over_p in (2.0, 5.0):
        (label, body), = rectangle_family(RIGID, alpha=ALPHA, p=[3.0])
        pulse = Pulse("rectangular", A0, w_over_p * 3.0)
        t, a = pulse.samples(800)
        rec = Record(time=t, acc=a, dt=t[1] - t[0], name="rectangular pulse")
        _, sp = run_spectrum([(label, body)], rec, fmu, SpectrumOptions(scales=(1.0,), tol=1e-5, tail=5.0),
                             workers=1)
        got = sp["least_scale"].iloc[0] * A0 / (G * math.tan(ALPHA))
        ref = rectangular_least_amplitude(ALPHA, w_over_p)
        lines.append(f"w/p = {w_over_p}: spectrum {got:.7f}, first integral {ref:.7f}, diff {got / ref - 1:+.1e}")
        assert got == pytest.approx(ref, rel=2e-5), "\n".join(lines)
    print("\n".join(lines))


def _rocking(*args):
    return subprocess.run([sys.executable, "-m", "rocking", *args], capture_output=True, text=True, timeout=120)


def test_spectrum_cli_writes_tables_plot_metadata(tmp_path, fmu_path):
    from importlib.metadata import version

    import pandas as pd
    out = tmp_path / "s"
    r = _rocking("spectrum", str(LOMA), "--fmu", fmu_path, "--interface", "rigid", "--alpha", "0.2",
                 "--p", "2,4,8", "--scales", "1,3", "--beside", "interface=elastic,kn=1e9", "--tail", "3",
                 "--workers", "2", "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert "spectrum body" in r.stderr and "3/3" in r.stderr  # the progress bar
    sp = pd.read_parquet(out / "spectrum.parquet")
    assert len(sp) == 2 * 3 * 2  # beds x bodies x scales
    assert set(sp["bed"]) == {"body", "interface=elastic,kn=1e9"} and set(sp["scale"]) == {1.0, 3.0}
    assert sp["p"].round(9).isin([2.0, 4.0, 8.0]).all()
    assert (sp["least_scale"] > sp["uplift_scale"]).all()
    runs = pd.read_parquet(out / "runs.parquet")
    assert {"hunt", "scan", "bracket", "asked"} <= set(runs["phase"])
    meta = read_metadata(out / "spectrum.parquet")
    assert meta["rocking_version"] == version("rocking") and meta["scales"] == [1.0, 3.0]
    assert meta["record"]["path"] == str(LOMA) and meta["beds"]["interface=elastic,kn=1e9"]["kn"] == 1e9
    assert read_metadata(out / "runs.parquet") == meta
    assert (out / "spectrum.png").stat().st_size > 0


def test_spectrum_cli_bodies_file(tmp_path, fmu_path, capsys):
    import pandas as pd
    bodies = tmp_path / "bodies.json"
    bodies.write_text('{"small": {"B": 0.2, "H": 1.0}, "large": {"B": 0.8, "H": 4.0}}')
    out = tmp_path / "b"
    status, err = _in_process(capsys, "spectrum", str(LOMA), "--fmu", fmu_path, "--interface", "rigid",
                              "--bodies", str(bodies), "--no-hunt", "--scales", "3", "--workers", "1", "--quiet",
                              "--no-plot", "--out", str(out))
    assert status == 0, err
    sp = pd.read_parquet(out / "spectrum.parquet")
    assert list(sp["body"]) == ["small", "large"]
    assert sp["p"].iloc[0] == pytest.approx(2 * sp["p"].iloc[1], rel=1e-12)  # 4 times the size


def _in_process(capsys, *args):
    """`rocking ARGS` in this process (no interpreter start): (exit status, stderr)."""
    from rocking.cli import main
    status = main(list(args))
    return status, capsys.readouterr().err


@pytest.mark.parametrize("args, message", [
    (["--p", ""], "--p '': the grid is empty"),
    (["--sizes", "1,0"], "--sizes 1,0: every value must be > 0"),
    (["--p", "1", "--shape", "hollowCircle"], "--p: a family by p or size is of solid rectangular prisms"),
    (["--p", "1", "--sizes", "1"], "one of --p P, --sizes R or --bodies FILE"),
    (["--bodies", "nothere.json"], "--bodies nothere.json: cannot read"),
])
def test_spectrum_bad_input_is_one_line(tmp_path, fmu_path, capsys, args, message):
    status, err = _in_process(capsys, "spectrum", str(LOMA), "--fmu", fmu_path, *args, "--out", str(tmp_path / "x"))
    assert status == 2, err
    assert message in err and len(err.strip().splitlines()) == 1, err


def test_spectrum_unreadable_record_is_one_line(tmp_path, fmu_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("x\n")
    for record, message in ((bad, "bad.csv: line 1"), (tmp_path / "none.csv", "none.csv: no such record file")):
        status, err = _in_process(capsys, "spectrum", str(record), "--fmu", fmu_path, "--p", "1",
                                  "--out", str(tmp_path / "x"))
        assert status == 2 and message in err and len(err.strip().splitlines()) == 1, err


def test_a_body_the_fmu_refuses_is_a_row_with_its_error(fmu, loma):
    """A crushing bed too weak for the largest body's weight (rho g H > fm at R = 30 m): that
    body's row carries the FMU's message, the smaller body is run as usual."""
    bodies = rectangle_family({"interface": "elastoPlastic", "kn": 1e9, "fm": 5e5}, alpha=ALPHA, sizes=[0.5, 30.0])
    runs, sp = run_spectrum(bodies, loma, fmu, SpectrumOptions(scales=(3.0,), hunt=False, tail=2.0), workers=1)
    assert sp["error"].iloc[0] == "" and sp["peak_theta_over_alpha"].iloc[0] > 0
    assert "crushes at rest" in sp["error"].iloc[1] and math.isnan(sp["p"].iloc[1])
    assert "crushes at rest" in sp["unresolved"].iloc[1]
    assert len(runs) == 2


def test_spectrum_on_dask_gives_the_process_pools_tables(fmu, loma):
    """The bodies as tasks of the fragility runner's Dask code (rocking.maps.on_dask: its FMU
    plugin, the record sent once), on an in-process scheduler and worker: the same tables as
    the process pool's; `rocking spectrum` takes --dask and --scheduler as `rocking map` does."""
    import pandas as pd
    from distributed import Client

    from rocking.cli import map as map_cli, spectrum as spectrum_cli
    from rocking.cli.main import build_parser
    bodies = rectangle_family(RIGID, alpha=ALPHA, p=[3.0, 6.0])
    short = Record(time=loma.time[:1500], acc=loma.acc[:1500], dt=loma.dt, name="first 1500 samples")
    options = SpectrumOptions(scales=(1.0, 2.0), hunt=False, tail=2.0)
    pool = run_spectrum(bodies, short, fmu, options, workers=2)
    done = []
    with Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=None) as client:
        dask = run_spectrum(bodies, short, fmu, options, client=client,
                            progress=lambda k, n, summary: done.append((k, n, summary["body"])))
    for a, b in zip(dask, pool):
        pd.testing.assert_frame_equal(a.drop(columns="wall_s", errors="ignore"),
                                      b.drop(columns="wall_s", errors="ignore"))
    assert sorted(d[2] for d in done) == ["p=3", "p=6"] and [d[:2] for d in done] == [(1, 2), (2, 2)]
    parser = build_parser({"map": map_cli, "spectrum": spectrum_cli})
    args = parser.parse_args(["spectrum", str(LOMA), "--p", "3", "--dask", "--scheduler", "tcp://h:1", "--out", "x"])
    assert args.dask and args.scheduler == "tcp://h:1" and args.func is spectrum_cli.cmd_spectrum
