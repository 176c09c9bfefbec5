"""The study's tasks on dask.distributed: a LocalCluster by default, a scheduler's address
otherwise, with the same code.

- The FMU travels once to each worker inside a worker plugin (its bytes): the
  worker writes and opens it when it starts (also a worker that replaces a lost
  one), so workers need the `rocking` package but neither the repository nor a
  shared file system.
- Each record travels once to each worker, in a worker plugin of the call's records
  (also to a worker that replaces a lost one), not inside every task that uses it; the
  tasks name their records and have no dependencies, so the scheduler gives each to the
  least busy worker (a task that depended on a record's task went only to the workers
  holding it, and one worker ended with the large tasks while the other was idle).
- The client submits the tasks in their order (the study's come largest first), two per
  worker thread at a time, and the next as each finishes: the workers take the tasks in
  that order and end together.
- Tasks return rows only; as each finishes, its rows go to the ResultStore and
  the future is released: the client holds no results it did not ask for.
- A task whose key is in the store is not submitted (resume). A task lost with
  its worker is rerun by the scheduler; one that fails anyway is reported and
  left for the next run of the same command.
"""

import contextlib
import hashlib
import importlib.util
import math
import os
import sys
import time
import uuid
from pathlib import Path

import dask
from distributed import Client, LocalCluster, WorkerPlugin, as_completed

from . import runner

PLUGIN_NAME = "rocking-fmu"

#: Dask settings of the LocalCluster (its workers inherit them through their nannies): no
#: statistical profiler (it samples every worker's stack every 10 ms), slower housekeeping
#: ticks, and the nannies' memory monitor every second instead of every 100 ms. Idle, a
#: two-worker cluster then costs 1.7 % of a core instead of 8.2 % (3.5 % with the memory
#: monitor at 100 ms; each measured over 6-10 s here), which on a loaded machine, where a
#: study's wall time stretches, was most of Dask's CPU overhead.
QUIET = {"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "500ms",
         "distributed.admin.system-monitor.interval": "2s", "distributed.worker.memory.monitor-interval": "1s"}

#: The environment variable that Dask's nannies set in their workers by default
#: (distributed.nanny.pre-spawn-environ) and the LocalCluster leaves out. Set, it makes glibc
#: return freed memory to the system at once and fixes its mmap threshold at 128 KiB: every
#: run's numpy arrays (the grid, the input line, the outputs: over 128 KiB) are then mapped
#: and unmapped afresh, 168 page faults a run (2-3 a run without it), and a run costs 10-14 %
#: more CPU in a worker than in a plain loop (docs/fragility.md, "Throughput").
MALLOC_TRIM = "MALLOC_TRIM_THRESHOLD_"


def worker_environ():
    """Dask's pre-spawn environment of the workers without MALLOC_TRIM (the rest kept)."""
    env = dask.config.get("distributed.nanny.pre-spawn-environ", {}) or {}
    return {k: v for k, v in env.items() if k != MALLOC_TRIM}


class FMUPlugin(WorkerPlugin):
    """Writes the FMU's bytes into the worker's local folder and opens it once per worker."""

    name = PLUGIN_NAME

    def __init__(self, fmu_bytes):
        self.fmu_bytes = fmu_bytes
        self.digest = digest_of(fmu_bytes)

    def setup(self, worker):
        from ..fmu import RockingFMU
        folder = Path(worker.local_directory) / "rocking-fmu"
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f"RockingBlock-{self.digest}.fmu"
        if not path.is_file():
            tmp = path.with_suffix(f".tmp{os.getpid()}")
            tmp.write_bytes(self.fmu_bytes)
            os.replace(tmp, path)
        self.fmu = RockingFMU(path)
        runner.install_fmu(self.digest, self.fmu)

    def teardown(self, worker):
        fmu = getattr(self, "fmu", None)
        if fmu is not None:
            fmu.close()


class RecordsPlugin(WorkerPlugin):
    """The records of one `execute` call {name: Record}, installed in each worker's runner
    (runner.RecordRef names them in the tasks) and removed at the call's end."""

    def __init__(self, name, records):
        self.name, self.records = name, records

    def setup(self, worker):
        runner.install_records(self.records)

    def teardown(self, worker):
        runner.remove_records(self.records)


def digest_of(fmu_bytes):
    """The name of an FMU in the tasks: a hash of its bytes."""
    return hashlib.sha1(fmu_bytes).hexdigest()[:16]


def fmu_digest(fmu_path):
    return digest_of(Path(fmu_path).read_bytes())


def dashboard_text(client):
    """The dashboard's link, or why there is none."""
    if importlib.util.find_spec("bokeh") is None:
        return "dashboard: none (the Dask dashboard needs bokeh: pip install bokeh)"
    return f"dashboard: {client.dashboard_link}"


