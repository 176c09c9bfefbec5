"""Pulses (rocking.pulses) and overturning maps (rocking.maps, `rocking map`): docs/maps.md.

References are independent of the code under test: the pulses' peaks, zero crossings and
durations from their formulas worked by hand; the rigid block's least overturning amplitude
from scipy's solve_ivp of Housner's equation with the restitution rule and an overturning event
(brute force); similarity of two rigid blocks of one slenderness."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from rocking.pulses import RICKER_HALF_WIDTH, Pulse, pulse_velocity_change, read_shape

W = 5.0  # rad/s
A = 2.0  # m/s2
T = 2 * math.pi / W


def _roots(pulse, n=399998):
    """Sign changes of ag inside the pulse, located on a fine grid (s)."""
    t = np.linspace(0, pulse.duration, n)
    a = pulse.acceleration(t)
    k = np.flatnonzero(np.sign(a[:-1]) * np.sign(a[1:]) < 0)
    return t[k] - a[k] * (t[k + 1] - t[k]) / (a[k + 1] - a[k])


@pytest.mark.parametrize("shape, duration, peak_t, crossings", [
    ("one-sine", T, [T / 4], [T / 2]),
    ("one-cosine", T, [0.0, T], [T / 4, 3 * T / 4]),
    # symmetric Ricker: (1 - x^2) e^{-x^2/2}, x = w s / sqrt 2: zeros at s = +-sqrt(2)/w
    ("ricker", 4 * T, [2 * T], [2 * T - math.sqrt(2) / W, 2 * T + math.sqrt(2) / W]),
    # antisymmetric: x (3 - x^2) e^{-x^2/2}, x = w s / sqrt 3: zeros at x = 0, +-sqrt 3,
    # peak at x^2 = 3 - sqrt 6
    ("ricker-antisymmetric", 4 * T, [2 * T + math.sqrt(3) * math.sqrt(3 - math.sqrt(6)) / W],
     [2 * T - 3 / W, 2 * T, 2 * T + 3 / W]),
])
def test_pulse_peak_zero_crossings_duration(shape, duration, peak_t, crossings):
    p = Pulse(shape, A, W)
    assert p.duration == pytest.approx(duration, rel=1e-12)
    t = np.linspace(0, p.duration, 400001)
    a = p.acceleration(t)
    assert np.max(np.abs(a)) == pytest.approx(A, rel=1e-8)
    for tp in peak_t:
        assert abs(p.acceleration(tp)) == pytest.approx(A, rel=1e-12)
    assert _roots(p) == pytest.approx(crossings, abs=1e-6)
    assert p.acceleration(-1e-9) == 0 and p.acceleration(p.duration + 1e-9) == 0
    # zero net velocity: the integral of each of these over its duration is 0
    v = np.trapezoid(a, t)
    assert abs(v) < 1e-8 * A * T
    assert pulse_velocity_change(p) == 0.0
    if shape.startswith("ricker"):  # the window's cut is below 1e-8 of the peak
        assert RICKER_HALF_WIDTH == 2.0
        assert abs(p.acceleration(1e-12)) < 1e-8 * A


def test_ricker_spectrum_peaks_at_w_p():
    for shape in ("ricker", "ricker-antisymmetric"):
        p = Pulse(shape, A, W)
        t = np.linspace(0, p.duration, 2 ** 14)
        spec = np.abs(np.fft.rfft(p.acceleration(t), n=2 ** 18))
        w = 2 * math.pi * np.fft.rfftfreq(2 ** 18, t[1] - t[0])
        assert w[np.argmax(spec)] == pytest.approx(W, rel=2e-3)


def published_ricker(w_p, t_c, antisymmetric, beta=None):
    """The Ricker pulses as Vassiliou & Makris (2012) write them (T_p = 2 pi / w_p, s = t - t_c):
    symmetric (1 - 2 pi^2 s^2 / T_p^2) exp(-pi^2 s^2 / T_p^2); antisymmetric
    (1 / beta) (4 pi^2 s^2 / (3 T_p^2) - 3) (2 pi s / (sqrt(3) T_p)) exp(-2 pi^2 s^2 / (3 T_p^2)),
    beta (published: 1.38) making its peak 1."""
    T_p = 2 * math.pi / w_p

    def f(t):
        s = np.asarray(t, dtype=float) - t_c
        if not antisymmetric:
            return (1 - 2 * math.pi ** 2 * s ** 2 / T_p ** 2) * np.exp(-math.pi ** 2 * s ** 2 / T_p ** 2)
        return ((4 * math.pi ** 2 * s ** 2 / (3 * T_p ** 2) - 3) * (2 * math.pi * s / (math.sqrt(3) * T_p))
                * np.exp(-2 * math.pi ** 2 * s ** 2 / (3 * T_p ** 2)) / beta)
    return f


#: The antisymmetric wavelet's peak from d/dx [x (x^2 - 3) e^{-x^2/2}] = 0, x^2 = 3 - sqrt 6:
#: |x (x^2 - 3)| = sqrt 6 x there.
BETA = math.sqrt(6) * math.sqrt(3 - math.sqrt(6)) * math.exp(-(3 - math.sqrt(6)) / 2)


def test_ricker_wavelets_are_the_published_ones():
    """Both wavelets against Vassiliou & Makris (2012)'s formulas written out here, sign
    included; the antisymmetric one's peak (value, time) and side lobes in closed form."""
    assert round(BETA, 2) == 1.38  # the published normalisation, to its two decimals
    for shape, anti in (("ricker", False), ("ricker-antisymmetric", True)):
        p = Pulse(shape, A, W)
        t_c = p.duration / 2
        t = np.linspace(0, p.duration, 20001)
        ref = A * published_ricker(W, t_c, anti, BETA)(t)
        assert np.max(np.abs(p.acceleration(t) - ref)) < 1e-12 * A
        if anti:  # with the published beta = 1.38 as printed: the rounding's 1e-4
            rounded = A * published_ricker(W, t_c, anti, 1.38)(t)
            assert np.max(np.abs(p.acceleration(t) - rounded)) < 1.5e-4 * A
    p = Pulse("ricker-antisymmetric", A, W)
    t_c = p.duration / 2
    s_peak = math.sqrt(9 - 3 * math.sqrt(6)) / W  # x* sqrt(3) / w_p
    assert p.acceleration(t_c + s_peak) == pytest.approx(-A, rel=1e-12)  # the large lobes: -, then +
    assert p.acceleration(t_c - s_peak) == pytest.approx(A, rel=1e-12)
    s_side = math.sqrt(3 * (3 + math.sqrt(6))) / W  # x^2 = 3 + sqrt 6: the side lobes
    side = math.sqrt(6) * math.sqrt(3 + math.sqrt(6)) * math.exp(-(3 + math.sqrt(6)) / 2) / BETA
    assert p.acceleration(t_c - s_side) == pytest.approx(-A * side, rel=1e-12)
    assert p.acceleration(t_c + s_side) == pytest.approx(A * side, rel=1e-12)
    t = np.linspace(0, p.duration, 400001)
    assert t[np.argmax(p.acceleration(t))] == pytest.approx(t_c - s_peak, abs=p.duration / 4e5)
    assert t[np.argmin(p.acceleration(t))] == pytest.approx(t_c + s_peak, abs=p.duration / 4e5)


