"""RotDnn intensity measures of two horizontal components (Boore 2010): the nn-th
percentile, over azimuths, of the peak of the component along the azimuth.

    rotd_pga(pair, 50)          # RotD50 of PGA, m/s²; pair a groundmotion.HorizontalPair
    rotd_sa(pair, 1.0, 100)     # RotD100 of SA(1 s), 5 % damped, m/s²

For the PGA the component along azimuth a is x cos a + y sin a; for SA(T) it is the
response u_x cos a + u_y sin a of the oscillator under that component, because the
oscillator is linear: each of u_x, u_y is computed once, exactly for the piecewise-linear
input (`intensity.oscillator_displacement`), and every azimuth is a sum of the two.

- RotD100 is the peak over *all* azimuths, which at each sample is the norm
  sqrt(x² + y²): RotD100 = max_t sqrt(x² + y²), exact, no azimuth sampled.
- Other percentiles are taken over the azimuths 0, 1, ..., 179 degrees (`STEP_DEG`, as
  Boore 2010; a and a + 180 give one peak) with numpy's linear interpolation: RotD50 is
  the mean of the 90th and 91st of the 180 sorted peaks.

Our own rather than pyrotd's (0.6.1, `calc_rotated_spec_accels`): pyrotd computes the
oscillator's response by the FFT of the record as it is, so the response is periodic over
the record's length and not exact for the piecewise-linear input the FMU sees (its
RotD100 of one component would not equal this package's SA of it); it takes RotD100 over
the sampled azimuths too (up to a factor cos(0.5 deg) low); it imports pkg_resources and
maps the periods over a multiprocessing pool of all cores but one by default, unwelcome in
a Dask worker. Its rotation, given the responses, is the same few lines of numpy as here.
"""

import math

import numpy as np

from .intensity import ZETA, oscillator_displacement

#: Step of the azimuths (degrees) over which percentiles below 100 are taken.
STEP_DEG = 1.0
#: Samples per block when all azimuths' rotated components are formed at once (memory).
_BLOCK = 4096


def azimuths(step_deg=STEP_DEG):
    """Azimuths 0, step, ..., < 180 (degrees); 180 / step must be a whole number."""
    count = 180.0 / step_deg
    if not step_deg > 0 or abs(count - round(count)) > 1e-9:
        raise ValueError(f"step_deg must divide 180 degrees, got {step_deg}")
    return np.arange(int(round(count))) * step_deg


def rotated_peaks(x, y, azimuths_deg):
    """max_t |x cos a + y sin a| for each azimuth a (degrees); x, y sampled together."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if x.shape != y.shape or x.ndim != 1:
        raise ValueError(f"x {x.shape} and y {y.shape} must be 1-D of one length")
    rad = np.radians(np.asarray(azimuths_deg, dtype=float))
    c, s = np.cos(rad)[:, None], np.sin(rad)[:, None]
    peaks = np.zeros(rad.size)
    for start in range(0, x.size, _BLOCK):
        block = np.abs(c * x[None, start:start + _BLOCK] + s * y[None, start:start + _BLOCK])
        peaks = np.maximum(peaks, block.max(axis=1))
    return peaks


def rotd(x, y, percentile, step_deg=STEP_DEG):
    """RotD of two perpendicular signals: the `percentile` (0-100) over azimuths of the peak
    of x cos a + y sin a; 100 exactly (max_t sqrt(x² + y²)), others over `azimuths(step_deg)`."""
    if not 0 <= percentile <= 100:
        raise ValueError(f"RotD percentile must be in [0, 100], got {percentile}")
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if percentile == 100:
        return float(np.sqrt(np.max(x * x + y * y)))
    return float(np.percentile(rotated_peaks(x, y, azimuths(step_deg)), percentile))


def rotd_pga(pair, percentile, step_deg=STEP_DEG):
    """RotDnn of the peak ground acceleration of a HorizontalPair, m/s²."""
    return rotd(pair.x.acc, pair.y.acc, percentile, step_deg)


def rotd_sa(pair, period, percentile, zeta=ZETA, step_deg=STEP_DEG):
    """RotDnn of the pseudo-spectral acceleration omega² max|u| (m/s²) at `period` (s) of a
    HorizontalPair; period 0 gives `rotd_pga`."""
    if period == 0:
        return rotd_pga(pair, percentile, step_deg)
    if not period > 0:
        raise ValueError(f"SA period must be positive, got {period}")
    ux = oscillator_displacement(pair.x.acc, pair.dt, period, zeta)
    uy = oscillator_displacement(pair.y.acc, pair.dt, period, zeta)
    return (2 * math.pi / period) ** 2 * rotd(ux, uy, percentile, step_deg)
