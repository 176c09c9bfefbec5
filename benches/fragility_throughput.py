"""Throughput of a fragility sweep on dask.distributed: the CPU and wall time of the study's
tasks on a LocalCluster of 1 and 2 worker processes against the same runs in a plain loop in
this process and against the machine's ceiling without Dask (the same runs in two plain-loop
processes at once), repeated and interleaved (the loop just before each cluster run and
before the ceiling), the median and the minimum of each figure printed.

    .venv/bin/python benches/fragility_throughput.py [--stripes 8,16,40] [--repeats 3]
    .venv/bin/python benches/fragility_throughput.py --large     # the 4000-run study

The task set: the slender block and the Dharahara tower (rigid) of examples/fragility.toml,
each under the 9 horizontal components of data/ground-motions, at --stripes intensities
(multiple stripes: 8 make the default 144-run study, 16 288 runs, 40 720), every run 5 s
past the record's end, batched as the study batches them (or --chunk runs a task). --large:
the slender block under 100 records (the 9 components repeated under new names) at 40
stripes, 4000 runs on 2 workers, the loop and the ceiling on every tenth task, one repeat.
Each cluster run starts from an empty store; the cluster's start and the FMU's transfer are
not timed. Progress goes to stderr (each measurement as it ends; a cluster run of 1000 runs
or more at every 10 %). Columns:

- CPU per run: all processes (the workers', and this process's, which hosts the
  LocalCluster's scheduler and nannies) over the runs; "in runs": the runs' own thread CPU
  (each row's cpu_s). overhead: all over in-runs, minus one (Dask's own cost). against the
  loop: all over the plain loop's CPU per run measured just before, minus one (what the
  study costs more than the loop); in-runs against the loop: whether a run itself costs more
  in a worker.
- Interleaved: a cluster of each size and the ceiling's two processes are open at once; each
  repeat runs, for each size, the loop and then the cluster, then the loop and the ceiling,
  so that all see the same load.
- schedule efficiency: the tasks' measured CPU (the sum of their rows' cpu_s) list-scheduled
  in submission order on the workers, total / (workers x makespan): the balance the batching
  allows, whatever the machine's load. wall-clock efficiency: the 1-worker wall over n times
  the n-worker wall of the same repeat; "against the loop": the loop's wall per run x the
  runs over n times the n-worker wall. Both need a quiet machine.
- the machine ceiling: the loop's runs (every --sample-th task's) in two plain-loop processes
  (spawned, each with its own FMU, in the environment the LocalCluster gives its workers),
  started together on a barrier once both have loaded the FMU, each taking the next run
  left, largest first by the loop's CPU, so that they end within a run of each other. Its
  wall-clock efficiency: the loop's wall over twice the two processes' wall (first start to
  last end): what two cores give plain loops, the most a 2-worker study could reach. Its row:
  CPU per run as for the clusters (no client, no idle cluster); workers busy: the processes'
  loop times over twice the wall; schedule efficiency: the two processes' run CPU, total /
  (2 x the larger); "a run's CPU in each process against the loop's": each process's CPU
  per run over the loop's. "Dask / ceiling": the 2-worker wall-clock efficiency over the
  ceiling's of the same repeat.
- idle cluster: its CPU while it waits (measured for IDLE_S before the runs), which grows
  with the wall time that a loaded machine stretches; "net of idle": the overhead without
  it (idle x wall).
- others' CPU: the machine's busy CPU while a measurement ran (/proc/stat) less the
  measurement's own, over its wall, in % of a core: near 0 on a quiet machine; a repeat with
  tens of % is not a quiet one, whatever the load average said.

Every row of every cluster run, and every run of the ceiling, is checked against the loop's
outcome for the same run.
"""

import argparse
import contextlib
import heapq
import math
import multiprocessing
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