def test_rectangular_pulse_samples_keep_the_impulse():
    p = Pulse("rectangular", A, W)
    assert p.duration == pytest.approx(math.pi / W)
    assert pulse_velocity_change(p) == pytest.approx(A * math.pi / W)
    t, a = p.samples(400)
    assert np.trapezoid(a, t) == pytest.approx(A * math.pi / W, rel=1e-12)
    assert a[0] == A and a[-1] == 0.0 and np.allclose(np.diff(t), t[1])


def test_user_pulse_from_csv(tmp_path):
    f = tmp_path / "tri.csv"
    f.write_text("# a triangle\ntau,value\n0,0\n0.25,-2\n0.75,2\n1,0\n")
    tau, v = read_shape(f)
    assert list(v) == [0, -1, 1, 0]
    p = Pulse("user", A, W, user=(tau, v))
    assert p.duration == pytest.approx(T)
    assert p.acceleration(0.75 * T) == pytest.approx(A)
    assert _roots(p) == pytest.approx([T / 2], abs=1e-6)
    assert pulse_velocity_change(p) == pytest.approx(0.0, abs=1e-9)
    empty = tmp_path / "empty.csv"
    empty.write_text("tau,value\n0,0\n1,0\n")
    with pytest.raises(ValueError, match="empty.csv: no pulse"):
        read_shape(empty)


def test_bad_pulse_is_one_clear_error():
    with pytest.raises(ValueError, match="frequency"):
        Pulse("one-sine", A, 0.0)
    with pytest.raises(ValueError, match="not one of"):
        Pulse("sine", A, W)


# ---------------------------------------------------------------------------
# Maps of a rigid block against brute force, similarity, the command

from scipy.integrate import solve_ivp  # noqa: E402

from rocking.fmu import RockingFMU  # noqa: E402
from rocking.maps import MapSpec, boundaries, first_overturning, read_metadata, run_map  # noqa: E402

G = 9.81
RIGID = dict(shape="solidRectangle", B=0.4, L=1.0, massModel="prism", H=2.0, interface="rigid")
MAP_W = [1.5, 3.0, 5.0]  # w_p / p
MAP_A = list(np.linspace(1.0, 6.0, 11))  # a_p / (g tan alpha)
TOL = 1e-3


def housner_overturns(alpha, p, eta, a_p, w_p, tail=5.0, wave=None, end=None):
    """Housner's rigid block (slender or not: the exact nonlinear equation)
    theta'' = -p^2 [sin(s alpha - theta) + ag/g cos(s alpha - theta)], s = sgn(theta), under
    ag = a_p sin(w_p t) for 0 <= t <= T_p (or a_p wave(t) for 0 <= t <= end), by solve_ivp:
    uplift when |ag| > g tan alpha (to the side -sgn(ag)), omega <- eta omega at each return to
    theta = 0, overturned when |theta| = alpha. Past the pulse, a free block whose energy
    omega^2/2 + p^2 cos(alpha - |theta|) is below p^2 can no longer overturn."""
    T = 2 * math.pi / w_p if end is None else end
    wave = wave or (lambda t: np.sin(w_p * t))

    def ag(t):
        return a_p * float(wave(t)) if t <= T else 0.0

    t, th, om, s = 0.0, 0.0, 0.0, 0
    while t < T + tail:
        if s == 0:  # at rest: the first time |ag| exceeds g tan alpha
            if t >= T:
                return False
            ts = np.linspace(t, T, 20001)
            over = np.abs(a_p * wave(ts)) > G * math.tan(alpha)
            if not over.any():
                return False
            t = float(ts[int(np.argmax(over))])
            s, th, om = (-1 if ag(t) > 0 else 1), 0.0, 0.0
        if t >= T and om ** 2 / 2 + p ** 2 * math.cos(alpha - abs(th)) < p ** 2 * (1 - 1e-12):
            return False

        def f(tt, y, s=s):
            return [y[1], -p ** 2 * (math.sin(s * alpha - y[0]) + ag(tt) / G * math.cos(s * alpha - y[0]))]

        def back(tt, y, s=s):
            return s * y[0]
        back.terminal, back.direction = True, -1

        def topple(tt, y):
            return alpha - abs(y[0])
        topple.terminal = True
        stop = T if t < T else T + tail  # the pulse and the tail apart: no step over its end
        sol = solve_ivp(f, (t, stop), [th, om], events=(back, topple), rtol=1e-10, atol=1e-12, max_step=T / 50)
        if sol.t_events[1].size:
            return True
        t, (th, om) = float(sol.t[-1]), sol.y[:, -1]
        if sol.t_events[0].size:
            th, om = 0.0, eta * om
            s = 0 if abs(om) < 1e-9 * p else (1 if om > 0 else -1)
    return False


