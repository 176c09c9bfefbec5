"""An assembly of axis-aligned rigid boxes and the interfaces where they touch: the input
of the block limit analysis (lp.py), built from the corner specimen or from a test case."""

from dataclasses import dataclass

import numpy as np

from .specimen import Block, load_direction


@dataclass
class Assembly:
    """blocks: the boxes; fixed[i]: block i does not move (table, taped course, clamped
    end); roller[i]: None, or a unit vector along which block i is restrained (a
    bilateral support at its centroid, no moment); rho, g: density (kg/m3), gravity (m/s2);
    clamp: the largest roller reaction in units of the block's weight (inf: rigid)."""

    blocks: list
    fixed: list
    roller: list
    rho: float
    g: float
    mu: float
    clamp: float = float("inf")

    @classmethod
    def from_specimen(cls, specimen):
        blocks = specimen.layout()
        return cls(blocks, [specimen.fixed(b) for b in blocks], [specimen.roller(b) for b in blocks],
                   specimen.rho, specimen.g, specimen.mu, specimen.clamp)

    def roller_bounds(self, i):
        """(low, high) of block i's roller reaction (N)."""
        if self.clamp == float("inf"):
            return (None, None)
        r = self.clamp * self.weight(i)
        return (-r, r)

    def weight(self, i):
        """W (N) of block i."""
        return self.rho * self.g * self.blocks[i].volume

    def dead_and_live(self, alpha):
        """(D, L): per free block, the 6 generalized forces at its centroid (N, N m) of its
        weight and of its lateral load per unit multiplier, orientation alpha."""
        d = load_direction(alpha)
        free = self.free()
        dead, live = np.zeros(6 * len(free)), np.zeros(6 * len(free))
        for k, i in enumerate(free):
            w = self.weight(i)
            dead[6 * k + 2] = -w
            live[6 * k:6 * k + 3] = w * d
        return dead, live

    def free(self):
        return [i for i, f in enumerate(self.fixed) if not f]


@dataclass
class Interface:
    """Blocks i and j touch on a face normal to axis; normal: unit vector from i into j;
    corners: the 4 corners (m) of the common rectangle, where the LP puts its forces."""

    i: int
    j: int
    axis: int
    normal: np.ndarray
    corners: np.ndarray


def interfaces(assembly, tol=1e-9):
    """Every face contact of positive area between two blocks, not both fixed (m, tol)."""
    boxes = assembly.blocks
    lo = np.array([b.lo for b in boxes])
    hi = np.array([b.hi for b in boxes])
    out = []
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            if assembly.fixed[i] and assembly.fixed[j]:
                continue
            face = _touching(lo[i], hi[i], lo[j], hi[j], tol)
            if face is not None:
                out.append(Interface(i, j, *face))
    return out


def _touching(lo_i, hi_i, lo_j, hi_j, tol):
    """(axis, normal i -> j, corners) if the boxes share a face of positive area, else None."""
    for axis in range(3):
        if abs(hi_i[axis] - lo_j[axis]) < tol:
            sign, at = 1.0, hi_i[axis]
        elif abs(hi_j[axis] - lo_i[axis]) < tol:
            sign, at = -1.0, lo_i[axis]
        else:
            continue
        a, b = [k for k in range(3) if k != axis]
        a0, a1 = max(lo_i[a], lo_j[a]), min(hi_i[a], hi_j[a])
        b0, b1 = max(lo_i[b], lo_j[b]), min(hi_i[b], hi_j[b])
        if a1 - a0 <= tol or b1 - b0 <= tol:
            return None
        corners = np.zeros((4, 3))
        corners[:, axis] = at
        corners[:, a] = [a0, a1, a1, a0]
        corners[:, b] = [b0, b0, b1, b1]
        normal = np.zeros(3)
        normal[axis] = sign
        return axis, normal, corners
    return None


def box(lo, hi, course=0, index=0):
    """A block of a test case (no wall)."""
    return Block(tuple(map(float, lo)), tuple(map(float, hi)), "", course, "", index)


def on_table(blocks, rho=1876.0, g=9.81, mu=0.66):
    """The blocks, free, standing on a fixed table (a slab under z = 0 wide enough for them)."""
    lo = np.min([b.lo for b in blocks], axis=0)
    hi = np.max([b.hi for b in blocks], axis=0)
    table = box((lo[0] - 1, lo[1] - 1, -0.1), (hi[0] + 1, hi[1] + 1, 0.0), course=-1)
    every = [table, *blocks]
    return Assembly(every, [True] + [False] * len(blocks), [None] * len(every), rho, g, mu)
