"""The `rocking` command end to end: run as a user would (a subprocess of
.venv/bin/rocking) on the shipped records and the packaged FMU.

What each output is checked against comes from elsewhere: the files' own header
statements or their numbers read here with plain numpy, the FMU's
modelDescription.xml read with the standard library's XML parser, closed forms
(alpha = atan(B/H) of a rectangular prism), and the command's other outputs
(the summary against the time history it wrote).
"""

import json
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

REPO = Path(__file__).resolve().parents[1]
DATA = REPO / "data" / "ground-motions"
KATNP = DATA / "katnp-standin" / "KATNP_NS_standin.csv"
V2 = DATA / "csmip-coalinga-1983" / "ce36456p_CE36456.V2"
DARFIELD_090 = DATA / "geonet-darfield-2010" / "3366146_DFHS_HN_20.090"
SMC_A = DATA / "usgs-lomaprieta-1989" / "0111a.smc"
G = 9.80665  # m/s² per g


def rocking_exe():
    for candidate in (Path(sys.executable).parent / "rocking", REPO / ".venv" / "bin" / "rocking"):
        if candidate.is_file():
            return str(candidate)
    found = shutil.which("rocking")
    if found is None:
        pytest.fail("the `rocking` command is not installed: run tools/venv.sh (pip install -e .)", pytrace=False)
    return found


def rocking(*args, env=None, cwd=None):
    return subprocess.run([rocking_exe(), *map(str, args)], capture_output=True, text=True, env=env,
                          cwd=cwd, timeout=120)


def ok(*args, **kwargs):
    proc = rocking(*args, **kwargs)
    assert proc.returncode == 0, f"rocking {' '.join(map(str, args))}: exit {proc.returncode}\n{proc.stderr}"
    assert "Traceback" not in proc.stderr
    return proc


def katnp_acc():
    """The stand-in's samples (m/s²) read with numpy, not with the package's reader."""
    return np.loadtxt(KATNP, delimiter=",", comments="#", skiprows=5)


# --------------------------------------------------------------------------
# simulate

@pytest.fixture(scope="module")
def overturning(fmu_path, tmp_path_factory):
    """A preset that overturns under the stand-in (docs/examples.md: I15_fm2 at 25.24 s)."""
    out = tmp_path_factory.mktemp("overturn")
    proc = ok("simulate", KATNP, "--preset", "dharahara-I15-fm2", "--out", out)
    return out, proc


def read_outputs(out):
    csv = pd.read_csv(out / "timehistory.csv", float_precision="round_trip")
    summary = json.loads((out / "summary.json").read_text())
    return csv, summary