def reference_least_amplitude(alpha, p, eta, w, step=0.05, rel=1e-5, start=1.0, top=6.5, **pulse):
    """The least a_p / (g tan alpha) that overturns, by a scan from `start` in steps of `step`
    and a bisection of the first overturning step to `rel`; `pulse`: housner_overturns' wave, end."""
    gta = G * math.tan(alpha)
    lo = start
    while not housner_overturns(alpha, p, eta, (lo + step) * gta, w * p, **pulse):
        lo += step
        assert lo < top, f"no overturning below {top} at w/p = {w}"
    hi = lo + step
    while hi - lo > rel * hi:
        mid = 0.5 * (lo + hi)
        if housner_overturns(alpha, p, eta, mid * gta, w * p, **pulse):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@pytest.fixture(scope="module")
def fmu(fmu_path):
    with RockingFMU(fmu_path) as f:
        yield f


@pytest.fixture(scope="module")
def rigid_map(fmu):
    spec = MapSpec(params=RIGID, shape="one-sine", frequencies=MAP_W, amplitudes=MAP_A, tol=TOL, tail=5.0)
    runs = run_map(spec, fmu, workers=2)
    return spec, runs, boundaries(runs, spec)


def test_rigid_least_overturning_amplitude_against_housner(rigid_map):
    spec, runs, bounds = rigid_map
    assert not (runs["error"] != "").any()
    first = first_overturning(bounds)
    sc = spec.scales
    # p = sqrt(3 g / (4 R)) for a rectangle, alpha = atan(B/H): by hand, not from the FMU
    R = math.hypot(0.2, 1.0)
    assert sc["p"] == pytest.approx(math.sqrt(3 * G / (4 * R)), rel=1e-12)
    assert sc["alpha"] == pytest.approx(math.atan(0.2), rel=1e-12)
    eta = 1 - 1.5 * math.sin(sc["alpha"]) ** 2  # Housner's restitution of a rectangle
    lines = []
    for w in MAP_W:
        ref = reference_least_amplitude(sc["alpha"], sc["p"], eta, w)
        lines.append(f"w/p = {w}: map {first[w]:.5f}, solve_ivp {ref:.5f}, diff {(first[w] - ref) / ref:+.2e}")
        assert first[w] == pytest.approx(ref, rel=TOL), "\n".join(lines)
    print("\n".join(lines))


def test_antisymmetric_ricker_overturning_against_solve_ivp(fmu):
    """A rigid block under the antisymmetric Ricker pulse: the map's least overturning
    amplitude at w_p/p = 2 and 3 against solve_ivp of Housner's equation under the published
    formula (scan in steps of 0.1 from 1, bisected to 1e-5), and at w_p/p = 3 the safe window
    above the first interval: solve_ivp overturns just inside each end and not just outside."""
    spec = MapSpec(params=RIGID, shape="ricker-antisymmetric", frequencies=[2.0, 3.0],
                   amplitudes=list(np.linspace(1.0, 8.0, 15)), tol=TOL, tail=5.0)
    bounds = boundaries(run_map(spec, fmu, workers=2), spec)
    sc = spec.scales
    gta = sc["g_tan_alpha"]
    for w in (2.0, 3.0):
        w_p = w * sc["p"]
        T_p = 2 * math.pi / w_p
        pulse = dict(wave=published_ricker(w_p, 2 * T_p, True, BETA), end=4 * T_p)
        ref = reference_least_amplitude(sc["alpha"], sc["p"], sc["eta"], w, step=0.1, top=8.0, **pulse)
        iv = bounds[bounds["w"] == w].sort_values("start")
        print(f"antisymmetric Ricker, w_p/p = {w}: least overturning {iv['start'].iloc[0]:.5f} (map), "
              f"{ref:.5f} (solve_ivp)")
        assert iv["start"].iloc[0] == pytest.approx(ref, rel=2 * TOL)
        if w == 3.0:  # a safe window: measured 2.80 to 3.52
            assert len(iv) >= 2
            first, second = iv.iloc[0], iv.iloc[1]

            def over(a):
                return housner_overturns(sc["alpha"], sc["p"], sc["eta"], a * gta, w_p, **pulse)
            assert over(first["end"] * (1 - 2 * TOL)) and not over(first["end"] * (1 + 2 * TOL))
            assert not over(second["start"] * (1 - 2 * TOL)) and over(second["start"] * (1 + 2 * TOL))


def test_bisection_brackets_are_within_tol_and_agree_with_the_runs(rigid_map):
    spec, runs, bounds = rigid_map
    for b in bounds.itertuples():
        assert not b.below_grid
        assert b.a_from_hi - b.a_from_lo <= TOL * b.a_from_hi * (1 + 1e-9)
        col = runs[runs["w"] == b.w].set_index("a")
        assert not col.loc[b.a_from_lo, "overturned"] and col.loc[b.a_from_hi, "overturned"]
    over = runs[runs["overturned"]]
    assert ((over["overturned_in"] == "pulse") == (over["t_overturn"] <= over["pulse_end"])).all()
    assert set(over["overturned_in"]) == {"pulse", "tail"} and (runs[~runs["overturned"]]["overturned_in"] == "").all()


