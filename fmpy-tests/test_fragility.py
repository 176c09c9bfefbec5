"""Fragility studies (rocking.fragility, `rocking ida`): intensity measures against the
closed-form oscillator, hunt-and-fill against an oracle and a brute-force grid, the
lognormal fits against synthetic data of known median and beta, and the Dask sweep on a
two-worker LocalCluster: a worker killed mid-sweep, resume after an interruption, the
command end to end.
"""

import json
import math
import os
import signal
from pathlib import Path

import numpy as np
import pytest

from distributed import Future

from rocking import groundmotion as gm
from rocking.fragility import cluster, fit, hunt, intensity, runner
from rocking.fragility.store import ResultStore
from rocking.fragility.study import Study
from rocking.fragility.suite import is_vertical, load_suite

REPO = Path(__file__).resolve().parents[1]
G = 9.80665


# ---------------------------------------------------------------------------
# Intensity measures

def _damped(t, w, zeta):
    wd = w * math.sqrt(1 - zeta * zeta)
    return np.exp(-zeta * w * t), wd


def test_oscillator_exact_for_constant_and_ramp_input():
    """u'' + 2 zeta w u' + w² u = -ag from rest: closed forms for ag = a0 and ag = r t."""
    period, zeta, dt = 0.7, 0.05, 0.013
    w = 2 * math.pi / period
    t = np.arange(600) * dt
    decay, wd = _damped(t, w, zeta)
    a0 = 1.7
    u = intensity.oscillator_displacement(np.full(t.size, a0), dt, period, zeta)
    exact = -a0 / w**2 * (1 - decay * (np.cos(wd * t) + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * t)))
    assert np.max(np.abs(u - exact)) < 1e-12 * np.max(np.abs(exact))

    r = 2.3
    u = intensity.oscillator_displacement(r * t, dt, period, zeta)
    particular = -r / w**2 * (t - 2 * zeta / w)
    c1 = -2 * zeta * r / w**3          # u_h(0) = -u_p(0)
    c2 = (r / w**2 + zeta * w * c1) / wd  # u_h'(0) = -u_p'(0) = r / w²
    exact = particular + decay * (c1 * np.cos(wd * t) + c2 * np.sin(wd * t))
    assert np.max(np.abs(u - exact)) < 1e-11 * np.max(np.abs(exact))


def test_spectral_acceleration_of_a_step_and_a_harmonic():
    zeta = 0.05
    dt = 0.0005
    acc = np.full(4000, 2.0)  # step from rest: peak u = a0/w² (1 + exp(-pi zeta / sqrt(1 - zeta²)))
    sa = intensity.spectral_acceleration(acc, dt, 0.5)
    assert sa == pytest.approx(2.0 * (1 + math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2))), rel=1e-4)

    period, ratio = 0.4, 0.5  # forcing at half the natural frequency; steady state after 60 cycles
    w = 2 * math.pi / period
    big_t = 2 * math.pi / (ratio * w)
    t = np.arange(int(70 * big_t / 0.001)) * 0.001
    u = intensity.oscillator_displacement(np.sin(ratio * w * t), 0.001, period, zeta)
    steady = 1 / w**2 / math.hypot(1 - ratio**2, 2 * zeta * ratio)
    assert np.max(np.abs(u[t > 60 * big_t])) == pytest.approx(steady, rel=2e-4)


def test_intensity_measures_by_name():
    rec = gm.Record.from_samples([0.0, 1.0, -3.0, 0.5, 0.0], 0.1)
    assert intensity.parse("PGA").of(rec) == pytest.approx(3.0 / G)
    assert intensity.parse("pgv").of(rec) == pytest.approx(0.175)  # trapezoids: 0.05, -0.1, -0.125
    assert intensity.parse("PGA/gtana").of(rec, alpha=0.2, g=9.81) == pytest.approx(3.0 / (9.81 * math.tan(0.2)))
    assert intensity.parse("SA(T=0.5 s)") == intensity.parse("sa(0.5)") == intensity.parse("SA0.5")
    for bad in ("SA(0)", "PGD", "SA(-1)"):
        with pytest.raises(ValueError, match="intensity measure"):
            intensity.parse(bad)


