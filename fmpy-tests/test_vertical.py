"""The vertical component from the Python side (issue 20): record sets and their vertical,
`rocking simulate --vertical`, one-sided rocking from the command line, the corner body,
and av in the studies.

References, none of them the code under test:
- the shipped files' own headers (data/ground-motions/README.md) for which component is
  vertical;
- Housner's rigid free rocking under g' = g + av: the quarter-cycle time T(A) of
  docs/model.md §7.3 by quadrature, and a second run with g set to g + av;
- the record's own samples: the first time the scaled av reaches -g (liftOff);
- N = W + m av for the least apparent weight;
- etaHousner = 1 - 2 m b²/IO computed from the body file's W, hG, Ic, B.
"""

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.integrate import quad

from rocking import groundmotion as gm
from rocking.fmu import RockingFMU

REPO = Path(__file__).resolve().parents[1]
DATA = REPO / "data" / "ground-motions"
KAIKOURA = DATA / "geonet-kaikoura-2016" / "20161113_110259_WTMC_20.V2A"
KATNP = DATA / "katnp-standin" / "KATNP_NS_standin.csv"
G = 9.80665

# Which component of each shipped set is vertical, as the files' headers say (README table).
SHIPPED_VERTICAL = {
    "csmip-coalinga-1983/ce36456p_CE36456.V2": ("ce36456p_CE36456.V2", "UP"),
    "geonet-kaikoura-2016/20161113_110259_WTMC_20.V2A": ("20161113_110259_WTMC_20.V2A", "Up"),
    "geonet-darfield-2010/3366146_DFHS_HN_20.000": ("3366146_DFHS_HN_20.ver", "ver"),
    "geonet-darfield-2010/3366146_DFHS_HN_20.090": ("3366146_DFHS_HN_20.ver", "ver"),
    "usgs-lomaprieta-1989/0111a.smc": ("0111b.smc", "up"),
    "usgs-lomaprieta-1989/0111c.smc": ("0111b.smc", "up"),
}


def rocking(*args):
    exe = Path(sys.executable).parent / "rocking"
    return subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def fmu(fmu_path):
    with RockingFMU(fmu_path) as f:
        yield f


# -- record sets ---------------------------------------------------------------------------

@pytest.mark.parametrize("name", sorted(SHIPPED_VERTICAL))
def test_the_auto_found_vertical_is_the_one_the_header_calls_vertical(name):
    path = DATA / name
    horizontal = next(r for r in gm.read_all(path) if not r.vertical)
    found = gm.vertical_of(horizontal)
    assert (Path(found.source).name, found.component) == SHIPPED_VERTICAL[name]
    assert found.orientation == gm.VERTICAL
    assert len(gm.components(path)) == 3


def test_a_set_without_vertical_has_none():
    assert gm.vertical_of(gm.read(KATNP)) is None


def _at2(path, title, values):
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", title, "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS=  {len(values)}, DT=   .0100 SEC", " ".join(f"{v:.6f}" for v in values)]
    path.write_text("\n".join(lines) + "\n")


def test_peer_at2_triplet_is_one_set_and_a_stranger_is_not(tmp_path):
    _at2(tmp_path / "RSN6_ELC180.AT2", "IMPERIAL VALLEY 05/19/40, EL CENTRO ARRAY #9, 180", [0.1, -0.2, 0.3])
    _at2(tmp_path / "RSN6_ELC270.AT2", "IMPERIAL VALLEY 05/19/40, EL CENTRO ARRAY #9, 270", [0.2, 0.1, 0.0])
    _at2(tmp_path / "RSN6_ELCUP.AT2", "IMPERIAL VALLEY 05/19/40, EL CENTRO ARRAY #9, UP", [0.05, 0.0, -0.05])
    _at2(tmp_path / "RSN9_OTHER.AT2", "OTHER EVENT 01/01/50, SOME STATION, UP", [0.0, 0.0, 0.0])
    rec = gm.read(tmp_path / "RSN6_ELC180.AT2")
    labels = sorted(r.component for r in gm.components(rec.source))
    assert labels == ["180", "270", "UP"]
    up = gm.vertical_of(rec)
    assert Path(up.source).name == "RSN6_ELCUP.AT2"
    np.testing.assert_allclose(up.acc, np.array([0.05, 0.0, -0.05]) * G, rtol=1e-15)


