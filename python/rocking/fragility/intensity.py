"""Intensity measures of a ground-motion record: PGA, PGV, SA(T), the averaged spectral
acceleration AvgSA(T1-T2), the rocking-specific dimensionless PGA / (g tan alpha) and
PGV / (g tan alpha / p), and of the record's two horizontal components together, RotDnn
of PGA and of SA(T) (`rotd`).

    im = parse("SA(1.0)")           # or "PGA", "PGV", "AvgSA(0.5-2)", "PGA/gtana", "PGV/(gtana/p)",
                                    # "RotD50" (of PGA), "RotD100(SA(1.0))"
    value = im.of(record, alpha=0.2, g=9.81, p=1.57)

RotDnn of a Record is that of the pair of its record set (`groundmotion.pair_of`): every
horizontal component of one set gets the same value, so a suite of components (each one
ground motion of a planar study) is scaled set by set. The Record must be as read from its
file (unscaled): the pair is read from the file again and checked against it.

AvgSA(T1-T2) is the geometric mean of SA at 10 periods log-spaced from T1 to T2
(Eads et al. 2015). PGV / (g tan alpha / p), p = sqrt(W R0 / IO) the body's frequency
parameter (rad/s), is the velocity measure of rocking's dimensional analysis
(Dimitrakopoulos & DeJong 2012): g tan alpha / p is the ground velocity scale at
which a body of that size and slenderness responds alike.

Every measure here is proportional to the record's scale factor, so a target
intensity x is reached with the scale x / im.of(record).

SA(T) is the 5 %-damped pseudo-spectral acceleration omega² max|u| of a
linear oscillator u'' + 2 zeta omega u' + omega² u = -ag(t) starting at rest,
ag the record's piecewise-linear interpolation -- the input the FMU sees. The
recurrence of Nigam & Jennings (1968) is exact for that input: over one step
the state (u, u') maps linearly on itself and on the step's end values of ag.
Its matrices come here from the matrix exponential of the oscillator
augmented with (ag, dag/dt) rather than from the closed-form coefficients,
and the recurrence runs as a second-order IIR filter (scipy.signal.lfilter).
Our own rather than a package's: of the candidates, eqsig's
`pseudo_response_spectra` loops over time in Python, uses 2 pi = 6.2831853
and returns PGA for every T < 6 dt; pyRotd works in the frequency domain
(not exact for the piecewise-linear input, zero padding). The tests check
this one against the closed-form oscillator.
"""

import functools
import math
import re
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm
from scipy.signal import lfilter

from ..groundmotion.units import G

#: Damping ratio of the spectral accelerations.
ZETA = 0.05
#: Periods AvgSA averages over.
AVGSA_PERIODS = 10


def oscillator_matrices(period, dt, zeta=ZETA):
    """(A, B0, B1) of the exact step x[k+1] = A x[k] + B0 ag[k] + B1 ag[k+1], x = (u, u'),
    for ag linear over the step; period and dt in s."""
    w = 2 * math.pi / period
    m = np.array([[0.0, 1.0, 0.0, 0.0],
                  [-w * w, -2 * zeta * w, -1.0, 0.0],
                  [0.0, 0.0, 0.0, 1.0],
                  [0.0, 0.0, 0.0, 0.0]])
    e = expm(m * dt)
    a = e[:2, :2]
    e_acc, e_slope = e[:2, 2], e[:2, 3] / dt  # slope = (ag[k+1] - ag[k]) / dt
    return a, e_acc - e_slope, e_slope


def oscillator_displacement(acc, dt, period, zeta=ZETA):
    """Relative displacement u at the samples (m) of the oscillator of `period` (s) under
    ground acceleration `acc` (m/s², step dt, linear between samples), from rest."""
    acc = np.asarray(acc, dtype=float)
    a, b0, b1 = oscillator_matrices(period, dt, zeta)
    den = [1.0, -(a[0, 0] + a[1, 1]), a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]]

    def num(b):  # first row of adj(zI - A) times b, strictly proper in 1/z
        return [0.0, b[0], -a[1, 1] * b[0] + a[0, 1] * b[1]]

    ahead = np.append(acc[1:], acc[-1])  # ag[k+1] enters the step that starts at k
    return lfilter(num(b0), den, acc) + lfilter(num(b1), den, ahead)


