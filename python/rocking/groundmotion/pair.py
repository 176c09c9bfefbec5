"""Both horizontal components of a record set as one ground motion, and their rotation.

    pair = pair_of("data/ground-motions/geonet-kaikoura-2016/20161113_110259_WTMC_20.V2A")
    pair.x, pair.y, pair.vertical      # Records on one time base (acc in m/s²)
    turned = pair.rotated(30.0)        # the components along 30 degrees and along 120 degrees
    rec = pair.along(pair.peak_azimuth())   # one Record, for today's planar runs

**Axes.** x is the first horizontal component, y the second, and the pair is ordered so
that y points 90 degrees counterclockwise from x seen from above: (x, y, up) is a
right-handed frame, the frame of a model with z up. When both components' labels give a
compass bearing (360, 090, N28W, S62W, NS, EW, HNE, ...) the pair is put in that order
(N and E give x = E, y = N; 360 and 270 give x = N, y = W), `bearing_x` is the compass
bearing of x, and components that are not perpendicular (beyond 1 degree) are refused.
When a label gives no bearing the components are taken in the order given, and the pair's
notes say that the frame's sense is then not known.

**Azimuth.** An azimuth a (degrees) is measured from the x axis towards the y axis:
counterclockwise seen from above, so its compass bearing is `bearing_x - a` (clockwise
from north). The component along a is x cos a + y sin a; `rotated(a)` gives it as the new
x and the component along a + 90 degrees, -x sin a + y cos a, as the new y (the same
sense of rotation as the pair). A rotation is exact: multiples of 90 degrees use exact
cosines and sines, others those of numpy, so rotating by a then b is rotating by a + b to
round-off, and the norm sqrt(x² + y²) of each sample does not change.

**One time base.** Each Record's samples are at i dt from 0. Components of one set read
from one file share dt, but their lengths may differ by a few samples (the Coalinga V2:
3251 and 3250; the Loma Prieta SMC files: 6001, 6002 and 6004): the shorter are padded
with zeros at the end to the longest, and the pair's notes say by how many samples.
Components of different dt are resampled to the smallest dt by linear interpolation
(`Record.resampled`, which is what the FMU sees between samples anyway), noted too.
"""

import dataclasses
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .record import Record
from .recordset import components

#: Largest departure from 90 degrees (degrees) of two components' bearings taken as
#: perpendicular; instruments are set to a degree or better.
PERPENDICULAR_TOLERANCE_DEG = 1.0
#: Relative difference of two steps dt taken as one step.
DT_TOLERANCE = 1e-9

_QUADRANT = re.compile(r"^([NS])(\d+(?:\.\d+)?)([EW])$")
_NUMBER = re.compile(r"^\d+(?:\.\d+)?$")


def bearing(label):
    """Compass bearing in degrees (clockwise from north, in [0, 360)) that a horizontal
    component's label names, or None: "360", "090", "0" (digits, up to 360); "N28W",
    "S62E" (quadrant); "N", "NS", "E", "EW"; SEED channel codes ending in N or E ("HNE")."""
    s = re.sub(r"[\s_-]+", "", str(label)).upper()
    if _NUMBER.match(s):
        value = float(s)
        return value % 360.0 if value <= 360.0 else None
    m = _QUADRANT.match(s)
    if m:
        ns, angle, ew = m.group(1), float(m.group(2)), m.group(3)
        if angle > 90.0:
            return None
        return {("N", "E"): angle, ("N", "W"): 360.0 - angle,
                ("S", "E"): 180.0 - angle, ("S", "W"): 180.0 + angle}[ns, ew] % 360.0
    if s in ("N", "NS", "NORTH") or re.fullmatch(r"[A-Z]{2}N", s):
        return 0.0
    if s in ("E", "EW", "EAST") or re.fullmatch(r"[A-Z]{2}E", s):
        return 90.0
    return None