def flat_runs(tasks):
    """The runs of `tasks` in their order: [((body, record, im), params, record, scale, opts)]."""
    return [((job["meta"]["body"], job["meta"]["record"], im), job["params"], job["record"],
             im / job["meta"]["im_record"], opts)
            for _key, _fn, (_digest, parts, opts, _phase), _ in tasks for job, stripes in parts for im in stripes]


def serial(fmu, runs):
    """`runs` in a plain loop: dict(cpu=process CPU s, start=, end= (time.monotonic: on Linux
    the system-wide CLOCK_MONOTONIC, comparable between processes), costs=[each run's thread
    CPU s], outcomes={(body, record, im): outcome})."""
    outcomes, costs = {}, []
    c0, start = time.process_time(), time.monotonic()
    for key, params, record, scale, opts in runs:
        r0 = time.thread_time()
        ov, t_ov, peak, _ = runner.run_once(fmu, params, record, scale, opts)
        costs.append(time.thread_time() - r0)
        outcomes[key] = (bool(ov), t_ov, peak)
    return dict(cpu=time.process_time() - c0, start=start, end=time.monotonic(), costs=costs, outcomes=outcomes)


def plain_process(conn, barrier, counter, fmu_path, runs):
    """One of the ceiling's two processes: opens its own FMU, then for each order of `runs`
    (indices) it receives, waits at `barrier` for the other process (so that neither's start
    nor FMU load is timed), and runs in a plain loop the next run of the order not yet taken
    (`counter`, shared by the two) until none is left; sends serial()'s figures back. None
    ends it."""
    with RockingFMU(fmu_path) as fmu:
        conn.send("ready")
        while (order := conn.recv()) is not None:
            barrier.wait()
            conn.send(serial(fmu, (runs[i] for i in taken(counter, order))))


def taken(counter, order):
    """The items of `order` this process takes, one at a time, from `counter` (the next
    index of `order` not yet taken by either process)."""
    while True:
        with counter.get_lock():
            k = counter.value
            counter.value = k + 1
        if k >= len(order):
            return
        yield order[k]


@contextlib.contextmanager
def environ(extra):
    """os.environ with `extra` set (a None value unsets), for the processes started inside."""
    saved = dict(os.environ)
    for k, v in extra.items():
        os.environ.pop(k, None) if v is None else os.environ.__setitem__(k, str(v))
    try:
        yield
    finally:
        os.environ.clear()
        os.environ.update(saved)


class Ceiling:
    """The machine's ceiling without Dask: two plain-loop processes (spawned, each with its
    own FMU, in the environment the LocalCluster gives its workers) that run the runs at once,
    each taking the next run left, largest first (by the loop's measured CPU), so that they end
    within a run of each other: a balance no batching of tasks beats."""

    def __init__(self, fmu_path, runs, env):
        ctx = multiprocessing.get_context("spawn")
        barrier = ctx.Barrier(2)
        self.counter = ctx.Value("q", 0)
        self.conns, self.procs = [], []
        with environ(env):
            for _ in range(2):
                mine, theirs = ctx.Pipe()
                proc = ctx.Process(target=plain_process, daemon=True,
                                   args=(theirs, barrier, self.counter, str(fmu_path), runs))
                proc.start()
                self.conns.append(mine)
                self.procs.append(proc)
        for conn in self.conns:
            if conn.recv() != "ready":
                raise RuntimeError("a ceiling process did not start")

    def run(self, order):
        """serial()'s figures of each process, the two taking the runs in `order` (indices)."""
        self.counter.value = 0
        for conn in self.conns:
            conn.send(order)
        return [conn.recv() for conn in self.conns]

    def close(self):
        for conn in self.conns:
            conn.send(None)
        for proc in self.procs:
            proc.join(30)


