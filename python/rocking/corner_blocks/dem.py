"""The DEM tilting test in LMGC90 (non-smooth contact dynamics) through the
`compas_lmgc90` wrapper: rigid polyhedral blocks, the contact law IQS_CLB (rigid,
no-tension contact with Coulomb friction mu, inelastic impacts), NLGS solver.

The wrapper has no gravity setting: the engine's gravity is -9.81 m/s2 along z, fixed
(a free block falls 0.5 g t^2 = 49.05 mm in 0.1 s). The horizontal component of the tilted
table is applied as a force lambda m g at every free block's centroid (the engine's
driven force dof), whose whole staircase, every level and its hold (`schedule`), is given
as a time table before the run starts; nothing is changed while it runs (the note above
`state` says why). For rigid blocks with Coulomb friction only the ratio of the lateral
to the vertical load matters, so this is the tilting table with lambda = tan(beta), up to
the time scale of the motion.

One driven force component per block: with two (Fx and Fy) on the same body this
version of the wrapper corrupts its memory (a crash at exit, "munmap_chunk(): invalid
pointer", or a segmentation fault when both are changed during the run). So the
assembly is turned about z by -alpha, which brings the load direction
d = load_direction(alpha) onto -x, and only Fx is driven; positions are turned back.
A roller end (ends=outOfPlane) is a driven velocity along x or y, so the DEM takes it
only where the turned restraint stays on an axis (alpha = 0 or pi/2).

Protocol (the paper's, section 3, with fixed holds): after settling under gravity,
lambda grows by `step`, each level held for `hold` seconds. Collapse is the first level
at whose end the fastest block corner is faster than `v_tol` (m/s), or a block has moved
more than `collapse` (m) from its settled position; lambda_c is that level. The paper
holds each level until rest; here the staircase is fixed before the run, so every hold
has the same length. The rest speed must sit well above the speed at which a standing
assembly still moves at the end of a hold (`rest_speed` says how it is chosen).

LMGC90 keeps one simulation per process: `run_isolated` runs each test in a fresh
Python process (`python -m rocking.corner_blocks.dem`, JSON in and out)."""

from dataclasses import asdict, dataclass
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

from .assembly import Assembly
from .draw import corners_of

CHECK = 0.05  # s: how often a hold looks for the collapse displacement
_ALIVE = []  # solvers kept until os._exit: the engine's teardown corrupts the heap (see main)
FACES = [[3, 2, 1, 0], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
DOFS = ("Vx", "Vy", "Vz", "Rx", "Ry", "Rz")


#: The rest speed (m/s) of single blocks, stacks and the 3 x 3 corner: at the end of a hold
#: that stands they move at 1e-17 m/s (a block) to 3e-6 m/s (the 3 x 3 corner), a residual
#: of the contact solver that falls with the time step and the solver's tolerance, so
#: 1 mm/s lies 300 or more times above it (docs/corner-blocks.md, "The DEM's own numerics").
V_TOL = 1e-3

#: The rest speed (m/s) of the paper's corner (9 courses of 7 blocks). A level of it that
#: stands still creeps at the end of its 0.3 s hold: 1.1e-6 to 9.9e-4 m/s in the study at
#: 1 mm/s (free ends 8.8e-5 to 9.9e-4), so 1 mm/s called two collapses at 1.0e-3 m/s, at
#: the background's edge. 10 mm/s sits 10 times above the fastest level that stood at 1 mm/s,
#: and the displacement (`collapse`, 5 mm, 2.5 times the largest creep of those levels)
#: still catches a collapse that accelerates slowly; a displacement alone cannot, as a
#: collapsing level moves only 0.7-5.7 mm in a hold while a standing one creeps up to 2 mm
#: (docs/corner-blocks.md, "Decision on the rest threshold"). At 10 mm/s the study's
#: collapsing levels end at 1.0e-2 to 5.3e-2 m/s, and four levels that ended at 1.0e-3 to
#: 7.0e-3 m/s count as standing; held 0.9 s, two of them (free ends) slide on and collapse
#: and two (fixed ends) come to rest, so no speed read at the end of a fixed hold separates
#: them: the study's lambda_c is one step high in three of those cases ("The longer hold").
V_TOL_CORNER = 1e-2


def rest_speed(courses, blocks):
    """The default rest speed v_tol (m/s) of a corner of `courses` courses and `blocks` full
    blocks a wall: V_TOL_CORNER for the paper's corner and larger ones (courses >= 9 and
    blocks >= 7), V_TOL otherwise. The background was measured on the 3 x 3 corner and on
    the paper's; a corner between them takes V_TOL unmeasured (pass v_tol to choose)."""
    return V_TOL_CORNER if courses >= 9 and blocks >= 7 else V_TOL


@dataclass
class Protocol:
    """step: lambda increment; v_tol: rest (m/s); collapse: displacement (m); dt: time
    step (s); settle: under gravity alone (s); hold: each level (s); start: first lambda;
    lam_max: the last; size_factor: the engine's contact detection room (see SIZE_FACTOR);
    nlgs_tol, nlgs_relax: the contact solver's tolerance and relaxation (see NLGS), 0 for
    the wrapper's own (1.666e-4 and 0.1). v_tol = inf: collapse is the displacement alone;
    its default is the small assemblies' (V_TOL), the paper's corner takes V_TOL_CORNER
    (rest_speed)."""

    step: float = 0.005
    v_tol: float = V_TOL
    collapse: float = 0.005
    dt: float = 1e-3
    settle: float = 0.1
    hold: float = 0.3
    start: float = 0.0
    lam_max: float = 1.5
    size_factor: int = 4
    nlgs_tol: float = 0.0
    nlgs_relax: float = 0.0


def turn(alpha):
    """The rotation about z (3 x 3) that brings load_direction(alpha) onto -x."""
    c, s = math.cos(alpha), math.sin(alpha)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def vertices_faces(block, rot):
    """The block, turned by rot, as the wrapper's raw polyhedron: 8 corners, 6 outward quads."""
    x0, y0, z0 = block.lo
    x1, y1, z1 = block.hi
    v = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0], [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]
    return {"vertices": (np.array(v) @ rot.T).tolist(), "faces": FACES}