def cos_sin(azimuth_deg):
    """(cos a, sin a) of an angle in degrees, exact at multiples of 90 degrees."""
    a = float(azimuth_deg) % 360.0
    exact = {0.0: (1.0, 0.0), 90.0: (0.0, 1.0), 180.0: (-1.0, 0.0), 270.0: (0.0, -1.0)}
    if a in exact:
        return exact[a]
    r = math.radians(a)
    return math.cos(r), math.sin(r)


def _label(bearing_deg, fallback):
    """A component label: the bearing in digits (which `bearing` reads back), or `fallback`."""
    if bearing_deg is None:
        return fallback
    b = round(bearing_deg % 360.0, 9) % 360.0
    return f"{b:03.0f}" if b == int(b) else f"{b:g}"


def _join(notes, more):
    return f"{notes}\n{more}" if notes else more


@dataclass(eq=False)
class HorizontalPair:
    """Two perpendicular horizontal components and the vertical of one record set, on one
    time base: one ground motion in space (see the module's docstring for the axes and
    the azimuth convention).

    x, y       the horizontal components (Records, acc in m/s²), y 90 degrees
               counterclockwise from x seen from above; one dt, one length
    vertical   the vertical component (a Record on the same time base) or None
    bearing_x  compass bearing of x in degrees (clockwise from north), None if unknown
    notes      what was done to put the components on one time base, and caveats

    Build one with `from_records` (which aligns the components) or `pair_of` (a file or
    a Record: its record set); the constructor only checks that the time base is one.
    """

    x: Record
    y: Record
    vertical: Record = None
    bearing_x: float = None
    notes: str = ""

    def __post_init__(self):
        parts = [("x", self.x), ("y", self.y)] + ([("vertical", self.vertical)] if self.vertical is not None else [])
        for role, rec in parts:
            if not isinstance(rec, Record):
                raise TypeError(f"HorizontalPair.{role} must be a Record, got {type(rec).__name__}")
            if abs(rec.dt - self.x.dt) > DT_TOLERANCE * self.x.dt or rec.npts != self.x.npts:
                raise ValueError(f"HorizontalPair.{role} ({rec.source} [{rec.component}]: dt {rec.dt:g} s, "
                                 f"{rec.npts} samples) is not on x's time base (dt {self.x.dt:g} s, "
                                 f"{self.x.npts} samples): build the pair with HorizontalPair.from_records")
        for role, rec in parts[:2]:
            if rec.vertical:
                raise ValueError(f"HorizontalPair.{role} ({rec.source} [{rec.component}]) is a vertical component")
        if self.vertical is not None and not self.vertical.vertical:
            raise ValueError(f"HorizontalPair.vertical ({self.vertical.source} [{self.vertical.component}]) "
                             "is not a vertical component")

    @classmethod
    def from_records(cls, first, second, vertical=None, bearings="labels"):
        """The pair of two horizontal Records (and the vertical, or None) on one time base.

        bearings: "labels" orders x and y by the compass bearings their labels name (see
        the module's docstring) and refuses components that are not perpendicular; None
        takes x = first, y = second whatever the labels say, bearing_x unknown.
        Different steps: resampled to the smallest (linear interpolation); different
        lengths: padded with zeros at the end to the longest. Both are written in notes.
        """
        if bearings not in ("labels", None):
            raise ValueError(f"bearings must be 'labels' or None, got {bearings!r}")
        notes = []
        bx = by = None
        if bearings == "labels":
            bx, by = bearing(first.component), bearing(second.component)
        if bx is not None and by is not None:
            turn = (by - bx) % 360.0  # clockwise, compass: 270 when y is counterclockwise of x
            if abs(turn - 90.0) <= PERPENDICULAR_TOLERANCE_DEG:
                first, second, bx, by = second, first, by, bx
                turn = (by - bx) % 360.0
            if abs(turn - 270.0) > PERPENDICULAR_TOLERANCE_DEG:
                raise ValueError(
                    f"{first.source} [{first.component}] and {second.source} [{second.component}]: bearings "
                    f"{bx:g} and {by:g} degrees are not perpendicular (within {PERPENDICULAR_TOLERANCE_DEG:g} "
                    "degree); pass bearings=None to take them as x and y regardless")
        else:
            bx = None
            notes.append(f"x = [{first.component}], y = [{second.component}] as given: "
                         + ("bearings not read from the labels" if bearings is None
                            else "their labels name no compass bearing")
                         + ", so whether y is counterclockwise of x is not known")
        recs = [first, second] + ([vertical] if vertical is not None else [])
        for rec in recs:
            if abs(rec.time[0]) > DT_TOLERANCE * rec.dt:
                raise ValueError(f"{rec.source} [{rec.component}]: its time starts at {rec.time[0]:g} s, "
                                 "not 0: the components' alignment is not known")
        dt = min(r.dt for r in recs)
        for i, rec in enumerate(recs):
            if abs(rec.dt - dt) > DT_TOLERANCE * dt:
                notes.append(f"[{rec.component}] resampled from dt = {rec.dt:g} s to {dt:g} s "
                             "(linear interpolation) to share the other components' step")
                recs[i] = rec.resampled(dt)
        n = max(r.npts for r in recs)
        for i, rec in enumerate(recs):
            if rec.npts < n:
                notes.append(f"[{rec.component}] padded with {n - rec.npts} zero sample(s) at the end "
                             f"({rec.npts} -> {n}) to the longest component's length")
            recs[i] = dataclasses.replace(rec, time=np.arange(n) * dt, dt=dt,
                                          acc=np.concatenate((rec.acc, np.zeros(n - rec.npts))),
                                          av_record=None)
        return cls(recs[0], recs[1], recs[2] if vertical is not None else None, bx, "\n".join(notes))

    @property
    def dt(self):
        """Time step, s."""
        return self.x.dt

    @property
    def npts(self):
        """Number of samples of each component."""
        return self.x.npts

    @property
    def time(self):
        """Sample times, s (i dt)."""
        return self.x.time

    @property
    def name(self):
        """Station / event of the set."""
        return self.x.name

    @property
    def pga(self):
        """Peak of the horizontal acceleration's magnitude, max sqrt(x² + y²), m/s²: the peak
        over all azimuths of the component along the azimuth (RotD100 of PGA)."""
        return float(np.sqrt(np.max(self.x.acc ** 2 + self.y.acc ** 2)))

    def bearing_of(self, azimuth_deg):
        """Compass bearing (degrees clockwise from north) of the direction at `azimuth_deg`
        from x, or None when bearing_x is unknown."""
        return None if self.bearing_x is None else (self.bearing_x - float(azimuth_deg)) % 360.0

    def azimuth_of_bearing(self, bearing_deg):
        """The azimuth from x (degrees, in [0, 360)) of the direction of compass bearing
        `bearing_deg`; ValueError when the pair's bearings are unknown."""
        if self.bearing_x is None:
            raise ValueError(f"{self.x.source}: the pair's labels give no compass bearing "
                             f"([{self.x.component}], [{self.y.component}]): give an azimuth from x")
        return (self.bearing_x - float(bearing_deg)) % 360.0

    def rotated(self, azimuth_deg):
        """The pair turned by `azimuth_deg` (degrees, from x towards y): x is the component
        along the azimuth, x cos a + y sin a, and y the one along azimuth + 90 degrees,
        -x sin a + y cos a. The vertical is unchanged; labels are the new bearings when
        bearing_x is known."""
        c, s = cos_sin(azimuth_deg)
        ax, ay = self.x.acc, self.y.acc
        new_x = c * ax + s * ay
        new_y = -s * ax + c * ay
        bx = self.bearing_of(azimuth_deg)
        by = None if bx is None else (bx - 90.0) % 360.0
        note = f"rotated by {float(azimuth_deg):g} degrees from [{self.x.component}] towards [{self.y.component}]"
        rx = dataclasses.replace(self.x, acc=new_x, component=_label(bx, f"{self.x.component}+{float(azimuth_deg):g}"),
                                 notes=_join(self.x.notes, note))
        ry = dataclasses.replace(self.y, acc=new_y,
                                 component=_label(by, f"{self.x.component}+{float(azimuth_deg) + 90.0:g}"),
                                 notes=_join(self.y.notes, note))
        return HorizontalPair(rx, ry, self.vertical, bx, _join(self.notes, note))

    def along(self, azimuth_deg, with_vertical=False):
        """The one component along `azimuth_deg` (degrees from x towards y) as a Record, for
        a planar run; with_vertical: its av_record is the pair's vertical (ValueError if none)."""
        rec = self.rotated(azimuth_deg).x
        if with_vertical:
            if self.vertical is None:
                raise ValueError(f"{self.x.source}: the pair has no vertical component for av")
            rec = dataclasses.replace(rec, av_record=self.vertical)
        return rec

    def peak_azimuth(self):
        """Azimuth (degrees from x, in [0, 180)) of the largest horizontal acceleration: the
        direction of the sample where sqrt(x² + y²) peaks, along which the rotated
        component's peak is the pair's `pga`."""
        k = int(np.argmax(self.x.acc ** 2 + self.y.acc ** 2))
        return math.degrees(math.atan2(self.y.acc[k], self.x.acc[k])) % 180.0

    def planar_records(self, azimuth_deg=None, with_vertical=False):
        """[(label, Record)] for the planar comparison: x, y and the component along
        `azimuth_deg` (default `peak_azimuth()`, the direction of the peak acceleration)."""
        a = self.peak_azimuth() if azimuth_deg is None else float(azimuth_deg)
        return [(f"x [{self.x.component}]", self.along(0.0, with_vertical)),
                (f"y [{self.y.component}]", self.along(90.0, with_vertical)),
                (f"azimuth {a:g} deg", self.along(a, with_vertical))]

    def scaled(self, factor):
        """Copy with every component (the vertical too) multiplied by `factor`."""
        return dataclasses.replace(self, x=self.x.scaled(factor), y=self.y.scaled(factor),
                                   vertical=None if self.vertical is None else self.vertical.scaled(factor))

    def __repr__(self):
        b = "" if self.bearing_x is None else f", bearing_x={self.bearing_x:g}"
        v = "" if self.vertical is None else f", vertical={self.vertical.component!r}"
        return (f"HorizontalPair(name={self.name!r}, x={self.x.component!r}, y={self.y.component!r}{v}{b}, "
                f"npts={self.npts}, dt={self.dt:g} s, source={self.x.source!r})")


def pair_of(source, units=None, fmt=None, bearings="labels"):
    """The HorizontalPair of a record set: `source` a record file's path or a Record read
    from one (its `source`). The set (the file's components, or its siblings', see
    `recordset.components`) must hold two horizontal components and at most one vertical;
    ValueError naming the file otherwise. units, fmt: as for `read_all`."""
    path = Path(source.source if isinstance(source, Record) else source)
    if not str(path) or not path.is_file():
        raise ValueError(f"{path}: no record file to read the pair from")
    recs = components(path, units=units, fmt=fmt)
    horizontal = [r for r in recs if not r.vertical]
    vertical = [r for r in recs if r.vertical]
    listed = ", ".join(f"[{r.component}]" if r.component else Path(r.source).name for r in recs)
    if len(horizontal) != 2:
        raise ValueError(f"{path}: its record set holds {len(horizontal)} horizontal component(s) ({listed}); "
                         "a pair needs two")
    if len(vertical) > 1:
        raise ValueError(f"{path}: its record set holds {len(vertical)} vertical components ({listed})")
    return HorizontalPair.from_records(horizontal[0], horizontal[1], vertical[0] if vertical else None,
                                      bearings=bearings)