def test_similarity_two_rigid_blocks_one_slenderness(fmu, rigid_map):
    """A block 3 times as large (p / sqrt 3) has the same dimensionless map."""
    spec, runs, bounds = rigid_map
    big = dict(RIGID, B=1.2, H=6.0)
    spec3 = MapSpec(params=big, shape="one-sine", frequencies=MAP_W, amplitudes=MAP_A, tol=TOL, tail=5.0 * math.sqrt(3))
    runs3 = run_map(spec3, fmu, workers=2)
    bounds3 = boundaries(runs3, spec3)
    assert spec3.scales["p"] == pytest.approx(spec.scales["p"] / math.sqrt(3), rel=1e-12)
    g1, g3 = (r[r["phase"] == "grid"].sort_values(["w", "a"]) for r in (runs, runs3))
    assert list(g1["outcome"]) == list(g3["outcome"])
    assert len(bounds) == len(bounds3)
    for a, b in zip(bounds.itertuples(), bounds3.itertuples()):
        assert b.start == pytest.approx(a.start, rel=TOL)
        assert b.mode_at_start == a.mode_at_start


def _rocking(*args):
    return subprocess.run([sys.executable, "-m", "rocking", *args], capture_output=True, text=True, timeout=120)


@pytest.fixture
def cli(capsys, monkeypatch):
    """`rocking ARGS` in this process (rocking.cli.main.main, without a new interpreter's
    imports: 4 s a call on the loaded machine): an object with returncode, stdout, stderr."""
    import types
    import warnings

    from rocking.cli.main import main
    monkeypatch.setattr(warnings, "showwarning", warnings.showwarning)  # main sets its own

    def run(*args):
        capsys.readouterr()
        try:
            code = main(list(args))
        except SystemExit as exc:  # argparse's errors
            code = exc.code
        out, err = capsys.readouterr()
        return types.SimpleNamespace(returncode=code, stdout=out, stderr=err)
    return run


def test_map_help():
    r = _rocking("map", "--help")
    assert r.returncode == 0
    assert "--frequencies" in r.stdout and "thetaOv" in r.stdout


def test_map_cli_tiny_run_writes_parquet_with_metadata(tmp_path, fmu_path, cli):
    from importlib.metadata import version

    import pandas as pd
    out = tmp_path / "m"
    r = _rocking("map", "--fmu", fmu_path, "--shape", "solidRectangle", "--B", "0.4", "--H", "2",
                 "--interface", "rigid", "--frequencies", "2,4", "--amplitudes", "1:4:3", "--tail", "3",
                 "--workers", "1", "--quiet", "--out", str(out))
    assert r.returncode == 0, r.stderr
    runs = pd.read_parquet(out / "runs.parquet")
    assert set(runs["w"]) == {2.0, 4.0} and {1.0, 2.5, 4.0} <= set(runs["a"])
    assert {"overturned", "t_overturn", "impacts", "peak_theta_over_alpha", "outcome"} <= set(runs.columns)
    meta = read_metadata(out / "runs.parquet")
    assert meta["rocking_version"] == version("rocking")
    assert meta["params"]["B"] == 0.4 and meta["shape"] == "one-sine" and meta["dimensionless"]
    assert meta["frequencies"] == [2.0, 4.0] and meta["tol"] == 1e-3
    assert read_metadata(out / "boundaries.parquet") == meta
    assert (out / "map.png").stat().st_size > 0
    # the same map with one more frequency, to the same folder: the two finished columns are read
    r = cli("map", "--fmu", fmu_path, "--shape", "solidRectangle", "--B", "0.4", "--H", "2",
            "--interface", "rigid", "--frequencies", "2,3,4", "--amplitudes", "1:4:3", "--tail", "3",
            "--workers", "1", "--quiet", "--no-plot", "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert "resumed     2 of 3 frequency columns" in r.stdout, r.stdout
    again = pd.read_parquet(out / "runs.parquet")
    pd.testing.assert_frame_equal(again[again["w"] != 3.0].drop(columns="wall_s").reset_index(drop=True),
                                  runs.drop(columns="wall_s"))


def test_map_resumes_after_an_interruption(fmu, tmp_path):
    """A map stopped after two of its four columns (Ctrl-C in the progress callback) and run
    again with the same store runs only the two others, and its table is that of a map run
    whole; a map with another tol, tail, grid or body has other keys; a finished map run
    again runs nothing."""
    import dataclasses

    import pandas as pd

    from rocking.map_store import MapStore
    spec = MapSpec(params=RIGID, shape="one-sine", frequencies=[2.0, 3.0, 4.0, 5.0],
                   amplitudes=list(np.linspace(1.0, 6.0, 6)), tol=TOL, tail=5.0)
    whole = run_map(dataclasses.replace(spec), fmu, workers=1)
    store = MapStore(tmp_path / "parts")

    def interrupt(done, total, rows):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_map(dataclasses.replace(spec), fmu, workers=1, progress=interrupt, store=store)
    assert len(store.files()) == 2
    ran = []
    resumed = run_map(dataclasses.replace(spec), fmu, workers=1, store=store,
                      progress=lambda done, total, rows: ran.append(rows[0]["w"]))
    assert resumed.attrs["resumed"] == 2 and sorted(ran) == [4.0, 5.0]
    pd.testing.assert_frame_equal(resumed.drop(columns="wall_s"), whole.drop(columns="wall_s"))
    from rocking.maps import column_key
    for change in (dict(tol=2e-3), dict(tail=6.0), dict(amplitudes=[1.0, 2.0]), dict(params=dict(RIGID, H=2.1))):
        assert column_key(dataclasses.replace(spec, **change), 2.0, "s") != column_key(spec, 2.0, "s")
    assert column_key(spec, 2.0, "s") != column_key(spec, 2.0, "t")  # another FMU or code
    done = run_map(dataclasses.replace(spec), fmu, workers=2, store=store)
    assert done.attrs["resumed"] == 4 and done.attrs["resumed_rows"] == len(whole)


def test_map_on_dask_gives_the_process_pools_table(fmu, tmp_path):
    """The columns as tasks of the fragility runner's Dask code (rocking.fragility.cluster:
    its FMU plugin and submission window), on an in-process scheduler and worker (a process
    LocalCluster took 9 s to start here): the same table, each column in the store."""
    import pandas as pd
    from distributed import Client

    from rocking.map_store import MapStore
    spec = MapSpec(params=RIGID, shape="one-sine", frequencies=[2.0, 3.0, 4.0],
                   amplitudes=list(np.linspace(1.0, 6.0, 6)), tol=TOL, tail=5.0)
    pool = run_map(spec, fmu, workers=2)
    store = MapStore(tmp_path / "parts")
    with Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=None) as client:
        dask = run_map(spec, fmu, store=store, client=client)
    pd.testing.assert_frame_equal(dask.drop(columns="wall_s"), pool.drop(columns="wall_s"))
    assert len(store.files()) == 3


