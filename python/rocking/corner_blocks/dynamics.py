"""The block assembly under a ground-motion record in LMGC90 (docs/corner-record.md).

The base moves as the record: every fixed block (the taped first course, clamped ends,
the table of a test case) is given a driven velocity along the load direction, the
record's integral, as a time table handed to the engine before the run (the wrapper
takes a driven velocity as a [2, n] table, as it takes the tilting test's staircase of
forces; nothing is changed while it runs: dem.py says why). The other five velocity
components of those blocks are held at 0. Gravity is the engine's -9.81 m/s2 along z.
No force is driven: the blocks feel the ground only through their contacts, as a
building does. A driven velocity was chosen over a body force -m ag(t) on every free
block because the force route drives one Fx per free block and the engine adds every
force value given to the earlier ones (dem.py); the velocity route drives the few
fixed blocks only and is the ground motion itself.

Frame and sign: the assembly is turned by dem.turn(alpha), which brings the load
direction d = load_direction(alpha) (outwards) onto -x. The record's acceleration ag
is taken along d, as the FMU's ag is along the macroblock body's outward +x
(docs/corner.md section 10): a negative ag pushes the blocks outwards. So the base's
velocity along the turned x is -v(t), v(t) = integral of ag from the record's start.
A block's outward rotation is its rotation about the turned y axis with its top
moving along -x, the FMU's theta > 0.

One LMGC90 simulation per process: `run_isolated` runs each record in a fresh Python
process (`python -m rocking.corner_blocks.dynamics`, JSON in and out)."""

from dataclasses import asdict, dataclass
import json
import math
import os
import sys
import time

import numpy as np

from . import dem

#: A free block has fallen once it has turned by more than this (rad) or its centroid
#: has dropped by more than half its height: the run ends there.
FALL = 0.8


@dataclass
class Protocol:
    """dt: time step (s); settle: under gravity, base at rest, before the record (s);
    tail: base at rest after the record (s); every: record the state every this many
    steps; size_factor: the engine's contact room (dem.SIZE_FACTOR); theta_ov: the
    rotation (rad) whose last upward crossing before a fall is the time of collapse."""

    dt: float = 1e-3
    settle: float = 0.1
    tail: float = 1.0
    every: int = 10
    size_factor: int = 8
    theta_ov: float = 0.4


def strong_part(time_s, acc, start, length):
    """(time from 0, acc, t0) of the window [t0, t0 + length] of a record (s), t0 the
    sample at or before `start` (s) where acc last changed sign, so that the window
    starts next to ag = 0."""
    time_s, acc = np.asarray(time_s, float), np.asarray(acc, float)
    k = int(np.searchsorted(time_s, start, side="right")) - 1
    while k > 0 and acc[k] * acc[k - 1] > 0 and acc[k] != 0:
        k -= 1
    end = int(np.searchsorted(time_s, time_s[k] + length + 1e-9, side="right"))
    return time_s[k:end] - time_s[k], acc[k:end].copy(), float(time_s[k])


def velocity(time_s, acc, at):
    """v(at) (m/s): the integral from time_s[0] of the acceleration (m/s2) taken linear
    between its samples, exact at any time `at` (s); ag = 0 before and after the record."""
    time_s, acc, at = np.asarray(time_s, float), np.asarray(acc, float), np.asarray(at, float)
    dt = np.diff(time_s)
    nodes = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * dt)])
    k = np.clip(np.searchsorted(time_s, at, side="right") - 1, 0, len(time_s) - 2)
    s = np.clip(at - time_s[k], 0.0, dt[k])
    inside = nodes[k] + acc[k] * s + (acc[k + 1] - acc[k]) * s * s / (2 * dt[k])
    return np.where(at < time_s[0], 0.0, np.where(at >= time_s[-1], nodes[-1], inside))


def base_table(time_s, acc, scale, protocol: Protocol):
    """The driven velocity of the base along the turned x: [times, values], at every
    time step from 0 (settling, at rest) to the record's end plus the tail."""
    duration = float(time_s[-1] - time_s[0]) + protocol.tail
    steps = int(round((protocol.settle + duration) / protocol.dt)) + 1
    t = np.arange(steps) * protocol.dt
    v = -scale * velocity(np.asarray(time_s) - time_s[0], acc, t - protocol.settle)
    return np.array([t, v])


def build(assembly, alpha, table, protocol: Protocol):
    """A preprocessed Solver of the assembly turned by dem.turn(alpha): every fixed block
    driven along the turned x by `table`, held in its other 5 velocities; no force."""
    from compas_lmgc90.solver import Solver

    rot = dem.turn(alpha)
    solver = Solver(dt=protocol.dt, theta=0.5, density=assembly.rho)
    if protocol.size_factor != 4:
        dem.size_factor(protocol.size_factor)
    solver.geometry_from_v_f([dem.vertices_faces(b, rot) for b in assembly.blocks])
    for i in range(len(assembly.blocks)):
        if assembly.fixed[i]:
            solver.apply_velocity(i, "Vx", table)
            for dof in dem.DOFS[1:]:
                solver.apply_velocity(i, dof, 0.0)
        elif assembly.roller[i] is not None:
            raise ValueError("invalid ends: the record run takes ends=fixed or free (a roller end would "
                             "need a second driven velocity that moves with the ground)")
    solver.contact_law("IQS_CLB", assembly.mu, alert=1e-2 * min(min(b.size) for b in assembly.blocks))
    solver.preprocess()
    return solver


