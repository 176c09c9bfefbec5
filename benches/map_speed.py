"""Runs per second per core of pulse runs (issue 34's speed table): a rigid block and the same
block on a crushing bed under one-sine pulses, through the map's path (`rocking.maps.run_one`:
the native stepping loop; the tail cut where the body can no longer overturn: a rigid block's
by its energy at the pulse's end, the crushing bed's at its first free turning point; or run
to its stated length) and through `run_grid`
with the pulse as a record (today's path for a user scripting it), in one process; then issue
34's two targets, each the `rocking map` command as a user runs it (its process start, the FMU's
extraction, the pool of --workers 2, the tables and the plot): the default one-sine map of the
rigid block over 200 frequencies (w_p/p 1 to 10) and 15 amplitudes (a_p/(g tan alpha) 1 to 8),
every boundary bisected to 1e-3 relative (target: 30 s wall on 2 cores), and the full
200 x 200 grid (target: 2 minutes wall on 2 cores).

    .venv/bin/python benches/map_speed.py [--tail 10] [--grid 12] [--targets | --no-targets]

The first table gives the runs, the CPU time of this process and the runs per CPU second (one
core). The second the command's wall time, the CPU time of it and its workers, the cores it got
(CPU / wall) and the wall it would take with 2 cores of its own: the serial part (the
1-frequency map's CPU: start, imports, extraction, the workers' start, one column, the tables,
the plot) plus half the rest (--tail and --grid are the first table's). The machine's
load average is printed with each (on a shared machine wall time follows it).
"""

import argparse
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

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


def command(args):
    """(wall s, CPU s of the command and its workers, runs) of `rocking map ARGS` in a new process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as out:
        proc = subprocess.run([sys.executable, "-m", "rocking", "map", "--shape", "solidRectangle", "--B", "0.4",
                               "--H", "2", "--interface", "rigid", "--workers", "2", "--quiet", "--no-resume",
                               *args, "--out", out], capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if proc.returncode:
            raise SystemExit(f"rocking map {' '.join(args)}: exit {proc.returncode}\n{proc.stderr}")
        import pyarrow.parquet as pq
        runs = pq.read_metadata(Path(out) / "runs.parquet").num_rows
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, runs


def targets():
    """Issue 34's two wall-time targets, through the command."""
    cases = [("1 frequency x 15 (the serial part)", ["--frequencies", "5", "--amplitudes", "1:8:15"], None),
             ("200 x 15, to 1e-3 (default map)", ["--frequencies", "1:10:200", "--amplitudes", "1:8:15"], 30.0),
             ("200 x 200 full grid, to 1e-3", ["--frequencies", "1:10:200", "--amplitudes", "1:8:200"], 120.0)]
    print(f"\nload average {os.getloadavg()[0]:.2f}; rocking map, rigid block B 0.4 m x H 2 m, one-sine, "
          "--workers 2, tail 10 s")
    print(f"{'map':<36} {'runs':>6} {'wall s':>7} {'CPU s':>7} {'cores':>6} {'runs/s':>7} "
          f"{'2 free cores s':>15} {'target s':>9}")
    serial = None
    for name, args, target in cases:
        wall, cpu, runs = command(args)
        if serial is None:
            serial = cpu  # what 2 cores do not split (an upper bound: the workers start in parallel)
            own = "-"
        else:
            own = f"{serial + max(0.0, cpu - serial) / 2:.1f}"
        print(f"{name:<36} {runs:>6} {wall:>7.1f} {cpu:>7.1f} {cpu / wall:>6.2f} {runs / wall:>7.0f} "
              f"{own:>15} {'-' if target is None else f'{target:.0f}':>9}", flush=True)
    print(f"load average at the end {os.getloadavg()[0]:.2f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tail", type=float, default=10.0, help="s of free motion after the pulse (default 10)")
    ap.add_argument("--grid", type=int, default=12, help="frequencies and amplitudes per axis (default 12)")
    ap.add_argument("--targets", action=argparse.BooleanOptionalAction, default=True,
                    help="also time issue 34's two maps through the command (default: yes)")
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
            print(f"{body:<10} {path:<36} {n:>5} {cpu:>7.2f} {n / cpu if cpu > 0 else math.inf:>12.1f}", flush=True)
    if args.targets:
        targets()


if __name__ == "__main__":
    main()
