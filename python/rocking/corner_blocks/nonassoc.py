"""Non-associative limit analysis of the block assembly: Coulomb friction without
dilatancy, by the iterative linear programs of Gilbert, Casapulla & Ahmed (Computers &
Structures 84, 2006, 873-887).

The contact model is lp.py's (docs/corner-blocks.md): at each corner of every interface a
normal force n >= 0 and two tangential forces t, the friction pyramid of `facets` planes.
Iteration 0 is lp.py's associative LP (friction t . e_k <= mu n, its flow dilates by mu
per unit slip). Every later iteration solves the same LP with the normal force inside
the friction rows frozen at the previous iteration's value n_hat: t . e_k <= mu n_hat.
The shear capacity no longer depends on the LP's own n, so the flow of that surface
slides without opening (the dual's normal velocity comes from n >= 0 alone). Its optimum
is rarely unique in n, so a second LP takes, among the optimal force fields, the one with
the least total normal force, nearest n_hat (_Problem.least_normal: our choice, so that
the normal forces can repeat). The normal forces found are then relaxed into n_hat, n_hat += relaxation (n - n_hat), until the LP
returns the normal forces it was given: max |n - n_hat| <= tol W_max (W_max the largest
block weight) and lambda moves by at most tol (relative). At that point the forces obey
Coulomb's |t| <= mu n (to tol), and the mechanism opens only where n = 0 and slides
only where friction is at its limit: a collapse state of the frictional assembly.

What it is, and is not: the converged lambda is the multiplier of one such collapse
state. It is at most the associative LP's (its forces are admissible there), but it is
not a bound of the frictional assembly's collapse multiplier in general: a non-associative
assembly can have several collapse states (its answer can depend on the prestress that
jammed contacts carry), and the iteration finds one, which depends on the start and on the
relaxation. Iterations that do not converge within max_iter, or an LP that fails, raise
NotConverged (or are returned with converged False when asked to), with the history."""

from dataclasses import dataclass, field
import math

import numpy as np
from scipy.optimize import linprog
from scipy.sparse import coo_matrix, hstack, vstack

from .assembly import Assembly, interfaces
from .draw import corners_of
from .lp import LAMBDA_CAP, point_velocity

#: Weight of sum |n - n_hat| against sum n in the choice among the LP's optima (least_normal).
PROXIMITY = 0.1
#: A corner "pressed" for Result.opening_max_pressed carries more than this share of the
#: largest block weight. Not tol: the last LP's forces are optimal only to tol in lambda,
#: so complementarity holds as n x opening <= tol-sized, and corners with n near tol
#: may still open.
PRESSED = 1e-3


@dataclass
class Result:
    """lam: the multiplier of the converged collapse state; lam_associative: iteration 0
    (lp.py's LP); converged; iterations: LPs after the associative one; history: per
    iteration (lambda, max |n - n_hat| / W_max); normal: the corners' normal forces (N),
    in interfaces(assembly)'s order, 4 per interface; velocity: (blocks, 6) the last LP's
    mechanism (m/s, rad/s), load power per unit lambda 1 W; moving: blocks moving faster
    than move_tol of the fastest; opening_max_pressed: the largest normal opening speed
    (m/s, same scale) at a corner whose normal force exceeds PRESSED W_max (0 up to
    round-off: pressed contacts slide without opening); status: a sentence."""

    lam: float
    lam_associative: float
    converged: bool
    iterations: int
    history: list = field(default_factory=list)
    normal: np.ndarray = None
    velocity: np.ndarray = None
    moving: list = field(default_factory=list)
    opening_max_pressed: float = math.nan
    status: str = ""
    #: with solve(certify=True): per iteration k >= 1 (k, lambda_k, lambda_min, lambda_max),
    #: the range of collapse states with that iteration's mechanism (complementarity.certify;
    #: nan, nan: none); certified_range: that of the iteration returned
    certified: list = field(default_factory=list)
    certified_range: tuple = (math.nan, math.nan)


class NotConverged(RuntimeError):
    """The iteration stopped without a collapse state; .result holds what it reached."""

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result