def build(assembly: Assembly, protocol: Protocol, alpha):
    """A preprocessed compas_lmgc90 Solver of the assembly turned by turn(alpha): fixed
    blocks held in all 6 dofs, rollers along their (turned) axis, Fx driven on every free
    block by the staircase of `schedule`, given before the run (see the note above state)."""
    from compas_lmgc90.solver import Solver

    if assembly.clamp != math.inf:
        raise ValueError(f"invalid clamp {assembly.clamp}: the DEM has no bounded restraint (the wrapper drives "
                         "a velocity or a force, no spring); only a rigid roller (clamp inf)")
    rot = turn(alpha)
    times, lams = schedule(protocol)
    solver = Solver(dt=protocol.dt, theta=0.5, density=assembly.rho)
    if protocol.size_factor != 4:
        size_factor(protocol.size_factor)
    if protocol.nlgs_tol or protocol.nlgs_relax:
        nlgs(tol=protocol.nlgs_tol or None, relax=protocol.nlgs_relax or None)
    solver.geometry_from_v_f([vertices_faces(b, rot) for b in assembly.blocks])
    for i, b in enumerate(assembly.blocks):
        if assembly.fixed[i]:
            for dof in DOFS:
                solver.apply_velocity(i, dof, 0.0)
            continue
        if assembly.roller[i] is not None:
            solver.apply_velocity(i, _roller_dof(rot @ assembly.roller[i]), 0.0)
        solver.apply_force(i, "Fx", np.array([times, -lams * assembly.weight(i)]))
    solver.contact_law("IQS_CLB", assembly.mu, alert=1e-3 * min(min(b.size) for b in assembly.blocks) * 10)
    solver.preprocess()
    return solver


#: The room of the engine's polyhedron contact detection (PRPRx_LowSizeArrayPolyr). Its
#: default 4 stops a corner of 3 courses x 3 blocks at the first step ("ERROR
#: [PRPRx::STO_fill_this_array] ... you reach the allocated size", STOP 1); 8 runs it;
#: the paper's corner needs 11 or more and runs with 16 (docs/corner-blocks.md).
SIZE_FACTOR = 16  # the engine's own default is 4


def size_factor(factor):
    """PRPRx_LowSizeArrayPolyr(factor), which the wrapper does not expose: the engine's
    Fortran setter, exported by the wrapper's library, called by reference."""
    import ctypes

    from compas_lmgc90 import _lmgc90

    lib = ctypes.CDLL(_lmgc90.__file__)
    lib.__prprx_MOD_set_size_factor_polyr_prprx(ctypes.byref(ctypes.c_int(factor)))


