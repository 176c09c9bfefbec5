"""Runs per second per core of pulse runs (issue 34's speed table): a rigid block and the same
block on a crushing bed under one-sine pulses, through the map's path (`rocking.maps.run_one`:
the native stepping loop; the tail cut where the body can no longer overturn: a rigid block's
by its energy at the pulse's end, the crushing bed's at its first free turning point; or run
to its stated length) and through `run_grid`
with the pulse as a record (today's path for a user scripting it), in one process.

    .venv/bin/python benches/map_speed.py [--tail 10] [--grid 8]

The table gives the runs, the CPU time of this process and the runs per CPU second (one
core); the machine's load average is printed first (on a shared machine wall time follows it).
"""

import argparse
import math
import os
import time

import numpy as np

from rocking import run_grid
from rocking.fmu import RockingFMU
from rocking.groundmotion.record import Record
from rocking.maps import MapSpec, body_scales, run_one
from rocking.pulses import Pulse

RIGID = dict(shape="solidRectangle", B=0.4, L=1.0, massModel="prism", H=2.0, interface="rigid")
CRUSHING = dict(RIGID, interface="elastoPlastic", kn=1e9, fm=2e5)


def timed(fn):
    c0 = time.process_time()
    n = fn()
    return n, time.process_time() - c0


def map_path(fmu, params, ws, amps, tail, cut):
    spec = MapSpec(params=params, shape="one-sine", frequencies=ws, amplitudes=amps, tail=tail, cut_tail=cut,
                   scales=body_scales(fmu, params))
    for w in ws:
        for a in amps:
            run_one(fmu, spec, w, a)
    return len(ws) * len(amps)


def grid_path(fmu, params, ws, amps, tail):
    scales = body_scales(fmu, params)
    n = 0
    for w in ws:
        pulse = Pulse("one-sine", 1.0, w * scales["p"])
        t, ag = pulse.samples()
        rec = Record(time=t, acc=ag, dt=float(t[1] - t[0]), name=f"one-sine w/p {w:g}")
        df = run_grid({"body": params}, records=[rec], scales=[a * scales["g_tan_alpha"] for a in amps],
                      workers=1, fmu=fmu, stop_time=pulse.duration + tail, outputs=("thetaOverAlpha", "impacts"))
        n += len(df)
    return n


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tail", type=float, default=10.0, help="s of free motion after the pulse (default 10)")
    ap.add_argument("--grid", type=int, default=8, help="frequencies and amplitudes per axis (default 8)")
    args = ap.parse_args()
    ws = list(np.linspace(1.0, 10.0, args.grid))
    amps = list(np.linspace(1.0, 8.0, args.grid))
    print(f"load average {os.getloadavg()[0]:.2f}; one-sine, w_p/p 1-10 x a_p/(g tan alpha) 1-8, "
          f"{args.grid} x {args.grid}, tail {args.tail:g} s")
    print(f"{'body':<10} {'path':<36} {'runs':>5} {'CPU s':>7} {'runs/s/core':>12}")
    with RockingFMU() as fmu:
        rows = [("rigid", "map (tail cut by energy)", lambda: map_path(fmu, RIGID, ws, amps, args.tail, True)),
                ("rigid", "map (tail run)", lambda: map_path(fmu, RIGID, ws, amps, args.tail, False)),
                ("rigid", "run_grid (pulse as a record)", lambda: grid_path(fmu, RIGID, ws, amps, args.tail)),
                ("crushing", "map (tail cut at a turning point)",
                 lambda: map_path(fmu, CRUSHING, ws, amps, args.tail, True)),
                ("crushing", "map (tail run)", lambda: map_path(fmu, CRUSHING, ws, amps, args.tail, False)),
                ("crushing", "run_grid (pulse as a record)", lambda: grid_path(fmu, CRUSHING, ws, amps, args.tail))]
        for body, path, fn in rows:
            n, cpu = timed(fn)
            print(f"{body:<10} {path:<36} {n:>5} {cpu:>7.2f} {n / cpu if cpu > 0 else math.inf:>12.1f}")


if __name__ == "__main__":
    main()
