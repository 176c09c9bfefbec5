"""The least collapse multiplier of the frictional block assembly (Coulomb friction
without dilatancy), as a mathematical program with complementarity constraints (Ferris &
Tin-Loi, Int. J. Mech. Sci. 43, 2001, 209-224), solved as a mixed-integer LP with big-M
switches by HiGHS through scipy (`scipy.optimize.milp`); and a check that a given
mechanism is a collapse state (`certify`, two LPs).

The contact model is nonassoc.py's (lp.py's): at each corner c of every interface a
normal force n_c >= 0 and tangential forces t_c, the friction pyramid of `facets` planes
e_k . t_c <= mu n_c. A collapse state at lambda is
- forces: equilibrium of every free block under its weight, lambda times it along the
  load, the contact forces (and rigid rollers' reactions); the pyramid with the corner's
  own n;
- a mechanism y (per free block 3 velocities, 3 angular velocities), load power 1
  (live . y = 1), with d = A_eq^T y its relative velocity at the contact columns:
  opening z_c = d_n >= 0, slip -d_t = sum_k s_k e_k with s_ck >= 0 (no dilatancy), a
  rigid roller's column d_r = 0;
- complementarity: n_c z_c = 0 (a corner opens only where n = 0), s_ck (mu n_c -
  e_k . t_c) = 0 (it slides only on planes where friction is at its limit).
These are the optimality conditions of nonassoc.py's fixed-capacity LP at a fixed point
n = n_hat, so every converged state of the iteration is one, and the least lambda over
all of them is at most the iteration's. `least` minimises lambda over them: binaries
b_c (corner closed: z_c = 0; open: n_c = 0) and q_ck (plane active: mu n_c = e_k . t_c;
inactive: s_ck = 0), with big-M bounds n_c <= N, |y| <= Y (translations Y/W_min m/s,
rotations Y/(W_min L_min) rad/s, W_min the lightest free block's weight, L_min the
smallest side of any free block), and the bounds on z and s these imply. HiGHS's branch and bound returns
the best state found (an upper end, a genuine collapse state) and a dual bound (a lower
end): together a certified interval for the least collapse multiplier among states
within those bounds. The bounds are an assumption, stated with every result: a state
with larger forces or a mechanism with a larger ratio of speed to load power is not
searched. The virtual-work identity lambda = -dead . y + sum mu n_c s_ck (from the
complementarity) gives the valid cut lambda + dead . y >= 0, added to tighten the
relaxation. Even so the relaxation decouples forces and mechanism, and its bound stays at
lambda = 0 beyond a block or two (docs/corner-nonassociative.md, section 1).

`certify(assembly, alpha, velocity)`: for a mechanism found elsewhere (the iteration's
last LP), the least and the largest lambda of force fields that are a collapse state with
it (the openings and slip directions of the mechanism fix which corners carry n = 0 and
which pyramid planes are at their limit): an LP each. Any lambda in that range is a
collapse state, so the least one is an upper end of the least collapse multiplier."""

from dataclasses import dataclass
import math
import time

import numpy as np
from scipy.optimize import Bounds, LinearConstraint, linprog, milp
from scipy.sparse import coo_matrix, csr_matrix, identity, vstack

from .nonassoc import _Problem


@dataclass
class Least:
    """lower, upper: the interval HiGHS certifies for the least collapse multiplier among
    states within the big-M bounds (upper nan: no state found within the time limit);
    status: HiGHS's message; cpu_s: process time (s); n_max (N), y_scale: the bounds;
    binaries; normal: the best state's normal forces (N, interfaces(assembly)'s order);
    velocity: its mechanism (blocks, 6), load power 1 W per unit lambda; bound_active:
    whether the best state touches a big-M bound (then a larger bound may find lower)."""

    lower: float
    upper: float
    status: str
    cpu_s: float
    n_max: float
    y_scale: float
    binaries: int
    normal: np.ndarray = None
    velocity: np.ndarray = None
    bound_active: bool = False