def on_ceiling(ceiling, costs):
    """One run of the ceiling, the runs taken largest first by `costs` (each run's CPU in the
    loop just before): its figures and {(body, record, im): outcome}."""
    res = ceiling.run(sorted(range(len(costs)), key=lambda i: -costs[i]))
    wall = max(r["end"] for r in res) - min(r["start"] for r in res)
    halves = [sum(r["costs"]) for r in res]
    outcomes = {k: v for r in res for k, v in r["outcomes"].items()}
    return dict(runs=len(outcomes), wall=wall, cpu=sum(r["cpu"] for r in res), in_runs=sum(halves),
                busy=sum(r["end"] - r["start"] for r in res) / (2 * wall),
                schedule=sum(halves) / (2 * max(halves)),
                per_process=[r["cpu"] / max(1, len(r["costs"])) for r in res]), outcomes


def idle_cpu(client):
    """The cluster's CPU while it waits, in cores."""
    w0, c0, t0 = client.run(time.process_time), time.process_time(), time.perf_counter()
    time.sleep(IDLE_S)
    w1, c1 = client.run(time.process_time), time.process_time()
    return (sum(w1[w] - w0[w] for w in w1) + c1 - c0) / (time.perf_counter() - t0)


def on_cluster(client, workers, tasks, progress=None):
    """One run of `tasks` on the cluster: its figures and rows."""
    with tempfile.TemporaryDirectory() as tmp:
        store = ResultStore(Path(tmp) / "runs")
        w0, c0, t0 = client.run(time.process_time), time.process_time(), time.perf_counter()
        _, runs, failures = cluster.execute(client, tasks, store, progress=progress)
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


def rows_of(df):
    """((body, record, im), (overturned, t_overturn, peak)) of each of the store's rows."""
    return zip(zip(df["body"], df["record"], df["im"]),
               zip(df["overturned"], df["t_overturn"], df["peak_theta_over_alpha"]))


def mismatches(got, outcomes):
    """Runs of `got` ((key, outcome) pairs) whose outcome differs from the loop's for the same
    run (bit for bit)."""
    bad = 0
    for key, (ov, t_ov, peak) in got:
        ref = outcomes.get(key)
        if ref is not None and not (ref[0] == ov and ref[2] == peak
                                    and (ref[1] == t_ov or (np.isnan(ref[1]) and np.isnan(t_ov)))):
            bad += 1
    return bad


def machine_cpu():
    """The CPU seconds all the machine's cores have spent busy since boot (/proc/stat: user,
    nice, system, irq, softirq, steal), nan where there is no /proc/stat."""
    try:
        with open("/proc/stat") as f:
            user, nice, system, _idle, _iowait, irq, softirq, steal = (int(x) for x in f.readline().split()[1:9])
    except (OSError, ValueError):
        return math.nan
    return (user + nice + system + irq + softirq + steal) / os.sysconf("SC_CLK_TCK")


def others(busy0, fig):
    """The CPU of processes other than this measurement's while it ran, in cores: the
    machine's busy CPU since `busy0` less the measurement's own, over its wall time."""
    return (machine_cpu() - busy0 - fig["cpu"]) / fig["wall"]


def loop_figures(fmu_path, runs):
    """The plain loop in this process (a fresh FMU, its load not timed)."""
    with RockingFMU(fmu_path) as fmu:
        return serial(fmu, runs)


class Log:
    """Progress on stderr: each measurement as it ends, and a long cluster run's every 10 %."""

    def __init__(self):
        self.t0 = time.perf_counter()

    def __call__(self, text):
        print(f"[{time.perf_counter() - self.t0:7.1f} s] {text}", file=sys.stderr, flush=True)

    def cluster_progress(self, total, label):
        done, shown = [0], [0]

        def progress(rows, _expected):
            done[0] += rows
            if total >= 1000 and 10 * done[0] // total > shown[0]:
                shown[0] = 10 * done[0] // total
                self(f"{label}: {done[0]} of {total} runs")
        return progress


