#!/usr/bin/env python3
"""What one run of RockingBlock.fmu costs through each host, and runs/s on 1 and 2 processes.

    .venv/bin/python benches/host_loop.py [--repeat 3] [--cases rigid,F170_fm5,I15_elastic] [--no-throughput]

Needs `cargo xtask fmu` (the FMU and target/release/libfmu_stepper.so) and a C
compiler (`cc`) for benches/host/plain_loop.c. Every host runs the same Dharahara
case (docs/model.md §4) under the KATNP stand-in at the case study's tolerance
(rtol 1e-11), recording thetaOverAlpha every 0.01 s:

- fmpy.simulate_fmu: fmpy's own loop (the input without its derivative, so its
  trajectory differs slightly; the library loaded at every call, as a user calls it);
- Python loop: RockingFMU.simulate(loop="python"), the per-step loop in Python;
- native loop: RockingFMU.simulate(loop="native"), the loop of fmu-stepper;
- plain C loop: benches/host/plain_loop.c, the same FMI calls from C (the baseline).

Times are CPU seconds of the process doing the run (min over --repeat), so that
other work on a shared machine does not count; ratios are to the plain C loop.
Throughput: the 49 Dharahara cases x --scales (default the main job's 245 runs)
through rocking.run_grid with 1 and 2 worker processes, runs/s by the wall clock, and efficiency = runs/s per process over
the 1-process runs/s; and by CPU time (runs per CPU second of the runs, its ratio
to the 1-process figure: what parallel running costs each run). The load average
is printed: on a busy machine the wall clock (and so the wall-clock throughput)
says more about the neighbours than about us.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import fmpy
import numpy as np

from rocking import RockingFMU, run_grid, stepper
from rocking import groundmotion as gm
from rocking.cases import dharahara_cases
from rocking.tables import markdown

REPO = Path(__file__).resolve().parents[1]

RTOL = 1e-11
OUTPUT = "thetaOverAlpha"


def cpu(fn, repeat):
    """min CPU time of fn() over repeat calls, and its last result."""
    best, result = float("inf"), None
    for _ in range(repeat):
        c0 = time.process_time()
        result = fn()
        best = min(best, time.process_time() - c0)
    return best, result


def build_plain_loop(tmp):
    exe = Path(tmp) / "plain_loop"
    subprocess.run(["cc", "-O2", "-o", str(exe), str(REPO / "benches/host/plain_loop.c"), "-ldl"], check=True)
    return exe


def plain_loop(exe, fmu, params, record, repeat, tmp):
    """The C loop over the same binary, inputs and parameters: (CPU s, rows)."""
    h = record.dt
    n = int(np.ceil(record.time[-1] / h - 1e-9))
    grid = np.arange(n + 1) * h
    grid[-1] = min(grid[-1], record.time[-1])
    acc = np.interp(grid, record.time, record.acc, right=0.0)
    slope = np.zeros(n + 1)
    slope[:-1] = np.diff(acc) / np.diff(grid)
    path = Path(tmp) / "input.bin"
    np.concatenate([grid, acc, slope]).astype("<f8").tofile(path)
    md = fmu.model_description
    lib = fmu.unzipdir / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so"
    args = [str(exe), str(lib), md.guid, repr(RTOL), str(path), str(n), str(fmu.variables["ag"].valueReference)]
    for name, value in fmu.start_values(params).items():
        v = fmu.variables[name]
        args.append(f"{'r' if v.type == 'Real' else 'i'}:{v.valueReference}:{value!r}")
    args.append(f"o:{fmu.variables[OUTPUT].valueReference}")
    best, rows = float("inf"), 0
    for _ in range(repeat):
        out = subprocess.run(args, check=True, capture_output=True, text=True).stdout.split()
        best, rows = min(best, float(out[0])), int(out[1])
    return best, rows


def simulate_fmu(fmu, params, record):
    md = fmu.model_description
    signal = np.array(list(zip(record.time, record.acc)), dtype=[("time", float), ("ag", float)])
    return fmpy.simulate_fmu(str(fmu.unzipdir), model_description=md, start_values=fmu.start_values(params),
                             input=signal, output=[OUTPUT], relative_tolerance=RTOL, step_size=record.dt,
                             output_interval=record.dt, stop_time=record.time[-1], terminate=True)


def table(header, rows):
    print(markdown(header, rows), flush=True)


def hosts(fmu, cases, record, repeat, tmp):
    exe = build_plain_loop(tmp)
    rows = []
    for case in cases:
        params = dharahara_cases()[case]
        c_cpu, c_rows = plain_loop(exe, fmu, params, record, repeat, tmp)
        sim = lambda loop: fmu.simulate(params, record=record, rtol=RTOL, outputs=(OUTPUT,), loop=loop)  # noqa: E731
        n_cpu, nat = cpu(lambda: sim("native"), repeat)
        p_cpu, py = cpu(lambda: sim("python"), repeat)
        same = all(nat.result[k].tobytes() == py.result[k].tobytes() for k in nat.result.dtype.names)
        f_cpu, _ = cpu(lambda: simulate_fmu(fmu, params, record), repeat)
        steps = c_rows - 1
        rows.append([case, steps, f"{1e3 * c_cpu:.1f} ms", f"{1e6 * c_cpu / steps:.2f} us",
                     f"{1e3 * n_cpu:.1f} ms ({n_cpu / c_cpu:.2f}x)", f"{1e3 * p_cpu:.1f} ms ({p_cpu / c_cpu:.2f}x)",
                     f"{1e3 * f_cpu:.1f} ms ({f_cpu / c_cpu:.2f}x)", "yes" if same else "NO",
                     "yes" if len(nat.result) == c_rows else f"NO ({len(nat.result)} vs {c_rows})"])
    print(f"\n## One run per host (CPU time, min of {repeat}; ratio to the plain C loop)\n")
    table(["case", "steps", "plain C loop", "per step", "native loop", "Python loop", "fmpy.simulate_fmu",
           "native = Python bit for bit", "rows = C loop's"], rows)


def throughput(fmu, record, scales):
    cases = dharahara_cases()
    rows, base, base_cpu = [], None, None
    for workers in (1, 2):
        t0, c0 = time.perf_counter(), time.process_time()
        df = run_grid(cases, records={"standin": record}, scales=scales, workers=workers, fmu=fmu, rtol=RTOL,
                      outputs=(OUTPUT,))
        wall = time.perf_counter() - t0
        runs_s = len(df) / wall
        base = base or runs_s
        per_cpu = len(df) / df["cpu_s"].sum()
        base_cpu = base_cpu or per_cpu
        rows.append([workers, len(df), f"{wall:.2f} s", f"{df['cpu_s'].sum():.2f} s", f"{runs_s:.2f}",
                     f"{runs_s / (workers * base):.2f}", f"{per_cpu:.1f}", f"{per_cpu / base_cpu:.2f}",
                     f"{os.getloadavg()[0]:.1f}"])
    print(f"\n## Throughput: the 49 Dharahara cases x scales {', '.join(f'{x:g}' for x in scales)} through run_grid"
          " (the pool's start-up included)\n")
    table(["processes", "runs", "wall", "CPU in runs", "runs/s", "efficiency (wall)", "runs per CPU s",
           "efficiency (CPU)", "load average after"], rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cases", default="rigid,F170_fm5,I15_elastic,F85_fm2")
    ap.add_argument("--no-throughput", action="store_true")
    ap.add_argument("--scales", default="1,0.99,1.01,1.5,2",
                    help="record scale factors of the throughput runs (default: the main job's 245 runs)")
    args = ap.parse_args()
    if stepper.library() is None:
        sys.exit(f"{stepper.library_path()} not built: run `cargo xtask fmu`")
    record = gm.katnp_standin()
    print(f"load average at start: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    with RockingFMU() as fmu, tempfile.TemporaryDirectory() as tmp:
        hosts(fmu, [c.strip() for c in args.cases.split(",")], record, args.repeat, tmp)
        if not args.no_throughput:
            throughput(fmu, record, [float(x) for x in args.scales.split(",")])


if __name__ == "__main__":
    main()