# -- the FMU with av -----------------------------------------------------------------------

def _quarter_time(a, alpha, r0, io, w):
    """Housner's T(A): time from rest at A to theta = 0, by quadrature of the energy integral."""
    v = lambda phi: w * r0 * (math.cos(alpha - phi) - math.cos(alpha))  # noqa: E731
    slope = w * r0 * math.sin(alpha - a)  # V'(A): the integrand's limit at phi = A

    def f(phi):
        drop = v(a) - v(phi)
        return math.sqrt(io / (2 * (drop / (a - phi) if phi < a and drop > 0 else slope)))
    return quad(f, 0.0, a, weight="alg", wvar=(0.0, -0.5), epsabs=1e-14, epsrel=1e-13)[0]


def _crossings(res):
    """Times theta reaches 0: a Newton step from the last row before each crossing (the rows
    after it are past the impact, where omega jumps), error about theta'' dt² / (2 omega)."""
    t, th, om = res["time"], res["theta"], res["omega"]
    k = np.flatnonzero(np.sign(th[:-1]) * np.sign(th[1:]) < 0)
    return t[k] - th[k] / om[k]


@pytest.mark.parametrize("av", [-3.0, 2.5])
def test_constant_av_is_rigid_rocking_under_g_plus_av(fmu, av):
    body = {"shape": "solidRectangle", "B": 0.4, "H": 2.0, "interface": "rigid", "theta": 0.1, "omega": 0.0,
            "g": 9.81}
    t = np.arange(0, 3.0001, 0.01)
    run = fmu.simulate(body, av=(t, np.full(t.size, av)), stop_time=3.0, output_interval=1e-4,
                       outputs=("theta", "omega", "apparentWeight"), rtol=1e-12)
    twin = fmu.simulate({**body, "g": 9.81 + av}, stop_time=3.0, output_interval=1e-4, outputs=("theta", "omega"),
                        rtol=1e-12)
    c = run.calculated
    m = c["mass"]
    w_prime = m * (9.81 + av)
    t1 = _quarter_time(0.1, c["alpha"], c["R0"], c["IO"], w_prime)
    got, twin_t = _crossings(run.result), _crossings(twin.result)
    assert got[0] == pytest.approx(t1, abs=1e-7)  # the Newton step from rows 1e-4 s apart
    np.testing.assert_allclose(got, twin_t, atol=1e-9)
    np.testing.assert_allclose(run.result["apparentWeight"], w_prime, rtol=1e-12)


def test_python_loop_with_zero_av_equals_the_native_loop_bit_for_bit(fmu):
    rec = gm.read(DATA / "usgs-lomaprieta-1989" / "0111a.smc")
    body = {"shape": "solidRectangle", "B": 0.3, "H": 1.5, "interface": "elastic", "kn": 1e9}
    native = fmu.simulate(body, record=rec, scale=8.0, outputs=("theta", "omega"), loop="native")
    python = fmu.simulate(body, record=rec, scale=8.0, outputs=("theta", "omega"),
                          av=(rec.time, np.zeros(rec.npts)), loop="python")
    assert np.array_equal(native.result["theta"], python.result["theta"])
    assert np.array_equal(native.result["omega"], python.result["omega"])


LOOP_OUTPUTS = ("theta", "omega", "af", "contactLength", "MR", "Fx", "Fz", "apparentWeight", "regime",
                "impacts", "zeroCrossings", "overturned")


def _same_runs(python, native):
    """Every output bit for bit, and the same end, overturning, terminal condition and messages."""
    assert python.result.dtype == native.result.dtype
    for name in python.result.dtype.names:
        assert python.result[name].tobytes() == native.result[name].tobytes(), name
    for f in ("overturned", "t_end", "impacts", "zero_crossings", "terminal", "messages"):
        assert getattr(python, f) == getattr(native, f), f