def test_katnp_spectral_accelerations_as_its_readme_states():
    """data/ground-motions/README.md: SA(0.3 s) 0.290 g, SA(1.0 s) 0.282 g, SA(3.0 s) 0.235 g."""
    rec = gm.katnp_standin()
    for period, stated in ((0.3, 0.290), (1.0, 0.282), (3.0, 0.235)):
        assert intensity.parse(f"SA({period})").of(rec) == pytest.approx(stated, abs=0.0006)


def test_suite_keeps_the_horizontal_components():
    suite = load_suite([REPO / "data" / "ground-motions"])
    assert len(suite) == 9  # README table: 13 components, 4 of them vertical
    assert not any(is_vertical(r.component) for r in suite.values())
    for label in ("UP", "Up", "ver", "up", "HNZ"):
        assert is_vertical(label)
    for label in ("000", "090", "N28W", "S62W", "360", "270", "90", "0", "NS"):
        assert not is_vertical(label)


# ---------------------------------------------------------------------------
# Hunt-and-fill

def test_hunt_and_fill_brackets_the_collapse_of_an_oracle():
    options = hunt.HuntOptions(tol=0.05)
    for c in (0.37, 1.0, 2.9, 11.0):
        trace = hunt.hunt_and_fill(lambda im: (im >= c, im), 0.5, options)
        lo, hi = hunt.bracket(trace)
        assert lo < c <= hi and hi / lo < 1 + options.tol and hunt.unresolved(trace, options) == ""
        assert len(trace) <= options.max_runs and len({t[0] for t in trace}) == len(trace)
        cap, censored, below = hunt.capacity(trace)
        assert not censored and not below and lo <= cap <= hi
        # the hunt's steps grow by a fixed amount: start (step + k grow)
        ims = [t[0] for t in trace if t[3] == "hunt"]
        if trace[0][1]:  # collapsed at the start: halved instead
            assert np.allclose(np.array(ims[1:]) / ims[:-1], 0.5)
            continue
        steps = np.diff(ims) / 0.5
        assert np.allclose(steps, options.step + options.grow * np.arange(steps.size))
    # a collapse window below a stable range (rocking is not monotonic), 14 % wide: the scan
    # at a resolution of 10 % finds it, and the new bracket around its lower edge is narrowed
    window = lambda im: (0.70 <= im < 0.8 or im >= 2.9, im)  # noqa: E731
    trace = hunt.hunt_and_fill(window, 0.5, hunt.HuntOptions(tol=0.05, resolution=0.1))
    lo, hi = hunt.bracket(trace)
    assert lo < 0.70 <= hi and hi / lo < 1.05, trace
    trace = hunt.hunt_and_fill(lambda im: (False, im), 0.5, options)
    assert hunt.capacity(trace) == (max(t[0] for t in trace), True, False)
    trace = hunt.hunt_and_fill(lambda im: (im >= 0.2, im), 1.0, options)  # the first run collapses
    lo, hi = hunt.bracket(trace)
    assert lo < 0.2 <= hi and trace[1][0] == 0.5


# ---------------------------------------------------------------------------
# Lognormal fits (Baker 2015) against synthetic data

MEDIAN, BETA = 0.6, 0.45


def test_fit_of_collapse_intensities_with_and_without_censoring():
    rng = np.random.default_rng(7)
    n = 2000
    x = MEDIAN * np.exp(BETA * rng.standard_normal(n))
    se_mu, se_beta = BETA / math.sqrt(n), BETA / math.sqrt(2 * n)
    m, b = fit.fit_capacities(x)
    assert abs(math.log(m / MEDIAN)) < 4 * se_mu and abs(b - BETA) < 4 * se_beta
    cut = np.quantile(x, 0.7)  # 30 % never collapse up to the cut
    m, b = fit.fit_capacities(np.minimum(x, cut), x > cut)
    assert abs(math.log(m / MEDIAN)) < 6 * se_mu and abs(b - BETA) < 6 * se_beta
    with pytest.raises(ValueError, match="no record collapsed"):
        fit.fit_capacities([1.0, 2.0], [True, True])