def test_simulate_writes_csv_summary_and_plot(overturning, model_description):
    out, proc = overturning
    csv, summary = read_outputs(out)
    names = {v.name for v in model_description.modelVariables}
    expected = ["time", "ag"] + [n for n in ("theta", "omega", "thetaOverAlpha", "MR", "af", "contactLength",
                                             "regime", "impacts", "zeroCrossings", "overturned") if n in names]
    assert list(csv.columns) == expected
    png = (out / "plot.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20_000
    assert "OVERTURNED" in proc.stdout and "SYNTHETIC STAND-IN" in proc.stdout


def test_simulate_summary_agrees_with_its_csv(overturning):
    out, _ = overturning
    csv, s = read_outputs(out)
    theta = csv["theta"].to_numpy()
    assert s["peak_theta_rad"] == np.max(np.abs(theta))
    assert s["t_peak_theta_s"] == csv["time"].to_numpy()[np.argmax(np.abs(theta))]
    assert s["peak_theta_over_alpha"] == pytest.approx(np.max(np.abs(csv["thetaOverAlpha"])), rel=1e-12)
    assert s["rows"] == len(csv)
    last = csv.iloc[-1]
    assert s["impacts"] == last["impacts"]
    if "zeroCrossings" in csv:
        assert s["zeroCrossings"] == last["zeroCrossings"]
    regimes = sorted(set(csv["regime"]))
    assert len(s["regimes_reached"]) == len(regimes)
    assert set(csv["overturned"]) <= {0, 1}


def test_simulate_reports_overturning_with_its_time(overturning):
    out, _ = overturning
    csv, s = read_outputs(out)
    assert s["overturned"] is True
    assert s["t_overturn_s"] == csv["time"].iloc[-1]
    assert 20.0 < s["t_overturn_s"] < 30.0  # docs/examples.md: 25.24 s with rtol 1e-11
    assert csv["overturned"].iloc[-1] == 1
    # the run ends where |theta| reaches the overturning rotation
    assert abs(csv["theta"].iloc[-1]) == pytest.approx(s["calculated"]["thetaOv"], rel=1e-6)


def test_simulate_feeds_the_scaled_record(fmu_path, tmp_path):
    ok("simulate", KATNP, "--preset", "dharahara-rigid", "--scale", "0.5", "--stop-time", "12", "--out", tmp_path)
    csv, s = read_outputs(tmp_path)
    raw = katnp_acc()
    n = len(csv)
    assert n == 1201 and csv["time"].iloc[-1] == pytest.approx(12.0)
    np.testing.assert_allclose(csv["ag"].to_numpy(), 0.5 * raw[:n, 1], rtol=0, atol=1e-15)
    assert s["overturned"] is False and s["t_overturn_s"] is None
    assert s["record"]["npts"] == 8001 and s["record"]["dt_s"] == 0.01
    assert s["record"]["pga_g"] == pytest.approx(np.max(np.abs(raw[:, 1])) / G, rel=1e-12)
    assert s["record"]["scaled_pga_g"] == pytest.approx(0.5 * s["record"]["pga_g"], rel=1e-14)


def test_simulate_parameters_by_name(fmu_path, tmp_path):
    """A prism B x H released from rest at theta0 on a rigid interface, no record:
    alpha = atan(B/H); rigid free rocking only loses energy, so the peak is the release
    angle; the first impact comes when energy conservation about the toe says,
    t1 = integral from 0 to theta0 of dtheta / sqrt(2 p² (cos(alpha - theta0) - cos(alpha - theta))),
    p² = m g R0 / IO = 3 g / (4 R0) for a prism."""
    from scipy.integrate import quad

    b, h, theta0, g = 0.4, 2.0, 0.1, 9.81
    ok("simulate", "--shape", "solidRectangle", "--B", b, f"--H={h}", "--massModel", "prism", "--g", g,
       "--interface", "rigid", "--theta", theta0, "--stop-time", "1.5", "--output-interval", "0.001",
       "--out", tmp_path)
    csv, s = read_outputs(tmp_path)
    alpha, r0 = math.atan(b / h), math.hypot(b, h) / 2
    assert s["calculated"]["alpha"] == pytest.approx(alpha, rel=1e-12)
    assert s["parameters"] == {"shape": "solidRectangle", "B": b, "H": h, "massModel": "prism", "g": g,
                               "interface": "rigid", "theta": theta0}
    assert s["peak_theta_rad"] == theta0 and csv["theta"].iloc[0] == theta0
    assert s["record"] is None and (csv["ag"] == 0).all()
    p2 = 3 * g / (4 * r0)

    def smooth(th):  # 1/theta' times sqrt(theta0 - theta); its limit at theta0 is 1/sqrt(2 p² sin(alpha - theta0))
        drop = math.cos(alpha - theta0) - math.cos(alpha - th)
        return math.sqrt((theta0 - th) / (2 * p2 * drop)) if drop > 0 else 1 / math.sqrt(2 * p2 * math.sin(alpha - theta0))

    t1 = quad(smooth, 0, theta0, weight="alg", wvar=(0, -0.5))[0]  # (theta0 - theta)^-1/2 singularity
    t, theta, omega = (csv[c].to_numpy() for c in ("time", "theta", "omega"))
    k = int(np.nonzero(theta <= 0)[0][0]) - 1  # the last sample before the impact
    # a Newton step from it (the impact changes omega, so no interpolation across it):
    # error about |theta''| dt² / (2 |omega|) = 1e-6 s at dt = 1 ms
    t_cross = t[k] - theta[k] / omega[k]
    assert t_cross == pytest.approx(t1, abs=1e-5)
    assert s["impacts"] >= 2  # the half cycles shorten after each impact: several in 1.5 s


# --------------------------------------------------------------------------
# info, record

def test_info_lists_every_variable_of_the_model_description(fmu_path):
    with zipfile.ZipFile(fmu_path) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    variables = root.find("ModelVariables")
    stdout = ok("info").stdout
    rows = {line.split()[0]: line.split() for line in stdout.splitlines() if line.strip()}
    assert len(variables) > 30
    for sv in variables:
        name = sv.get("name")
        assert name in rows, name
        assert rows[name][1] == sv.get("causality", "local"), name
    presets = ok("info", "--presets").stdout
    # 1 rigid + (6 foundation + 6 interface stiffnesses) x 4 crushing strengths + 6 blocks x 2 formulations
    assert re.search(r"^61 presets", presets, re.M)
    names = re.findall(r"^  (\S+)  ", presets, re.M)
    assert len(names) == len(set(names)) == 61
    assert {"dharahara-rigid", "dharahara-F170-fm5", "dharahara-I1500-elastic", "fig15-alpha0.20-costa",
            "fig15-alpha0.35-shiftingPivot"} <= set(names)
    help_text = " ".join(ok("simulate", "--help").stdout.split())
    assert "dharahara-F{85,170,340,680,1350,13500}-{fm2,fm5,fm15,elastic}" in help_text


def record_values(stdout):
    """[(component, npts, dt, pga_g, pga_m_s2)] from `rocking record` output."""
    blocks = re.findall(r"^\[(.*?)\].*?npts\s+(\d+)\s+dt\s+(\S+) s.*?PGA\s+(\S+) g = (\S+) m/s2",
                        stdout, re.M | re.S)
    return [(c, int(n), float(dt), float(g), float(ms2)) for c, n, dt, g, ms2 in blocks]


def test_record_v2_matches_its_header(tmp_path):
    text = V2.read_text(encoding="latin-1")
    header = re.findall(r"^\s*(\d+) POINTS OF ACCEL DATA EQUALLY SPACED AT\s+([\d.]+) SEC", text, re.M)
    peaks = [abs(float(p)) for p in re.findall(r"^PEAK ACCELERATION =\s*(\S+)\s+CM/SEC/SEC", text, re.M)]
    proc = ok("record", V2, "--plot", tmp_path / "v2.png")
    assert "format      csmip_v2" in proc.stdout
    got = record_values(proc.stdout)
    assert [c for c, *_ in got] == ["90", "UP", "0"]
    for (_, npts, dt, pga_g, pga_ms2), (h_npts, h_dt), peak in zip(got, header, peaks, strict=True):
        assert (npts, dt) == (int(h_npts), float(h_dt))
        assert pga_ms2 == pytest.approx(peak / 100, abs=5e-5)  # printed to 4 decimals
        assert pga_g == pytest.approx(peak / 100 / G, abs=5e-5)
    assert (tmp_path / "v2.png").read_bytes()[:4] == b"\x89PNG"


def test_record_plain_ascii_matches_its_numbers():
    lines = DARFIELD_090.read_text().splitlines()
    npts, dt = lines[1].split()[:2]
    values = np.array([float(w) for line in lines[2:] for w in line.split()])
    got = record_values(ok("record", DARFIELD_090).stdout)
    assert got == [("090", int(npts), float(dt), pytest.approx(np.max(np.abs(values)), abs=5e-5),
                    pytest.approx(np.max(np.abs(values)) * G, abs=5e-5))]
    assert len(values) == int(npts)


@pytest.mark.parametrize("interval", [0.003, 0.005])
def test_simulate_honours_the_output_interval(fmu_path, tmp_path, interval):
    """Rows every `interval` s (and at the end), not every record dt (issue 25: 0.003 and 0.005
    gave the record's 0.01 s rows); theta at the times both grids share agrees with the run
    at the record's dt, to the integrator's tolerance."""
    runs = {}
    for every in (interval, None):
        out = tmp_path / f"o{every}"
        extra = ["--output-interval", str(every)] if every else []
        ok("simulate", KATNP, "--theta", "0.05", "--stop-time", "0.6", "--rtol", "1e-9", *extra, "--out", out)
        runs[every] = read_outputs(out)[0]
    t = runs[interval]["time"].to_numpy()
    want = np.arange(int(0.6 / interval + 1e-9) + 1) * interval
    assert len(t) in (len(want), len(want) + 1) and t[-1] == pytest.approx(0.6)
    np.testing.assert_allclose(t[:len(want)], want, atol=1e-9)
    base = runs[None].set_index(runs[None]["time"].round(9))
    shared = runs[interval][runs[interval]["time"].round(9).isin(base.index)]
    assert len(shared) >= 0.6 / max(interval, 0.01) * 0.3
    peak = np.abs(base["theta"]).max()
    np.testing.assert_allclose(shared["theta"], base.loc[shared["time"].round(9), "theta"], atol=1e-6 * peak)


def test_simulate_refuses_bad_times(fmu_path, tmp_path):
    for value, record in (("0", []), ("-0.01", [KATNP])):  # 0 without a record: ZeroDivisionError
        line = fails("simulate", *record, "--output-interval", value, "--out", tmp_path)
        assert "--output-interval" in line and "must be > 0 s" in line
    line = fails("simulate", "--stop-time", "-1", "--out", tmp_path)
    assert "--stop-time" in line and "must be >= 0 s" in line


def test_parameters_of_another_interface_are_ignored_not_recorded(fmu_path, tmp_path):
    """`--interface rigid --kn -5 --fm 0` (issue 25): summary.json recorded kn and fm as used.
    The rigid interface uses neither (docs/model.md); the shape hollowCircle does not use B."""
    proc = ok("simulate", "--interface", "rigid", "--kn", "-5", "--fm", "0", "--stop-time", "0.5",
              "--out", tmp_path)
    assert "--kn -5, --fm 0 ignored: not used by interface = rigid" in proc.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert "kn" not in summary["parameters"] and "fm" not in summary["parameters"]
    assert set(summary["ignored_parameters"]) == {"kn", "fm"}
    proc = ok("simulate", "--preset", "dharahara-F170-fm5", "--B", "3", "--stop-time", "0.5", "--out", tmp_path)
    assert "--B 3 ignored: not used by shape = hollowCircle" in proc.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["parameters"]["kn"] == 170e6 and summary["parameters"]["fm"] == 5e6
    # the interface that uses kn still has it checked
    line = fails("simulate", "--interface", "elastoPlastic", "--kn", "-5", "--out", tmp_path)
    assert "kn" in line and "-5" in line


def test_plot_theta_axis_follows_the_response():
    """A 0.008 alpha response was drawn flat on a fixed ±1.1 axis (issue 25); the ±alpha and
    ±thetaOv lines, off such a scale, are named in the legend instead."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rocking.cli.plots import theta_panel

    t = np.linspace(0, 10, 501)
    fig, (small, large) = plt.subplots(2)
    theta_panel(small, t, 0.008 * np.sin(t), alpha=0.13, theta_ov=0.107)
    theta_panel(large, t, 0.8 * np.sin(t), alpha=0.13, theta_ov=0.107)
    assert small.get_ylim() == pytest.approx((-0.0104, 0.0104), rel=1e-3)
    assert "off this scale" in small.get_legend().get_texts()[-1].get_text()
    assert large.get_ylim() == pytest.approx((-1.1, 1.1))
    levels = sorted({round(line.get_ydata()[0], 6) for line in large.get_lines()[1:]})
    assert levels == pytest.approx([-1, -0.107 / 0.13, 0, 0.107 / 0.13, 1])
    assert all(legend_outside(ax) for ax in (small, large))
    plt.close(fig)


def legend_outside(ax):
    """Whether the panel's legend lies wholly above its plotting area (off the curves)."""
    ax.figure.canvas.draw()
    box = ax.get_legend().get_window_extent()
    return box.y0 >= ax.get_window_extent().y1 - 1


def test_plot_regime_reaches_overturned():
    """The FMU's last row holds the regime before overturning; the trace must end on it."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rocking.cli.plots import _regime_panel

    fig, ax = plt.subplots()
    _regime_panel(ax, [0.0, 1.0, 2.0], [0, 1, 2], {0: "full", 1: "partial", 2: "crushing", 4: "overturned"}, 2.5)
    ends = [(line.get_xdata()[-1], line.get_ydata()[-1]) for line in ax.get_lines()]
    assert (2.5, 4) in ends
    plt.close(fig)


def test_simulate_tail_and_outputs(fmu_path, tmp_path):
    """--tail 3: the run goes 3 s past the record's end (free motion); --outputs picks the
    columns, Fx and Fz among them."""
    ok("simulate", KATNP, "--preset", "dharahara-F170-fm5", "--scale", "0.5", "--tail", "3",
       "--outputs", "theta,Fx,Fz", "--output-interval", "0.05", "--out", tmp_path)
    csv, summary = read_outputs(tmp_path)
    end = (len(katnp_acc()) - 1) * 0.01
    assert list(csv.columns) == ["time", "ag", "theta", "Fx", "Fz"]
    assert csv["time"].iloc[-1] == pytest.approx(end + 3) and summary["tail_s"] == 3
    after = csv[csv["time"] > end]
    assert len(after) >= 59 and (after["ag"] == 0).all()
    # at rest in full contact the support carries the weight: Fz = W (the preset's 24003.94 kN)
    assert csv["Fz"].iloc[0] == pytest.approx(24003.94e3, rel=1e-9)
    line = fails("simulate", KATNP, "--outputs", "theta,Fy", "--out", tmp_path)
    assert "'Fy'" in line and "Fx" in line
    line = fails("simulate", "--tail", "3", "--out", tmp_path)
    assert "--tail" in line and "RECORD" in line


def test_simulate_reports_the_friction_demand_against_mu(fmu_path, tmp_path):
    """A rigid block held at rest by a constant ag (below uplift) needs a friction coefficient of
    |ag|/g (Fx = m ag, Fz = W): the summary's peak demand is that, and --mu flags it only when the
    demand is above mu (docs/model.md §5, "Friction demand")."""
    ag = 0.8  # m/s2: 0.0816 g, below uplift of the default 0.5 x 2.5 m block (g tan(alpha) = 1.96 m/s2)
    record = tmp_path / "constant.csv"
    record.write_text("time,acc\n" + "".join(f"{k * 0.01:.2f},{ag}\n" for k in range(101)))
    for mu, exceeds in [(0.05, True), (0.2, False)]:
        out = tmp_path / f"mu{mu}"
        proc = ok("simulate", record, "--units", "m/s2", "--interface", "rigid", "--mu", mu, "--out", out)
        friction = json.loads((out / "summary.json").read_text())["friction"]
        assert friction["peak_demand"] == pytest.approx(ag / 9.81, rel=1e-12)
        assert friction["mu"] == mu and friction["exceeds_mu"] is exceeds
        assert (friction["t_first_exceeds_s"] == 0.0) if exceeds else friction["t_first_exceeds_s"] is None
        assert ("EXCEEDS mu" in proc.stdout) is exceeds
    out = tmp_path / "nomu"
    ok("simulate", record, "--units", "m/s2", "--interface", "rigid", "--out", out)
    assert json.loads((out / "summary.json").read_text())["friction"]["exceeds_mu"] is None


# --------------------------------------------------------------------------
# sweep

def test_sweep_two_records_three_scales(fmu_path, tmp_path):
    records = tmp_path / "records"
    records.mkdir()
    shutil.copy(KATNP, records)
    shutil.copy(SMC_A, records)
    (records / "README.md").write_text("not a record: passed over\n")
    cases = tmp_path / "cases.toml"
    cases.write_text('[cases.tower]\npreset = "dharahara-I15-fm2"\n')
    out = tmp_path / "results.parquet"
    proc = ok("sweep", cases, "--records", records, "--scales", "0.5:1.5:0.5", "--stop-time", "30",
              "--workers", "2", "--out", out)
    assert re.search(r"6/6 \[.*run/s\]", proc.stderr), proc.stderr
    df = pd.read_parquet(out)
    assert len(df) == 6
    assert sorted(df["scale"]) == [0.5, 0.5, 1.0, 1.0, 1.5, 1.5]
    assert sorted(set(df["record"])) == ["0111a.smc", "KATNP_NS_standin.csv"]
    assert (df["error"] == "").all() and (df["case"] == "tower").all()
    assert (df["kn"] == 15e9).all() and (df["interface"] == "elastoPlastic").all()
    # the stand-in at scale 1 overturns this case (as `simulate` reports), in 30 s
    row = df[(df["record"] == "KATNP_NS_standin.csv") & (df["scale"] == 1.0)].iloc[0]
    assert bool(row["overturned"]) and 20 < row["t_overturn"] < 30
    assert df["t_end"].max() <= 30.0 + 1e-9


def test_sweep_defaults_lie_under_the_preset(fmu_path, tmp_path):
    """[defaults] interface = "rigid" must not turn a preset's tower rigid (issue 25): the
    row has the preset's interface and the peak `simulate --preset` gives; a case's own
    key still wins over its preset."""
    cases = tmp_path / "cases.toml"
    cases.write_text('[defaults]\ninterface = "rigid"\n'
                     '[cases.tower]\npreset = "dharahara-F170-fm5"\n'
                     '[cases.tower-rigid]\npreset = "dharahara-F170-fm5"\ninterface = "rigid"\n'
                     '[cases.block]\nshape = "solidRectangle"\n')
    out = tmp_path / "results.csv"
    ok("sweep", cases, "--records", KATNP, "--stop-time", "20", "--workers", "1", "--out", out)
    df = pd.read_csv(out).set_index("case")
    assert df.loc["tower", "interface"] == "elastoPlastic"
    assert df.loc["tower", "kn"] == 170e6 and df.loc["tower", "fm"] == 5e6
    assert df.loc["tower-rigid", "interface"] == "rigid"
    assert df.loc["block", "interface"] == "rigid"
    sim = tmp_path / "sim"
    ok("simulate", KATNP, "--preset", "dharahara-F170-fm5", "--stop-time", "20", "--out", sim)
    peak = json.loads((sim / "summary.json").read_text())["peak_theta_over_alpha"]
    assert df.loc["tower", "peak_theta_over_alpha"] == pytest.approx(peak, rel=1e-9)
    assert df.loc["tower-rigid", "peak_theta_over_alpha"] != pytest.approx(peak, rel=0.1)


def test_sweep_leaves_vertical_components_out(fmu_path, tmp_path):
    """The README's sweep folder holds 0111b.smc, whose header says `component= up`: it must not
    run as the horizontal ag (issue 25); the V2's UP channel neither."""
    cases = tmp_path / "cases.toml"
    cases.write_text('[cases.block]\nshape = "solidRectangle"\n')
    out = tmp_path / "r.csv"
    proc = ok("sweep", cases, "--records", SMC_A.parent, "--records", V2, "--stop-time", "2",
              "--workers", "1", "--out", out)
    assert sorted(pd.read_csv(out)["record"]) == sorted(["0111a.smc", "0111c.smc", f"{V2.name}[90]",
                                                         f"{V2.name}[0]"])
    assert "2 vertical component(s) left out" in proc.stderr and "0111b.smc" in proc.stderr
    line = fails("sweep", cases, "--records", V2, "--component", "UP", "--out", out)
    assert "vertical" in line and "av" in line and "90 or 0" in line


def test_simulate_refuses_a_vertical_component(fmu_path, tmp_path):
    v2a = DATA / "geonet-kaikoura-2016" / "20161113_110259_WTMC_20.V2A"
    line = fails("simulate", v2a, "--component", "Up", "--out", tmp_path)
    assert "[Up]" in line and "input av: simulate --vertical" in line and "N28W or S62W" in line
    line = fails("simulate", SMC_A.parent / "0111b.smc", "--out", tmp_path)
    assert "vertical" in line and "no horizontal component" in line
    assert not (tmp_path / "summary.json").exists()


def test_record_shows_each_components_orientation():
    v2a = DATA / "geonet-kaikoura-2016" / "20161113_110259_WTMC_20.V2A"
    lines = ok("record", v2a).stdout.splitlines()
    shown = [line.split()[1] for line in lines if line.strip().startswith("orientation")]
    assert shown == ["horizontal", "horizontal", "vertical"]  # N28W, S62W, Up


def test_component_on_a_csv_names_its_columns(fmu_path, tmp_path):
    line = fails("simulate", KATNP, "--component", "XYZ", "--out", tmp_path)
    assert "'XYZ'" in line and "'time_s', 'acc_m_s2'" in line


def test_sweep_help_states_the_precedence():
    text = " ".join(ok("sweep", "--help").stdout.split())
    assert "[defaults] first, its preset" in text and "own keys over both" in text


# --------------------------------------------------------------------------
# errors: one line on stderr, exit status 2, no traceback

def fails(*args, env=None):
    proc = rocking(*args, env=env)
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    return lines[0]


def test_error_missing_record(tmp_path):
    line = fails("simulate", tmp_path / "nope.V2", "--out", tmp_path)
    assert "nope.V2" in line and "no such" in line


def test_error_unreadable_record(tmp_path):
    bad = tmp_path / "bad.V2"
    bad.write_text("CORRECTED ACCELEROGRAM chan 1\nnothing else\n")
    line = fails("record", bad)
    assert "bad.V2" in line


def test_error_unknown_parameter_lists_close_matches(fmu_path, tmp_path):
    line = fails("simulate", "--Rout", "3", "--out", tmp_path)
    assert "Rout" in line and "Ro" in line.split("did you mean", 1)[1]


def test_error_bad_values(fmu_path, tmp_path):
    line = fails("simulate", "--kn", "stiff", "--out", tmp_path)
    assert "--kn" in line and "'stiff'" in line and "not a number" in line
    line = fails("simulate", "--shape", "hexagon", "--out", tmp_path)
    assert "hexagon" in line and "hollowCircle" in line
    # a value only the FMU can judge: its logger's message names the parameter
    line = fails("simulate", "--kn", "-5", "--out", tmp_path)
    assert "kn = -5" in line


def test_fmu_error_leads_with_the_parameter_as_typed(fmu_path, tmp_path):
    """It began with 190 characters of FMI wording and printed -1e9 as -1000000000 (issue 25)."""
    line = fails("simulate", "--interface", "elastic", "--kn", "-1e9", "--out", tmp_path)
    assert line.startswith("rocking simulate: error: kn = -1e9: must be"), line
    assert "fmi2ExitInitializationMode" in line and len(line) < 130


def test_python_api_suggests_close_names(fmu_path):
    from rocking import RockingFMU
    with RockingFMU(fmu_path) as fmu, pytest.raises(KeyError) as info:
        fmu.simulate({"knn": 1e9}, stop_time=0.1)
    assert "did you mean kn?" in str(info.value)


def test_record_options_the_messages_name(tmp_path):
    """The readers' messages suggest units= and fmt=; the CLI has --units and --fmt to match."""
    plain = tmp_path / "plain.csv"
    plain.write_text("time,acc\n0,0\n0.01,0.5\n0.02,-0.25\n")
    line = fails("record", plain)
    assert "--units" in line
    assert "PGA            0.5000 g" in ok("record", plain, "--units", "g").stdout
    odd = tmp_path / "odd.dat"
    odd.write_text("a record\nwith no header a reader knows\n")
    line = fails("record", odd)
    assert "--fmt" in line and "csv" in line
    line = fails("record", plain, "--units", "furlongs")
    assert line.startswith("rocking record: error: --units furlongs: unknown acceleration units")


def test_simulate_usage_names_params():
    usage = ok("simulate", "--help").stdout.split("\n\n", 1)[0]
    for option in ("--params FILE", "--units", "--fmt", "--tail", "--outputs"):
        assert option in usage


def test_error_unknown_preset(fmu_path, tmp_path):
    line = fails("simulate", "--preset", "dharahara-F171-fm5", "--out", tmp_path)
    assert "dharahara-F171-fm5" in line and "dharahara-F170-fm5" in line


def test_error_sweep_cases_file(fmu_path, tmp_path):
    cases = tmp_path / "cases.toml"
    cases.write_text("[cases.a]\nkn = \n")
    line = fails("sweep", cases, "--records", KATNP, "--out", tmp_path / "r.parquet")
    assert "cases.toml" in line and "TOML" in line
    cases.write_text('[cases.a]\npreset = "dharahara-rigid"\nknn = 1e9\n')
    line = fails("sweep", cases, "--records", KATNP, "--out", tmp_path / "r.parquet")
    assert "cases.a.knn" in line and "kn" in line.split("did you mean", 1)[1]


def test_error_missing_fmu_says_how_to_build_it(tmp_path):
    env = dict(os.environ, CARGO_TARGET_DIR=str(tmp_path / "empty-target"))
    line = fails("info", env=env)
    assert "cargo xtask fmu" in line


def test_corner_forwards_or_says_how_to_build(tmp_path):
    env = dict(os.environ, CARGO_TARGET_DIR=str(tmp_path / "empty-target"),
               PATH=os.pathsep.join([str(tmp_path / "bin"), "/usr/bin", "/bin"]))
    line = fails("corner", "--anything", env=env)
    assert "cargo build --release -p corner" in line
    (tmp_path / "bin").mkdir()
    fake = tmp_path / "bin" / "rocking-corner"
    fake.write_text('#!/bin/sh\necho "args: $*"\nexit 3\n')
    fake.chmod(0o755)
    proc = rocking("corner", "--shape", "hollowCircle", "a b", env=env)
    assert proc.returncode == 3 and proc.stdout == "args: --shape hollowCircle a b\n"


def test_simulate_takes_the_corner_body_file(fmu_path, tmp_path):
    """`rocking-corner --body FILE` then `rocking simulate --params FILE`: the body the
    limit analysis wrote is the one the FMU rocks. Checked against the file itself and
    closed forms of a lumped body on a solid rectangle: alpha = atan((B/2)/hG), and the
    rigid body stays at rest below the uplift acceleration g tan(alpha) (ag = 0 here)."""
    exe = REPO / "target" / "release" / "rocking-corner"
    if not exe.is_file():
        pytest.skip("target/release/rocking-corner not built (cargo build --release -p corner)")
    body = tmp_path / "body.json"
    subprocess.run([str(exe), "--alpha", "1.570796", "--body", str(body)], check=True,
                   capture_output=True, timeout=60)
    values = json.loads(body.read_text())
    ok("simulate", "--params", body, "--stop-time", "1", "--out", tmp_path / "run")
    csv, s = read_outputs(tmp_path / "run")
    assert s["parameters"] == values
    assert s["calculated"]["alpha"] == pytest.approx(math.atan(values["B"] / 2 / values["hG"]), rel=1e-12)
    assert s["calculated"]["weight"] == pytest.approx(values["W"], rel=1e-15)
    assert (csv["theta"] == 0).all() and not s["overturned"]


def test_error_params_file(fmu_path, tmp_path):
    bad = tmp_path / "body.json"
    bad.write_text('{"W": 500, ')
    line = fails("simulate", "--params", bad, "--out", tmp_path)
    assert "body.json" in line and "not JSON" in line
    bad.write_text('{"Wt": 500}')
    line = fails("simulate", "--params", bad, "--out", tmp_path)
    assert "body.json: Wt" in line and "W" in line.split("did you mean", 1)[1]


def test_summaries_are_strict_json():
    """NaN and infinities become null: JSON has neither, and strict readers refuse the `NaN` that
    json.dumps writes by default."""
    import math

    from rocking import jsonfile

    text = jsonfile.dumps({"a": math.nan, "b": [1.0, math.inf, np.float64(-math.inf)], "c": np.float32(0.5),
                           "d": {"e": np.array([2.0, math.nan])}})

    def refuse(name):
        raise ValueError(name)

    assert json.loads(text, parse_constant=refuse) == {"a": None, "b": [1.0, None, None], "c": 0.5,
                                                       "d": {"e": [2.0, None]}}
