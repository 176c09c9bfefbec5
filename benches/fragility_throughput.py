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


def study(n_stripes, chunk):
    bodies = {"slender-block": dict(presets.preset("fig15-alpha0.20-shiftingPivot"), theta=0.0),
              "dharahara-rigid": presets.preset("dharahara-rigid")}
    return Study(bodies=bodies, suite=load_suite([paths.data_dir()]), im=parse("PGV"), method="msa",
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
        with tempfile.TemporaryDirectory() as tmp:
            store = ResultStore(Path(tmp) / "runs")
            w0, c0, t0 = client.run(time.process_time), time.process_time(), time.perf_counter()
            _, runs, failures = cluster.execute(client, tasks, store)
            wall = time.perf_counter() - t0
            w1, c1 = client.run(time.process_time), time.process_time()
            cpu = sum(w1[w] - w0[w] for w in w1) + c1 - c0
            busy = store.read()["wall_s"].sum() / (wall * workers)
            client_ms = (c1 - c0) / len(tasks) * 1e3
    if failures:
        raise RuntimeError(f"{len(failures)} tasks failed: {next(iter(failures.values()))}")
    return runs, wall, cpu, busy, client_ms


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--stripes", type=int, default=4)
    ap.add_argument("--chunk", type=int, default=2, help="stripe runs per task (default 2)")
    args = ap.parse_args()
    fmu_path = paths.default_fmu()
    st = study(args.stripes, args.chunk)
    with RockingFMU(fmu_path) as fmu:
        tasks = st.tasks(fmu, cluster.fmu_digest(fmu_path))
        rows = [("in-process, no Dask", 1, *serial(st, fmu, tasks), 1.0, 0.0)]
    for n in (int(w) for w in args.workers.split(",")):
        rows.append((f"LocalCluster, {n} worker(s)", n, *on_cluster(n, fmu_path, tasks)))
    base = next(r[2] / r[3] for r in rows if r[1] == 1 and r[0].startswith("Local"))
    print(f"host: {os.uname().nodename}, {os.cpu_count()} cores, load average before: "
          f"{' '.join(f'{x:.1f}' for x in LOAD)}, after: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    print(f"{len(tasks)} tasks of {args.chunk} run(s)")
    cpu_base = rows[0][4] / rows[0][2]
    print("| configuration | runs | wall (s) | runs/s | runs/s per core | efficiency | workers busy "
          "| CPU s per run | CPU / in-process | client CPU per task (ms) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, n, runs, wall, cpu, busy, client_ms in rows:
        rate = runs / wall
        print(f"| {name} | {runs} | {wall:.2f} | {rate:.2f} | {rate / n:.2f} | {rate / n / base:.2f} "
              f"| {busy:.3f} | {cpu / runs:.4f} | {cpu / runs / cpu_base:.3f} | {client_ms:.1f} |")
    return 0


LOAD = os.getloadavg()

if __name__ == "__main__":
    sys.exit(main())