def spectral_acceleration(acc, dt, period, zeta=ZETA):
    """Pseudo-spectral acceleration omega² max|u| (m/s²); period 0 gives the PGA."""
    if period == 0:
        return float(np.max(np.abs(acc)))
    if not period > 0:
        raise ValueError(f"SA period must be positive, got {period}")
    u = oscillator_displacement(acc, dt, period, zeta)
    return float((2 * math.pi / period) ** 2 * np.max(np.abs(u)))


@dataclass(frozen=True)
class IntensityMeasure:
    """One intensity measure. kind: 'PGA', 'PGV', 'SA', 'AvgSA', 'PGA/gtana',
    'PGV/(gtana/p)' or 'RotD'; period for SA, (period, period2) the range of AvgSA (s);
    for RotD, percentile (0-100) and period (s; 0 for PGA)."""

    kind: str
    period: float = math.nan
    period2: float = math.nan
    percentile: float = math.nan

    @property
    def name(self):
        if self.kind == "SA":
            return f"SA({self.period:g})"
        if self.kind == "AvgSA":
            return f"AvgSA({self.period:g}-{self.period2:g})"
        if self.kind == "RotD":
            return f"RotD{self.percentile:g}({self._rotd_of()})"
        return self.kind

    def _rotd_of(self):
        return "PGA" if self.period == 0 else f"SA({self.period:g})"

    @property
    def unit(self):
        return {"PGA": "g", "PGV": "m/s", "SA": "g", "AvgSA": "g", "PGA/gtana": "-", "PGV/(gtana/p)": "-",
                "RotD": "g"}[self.kind]

    @property
    def label(self):
        """Axis label."""
        if self.kind == "PGA/gtana":
            return "PGA / (g tan alpha)"
        if self.kind == "PGV/(gtana/p)":
            return "PGV / (g tan alpha / p)"
        if self.kind == "SA":
            return f"SA({self.period:g} s) ({self.unit})"
        if self.kind == "AvgSA":
            return f"AvgSA({self.period:g}-{self.period2:g} s) ({self.unit})"
        if self.kind == "RotD":
            of = "PGA" if self.period == 0 else f"SA({self.period:g} s)"
            return f"RotD{self.percentile:g} of {of} ({self.unit})"
        return f"{self.kind} ({self.unit})"

    def periods(self):
        """The periods (s) AvgSA averages over."""
        return np.geomspace(self.period, self.period2, AVGSA_PERIODS)

    def of(self, record, alpha=None, g=None, p=None):
        """Value for the unscaled `record` (a groundmotion Record, acc in m/s²; for RotD also
        a HorizontalPair). alpha (rad) and g (m/s², the body's) are needed for PGA/gtana,
        with p (rad/s) for PGV/(gtana/p)."""
        if self.kind == "RotD":
            from .rotd import rotd_sa
            try:
                pair = _pair(record)
            except ValueError as exc:
                raise ValueError(f"{self.name}: {exc}") from None
            return rotd_sa(pair, self.period, self.percentile) / G
        if self.kind == "PGA":
            return record.pga / G
        if self.kind == "PGV":
            return record.pgv
        if self.kind == "SA":
            return spectral_acceleration(record.acc, record.dt, self.period) / G
        if self.kind == "AvgSA":
            sa = [spectral_acceleration(record.acc, record.dt, t) for t in self.periods()]
            return float(np.exp(np.mean(np.log(sa)))) / G
        if alpha is None or g is None:
            raise ValueError(f"{self.kind} needs the body's alpha and g")
        if self.kind == "PGA/gtana":
            return record.pga / (g * math.tan(alpha))
        if p is None:
            raise ValueError("PGV/(gtana/p) needs the body's frequency parameter p")
        return record.pgv * p / (g * math.tan(alpha))


_AVGSA = re.compile(r"AVGSA\s*\(\s*(?:T\s*=\s*)?([0-9.eE+]+)\s*(?:-|,|:|TO)\s*([0-9.eE+]+)\s*S?\s*\)$",
                    re.IGNORECASE)
