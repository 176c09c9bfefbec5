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
intensities, stripes that separate standing from overturning), the fits raise
`Undetermined` with the reason instead of returning the optimiser's last step.
"""

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import stats
from scipy.special import log_ndtr, ndtr

_LOG_SQRT_2PI = 0.5 * math.log(2 * math.pi)
ESTIMATORS = ("mle", "moments")


class Undetermined(ValueError):
    """The data do not determine a lognormal fit; the message says why."""


@dataclass
class Fragility:
    """median (IM units), beta (record-to-record dispersion of ln IM), n records, and the
    bootstrap's (lo, hi) intervals of both at `level` (nan without a bootstrap).

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
    return median, beta


def _censored_loglik(xs, xc, a, b):
    r = b * xs - a
    return float(-0.5 * r @ r + xs.size * math.log(b) + log_ndtr(a - b * xc).sum())


def _censored_newton(xs, xc, iterations=100):
    """Maximum of the log-likelihood of ln-capacities `xs` and lower bounds `xc` under a
    normal of mean mu and deviation beta, by Newton's method with step halving in
    (a, b) = (mu/beta, 1/beta), where it is concave (Olsen 1978, the Tobit model):
    l = sum_s [ln b - (b x - a)²/2] + sum_c ln Phi(a - b x) + const. Returns (mu, beta)."""
    a, b = xs.mean() / xs.std(), 1.0 / xs.std()
    ll = _censored_loglik(xs, xc, a, b)
    sx, sxx = xs.sum(), xs @ xs
    for _ in range(iterations):
        r = b * xs - a
        u = a - b * xc
        lam = np.exp(-0.5 * u * u - _LOG_SQRT_2PI - log_ndtr(u))  # inverse Mills ratio
        k = lam * (u + lam)                                       # -d lambda/du > 0
        g = np.array([r.sum() + lam.sum(), -(r @ xs) + xs.size / b - lam @ xc])
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
                ll1 = _censored_loglik(xs, xc, a1, b1)
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


def fit_capacities(capacities, censored=None, estimator="mle"):
    """(median, beta) from collapse intensities; censored[i] True where capacities[i] is
    only a lower bound. estimator 'mle' (1/n) or 'moments' (n-1, uncensored only).
    Undetermined when fewer than two distinct intensities collapsed."""
    if estimator not in ESTIMATORS:
        raise ValueError(f"beta estimator {estimator!r}: expected one of {', '.join(ESTIMATORS)}")
    x = np.log(np.asarray(capacities, dtype=float))
    c = np.zeros(x.size, bool) if censored is None else np.asarray(censored, bool)
    xs, xc = x[~c], x[c]
    if xs.size == 0:
        raise Undetermined("no record collapsed: no fragility can be fitted")
    if np.unique(xs).size < 2:
        raise Undetermined(f"fewer than two distinct collapse intensities ({xs.size} of {x.size} "
                           "record(s) collapsed): beta is not determined")
    if estimator == "moments":
        if xc.size:
            raise Undetermined(f"the moments estimator needs every record to collapse ({xc.size} censored); "
                               "use the MLE")
        return math.exp(xs.mean()), float(xs.std(ddof=1))
    if xc.size == 0:
        return math.exp(xs.mean()), float(xs.std())

    mu, beta = _censored_newton(xs, xc)
    return _finite_fit(math.exp(mu), beta, "censored collapse intensities")


def stripes_determined(im, n, collapsed):
    """Why the stripes (intensity, runs, collapsed) do not determine a fit, or '' if they do:
    a probit fit on ln x has a maximum when some run overturned below an intensity at which
    another stood, and some run stood below one that overturned."""
    im, n, z = (np.asarray(v, dtype=float) for v in (im, n, collapsed))
    ran = n > 0
    if np.unique(im[ran]).size < 2:
        return "runs at fewer than two distinct intensities"
    if z.sum() == 0:
        return "no run overturned"
    if z.sum() == n.sum():
        return "every run overturned"
    overturned, stood = im[z > 0], im[(n - z) > 0]
    if not overturned.min() < stood.max():
        return ("the stripes separate standing from overturning (no run overturned below an intensity "
                "at which another stood): beta is not determined")
    if not stood.min() < overturned.max():
        return "the fraction overturned does not increase with the intensity"
    return ""


def fit_stripes(im, n, collapsed):
    """(median, beta) from stripes: at intensity im[j], collapsed[j] of n[j] records collapsed.
    Undetermined when the counts cannot fix both (stripes_determined)."""
    why = stripes_determined(im, n, collapsed)
    if why:
        raise Undetermined(why)
    im, n, z = (np.asarray(v, dtype=float) for v in (im, n, collapsed))
    keep = n > 0
    x, n, z = np.log(im[keep]), n[keep], z[keep]
    frac = z / n
    mid = np.interp(0.5, np.maximum.accumulate(frac), x) if frac.max() >= 0.5 else x.max()
    a, b = _probit_newton(x, n, z, -mid / 0.4, 1 / 0.4)
    if not b > 1e-3:  # beta > 1000: a flat curve, the maximum at beta -> infinity
        raise Undetermined("the fraction overturned does not increase with the intensity")
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
                  beta_modelling=0.0, stations=None):
    """Fragility (with a bootstrap over records, or over `stations` if given: the station
    of each record) from IDA collapse intensities. Undetermined if the data fix no fit."""
    pairs = list(zip(capacities, censored))
    median, beta = fit_capacities(capacities, censored, estimator)

    def refit(sample):
        xs, cs = zip(*_flat(sample))
        return fit_capacities(xs, cs, estimator)

    f = Fragility(median, beta, len(pairs), level=level, censored=int(np.sum(censored)), estimator=estimator,
                  beta_modelling=beta_modelling)
    if n_boot:
        f.median_ci, f.beta_ci, f.boot, f.boot_undetermined = bootstrap(
            refit, _groups(pairs, stations), n_boot, level, seed)
    f.gof = gof_capacities(capacities, censored, median, beta)
    return f


def msa_fragility(stripes, outcomes, n_boot=1000, level=0.9, seed=0, beta_modelling=0.0, stations=None):
    """Fragility from stripes: `outcomes` one row per record, collapsed (bool) at each
    intensity of `stripes` (nan where the run failed); bootstrap over records or stations."""
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
                fits[key] = fit_stripes(stripes, n, z)
            except (ValueError, OverflowError, FloatingPointError) as exc:
                fits[key] = exc
        if isinstance(fits[key], Exception):
            raise fits[key].with_traceback(None)
        return fits[key]

    n, z = counts(table)
    median, beta = fit_stripes(stripes, n, z)
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