def measure(fmu_path, tasks, worker_counts, repeats, sample, log):
    """({workers: ([figures of each repeat], idle CPU)}, [the ceiling's figures of each
    repeat]): a cluster of each size and the ceiling's two processes open at once, and in each
    repeat, for each size, the loop then the cluster, and the loop then the ceiling (so that
    all see the same load, which drifts in minutes on a shared machine)."""
    runs = flat_runs(tasks[::sample])
    total = sum(t[3] for t in tasks)
    with contextlib.ExitStack() as stack:
        clients = {}
        for workers in worker_counts:
            client = clients[workers] = stack.enter_context(
                cluster.open_client(workers=workers, quiet=True, dashboard=":0"))
            client.wait_for_workers(workers)
            cluster.register_fmu(client, fmu_path)
            client.run(lambda: None)
        ceiling = stack.enter_context(contextlib.closing(Ceiling(fmu_path, runs, cluster.worker_environ())))
        log(f"LocalCluster(s) of {', '.join(map(str, clients))} worker(s) and the ceiling's two processes ready; "
            f"the idle clusters' CPU for {IDLE_S:.0f} s")
        results = {w: ([], idle_cpu(c)) for w, c in clients.items()}
        ceilings = []
        for r in range(1, repeats + 1):
            for workers, client in clients.items():
                loop = loop_figures(fmu_path, runs)
                label = f"repeat {r}/{repeats}, {workers} worker(s)"
                log(f"{label}: loop {len(runs)} runs {loop['end'] - loop['start']:.2f} s")
                busy0 = machine_cpu()
                fig, df = on_cluster(client, workers, tasks, log.cluster_progress(total, label))
                fig.update(others=others(busy0, fig), loop=loop["cpu"] / len(runs), loop_wall=loop["end"] - loop["start"], loop_runs=len(runs),
                           bad=mismatches(rows_of(df), loop["outcomes"]), checked=len(runs))
                results[workers][0].append(fig)
                log(f"{label}: cluster {fig['runs']} runs "
                    f"{fig['wall']:.2f} s, others' CPU {100 * fig['others']:.0f} % of a core")
            loop = loop_figures(fmu_path, runs)
            busy0 = machine_cpu()
            fig, outcomes = on_ceiling(ceiling, loop["costs"])
            fig.update(others=others(busy0, fig), loop=loop["cpu"] / len(runs), loop_wall=loop["end"] - loop["start"], loop_runs=len(runs),
                       bad=mismatches(outcomes.items(), loop["outcomes"]) + len(runs) - len(outcomes),
                       checked=len(runs))
            ceilings.append(fig)
            log(f"repeat {r}/{repeats}, ceiling: loop {len(runs)} runs {fig['loop_wall']:.2f} s, "
                f"two processes {fig['wall']:.2f} s, others' CPU {100 * fig['others']:.0f} % of a core")
    return results, ceilings


def cell(values, fmt):
    return f"{fmt.format(statistics.median(values))} / {fmt.format(min(values))}"


def each(values, fmt="{:.3f}"):
    return f"{fmt.format(statistics.median(values))} ({' '.join(fmt.format(v) for v in values)})"


def config_row(label, reps, idle=None):
    """A row of the table; idle None: not a cluster (no client, no idle CPU)."""
    col = {k: [r[k] for r in reps] for k in reps[0]}
    runs = col["runs"][0]
    idle_s = 0.0 if idle is None else idle
    client = "-" if idle is None else cell([1e3 * c for c in col["client"]], "{:.1f}")
    return (f"| {label} | {cell(col['wall'], '{:.2f}')} "
            f"| {cell([1e3 * c / runs for c in col['cpu']], '{:.2f}')} "
            f"| {cell([1e3 * c / runs for c in col['in_runs']], '{:.2f}')} | {cell([1e3 * x for x in col['loop']], '{:.2f}')} "
            f"| {cell([100 * (r['cpu'] / r['in_runs'] - 1) for r in reps], '{:.1f}')} "
            f"| {cell([100 * ((r['cpu'] - idle_s * r['wall']) / r['in_runs'] - 1) for r in reps], '{:.1f}')} "
            f"| {cell([100 * (r['cpu'] / runs / r['loop'] - 1) for r in reps], '{:.1f}')} "
            f"| {cell([100 * (r['in_runs'] / runs / r['loop'] - 1) for r in reps], '{:.1f}')} "
            f"| {client} | {'-' if idle is None else f'{100 * idle:.1f}'} "
            f"| {cell(col['busy'], '{:.3f}')} | {cell(col['schedule'], '{:.3f}')} "
            f"| {sum(col['checked']) - sum(col['bad'])} of {sum(col['checked'])} "
            f"| {cell([100 * x for x in col['others']], '{:.0f}')} |")