@pytest.mark.parametrize("interface", ["rigid", "elastic", "elastoPlastic"])
def test_native_loop_with_av_equals_the_python_loop_bit_for_bit(fmu, interface):
    """The native loop sets av and dav/dt as the Python loop (the reference) does: the same
    FMI calls, so the same outputs bit for bit, under the Kaikoura record's own vertical
    (a varying av, scaled with ag)."""
    rec = next(r for r in gm.read_all(KAIKOURA) if r.component == "N28W")
    up = next(r for r in gm.read_all(KAIKOURA) if r.vertical)
    body = {"shape": "solidRectangle", "B": 0.4, "H": 2.0, "interface": interface, "kn": 1e9, "fm": 2e6}
    runs = [fmu.simulate(body, record=rec, vertical=up, scale=0.5, outputs=LOOP_OUTPUTS, loop=loop)
            for loop in ("python", "native")]
    _same_runs(*runs)
    assert runs[1].result["apparentWeight"].std() > 0  # av did vary
    assert len(runs[1].result) > 1000


def test_native_loop_ends_at_liftoff_as_the_python_loop(fmu):
    """A terminal condition under av (liftOff): both loops stop at fmi2LastSuccessfulTime
    with the same rows and the same message."""
    rec = next(r for r in gm.read_all(KAIKOURA) if r.component == "N28W")
    up = next(r for r in gm.read_all(KAIKOURA) if r.vertical)
    body = {"shape": "solidRectangle", "B": 3.0, "H": 4.0, "interface": "rigid", "g": G}
    runs = [fmu.simulate(body, record=rec, vertical=up, outputs=LOOP_OUTPUTS, loop=loop)
            for loop in ("python", "native")]
    _same_runs(*runs)
    assert runs[1].terminal.startswith("liftOff")


def _first_below(time, acc, level):
    """First time the linear interpolation of (time, acc) reaches `level` from above."""
    k = int(np.flatnonzero(acc <= level)[0])
    return time[k - 1] + (level - acc[k - 1]) / (acc[k] - acc[k - 1]) * (time[k] - time[k - 1])


def test_liftoff_ends_the_run_where_the_scaled_av_reaches_minus_g(tmp_path):
    up = next(r for r in gm.read_all(KAIKOURA) if r.vertical)
    scale = 1.0
    out = tmp_path / "run"
    proc = rocking("simulate", KAIKOURA, "--component", "N28W", "--vertical", "auto", "--scale", scale,
                   "--shape", "solidRectangle", "--B", 3.0, "--H", 4.0, "--interface", "rigid", "--g", G,
                   "--out", out)
    assert proc.returncode == 0, proc.stderr
    s = json.loads((out / "summary.json").read_text())
    assert s["vertical"]["component"] == "Up"
    assert s["vertical"]["pga_g"] == pytest.approx(up.pga_g, rel=1e-12)
    assert s["terminal"].startswith("liftOff") and "av = " in s["terminal"]
    t_star = float(s["terminal"].split("t = ")[1].split(":")[0])
    assert t_star == pytest.approx(_first_below(up.time, scale * up.acc, -G), abs=1e-9)
    assert not s["overturned"]
    table = pd.read_csv(out / "timehistory.csv")
    assert "av" in table.columns
    expected = 1 + (table["av"].to_numpy()).min() / G  # N / W = 1 + av / g at the rows
    assert s["vertical"]["min_apparent_weight_over_W"] == pytest.approx(expected, abs=1e-9)
    assert "OUT OF THE MODEL'S RANGE" in proc.stdout


def test_vertical_auto_without_a_vertical_says_so_in_one_line(tmp_path):
    proc = rocking("simulate", KATNP, "--vertical", "auto", "--preset", "dharahara-rigid", "--out", tmp_path)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "no vertical component" in lines[0] and "Traceback" not in proc.stderr