@pytest.mark.parametrize("args, message", [
    (["--frequencies", "1:2:0", "--amplitudes", "1,2"], "--frequencies 1:2:0: the grid is empty"),
    (["--frequencies", "0,2", "--amplitudes", "1,2"], "--frequencies 0,2: every value must be > 0"),
    (["--frequencies", "1,2", "--amplitudes", "1,2", "--pulse", "user"], "--pulse-file"),
])
def test_map_bad_input_is_one_line(tmp_path, args, message, cli):
    r = cli("map", *args, "--out", str(tmp_path / "x"))
    assert r.returncode == 2
    assert message in r.stderr and len(r.stderr.strip().splitlines()) == 1


def _rect_time(alpha, r, phi):
    """Time (in 1/p) for a rigid block to rotate from rest to phi under a constant ag = r g
    beyond uplift, by the first integral phi'^2 / 2 = p^2 F(phi),
    F = 2 sin(phi/2) [r cos(alpha - phi/2) - sin(alpha - phi/2)], with phi = u^2 (no singularity)."""
    from scipy.integrate import quad

    def integrand(u):
        if u == 0:
            return 2 / math.sqrt(2 * (r * math.cos(alpha) - math.sin(alpha)))
        F = 2 * math.sin(u * u / 2) * (r * math.cos(alpha - u * u / 2) - math.sin(alpha - u * u / 2))
        return 2 * u / math.sqrt(2 * F)
    return quad(integrand, 0, math.sqrt(phi), epsabs=1e-14, epsrel=1e-13, limit=200)[0]


def rectangular_least_amplitude(alpha, w_over_p):
    """The least a_p / (g tan alpha) of a rectangular pulse of duration pi / w_p that overturns
    a rigid block, exact: it overturns during the pulse (phi reaches alpha by t_d), or its free
    energy after it, phi'^2/2 + p^2 cos(alpha - phi), reaches p^2, which is
    r (sin alpha - sin(alpha - phi_d)) >= 1 - cos alpha at phi_d = phi(t_d)."""
    import warnings

    from scipy.integrate import IntegrationWarning
    from scipy.optimize import brentq
    td = math.pi / w_over_p

    def excess(A):
        r = A * math.tan(alpha)
        if _rect_time(alpha, r, alpha) <= td:
            return 1.0
        phid = brentq(lambda ph: _rect_time(alpha, r, ph) - td, 1e-14, alpha, xtol=1e-15, rtol=1e-14)
        return r * (math.sin(alpha) - math.sin(alpha - phid)) - (1 - math.cos(alpha))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)  # roundoff near u = 0, far below 1e-9
        hi = 1.0 + 1e-6
        while excess(hi) < 0:
            hi *= 1.5
        return brentq(excess, max(1 + 1e-12, hi / 1.5), hi, xtol=1e-14, rtol=1e-13)


def test_rectangular_pulse_least_amplitude_exact(fmu):
    """To 1e-6 relative against the first integral (the map bisected to 5e-7, 800 samples
    per period: the ramp of the step's linear interpolation errs by O(dt^2), 9e-7 at 400)."""
    spec = MapSpec(params=RIGID, shape="rectangular", frequencies=[2.0, 4.0, 8.0],
                   amplitudes=list(np.geomspace(1.01, 6.0, 8)), tol=5e-7, tail=5.0, per_period=800)
    first = first_overturning(boundaries(run_map(spec, fmu, workers=2), spec))
    lines = []
    for w in spec.frequencies:
        ref = rectangular_least_amplitude(spec.scales["alpha"], w)
        lines.append(f"w/p = {w}: map {first[w]:.8f}, first integral {ref:.8f}, diff {(first[w] - ref) / ref:+.2e}")
    print("\n".join(lines))
    for w in spec.frequencies:
        ref = rectangular_least_amplitude(spec.scales["alpha"], w)
        assert first[w] == pytest.approx(ref, rel=1e-6), "\n".join(lines)


def test_short_rectangular_pulse_tends_to_housners_impulse_limit(fmu):
    """A velocity impulse v = a_p t_d gives omega0 = v cos(alpha) p^2 / g; it overturns when
    omega0^2 / 2 >= p^2 (1 - cos alpha): a_p / (g tan alpha) >= (w_p/p) sqrt(2 (1 - cos alpha))
    / (pi sin alpha). The pulse's own duration t_d p = pi / (w_p/p) adds a gap of that order."""
    spec = MapSpec(params=RIGID, shape="rectangular", frequencies=[100.0, 200.0, 400.0],
                   amplitudes=list(np.geomspace(20, 200, 6)), tol=1e-5, tail=3.0, per_period=20)
    first = first_overturning(boundaries(run_map(spec, fmu, workers=2), spec))
    alpha = spec.scales["alpha"]
    gaps = []
    for w in spec.frequencies:
        limit = w * math.sqrt(2 * (1 - math.cos(alpha))) / (math.pi * math.sin(alpha))
        gaps.append((first[w] - limit) / limit)
        assert 0 < gaps[-1] < math.pi / w, (w, first[w], limit)
    print("gaps to the impulse limit:", ", ".join(f"{g:.2e}" for g in gaps))
    assert gaps[1] == pytest.approx(gaps[0] / 2, rel=0.05) and gaps[2] == pytest.approx(gaps[1] / 2, rel=0.05)


