"""The `Record` of one acceleration component, and the format error."""

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .orientation import HORIZONTAL, VERTICAL
from .units import G


class GroundMotionFormatError(ValueError):
    """A file does not follow its format.

    The message names the file, the line (1-based) and what was expected there,
    e.g. "rec.V2: line 27: expected 8 numbers of width 10, found 'abc'".
    `path` and `line` are kept as attributes (either may be None).
    """

    def __init__(self, message, path=None, line=None):
        self.path = None if path is None else str(path)
        self.line = line
        where = [p for p in (self.path, None if line is None else f"line {line}") if p]
        super().__init__(": ".join(where + [message]))


class GroundMotionWarning(UserWarning):
    """A file reads, but something in it deserves a look: an implausible peak, a shifted time."""


#: Peak ground acceleration beyond which a record is taken for a units mistake, in g. The
#: largest peaks ever recorded are about 4 g (2008 Iwate-Miyagi, station IWTH25, 3.9 g
#: vertical); a file of cm/s² values read as g gives hundreds of g.
PLAUSIBLE_PGA_G = 5.0


@dataclass(eq=False)
class Record:
    """One component of a ground-acceleration record, sampled at a constant step.

    time           sample times in s, starting at 0 (time[i] = i * dt)
    acc            ground acceleration in m/s², converted from the file's units
    dt             time step in s
    name           station / event description taken from the file
    component      component label as the file gives it ("N28W", "360", "UP", ...)
    units_in_file  canonical name of the units the file's numbers are in ("g", "cm/s2", ...)
    source         path of the file read
    notes          free text: provenance, caveats (e.g. that a record is synthetic)
    orientation    "horizontal" or "vertical", from the file's header (see `orientation`)
    av_record      the vertical component that goes with this horizontal one as the FMU's
                   input av (a Record, e.g. `recordset.vertical_of(self)`), or None: no av;
                   `scaled` scales it by the same factor
    """

    time: np.ndarray
    acc: np.ndarray
    dt: float
    name: str = ""
    component: str = ""
    units_in_file: str = "m/s2"
    source: str = ""
    notes: str = ""
    orientation: str = HORIZONTAL
    av_record: "Record" = None

    def __post_init__(self):
        self.time = np.asarray(self.time, dtype=float)
        self.acc = np.asarray(self.acc, dtype=float)
        self.dt = float(self.dt)
        if self.time.shape != self.acc.shape or self.acc.ndim != 1:
            raise ValueError(f"time {self.time.shape} and acc {self.acc.shape} must be 1-D of one length")
        if not self.dt > 0:
            raise ValueError(f"dt must be positive, got {self.dt}")
        if self.orientation not in (HORIZONTAL, VERTICAL):
            raise ValueError(f"orientation must be {HORIZONTAL!r} or {VERTICAL!r}, got {self.orientation!r}")

    @property
    def vertical(self):
        """Whether the file says this component is the vertical one."""
        return self.orientation == VERTICAL

    @classmethod
    def from_samples(cls, acc, dt, **meta):
        """Record from accelerations in m/s² at step dt (s); time = 0, dt, 2 dt, ..."""
        acc = np.asarray(acc, dtype=float)
        return cls(time=np.arange(acc.size) * float(dt), acc=acc, dt=dt, **meta)

    @property
    def npts(self):
        """Number of samples."""
        return self.acc.size

    @property
    def duration(self):
        """Time of the last sample, s: (npts - 1) * dt."""
        return (self.npts - 1) * self.dt

    @property
    def pga(self):
        """Peak ground acceleration, max |acc|, in m/s²."""
        return float(np.max(np.abs(self.acc)))

    @property
    def pga_g(self):
        """Peak ground acceleration in g (g = 9.80665 m/s²)."""
        return self.pga / G

    @property
    def velocity(self):
        """Ground velocity in m/s: trapezoidal integral of acc from v(0) = 0."""
        increments = 0.5 * (self.acc[1:] + self.acc[:-1]) * self.dt
        return np.concatenate(([0.0], np.cumsum(increments)))

    @property
    def pgv(self):
        """Peak ground velocity, max |velocity|, in m/s (trapezoidal integration of acc)."""
        return float(np.max(np.abs(self.velocity)))

    def implausible(self):
        """Why this record is implausible as a ground motion (a sentence), or None."""
        if self.pga_g > PLAUSIBLE_PGA_G:
            return (f"PGA {self.pga_g:.3g} g, beyond the {PLAUSIBLE_PGA_G:g} g of any recorded ground motion "
                    f"(the largest are about 4 g): are the units ({self.units_in_file}) right?")
        return None

    def scaled(self, factor):
        """Copy with the acceleration multiplied by `factor` (PGA scales by |factor|)."""
        note = f"scaled by {factor:g}"
        av = None if self.av_record is None else self.av_record.scaled(factor)
        return dataclasses.replace(self, acc=self.acc * factor, notes=_join(self.notes, note), av_record=av)

    def resampled(self, dt):
        """Copy sampled at step `dt` (s) by linear interpolation over [0, duration].

        No anti-alias filtering: going to a coarser step keeps the interpolated
        values only, so the PGA may drop.
        """
        dt = float(dt)
        n = int(np.floor(self.duration / dt * (1 + 1e-12))) + 1
        time = np.arange(n) * dt
        acc = np.interp(time, self.time, self.acc)
        note = f"resampled from dt = {self.dt:g} s to {dt:g} s (linear interpolation)"
        av = None if self.av_record is None else self.av_record.resampled(dt)
        return dataclasses.replace(self, time=time, acc=acc, dt=dt, notes=_join(self.notes, note), av_record=av)

    def to_csv(self, path):
        """Write `#` comment lines (name, component, source, notes), the header
        `time_s,acc_m/s2` and one `time,acc` row per sample (s, m/s²)."""
        lines = [f"# name: {self.name}", f"# component: {self.component}", f"# source: {self.source}"]
        lines += [f"# notes: {line}" for line in self.notes.splitlines() if line.strip()]
        lines.append("time_s,acc_m/s2")
        lines += [f"{t:.10g},{a:.10e}" for t, a in zip(self.time, self.acc)]
        Path(path).write_text("\n".join(lines) + "\n")

    def __repr__(self):
        return (f"Record(name={self.name!r}, component={self.component!r}, npts={self.npts}, "
                f"dt={self.dt:g} s, pga={self.pga_g:.3f} g, source={self.source!r})")


def _join(notes, more):
    return f"{notes}\n{more}" if notes else more