def test_vertical_given_as_file_component(tmp_path):
    darfield = DATA / "geonet-darfield-2010"
    out = tmp_path / "run"
    proc = rocking("simulate", darfield / "3366146_DFHS_HN_20.090", "--vertical", darfield / "3366146_DFHS_HN_20.ver",
                   "--scale", 0.5, "--preset", "dharahara-rigid", "--stop-time", 2.0, "--out", out)
    assert proc.returncode == 0, proc.stderr
    s = json.loads((out / "summary.json").read_text())
    assert s["vertical"]["component"] == "ver" and s["vertical"]["scale"] == 0.5
    words = (darfield / "3366146_DFHS_HN_20.ver").read_text().split("\n", 2)[2].split()
    values = np.array(words, dtype=float)  # in g, after the station and the "npts dt" lines
    table = pd.read_csv(out / "timehistory.csv")
    n = len(table)
    np.testing.assert_allclose(table["av"].to_numpy(), 0.5 * G * values[:n], rtol=1e-12, atol=1e-15)
    horizontal = rocking("simulate", darfield / "3366146_DFHS_HN_20.090", "--vertical",
                         darfield / "3366146_DFHS_HN_20.000", "--out", tmp_path / "h")
    assert horizontal.returncode == 2 and "horizontal component" in horizontal.stderr


# -- one-sided rocking from the command line -----------------------------------------------

@pytest.mark.parametrize("side", [1, -1])
def test_one_sided_options_keep_theta_on_its_side(tmp_path, side):
    out = tmp_path / "run"
    proc = rocking("simulate", DATA / "usgs-lomaprieta-1989" / "0111a.smc", "--scale", 12,
                   "--shape", "solidRectangle", "--B", 0.2, "--H", 1.0, "--interface", "rigid",
                   "--restraint", "oneSided", "--side", side, "--eRestraint", 0.6, "--out", out)
    assert proc.returncode == 0, proc.stderr
    s = json.loads((out / "summary.json").read_text())
    assert s["parameters"]["restraint"] in ("oneSided", 2) and s["parameters"]["side"] == side
    theta = pd.read_csv(out / "timehistory.csv")["theta"].to_numpy()
    assert (side * theta >= -1e-12).all() and np.abs(theta).max() > 0.01  # it rocked, on one side only


def test_one_sided_start_on_the_wrong_side_is_refused_in_one_line(tmp_path):
    proc = rocking("simulate", "--shape", "solidRectangle", "--B", 0.2, "--H", 1.0, "--interface", "rigid",
                   "--restraint", "oneSided", "--side", 1, "--theta", -0.05, "--out", tmp_path)
    assert proc.returncode == 2 and "theta" in proc.stderr and "Traceback" not in proc.stderr


def test_corner_body_is_one_sided_with_its_housner_eta(tmp_path):
    body_path = tmp_path / "body.json"
    proc = rocking("corner", "--alpha", "1.570796", "--body", body_path)
    assert proc.returncode == 0, proc.stderr
    body = json.loads(body_path.read_text())
    assert body["restraint"] == "oneSided" and body["side"] == 1
    m = body["W"] / body["g"]
    b = body["B"] / 2
    io = body["Ic"] + m * (b * b + body["hG"] ** 2)
    assert body["eRestraint"] == pytest.approx(1 - 2 * m * b * b / io, rel=1e-12)


# -- studies -------------------------------------------------------------------------------

def test_sweep_vertical_case_runs_with_the_records_vertical(fmu):
    from rocking.parametric import run_grid
    rec = gm.read(DATA / "usgs-lomaprieta-1989" / "0111a.smc")
    body = {"shape": "solidRectangle", "B": 0.2, "H": 1.0, "interface": "rigid"}
    df = run_grid({"h": body, "hv": {**body, "vertical": True}}, records={"a": gm.with_vertical(rec),
                  "csv": gm.read(KATNP)}, scales=[6.0], workers=1, fmu=fmu, stop_time=6.0)
    direct = fmu.simulate(body, record=rec, vertical=gm.vertical_of(rec), scale=6.0, stop_time=6.0)
    row = df[(df.case == "hv") & (df.record == "a")].iloc[0]
    assert row["peak_theta_over_alpha"] == direct.peak_theta_over_alpha
    bare = df[(df.case == "h") & (df.record == "a")].iloc[0]
    assert bare["peak_theta_over_alpha"] == fmu.simulate(body, record=rec, scale=6.0,
                                                         stop_time=6.0).peak_theta_over_alpha
    assert "no vertical component" in df[(df.case == "hv") & (df.record == "csv")].iloc[0]["error"]