def linear_psi(lam, b, wt):
    """The linearised one-sine response psi = phi / alpha of a slender block (docs/maps.md,
    "Overturning without impact: the linearised boundary"): phi'' = p^2 (phi - alpha +
    ag / g), ag = a_p sin(w_p t), lam = a_p / (g alpha), b = w_p / p, from rest at the uplift
    w_p t_u = asin(1 / lam); wt = w_p t (>= w_p t_u), worked by hand."""
    wtu = math.asin(1 / lam)
    ps = (np.asarray(wt) - wtu) / b  # p (t - t_u)
    return (1 - lam / (1 + b * b) * np.sin(wt) - b * b / (1 + b * b) * np.cosh(ps)
            + b * math.sqrt(lam * lam - 1) / (1 + b * b) * np.sinh(ps))


def linear_reaches_alpha(lam, b):
    """Whether the linearised block reaches phi = alpha before it returns to phi = 0: during
    the pulse (the largest psi before its first zero, refined by a bounded search), or in the
    free motion after it, psi'' = p^2 (psi - 1), which reaches 1 when (psi - 1) + psi' / p >= 0
    at the pulse's end: e^{p (T_p - t_u)} (sqrt(lam^2 - 1) - b) >= lam."""
    from scipy.optimize import minimize_scalar
    wtu = math.asin(1 / lam)
    wt = np.linspace(wtu, 2 * math.pi, 4001)
    y = linear_psi(lam, b, wt)
    zero = np.flatnonzero(y[1:] <= 0)
    end = zero[0] + 1 if zero.size else len(wt) - 1
    k = int(np.argmax(y[:end + 1]))
    best = minimize_scalar(lambda x: -linear_psi(lam, b, x), bounds=(wt[max(k - 1, 0)], wt[min(k + 1, end)]),
                           method="bounded", options={"xatol": 1e-12})
    if max(-best.fun, y[k]) >= 1:
        return True
    if zero.size:
        return False
    return math.exp((2 * math.pi - wtu) / b) * (math.sqrt(lam * lam - 1) - b) >= lam


def linear_no_impact_boundary(b):
    """The least lam = a_p / (g alpha) at which the linearised block reaches alpha without an
    impact, bisected to 1e-11."""
    lo, hi = 1.0 + 1e-12, 2.0
    while not linear_reaches_alpha(hi, b):
        lo, hi = hi, hi * 1.5
    while hi - lo > 1e-11 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if linear_reaches_alpha(mid, b) else (mid, hi)
    return 0.5 * (lo + hi)


def test_linearised_one_sine_response_is_the_linear_equations_solution():
    """The closed form of linear_psi against solve_ivp of the linearised equation itself."""
    for lam, b in ((1.4, 1.0), (3.2, 3.0), (6.0, 5.0)):
        wtu = math.asin(1 / lam)
        sol = solve_ivp(lambda wt, y: [y[1], (y[0] - 1 + lam * math.sin(wt)) / (b * b)], (wtu, 2 * math.pi),
                        [0.0, 0.0], rtol=1e-12, atol=1e-14, dense_output=True)
        wt = np.linspace(wtu, 2 * math.pi, 50)
        assert np.max(np.abs(sol.sol(wt)[0] - linear_psi(lam, b, wt))) < 1e-8


def test_one_sine_no_impact_boundary_against_the_linearised_solution(fmu):
    """Slender blocks (alpha 0.2, 0.1, 0.05 rad): the map's least amplitude of overturning
    without impact (the onset of its no-impact region, bisected to 1e-5) against the
    linearised solution's (sin(alpha - phi) ~ alpha - phi, cos ~ 1; a_p / (g alpha) of the
    linear model against the map's a_p / (g tan alpha): both the uplift threshold). The gap
    is the linearisation's: it falls as alpha^2, the order of the terms it drops
    (measured: at w_p/p = 2, 3, 5: +8.9e-4, +2.24e-3, +4.34e-3 at alpha 0.2; about a quarter
    of that at each halving of alpha)."""
    from rocking.maps import NO_IMPACT, outcome
    ws = [2.0, 3.0, 5.0]
    linear = {w: linear_no_impact_boundary(w) for w in ws}
    gaps, lines = {}, []
    for alpha in (0.2, 0.1, 0.05):
        body = dict(RIGID, B=2.0 * math.tan(alpha), H=2.0)
        spec = MapSpec(params=body, shape="one-sine", frequencies=ws, amplitudes=[1.0, 2.5, 4.0, 5.5, 7.0],
                       tol=1e-5, tail=10.0)
        runs = run_map(spec, fmu, workers=1)
        assert spec.scales["alpha"] == pytest.approx(alpha, rel=1e-12)
        for w, col in runs.groupby("w"):
            recs = col.sort_values("a").to_dict("records")
            k = next(i for i, r in enumerate(recs) if outcome(r) == NO_IMPACT)
            assert k > 0 and all(outcome(r) == NO_IMPACT for r in recs[k:])  # one onset, mode 1 above it
            assert recs[k]["a"] - recs[k - 1]["a"] <= 1e-5 * recs[k]["a"] * (1 + 1e-9)
            onset = 0.5 * (recs[k - 1]["a"] + recs[k]["a"])
            gaps[alpha, w] = onset / linear[w] - 1
            lines.append(f"alpha {alpha} w/p {w}: map {onset:.6f}, linearised {linear[w]:.6f}, "
                         f"gap {gaps[alpha, w]:+.2e}")
    print("\n".join(lines))
    for w in ws:
        assert 0 < gaps[0.2, w] < 0.01, "\n".join(lines)
        # halving alpha cuts the gap to about 1/4 (alpha^2); 1/2 (a gap linear in alpha) fails
        for big, small in ((0.2, 0.1), (0.1, 0.05)):
            assert 0.18 < gaps[small, w] / gaps[big, w] < 0.36, "\n".join(lines)


