"""Lognormal fragility P(collapse | IM = x) = Phi(ln(x / median) / beta), fitted by maximum
likelihood (Baker 2015, "Efficient analytical fragility function fitting using dynamic
structural analysis data", Earthquake Spectra 31(1)).

- from IDA: the records' collapse intensities, some right-censored (no collapse up to the
  highest intensity run): density for the others, survival for the censored. Without
  censoring the MLE is the mean and the 1/n standard deviation of ln x; the moments
  estimator (`estimator="moments"`, Baker's) takes the n-1 one;
- from multiple stripes: z of n records collapsed at intensity x_j, binomial likelihood
  (a probit regression on ln x);
- a bootstrap over records, or stations (groups of records), for intervals on both and a
  confidence band on the curve;
- goodness of fit: Anderson-Darling on ln x (IDA, uncensored), the likelihood-ratio
  (deviance) test against one probability per stripe (MSA).

Where the data do not determine a fit (no collapse, fewer than two distinct collapse
intensities, stripes that separate standing from overturning, a beta below BETA_FLOOR), the
fits raise `Undetermined` with the reason instead of returning the optimiser's last step.
A capacity may be censored either way: from above (the state was not reached up to the
highest intensity run: survival term) or from below (reached at the lowest intensity run, the
search's floor: distribution-function term).
"""

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import stats
from scipy.special import log_ndtr, ndtr

_LOG_SQRT_2PI = 0.5 * math.log(2 * math.pi)
ESTIMATORS = ("mle", "moments")

#: Capacities closer than this (relative) are one intensity when counting distinct ones:
#: searches bracket to a few percent, so a difference in the last digits is rounding, not data.
DISTINCT_RTOL = 1e-6

#: The smallest beta a fit returns: a dispersion under 0.1 % of the intensity is below the
#: resolution of any capacity a search or a grid locates (5 % and 6.9 % by default), so the
#: data say the capacities coincide, not how they scatter.
BETA_FLOOR = 1e-3


class Undetermined(ValueError):
    """The data do not determine a lognormal fit; the message says why."""


@dataclass
class Fragility:
    """median (IM units), beta (record-to-record dispersion of ln IM), n records, and the
    bootstrap's (lo, hi) intervals of both at `level` (nan without a bootstrap).

    censored: capacities censored from above (never reached); censored_below: from below
    (reached already at the search's floor).
    beta_modelling: the modelling-uncertainty dispersion combined with beta as FEMA P-58
    does, beta_total = sqrt(beta² + beta_modelling²). boot: (medians, betas) of the
    resamples that could be fitted; boot_undetermined: how many could not; gof: the
    goodness-of-fit statement (dict)."""

    median: float
    beta: float
    n: int
    median_ci: tuple = (math.nan, math.nan)
    beta_ci: tuple = (math.nan, math.nan)
    level: float = 0.9
    censored: int = 0
    censored_below: int = 0
    estimator: str = "mle"
    beta_modelling: float = 0.0
    boot: tuple = field(default=((), ()), repr=False)
    boot_undetermined: int = 0
    gof: dict = field(default_factory=dict)

    @property
    def beta_total(self):
        return math.hypot(self.beta, self.beta_modelling)

    def probability(self, x, total=True):
        """P(collapse | IM = x), with beta_total (total=True) or the record-to-record beta."""
        b = self.beta_total if total else self.beta
        return ndtr(np.log(np.asarray(x, dtype=float) / self.median) / b)

    def band(self, x):
        """(lo, hi) of P(collapse | IM = x) at `level` over the bootstrap's fits (each with
        the modelling beta combined); nan without a bootstrap."""
        x = np.asarray(x, dtype=float)
        m, b = (np.asarray(v, dtype=float) for v in self.boot)
        if m.size < 10:
            return np.full(x.shape, math.nan), np.full(x.shape, math.nan)
        b = np.hypot(b, self.beta_modelling)
        p = ndtr(np.log(x[None, :] / m[:, None]) / b[:, None])
        q = [(1 - self.level) / 2 * 100, (1 + self.level) / 2 * 100]
        lo, hi = np.percentile(p, q, axis=0)
        return lo, hi


