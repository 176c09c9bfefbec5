"""Rigid-block limit analysis of the actual assembly (the static formulation of Livesley,
as a linear program over contact forces), solved by HiGHS through scipy.

Unknowns: at each corner of every interface a normal force n >= 0 (no tension) and two
tangential forces (t1, t2) along the face's axes; the multiplier lambda; for a roller
end, its reaction (bounded by the assembly's clamp, if finite). Each free block is in
equilibrium (3 forces, 3 moments about its centroid) under its weight W, the lateral
load lambda W d (d = load_direction(alpha)), and the contact forces. Friction: the cone
|t| <= mu n replaced by the pyramid of `facets` planes t . (cos phi_k, sin phi_k) <= mu
n, which contains the cone (exact along the face's axes, at most 1/cos(pi/facets) - 1
wider in between), so its lambda is at least the cone's and cannot rise as the planes
double; the same pyramid with mu cos(pi/facets) lies inside the cone and bounds the
cone's lambda from below. No second-order cone solver is among the project's packages,
hence the pyramid; FACETS planes by default. With associative flow, lambda is an upper
bound of the answer of a frictional (non-associative) assembly.

The dual variables of the equilibrium rows are the blocks' virtual velocities (3
translations, 3 rotations per block): the collapse mechanism."""

from dataclasses import dataclass
import math

import numpy as np

from .assembly import Assembly, interfaces
from .draw import corners_of

LAMBDA_CAP = 100.0  # the LP's bound on lambda: reaching it means nothing can collapse

#: Planes of the friction pyramid by default: on the paper's corner 32 keep lambda within
#: 0.27 % of 64 planes (8 are up to 6.3 % above; docs/corner-blocks.md section 2)
FACETS = 32


@dataclass
class Result:
    """lam: the largest multiplier; velocity: (blocks, 6) virtual velocities of the
    mechanism (m/s, rad/s; fixed blocks zero), scaled so that the load's power per unit
    lambda is 1 W; moving: the indices of the blocks that move; power_dead: the
    weights' power in that mechanism (W), -lam by virtual work; opening_min: the
    least normal relative velocity at any contact corner (>= 0 up to round-off: no
    interpenetration)."""

    lam: float
    velocity: np.ndarray
    moving: list
    power_dead: float
    opening_min: float
    status: str


def solve(assembly: Assembly, alpha, facets=FACETS, move_tol=0.02):
    """The LP at orientation alpha (rad); see the module's doc."""
    # scipy here, not at the top: the command line shows FACETS in its help without the
    # 0.6 s of importing scipy.optimize and scipy.sparse
    from scipy.optimize import linprog
    from scipy.sparse import coo_matrix

    if not (isinstance(facets, int) and facets >= 3):
        raise ValueError(f"invalid facets: an integer of at least 3 (a pyramid that bounds the cone), got {facets!r}")
    faces = interfaces(assembly)
    free = assembly.free()
    row_of = {i: 6 * k for k, i in enumerate(free)}
    centroid = [b.centroid for b in assembly.blocks]
    rows, cols, vals = [], [], []
    friction = []  # (column of n, column of t1, column of t2)
    col = 0
    for face in faces:
        e1, e2 = _tangents(face.axis)
        for p in face.corners:
            for k, vec in enumerate((-face.normal, e1, e2)):
                for block, sign in ((face.i, 1.0), (face.j, -1.0)):
                    if block in row_of:
                        _add_wrench(rows, cols, vals, row_of[block], col + k, sign * vec, p - centroid[block])
            friction.append((col, col + 1, col + 2))
            col += 3
    rollers = []  # (column, block)
    for i in free:
        r = assembly.roller[i]
        if r is not None:
            _add_wrench(rows, cols, vals, row_of[i], col, r, np.zeros(3))
            rollers.append((col, i))
            col += 1
    dead, live = assembly.dead_and_live(alpha)
    lam_col = col
    n_var = col + 1
    for r, v in enumerate(live):
        if v != 0.0:
            rows.append(r), cols.append(lam_col), vals.append(v)
    a_eq = coo_matrix((vals, (rows, cols)), shape=(6 * len(free), n_var)).tocsr()
    a_ub = _pyramid(friction, n_var, assembly.mu, facets)
    bounds = [(None, None)] * n_var
    for cn, _, _ in friction:
        bounds[cn] = (0.0, None)
    for rc, i in rollers:
        bounds[rc] = assembly.roller_bounds(i)
    bounds[lam_col] = (0.0, LAMBDA_CAP)
    c = np.zeros(n_var)
    c[lam_col] = -1.0
    res = linprog(c, A_ub=a_ub, b_ub=np.zeros(a_ub.shape[0]), A_eq=a_eq, b_eq=-dead, bounds=bounds,
                  method="highs")
    if res.status != 0:
        return Result(math.nan, np.zeros((len(assembly.blocks), 6)), [], math.nan, math.nan, res.message)
    lam = float(res.x[lam_col])
    u = np.asarray(res.eqlin.marginals)
    scale = float(live @ u)
    u = u / scale if scale != 0 else u
    velocity = np.zeros((len(assembly.blocks), 6))
    for i, r in row_of.items():
        velocity[i] = u[r:r + 6]
    moving = _moving(assembly, velocity, move_tol)
    opening = _openings(faces, velocity, centroid)
    return Result(lam, velocity, moving, float(dead @ u), float(min(opening, default=0.0)), "optimal")


def _tangents(axis):
    a, b = [k for k in range(3) if k != axis]
    e1, e2 = np.zeros(3), np.zeros(3)
    e1[a], e2[b] = 1.0, 1.0
    return e1, e2


def _add_wrench(rows, cols, vals, row, col, force, arm):
    """The force (per unit of the variable at col) and its moment about the centroid."""
    wrench = np.concatenate([force, np.cross(arm, force)])
    for k, v in enumerate(wrench):
        if v != 0.0:
            rows.append(row + k), cols.append(col), vals.append(v)


def _pyramid(friction, n_var, mu, facets):
    """Rows cos(phi) t1 + sin(phi) t2 - mu n <= 0, phi = 2 pi k / facets."""
    from scipy.sparse import coo_matrix

    rows, cols, vals = [], [], []
    r = 0
    for cn, c1, c2 in friction:
        for k in range(facets):
            phi = 2 * math.pi * k / facets
            for c, v in ((c1, math.cos(phi)), (c2, math.sin(phi)), (cn, -mu)):
                if abs(v) > 1e-15:
                    rows.append(r), cols.append(c), vals.append(v)
            r += 1
    return coo_matrix((vals, (rows, cols)), shape=(r, n_var)).tocsr()


def point_velocity(velocity, centroid, p):
    """Velocity (m/s) of point p of a block whose centroid and (v, omega) are given."""
    return velocity[:3] + np.cross(velocity[3:], p - centroid)


def _openings(faces, velocity, centroid):
    """Normal relative velocity of j from i at every interface corner (>= 0: no overlap)."""
    out = []
    for f in faces:
        for p in f.corners:
            dv = point_velocity(velocity[f.j], centroid[f.j], p) - point_velocity(velocity[f.i], centroid[f.i], p)
            out.append(float(dv @ f.normal))
    return out


def _moving(assembly, velocity, tol):
    """Blocks whose fastest corner moves faster than tol times the fastest block's."""
    speed = np.zeros(len(assembly.blocks))
    for i, b in enumerate(assembly.blocks):
        speed[i] = max(np.linalg.norm(point_velocity(velocity[i], b.centroid, p)) for p in corners_of(b))
    top = speed.max()
    return [i for i in range(len(speed)) if top > 0 and speed[i] > tol * top]