def _blocks(p):
    free = p.assembly.free()
    return free, len(free)


def _mechanism_bounds(p, y_scale):
    """Per free block's 6 components: Y/W_min for velocities, Y/(W_min L_min) for rotations."""
    a = p.assembly
    free, nf = _blocks(p)
    w_min = min(a.weight(i) for i in free)
    l_min = min(min(a.blocks[i].size) for i in free)
    per = np.array([1.0, 1.0, 1.0, 1.0 / l_min, 1.0 / l_min, 1.0 / l_min]) * y_scale / w_min
    return np.tile(per, nf)


def _contact_columns(p):
    """Column indices: n per corner, (t1, t2) per corner, rollers (everything between the
    contacts and lambda)."""
    n = p.n_cols
    t1, t2 = n + 1, n + 2
    rollers = np.arange(3 * len(n), p.lam_col)
    return n, t1, t2, rollers


def least(assembly, alpha, facets=8, n_max=None, y_scale=10.0, time_limit=600.0, mip_rel_gap=1e-4, log=False):
    """The MILP of the module's doc at orientation alpha (rad). n_max: the bound N on a
    corner's normal force (N; default the free blocks' total weight); y_scale: Y (the
    mechanism's bound, in units of the lightest block: 1 means that block alone moving
    along the load at the unit load power); time_limit (s) and mip_rel_gap go to HiGHS."""
    p = _Problem(assembly, alpha, facets)
    for i in assembly.free():
        if assembly.roller[i] is not None and assembly.clamp != math.inf:
            raise ValueError(f"a bounded roller (clamp {assembly.clamp}) is not modelled here: "
                             "its reaction's complementarity is not implemented")
    free, nf = _blocks(p)
    mu = assembly.mu
    if n_max is None:
        n_max = sum(assembly.weight(i) for i in free)
    m = len(p.n_cols)
    nx = len(p.c)
    ny = 6 * nf
    ns = facets * m
    ncol, t1, t2, rollers = _contact_columns(p)
    # variable layout: x (nx), y (ny), s (ns), b (m), q (ns)
    oy, os_, ob, oq = nx, nx + ny, nx + ny + ns, nx + ny + ns + m
    nv = oq + ns
    y_bound = _mechanism_bounds(p, y_scale)
    g = p.a_eq.T.tocsr()  # (nx, ny): d = g y, relative velocities per LP column
    gabs = abs(g)
    z_max = gabs[ncol] @ y_bound  # the largest opening per corner
    slip_max = gabs[t1] @ y_bound + gabs[t2] @ y_bound
    # at most two adjacent planes carry a slip (an open corner's slip too has such a
    # representation): each s <= |slip| / sin(2 pi / facets)
    s_max = np.repeat(slip_max / math.sin(2 * math.pi / max(facets, 4)), facets) * 1.01
    rows = []

    def block(parts, lo, hi):
        """parts: (offset, matrix) pairs placed into a row block of nv columns."""
        r = parts[0][1].shape[0]
        total = csr_matrix((r, nv))
        for off, mat in parts:
            mat = mat.tocoo()
            total = total + coo_matrix((mat.data, (mat.row, mat.col + off)), shape=(r, nv)).tocsr()
        rows.append(LinearConstraint(total, lo, hi))

    # equilibrium
    block([(0, p.a_eq)], -p.dead, -p.dead)
    # Coulomb with the corner's own n: a_assoc x <= 0
    block([(0, p.a_assoc)], -np.inf, 0.0)
    # stationarity in t: g_t y + (a_fixed^T s)_t = 0
    af_t = p.a_fixed.T.tocsr()
    tcols = np.concatenate([t1, t2])
    block([(oy, g[tcols]), (os_, af_t[tcols])], 0.0, 0.0)
    # openings z = g_n y >= 0
    block([(oy, g[ncol])], 0.0, np.inf)
    # rigid rollers: no relative velocity along them
    if len(rollers) and assembly.clamp == math.inf:
        block([(oy, g[rollers])], 0.0, 0.0)
    # load power 1
    block([(oy, csr_matrix(p.live.reshape(1, -1)))], 1.0, 1.0)
    # virtual work: lambda + dead . y >= 0
    lam_row = csr_matrix(([1.0], ([0], [p.lam_col])), shape=(1, nx))
    block([(0, lam_row), (oy, csr_matrix(p.dead.reshape(1, -1)))], 0.0, np.inf)
    # corner closed (b = 1): z <= z_max (1 - b); open (b = 0): n <= N b
    pick_n = coo_matrix((np.ones(m), (np.arange(m), ncol)), shape=(m, nx))
    block([(oy, g[ncol]), (ob, _diag(z_max))], -np.inf, z_max)
    block([(0, pick_n), (ob, _diag(np.full(m, -n_max)))], -np.inf, 0.0)
    # plane active (q = 1): mu n - e_k . t <= T (1 - q); inactive: s <= s_max q
    # mu n - e_k . t <= mu N + |t|, |t| <= mu N / cos(pi / facets) inside the pyramid
    t_big = 1.01 * mu * n_max * (1 + 1 / math.cos(math.pi / facets)) + 1e-9
    block([(0, -p.a_assoc), (oq, _diag(np.full(ns, t_big)))], -np.inf, t_big)
    block([(os_, identity(ns, format="csr")), (oq, _diag(-s_max))], -np.inf, 0.0)

    lo = np.full(nv, -np.inf)
    hi = np.full(nv, np.inf)
    for k, (a, b) in enumerate(p.bounds):
        lo[k] = -np.inf if a is None else a
        hi[k] = np.inf if b is None else b
    hi[ncol] = n_max
    lo[oy:os_], hi[oy:os_] = -y_bound, y_bound
    lo[os_:ob], hi[os_:ob] = 0.0, s_max
    lo[ob:], hi[ob:] = 0.0, 1.0
    integrality = np.zeros(nv)
    integrality[ob:] = 1
    c = np.zeros(nv)
    c[p.lam_col] = 1.0
    t0 = time.process_time()
    res = milp(c, constraints=rows, integrality=integrality, bounds=Bounds(lo, hi),
               options={"time_limit": time_limit, "mip_rel_gap": mip_rel_gap, "disp": log})
    cpu = time.process_time() - t0
    # no dual bound reported (no node solved to the end): lambda >= 0 is the model's own bound
    bound = getattr(res, "mip_dual_bound", None)
    lower = max(0.0, float(bound)) if bound is not None and not math.isnan(bound) else 0.0
    out = Least(lower, math.nan, res.message, cpu, n_max, y_scale, m + ns)
    if res.x is not None:
        x = res.x
        out.upper = float(x[p.lam_col])
        out.normal = x[ncol]
        velocity = np.zeros((len(assembly.blocks), 6))
        for i, r in p.row_of.items():
            velocity[i] = x[oy + r:oy + r + 6]
        out.velocity = velocity
        out.bound_active = bool((np.abs(x[oy:os_]) >= y_bound * (1 - 1e-6)).any() or (x[ncol] >= n_max * (1 - 1e-6)).any())
        if res.status == 0:  # optimal within the gap: the lower end is the dual bound or the optimum
            out.lower = min(out.upper, lower) if not math.isnan(lower) else out.upper
    return out


