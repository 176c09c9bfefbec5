"""Risk from a fragility and a hazard curve: the mean annual frequency (MAF) of collapse,
the probability of collapse in a number of years, and the collapse margin ratio.

    hazard = read_hazard("hazard.csv")          # intensity, annual frequency of exceedance
    maf = collapse_frequency(fragility, hazard)  # lambda_c = integral of P(C | x) |d lambda(x)|

lambda_c = integral of lambda(x) f(x) dx (by parts), f the fragility's density: the
hazard is interpolated linearly in log-log between its points and extended beyond
them along its end segments, so it is a power law lambda_i (x / x_i)^-k_i on each
segment and on the two unbounded ends, and the integral is a sum of closed forms, one per
segment: lambda_i (x_i / median)^k_i exp(k_i² beta² / 2) [Phi(z_i+1 + k_i beta) -
Phi(z_i + k_i beta)], z = ln(x / median) / beta. No range is cut off: the
hazard-weighted density, centred at ln median - k beta², is counted wherever it lies (a
fixed range of +-8 beta in ln x under-counted by 2.3 % at k = 4, beta = 1.5). For a single
power law lambda(x) = k0 x^-k it is lambda_c = k0 median^-k exp(k² beta² / 2).
P(collapse in t years) = 1 - exp(-lambda_c t), the Poisson model. The collapse margin ratio (FEMA P695) is the median over the MCE
intensity.
"""

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.special import log_ndtr, ndtr


@dataclass(frozen=True)
class Hazard:
    """Intensities x (increasing, > 0) and their annual frequencies of exceedance (> 0, decreasing)."""

    x: np.ndarray
    frequency: np.ndarray

    def __call__(self, x):
        """lambda(x), log-log interpolation, power-law extension beyond the ends."""
        lx, lf = np.log(self.x), np.log(self.frequency)
        u = np.log(np.asarray(x, dtype=float))
        inside = np.interp(u, lx, lf)
        lo = lf[0] + (u - lx[0]) * (lf[1] - lf[0]) / (lx[1] - lx[0])
        hi = lf[-1] + (u - lx[-1]) * (lf[-1] - lf[-2]) / (lx[-1] - lx[-2])
        return np.exp(np.where(u < lx[0], lo, np.where(u > lx[-1], hi, inside)))


def hazard_from(x, frequency, where="hazard"):
    """A Hazard, checked: at least two points, x increasing and positive, frequencies positive
    and not increasing. ValueError naming `where` otherwise."""
    x, f = np.asarray(x, dtype=float), np.asarray(frequency, dtype=float)
    if x.size < 2 or x.size != f.size:
        raise ValueError(f"{where}: needs at least two (intensity, frequency) points")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(f)) and np.all(x > 0) and np.all(f > 0)):
        raise ValueError(f"{where}: intensities and frequencies must be finite and positive")
    if not np.all(np.diff(x) > 0):
        raise ValueError(f"{where}: intensities must increase")
    if np.any(np.diff(f) > 0):
        raise ValueError(f"{where}: annual frequencies of exceedance must not increase with the intensity")
    return Hazard(x, f)


def read_hazard(path):
    """A Hazard from a CSV of two columns, intensity and annual frequency of exceedance (a
    header line is skipped if it is not numeric; '#' lines are comments)."""
    path = Path(path)
    rows = []
    try:
        text = path.read_text()
    except OSError as exc:
        raise ValueError(f"{path}: cannot read ({exc.strerror or exc})") from None
    for n, line in enumerate(csv.reader(text.splitlines()), 1):
        if not line or not "".join(line).strip() or line[0].lstrip().startswith("#"):
            continue
        try:
            rows.append((float(line[0]), float(line[1])))
        except (ValueError, IndexError):
            if rows:
                raise ValueError(f"{path}:{n}: expected two numbers, intensity and annual frequency") from None
    return hazard_from(*zip(*rows), where=str(path)) if rows else hazard_from([], [], str(path))


def _log_mass(a, b):
    """ln(Phi(b) - Phi(a)) for a < b (either may be infinite), accurate in both tails."""
    if a >= 0:  # upper tail: Phi(-a) - Phi(-b)
        a, b = -b, -a
    hi, lo = log_ndtr(b), log_ndtr(a)
    return hi + math.log1p(-math.exp(lo - hi)) if lo < hi else -math.inf


def collapse_frequency(median, beta, hazard):
    """Mean annual frequency of collapse, integral of lambda(x) f(x) dx (f the lognormal
    density of median, beta), in closed form on each power-law segment of the hazard and on
    its two power-law extensions."""
    lx, lf = np.log(hazard.x), np.log(hazard.frequency)
    k = -np.diff(lf) / np.diff(lx)  # the segments' slopes, >= 0
    k = np.concatenate([k[:1], k, k[-1:]])  # the ends extend the end segments
    anchor = np.concatenate([lx[:1], lx])  # a point of each piece: lambda = exp(lf) there
    level = np.concatenate([lf[:1], lf])
    z = np.concatenate([[-math.inf], (lx - math.log(median)) / beta, [math.inf]])
    total = 0.0
    for i in range(k.size):
        kb = k[i] * beta
        log_term = (level[i] + k[i] * (anchor[i] - math.log(median)) + 0.5 * kb * kb
                    + _log_mass(z[i] + kb, z[i + 1] + kb))
        total += math.exp(log_term)
    return total


def outside_range(median, beta, hazard):
    """The fragility's probability mass outside the hazard curve's intensities (where the
    power-law extension was used)."""
    lo = ndtr(math.log(hazard.x[0] / median) / beta)
    hi = 1 - ndtr(math.log(hazard.x[-1] / median) / beta)
    return float(lo + hi)


def in_years(maf, years=50.0):
    """Probability of at least one collapse in `years` (Poisson)."""
    return -math.expm1(-maf * years)


def margin_ratio(median, mce):
    """Collapse margin ratio: the median collapse intensity over the MCE intensity."""
    return median / mce


def risk(fragility, hazard, mce=None, years=50.0):
    """{maf, p_years, years, cmr (None without mce), outside} of a Fragility (its beta_total)."""
    b = fragility.beta_total
    maf = collapse_frequency(fragility.median, b, hazard)
    return dict(maf=maf, p_years=in_years(maf, years), years=years,
                cmr=None if mce is None else margin_ratio(fragility.median, mce),
                outside=outside_range(fragility.median, b, hazard))