#: The contact solver's parameters, which the wrapper (compas_lmgc90 0.1.11) passes to the
#: engine's set_nlgs_parameter at every step from its library's writable data and does not
#: expose: name -> (offset of the value from the exported lmgc90_compute_one_step, ctypes
#: type, the wrapper's value). tol: the NLGS convergence tolerance (norm QM/16); relax:
#: its relaxation; the loop is up to 500 checks of 50 Gauss-Seidel sweeps each.
NLGS = {"tol": (0x53B850 - 0x7D8E0, "c_double", 1.666e-4), "relax": (0x53B860 - 0x7D8E0, "c_double", 0.1)}


def nlgs(**values):
    """Set the contact solver's tol and/or relax (None: leave it). Refuses, naming the
    parameter, when the value found is not the wrapper's own: another build of the wrapper
    keeps its data elsewhere, and a blind write there would corrupt it. Once per process
    (one LMGC90 run per process: run_isolated)."""
    import ctypes

    from compas_lmgc90 import _lmgc90

    lib = ctypes.CDLL(_lmgc90.__file__)
    anchor = ctypes.cast(lib.lmgc90_compute_one_step, ctypes.c_void_p).value
    for name, value in values.items():
        if value is None:
            continue
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"invalid nlgs_{name}: must be positive and finite, got {value}")
        offset, kind, default = NLGS[name]
        cell = getattr(ctypes, kind).from_address(anchor + offset)
        if abs(cell.value - default) > 1e-6 * default:
            raise RuntimeError(f"nlgs_{name}: the wrapper's value is not where compas_lmgc90 0.1.11 keeps it "
                               f"(found {cell.value!r}, expected {default}); this build's solver cannot be tuned")
        cell.value = value


def _roller_dof(direction):
    for k, name in enumerate(("Vx", "Vy")):
        if abs(abs(direction[k]) - 1.0) < 1e-9:
            return name
    raise ValueError("invalid alpha: the DEM takes ends=outOfPlane only at alpha = 0 or pi/2")


# The load is not changed during the run: the engine adds every value given to a driven
# force to the ones before (a block given 0.2 m g twice accelerates at 0.4 g), and runs
# that change it step by step end, at random, in heap corruption ("double free or
# corruption", STOP 1) or a blow-up (blocks at 10 m/s): the same input gave 0.4095, a
# crash, 0.4095 in three runs. The staircase is given whole before the run instead.


def state(result, n):
    """(centroids (n, 3), frames (n, 3, 3)) of a step's result."""
    return (np.array([result.bodies[i] for i in range(n)]),
            np.array([np.array(result.body_frames[i]).reshape(3, 3) for i in range(n)]))


def corner_positions(assembly, rot, c0, f0, c, f):
    """Every block's corners now (turned frame), from its settled centroid/frame and the
    current ones; rot: the turn of the assembly."""
    out = []
    for i, b in enumerate(assembly.blocks):
        step = f[i].T @ f0[i]  # the wrapper's own composition (its _update_meshes)
        out.append((corners_of(b) @ rot.T - c0[i]) @ step.T + c[i])
    return out


def levels(protocol):
    """The lambda of every load step, start .. lam_max."""
    count = int(math.floor((protocol.lam_max - protocol.start) / protocol.step + 1e-9)) + 1
    return [protocol.start + k * protocol.step for k in range(count)]


def schedule(protocol):
    """(times, lambdas) of the staircase: 0 while settling, then each level reached in one
    time step and held for `hold` seconds."""
    times, lams = [0.0, protocol.settle], [0.0, 0.0]
    t = protocol.settle
    for lam in levels(protocol):
        times += [t + protocol.dt, t + protocol.hold]
        lams += [lam, lam]
        t += protocol.hold
    return np.array(times), np.array(lams)