def test_rigid_tail_skipped_by_energy_agrees_with_full_runs(fmu, rigid_map):
    """A rigid block's tail is not run when its free energy at the pulse's end is below p^2
    (it cannot overturn any more), and is run from the pulse's last state when it can: the
    same outcomes, impacts and overturning times of the overturned (to 1e-9 s), and peaks (to
    1e-5, sampled against the energy's) as runs through the whole tail, on the map's grid."""
    from rocking.maps import body_scales, run_one
    spec, runs, _ = rigid_map
    full = MapSpec(params=RIGID, shape="one-sine", frequencies=MAP_W, amplitudes=MAP_A, tol=TOL, tail=5.0,
                   cut_tail=False, scales=body_scales(fmu, RIGID))
    grid = runs[runs["phase"] == "grid"]
    assert grid["tail_skipped"].sum() >= 5
    assert (grid["overturned"].astype(bool) & (grid["t_overturn"] > grid["pulse_end"])).sum() >= 5  # tail runs
    for r in grid.itertuples():
        f = run_one(fmu, full, r.w, r.a)
        assert not f["tail_skipped"]
        assert f["overturned"] == r.overturned, (r.w, r.a)
        if r.overturned:
            assert f["impacts"] == r.impacts and f["t_overturn"] == pytest.approx(r.t_overturn, abs=1e-9)
        assert f["peak_theta_over_alpha"] == pytest.approx(r.peak_theta_over_alpha, abs=1e-5)


@pytest.mark.parametrize("bed, first_tail", [(dict(interface="elastic", kn=1e9), 1.0),
                                             (dict(interface="elastoPlastic", kn=1e9, fm=2e5), 0.02)],
                         ids=["elastic", "crushing"])
def test_flexible_tail_ends_when_the_body_cannot_overturn(fmu, bed, first_tail, monkeypatch):
    """On flexible and crushing beds (shiftingPivot) the tail ends at the first free turning
    point or rest: the same outcomes, overturning times, impacts when overturned and peaks as
    runs through the whole 20 s tail, on a 6 x 8 one-sine grid where some bodies overturn in
    the tail, with most safe runs cut short. With a first tail of 0.02 periods 2 pi / p (the
    crushing bed's case) the criterion is tested at many points of each tail (a tail cut at the
    pulse's end fails it)."""
    import dataclasses

    from rocking import maps
    from rocking.maps import body_scales, run_one
    monkeypatch.setattr(maps, "FIRST_TAIL", first_tail)
    body = dict(RIGID, **bed)
    spec = MapSpec(params=body, shape="one-sine", frequencies=[1], amplitudes=[1], tail=20.0,
                   scales=body_scales(fmu, body))
    full = dataclasses.replace(spec, cut_tail=False)
    cut = in_tail = 0
    for w in np.linspace(1.2, 8.0, 6):
        for a in np.linspace(0.6, 6.0, 8):
            c, f = run_one(fmu, spec, w, a), run_one(fmu, full, w, a)
            assert not c["error"] and not f["error"]
            assert f["tail_end"] == ("overturned" if f["overturned"] else "time")
            assert c["overturned"] == f["overturned"], (w, a)
            if f["overturned"]:
                in_tail += f["t_overturn"] > f["pulse_end"]
                assert c["tail_end"] == "overturned"
                assert c["t_overturn"] == pytest.approx(f["t_overturn"], abs=1e-9) and c["impacts"] == f["impacts"]
            else:
                assert c["tail_end"] == "cannot overturn"
                cut += c["tail_skipped"] and c["tail_run"] < 20.0
            assert c["peak_theta_over_alpha"] == pytest.approx(f["peak_theta_over_alpha"], rel=1e-9, abs=1e-12)
    assert in_tail >= 3 and cut >= 10, (in_tail, cut)


def test_costa_flexible_tail_runs_to_its_stated_length(fmu):
    """costa's free motion on a flexible bed may gain energy: its tail is not cut."""
    from rocking.maps import body_scales, run_one
    body = dict(RIGID, interface="elastic", kn=1e9, formulation="costa")
    spec = MapSpec(params=body, shape="one-sine", frequencies=[1], amplitudes=[1], tail=3.0,
                   scales=body_scales(fmu, body))
    assert not spec.scales["conservative"]
    row = run_one(fmu, spec, 4.0, 1.5)
    assert row["tail_end"] in ("overturned", "time") and not row["tail_skipped"]


def test_boundaries_against_a_dense_grid_on_random_bodies(fmu):
    """Random rigid bodies and pulses: the map (12 amplitudes, bisected to 1e-3) against 300
    runs per frequency. Every dense run's outcome (overturns or not) is what the map's
    intervals say, except next to a map boundary (within one dense step) or inside a window
    (of overturning or of safety) narrower than the map's grid step, which a grid cannot see."""
    from rocking.maps import run_one
    rng = np.random.default_rng(34)
    coarse, dense = np.geomspace(1.05, 20, 14), np.geomspace(1.05, 20, 300)
    coarse_step = coarse[1] / coarse[0] - 1
    report = []
    for shape in ("one-cosine", "ricker", "ricker-antisymmetric"):
        alpha, H = rng.uniform(0.12, 0.3), rng.uniform(1.0, 5.0)
        body = dict(RIGID, B=H * math.tan(alpha), H=H)
        ws = sorted(rng.uniform(0.8, 4.0, 2).round(3))
        spec = MapSpec(params=body, shape=shape, frequencies=ws, amplitudes=list(coarse), tol=TOL, tail=5.0)
        bounds = boundaries(run_map(spec, fmu, workers=2), spec)
        for w in ws:
            iv = bounds[bounds["w"] == w]
            edges = np.concatenate([iv["start"], iv["end"][np.isfinite(iv["end"])]])
            said = np.array([((iv["start"] <= a) & (a <= iv["end"])).any() for a in dense])
            got = np.array([bool(run_one(fmu, spec, w, a)["overturned"]) for a in dense])
            bad = np.flatnonzero(said != got)
            # runs of consecutive disagreements, each explained or not
            for group in np.split(bad, np.flatnonzero(np.diff(bad) > 1) + 1) if bad.size else []:
                lo, hi = dense[max(group[0] - 1, 0)], dense[min(group[-1] + 1, len(dense) - 1)]
                near_edge = len(group) <= 2 and any(lo <= e <= hi for e in edges)
                # an island of the dense runs (a window) the grid stepped over
                inside = set(got[group])
                island = (len(inside) == 1 and 0 < group[0] and group[-1] + 1 < len(dense)
                          and got[group[0] - 1] != got[group[0]] and got[group[-1] + 1] != got[group[0]])
                narrow = island and hi / lo - 1 < coarse_step
                assert near_edge or narrow, (shape, alpha, H, w, dense[group])
            report.append(f"{shape} alpha {alpha:.3f} H {H:.2f} w/p {w}: {len(iv)} interval(s), "
                          f"{bad.size} of 300 dense runs differ (next to a boundary or in a window "
                          f"narrower than the grid's step)")
    print("\n".join(report))