def solve(assembly: Assembly, alpha, facets=8, relaxation=0.5, tol=1e-7, max_iter=200, move_tol=0.02,
          raise_on_failure=True, log=None, certify=False):
    """The non-associative multiplier at orientation alpha (rad); see the module's doc.
    relaxation in (0, 1]: the share of the new normal forces taken into n_hat; tol: on
    max |n - n_hat| / W_max and on lambda's relative change; log(str): one line per
    iteration if given.

    certify: also stop at the first iteration whose lambda_k is a collapse multiplier with
    that iteration's own mechanism: complementarity.certify finds the range of lambda over
    force fields in equilibrium, within Coulomb with their own n, with n = 0 where the
    mechanism opens and friction at its limit where it slides; lambda_k inside it (to tol,
    relative) is a collapse state by definition, whether or not the LP's normal forces have
    repeated. Two more LPs an iteration; the ranges are kept in Result.certified."""
    if not 0 < relaxation <= 1:
        raise ValueError(f"invalid relaxation {relaxation}: must lie in (0, 1]")
    if not tol > 0:
        raise ValueError(f"invalid tol {tol}: must be > 0")
    p = _Problem(assembly, alpha, facets)
    w_max = max(assembly.weight(i) for i in assembly.free())
    x, res = p.solve(mu_n=None)
    if x is None:
        r = Result(math.nan, math.nan, False, 0, status=f"the associative LP failed: {res.message}")
        return _fail(r, raise_on_failure)
    lam_assoc = x[p.lam_col]
    n_hat = x[p.n_cols].copy()
    history = [(lam_assoc, math.nan)]
    certified = []
    lam_prev = lam_assoc
    if log:
        log(f"iteration 0 (associative): lambda {lam_assoc:.9f}")
    for k in range(1, max_iter + 1):
        x, res = p.solve(mu_n=assembly.mu * n_hat)
        if x is None:
            r = Result(math.nan, lam_assoc, False, k, history, n_hat,
                       status=f"the LP of iteration {k} failed: {res.message}")
            return _fail(r, raise_on_failure)
        lam = float(x[p.lam_col])
        near = p.least_normal(assembly.mu * n_hat, n_hat, lam, tol * max(1.0, lam))
        if near is None:
            r = Result(math.nan, lam_assoc, False, k, history, n_hat,
                       status=f"the least-normal-force LP of iteration {k} failed")
            return _fail(r, raise_on_failure)
        n = near[p.n_cols]
        change = float(np.abs(n - n_hat).max(initial=0.0)) / w_max
        history.append((lam, change))
        if log:
            log(f"iteration {k}: lambda {lam:.9f}, max |n - n_hat| / W_max {change:.3e}")
        if certify:
            from .complementarity import _certify

            lo, hi = _certify(p, p.velocity(res))
            certified.append((k, lam, lo, hi))
            if log:
                log(f"iteration {k}: collapse states with its mechanism: lambda {lo:.9f} to {hi:.9f}")
            slack = tol * max(1.0, abs(lam))
            if lo - slack <= lam <= hi + slack and lam < LAMBDA_CAP * (1 - 1e-9):
                velocity = p.velocity(res)
                return Result(lam, lam_assoc, True, k, history, n, velocity, _moving(assembly, velocity, move_tol),
                              math.nan, f"certified at iteration {k}: lambda_k is a collapse state with its mechanism "
                              f"(collapse states {lo:.6g} to {hi:.6g}; relaxation {relaxation:g})",
                              certified, (lo, hi))
        if change <= tol and abs(lam - lam_prev) <= tol * max(1.0, abs(lam)):
            if lam >= LAMBDA_CAP * (1 - 1e-9):
                r = Result(lam, lam_assoc, False, k, history, n, status=f"lambda reached the cap {LAMBDA_CAP}: "
                           "nothing collapses")
                return _fail(r, raise_on_failure)
            velocity = p.velocity(res)
            return Result(lam, lam_assoc, True, k, history, n, velocity, _moving(assembly, velocity, move_tol),
                          p.opening_max_pressed(velocity, n, PRESSED * w_max),
                          f"converged in {k} iterations (tol {tol:g}, relaxation {relaxation:g})",
                          certified, certified[-1][2:] if certified else (math.nan, math.nan))
        n_hat = n_hat + relaxation * (n - n_hat)
        lam_prev = lam
    r = Result(lam, lam_assoc, False, max_iter, history, n, certified=certified,
               status=f"not converged in {max_iter} iterations: last max |n - n_hat| / W_max {change:.3e}, "
                      f"last lambda change {abs(lam - history[-2][0]):.3e} (tol {tol:g}, relaxation {relaxation:g})")
    return _fail(r, raise_on_failure)


