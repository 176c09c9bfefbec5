"""The study's tasks on dask.distributed: a LocalCluster by default, a scheduler's address
otherwise, with the same code.

- The FMU travels once to each worker inside a worker plugin (its bytes): the
  worker writes and opens it when it starts (also a worker that replaces a lost
  one), so workers need the `rocking` package but neither the repository nor a
  shared file system.
- Each record travels to the cluster once, as the value of a task of its own that the
  runs depend on (not inside every task that uses it): the scheduler keeps it, so a
  worker lost with it costs a recomputation, not the runs.
- Tasks return rows only; as each finishes, its rows go to the ResultStore and
  the future is released: the client holds no results it did not ask for.
- A task whose key is in the store is not submitted (resume). A task lost with
  its worker is rerun by the scheduler; one that fails anyway is reported and
  left for the next run of the same command.
"""

import contextlib
import hashlib
import importlib.util
import os
import sys
import uuid
from pathlib import Path

import dask
from distributed import Client, LocalCluster, WorkerPlugin, as_completed

from . import runner

PLUGIN_NAME = "rocking-fmu"

#: Dask settings of the LocalCluster (its workers inherit them through their nannies): no
#: statistical profiler (it samples every worker's stack every 10 ms) and slower
#: housekeeping ticks. Idle, a two-worker cluster then costs 2.8 % of a core instead of
#: 8.2 % (measured over 10 s here), which on a loaded machine, where a study's wall time
#: stretches, was most of Dask's CPU overhead.
QUIET = {"distributed.worker.profile.enabled": False, "distributed.admin.tick.interval": "500ms",
         "distributed.admin.system-monitor.interval": "2s"}

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


def execute(client, tasks, store, progress=None, stop_after=None):
    """Run `tasks` [(key, function, args, expected_runs)] not yet in `store`; write each
    one's rows as it finishes. progress(runs_done, row_count, expected_runs) after each task.
    stop_after: return after that many tasks (tests of resuming). Returns
    (tasks run, rows written, {key: error} of the tasks that failed)."""
    done = store.finished(t[0] for t in tasks)
    todo = [t for t in tasks if t[0] not in done]
    failures, written, finished = {}, 0, 0
    if not todo:
        return 0, 0, failures
    by_future = {}
    # Dask keys unique to this call: a key cancelled by an earlier, interrupted call may
    # still be cancelling on the scheduler, and would cancel its namesake submitted now.
    call = uuid.uuid4().hex[:8]
    records = {}
    for key, fn, args, expected in todo:
        args = tuple(_record_as_future(client, a, records, call) for a in args)
        fut = client.submit(fn, *args, key=f"rocking-{hashlib.sha1(key.encode()).hexdigest()[:24]}-{call}",
                            pure=False)
        by_future[fut] = (key, expected)
    pending = as_completed(list(by_future))
    try:
        for fut in pending:
            key, expected = by_future.pop(fut)
            try:
                rows = fut.result()
            except Exception as exc:  # noqa: BLE001 - e.g. KilledWorker: left for a rerun
                failures[key] = f"{type(exc).__name__}: {exc}"
                fut.release()
                continue
            fut.release()
            store.write(key, rows)
            written += len(rows)
            finished += 1
            if progress:
                progress(len(rows), expected)
            if stop_after is not None and finished >= stop_after:
                break
    finally:
        if by_future:
            client.cancel(list(by_future))
        client.cancel(list(records.values()))
    return finished, written, failures


def _value(x):
    return x


def _record_as_future(client, arg, records, call):
    """`arg`, a job dict's record (also in lists and tuples of them) replaced by the future of
    one task per record (`records` {id: future}, filled here): sent once, recomputable if its
    worker is lost."""
    if isinstance(arg, (list, tuple)):
        return type(arg)(_record_as_future(client, a, records, call) for a in arg)
    if not (isinstance(arg, dict) and "record" in arg):
        return arg
    rec = arg["record"]
    fut = records.get(id(rec))
    if fut is None:
        fut = records[id(rec)] = client.submit(_value, rec, key=f"rocking-record-{len(records)}-{call}",
                                               pure=False)
    return dict(arg, record=fut)