def outward_rotation(frames, frames0):
    """Each block's rotation (rad) about the turned y axis since settling, positive
    outwards (its top moving along -x), from the engine's frames."""
    out = []
    for f, f0 in zip(frames, frames0):
        r = f.T @ f0  # the wrapper's composition: p - c = r (p0 - c0)
        out.append(math.atan2(-r[0, 2], r[2, 2]))
    return np.array(out)


def run(assembly, alpha, time_s, acc, scale, track, protocol: Protocol, log=None):
    """The assembly under the record scaled by `scale` (this process is spent on it).
    track: the block indices whose mean outward rotation (volume-weighted) is recorded."""
    t0 = time.process_time()
    table = base_table(time_s, acc, scale, protocol)
    solver = build(assembly, alpha, table, protocol)
    dem._ALIVE.append(solver)
    n = len(assembly.blocks)
    free = [i for i in range(n) if not assembly.fixed[i]]
    vol = np.array([assembly.blocks[i].volume for i in track])
    half = np.array([assembly.blocks[i].size[2] / 2 for i in range(n)])
    steps = int(round(protocol.settle / protocol.dt))
    for _ in range(steps):
        c, f = dem.state(solver.lmgc90.compute_one_step(), n)
    c0, f0 = c.copy(), f.copy()
    total = int(round(float(table[0, -1]) / protocol.dt)) - steps
    times, mean_rot, max_rot, min_rot = [], [], [], []
    fallen, t_fall = False, math.nan
    for k in range(1, total + 1):
        c, f = dem.state(solver.lmgc90.compute_one_step(), n)
        if k % protocol.every and k != total:
            continue
        rot = outward_rotation(f, f0)
        tracked = rot[track]
        times.append(round(k * protocol.dt, 9))
        mean_rot.append(float(np.dot(vol, tracked) / vol.sum()))
        max_rot.append(float(tracked.max()))
        min_rot.append(float(tracked.min()))
        drop = c0[free, 2] - c[free, 2]
        if np.abs(rot[free]).max() > FALL or (drop > half[free]).any():
            fallen, t_fall = True, k * protocol.dt
            break
    side, t_collapse = collapse(times, max_rot, min_rot, protocol.theta_ov) if fallen else (0, math.nan)
    if log:
        log(f"scale {scale:.4f}: {'collapses' if fallen else 'stands'}, peak mean rotation "
            f"{max(mean_rot):.4f} rad, {k + steps} steps, {time.process_time() - t0:.1f} s CPU")
    return {"scale": scale, "alpha": alpha, "collapsed": fallen, "t_fall": t_fall,
            "fall_side": side, "t_collapse": t_collapse,
            "peak_rotation": float(max(mean_rot)), "least_rotation": float(min(min_rot)),
            "track": list(track), "time": times, "rotation": mean_rot, "rotation_max": max_rot,
            "rotation_min": min_rot, "protocol": asdict(protocol), "steps": k + steps,
            "cpu_s": time.process_time() - t0}


def collapse(times, rotation_max, rotation_min, theta_ov):
    """(side, time) of a fall: side +1 (outwards) when the tracked blocks' largest
    outward rotation at the end exceeds their largest inward one, else -1; time: the last
    time (linear between samples) at which that extreme passed theta_ov (rad) on that
    side, nan if it never did (the block that fell was not tracked)."""
    side = 1 if rotation_max[-1] >= -rotation_min[-1] else -1
    values = rotation_max if side > 0 else [-v for v in rotation_min]
    out = math.nan
    for k in range(1, len(values)):
        if values[k - 1] < theta_ov <= values[k]:
            out = times[k - 1] + (theta_ov - values[k - 1]) / (values[k] - values[k - 1]) * (times[k] - times[k - 1])
    return side, out


def assembly_of(spec):
    """dem.assembly_of(spec), and with spec["inner_restraint"] true a fixed slab against
    the inner face of WX above its first course: the rest of a building that holds the
    out-of-plane wall inwards (the macroblock body's one-sided restraint), moving with the
    ground. It starts 5 mm clear of WY's inner face so that it holds WX only."""
    from .assembly import box

    assembly = dem.assembly_of(spec)
    if spec.get("inner_restraint"):
        from .specimen import Specimen

        sp = Specimen(**spec["specimen"])
        slab = box((sp.t + 0.005, sp.t, sp.h), (sp.length, sp.t + 0.05, sp.height), course=-1)
        assembly.blocks.append(slab)
        assembly.fixed.append(True)
        assembly.roller.append(None)
    return assembly


def run_isolated(spec, alpha, time_s, acc, scale, track, protocol: Protocol, timeout=None):
    """`run` in a fresh Python process. spec: as dem.run_isolated's."""
    job = {"spec": spec, "alpha": alpha, "time": list(map(float, time_s)), "acc": list(map(float, acc)),
           "scale": scale, "track": list(track), "protocol": asdict(protocol)}
    return dem.run_module("rocking.corner_blocks.dynamics", job, "the LMGC90 record run", timeout)


def main():
    job = json.loads(sys.stdin.read())
    result = run(assembly_of(job["spec"]), job["alpha"], np.array(job["time"]), np.array(job["acc"]),
                 job["scale"], job["track"], Protocol(**job["protocol"]),
                 log=lambda s: print(s, file=sys.stderr, flush=True))
    print(json.dumps(result), flush=True)
    sys.stderr.flush()
    os._exit(0)  # the engine's teardown corrupts the heap (dem.main)


if __name__ == "__main__":
    main()
