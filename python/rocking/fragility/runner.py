"""The runs of a study, as they execute in a worker: one FMU per process, rows out.

`run_once` is the one place a study calls the FMU (`RockingFMU.simulate`); a
faster stepping loop behind that method serves the studies unchanged. The
rows carry only what a fragility needs (no time histories): overturned,
t_overturn, peak |theta| / alpha, and the run's wall time and error.

A batch of runs at fixed intensities (`run_batch`) and one record's search
(`run_hunt`, sequential by nature) are the tasks; both never raise for a
failed run (the error is in the row).
"""

import math
import os
import socket
import threading
import time

from .hunt import HuntOptions, hunt_and_fill, unresolved

_FMUS = {}  # the RockingFMU of this process, by FMU digest
_RECORDS = {}  # the records of the tasks in flight, by RecordRef name (cluster.RecordsPlugin)
_LOCK = threading.Lock()  # one run at a time per process (RockingFMU is not thread-safe)


def install_fmu(digest, fmu):
    """Make `fmu` (a RockingFMU) the one this process runs for `digest`."""
    _FMUS[digest] = fmu


class RecordRef:
    """A record of the worker's RecordsPlugin, by name, in a task's job in place of the record."""

    __slots__ = ("name",)

    def __init__(self, name):
        self.name = name

    def __getstate__(self):
        return self.name

    def __setstate__(self, name):
        self.name = name


def install_records(records):
    """Make `records` {name: Record} those RecordRef names in this process."""
    _RECORDS.update(records)


def remove_records(records):
    for name in records:
        _RECORDS.pop(name, None)


def _with_record(job):
    """`job` with its record itself (a RecordRef looked up in this process's records)."""
    rec = job["record"]
    if not isinstance(rec, RecordRef):
        return job
    if rec.name not in _RECORDS:
        raise RuntimeError(f"record {rec.name} is not in this worker (the study's records plugin is missing)")
    return dict(job, record=_RECORDS[rec.name])


def process_fmu(digest, path=None):
    """The RockingFMU of this process for `digest`, opened from `path` on first use."""
    fmu = _FMUS.get(digest)
    if fmu is None:
        if path is None:
            raise RuntimeError("the FMU was not loaded in this worker (the study's worker plugin is missing)")
        from ..fmu import RockingFMU
        fmu = _FMUS[digest] = RockingFMU(path)
    return fmu


def run_once(fmu, params, record, scale, opts):
    """One run: (overturned, t_overturn, peak |theta|/alpha, calculated) of `params` under
    `record` x `scale`, simulated to the record's end plus opts['tail'] s."""
    stop = record.duration + opts.get("tail", 0.0)
    run = fmu.simulate(params, record=record, scale=scale, stop_time=stop, rtol=opts.get("rtol"),
                       outputs=("thetaOverAlpha",))
    return run.overturned, run.t_overturn, run.peak_theta_over_alpha, run.calculated


def _row(job, scale, im, phase, fmu, opts):
    t0, c0 = time.perf_counter(), time.thread_time()
    row = dict(job["meta"], scale=float(scale), im=float(im), phase=phase, overturned=None,
               t_overturn=math.nan, peak_theta_over_alpha=math.nan, error="", unresolved="",
               worker=f"{socket.gethostname()}:{os.getpid()}")
    try:
        with _LOCK:
            overturned, t_ov, peak, _ = run_once(fmu, job["params"], job["record"], scale, opts)
        row.update(overturned=bool(overturned), t_overturn=float(t_ov), peak_theta_over_alpha=float(peak))
    except Exception as exc:  # noqa: BLE001 - the row says what failed
        row["error"] = " ".join(str(exc).split())[:500]
    row["wall_s"] = time.perf_counter() - t0
    # the run's own CPU: this thread's, not the worker's other threads (Dask's event loop,
    # heartbeats, transfers), which are the overhead a study measures against it
    row["cpu_s"] = time.thread_time() - c0
    return row


def run_stripes(digest, job, stripes, opts, phase="stripe"):
    """Rows of `job` (params, record, meta with im_record) at the intensities `stripes`."""
    fmu = process_fmu(digest, opts.get("fmu_path"))
    job = _with_record(job)
    return [_row(job, im / job["meta"]["im_record"], im, phase, fmu, opts) for im in stripes]


def run_batch(digest, parts, opts, phase="stripe"):
    """Rows of several jobs' runs in one task: parts [(job, intensities)]."""
    return [row for job, ims in parts for row in run_stripes(digest, job, ims, opts, phase)]


def run_hunt(digest, job, start, hunt, opts, states=None):
    """Rows of one record's search for its first collapse, and for the first intensity of each
    damage state of `states` {name: threshold on peak |theta| / alpha}, from intensity `start`
    (HuntOptions fields in `hunt`)."""
    fmu = process_fmu(digest, opts.get("fmu_path"))
    job = _with_record(job)
    rows = []

    def collapses(im):
        row = _row(job, im / job["meta"]["im_record"], im, "", fmu, opts)
        rows.append(row)
        if row["error"]:
            raise _RunFailed(row["error"])
        return row["overturned"], row["peak_theta_over_alpha"]

    options = HuntOptions(**hunt)
    try:
        trace = hunt_and_fill(collapses, start, options, states)
        for row, (_, _, _, phase) in zip(rows, trace):
            row["phase"] = phase
        why = unresolved(trace, options, states)
    except _RunFailed:
        why = "the hunt stopped on a failed run"  # the failed row is kept and reported
    for row in rows:
        row["unresolved"] = why
    return rows


class _RunFailed(Exception):
    pass
