"""Throughput of a fragility sweep on dask.distributed: the CPU and wall time of the study's
tasks on a LocalCluster of 1 and 2 worker processes against the same runs in a plain loop in
this process, repeated and interleaved (the loop just before each cluster run), the median
and the minimum of each figure printed.

    .venv/bin/python benches/fragility_throughput.py [--stripes 8,16,40] [--repeats 3]

The task set: the slender block and the Dharahara tower (rigid) of examples/fragility.toml,
each under the 9 horizontal components of data/ground-motions, at --stripes intensities
(multiple stripes: 8 make the default 144-run study, 16 288 runs, 40 720), every run 5 s
past the record's end, batched as the study batches them (or --chunk runs a task). Each
cluster run starts from an empty store; the cluster's start and the FMU's transfer are not
timed. Columns:

- CPU per run: all processes (the workers', and this process's, which hosts the
  LocalCluster's scheduler and nannies) over the runs; "in runs": the runs' own thread CPU
  (each row's cpu_s). overhead: all over in-runs, minus one (Dask's own cost). against the
  loop: all over the plain loop's CPU per run measured just before, minus one (what the
  study costs more than the loop); in-runs against the loop: whether a run itself costs more
  in a worker.
- Interleaved: a cluster of each size is open at once; each repeat runs, for each size, the
  loop and then the cluster, so that every size sees the same load.
- schedule efficiency: the tasks' measured CPU (the sum of their rows' cpu_s) list-scheduled
  in submission order on the workers, total / (workers x makespan): the balance the batching
  allows, whatever the machine's load. wall-clock efficiency: the 1-worker wall over n times
  the n-worker wall of the same repeat; it needs a quiet machine.
- idle cluster: its CPU while it waits (measured for IDLE_S before the runs), which grows
  with the wall time that a loaded machine stretches; "net of idle": the overhead without
  it (idle x wall).

Every row of every cluster run is checked against the loop's outcome for the same run.
"""

import argparse
import contextlib
import heapq
import os
import statistics
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

IDLE_S = 3.0


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


def serial(fmu, tasks):
    """The runs of `tasks` in a plain loop: (runs, CPU s, {(body, record, im): outcome})."""
    c0 = time.process_time()
    outcomes = {}
    for _key, _fn, (_digest, parts, opts, _phase), _ in tasks:
        for job, stripes in parts:
            for im in stripes:
                ov, t_ov, peak, _ = runner.run_once(fmu, job["params"], job["record"],
                                                    im / job["meta"]["im_record"], opts)
                outcomes[(job["meta"]["body"], job["meta"]["record"], im)] = (bool(ov), t_ov, peak)
    return len(outcomes), time.process_time() - c0, outcomes


def idle_cpu(client):
    """The cluster's CPU while it waits, in cores."""
    w0, c0, t0 = client.run(time.process_time), time.process_time(), time.perf_counter()
    time.sleep(IDLE_S)
    w1, c1 = client.run(time.process_time), time.process_time()
    return (sum(w1[w] - w0[w] for w in w1) + c1 - c0) / (time.perf_counter() - t0)


def on_cluster(client, workers, tasks):
    """One run of `tasks` on the cluster: its figures and rows."""
    with tempfile.TemporaryDirectory() as tmp:
        store = ResultStore(Path(tmp) / "runs")
        w0, c0, t0 = client.run(time.process_time), time.process_time(), time.perf_counter()
        _, runs, failures = cluster.execute(client, tasks, store)
        wall = time.perf_counter() - t0
        w1, c1 = client.run(time.process_time), time.process_time()
        df = store.read()
    if failures:
        raise RuntimeError(f"{len(failures)} tasks failed: {next(iter(failures.values()))}")
    cpu = sum(w1[w] - w0[w] for w in w1) + c1 - c0
    order = {t[0]: k for k, t in enumerate(tasks)}
    per_task = df.groupby("task")["cpu_s"].sum()
    costs = [c for _, c in sorted((order[k], c) for k, c in per_task.items())]
    return dict(runs=runs, wall=wall, cpu=cpu, in_runs=df["cpu_s"].sum(), client=(c1 - c0) / len(tasks),
                busy=df["wall_s"].sum() / (wall * workers), schedule=schedule_efficiency(costs, workers)), df


def schedule_efficiency(costs, workers):
    """total / (workers x makespan) of `costs` list-scheduled in order on `workers`."""
    free = [0.0] * workers
    for c in costs:
        heapq.heappush(free, heapq.heappop(free) + c)
    return sum(costs) / (workers * max(free))


def mismatches(df, outcomes):
    """Rows whose outcome differs from the loop's for the same run (bit for bit)."""
    bad = 0
    for body, rec, im, ov, t_ov, peak in zip(df["body"], df["record"], df["im"], df["overturned"],
                                             df["t_overturn"], df["peak_theta_over_alpha"]):
        ref = outcomes.get((body, rec, im))
        if ref is not None and not (ref[0] == ov and ref[2] == peak
                                    and (ref[1] == t_ov or (np.isnan(ref[1]) and np.isnan(t_ov)))):
            bad += 1
    return bad