def _diag(v):
    k = len(v)
    return coo_matrix((v, (np.arange(k), np.arange(k))), shape=(k, k)).tocsr()


def relative_velocities(p, velocity):
    """(z, slip): per corner the opening speed (m/s) and the slip (m/s, along the face's
    two axes) of the mechanism, as the LP's columns see them (z = g_n y, slip = -g_t y)."""
    y = np.concatenate([velocity[i] for i in sorted(p.row_of, key=p.row_of.get)])
    d = p.a_eq.T @ y
    ncol, t1, t2, _ = _contact_columns(p)
    return d[ncol], -np.stack([d[t1], d[t2]], axis=1), d


def certify(assembly, alpha, velocity, facets=8, rel_tol=1e-7):
    """(lambda_min, lambda_max): the range of lambda over force fields that make a collapse
    state with the given mechanism (blocks, 6; load power 1), or (nan, nan) if none does.
    A corner opening faster than rel_tol times the largest relative speed gets n = 0; a
    corner slipping gets its force on the plane, or the two adjacent planes, whose normals
    span the slip direction at their limit (e_k . t = mu n); the rest only Coulomb. The
    mechanism's own conditions (openings >= 0, no relative speed along a rigid roller) are
    checked too: a mechanism that fails them gives (nan, nan)."""
    if assembly.clamp != math.inf and any(assembly.roller[i] is not None for i in assembly.free()):
        raise ValueError(f"a bounded roller (clamp {assembly.clamp}) is not modelled here")
    return _certify(_Problem(assembly, alpha, facets), velocity, rel_tol)