def _finite_fit(median, beta, what):
    if not (math.isfinite(median) and math.isfinite(beta) and median > 0 and 0 < beta < 1e3):
        raise Undetermined(f"{what}: the likelihood has no maximum (median {median:.3g}, beta {beta:.3g})")
    if beta < BETA_FLOOR:
        raise Undetermined(f"{what}: beta {beta:.3g} is below the floor {BETA_FLOOR:g} (the data put every "
                           f"capacity at one intensity, {median:.4g}): beta is not determined")
    return median, beta


def distinct(values, rtol=DISTINCT_RTOL):
    """How many of `values` (> 0) differ from each other by more than `rtol`, relative."""
    v = np.sort(np.asarray(values, dtype=float))
    if v.size == 0:
        return 0
    return 1 + int(np.count_nonzero(np.diff(np.log(v)) > math.log1p(rtol)))


def _censored_loglik(xs, xc, sc, a, b):
    r = b * xs - a
    return float(-0.5 * r @ r + xs.size * math.log(b) + log_ndtr(sc * (a - b * xc)).sum())


def _censored_newton(xs, xc, sc, iterations=100):
    """Maximum of the log-likelihood of ln-capacities `xs` and bounds `xc` (sc +1: a lower
    bound, the capacity above it; -1: an upper bound) under a normal of mean mu and deviation
    beta, by Newton's method with step halving in (a, b) = (mu/beta, 1/beta), where it is
    concave (Olsen 1978, the Tobit model): l = sum_s [ln b - (b x - a)²/2]
    + sum_c ln Phi(s (a - b x)) + const. Returns (mu, beta)."""
    a, b = xs.mean() / xs.std(), 1.0 / xs.std()
    ll = _censored_loglik(xs, xc, sc, a, b)
    sx, sxx = xs.sum(), xs @ xs
    for _ in range(iterations):
        r = b * xs - a
        u = sc * (a - b * xc)
        lam = np.exp(-0.5 * u * u - _LOG_SQRT_2PI - log_ndtr(u))  # inverse Mills ratio
        k = lam * (u + lam)                                       # -d lambda/du > 0
        g = np.array([r.sum() + sc @ lam, -(r @ xs) + xs.size / b - (sc * lam) @ xc])
        h = np.array([[xs.size + k.sum(), -sx - k @ xc],
                      [-sx - k @ xc, sxx + xs.size / (b * b) + k @ (xc * xc)]])  # -Hessian
        det = h[0, 0] * h[1, 1] - h[0, 1] * h[1, 0]
        if not det > 0:
            break
        step = np.array([h[1, 1] * g[0] - h[0, 1] * g[1], h[0, 0] * g[1] - h[1, 0] * g[0]]) / det
        t = 1.0
        while t > 1e-10:
            a1, b1 = a + t * step[0], b + t * step[1]
            if b1 > 0:
                ll1 = _censored_loglik(xs, xc, sc, a1, b1)
                if ll1 >= ll - 1e-13 * abs(ll):
                    break
            t /= 2
        else:
            break
        done = abs(ll1 - ll) <= 1e-15 * max(1.0, abs(ll)) and np.max(np.abs(t * step)) < 1e-12 * max(1.0, abs(a))
        a, b, ll = a1, b1, ll1
        if done:
            break
    return a / b, 1.0 / b