def test_fit_of_stripes_counts():
    rng = np.random.default_rng(11)
    stripes = np.linspace(0.1, 1.5, 12)
    n = np.full(stripes.size, 400)
    p = fit.Fragility(MEDIAN, BETA, 0).probability(stripes)
    z = rng.binomial(n, p)
    m, b = fit.fit_stripes(stripes, n, z)
    assert abs(math.log(m / MEDIAN)) < 0.03 and abs(b - BETA) < 0.04
    with pytest.raises(fit.Undetermined, match="no run overturned"):
        fit.fit_stripes(stripes, n, np.zeros(stripes.size))


def test_bootstrap_interval_of_the_median():
    """90 % interval of ln median ~ +-1.645 beta / sqrt(n) for n records; it holds the truth."""
    rng = np.random.default_rng(3)
    n = 100
    x = MEDIAN * np.exp(BETA * rng.standard_normal(n))
    f = fit.ida_fragility(x, np.zeros(n, bool), n_boot=400)
    width = math.log(f.median_ci[1] / f.median_ci[0])
    assert width == pytest.approx(2 * 1.645 * BETA / math.sqrt(n), rel=0.25)
    assert f.median_ci[0] < MEDIAN < f.median_ci[1] and f.beta_ci[0] < BETA < f.beta_ci[1]


def test_analysis_leaves_out_a_hunt_that_failed():
    import pandas as pd
    rows = [dict(method="ida", body="b", record=r, im=im, overturned=im >= c, error="", peak_theta_over_alpha=0.5)
            for r, c in (("r1", 1.0), ("r2", 2.0), ("r3", 4.0)) for im in (0.5, 0.9, 1.1, 1.9, 2.1, 3.0)]
    rows.append(dict(method="ida", body="b", record="r4", im=0.5, overturned=None, error="FMU said no",
                     peak_theta_over_alpha=math.nan))
    study = Study(bodies={"b": {}}, suite={}, im=intensity.parse("PGA"))
    entry = study.analyse(pd.DataFrame(rows), n_boot=0)["b"]
    assert entry["records"]["r4"]["error"] == "FMU said no"
    assert entry["records"]["r3"]["censored"] and entry["records"]["r3"]["capacity"] == 3.0
    assert entry["records"]["r1"]["capacity"] == pytest.approx(math.sqrt(0.9 * 1.1))
    frag = entry["fragility"]
    assert frag.n == 3 and frag.censored == 1  # r4 is not a record of the fit


# ---------------------------------------------------------------------------
# The sweep on Dask

def _pulse(period, duration=2.0, dt=0.01, name="pulse"):
    """One full sine cycle of ground acceleration (1 m/s² peak), then rest."""
    t = np.arange(int(round(duration / dt)) + 1) * dt
    acc = np.where(t < period, np.sin(2 * math.pi * t / period), 0.0)
    return gm.Record.from_samples(acc, dt, name=name, component="H")


BLOCK = dict(shape="solidRectangle", B=0.3, L=1.0, massModel="prism", H=1.5, rho=1800.0,
             interface="rigid", formulation="shiftingPivot", restitution="housner")


def _study(method, **kw):
    suite = {f"pulse{p:g}": _pulse(p, name=f"pulse{p:g}") for p in (0.4, 0.6, 0.8, 1.0)}
    return Study(bodies={"block": BLOCK}, suite=suite, im=intensity.parse("PGA"), method=method, tail=0.5, **kw)


@pytest.fixture(scope="module")
def client(fmu_path):
    with cluster.open_client(workers=2, quiet=True, dashboard=":0") as c:
        c.wait_for_workers(2, timeout=60)
        yield c


@pytest.fixture(scope="module")
def local_fmu(fmu_path):
    from rocking import RockingFMU
    with RockingFMU(fmu_path) as f:
        yield f


def _check_exactly_once(store, tasks):
    df = store.read()
    expected = {(t[0], im) for t in tasks for _, ims in t[2][1] for im in ims}  # msa: (task, stripe)
    got = list(zip(df["task"], df["im"]))
    assert len(got) == len(set(got)) and set(got) == expected
    assert (df["error"] == "").all()
    return df