def _certify(p, velocity, rel_tol=1e-7, fields=None, time_limit=None):
    """certify on a built nonassoc._Problem; fields: a list that receives the LP's column
    values (the force fields) at lambda_min and lambda_max; time_limit (s) per LP: an LP
    that HiGHS has not decided by then counts as none found (on the paper's corner a
    certify LP took from under a minute to more than ten)."""
    assembly = p.assembly
    facets = p.facets
    z, slip, d = relative_velocities(p, velocity)
    ncol, t1, t2, rollers = _contact_columns(p)
    scale = max(float(np.abs(z).max(initial=0.0)), float(np.abs(slip).max(initial=0.0)), 1e-300)
    eps = rel_tol * scale
    if (z < -eps).any() or (len(rollers) and assembly.clamp == math.inf and (np.abs(d[rollers]) > eps).any()):
        return math.nan, math.nan
    if abs(float(p.live @ np.concatenate([velocity[i] for i in sorted(p.row_of, key=p.row_of.get)])) - 1) > 1e-6:
        raise ValueError("certify: the mechanism's load power must be 1 (velocity scaled by live . y)")
    m = len(ncol)
    nx = len(p.c)
    eq_rows, eq_cols, eq_vals = [], [], []
    r = 0
    step = 2 * math.pi / facets
    for c in range(m):
        if z[c] > eps:
            eq_rows.append(r), eq_cols.append(ncol[c]), eq_vals.append(1.0)
            r += 1
        s = slip[c]
        if math.hypot(*s) > eps:
            phi = math.atan2(s[1], s[0]) % (2 * math.pi)
            k = phi / step
            near = round(k)
            planes = [near % facets] if abs(k - near) * step * math.hypot(*s) <= eps else \
                [int(math.floor(k)) % facets, (int(math.floor(k)) + 1) % facets]
            for kk in planes:
                a = kk * step
                for col, v in ((t1[c], math.cos(a)), (t2[c], math.sin(a)), (ncol[c], -assembly.mu)):
                    if abs(v) > 1e-15:
                        eq_rows.append(r), eq_cols.append(col), eq_vals.append(v)
                r += 1
    extra = coo_matrix((eq_vals, (eq_rows, eq_cols)), shape=(r, nx))
    a_eq = vstack([p.a_eq, extra]).tocsr()
    b_eq = np.concatenate([-p.dead, np.zeros(r)])
    out = []
    for sign in (1.0, -1.0):
        c = np.zeros(nx)
        c[p.lam_col] = sign
        res = linprog(c, A_ub=p.a_assoc, b_ub=np.zeros(p.a_assoc.shape[0]), A_eq=a_eq, b_eq=b_eq,
                      bounds=p.bounds, method="highs",
                      options={} if time_limit is None else {"time_limit": time_limit})
        if res.status != 0:  # infeasible (no force field completes this mechanism) or undecided
            return math.nan, math.nan
        out.append(float(res.x[p.lam_col]))
        if fields is not None:
            fields.append(res.x)
    return out[0], out[1]