def run(assembly: Assembly, alpha, protocol: Protocol, log=None):
    """The tilting test in this process (which it spends: one LMGC90 run per process)."""
    t0 = time.process_time()
    solver = build(assembly, protocol, alpha)
    _ALIVE.append(solver)
    n = len(assembly.blocks)
    reach = np.array([np.linalg.norm(b.size) / 2 for b in assembly.blocks])
    rot = turn(alpha)
    c, f = state(solver.lmgc90.compute_one_step(), n)
    steps = 1

    def advance(seconds):
        """Steps for `seconds`; the fastest block corner's speed (m/s) over the last step."""
        nonlocal c, f, steps
        speed = math.inf
        for _ in range(max(1, int(round(seconds / protocol.dt)))):
            cn, fn = state(solver.lmgc90.compute_one_step(), n)
            omega = np.linalg.norm((fn - f).reshape(n, -1), axis=1)  # |dR| = sqrt(2) |omega| dt
            speed = float(np.max(np.linalg.norm(cn - c, axis=1) + omega / math.sqrt(2) * reach) / protocol.dt)
            c, f, steps = cn, fn, steps + 1
        return speed

    advance(protocol.settle - protocol.dt)
    c0, f0 = c.copy(), f.copy()
    history, lam, collapsed = [], math.nan, False
    for lam in levels(protocol):
        # in slices, so that a collapse ends the run before falling blocks overflow the
        # engine's contact room (a 1 s hold did on the small corner)
        for _ in range(max(1, int(round(protocol.hold / CHECK)))):
            speed = advance(protocol.hold / max(1, int(round(protocol.hold / CHECK))))
            disp = _displacements(assembly, rot, c0, f0, c, f)
            if disp.max() > protocol.collapse:
                break
        rested = speed < protocol.v_tol
        history.append((round(lam, 10), rested, speed, float(disp.max()), steps))
        if log:
            log(f"lambda {lam:.4f}: rest {rested}, speed {speed:.2e} m/s, displacement {disp.max() * 1e3:.2f} mm")
        if not rested or disp.max() > protocol.collapse:
            collapsed = True
            break
    advance(0.1)  # the mechanism a little further on, so the moving blocks stand out
    disp = _displacements(assembly, rot, c0, f0, c, f)
    top = disp.max()
    moving = [i for i in range(n) if not assembly.fixed[i] and disp[i] > 0.1 * top] if top > 0 else []
    corners = [p @ rot for p in corner_positions(assembly, rot, c0, f0, c, f)]  # back to the corner's frame
    return {"lam": lam if collapsed else math.nan, "collapsed": collapsed, "alpha": alpha,
            "protocol": asdict(protocol), "history": history, "moving": moving,
            "displacement": disp.tolist(), "corners": [p.tolist() for p in corners],
            "steps": steps, "cpu_s": time.process_time() - t0}


def _displacements(assembly, rot, c0, f0, c, f):
    """Largest corner displacement (m) of every block since settling."""
    now = corner_positions(assembly, rot, c0, f0, c, f)
    return np.array([np.linalg.norm(p - corners_of(b) @ rot.T, axis=1).max() for p, b in zip(now, assembly.blocks)])


def run_isolated(spec, alpha, protocol: Protocol, timeout=None):
    """`run` in a fresh Python process. spec: a dict, {"specimen": {Specimen fields}} or
    {"boxes": [[lo, hi], ...], "mu": ...} (free boxes on a fixed table)."""
    job = {"spec": spec, "alpha": alpha, "protocol": asdict(protocol)}
    return run_module("rocking.corner_blocks.dem", job, "the LMGC90 run", timeout)


def run_module(module, job, what, timeout=None):
    """`python -m module` in a fresh process (LMGC90 keeps one simulation a process) with the
    dict `job` as JSON on its standard input; the JSON of its last output line. A failure raises
    RuntimeError "`what` failed: " with the engine's last ERROR line and the last line it printed."""
    out = subprocess.run([sys.executable, "-m", module], input=json.dumps(job), capture_output=True,
                         text=True, timeout=timeout)
    if out.returncode != 0:
        lines = [" ".join(x.split()) for x in out.stderr.replace("\0", "").splitlines() if x.strip()]
        errors = [x for x in lines if x.startswith("ERROR")]
        tail = "; ".join(errors[-1:] + lines[-1:]) or f"exit status {out.returncode}"
        raise RuntimeError(f"{what} failed: {tail}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def assembly_of(spec):
    """The Assembly a run_isolated spec describes."""
    from .assembly import box, on_table
    from .specimen import Specimen

    if "specimen" in spec:
        return Assembly.from_specimen(Specimen(**spec["specimen"]))
    return on_table([box(lo, hi) for lo, hi in spec["boxes"]], mu=spec.get("mu", 0.66))


def main():
    job = json.loads(sys.stdin.read())
    result = run(assembly_of(job["spec"]), job["alpha"], Protocol(**job["protocol"]),
                 log=lambda s: print(s, file=sys.stderr, flush=True))
    print(json.dumps(result), flush=True)
    sys.stderr.flush()
    # the engine's state is torn down at exit with a heap error ("corrupted size vs.
    # prev_size", a segmentation fault while collecting); the result is out: skip it
    os._exit(0)


if __name__ == "__main__":
    main()
