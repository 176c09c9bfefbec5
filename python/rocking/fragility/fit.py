"""Lognormal fragility P(collapse | IM = x) = Phi(ln(x / median) / beta), fitted by maximum
likelihood (Baker 2015, "Efficient analytical fragility function fitting using dynamic
structural analysis data", Earthquake Spectra 31(1)).

- from IDA: the records' collapse intensities, some right-censored (no collapse up to the
  highest intensity run): density for the others, survival for the censored;
- from multiple stripes: z of n records collapsed at intensity x_j, binomial likelihood;
- a bootstrap over the records (resampled with replacement) for an interval on both.
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.special import log_ndtr, ndtr

_LOG_SQRT_2PI = 0.5 * math.log(2 * math.pi)


@dataclass
class Fragility:
    """median (IM units), beta (dispersion of ln IM), n records, and the bootstrap's
    (lo, hi) intervals of both at `level` (nan without a bootstrap)."""

    median: float
    beta: float
    n: int
    median_ci: tuple = (math.nan, math.nan)
    beta_ci: tuple = (math.nan, math.nan)
    level: float = 0.9
    censored: int = 0

    def probability(self, x):
        return ndtr(np.log(np.asarray(x, dtype=float) / self.median) / self.beta)


def _maximize(nll, mu0, beta0):
    res = minimize(lambda p: nll(p[0], math.exp(p[1])), [mu0, math.log(max(beta0, 1e-3))],
                   method="BFGS", options=dict(gtol=1e-9))
    return math.exp(res.x[0]), math.exp(res.x[1])


def fit_capacities(capacities, censored=None):
    """(median, beta) from collapse intensities; censored[i] True where capacities[i] is
    only a lower bound. Without censoring this is the mean and the (1/n) standard deviation
    of ln x. ValueError if no record collapsed."""
    x = np.log(np.asarray(capacities, dtype=float))
    c = np.zeros(x.size, bool) if censored is None else np.asarray(censored, bool)
    if c.all() or x.size == 0:
        raise ValueError("no record collapsed: no fragility can be fitted")
    if not c.any():
        return math.exp(x.mean()), float(x.std()) if x.size > 1 else math.nan
    xs, xc = x[~c], x[c]

    def nll(mu, beta):
        zs = (xs - mu) / beta
        return (0.5 * zs @ zs + xs.size * (math.log(beta) + _LOG_SQRT_2PI)
                - log_ndtr(-(xc - mu) / beta).sum())

    return _maximize(nll, x.mean(), max(x.std(), 0.1))


def fit_stripes(im, n, collapsed):
    """(median, beta) from stripes: at intensity im[j], collapsed[j] of n[j] records collapsed.
    ValueError when the counts cannot fix both (all zero, or all collapsed)."""
    im, n, z = (np.asarray(v, dtype=float) for v in (im, n, collapsed))
    if z.sum() == 0 or z.sum() == n.sum():
        raise ValueError("stripes all standing or all collapsed: no fragility can be fitted")
    x = np.log(im)

    def nll(mu, beta):
        s = (x - mu) / beta
        return -(z @ log_ndtr(s) + (n - z) @ log_ndtr(-s))

    frac = z / n
    mid = np.interp(0.5, np.maximum.accumulate(frac), x) if frac.max() >= 0.5 else x.max()
    return _maximize(nll, mid, 0.4)


def bootstrap(fit, groups, n_boot=1000, level=0.9, seed=0):
    """(median_ci, beta_ci) of `fit(sample)` over `n_boot` resamples (with replacement) of
    `groups` (one item per record); resamples the fit refuses are skipped."""
    rng = np.random.default_rng(seed)
    medians, betas = [], []
    for _ in range(n_boot):
        pick = rng.integers(0, len(groups), len(groups))
        try:
            m, b = fit([groups[i] for i in pick])
        except ValueError:
            continue
        if math.isfinite(m) and math.isfinite(b):
            medians.append(m)
            betas.append(b)
    if len(medians) < 10:
        return (math.nan, math.nan), (math.nan, math.nan)
    q = [(1 - level) / 2 * 100, (1 + level) / 2 * 100]
    return tuple(np.percentile(medians, q)), tuple(np.percentile(betas, q))


def ida_fragility(capacities, censored, n_boot=1000, level=0.9, seed=0):
    """Fragility (with a bootstrap over records) from IDA collapse intensities."""
    pairs = list(zip(capacities, censored))
    median, beta = fit_capacities(capacities, censored)

    def refit(sample):
        xs, cs = zip(*sample)
        return fit_capacities(xs, cs)

    m_ci, b_ci = bootstrap(refit, pairs, n_boot, level, seed) if n_boot else ((math.nan,) * 2, (math.nan,) * 2)
    return Fragility(median, beta, len(pairs), m_ci, b_ci, level, int(np.sum(censored)))


def msa_fragility(stripes, outcomes, n_boot=1000, level=0.9, seed=0):
    """Fragility from stripes: `outcomes` one row per record, collapsed (bool) at each
    intensity of `stripes` (nan where the run failed); bootstrap over records."""
    stripes = np.asarray(stripes, dtype=float)
    table = np.asarray(outcomes, dtype=float)

    def refit(rows):
        rows = np.asarray(rows, dtype=float)
        ok = ~np.isnan(rows)
        return fit_stripes(stripes, ok.sum(axis=0), np.nansum(rows, axis=0))

    median, beta = refit(table)
    m_ci, b_ci = bootstrap(refit, list(table), n_boot, level, seed) if n_boot else ((math.nan,) * 2, (math.nan,) * 2)
    return Fragility(median, beta, len(table), m_ci, b_ci, level)