_SA = re.compile(r"SA\s*\(?\s*(?:T\s*=\s*)?([0-9.eE+-]+)\s*s?\s*\)?$", re.IGNORECASE)


_ROTD = re.compile(r"ROTD([0-9.]+)(?:\((.+)\))?$", re.IGNORECASE)


def _pair(motion):
    """The HorizontalPair of `motion`: itself, or the pair of a Record's set, whose component
    of the Record's label must hold the Record's samples (ValueError naming the file)."""
    from ..groundmotion.pair import HorizontalPair
    if isinstance(motion, HorizontalPair):
        return motion
    pair = _pair_of_file(str(motion.source), _mtime(motion.source))
    for rec in (pair.x, pair.y):
        if rec.component == motion.component:
            n = motion.npts
            if (abs(rec.dt - motion.dt) <= 1e-9 * motion.dt and rec.npts >= n
                    and np.array_equal(rec.acc[:n], motion.acc) and not np.any(rec.acc[n:])):
                return pair
            raise ValueError(f"{motion.source} [{motion.component}]: RotD needs the record as read from its "
                             "file (it differs: scaled or resampled?)")
    raise ValueError(f"{motion.source} [{motion.component}]: not a horizontal component of its pair "
                     f"([{pair.x.component}], [{pair.y.component}])")


def _mtime(path):
    import os
    try:
        return os.stat(path).st_mtime_ns
    except OSError:
        return None


@functools.lru_cache(maxsize=64)
def _pair_of_file(path, mtime):
    from ..groundmotion.pair import pair_of
    del mtime  # part of the cache key: a file changed on disk is read again
    return pair_of(path)


def parse(text):
    """IntensityMeasure of 'PGA', 'PGV', 'SA(1.0)' (also 'SA1', 'sa(T=0.5s)'), 'AvgSA(0.5-2)',
    'PGA/gtana', 'PGV/(gtana/p)', 'RotD50' (of PGA, also 'RotD50(PGA)') or
    'RotD100(SA(1.0))' (any percentile 0-100); ValueError naming the choices otherwise."""
    t = text.strip()
    key = t.upper().replace(" ", "")
    m = _ROTD.match(key)
    if m:
        try:
            pct = float(m.group(1))
        except ValueError:
            pct = math.nan
        inner = IntensityMeasure("PGA") if m.group(2) is None else None
        if inner is None:
            try:
                inner = parse(m.group(2))
            except ValueError:
                inner = None
        if 0 <= pct <= 100 and inner is not None and inner.kind in ("PGA", "SA"):
            return IntensityMeasure("RotD", 0.0 if inner.kind == "PGA" else inner.period, percentile=pct)
        raise ValueError(f"intensity measure {text!r}: expected RotDnn, RotDnn(PGA) or RotDnn(SA(T)) "
                         "with nn in [0, 100] and T > 0 in s")
    if key in ("PGA", "PGV"):
        return IntensityMeasure(key)
    if key in ("PGA/GTANA", "PGA/GTAN(ALPHA)", "PGA/(GTANALPHA)", "PGA/(GTANA)"):
        return IntensityMeasure("PGA/gtana")
    if key in ("PGV/(GTANA/P)", "PGVP/GTANA", "PGV*P/(GTANA)", "PGV/(GTAN(ALPHA)/P)"):
        return IntensityMeasure("PGV/(gtana/p)")
    m = _AVGSA.match(t.replace(" ", ""))
    if m:
        try:
            t1, t2 = float(m.group(1)), float(m.group(2))
        except ValueError:
            t1 = t2 = math.nan
        if 0 < t1 < t2:
            return IntensityMeasure("AvgSA", t1, t2)
    m = _SA.match(t)
    if m:
        try:
            period = float(m.group(1))
        except ValueError:
            period = math.nan
        if period > 0:
            return IntensityMeasure("SA", period)
    raise ValueError(f"intensity measure {text!r}: expected PGA, PGV, SA(T) with T > 0 in s, "
                     "AvgSA(T1-T2) with 0 < T1 < T2, PGA/gtana, PGV/(gtana/p), RotDnn (of PGA) "
                     "or RotDnn(SA(T))")