def test_worker_killed_mid_sweep_every_run_once(client, fmu_path, local_fmu, tmp_path):
    study = _study("msa", stripes=tuple(np.linspace(0.5, 6.0, 16)), chunk=2)
    digest = cluster.register_fmu(client, fmu_path)
    tasks = study.tasks(local_fmu, digest)
    store = ResultStore(tmp_path / "runs")
    pids = client.run(os.getpid)
    killed = []

    def progress(rows, expected):
        if not killed:  # after the first finished task: a worker dies with tasks in flight
            victim = sorted(pids.values())[0]
            os.kill(victim, signal.SIGKILL)
            killed.append(victim)

    finished, written, failures = cluster.execute(client, tasks, store, progress)
    assert killed and not failures
    assert finished == len(tasks) and written == 16 * 4
    df = _check_exactly_once(store, tasks)
    # the rows are what the FMU gives in this process, bit for bit
    for _, row in df.sample(5, random_state=0).iterrows():
        rec = study.suite[row["record"]]
        ov, t_ov, peak, _ = runner.run_once(local_fmu, BLOCK, rec, row["scale"], study.opts())
        assert (ov, peak) == (row["overturned"], row["peak_theta_over_alpha"])
        assert t_ov == row["t_overturn"] or (math.isnan(t_ov) and math.isnan(row["t_overturn"]))


def test_each_record_goes_to_each_worker_once(client, fmu_path, local_fmu, tmp_path, monkeypatch):
    """4 records x 4 tasks each: the records travel in one worker plugin (once to each
    worker), not inside the 16 runs' tasks, and the tasks depend on no other task (so the
    scheduler may give each to any worker); the plugin is gone after the call."""
    study = _study("msa", stripes=tuple(np.linspace(0.5, 6.0, 8)), chunk=2)
    tasks = study.tasks(local_fmu, cluster.register_fmu(client, fmu_path))
    carried, plugins = [], []
    submit, register = client.submit, client.register_plugin

    def spy(fn, *args, **kw):
        values = [x for a in args for x in (a.values() if isinstance(a, dict) else [a])]
        values += [x for a in args if isinstance(a, list) for part in a for x in part[0].values()]
        carried.append(sum(isinstance(x, (gm.Record, Future)) for x in values))
        return submit(fn, *args, **kw)

    def spy_plugin(plugin, *args, **kw):
        plugins.append(plugin)
        return register(plugin, *args, **kw)

    monkeypatch.setattr(client, "submit", spy)
    monkeypatch.setattr(client, "register_plugin", spy_plugin)
    finished, written, failures = cluster.execute(client, tasks, ResultStore(tmp_path / "runs"))
    assert not failures and finished == len(tasks) == 16 and written == 32
    assert len(carried) == 16 and sum(carried) == 0
    assert len(plugins) == 1 and sorted(map(id, plugins[0].records.values())) == sorted(map(id, study.suite.values()))
    assert client.run(lambda: len(runner._RECORDS)) == {w: 0 for w in client.nthreads()}


def test_default_batching_gives_every_run_as_a_direct_run(client, fmu_path, local_fmu, tmp_path, monkeypatch):
    """The study's own batching (shrinking tasks, largest first, records by plugin; made
    small here so that 32 runs make several tasks): every run's row equals, bit for bit, the
    FMU run directly in this process."""
    from rocking.fragility import study as study_mod
    monkeypatch.setattr(study_mod, "STEPS_PER_TASK", 2000)
    monkeypatch.setattr(study_mod, "SMALLEST_TASK", 600)
    study = _study("msa", stripes=tuple(np.linspace(0.5, 6.0, 8)))
    tasks = study.tasks(local_fmu, cluster.register_fmu(client, fmu_path))
    sizes = [t[3] for t in tasks]
    assert len(tasks) >= 4 and sizes[0] > sizes[-1]
    store = ResultStore(tmp_path / "runs")
    assert cluster.execute(client, tasks, store)[2] == {}
    df = _check_exactly_once(store, tasks)
    assert len(df) == 32
    for _, row in df.iterrows():
        ov, t_ov, peak, _ = runner.run_once(local_fmu, BLOCK, study.suite[row["record"]], row["scale"], study.opts())
        assert (ov, peak) == (row["overturned"], row["peak_theta_over_alpha"])
        assert t_ov == row["t_overturn"] or (math.isnan(t_ov) and math.isnan(row["t_overturn"]))


