"""Throughput of a fragility sweep on dask.distributed: runs/s for 1 and 2 worker processes
(LocalCluster) and for the same runs in this process without Dask, on one task set, and
the CPU time each run costs in all processes (workers, client and scheduler).

    .venv/bin/python benches/fragility_throughput.py [--workers 1,2] [--stripes 4]

The task set: the slender block and the Dharahara tower (rigid) of
examples/fragility.toml, each under the 9 horizontal components of
data/ground-motions, at --stripes intensities (multiple stripes, --chunk runs per task),
every run 5 s past the record's end. Each configuration starts from an empty store;
the cluster's start and the FMU's transfer are outside the timed part. Efficiency =
(runs/s with n workers / n) / (runs/s with 1 worker). The load average is printed:
on a shared machine it bounds what the wall-clock columns can show; the CPU
columns (the workers' and this process's, which hosts the LocalCluster's
scheduler) say what Dask adds per run whatever the load, and "workers busy" is
the time the workers spent inside runs over wall x workers.
"""

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from rocking import RockingFMU, paths, presets
from rocking.fragility import cluster, runner
from rocking.fragility.intensity import parse
from rocking.fragility.store import ResultStore
from rocking.fragility.study import Study
from rocking.fragility.suite import load_suite


def study(n_stripes, chunk, n_records=0, bodies=2):
    """The study; n_records > 0: that many records, the suite's components repeated under
    new names (their runs cost what the originals' do)."""
    bodies = dict(list({"slender-block": dict(presets.preset("fig15-alpha0.20-shiftingPivot"), theta=0.0),
                        "dharahara-rigid": presets.preset("dharahara-rigid")}.items())[:bodies])
    suite = load_suite([paths.data_dir()])
    if n_records:
        items = list(suite.items())
        suite = {f"{items[i % len(items)][0]}#{i}": items[i % len(items)][1] for i in range(n_records)}
    return Study(bodies=bodies, suite=suite, im=parse("PGV"), method="msa",
                 stripes=tuple(np.linspace(0.2, 1.2, n_stripes)), chunk=chunk)


def serial(st, fmu, tasks):
    t0, c0 = time.perf_counter(), time.process_time()
    n = 0
    for _key, _fn, (_digest, parts, opts, _phase), _ in tasks:
        for job, stripes in parts:
            for im in stripes:
                runner.run_once(fmu, job["params"], job["record"], im / job["meta"]["im_record"], opts)
                n += 1
    return n, time.perf_counter() - t0, time.process_time() - c0


def on_cluster(workers, fmu_path, tasks):
    with cluster.open_client(workers=workers, quiet=True, dashboard=":0") as client:
        client.wait_for_workers(workers)
        cluster.register_fmu(client, fmu_path)
        client.run(lambda: None)
        w0, c0, t0 = client.run(time.process_time), time.process_time(), time.perf_counter()
        time.sleep(IDLE_S)  # the cluster's own CPU while it waits: heartbeats, ticks
        w1, c1 = client.run(time.process_time), time.process_time()
        idle = (sum(w1[w] - w0[w] for w in w1) + c1 - c0) / (time.perf_counter() - t0)
        with tempfile.TemporaryDirectory() as tmp:
            store = ResultStore(Path(tmp) / "runs")
            w0, c0, t0 = client.run(time.process_time), time.process_time(), time.perf_counter()
            _, runs, failures = cluster.execute(client, tasks, store)
            wall = time.perf_counter() - t0
            w1, c1 = client.run(time.process_time), time.process_time()
            cpu = sum(w1[w] - w0[w] for w in w1) + c1 - c0
            df = store.read()
            busy = df["wall_s"].sum() / (wall * workers)
            in_runs = df["cpu_s"].sum()
            client_ms = (c1 - c0) / len(tasks) * 1e3
    if failures:
        raise RuntimeError(f"{len(failures)} tasks failed: {next(iter(failures.values()))}")
    return runs, wall, cpu, busy, client_ms, idle, in_runs


IDLE_S = 5.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--stripes", type=int, default=8)
    ap.add_argument("--chunk", type=int, default=0, help="runs per task (default 0: the study's batching)")
    ap.add_argument("--records", type=int, default=0, help="records (default: the 9 shipped; more: repeated)")
    ap.add_argument("--bodies", type=int, default=2, help="bodies, 1 or 2 (default 2)")
    ap.add_argument("--sample", type=int, default=1,
                    help="the in-process loop runs every SAMPLE-th task only (its CPU per run is the base)")
    args = ap.parse_args()
    fmu_path = paths.default_fmu()
    st = study(args.stripes, args.chunk, args.records, args.bodies)
    with RockingFMU(fmu_path) as fmu:
        tasks = st.tasks(fmu, cluster.fmu_digest(fmu_path))
        n, wall, cpu = serial(st, fmu, tasks[::args.sample])
    rows = [("in-process, no Dask", 1, n, wall, cpu, 1.0, 0.0, 0.0, cpu, cpu / n)]
    for n in (int(w) for w in args.workers.split(",")):
        # the loop again just before each cluster: the load drifts by 10-15 % in minutes
        with RockingFMU(fmu_path) as fmu:
            m, _, loop_cpu = serial(st, fmu, tasks[::args.sample])
        rows.append((f"LocalCluster, {n} worker(s)", n, *on_cluster(n, fmu_path, tasks), loop_cpu / m))
    print(f"host: {os.uname().nodename}, {os.cpu_count()} cores, load average before: "
          f"{' '.join(f'{x:.1f}' for x in LOAD)}, after: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    runs_all = sum(t[3] for t in tasks)
    print(f"{runs_all} runs in {len(tasks)} tasks ({runs_all / len(tasks):.1f} runs a task)")
    print("| configuration | runs | wall (s) | runs/s | workers busy | CPU s per run | CPU in runs per run "
          "| overhead (% of the runs' CPU) | CPU efficiency | client CPU per task (ms) | idle cluster (% of a core) "
          "| overhead net of idle (%) | against the in-process loop just before (%) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, n, runs, wall, cpu, busy, client_ms, idle, in_runs, cpu_base in rows:
        over = cpu / in_runs - 1
        net = (cpu - idle * wall) / in_runs - 1
        print(f"| {name} | {runs} | {wall:.2f} | {runs / wall:.2f} | {busy:.3f} | {cpu / runs:.4f} "
              f"| {in_runs / runs:.4f} | {100 * over:.1f} | {1 / (1 + over):.3f} | {client_ms:.1f} "
              f"| {100 * idle:.1f} | {100 * net:.1f} | {100 * (cpu / runs / cpu_base - 1):.1f} |")
    one = next((r for r in rows if r[1] == 1 and r[0].startswith("Local")), None)
    for r in rows:
        if one and r[0].startswith("Local") and r[1] > 1:
            print(f"wall-clock efficiency on {r[1]} workers: {(r[2] / r[3] / r[1]) / (one[2] / one[3]):.3f}")
    print("overhead: CPU of all processes (workers, client, scheduler) over the CPU spent inside the runs "
          "(each row's cpu_s, measured in the same study); CPU efficiency: 1 / (1 + overhead), what the "
          "wall-clock efficiency is on an idle machine whose cores the workers do not share; idle cluster: "
          f"its CPU while it waits ({IDLE_S:g} s before the runs), which grows with the wall time a loaded "
          "machine stretches; net of idle: the overhead without it; against the in-process loop: CPU per "
          "run of all processes over the loop's, the same runs measured just before the cluster's")
    return 0


LOAD = os.getloadavg()

if __name__ == "__main__":
    sys.exit(main())
