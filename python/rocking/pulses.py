"""Pulses as ground motions: closed-form ground accelerations ag(t) (m/s2) of amplitude a_p
and frequency w_p (rad/s, period T_p = 2 pi / w_p), starting at t = 0 and zero after their
duration (the free tail). Formulas and sources: docs/maps.md, "Pulses".

    from rocking.pulses import Pulse
    p = Pulse("one-sine", amplitude=2.0, frequency=6.0)
    t, ag = p.samples()                       # equally spaced, for RockingFMU.simulate(ag=...)
    run = fmu.simulate(params, ag=(t, ag), stop_time=p.duration + 5.0)

Shapes (tau = t / T_p):
- rectangular: ag = a_p for 0 <= t < t_d, t_d = T_p / 2 = pi / w_p (Housner 1963);
- one-sine: ag = a_p sin(w_p t), 0 <= t <= T_p (Zhang & Makris 2001, type A);
- one-cosine: ag = a_p cos(w_p t), 0 <= t <= T_p (Zhang & Makris 2001, type B);
- ricker: the symmetric Ricker wavelet a_p (1 - w_p^2 s^2 / 2) exp(-w_p^2 s^2 / 4),
  s = t - t_c (Vassiliou & Makris 2012), its Fourier amplitude largest at w_p;
- ricker-antisymmetric: a_p x (x^2 - 3) exp(-x^2 / 2) / c, x = w_p s / sqrt(3), c its peak
  (1.3801; the published beta = 1.38), minus the third derivative of a Gaussian, its Fourier
  amplitude largest at w_p: Vassiliou & Makris (2012)'s (a_p / beta) (4 pi^2 s^2 / (3 T_p^2) - 3)
  (2 pi s / (sqrt(3) T_p)) exp(-2 pi^2 s^2 / (3 T_p^2)), its sign included (a small negative
  lobe, then the large positive, the large negative, a small positive);
- user: a shape from a CSV file (tau, value), scaled to peak |value| = 1 (`read_shape`).
The Ricker wavelets are centred at t_c = RICKER_HALF_WIDTH T_p and cut to [0, 2 t_c], where
their envelope is below 1e-8 of the peak.
"""

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

SHAPES = ("rectangular", "one-sine", "one-cosine", "ricker", "ricker-antisymmetric", "user")

#: Half-width of the Ricker wavelets' window, in periods T_p: exp(-w^2 s^2/6) < 1e-8 beyond.
RICKER_HALF_WIDTH = 2.0

#: x of the antisymmetric wavelet's peak, |x (x^2 - 3)| exp(-x^2/2) largest: x^4 - 6 x^2 + 3 = 0.
_X_PEAK = math.sqrt(3.0 - math.sqrt(6.0))
_ANTI_PEAK = _X_PEAK * (3.0 - _X_PEAK ** 2) * math.exp(-_X_PEAK ** 2 / 2.0)


def read_shape(path):
    """(tau, value) of a user's pulse shape: a CSV of two numeric columns (a header row and
    '#' comments allowed), tau = t / T_p increasing from 0, value scaled to peak |value| = 1.
    ValueError naming the file when it holds no pulse."""
    path = Path(path)
    rows = []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        cells = [c.strip() for c in text.split(",")]
        try:
            values = [float(c) for c in cells[:2]]
        except ValueError:
            if rows:
                raise ValueError(f"{path}: line {number}: not two numbers ({text!r})") from None
            continue  # the header row
        if len(values) < 2:
            raise ValueError(f"{path}: line {number}: expected two columns tau, value ({text!r})")
        rows.append(values)
    if len(rows) < 2:
        raise ValueError(f"{path}: no pulse: expected at least two rows of tau = t/T_p, value")
    tau, value = np.array(rows).T
    if not np.all(np.isfinite(tau)) or not np.all(np.isfinite(value)):
        raise ValueError(f"{path}: a value is not finite")
    if abs(tau[0]) > 1e-12 or np.any(np.diff(tau) <= 0):
        raise ValueError(f"{path}: tau (the first column, t / T_p) must start at 0 and increase")
    peak = float(np.max(np.abs(value)))
    if peak == 0.0:
        raise ValueError(f"{path}: no pulse: every value is 0")
    return tau, value / peak


