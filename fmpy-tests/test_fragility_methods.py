"""Fragility methods without the FMU (issue 21): fits where the data fix none, the search for
the first collapse against a brute-force dense grid of a synthetic non-monotonic outcome,
damage states, the bootstrap's band and stations, goodness of fit, hazard risk against the
closed form of a lognormal fragility under a power-law hazard, the new intensity measures,
units in the Parquet schema, and the command's option checks (one line, exit 2).
"""

import argparse
import json
import math

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest
from scipy.special import ndtr

from rocking import groundmotion as gm
from rocking.fragility import fit, hunt, intensity, risk
from rocking.fragility.store import ResultStore
from rocking.fragility.study import Study, station_of

G = 9.80665


# ---------------------------------------------------------------------------
# Section 2: fits where none exists

@pytest.mark.parametrize("im,n,z", [
    ([0.2, 5.0], [9, 9], [0, 9]),          # all stand, then all overturn
    ([1.0], [9], [4]),                     # a single stripe
    ([0.5, 1.0], [9, 9], [0, 1]),          # 0/9 then 1/9: separated
    ([0.5, 1.0, 2.0], [9, 9, 9], [0, 3, 9]),  # one partial stripe between 0 and 1
    ([0.5, 1.0], [9, 9], [2, 0]),          # decreasing
    ([0.6, 1.0], [9, 9], [8, 8]),          # flat: gave 'median 0, beta 1.3e16'
    ([0.6, 1.0, 1.6], [9, 9, 9], [6, 3, 6]),  # falling, then rising: the fit is flat
])
def test_stripes_that_fix_no_fit_are_undetermined(im, n, z):
    with pytest.raises(fit.Undetermined):
        fit.fit_stripes(im, n, z)


def test_stripes_that_fix_a_fit_give_the_mle():
    """Two partial stripes: the probit through both points exactly is the MLE (saturated)."""
    im, n, z = [0.5, 2.0], [10, 10], [2, 7]
    m, b = fit.fit_stripes(im, n, z)
    assert ndtr(math.log(0.5 / m) / b) == pytest.approx(0.2, abs=1e-6)
    assert ndtr(math.log(2.0 / m) / b) == pytest.approx(0.7, abs=1e-6)


def test_capacities_that_fix_no_fit_are_undetermined():
    with pytest.raises(fit.Undetermined, match="fewer than two distinct"):
        fit.fit_capacities([1.0, 0.5], [False, True])  # gave beta = 0
    with pytest.raises(fit.Undetermined, match="no record collapsed"):
        fit.fit_capacities([1.0, 2.0], [True, True])
    with pytest.raises(fit.Undetermined):
        fit.fit_capacities([1.0, 1.0, 3.0], [False, False, True])


def test_moments_estimator_is_the_n_minus_1_deviation():
    x = np.array([0.3, 0.5, 0.9, 1.4, 2.0])
    m, b = fit.fit_capacities(x, estimator="moments")
    ln = np.log(x)
    assert b == pytest.approx(math.sqrt(((ln - ln.mean()) ** 2).sum() / (x.size - 1)), rel=1e-12)
    assert fit.fit_capacities(x)[1] == pytest.approx(math.sqrt(((ln - ln.mean()) ** 2).sum() / x.size), rel=1e-12)
    with pytest.raises(fit.Undetermined, match="moments"):
        fit.fit_capacities(x, [False] * 4 + [True], estimator="moments")


def test_degenerate_bootstrap_resamples_are_counted_not_fatal():
    """Two stripes, few partial records: many resamples separate (the OverflowError case)."""
    table = [[0.0, 0.0]] * 20 + [[0.0, 1.0]] * 5 + [[1.0, 1.0]] * 1 + [[0.0, 0.0]]
    f = fit.msa_fragility([0.6, 1.0], table, n_boot=300)
    assert 0 < f.boot_undetermined < 300 and len(f.boot[0]) + f.boot_undetermined == 300
    assert math.isfinite(f.median) and f.beta > 0