def fit_capacities(capacities, censored=None, estimator="mle", below=None):
    """(median, beta) from collapse intensities; censored[i] True where capacities[i] is
    only a lower bound (never reached up to it), below[i] True where it is only an upper bound
    (reached already there, the search's floor). estimator 'mle' (1/n) or 'moments' (n-1,
    uncensored only). Undetermined when fewer than two distinct intensities (DISTINCT_RTOL)
    are exact, or beta comes out below BETA_FLOOR."""
    if estimator not in ESTIMATORS:
        raise ValueError(f"beta estimator {estimator!r}: expected one of {', '.join(ESTIMATORS)}")
    x = np.log(np.asarray(capacities, dtype=float))
    c = np.zeros(x.size, bool) if censored is None else np.asarray(censored, bool)
    lb = np.zeros(x.size, bool) if below is None else np.asarray(below, bool)
    if np.any(c & lb):
        raise ValueError("a capacity cannot be censored from above and from below")
    exact = ~(c | lb)
    xs = x[exact]
    if xs.size == 0:
        raise Undetermined("no record collapsed: no fragility can be fitted" if not lb.any() else
                           f"no capacity located ({int(c.sum())} never reached, {int(lb.sum())} reached "
                           "already at the search's floor): no fragility can be fitted")
    n_distinct = distinct(np.exp(xs))
    if n_distinct < 2:
        raise Undetermined(f"fewer than two distinct collapse intensities ({xs.size} of {x.size} record(s) located, "
                           f"{n_distinct} distinct to {DISTINCT_RTOL:g} relative): beta is not determined")
    if estimator == "moments":
        if not exact.all():
            raise Undetermined(f"the moments estimator needs every record to collapse ({int(c.sum() + lb.sum())} "
                               "censored); use the MLE")
        return _finite_fit(math.exp(xs.mean()), float(xs.std(ddof=1)), "collapse intensities")
    if exact.all():
        return _finite_fit(math.exp(xs.mean()), float(xs.std()), "collapse intensities")

    xc = x[~exact]
    sc = np.where(c[~exact], 1.0, -1.0)
    mu, beta = _censored_newton(xs, xc, sc)
    return _finite_fit(math.exp(mu), beta, "censored collapse intensities")


def stripe_counts(im, n, collapsed, event="overturned"):
    """What happened at each stripe, in words: 'overturned in 0 of 9 at 0.2, 3 of 9 at 0.45, ...'."""
    parts = [f"{int(z)} of {int(k)} at {x:.4g}" for x, k, z in zip(im, n, collapsed) if k > 0]
    return f"{event} in {', '.join(parts)}"


def stripes_determined(im, n, collapsed, event="overturned"):
    """Why the stripes (intensity, runs, collapsed) do not determine a fit, or '' if they do:
    a probit fit on ln x has a maximum when some run reached the state (`event`, a past
    participle: 'overturned', 'reached DS1') below an intensity at which another did not, and
    some run did not below one that did. The reason ends with the counts at each stripe."""
    im, n, z = (np.asarray(v, dtype=float) for v in (im, n, collapsed))
    ran = n > 0
    counts = stripe_counts(im, n, z, event)
    if np.unique(im[ran]).size < 2:
        return f"runs at fewer than two distinct intensities ({counts})"
    if z.sum() == 0:
        return f"no run {event} ({counts})"
    if z.sum() == n.sum():
        return f"every run {event} ({counts})"
    hit, missed = im[z > 0], im[(n - z) > 0]
    if not hit.min() < missed.max():
        return (f"the stripes separate the runs that {event} from those that did not (no run {event} below an "
                f"intensity at which another did not): beta is not determined ({counts})")
    if not missed.min() < hit.max():
        return f"the fraction {event} does not increase with the intensity ({counts})"
    return ""


def fit_stripes(im, n, collapsed, event="overturned"):
    """(median, beta) from stripes: at intensity im[j], collapsed[j] of n[j] records reached the
    state (`event` names it in the reasons). Undetermined when the counts cannot fix both
    (stripes_determined) or beta is below BETA_FLOOR."""
    why = stripes_determined(im, n, collapsed, event)
    if why:
        raise Undetermined(why)
    im, n, z = (np.asarray(v, dtype=float) for v in (im, n, collapsed))
    keep = n > 0
    x, n, z = np.log(im[keep]), n[keep], z[keep]
    frac = z / n
    mid = np.interp(0.5, np.maximum.accumulate(frac), x) if frac.max() >= 0.5 else x.max()
    a, b = _probit_newton(x, n, z, -mid / 0.4, 1 / 0.4)
    if not b > 1e-3:  # beta > 1000: a flat curve, the maximum at beta -> infinity
        raise Undetermined(f"the fraction {event} does not increase with the intensity "
                           f"({stripe_counts(np.exp(x), n, z, event)})")
    return _finite_fit(math.exp(-a / b), 1 / b, "stripes")