def test_execute_collects_on_its_own_clients_loop(client, fmu_path, local_fmu, tmp_path, monkeypatch):
    """The results are collected on the event loop of the client given, not on that of Dask's
    default client (the last one opened): with two clusters open in one process (the
    throughput benchmark), the other's loop slowed execute down threefold or hung it."""
    study = _study("msa", stripes=(1.0,), chunk=4)
    tasks = study.tasks(local_fmu, cluster.register_fmu(client, fmu_path))
    loops = []
    real = cluster.as_completed

    def spy(*args, **kw):
        loops.append(kw.get("loop"))
        return real(*args, **kw)

    monkeypatch.setattr(cluster, "as_completed", spy)
    assert cluster.execute(client, tasks, ResultStore(tmp_path / "runs"))[:2] == (1, 4)
    assert loops == [client.loop]


def test_local_workers_run_without_the_malloc_trim_threshold(client):
    """Dask's nannies set MALLOC_TRIM_THRESHOLD_=65536 in their workers by default, which made
    every run fault its arrays' pages in afresh (168 page faults a run instead of 2-3, +13 %
    CPU): the LocalCluster's workers run without it, and with the rest of Dask's environment."""
    env = client.run(lambda: (os.environ.get("MALLOC_TRIM_THRESHOLD_"), os.environ.get("OMP_NUM_THREADS")))
    assert env and all(v == (None, "1") for v in env.values())


def test_resume_skips_finished_tasks(client, fmu_path, local_fmu, tmp_path):
    study = _study("msa", stripes=(1.0, 2.0, 4.0, 8.0), chunk=2)
    tasks = study.tasks(local_fmu, cluster.register_fmu(client, fmu_path))
    store = ResultStore(tmp_path / "runs")
    finished, _, _ = cluster.execute(client, tasks, store, stop_after=3)  # interrupted
    assert finished == 3 and len(store.done()) == 3
    assert store.finished(t[0] for t in tasks) == store.done()  # file names match contents
    first = {f.name: f.stat().st_mtime_ns for f in store.files()}
    finished, _, failures = cluster.execute(client, tasks, store)
    assert not failures and finished == len(tasks) - 3
    assert all(f.stat().st_mtime_ns == first[f.name] for f in store.files() if f.name in first)
    _check_exactly_once(store, tasks)
    assert cluster.execute(client, tasks, store)[0] == 0


def test_ida_on_the_cluster_against_a_brute_force_grid(client, fmu_path, local_fmu, tmp_path):
    """The hunt's first collapse and the dense-grid mode's against a brute-force loop of
    the FMU in this process (the dense grid's capacity exactly: same runs, same bracket)."""
    study = _study("ida", hunt=hunt.HuntOptions(tol=0.03))
    study.suite = {k: v for k, v in study.suite.items() if k in ("pulse0.4", "pulse1")}
    dense = _study("ida", hunt=hunt.HuntOptions(tol=0.03), grid=30, chunk=15)
    dense.suite = study.suite
    digest = cluster.register_fmu(client, fmu_path)
    tasks = study.tasks(local_fmu, digest) + dense.tasks(local_fmu, digest)
    store = ResultStore(tmp_path / "runs")
    assert cluster.execute(client, tasks, store)[2] == {}
    df = store.read()
    result = study.analyse(df[~df["task"].str.endswith("|grid")], n_boot=0)["block"]
    on_grid = dense.analyse(df[df["task"].str.endswith("|grid")], n_boot=0)["block"]
    for rname, entry in result["records"].items():
        rec = study.suite[rname]
        grid = np.geomspace(0.5, 20.0, 120)  # PGA of the pulse is 1 m/s²: scale = PGA in m/s²
        first = next(s for s in grid if runner.run_once(local_fmu, BLOCK, rec, s, study.opts())[0])
        cap_scale = entry["capacity"] * G
        assert entry["unresolved"] == "" and not entry["censored"]
        assert abs(math.log(cap_scale / first)) < math.log(grid[1] / grid[0]) + 0.03, rname
        rows = df[(df["record"] == rname) & df["task"].str.endswith("|grid")].sort_values("im")
        assert len(rows) == 30 and (rows["phase"] == "grid").all()
        ims = rows["im"].to_numpy()
        outcomes = [runner.run_once(local_fmu, BLOCK, rec, s, study.opts())[0] for s in rows["scale"]]
        k = outcomes.index(True)
        assert on_grid["records"][rname]["capacity"] == pytest.approx(math.sqrt(ims[k - 1] * ims[k]), rel=1e-12)