def _fail(result, raise_on_failure):
    if raise_on_failure:
        raise NotConverged(result.status, result)
    return result


class _Problem:
    """The LP's matrices, built once: equilibrium rows (6 per free block) over the columns
    (n, t1, t2) per interface corner, a roller's reaction, lambda; friction rows
    cos(phi_k) t1 + sin(phi_k) t2 (- mu n in the associative LP) <= (mu n_hat)."""

    def __init__(self, assembly, alpha, facets):
        self.assembly = assembly
        self.faces = interfaces(assembly)
        free = assembly.free()
        self.row_of = {i: 6 * k for k, i in enumerate(free)}
        self.centroid = [b.centroid for b in assembly.blocks]
        rows, cols, vals = [], [], []
        n_cols = []
        col = 0
        for face in self.faces:
            e1, e2 = _tangents(face.axis)
            for p in face.corners:
                for k, vec in enumerate((-face.normal, e1, e2)):
                    for block, sign in ((face.i, 1.0), (face.j, -1.0)):
                        if block in self.row_of:
                            _add_wrench(rows, cols, vals, self.row_of[block], col + k, sign * vec,
                                        p - self.centroid[block])
                n_cols.append(col)
                col += 3
        rollers = []  # (column, block)
        for i in free:
            r = assembly.roller[i]
            if r is not None:
                _add_wrench(rows, cols, vals, self.row_of[i], col, r, np.zeros(3))
                rollers.append((col, i))
                col += 1
        self.dead, self.live = assembly.dead_and_live(alpha)
        self.lam_col = col
        n_var = col + 1
        for r, v in enumerate(self.live):
            if v != 0.0:
                rows.append(r), cols.append(self.lam_col), vals.append(v)
        self.a_eq = coo_matrix((vals, (rows, cols)), shape=(6 * len(free), n_var)).tocsr()
        self.n_cols = np.array(n_cols, dtype=int)
        self.facets = facets
        self.a_assoc = _pyramid(self.n_cols, n_var, assembly.mu, facets)
        self.a_fixed = _pyramid(self.n_cols, n_var, 0.0, facets)
        self.bounds = [(None, None)] * n_var
        for cn in self.n_cols:
            self.bounds[cn] = (0.0, None)
        for rc, i in rollers:
            self.bounds[rc] = assembly.roller_bounds(i)
        self.bounds[self.lam_col] = (0.0, LAMBDA_CAP)
        self.c = np.zeros(n_var)
        self.c[self.lam_col] = -1.0
        self.proximity = PROXIMITY

    def solve(self, mu_n):
        """(x, scipy's result): the associative LP if mu_n is None, else the one with the
        shear capacity mu_n (N) per corner; x is None if HiGHS found no optimum."""
        if mu_n is None:
            a_ub, b_ub = self.a_assoc, np.zeros(self.a_assoc.shape[0])
        else:
            a_ub, b_ub = self.a_fixed, np.repeat(mu_n, self.facets)
        res = linprog(self.c, A_ub=a_ub, b_ub=b_ub, A_eq=self.a_eq, b_eq=-self.dead, bounds=self.bounds,
                      method="highs")
        return (res.x if res.status == 0 else None), res

    def least_normal(self, mu_n, n_hat, lam, slack):
        """Among the force fields of the fixed-capacity LP that carry lambda >= lam - slack,
        the one with the least total normal force, and among those the nearest n_hat
        (objective sum n + PROXIMITY sum |n - n_hat|); x or None. The LP's optimum is
        rarely unique in n: jammed contacts can carry any prestress the capacities allow,
        and a block's corners share its weight in many ways, so the vertex HiGHS returns
        can jump between iterations. This choice keeps no prestress the load does not
        need, and n = n_hat where n_hat is such a field."""
        m, n_var = len(self.n_cols), len(self.c)
        # columns: the LP's, then s >= |n - n_hat| per corner
        pick = coo_matrix((np.ones(m), (np.arange(m), self.n_cols)), shape=(m, n_var))
        eye = coo_matrix((np.ones(m), (np.arange(m), np.arange(m))), shape=(m, m))
        zeros = coo_matrix((self.a_fixed.shape[0], m))
        a_ub = vstack([hstack([self.a_fixed, zeros]), hstack([pick, -eye]), hstack([-pick, -eye])]).tocsr()
        b_ub = np.concatenate([np.repeat(mu_n, self.facets), n_hat, -n_hat])
        a_eq = hstack([self.a_eq, coo_matrix((self.a_eq.shape[0], m))]).tocsr()
        bounds = list(self.bounds) + [(0.0, None)] * m
        bounds[self.lam_col] = (max(0.0, lam - slack), LAMBDA_CAP)
        c = np.zeros(n_var + m)
        c[self.n_cols] = 1.0
        c[n_var:] = self.proximity
        res = linprog(c, A_ub=a_ub, b_ub=b_ub, A_eq=a_eq, b_eq=-self.dead, bounds=bounds, method="highs")
        return res.x[:n_var] if res.status == 0 else None

    def velocity(self, res):
        """The dual of the equilibrium rows, per block, scaled to unit load power."""
        u = np.asarray(res.eqlin.marginals)
        scale = float(self.live @ u)
        u = u / scale if scale != 0 else u
        velocity = np.zeros((len(self.assembly.blocks), 6))
        for i, r in self.row_of.items():
            velocity[i] = u[r:r + 6]
        return velocity

    def opening_max_pressed(self, velocity, n, n_tol):
        """The largest normal opening speed at a corner carrying more than n_tol (N)."""
        out, k = 0.0, 0
        for f in self.faces:
            for p in f.corners:
                if n[k] > n_tol:
                    dv = (point_velocity(velocity[f.j], self.centroid[f.j], p)
                          - point_velocity(velocity[f.i], self.centroid[f.i], p))
                    out = max(out, abs(float(dv @ f.normal)))
                k += 1
        return out


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