def _cosim_case(tmp_path, vertical):
    case = tmp_path / "case.toml"
    case.write_text(f"""
[frame]
masses = [1e4, 1e4]
stiffnesses = [4e6, 4e6]
[block]
interface = "rigid"
[ground]
record = "{DATA / 'csmip-coalinga-1983' / 'ce36456p_CE36456.V2'}"
scale = 0.05
vertical = {vertical}
[coupling]
floor = 2
step = 0.01
stop_time = 4.0
""")
    return case


def test_cosim_block_gets_the_grounds_av(tmp_path):
    """A rigid block at rest on the roof (ag far below its uplift level): its support force
    is Fz = m (g + av(t)) with av the record's vertical, scaled alike, at every step."""
    out = tmp_path / "out"
    proc = rocking("cosim", _cosim_case(tmp_path, "true"), "--out", out)
    assert proc.returncode == 0, proc.stderr
    s = json.loads((out / "summary.json").read_text())
    assert s["ground"]["vertical"]["component"] == "UP"
    up = next(r for r in gm.read_all(DATA / "csmip-coalinga-1983" / "ce36456p_CE36456.V2") if r.vertical)
    table = pd.read_csv(out / "timehistory.csv")
    m = 2250.0  # the FMU's default prism: 0.5 x 1 x 2.5 m at 1800 kg/m3
    av = 0.05 * np.interp(table["time"], up.time, up.acc, right=0.0)
    assert np.abs(table["theta"]).max() == 0.0
    np.testing.assert_allclose(table["Fz"], m * (9.81 + av), rtol=1e-12)


def test_cosim_vertical_on_a_sine_is_refused_in_one_line(tmp_path):
    case = tmp_path / "sine.toml"
    case.write_text("[frame]\nmasses = [1e4]\nstiffnesses = [4e6]\n[ground]\namplitude = 1.0\nfrequency = 2.0\n"
                    "vertical = true\n[coupling]\nfloor = 1\n")
    proc = rocking("cosim", case, "--out", tmp_path / "o")
    assert proc.returncode == 2 and "vertical" in proc.stderr and len(proc.stderr.strip().splitlines()) == 1


def test_msa_study_key_vertical_takes_each_records_vertical(tmp_path):
    study = tmp_path / "study.toml"
    body = '[bodies.block]\nshape = "solidRectangle"\nB = 0.3\nH = 1.5\ninterface = "rigid"\n'
    study.write_text(f'records = ["{DATA / "usgs-lomaprieta-1989" / "0111a.smc"}"]\nstripes = "0.2"\nim = "PGA"\n'
                     f'vertical = true\ntail = 0.5\n{body}')
    proc = rocking("msa", study, "--out", tmp_path / "o", "--workers", 1, "--boot", 0)
    assert proc.returncode == 0, proc.stderr
    s = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert list(s["vertical"].values()) == [f"{DATA / 'usgs-lomaprieta-1989' / '0111b.smc'} [up]"]
    study.write_text(f'records = ["{KATNP}"]\nstripes = "0.2"\nvertical = true\n{body}')
    proc = rocking("msa", study, "--out", tmp_path / "k", "--workers", 1, "--boot", 0)
    assert proc.returncode == 2 and "no vertical component" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1


def test_restraint_items_use_only_eRestraint(fmu_path):
    """Regression: restraint's description says "sgn(theta)"; read as the items' parameter list
    it made theta (the initial condition) 'unused' whenever restraint = none."""
    from rocking.cli.common import parameters_of_items
    with RockingFMU(fmu_path) as f:
        uses = parameters_of_items(f)["restraint"]
    assert uses == {"none": set(), "oneSided": {"eRestraint"}}
