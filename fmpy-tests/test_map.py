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