def _pyramid(n_cols, n_var, mu, facets):
    """Rows cos(phi) t1 + sin(phi) t2 - mu n <= 0, phi = 2 pi k / facets, per corner
    (the n term left out when mu is 0: the fixed-capacity rows)."""
    rows, cols, vals = [], [], []
    r = 0
    for cn in n_cols:
        for k in range(facets):
            phi = 2 * math.pi * k / facets
            for c, v in ((cn + 1, math.cos(phi)), (cn + 2, math.sin(phi)), (cn, -mu)):
                if abs(v) > 1e-15:
                    rows.append(r), cols.append(c), vals.append(v)
            r += 1
    return coo_matrix((vals, (rows, cols)), shape=(r, n_var)).tocsr()


def _moving(assembly, velocity, tol):
    """Blocks whose fastest corner moves faster than tol times the fastest block's."""
    speed = np.zeros(len(assembly.blocks))
    for i, b in enumerate(assembly.blocks):
        speed[i] = max(np.linalg.norm(point_velocity(velocity[i], b.centroid, p)) for p in corners_of(b))
    top = speed.max()
    return [i for i in range(len(speed)) if top > 0 and speed[i] > tol * top]


def case(specimen, alpha, **options):
    """One corner case as a JSON-able dict: the non-associative and the associative
    multipliers, convergence, the history and the moving blocks' labels."""
    a = Assembly.from_specimen(specimen)
    r = solve(a, alpha, raise_on_failure=False, **options)
    return {"lam": r.lam, "lam_associative": r.lam_associative, "converged": r.converged,
            "iterations": r.iterations, "history": r.history, "status": r.status,
            "moving": r.moving, "labels": [a.blocks[i].label() for i in r.moving],
            "opening_max_pressed": r.opening_max_pressed, "alpha": alpha, "ends": specimen.ends,
            "mu": specimen.mu, "certified": r.certified, "certified_range": list(r.certified_range)}