def measure(fmu_path, tasks, worker_counts, repeats, sample):
    """{workers: ([figures of each repeat], idle CPU)}: a cluster of each size open at once,
    and in each repeat, for each size, the loop then the cluster (so that the sizes see the
    same load, which drifts in minutes on a shared machine)."""
    with contextlib.ExitStack() as stack:
        clients = {}
        for workers in worker_counts:
            client = clients[workers] = stack.enter_context(
                cluster.open_client(workers=workers, quiet=True, dashboard=":0"))
            client.wait_for_workers(workers)
            cluster.register_fmu(client, fmu_path)
            client.run(lambda: None)
        results = {w: ([], idle_cpu(c)) for w, c in clients.items()}
        for _ in range(repeats):
            for workers, client in clients.items():
                with RockingFMU(fmu_path) as fmu:
                    n, loop_cpu, outcomes = serial(fmu, tasks[::sample])
                fig, df = on_cluster(client, workers, tasks)
                fig.update(loop=loop_cpu / n, bad=mismatches(df, outcomes), checked=n)
                results[workers][0].append(fig)
    return results


def cell(values, fmt):
    return f"{fmt.format(statistics.median(values))} / {fmt.format(min(values))}"


def table(title, runs_all, n_tasks, results):
    print(f"\n{title}: {runs_all} runs in {n_tasks} tasks; each cell: median / min of the repeats")
    print("| configuration | wall (s) | CPU per run (ms) | in runs (ms) | loop (ms) | overhead (%) "
          "| overhead net of idle (%) | against the loop (%) | in-runs against the loop (%) "
          "| client CPU per task (ms) | idle cluster (% of a core) | workers busy | schedule efficiency "
          "| rows equal to the loop's |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for workers, (reps, idle) in results.items():
        col = {k: [r[k] for r in reps] for k in reps[0]}
        runs = col["runs"][0]
        print(f"| LocalCluster, {workers} worker(s) | {cell(col['wall'], '{:.2f}')} "
              f"| {cell([1e3 * c / runs for c in col['cpu']], '{:.2f}')} "
              f"| {cell([1e3 * c / runs for c in col['in_runs']], '{:.2f}')} | {cell([1e3 * x for x in col['loop']], '{:.2f}')} "
              f"| {cell([100 * (r['cpu'] / r['in_runs'] - 1) for r in reps], '{:.1f}')} "
              f"| {cell([100 * ((r['cpu'] - idle * r['wall']) / r['in_runs'] - 1) for r in reps], '{:.1f}')} "
              f"| {cell([100 * (r['cpu'] / runs / r['loop'] - 1) for r in reps], '{:.1f}')} "
              f"| {cell([100 * (r['in_runs'] / runs / r['loop'] - 1) for r in reps], '{:.1f}')} "
              f"| {cell([1e3 * c for c in col['client']], '{:.1f}')} | {100 * idle:.1f} "
              f"| {cell(col['busy'], '{:.3f}')} | {cell(col['schedule'], '{:.3f}')} "
              f"| {sum(col['checked']) - sum(col['bad'])} of {sum(col['checked'])} |")
    one = results.get(1)
    for workers, (reps, _) in results.items():
        if one and workers > 1:
            pairs = [a["wall"] / b["wall"] / workers for a, b in zip(one[0], reps)]
            print(f"wall-clock efficiency on {workers} workers (1-worker wall / {workers}-worker wall / "
                  f"{workers}, each repeat's pair): median {statistics.median(pairs):.3f}, best {max(pairs):.3f}, "
                  f"all {' '.join(f'{e:.3f}' for e in pairs)}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--stripes", default="8", help="comma-separated: one study each (8: 144 runs)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--chunk", type=int, default=0, help="runs per task (default 0: the study's batching)")
    ap.add_argument("--records", type=int, default=0, help="records (default: the 9 shipped; more: repeated)")
    ap.add_argument("--bodies", type=int, default=2, help="bodies, 1 or 2 (default 2)")
    ap.add_argument("--sample", type=int, default=1,
                    help="the in-process loop runs every SAMPLE-th task only (its CPU per run is the base)")
    args = ap.parse_args()
    fmu_path = paths.default_fmu()
    load = os.getloadavg()
    for stripes in (int(s) for s in args.stripes.split(",")):
        st = study(stripes, args.chunk, args.records, args.bodies)
        with RockingFMU(fmu_path) as fmu:
            tasks = st.tasks(fmu, cluster.fmu_digest(fmu_path))
        results = measure(fmu_path, tasks, [int(x) for x in args.workers.split(",")], args.repeats, args.sample)
        table(f"--stripes {stripes}", sum(t[3] for t in tasks), len(tasks), results)
    print(f"\nhost: {os.uname().nodename}, {os.cpu_count()} cores, load average before: "
          f"{' '.join(f'{x:.1f}' for x in load)}, after: {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