def against_loop(r, workers):
    """Wall-clock efficiency against the loop just before: the loop's wall per run x the runs
    over `workers` x the wall."""
    return r["loop_wall"] / r["loop_runs"] * r["runs"] / (workers * r["wall"])


def table(title, runs_all, n_tasks, results, ceilings):
    """The study's table and its efficiency lines; returns its summary (a dict)."""
    print(f"\n{title}: {runs_all} runs in {n_tasks} tasks; each cell: median / min of the repeats")
    print("| configuration | wall (s) | CPU per run (ms) | in runs (ms) | loop (ms) | overhead (%) "
          "| overhead net of idle (%) | against the loop (%) | in-runs against the loop (%) "
          "| client CPU per task (ms) | idle cluster (% of a core) | workers busy | schedule efficiency "
          "| rows equal to the loop's | others' CPU (% of a core) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for workers, (reps, idle) in results.items():
        print(config_row(f"LocalCluster, {workers} worker(s)", reps, idle))
    print(config_row(f"ceiling: 2 plain processes, no Dask ({ceilings[0]['runs']} runs)", ceilings))
    summary = dict(title=title, runs=runs_all, tasks=n_tasks, ceilings=ceilings, ceiling=[c["loop_wall"] / (2 * c["wall"]) for c in ceilings],
                   procs=[[100 * (p / c["loop"] - 1) for p in c["per_process"]] for c in ceilings])
    one = results.get(1)
    for workers, (reps, idle) in results.items():
        summary[workers] = reps, idle
        if one and workers > 1:
            pairs = [a["wall"] / b["wall"] / workers for a, b in zip(one[0], reps)]
            summary["dask"] = pairs
            print(f"wall-clock efficiency on {workers} workers (1-worker wall / {workers}-worker wall / "
                  f"{workers}, each repeat's pair): median {statistics.median(pairs):.3f}, best {max(pairs):.3f}, "
                  f"all {' '.join(f'{e:.3f}' for e in pairs)}")
    if 2 in results:
        summary["dask_loop"] = [against_loop(r, 2) for r in results[2][0]]
        print(f"wall-clock efficiency on 2 workers against the loop just before (loop wall per run x runs / "
              f"(2 x wall)): {each(summary['dask_loop'])}")
    print(f"machine ceiling (loop wall / (2 x the two processes' wall), the same runs, each repeat): "
          f"{each(summary['ceiling'])}")
    print("a run's process CPU in each of the two processes against the loop's (%, each repeat): "
          + ", ".join(f"{p[0]:+.1f} and {p[1]:+.1f}" for p in summary["procs"]))
    if "dask" in summary:
        print(f"Dask's efficiency / the ceiling (each repeat): "
              f"{each([d / c for d, c in zip(summary['dask'], summary['ceiling'])])}")
    return summary


def summary_table(summaries):
    """One row a study: Dask's wall-clock efficiency on 2 workers beside the machine ceiling."""
    print("\nSummary, 2 workers against the machine ceiling; each efficiency: median (each repeat)")
    print("| study | tasks | 1 worker: wall (s) | 2 workers: wall (s) | wall-clock efficiency (1-worker wall / 2 x 2-worker wall) "
          "| against the loop (loop wall per run x runs / 2 x 2-worker wall) | ceiling (loop wall / 2 x two processes' wall) "
          "| Dask / ceiling | Dask against the loop / ceiling | a run's CPU in the two processes against the loop (%) "
          "| workers busy | schedule efficiency | Dask's overhead (%) | net of idle (%) | study's CPU against the loop (%) "
          "| others' CPU, 2 workers / ceiling (% of a core) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s in summaries:
        if 2 not in s:
            continue
        reps, idle = s[2]
        one = cell([r["wall"] for r in s[1][0]], "{:.2f}") if 1 in s else "-"
        dask = each(s["dask"]) if "dask" in s else "-"
        ratio = each([d / c for d, c in zip(s["dask"], s["ceiling"])]) if "dask" in s else "-"
        ratio_loop = each([d / c for d, c in zip(s["dask_loop"], s["ceiling"])])
        procs = statistics.median(p for pair in s["procs"] for p in pair)
        print(f"| {s['runs']} runs | {s['tasks']} | {one} | {cell([r['wall'] for r in reps], '{:.2f}')} | {dask} "
              f"| {each(s['dask_loop'])} | {each(s['ceiling'])} | {ratio} | {ratio_loop} | {procs:+.1f} "
              f"| {cell([r['busy'] for r in reps], '{:.3f}')} | {cell([r['schedule'] for r in reps], '{:.3f}')} "
              f"| {cell([100 * (r['cpu'] / r['in_runs'] - 1) for r in reps], '{:.1f}')} "
              f"| {cell([100 * ((r['cpu'] - idle * r['wall']) / r['in_runs'] - 1) for r in reps], '{:.1f}')} "
              f"| {cell([100 * (r['cpu'] / r['runs'] / r['loop'] - 1) for r in reps], '{:+.1f}')} "
              f"| {statistics.median(100 * r['others'] for r in reps):.0f} / "
              f"{statistics.median(100 * c['others'] for c in s['ceilings']):.0f} |")


#: --large: the 4000-run study of issue 21 (100 records: the 9 shipped components repeated
#: under new names, x 40 stripes of the slender block), the loop and the ceiling on every
#: tenth task, one repeat.
LARGE = dict(bodies=1, records=100, stripes="40", workers="2", sample=10, repeats=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--stripes", default="8", help="comma-separated: one study each (8: 144 runs)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--chunk", type=int, default=0, help="runs per task (default 0: the study's batching)")
    ap.add_argument("--records", type=int, default=0, help="records (default: the 9 shipped; more: repeated)")
    ap.add_argument("--bodies", type=int, default=2, help="bodies, 1 or 2 (default 2)")
    ap.add_argument("--sample", type=int, default=1,
                    help="the loop and the ceiling run every SAMPLE-th task only (the loop's CPU per run is the base)")
    ap.add_argument("--large", action="store_true",
                    help="the 4000-run study: " + " ".join(f"--{k} {v}" for k, v in LARGE.items()))
    args = ap.parse_args()
    if args.large:
        vars(args).update(LARGE)
    t_start = time.perf_counter()
    log = Log()
    fmu_path = paths.default_fmu()
    load = os.getloadavg()
    summaries = []
    for stripes in (int(s) for s in args.stripes.split(",")):
        st = study(stripes, args.chunk, args.records, args.bodies)
        with RockingFMU(fmu_path) as fmu:
            tasks = st.tasks(fmu, cluster.fmu_digest(fmu_path))
        log(f"--stripes {stripes}: {sum(t[3] for t in tasks)} runs in {len(tasks)} tasks; starting the clusters")
        results, ceilings = measure(fmu_path, tasks, [int(x) for x in args.workers.split(",")], args.repeats,
                                    args.sample, log)
        summaries.append(table(f"--stripes {stripes}", sum(t[3] for t in tasks), len(tasks), results, ceilings))
    summary_table(summaries)
    print(f"\nhost: {os.uname().nodename}, {os.cpu_count()} cores, load average before: "
          f"{' '.join(f'{x:.1f}' for x in load)}, after: {' '.join(f'{x:.1f}' for x in os.getloadavg())}; "
          f"the whole command: {time.perf_counter() - t_start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