def _probit_loglik(x, n, z, a, b):
    s = a + b * x
    return float(z @ log_ndtr(s) + (n - z) @ log_ndtr(-s))


def _probit_newton(x, n, z, a, b, iterations=100):
    """Maximum of the binomial probit log-likelihood in s = a + b x by Newton's method with
    step halving (the log-likelihood is concave; the data overlap, so the maximum is finite).
    A few tenths of a millisecond: the bootstrap refits thousands of times."""
    ll = _probit_loglik(x, n, z, a, b)
    for _ in range(iterations):
        s = a + b * x
        log_pdf = -0.5 * s * s - _LOG_SQRT_2PI
        l1, l2 = np.exp(log_pdf - log_ndtr(s)), np.exp(log_pdf - log_ndtr(-s))  # Mills ratios
        w = z * l1 - (n - z) * l2                                  # dl/ds
        h = z * l1 * (s + l1) + (n - z) * l2 * (l2 - s)           # -d²l/ds² > 0
        g = np.array([w.sum(), w @ x])
        hess = np.array([[h.sum(), h @ x], [h @ x, h @ (x * x)]])
        try:
            step = np.linalg.solve(hess, g)
        except np.linalg.LinAlgError:
            break
        t = 1.0
        while t > 1e-10:
            a1, b1 = a + t * step[0], b + t * step[1]
            ll1 = _probit_loglik(x, n, z, a1, b1)
            if ll1 >= ll - 1e-13 * abs(ll):
                break
            t /= 2
        a, b, done = a1, b1, abs(ll1 - ll) <= 1e-15 * max(1.0, abs(ll)) and np.max(np.abs(t * step)) < 1e-10
        ll = ll1
        if done:
            break
    return a, b


def bootstrap(fit, groups, n_boot=1000, level=0.9, seed=0):
    """(median_ci, beta_ci, (medians, betas), undetermined) of `fit(sample)` over `n_boot`
    resamples (with replacement) of `groups` (one item per record, or per station: a list of
    records); resamples the fit cannot determine are counted, never fatal."""
    rng = np.random.default_rng(seed)
    medians, betas, undetermined = [], [], 0
    for _ in range(n_boot):
        pick = rng.integers(0, len(groups), len(groups))
        try:
            m, b = fit([groups[i] for i in pick])
        except (ValueError, OverflowError, FloatingPointError):
            undetermined += 1
            continue
        medians.append(m)
        betas.append(b)
    nan2 = (math.nan, math.nan)
    if len(medians) < 10:
        return nan2, nan2, (np.array(medians), np.array(betas)), undetermined
    q = [(1 - level) / 2 * 100, (1 + level) / 2 * 100]
    return (tuple(np.percentile(medians, q)), tuple(np.percentile(betas, q)),
            (np.array(medians), np.array(betas)), undetermined)


def _groups(items, stations):
    """Items grouped by station (stations[i] the station of items[i]; None: one each)."""
    if stations is None:
        return [[it] for it in items]
    by = {}
    for it, s in zip(items, stations):
        by.setdefault(s, []).append(it)
    return list(by.values())


def _flat(sample):
    return [it for group in sample for it in group]


def ida_fragility(capacities, censored, n_boot=1000, level=0.9, seed=0, estimator="mle",
                  beta_modelling=0.0, stations=None, below=None):
    """Fragility (with a bootstrap over records, or over `stations` if given: the station
    of each record) from IDA collapse intensities, `censored` from above and `below` from
    below (fit_capacities). Undetermined if the data fix no fit."""
    below = np.zeros(len(capacities), bool) if below is None else np.asarray(below, bool)
    triples = list(zip(capacities, censored, below))
    median, beta = fit_capacities(capacities, censored, estimator, below)

    def refit(sample):
        xs, cs, bs = zip(*_flat(sample))
        return fit_capacities(xs, cs, estimator, bs)

    f = Fragility(median, beta, len(triples), level=level, censored=int(np.sum(censored)),
                  censored_below=int(below.sum()), estimator=estimator, beta_modelling=beta_modelling)
    if n_boot:
        f.median_ci, f.beta_ci, f.boot, f.boot_undetermined = bootstrap(
            refit, _groups(triples, stations), n_boot, level, seed)
    f.gof = gof_capacities(capacities, np.asarray(censored, bool) | below, median, beta)
    return f