def test_msa_bootstrap_fits_each_resample_as_a_plain_loop_does():
    """The bootstrap fits each distinct resample's counts once: the same medians and betas,
    bit for bit, and the same undetermined count, as fitting every resample in a loop written
    here (over records, and over stations, where some resamples are undetermined)."""
    rng = np.random.default_rng(3)
    stripes = [0.4, 0.7, 1.0, 1.4]
    table = (rng.random((11, 4)) < np.array([0.05, 0.3, 0.6, 0.9])).astype(float)
    stations = [k // 2 for k in range(11)]
    undetermined_seen = 0
    for groups_of in (None, stations):
        f = fit.msa_fragility(stripes, table, n_boot=400, seed=7, stations=groups_of)
        groups = fit._groups(list(table), groups_of)
        pick_rng = np.random.default_rng(7)
        medians, betas, undetermined = [], [], 0
        for _ in range(400):
            pick = pick_rng.integers(0, len(groups), len(groups))
            rows = np.array([row for i in pick for row in groups[i]])
            try:
                m, b = fit.fit_stripes(stripes, (~np.isnan(rows)).sum(axis=0), np.nansum(rows, axis=0))
            except (ValueError, OverflowError, FloatingPointError):
                undetermined += 1
                continue
            medians.append(m)
            betas.append(b)
        assert f.boot_undetermined == undetermined
        assert np.array_equal(f.boot[0], medians) and np.array_equal(f.boot[1], betas)
        assert len(set(zip(medians, betas))) < len(medians)  # resamples repeat
        undetermined_seen += undetermined
    assert undetermined_seen > 0


def test_an_undetermined_body_is_one_line_and_everything_is_written(tmp_path):
    """A body whose stripes separate gets 'no fit: ...'; the other body, the summary and the
    plot are written (the command used to die in the bootstrap)."""
    from rocking.cli.ida import write_outputs
    rows = []
    for body in ("sep", "ok"):
        for k in range(9):
            for im in (0.6, 1.0, 1.6):
                over = im >= 1.0 if body == "sep" else im >= 0.6 * 1.25 ** k
                rows.append(dict(method="msa", body=body, record=f"r{k}", im=im, overturned=over, error="",
                                 alpha=0.2, peak_theta_over_alpha=2.0 if over else 0.3, unresolved=""))
    df = pd.DataFrame(rows)
    suite = {f"r{k}": gm.Record.from_samples([0.0, 1.0, 0.0], 0.01) for k in range(9)}
    study = Study(bodies={"sep": {}, "ok": {}}, suite=suite, im=intensity.parse("PGV"), method="msa",
                  stripes=(0.6, 1.0, 1.6))
    result = study.analyse(df, n_boot=50)
    text = write_outputs(tmp_path, study, df, result, argparse.Namespace(boot=50), dict(years=50.0))
    lines = [ln for ln in text.splitlines() if ln.startswith("  sep:")]
    assert len(lines) == 1 and "no fit: the stripes separate" in lines[0]
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["bodies"]["sep"]["median"] is None and summary["bodies"]["ok"]["median"] > 0
    assert (tmp_path / "fragility.png").stat().st_size > 10_000


# ---------------------------------------------------------------------------
# Section 1: the first collapse, against a brute-force dense grid

def _windows(rng, start, res):
    """A non-monotonic outcome: collapse in 0-3 windows (each wider than 1 + res, in ratio)
    below a threshold, or no threshold (censored)."""
    wins = []
    for _ in range(rng.integers(0, 4)):
        a = start * math.exp(rng.uniform(0.2, math.log(40)))
        wins.append((a, a * (1 + res) * math.exp(rng.uniform(0.01, 0.4))))
    top = start * math.exp(rng.uniform(0.5, math.log(60))) if rng.random() < 0.8 else math.inf
    return lambda im: any(a <= im < b for a, b in wins) or im >= top


def test_first_collapse_against_a_dense_grid_of_a_non_monotonic_outcome():
    rng = np.random.default_rng(5)
    o = hunt.HuntOptions()  # the defaults
    start = 0.3
    grid = np.geomspace(start, o.stop * start, 20001)  # brute force: 0.02 % apart
    found = 0
    for _ in range(200):
        collapses = _windows(rng, start, o.resolution)
        trace = hunt.hunt_and_fill(lambda im: (collapses(im), 0.0), start, o)
        truth = next((x for x in grid if collapses(x)), None)
        cap, censored, _ = hunt.capacity(trace)
        why = hunt.unresolved(trace, o)
        assert len(trace) <= o.max_runs
        if why:
            assert len(trace) == o.max_runs  # only the budget leaves a search unresolved
            continue
        found += 1
        if truth is None:
            assert censored
        else:
            assert not censored and abs(math.log(cap / truth)) < math.log(1 + o.tol), (truth, cap, trace)
    assert found >= 190


def test_a_window_below_the_first_collapse_found_is_found():
    """The old hunt stepped over [0.9, 1.15) and reported the collapse at 2.9."""
    collapses = lambda im: (0.9 <= im < 1.15 or im >= 2.9, 0.0)  # noqa: E731
    trace = hunt.hunt_and_fill(collapses, 0.5, hunt.HuntOptions())
    cap, censored, _ = hunt.capacity(trace)
    assert not censored and abs(math.log(cap / 0.9)) < math.log(1.05)
    # a record that overturns anywhere in the searched range is not censored
    collapses = lambda im: (4.0 <= im < 5.0, 0.0)  # noqa: E731
    cap, censored, _ = hunt.capacity(hunt.hunt_and_fill(collapses, 0.5, hunt.HuntOptions()))
    assert not censored and abs(math.log(cap / 4.0)) < math.log(1.05)


def test_a_spent_budget_is_marked_unresolved():
    o = hunt.HuntOptions(max_runs=6)
    trace = hunt.hunt_and_fill(lambda im: (im >= 7.3, 0.0), 0.5, o)
    assert len(trace) == 6 and hunt.unresolved(trace, o)
    trace = hunt.hunt_and_fill(lambda im: (False, 0.0), 0.5, o)
    assert "short of the hunt's stop" in hunt.unresolved(trace, o)
    o = hunt.HuntOptions(max_runs=60)
    trace = hunt.hunt_and_fill(lambda im: (im >= 7.3, 0.0), 0.5, o)
    assert hunt.unresolved(trace, o) == ""


# ---------------------------------------------------------------------------
# Section 4: damage states, uncertainty, goodness of fit, risk, intensity measures, units

def test_damage_states_have_their_own_fits_from_the_same_runs():
    """peak |theta| / alpha = im / c for record of capacity c (overturning at im >= c): the
    damage state at threshold t is reached at im = t c; the fit's median scales by t."""
    rng = np.random.default_rng(2)
    caps = 0.8 * np.exp(0.4 * rng.standard_normal(30))
    grid = np.geomspace(0.05, 20, 300)
    rows = [dict(method="ida", body="b", record=f"r{k}", im=im, overturned=im >= c, error="",
                 peak_theta_over_alpha=min(im / c, 5.0), unresolved="")
            for k, c in enumerate(caps) for im in grid]
    study = Study(bodies={"b": {}}, suite={}, im=intensity.parse("PGA"), damage_states={"DS1": 0.2, "DS2": 0.5})
    entry = study.analyse(pd.DataFrame(rows), n_boot=0)["b"]
    over = entry["states"]["overturning"]["fragility"]
    step = math.log(grid[1] / grid[0])
    for name, t in (("DS1", 0.2), ("DS2", 0.5)):
        f = entry["states"][name]["fragility"]
        assert abs(math.log(f.median / (t * over.median))) < step and abs(f.beta - over.beta) < step
    assert abs(math.log(over.median / math.exp(np.log(caps).mean()))) < step


def test_bootstrap_band_on_the_curve_and_station_resampling():
    """90 % band of P at the median ~ +-1.645 phi(0) / sqrt(n); with two identical components
    per station, resampling stations widens the median's interval by sqrt(2)."""
    rng = np.random.default_rng(4)
    n = 100
    x = 0.6 * np.exp(0.45 * rng.standard_normal(n))
    f = fit.ida_fragility(x, np.zeros(n, bool), n_boot=800)
    lo, hi = f.band(np.array([f.median]))
    assert hi[0] - lo[0] == pytest.approx(2 * 1.645 * 0.3989 / math.sqrt(n), rel=0.25)
    pairs = np.repeat(x[:50], 2)
    stations = np.repeat(np.arange(50), 2)
    by_rec = fit.ida_fragility(pairs, np.zeros(100, bool), n_boot=800)
    by_sta = fit.ida_fragility(pairs, np.zeros(100, bool), n_boot=800, stations=stations)
    ratio = math.log(by_sta.median_ci[1] / by_sta.median_ci[0]) / math.log(by_rec.median_ci[1] / by_rec.median_ci[0])
    assert ratio == pytest.approx(math.sqrt(2), rel=0.2)


def test_modelling_beta_combines_as_fema_p58():
    f = fit.Fragility(1.0, 0.3, 10, beta_modelling=0.4)
    assert f.beta_total == pytest.approx(0.5)
    assert f.probability(math.exp(0.5)) == pytest.approx(ndtr(1.0))


def test_goodness_of_fit_statements():
    rng = np.random.default_rng(8)
    x = 0.6 * np.exp(0.45 * rng.standard_normal(200))
    m, b = fit.fit_capacities(x)
    assert not fit.gof_capacities(x, np.zeros(200, bool), m, b)["rejected"]
    u = rng.uniform(1.0, 2.0, 200) ** 8  # far from lognormal
    mu, bu = fit.fit_capacities(u)
    assert fit.gof_capacities(u, np.zeros(200, bool), mu, bu)["rejected"]
    stripes = np.array([0.3, 0.6, 1.0, 1.6])  # counts exactly on the curve: G = 0
    n = np.full(4, 1000)
    z = n * ndtr(np.log(stripes / 0.8) / 0.5)
    g = fit.gof_stripes(stripes, n, z, 0.8, 0.5)
    assert g["statistic"] == pytest.approx(0.0, abs=1e-9) and g["p_value"] == pytest.approx(1.0)


@pytest.mark.parametrize("median,beta,k", [(0.8, 0.4, 2.5), (0.3, 0.7, 1.8), (2.0, 0.2, 3.2)])
def test_collapse_frequency_against_the_power_law_closed_form(tmp_path, median, beta, k):
    """lambda(x) = k0 x^-k, lognormal fragility: lambda_c = k0 median^-k exp(k² beta² / 2)."""
    k0 = 1e-4
    xs = np.geomspace(0.01, 10.0, 12)
    path = tmp_path / "hazard.csv"
    path.write_text("intensity,frequency\n" + "".join(f"{float(x)!r},{float(k0 * x ** -k)!r}\n" for x in xs))
    hz = risk.read_hazard(path)
    exact = k0 * median ** -k * math.exp(k * k * beta * beta / 2)
    r = risk.risk(fit.Fragility(median, beta, 10), hz, mce=0.5)
    assert r["maf"] == pytest.approx(exact, rel=1e-6)
    assert r["p_years"] == pytest.approx(1 - math.exp(-50 * exact), rel=1e-6)
    assert r["cmr"] == pytest.approx(median / 0.5)
    for bad, match in (("0.1,1e-3\n0.2,2e-3\n", "not increase"), ("0.1,1e-3\n", "two"), ("0.1,1e-3\n0.2,x\n", ":2:")):
        path.write_text(bad)
        with pytest.raises(ValueError, match=match):
            risk.read_hazard(path)


def test_new_intensity_measures():
    """AvgSA of a step is its constant SA (the step's peak factor at every period); PGV over
    g tan alpha / p of a record scales as PGV."""
    zeta = intensity.ZETA
    acc = np.full(8000, 2.0)
    rec = gm.Record.from_samples(acc, 0.0005)
    peak = 2.0 * (1 + math.exp(-math.pi * zeta / math.sqrt(1 - zeta ** 2)))
    assert intensity.parse("AvgSA(0.2-0.8)").of(rec) == pytest.approx(peak / G, rel=2e-4)
    rec = gm.Record.from_samples([0.0, 1.0, -3.0, 0.5, 0.0], 0.1)
    im = intensity.parse("PGV/(gtana/p)")
    assert im.of(rec, alpha=0.2, g=9.81, p=1.5) == pytest.approx(0.175 * 1.5 / (9.81 * math.tan(0.2)))
    for bad in ("AvgSA(2-1)", "AvgSA(0-1)"):
        with pytest.raises(ValueError, match="intensity measure"):
            intensity.parse(bad)


def test_units_in_the_parquet_schema(tmp_path):
    store = ResultStore(tmp_path)
    store.write("k", [dict(task="k", method="msa", body="b", record="r", im=1.0, overturned=False, error="")])
    schema = pq.read_schema(store.files()[0])
    assert schema.field("t_overturn").metadata[b"unit"] == b"s"
    assert schema.field("alpha").metadata[b"unit"] == b"rad"
    assert json.loads(schema.metadata[b"im_units"])["PGV"] == "m/s"


def test_stations_of_the_shipped_suite():
    from rocking import paths
    from rocking.fragility.suite import load_suite
    stations = {station_of(n) for n in load_suite([paths.data_dir()])}
    assert len(stations) == 5  # data/ground-motions/README.md: 5 stations of 5 events


# ---------------------------------------------------------------------------
# Section 3: options checked up front, one line naming the option, exit 2

@pytest.mark.parametrize("method,extra,named", [
    ("ida", ["--rtol", "-1"], "--rtol"), ("ida", ["--tail", "-50"], "--tail"),
    ("msa", ["--stripes", "1", "--chunk", "-2"], "--chunk"), ("msa", ["--stripes", "1", "--chunk", "0"], "--chunk"),
    ("msa", ["--stripes", "0.5,nan"], "--stripes"), ("msa", ["--stripes", "0.5,inf"], "--stripes"),
    ("msa", ["--stripes", "a,b"], "--stripes"), ("ida", ["--max-runs", "0"], "--max-runs"),
    ("ida", ["--max-runs", "-3"], "--max-runs"), ("ida", ["--tol", "-0.2"], "--tol"),
    ("ida", ["--resolution", "0"], "--resolution"), ("ida", ["--grid", "1"], "--grid"),
    ("ida", ["--beta-modelling", "-0.1"], "--beta-modelling"), ("ida", ["--mce", "0"], "--mce"),
    ("ida", ["--damage-states", "DS1=x"], "--damage-states"), ("ida", ["--damage-states", "DS1=-1"], "--damage-states"),
    ("ida", ["--workers", "0"], "--workers"), ("ida", ["--boot", "-1"], "--boot"),
])
def test_bad_options_are_one_line_naming_them(tmp_path, capsys, method, extra, named):
    from rocking.cli import main
    rec = tmp_path / "r.csv"
    rec.write_text("time,acc\n0,0\n0.01,1\n0.02,0\n")
    status = main([method, str(rec), "--preset", "dharahara-rigid", *extra, "--fmu", str(tmp_path / "none.fmu"),
                   "--out", str(tmp_path / "o")])
    lines = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and len(lines) == 1 and named in lines[0], lines


@pytest.mark.parametrize("text,named", [
    ("stripes = []", "stripes"), ("tol = -0.2", "tol"), ("max_runs = 0", "max_runs"), ("chunk = 1.5", "chunk"),
    ("rtol = true", "rtol"), ("damage_states = { DS1 = 0 }", "damage_states.DS1"), ("hazard = 'nope.csv'", "hazard"),
    ("bootstrap = 'events'", "bootstrap"), ("beta_estimator = 'ols'", "beta_estimator"), ("records = 3", "records"),
])
def test_bad_study_keys_are_one_line_naming_them(tmp_path, capsys, text, named):
    from rocking.cli import main
    study = tmp_path / "s.toml"
    study.write_text(f'im = "PGV"\n{text}\n' + ("" if "stripes" in text else "stripes = [1.0]\n"))
    method = "msa" if "stripes" in text or "chunk" in text else "ida"
    status = main([method, str(study), "--preset", "dharahara-rigid", "--fmu", str(tmp_path / "none.fmu"),
                   "--out", str(tmp_path / "o")])
    lines = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and len(lines) == 1 and f"{study}: {named}" in lines[0], lines


def test_stripes_fit_is_the_maximum_likelihood_of_an_independent_optimiser():
    """Newton on the probit against Nelder-Mead on (ln median, ln beta) of the binomial
    likelihood: ours is at least as likely, and the same point to 1e-5."""
    from scipy.optimize import minimize
    from scipy.special import log_ndtr
    rng = np.random.default_rng(1)
    checked = 0
    for _ in range(60):
        k = rng.integers(3, 12)
        im = np.sort(rng.uniform(0.1, 5, k))
        n = rng.integers(3, 30, k)
        z = rng.binomial(n, fit.Fragility(math.exp(rng.normal(0, 0.5)), rng.uniform(0.2, 1.2), 0).probability(im))
        try:
            m, b = fit.fit_stripes(im, n, z)
        except fit.Undetermined:
            continue
        x = np.log(im)

        def nll(q):
            s = (x - q[0]) / math.exp(q[1])
            return -(z @ log_ndtr(s) + (n - z) @ log_ndtr(-s))

        r = minimize(nll, [math.log(m) + 0.1, math.log(b) - 0.1], method="Nelder-Mead",
                     options=dict(xatol=1e-11, fatol=1e-13, maxiter=20000))
        assert nll([math.log(m), math.log(b)]) <= r.fun + 1e-9
        assert abs(r.x[0] - math.log(m)) < 1e-5 and abs(math.exp(r.x[1]) - b) < 1e-5
        checked += 1
    assert checked > 40


def test_censored_fit_is_the_maximum_likelihood_of_an_independent_optimiser():
    """Newton on the censored normal (Tobit) likelihood against Nelder-Mead on (ln median,
    ln beta): ours is at least as likely, and the same point to 1e-6; 0 to 90 % censored."""
    from scipy.optimize import minimize
    from scipy.special import log_ndtr
    rng = np.random.default_rng(5)
    checked = 0
    for _ in range(60):
        k = int(rng.integers(4, 40))
        x = math.exp(rng.normal(0, 0.7)) * np.exp(rng.uniform(0.15, 1.2) * rng.standard_normal(k))
        cut = np.quantile(x, rng.uniform(0.1, 1.0))
        censored = x > cut
        try:
            m, b = fit.fit_capacities(np.minimum(x, cut), censored)
        except fit.Undetermined:
            continue
        ln = np.log(np.minimum(x, cut))
        xs, xc = ln[~censored], ln[censored]

        def nll(q):
            beta = math.exp(q[1])
            zs = (xs - q[0]) / beta
            return 0.5 * zs @ zs + xs.size * q[1] - log_ndtr((q[0] - xc) / beta).sum()

        r = minimize(nll, [math.log(m) + 0.1, math.log(b) - 0.1], method="Nelder-Mead",
                     options=dict(xatol=1e-11, fatol=1e-13, maxiter=20000))
        assert nll([math.log(m), math.log(b)]) <= r.fun + 1e-9
        assert abs(r.x[0] - math.log(m)) < 1e-6 and abs(math.exp(r.x[1]) - b) < 1e-6 * b
        checked += 1
    assert checked > 40


def test_margin_ratio_without_a_hazard_curve(tmp_path):
    from rocking.cli.ida import write_outputs
    rows = [dict(method="ida", body="b", record=f"r{k}", im=im, overturned=im >= c, error="", alpha=0.2,
                 peak_theta_over_alpha=0.1, unresolved="")
            for k, c in enumerate((0.5, 0.8, 1.3)) for im in np.geomspace(0.1, 3, 40)]
    suite = {f"r{k}": gm.Record.from_samples([0.0, 1.0, 0.0], 0.01) for k in range(3)}
    study = Study(bodies={"b": {}}, suite=suite, im=intensity.parse("PGV"))
    df = pd.DataFrame(rows)
    text = write_outputs(tmp_path, study, df, study.analyse(df, n_boot=0), argparse.Namespace(boot=0),
                         dict(mce=0.4, years=50.0))
    median = json.loads((tmp_path / "summary.json").read_text())["bodies"]["b"]["median"]
    assert f"collapse margin ratio {median / 0.4:.3g}" in text


# ---------------------------------------------------------------------------
# Section 5: tasks a small study can balance over its workers

def _list_schedule(batches, cost, workers):
    """Makespan of the batches run in order, each by the first worker free (what the client's
    submission in order, a few tasks in flight per worker, approaches)."""
    free = [0.0] * workers
    for batch in batches:
        k = free.index(min(free))
        free[k] += sum(cost(u) for u in batch)
    return max(free)


@pytest.mark.parametrize("costs", [
    [9800] * 144,                                     # the 144-run study
    [int(c) for c in np.random.default_rng(7).integers(500, 40_000, 297)],
    [300_000] * 3,                                    # units above the largest task
    [1000] * 4000,                                    # a large study: STEPS_PER_TASK rules
    [5000] * 3,                                       # below the smallest task: one batch
])
def test_batches_shrink_largest_first_within_bounds(costs):
    from rocking.fragility.study import SHARE, SMALLEST_TASK, STEPS_PER_TASK, shrinking_batches
    units = list(enumerate(costs))
    batches = shrinking_batches(units, lambda u: u[1])
    assert [u for b in batches for u in b] == units  # every run once, in order
    sizes = [sum(c for _, c in b) for b in batches]
    big = max(costs)
    total = sum(costs)
    assert all(s < STEPS_PER_TASK + big for s in sizes)
    assert all(s >= SMALLEST_TASK for s in sizes[:-1])  # only the last may be below the smallest
    assert all(b <= a + big for a, b in zip(sizes, sizes[1:]))  # never larger by more than one run
    # each batch (but the last) reaches SHARE of what was left, within its bounds
    left = total
    for s in sizes[:-1]:
        assert s >= min(STEPS_PER_TASK, max(SMALLEST_TASK, SHARE * left))
        left -= s
    if len(units) > 1 and total > STEPS_PER_TASK:
        assert sizes[-1] < SMALLEST_TASK + big
    # two workers taking the batches in order end within the last batches' size of each other
    makespan = _list_schedule(batches, lambda u: u[1], 2)
    assert makespan <= total / 2 + max(sizes[-3:] if len(sizes) > 2 else sizes)


# ---------------------------------------------------------------------------
# Issue 38: damage states located as overturning is, fits the data cannot determine, the risk
# integral's range, what happened at each stripe

class _Outcome:
    """A synthetic body for one record: peak |theta| / alpha = (im / c)^p below collapse, raised
    to `bump` in 0-2 windows, overturning at im >= top and in 0-2 collapse windows (the windows
    above the start, 1, each wider than 1 + 2 resolution in ratio): not monotonic in im."""

    def __init__(self, rng, res):
        self.p = rng.uniform(1.0, 3.0)
        self.c = math.exp(rng.uniform(math.log(1 / 32), math.log(4))) / 0.01 ** (1 / self.p)

        def windows(n):
            out = []
            for _ in range(n):
                a = math.exp(rng.uniform(0.1, math.log(40)))
                out.append((a, a * (1 + 2 * res) * math.exp(rng.uniform(0.01, 0.4))))
            return out
        self.falls, self.bumps = windows(rng.integers(0, 3)), windows(rng.integers(0, 3))
        self.bump = rng.uniform(0.05, 0.9)
        self.top = math.exp(rng.uniform(0.3, math.log(60))) if rng.random() < 0.8 else math.inf

    def __call__(self, im):
        over = im >= self.top or any(a <= im < b for a, b in self.falls)
        peak = (im / self.c) ** self.p
        if any(a <= im < b for a, b in self.bumps):
            peak = max(peak, self.bump)
        return over, (max(peak, 1.0) if over else min(peak, 0.99))


class _FakeRun:
    def __init__(self, over, peak):
        self.overturned, self.t_overturn, self.peak_theta_over_alpha, self.calculated = over, 0.0, peak, {}


class _FakeFMU:
    """RockingFMU's two calls a study makes, for outcomes {id(record): _Outcome} of the
    intensity PGA / (g tan alpha)."""

    alpha = 0.2

    def __init__(self, outcomes):
        self.outcomes = outcomes

    def calculated(self, params):
        return dict(weight=G, mass=1.0, R0=1.0, IO=1.0, alpha=self.alpha)

    def simulate(self, params, record, scale, **_):
        im = scale * record.pga / (G * math.tan(self.alpha))  # record.pga in m/s²
        return _FakeRun(*self.outcomes[id(record)](im))


def _study_rows(study, fmu):
    """Every task of `study` run in this process on `fmu`: the rows, as the store gives them."""
    from rocking.fragility import runner
    runner.install_fmu("fake", fmu)
    rows = []
    for _, fn, args, _ in study.tasks(fmu, "fake"):
        rows += fn(*args)
    return pd.DataFrame(rows)


STATES = {"uplift": 0.01, "DS1": 0.2, "DS2": 0.5}


def test_damage_state_capacities_against_a_dense_grid_of_a_non_monotonic_outcome():
    """Each record's capacity for each damage state, from the IDA's own search (study, runner,
    hunt), against the first intensity of a brute-force grid 0.02 % apart at which the state
    is reached: within the bracket's tolerance; censored from below where the grid reaches it
    below the search's floor (start / 16); a resolved search may differ from the grid only
    where the budget left it unresolved. Before, a state reached at the first run got that
    run's intensity, exact."""
    rng = np.random.default_rng(38)
    o = hunt.HuntOptions()
    floor = 1 / 2 ** o.halvings  # the start is 1 in PGA / (g tan alpha)
    grid = np.geomspace(floor / 8, o.stop, 20001)  # 0.04 % apart
    suite = {f"r{k}": gm.Record.from_samples([0.0, 0.1 + 0.01 * k, 0.0], 0.01) for k in range(60)}
    outcomes = {id(rec): _Outcome(rng, o.resolution) for rec in suite.values()}
    study = Study(bodies={"b": {}}, suite=suite, im=intensity.parse("PGA/gtana"), damage_states=STATES, tail=0.0,
                  hunt=o)
    records = study.analyse(_study_rows(study, _FakeFMU(outcomes)), n_boot=0)["b"]["records"]
    checked = below_floor = first_run = 0
    for name, rec in suite.items():
        info, outcome = records[name], outcomes[id(rec)]
        if info["unresolved"]:
            assert info["runs"] == o.max_runs
            continue
        over, peak = np.array([outcome(x) for x in grid]).T
        for state, thr in STATES.items():
            got = info["damage_states"][state]
            hits = np.flatnonzero((over > 0) | (peak >= thr))
            truth = grid[hits[0]] if hits.size else None
            first_run += truth is not None and truth <= 1.0
            if truth is None:
                assert got["censored"] and not got["below"]
            elif truth < floor:
                below_floor += 1
                assert got["below"] and got["capacity"] == pytest.approx(floor, rel=1e-12), (state, truth, got)
            else:
                assert not got["censored"] and not got["below"], (state, truth, got)
                assert abs(math.log(got["capacity"] / truth)) < math.log(1 + o.tol), (state, truth, got)
            checked += 1
    assert checked >= 150 and below_floor >= 3 and first_run >= 30, (checked, below_floor, first_run)


def test_interpolated_damage_capacity_is_the_ida_curve_at_the_threshold():
    """Vamvatsikos & Cornell 2002: where the IDA curve is linear in the intensity (peak = im / c),
    interpolating between any two runs that straddle the threshold gives t c exactly; the
    bracket gives it to the tolerance."""
    rng = np.random.default_rng(7)
    suite = {f"r{k}": gm.Record.from_samples([0.0, 0.1 + 0.01 * k, 0.0], 0.01) for k in range(12)}
    caps = {id(rec): math.exp(rng.uniform(0.5, 2.5)) for rec in suite.values()}
    outcomes = {key: (lambda im, c=c: (im >= c, im / c)) for key, c in caps.items()}
    for how, rel in (("interpolate", 1e-12), ("bracket", 0.05)):
        study = Study(bodies={"b": {}}, suite=suite, im=intensity.parse("PGA/gtana"), damage_states={"DS1": 0.2},
                      tail=0.0, damage_capacity=how)
        records = study.analyse(_study_rows(study, _FakeFMU(outcomes)), n_boot=0)["b"]["records"]
        for name, rec in suite.items():
            got = records[name]["damage_states"]["DS1"]["capacity"]
            assert abs(math.log(got / (0.2 * caps[id(rec)]))) < math.log1p(rel), (how, got)
    with pytest.raises(ValueError, match="damage_capacity"):
        Study(bodies={}, suite={}, im=intensity.parse("PGV"), damage_capacity="spline")


def test_capacities_censored_from_below_fit_as_an_independent_optimiser_does():
    """Capacities known only to lie below a floor (reached already at the search's lowest
    run) enter the likelihood as Phi((ln floor - mu) / beta): Newton against Nelder-Mead."""
    from scipy.optimize import minimize
    from scipy.special import log_ndtr
    rng = np.random.default_rng(11)
    checked = 0
    for _ in range(40):
        k = int(rng.integers(6, 40))
        x = math.exp(rng.normal(0, 0.7)) * np.exp(rng.uniform(0.15, 1.2) * rng.standard_normal(k))
        lo, hi = np.quantile(x, rng.uniform(0.0, 0.4)), np.quantile(x, rng.uniform(0.6, 1.0))
        below, above = x <= lo, x > hi
        caps = np.clip(x, lo, hi)
        try:
            m, b = fit.fit_capacities(caps, above, below=below)
        except fit.Undetermined:
            continue
        ln = np.log(caps)
        xs, xa, xb = ln[~(below | above)], ln[above], ln[below]

        def nll(q):
            beta = math.exp(q[1])
            zs = (xs - q[0]) / beta
            return (0.5 * zs @ zs + xs.size * q[1] - log_ndtr((q[0] - xa) / beta).sum()
                    - log_ndtr((xb - q[0]) / beta).sum())

        r = minimize(nll, [math.log(m) + 0.1, math.log(b) - 0.1], method="Nelder-Mead",
                     options=dict(xatol=1e-11, fatol=1e-13, maxiter=20000))
        assert nll([math.log(m), math.log(b)]) <= r.fun + 1e-9
        assert abs(r.x[0] - math.log(m)) < 1e-6 and abs(math.exp(r.x[1]) - b) < 1e-6 * b
        checked += 1
    assert checked > 30


@pytest.mark.parametrize("capacities,censored,match", [
    # the data: every capacity the first run's intensity, differing in the last digit
    ([0.25008540123283696, 0.2500854012328369] * 2 + [0.25008540123283696], [False] * 5, "distinct"),
    ([0.25, 0.25 * (1 + 1e-9), 0.25, 0.3], [False, False, False, True], "distinct"),
    ([0.25, 0.25 * (1 + 1e-5), 0.25, 0.25 * (1 - 1e-5)], [False] * 4, "below the floor"),
    ([0.25] * 5, [False] * 5, "distinct"),
])
def test_capacities_that_fix_no_fit_whatever_the_rounding(capacities, censored, match):
    with pytest.raises(fit.Undetermined, match=match):
        fit.fit_capacities(capacities, censored)
    with pytest.raises(fit.Undetermined, match=match):
        fit.ida_fragility(capacities, censored, n_boot=0)


def test_a_damage_state_reached_in_every_stripe_says_what_happened_at_each():
    """A state reached in every run while most runs stood: the reason names the state and the
    counts at each stripe, not 'every run overturned'."""
    rows = [dict(method="msa", body="b", record=f"r{k}", im=im, overturned=(k == 0 and im > 1), error="",
                 peak_theta_over_alpha=0.05 * im, unresolved="")
            for k in range(5) for im in (0.5, 1.0, 2.0)]
    suite = {f"r{k}": gm.Record.from_samples([0.0, 1.0, 0.0], 0.01) for k in range(5)}
    study = Study(bodies={"b": {}}, suite=suite, im=intensity.parse("PGV"), method="msa",
                  stripes=(0.5, 1.0, 2.0), damage_states={"uplift": 0.01})
    states = study.analyse(pd.DataFrame(rows), n_boot=0)["b"]["states"]
    why = states["uplift"]["error"]
    assert "overturned" not in why and "every run reached uplift" in why
    assert "5 of 5 at 0.5, 5 of 5 at 1, 5 of 5 at 2" in why
    why = states["overturning"]["error"]
    assert "overturned in 0 of 5 at 0.5, 0 of 5 at 1, 1 of 5 at 2" in why


@pytest.mark.parametrize("k", [1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
def test_collapse_frequency_over_slopes_and_dispersions(k):
    """The power-law closed form lambda_c = k0 median^-k exp(k² beta² / 2) to 1e-6 for beta up
    to 1.5 and medians across and beyond the curve (the +-8 beta range was 2.3 % low at k = 4,
    beta = 1.5, 84 % at k = 6)."""
    k0 = 1e-4
    xs = np.geomspace(0.01, 10.0, 12)
    hz = risk.hazard_from(xs, k0 * xs ** -k)
    for beta in np.linspace(0.1, 1.5, 15):
        for median in (0.005, 0.05, 0.8, 5.0, 30.0):
            exact = k0 * median ** -k * math.exp(k * k * beta * beta / 2)
            assert risk.collapse_frequency(median, beta, hz) == pytest.approx(exact, rel=1e-6), (beta, median)


def test_collapse_frequency_of_a_curved_hazard_against_quadrature():
    """A hazard whose log-log slope runs from 0.5 to 5 (12 points): the MAF against adaptive
    quadrature of lambda(x) f(x) over ln x, piece by piece, with the tails to +-40 beta."""
    from scipy.integrate import quad
    xs = np.geomspace(0.02, 5.0, 12)
    lf = np.cumsum(-np.linspace(0.5, 5.0, 11) * np.diff(np.log(xs)))
    hz = risk.hazard_from(xs, 1e-2 * np.exp(np.concatenate([[0.0], lf])))
    for median, beta in ((0.3, 0.4), (1.0, 1.0), (0.05, 1.5), (3.0, 0.8)):
        def integrand(u):
            return float(hz(median * math.exp(beta * u))) * math.exp(-0.5 * u * u) / math.sqrt(2 * math.pi)
        knots = sorted({-40.0, 40.0, *((np.log(xs / median) / beta).clip(-40, 40))})
        total = sum(quad(integrand, a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in zip(knots, knots[1:]))
        assert risk.collapse_frequency(median, beta, hz) == pytest.approx(total, rel=1e-8)


def test_the_ida_progress_bar_counts_what_it_will_do(monkeypatch):
    """`rocking ida`'s bar ends where it started: 9 searches of at most 5 runs that take 4 or 5
    each (it started at 0/45 and ended at 40/40), and 3 tasks of stripes of 4 runs each."""
    import contextlib
    import io

    import tqdm

    from rocking.cli import ida
    from rocking.fragility import cluster, runner

    bars = []

    class Bar(tqdm.tqdm):
        def __init__(self, *a, **kw):
            super().__init__(*a, **dict(kw, file=io.StringIO()))
            self.first_total = self.total
            bars.append(self)

    monkeypatch.setattr(tqdm, "tqdm", Bar)
    monkeypatch.setattr(cluster, "open_client", lambda *a: contextlib.nullcontext(None))
    monkeypatch.setattr(cluster, "register_fmu", lambda *a: None)
    for todo, done in (([(f"h{k}", runner.run_hunt, (), 5) for k in range(9)], [4] * 5 + [5] * 4),
                       ([(f"s{k}", runner.run_batch, (), 4) for k in range(3)], [4] * 3)):
        def execute(client, tasks, store, progress, todo=todo, done=done):
            for (_, _, _, expected), rows in zip(tasks, done):
                progress(rows, expected)
            return len(tasks), sum(done), {}
        monkeypatch.setattr(cluster, "execute", execute)
        ida.run_tasks(argparse.Namespace(scheduler=None, workers=1, method="ida"), None, todo, None)
        bar = bars[-1]
        assert bar.n == bar.total == bar.first_total, (bar.n, bar.total, bar.first_total)