@contextlib.contextmanager
def open_client(scheduler=None, workers=None, quiet=False, dashboard=":8787"):
    """A Client on `scheduler` (an address), else on a LocalCluster of `workers` processes
    (default: one per core), one thread each, its dashboard at `dashboard` (another port if
    that one is taken), with the QUIET settings and without MALLOC_TRIM in its workers."""
    with dask.config.set({**QUIET, "distributed.nanny.pre-spawn-environ": worker_environ()}):
        if scheduler:
            client = Client(scheduler)
            cluster = None
        else:
            n = workers or os.cpu_count() or 1
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                   dashboard_address=dashboard if importlib.util.find_spec("bokeh") else None,
                                   silence_logs=40)
            client = Client(cluster)
    try:
        if not quiet:
            where = scheduler or f"LocalCluster, {len(client.scheduler_info()['workers'])} worker process(es)"
            print(f"dask: {where}; {dashboard_text(client)}", file=sys.stderr, flush=True)
        yield client
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def register_fmu(client, fmu_path):
    """Send the FMU to every worker (present and future); its digest names it in the tasks."""
    plugin = FMUPlugin(Path(fmu_path).read_bytes())
    client.register_plugin(plugin)
    return plugin.digest


#: Tasks in flight per worker thread: one running, one waiting in the worker, so that no
#: worker waits for the client between tasks; the rest stay in the client, which submits the
#: next (the largest left: the tasks come largest first) as each finishes. Submitted all at
#: once, tasks were assigned to workers ahead of time (they depend on their records' tasks, so
#: the scheduler does not queue them) and work stealing did not keep the largest first: one
#: worker ended with a large task while the other was idle.
IN_FLIGHT_PER_THREAD = 2


def execute(client, tasks, store, progress=None, stop_after=None):
    """Run `tasks` [(key, function, args, expected_runs)] not yet in `store`, in their order,
    IN_FLIGHT_PER_THREAD per worker thread at a time; write each one's rows as it finishes.
    progress(row_count, expected_runs) after each task. stop_after: return after that many
    tasks (tests of resuming). Returns (tasks run, rows written, {key: error} of the tasks
    that failed)."""
    done = store.finished(t[0] for t in tasks)
    # Dask keys unique to this call: a key cancelled by an earlier, interrupted call may
    # still be cancelling on the scheduler, and would cancel its namesake submitted now.
    call = uuid.uuid4().hex[:8]
    records = {}
    todo = iter([(key, fn, tuple(_record_as_ref(a, records, call) for a in args), expected)
                 for key, fn, args, expected in tasks if key not in done])
    plugin = RecordsPlugin(f"rocking-records-{call}", {ref.name: rec for ref, rec in records.values()})
    failures, written, finished = {}, 0, 0
    by_future = {}
    pending = as_completed(loop=client.loop, with_results=True, raise_errors=False)  # this client's loop, not the default client's
    window = _Window(client)

    def fill():
        while len(by_future) < window.size():
            task = next(todo, None)
            if task is None:
                return
            key, fn, args, expected = task
            fut = client.submit(fn, *args, key=f"rocking-{hashlib.sha1(key.encode()).hexdigest()[:24]}-{call}",
                                pure=False)
            by_future[fut] = (key, expected)
            pending.add(fut)

    if plugin.records:
        client.register_plugin(plugin)
    try:
        fill()
        for fut, result in pending:
            key, expected = by_future.pop(fut)
            ok = fut.status == "finished"
            fut.release()
            fill()
            if not ok:  # e.g. KilledWorker: left for a rerun
                exc = result[1] if isinstance(result, tuple) else result
                failures[key] = f"{type(exc).__name__}: {exc}"
                continue
            store.write(key, result)
            written += len(result)
            finished += 1
            if progress:
                progress(len(result), expected)
            if stop_after is not None and finished >= stop_after:
                break
    finally:
        if by_future:
            client.cancel(list(by_future))
        if plugin.records:
            client.unregister_worker_plugin(plugin.name)
    return finished, written, failures


class _Window:
    """How many tasks to keep in flight: IN_FLIGHT_PER_THREAD per worker thread (at least one
    thread: workers may still be starting), the threads asked of the scheduler at most every
    REFRESH_S (each asking is a round trip)."""

    REFRESH_S = 2.0

    def __init__(self, client):
        self.client, self.checked, self.threads = client, -math.inf, 1

    def size(self):
        now = time.monotonic()
        if now - self.checked >= self.REFRESH_S:
            self.checked = now
            self.threads = max(1, sum(self.client.nthreads().values()))
        return IN_FLIGHT_PER_THREAD * self.threads


def _record_as_ref(arg, records, call):
    """`arg`, a job dict's record (also in lists and tuples of them) replaced by a RecordRef
    (`records` {id: (ref, record)}, filled here): each record once in the call's plugin."""
    if isinstance(arg, (list, tuple)):
        return type(arg)(_record_as_ref(a, records, call) for a in arg)
    if not (isinstance(arg, dict) and "record" in arg):
        return arg
    rec = arg["record"]
    if id(rec) not in records:
        records[id(rec)] = (runner.RecordRef(f"{call}-{len(records)}"), rec)
    return dict(arg, record=records[id(rec)][0])