def msa_fragility(stripes, outcomes, n_boot=1000, level=0.9, seed=0, beta_modelling=0.0, stations=None,
                  event="overturned"):
    """Fragility from stripes: `outcomes` one row per record, collapsed (bool) at each
    intensity of `stripes` (nan where the run failed); bootstrap over records or stations;
    `event` names the state in the reasons of a fit that is undetermined."""
    stripes = np.asarray(stripes, dtype=float)
    table = np.asarray(outcomes, dtype=float)

    def counts(rows):
        rows = np.asarray(rows, dtype=float)
        return (~np.isnan(rows)).sum(axis=0), np.nansum(rows, axis=0)

    fits = {}

    def refit(sample):
        # A resample's fit depends on its counts alone, and resamples of a few records or
        # stations repeat them (5 stations: at most 126 distinct resamples): each fitted once.
        n, z = counts(_flat(sample))
        key = (n.tobytes(), z.tobytes())
        if key not in fits:
            try:
                fits[key] = fit_stripes(stripes, n, z, event)
            except (ValueError, OverflowError, FloatingPointError) as exc:
                fits[key] = exc
        if isinstance(fits[key], Exception):
            raise fits[key].with_traceback(None)
        return fits[key]

    n, z = counts(table)
    median, beta = fit_stripes(stripes, n, z, event)
    f = Fragility(median, beta, len(table), level=level, beta_modelling=beta_modelling)
    if n_boot:
        f.median_ci, f.beta_ci, f.boot, f.boot_undetermined = bootstrap(
            refit, _groups(list(table), stations), n_boot, level, seed)
    f.gof = gof_stripes(stripes, n, z, median, beta)
    return f


# ---------------------------------------------------------------------------
# Goodness of fit

def gof_capacities(capacities, censored, median, beta):
    """Anderson-Darling test of ln(collapse intensity) against a normal of estimated
    parameters (Stephens' critical values, scipy.stats.anderson); not tested with censoring."""
    c = np.asarray(censored, bool)
    if c.any():
        return dict(test="none", text=f"not tested ({int(c.sum())} censored record(s))")
    x = np.log(np.asarray(capacities, dtype=float))
    if x.size < 8:
        return dict(test="none", text=f"not tested (n = {x.size} < 8)")
    res = stats.anderson(x, "norm")
    crit = float(res.critical_values[list(res.significance_level).index(5.0)])
    ok = res.statistic < crit
    return dict(test="anderson-darling", statistic=float(res.statistic), critical_5pct=crit, rejected=not ok,
                text=f"Anderson-Darling A2 = {res.statistic:.3f} ({'not ' if ok else ''}rejected at 5 %, "
                     f"critical {crit:.3f})")


def gof_stripes(stripes, n, z, median, beta):
    """Likelihood-ratio (deviance) test of the lognormal against one probability per stripe:
    G = 2 sum[z ln(z / n p) + (n - z) ln((n - z) / n (1 - p))], chi² with k - 2 degrees of freedom."""
    stripes, n, z = (np.asarray(v, dtype=float) for v in (stripes, n, z))
    keep = n > 0
    stripes, n, z = stripes[keep], n[keep], z[keep]
    dof = stripes.size - 2
    if dof < 1:
        return dict(test="none", text="not tested (fewer than 3 stripes)")
    p = np.clip(ndtr(np.log(stripes / median) / beta), 1e-300, 1 - 1e-16)
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = np.where(z > 0, z * np.log(z / (n * p)), 0.0)
        t2 = np.where(n - z > 0, (n - z) * np.log((n - z) / (n * (1 - p))), 0.0)
    g = float(2 * (t1 + t2).sum())
    pval = float(stats.chi2.sf(g, dof))
    return dict(test="deviance", statistic=g, dof=dof, p_value=pval, rejected=pval < 0.05,
                text=f"deviance G = {g:.2f} on {dof} dof, p = {pval:.3f} "
                     f"({'rejected' if pval < 0.05 else 'not rejected'} at 5 %)")