def diagnose(assembly, alpha, relaxation=0.5, iterations=40, proximity=PROXIMITY, facets=8, tol=1e-4, log=None,
             certify=False, on_row=None, certify_time=None):
    """solve's iteration with what moves in it (docs/corner-nonassociative.md, section 4):
    per iteration a dict of lambda, the largest change of a corner's normal force and of an
    interface's resultant normal force (sum of its 4 corners) against n_hat, the largest
    change against the iterate before last (0 for a two-state cycle), all / W_max, and the
    labels of the interface where the corner change is largest. proximity replaces
    PROXIMITY in the choice among optima; certify: also "certified", the range of lambda
    of the collapse states with that iteration's mechanism (complementarity.certify; nan:
    none, or not decided within certify_time s per LP), and "cpu_s", the process time
    since the start; on_row(rows) after every
    iteration if given. Stops when the corner change is below tol, or after `iterations`."""
    import time

    t0 = time.process_time()
    p = _Problem(assembly, alpha, facets)
    p.proximity = proximity
    w_max = max(assembly.weight(i) for i in assembly.free())
    x, _ = p.solve(mu_n=None)
    n_hat = x[p.n_cols].copy()
    found, rows = [n_hat.copy()], []  # the LPs' normal forces, iteration 0 on
    for k in range(1, iterations + 1):
        x, res = p.solve(mu_n=assembly.mu * n_hat)
        lam = float(x[p.lam_col])
        n = p.least_normal(assembly.mu * n_hat, n_hat, lam, tol * max(1.0, lam))[p.n_cols]
        where = int(np.argmax(np.abs(n - n_hat))) // 4
        face = p.faces[where]
        row = {"iteration": k, "lam": lam, "corner": float(np.abs(n - n_hat).max()) / w_max,
               "interface": float(np.abs((n - n_hat).reshape(-1, 4).sum(axis=1)).max()) / w_max,
               "against_k_minus_2": float(np.abs(n - found[-2]).max()) / w_max if len(found) > 1 else math.nan,
               "at": f"{assembly.blocks[face.i].label()}/{assembly.blocks[face.j].label()}"}
        if certify:
            from .complementarity import _certify

            row["certified"] = list(_certify(p, p.velocity(res), time_limit=certify_time))
            row["cpu_s"] = time.process_time() - t0
        rows.append(row)
        if on_row:
            on_row(rows)
        if log:
            log(" ".join(f"{key} {v:.4g}" if isinstance(v, float) else f"{key} {v}" for key, v in row.items()))
        if row["corner"] < tol:
            break
        found.append(n.copy())
        n_hat = n_hat + relaxation * (n - n_hat)
    return rows