# ---------------------------------------------------------------------------
# The command

def _write_at2(path, rec, title):
    values = rec.acc / G
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", f"SYNTHETIC PULSE, TEST STATION, {title}",
             "ACCELERATION TIME SERIES IN UNITS OF G", f"NPTS=  {values.size}, DT=   {rec.dt:.4f} SEC"]
    lines += ["  ".join(f"{v: .7E}" for v in values[i:i + 5]) for i in range(0, values.size, 5)]
    path.write_text("\n".join(lines) + "\n")


def test_rocking_ida_command_runs_and_resumes(client, fmu_path, tmp_path, capsys):
    """The command on a folder of PEER AT2 files, through --scheduler (the module's
    two-worker LocalCluster: no second cluster to start), then again: nothing left to run."""
    from rocking.cli import main
    suite = tmp_path / "suite"
    suite.mkdir()
    _write_at2(suite / "pulse_H1.AT2", _pulse(0.5), "H1")
    _write_at2(suite / "pulse_H2.AT2", _pulse(0.8), "H2")
    body = tmp_path / "block.json"
    body.write_text(json.dumps(BLOCK))
    hazard = tmp_path / "hazard.csv"
    hazard.write_text("0.01,1e-2\n10,1e-8\n")  # lambda = 1e-6 PGA^-2 (PGA in g)
    argv = ["ida", str(suite), "--params", str(body), "--im", "PGA", "--tail", "0.5", "--boot", "100",
            "--damage-states", "DS1=0.3", "--hazard", str(hazard), "--mce", "0.5",
            "--scheduler", client.scheduler.address, "--fmu", fmu_path, "--out", str(tmp_path / "out")]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert "dashboard" in err and "record/s" in err and "runs in" in err  # the bar counts the searches
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    entry = summary["bodies"]["block"]
    assert entry["median"] > 0 and entry["n"] == 2 and set(entry["records"]) == {"pulse_H1.AT2[H1]", "pulse_H2.AT2[H2]"}
    assert entry["unresolved_records"] == 0 and entry["damage_states"]["DS1"]["threshold"] == 0.3
    assert entry["risk"]["cmr"] == pytest.approx(entry["median"] / 0.5)
    # the closed form of a lognormal fragility under lambda = k0 x^-k: k0 median^-k exp(k² beta² / 2)
    assert entry["risk"]["maf"] == pytest.approx(1e-6 * entry["median"] ** -2 * math.exp(2 * entry["beta"] ** 2),
                                                 rel=1e-6)
    for name in ("fragility.png", "ida-block.png"):
        assert (tmp_path / "out" / name).stat().st_size > 10_000
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert "2 tasks, 2 already" in err and "runs in" not in err
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["bodies"]["block"]["median"] == entry["median"]


def test_rocking_ida_errors_are_one_line(fmu_path, tmp_path, capsys):
    from rocking.cli import main
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(dict(BLOCK, interface="elastic", kn=1.0)))  # kn Is < W hG: refused
    suite = REPO / "data" / "ground-motions" / "katnp-standin"
    for extra, expected in ((["--params", str(bad)], "body bad: "),
                            (["--preset", "dharahara-rigid", "--im", "PGD"], "--im: intensity measure 'PGD'"),
                            (["--preset", "dharahara-rigid", "--stripes", "0:1:0.5"],
                             "--stripes 0.0: expected a finite number > 0"),
                            (["--preset", "nope"], "unknown preset 'nope'")):
        method = "msa" if "--stripes" in extra else "ida"
        status = main([method, str(suite), *extra, "--fmu", fmu_path, "--out", str(tmp_path / "o")])
        lines = capsys.readouterr().err.strip().splitlines()
        assert status == 2 and len(lines) == 1 and expected in lines[0], lines
