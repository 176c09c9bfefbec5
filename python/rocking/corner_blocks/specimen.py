"""The dry-joint corner as a list of blocks: one description for the drawings, the
block limit analysis (lp.py) and the DEM tilting test (dem.py).

Frame (as docs/corner.md): wall WX runs along +x with its outer face on y = 0, wall WY
along +y with its outer face on x = 0, z up from the table; the origin is the outer
vertex. The load of orientation alpha pushes the corner outwards, along
-(cos alpha, sin alpha, 0): alpha = 0 loads WX in its plane and WY out of its plane.
"""

from dataclasses import dataclass, replace
import math

import numpy as np

#: End conditions of the walls' free ends (the last block of each wall in every course).
ENDS = ("fixed", "free", "outOfPlane")
#: What the closing pieces (the end blocks of the butting courses, l - t long) do: as the
#: other end blocks ("held"), or move like any block ("free").
CLOSERS = ("held", "free")


@dataclass(frozen=True)
class Block:
    """An axis-aligned box. lo, hi: opposite corners (m); wall: "WX", "WY" or "" (tests);
    course: 0 at the table; role: "base" (fixed, the taped first course), "end" (the
    wall's last block in its course), "" otherwise; index: along the wall from the corner."""

    lo: tuple
    hi: tuple
    wall: str = ""
    course: int = 0
    role: str = ""
    index: int = 0

    @property
    def size(self):
        return np.subtract(self.hi, self.lo)

    @property
    def centroid(self):
        return (np.asarray(self.lo) + np.asarray(self.hi)) / 2

    @property
    def volume(self):
        return float(np.prod(self.size))

    def label(self):
        """e.g. WX3.2: wall, course (0 at the table), index along the wall from the corner."""
        return f"{self.wall}{self.course}.{self.index}" if self.wall else f"B{self.course}.{self.index}"


@dataclass(frozen=True)
class Specimen:
    """The paper's 1:4 corner (its section 2.1; lengths in m, density in kg/m3).

    t, l, h: block thickness (= wall thickness), length, height; courses; blocks:
    full blocks per wall in the course where the wall runs through the corner
    (its length L = blocks * l from the outer vertex); mu: joint friction;
    ends: one of ENDS; fixed_base: the first course taped to the table; closers: one of
    CLOSERS; clamp: with ends=outOfPlane, the largest out-of-plane reaction of an end block,
    in units of that block's weight (inf: a rigid roller; a finite one is a clamp that slips
    at that force, the rigid-plastic stand-in for a spring, docs/corner-blocks.md)."""

    t: float = 0.0573
    l: float = 0.1149
    h: float = 0.0703
    rho: float = 1876.0
    g: float = 9.81
    courses: int = 9
    blocks: int = 7
    mu: float = 0.66
    ends: str = "fixed"
    fixed_base: bool = True
    closers: str = "held"
    clamp: float = math.inf

    def __post_init__(self):
        for name in ("t", "l", "h", "rho", "g", "mu"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"invalid {name}: must be positive and finite, got {value}")
        if self.courses < 2:
            raise ValueError(f"invalid courses: at least 2, got {self.courses}")
        if self.blocks < 2:
            raise ValueError(f"invalid blocks: at least 2, got {self.blocks}")
        if self.ends not in ENDS:
            raise ValueError(f"invalid ends: one of {', '.join(ENDS)}, got {self.ends}")
        if self.closers not in CLOSERS:
            raise ValueError(f"invalid closers: one of {', '.join(CLOSERS)}, got {self.closers}")
        if not (self.clamp >= 0 and not math.isnan(self.clamp)):
            raise ValueError(f"invalid clamp: must be >= 0 (inf: rigid), got {self.clamp}")
        if self.clamp != math.inf and self.ends != "outOfPlane":
            raise ValueError(f"invalid clamp: bounds the outOfPlane ends' reaction, got ends={self.ends}")
        if not self.t < self.l:
            raise ValueError(f"invalid l: must exceed t = {self.t}, got {self.l}")

    @property
    def length(self):
        """L: each wall's length from the outer vertex (m)."""
        return self.blocks * self.l

    @property
    def height(self):
        return self.courses * self.h

    def with_(self, **changes):
        return replace(self, **changes)

    def layout(self):
        """The blocks, course by course: WX then WY, each from the corner outwards.

        Even courses: WX runs through the corner (blocks from x = 0), WY butts against
        WX's inner face (from y = t); odd courses the opposite. The butting wall has
        blocks - 1 full blocks and a closing piece of length l - t, so both walls end
        flush at L in every course (head joints alternate by t, about l/2)."""
        out = []
        for c in range(self.courses):
            z0, z1 = c * self.h, (c + 1) * self.h
            for wall in ("WX", "WY"):
                through = (wall == "WX") == (c % 2 == 0)
                starts = self._starts(through)
                for i, (s0, s1) in enumerate(starts):
                    lo, hi = ((s0, 0.0, z0), (s1, self.t, z1)) if wall == "WX" else ((0.0, s0, z0), (self.t, s1, z1))
                    role = "base" if (c == 0 and self.fixed_base) else ("end" if i == len(starts) - 1 else "")
                    out.append(Block(lo, hi, wall, c, role, i))
        return out

    def _starts(self, through):
        """[(s0, s1)] along the wall from the outer vertex."""
        if through:
            return [(i * self.l, (i + 1) * self.l) for i in range(self.blocks)]
        full = [(self.t + i * self.l, self.t + (i + 1) * self.l) for i in range(self.blocks - 1)]
        return full + [(full[-1][1], self.length)]

    def restrained(self, block):
        """True for an end block that takes the ends' restraint (a closing piece only if
        closers is "held")."""
        return block.role == "end" and (self.closers == "held" or not self.is_closer(block))

    def is_closer(self, block):
        """The closing piece: the end block of a course where its wall butts (shorter than l)."""
        return block.role == "end" and (block.wall == "WX") != (block.course % 2 == 0)

    def fixed(self, block):
        """True if the block does not move: the base course, the ends under ends=fixed."""
        return block.role == "base" or (self.restrained(block) and self.ends == "fixed")

    def roller(self, block):
        """The restrained direction (unit vector) of an end block under ends=outOfPlane, else None:
        out of the wall's plane (y for WX, x for WY)."""
        if not self.restrained(block) or self.ends != "outOfPlane":
            return None
        return np.array([0.0, 1.0, 0.0]) if block.wall == "WX" else np.array([1.0, 0.0, 0.0])


def load_direction(alpha):
    """Unit horizontal vector of the load at orientation alpha (rad): outwards from the corner."""
    return -np.array([math.cos(alpha), math.sin(alpha), 0.0])


#: The paper's five orientations, and their labels.
ORIENTATIONS = [(math.pi / 4, "pi/4"), (5 * math.pi / 16, "5pi/16"), (3 * math.pi / 8, "3pi/8"),
                (7 * math.pi / 16, "7pi/16"), (math.pi / 2, "pi/2")]