def main(argv=None):
    """python -m rocking.corner_blocks.nonassoc --ends free --out DIR: the paper's corner (or
    --courses, --blocks) at its five orientations (or --cases), one JSON per case
    (nonassoc_<ends>_mu<mu>_<i>[_<courses>x<blocks>].json, as study.py names its LP
    cases), cached: a case whose file exists is not rerun."""
    import argparse
    import json
    import sys
    import time
    from pathlib import Path

    from .specimen import ORIENTATIONS, Specimen

    p = argparse.ArgumentParser(prog="python -m rocking.corner_blocks.nonassoc")
    p.add_argument("--ends", default="free")
    p.add_argument("--mu", type=float, default=0.66)
    p.add_argument("--relaxation", type=float, default=0.5)
    p.add_argument("--tol", type=float, default=1e-7)
    p.add_argument("--max-iter", type=int, default=200)
    p.add_argument("--cases", default="0,1,2,3,4", help="indices into the five orientations")
    p.add_argument("--courses", type=int, default=9)
    p.add_argument("--blocks", type=int, default=7)
    p.add_argument("--out", required=True)
    p.add_argument("--diagnose", action="store_true",
                   help="run diagnose() instead (--max-iter iterations, --proximity): diagnose_*.json in --out")
    p.add_argument("--proximity", type=float, default=PROXIMITY)
    p.add_argument("--certify", action="store_true",
                   help="stop at the first iterate that is a collapse state with its own mechanism "
                        "(solve(certify=True)): nonassoc_certify_*.json")
    p.add_argument("--least", action="store_true",
                   help="the least collapse multiplier by complementarity.least (MILP, --time-limit s): "
                        "least_*.json")
    p.add_argument("--time-limit", type=float, default=600.0)
    p.add_argument("--certify-time", type=float, default=None,
                   help="with --diagnose --certify: HiGHS's time limit per certify LP (s)")
    p.add_argument("--y-scale", type=float, default=10.0)
    args = p.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    if args.diagnose:
        for i in (int(k) for k in args.cases.split(",")):
            alpha, label = ORIENTATIONS[i]
            spec = Specimen(ends=args.ends, mu=args.mu, courses=args.courses, blocks=args.blocks)
            name = (f"diagnose_{args.ends}_{i}_{args.courses}x{args.blocks}_r{args.relaxation:g}"
                    f"_p{args.proximity:g}{'_certify' if args.certify else ''}.json")
            # written after every iteration: a run stopped early keeps what it found
            diagnose(Assembly.from_specimen(spec), alpha, args.relaxation, args.max_iter, args.proximity,
                     tol=args.tol, log=lambda s: print(f"{args.ends} {label}: {s}", file=sys.stderr, flush=True),
                     certify=args.certify, certify_time=args.certify_time,
                     on_row=lambda rows: (out / name).write_text(json.dumps(rows)))
        return
    for i in (int(k) for k in args.cases.split(",")):
        suffix = "" if (args.courses, args.blocks) == (9, 7) else f"_{args.courses}x{args.blocks}"
        spec = Specimen(ends=args.ends, mu=args.mu, courses=args.courses, blocks=args.blocks)
        alpha, label = ORIENTATIONS[i]
        if args.least:
            from . import complementarity

            path = out / f"least_{args.ends}_mu{args.mu:g}_{i}{suffix}.json"
            if path.is_file():
                continue
            r = complementarity.least(Assembly.from_specimen(spec), alpha, time_limit=args.time_limit,
                                      y_scale=args.y_scale)
            row = {"lower": r.lower, "upper": r.upper, "status": r.status, "cpu_s": r.cpu_s, "n_max": r.n_max,
                   "y_scale": r.y_scale, "binaries": r.binaries, "bound_active": r.bound_active,
                   "time_limit": args.time_limit, "alpha": alpha, "ends": args.ends, "mu": args.mu}
            path.write_text(json.dumps(row))
            print(f"{args.ends} alpha {label}: least collapse multiplier in [{r.lower:.4f}, {r.upper:.4f}], "
                  f"{r.status}, {r.cpu_s:.0f} s CPU", flush=True)
            continue
        kind = "nonassoc_certify" if args.certify else "nonassoc"
        path = out / f"{kind}_{args.ends}_mu{args.mu:g}_{i}{suffix}.json"
        if path.is_file():
            continue
        t0 = time.process_time()
        r = case(spec, alpha, relaxation=args.relaxation, tol=args.tol, certify=args.certify,
                 max_iter=args.max_iter, log=lambda s: print(f"{args.ends} {label}: {s}", file=sys.stderr, flush=True))
        r["cpu_s"] = time.process_time() - t0
        r["relaxation"], r["tol"] = args.relaxation, args.tol
        path.write_text(json.dumps(r))
        print(f"{args.ends} alpha {label}: lambda {r['lam']:.4f} (associative {r['lam_associative']:.4f}), "
              f"{r['status']}, {r['cpu_s']:.0f} s CPU", flush=True)


if __name__ == "__main__":
    main()