@dataclass(frozen=True)
class Pulse:
    """A pulse: shape (one of SHAPES), amplitude a_p (m/s2, the peak |ag|), frequency w_p
    (rad/s); `user` the (tau, value) of shape "user" (`read_shape`)."""

    shape: str
    amplitude: float
    frequency: float
    user: tuple = None

    def __post_init__(self):
        if self.shape not in SHAPES:
            raise ValueError(f"pulse shape {self.shape!r}: not one of {', '.join(SHAPES)}")
        if not (math.isfinite(self.frequency) and self.frequency > 0):
            raise ValueError(f"pulse frequency w_p = {self.frequency!r}: must be finite and > 0 rad/s")
        if not math.isfinite(self.amplitude):
            raise ValueError(f"pulse amplitude a_p = {self.amplitude!r}: must be finite (m/s2)")
        if (self.shape == "user") != (self.user is not None):
            raise ValueError("pulse shape 'user' needs its (tau, value) shape, and only it")

    @property
    def period(self):
        """T_p = 2 pi / w_p, s."""
        return 2.0 * math.pi / self.frequency

    @property
    def duration(self):
        """s: where the pulse ends and the free tail begins."""
        T = self.period
        return {"rectangular": T / 2.0, "one-sine": T, "one-cosine": T,
                "ricker": 2.0 * RICKER_HALF_WIDTH * T, "ricker-antisymmetric": 2.0 * RICKER_HALF_WIDTH * T,
                }.get(self.shape) or float(self.user[0][-1]) * T

    def acceleration(self, t):
        """ag(t) in m/s2 (t in s, array or number); 0 before 0 and after `duration`."""
        t = np.asarray(t, dtype=float)
        w, a, end = self.frequency, self.amplitude, self.duration
        inside = (t >= 0.0) & (t <= end)
        if self.shape == "rectangular":
            shape = np.where(t < end, 1.0, 0.0)
        elif self.shape == "one-sine":
            shape = np.sin(w * t)
        elif self.shape == "one-cosine":
            shape = np.cos(w * t)
        elif self.shape == "ricker":
            s = t - end / 2.0
            shape = (1.0 - (w * s) ** 2 / 2.0) * np.exp(-(w * s) ** 2 / 4.0)
        elif self.shape == "ricker-antisymmetric":
            x = w * (t - end / 2.0) / math.sqrt(3.0)
            shape = x * (x ** 2 - 3.0) * np.exp(-x ** 2 / 2.0) / _ANTI_PEAK
        else:
            shape = np.interp(t / self.period, *self.user)
        return np.where(inside, a * shape, 0.0)

    def samples(self, per_period=400):
        """(t, ag): the pulse sampled every T_p / per_period (s, m/s2), from 0 to its end, for
        RockingFMU.simulate(ag=...), which steps at these samples and sees their linear
        interpolation. The rectangular pulse's step down falls midway between two samples,
        so that the ramp between them keeps the pulse's impulse a_p t_d exactly; the ramp
        still errs by O(dt^2) (a rigid block's least overturning amplitude by 9e-7 relative
        at 400 samples per period, 2.4e-4 at 20: fmpy-tests/test_map.py)."""
        if self.shape == "rectangular":
            n = max(2, int(round(per_period / 2)))
            dt = self.duration / (n + 0.5)
            t = np.arange(n + 2) * dt
            return t, np.where(np.arange(n + 2) <= n, self.amplitude, 0.0)
        n = max(8, int(math.ceil(self.duration / self.period * per_period)))
        t = np.linspace(0.0, self.duration, n + 1)
        return t, self.acceleration(t)


def pulse_velocity_change(pulse):
    """The ground velocity at the pulse's end, m/s (closed form where there is one):
    a_p t_d for the rectangular pulse, 0 for the others but a user's (numerical)."""
    if pulse.shape == "rectangular":
        return pulse.amplitude * pulse.duration
    if pulse.shape == "user":
        t, a = pulse.samples(4000)
        return float(np.trapezoid(a, t))
    return 0.0