def test_similarity_on_flexible_beds_elastic_keeps_it_crushing_breaks_it(fmu):
    """Scaled 3 times with the same bed, a no-tension Winkler bed keeps the dimensionless map
    (stress and closure grow as the size, so the uplift rotation does not change, and the
    bed's frequency squared falls as p^2 does); a crushing bed of the same strength fm does
    not (the stress grows, fm does not): measured, at w_p/p = 5, -44 %."""
    first = {}
    for interface, extra in (("elastic", {}), ("elastoPlastic", {"fm": 2e5})):
        for scale in (1, 3):
            body = dict(RIGID, B=0.4 * scale, H=2.0 * scale, interface=interface, kn=1e9, **extra)
            spec = MapSpec(params=body, shape="one-sine", frequencies=[3.0, 5.0], amplitudes=MAP_A, tol=TOL,
                           tail=5.0 * math.sqrt(scale), dimensionless=True)
            first[interface, scale] = first_overturning(boundaries(run_map(spec, fmu, workers=2), spec))
    for w in (3.0, 5.0):
        assert first["elastic", 3][w] == pytest.approx(first["elastic", 1][w], rel=TOL)
    change = first["elastoPlastic", 3][5.0] / first["elastoPlastic", 1][5.0] - 1
    print(f"crushing bed fm = 0.2 MPa, 3 times larger: least overturning a_p/(g tan alpha) at w_p/p = 5 "
          f"{first['elastoPlastic', 1][5.0]:.4f} -> {first['elastoPlastic', 3][5.0]:.4f} ({change:+.1%})")
    assert change < -0.2


def test_map_cli_user_pulse_and_a_file_without_a_pulse(tmp_path, fmu_path, cli):
    import pandas as pd
    good, empty = tmp_path / "half-sine.csv", tmp_path / "flat.csv"
    tau = np.linspace(0, 0.5, 51)
    good.write_text("tau,value\n" + "".join(f"{t},{math.sin(2 * math.pi * t)}\n" for t in tau))
    empty.write_text("tau,value\n0,0\n0.5,0\n")
    body = ["--fmu", fmu_path, "--shape", "solidRectangle", "--B", "0.4", "--H", "2", "--interface", "rigid",
            "--frequencies", "3", "--amplitudes", "1,3", "--workers", "1", "--quiet", "--no-plot"]
    r = cli("map", *body, "--pulse", "user", "--pulse-file", str(good), "--out", str(tmp_path / "u"))
    assert r.returncode == 0, r.stderr
    runs = pd.read_parquet(tmp_path / "u" / "runs.parquet")
    # the pulse lasts tau_end T_p = 0.5 T_p
    assert runs["pulse_end"].iloc[0] == pytest.approx(0.5 * 2 * math.pi / runs["w_p"].iloc[0])
    assert read_metadata(tmp_path / "u" / "runs.parquet")["user"][0][-1] == 0.5
    r = cli("map", *body, "--pulse", "user", "--pulse-file", str(empty), "--out", str(tmp_path / "e"))
    assert r.returncode == 2 and "flat.csv: no pulse" in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_map_cli_beside_maps_variants_of_the_body(tmp_path, fmu_path, cli):
    """--beside: the body with parameters changed, its rows labelled, its parameters (and those
    the body's interface left out, here kn) in the metadata, one panel each."""
    import pandas as pd
    out = tmp_path / "b"
    r = cli("map", "--fmu", fmu_path, "--shape", "solidRectangle", "--B", "0.4", "--H", "2",
            "--interface", "rigid", "--kn", "1e9", "--dimensionless", "--beside", "interface=elastic",
            "--frequencies", "2,4", "--amplitudes", "1:4:3", "--tail", "3", "--workers", "1", "--quiet",
            "--out", str(out))
    assert r.returncode == 0, r.stderr
    runs = pd.read_parquet(out / "runs.parquet")
    assert set(runs["body"]) == {"body", "interface=elastic"}
    meta = read_metadata(out / "runs.parquet")
    assert meta["bodies"]["interface=elastic"]["params"]["kn"] == 1e9
    assert "kn" not in meta["bodies"]["body"]["params"]
    assert meta["bodies"]["interface=elastic"]["scales"]["thetaOv"] < meta["bodies"]["body"]["scales"]["thetaOv"]
    bad = cli("map", "--fmu", fmu_path, "--beside", "interface", "--frequencies", "2", "--amplitudes", "1",
              "--out", str(tmp_path / "x"))
    assert bad.returncode == 2 and "--beside 'interface': expected NAME=VALUE" in bad.stderr
