"""Parametric runs: a grid of cases x records x scale factors through the FMU,
in parallel processes, one FMU extraction shared by all of them.

    from rocking import groundmotion as gm
    from rocking import run_grid
    df = run_grid({"soft": {...params...}, "stiff": {...}},
                  records=[gm.katnp_standin()], scales=[0.5, 1.0], workers=2)

One row per run, in grid order (cases outer, then records, then scales)
whatever the number of workers: case, the parameters, record, scale,
overturned, t_overturn, peak_theta_over_alpha, impacts, zero_crossings, t_end,
alpha, thetaOv (the FMU's calculated parameters), terminal (regime 5's message
when a vertical input ended the run, else None), wall_s, cpu_s (this run's wall and CPU time
in its process), error (empty when the run succeeded)
(and history, the recorded outputs, with `histories=True`).
"""

import dataclasses
import math
import os
import time as _time
from concurrent.futures import ProcessPoolExecutor, as_completed
from itertools import product

import pandas as pd

from .fmu import DEFAULT_OUTPUTS, RockingFMU

_WORKER_FMU = None  # the RockingFMU of this process (set by _init_worker)


def _init_worker(unzipdir):
    global _WORKER_FMU
    _WORKER_FMU = RockingFMU(unzipdir=unzipdir)


def _run_task(task):
    """Run one grid point in this process; never raises (errors go in the row)."""
    index, case, params, rec_name, record, scale, opts, keep_history = task
    t0, c0 = _time.perf_counter(), _time.process_time()
    row = {"case": case, "record": rec_name, "scale": scale, "terminal": None}
    history = None
    try:
        params, record = with_av(params, record, rec_name)
        run = _WORKER_FMU.simulate(params, record=record, scale=scale,
                                   stop_time=opts["stop_time"], output_interval=opts["output_interval"],
                                   rtol=opts["rtol"], outputs=opts["outputs"])
        row.update(overturned=run.overturned, t_overturn=run.t_overturn,
                   peak_theta_over_alpha=run.peak_theta_over_alpha, impacts=run.impacts,
                   zero_crossings=run.zero_crossings,
                   t_end=run.t_end, alpha=run.calculated.get("alpha", math.nan),
                   thetaOv=run.calculated.get("thetaOv", math.nan), error="", terminal=run.terminal)
        if keep_history:
            history = run.result
    except Exception as exc:  # noqa: BLE001 - reported in the row
        row.update(overturned=None, t_overturn=math.nan, peak_theta_over_alpha=math.nan,
                   impacts=-1, zero_crossings=-1, t_end=math.nan, alpha=math.nan, thetaOv=math.nan,
                   error=str(exc))
    row["wall_s"] = _time.perf_counter() - t0
    row["cpu_s"] = _time.process_time() - c0
    return index, row, history


def with_av(params, record, rec_name=""):
    """(params without the case key `vertical`, the record to run): with `vertical = True` the
    record with its vertical companion (`Record.av_record`, the FMU's av), else without one."""
    params = dict(params)
    if not params.pop("vertical", False):
        if record is not None and record.av_record is not None:
            record = dataclasses.replace(record, av_record=None)
        return params, record
    if record is None or record.av_record is None:
        raise ValueError(f"vertical = true: record {rec_name or getattr(record, 'source', '')} has no vertical "
                         "component (attach one: groundmotion.with_vertical)")
    return params, record


def _named(items, what):
    if isinstance(items, dict):
        return list(items.items())
    out = []
    for i, item in enumerate(items):
        if what == "record":
            out.append((getattr(item, "name", "") or f"record{i}", item))
        else:
            out.append((f"case{i}", item))
    return out


def run_grid(cases, records=(None,), scales=(1.0,), workers=None, fmu=None, *, stop_time=None,
             output_interval=None, rtol=None, outputs=DEFAULT_OUTPUTS, histories=False,
             progress=None):
    """Run every (case, record, scale) and return a pandas DataFrame, one row per run.

    cases            {name: params} or a list of params dicts (named case0, case1, ...);
                     params as for `RockingFMU.simulate` (enumerations by name or value)
    records          groundmotion Records, or {name: Record}; None for no ground motion
                     (a case with the key `vertical = True` runs each record with its
                     `av_record` as the FMU's av, scaled alike; terminal: regime 5's message)
    scales           factors applied to each record's acceleration
    workers          processes (default: os.cpu_count(), at most the number of runs);
                     1 runs in this process, without a pool
    fmu              a RockingFMU (its extraction is shared), a path to a .fmu, or None
                     for target/fmu/RockingBlock.fmu
    stop_time, output_interval, rtol, outputs
                     as for `RockingFMU.simulate`
    histories        keep each run's recorded outputs in a 'history' column: True, or a
                     function (case, record name, scale) -> bool choosing the runs (None
                     in the others' column)
    progress         callback(done, total, row) called in this process as runs finish
    """
    own = not isinstance(fmu, RockingFMU)
    handle = RockingFMU(fmu) if own else fmu
    try:
        opts = dict(stop_time=stop_time, output_interval=output_interval, rtol=rtol,
                    outputs=tuple(outputs))
        case_list, rec_list = _named(cases, "case"), _named(records, "record")
        keep = histories if callable(histories) else (lambda *_: bool(histories))
        tasks = [(i, cname, params, rname, rec, float(scale), opts, keep(cname, rname, float(scale)))
                 for i, ((cname, params), (rname, rec), scale)
                 in enumerate(product(case_list, rec_list, scales))]
        total = len(tasks)
        if workers is None:
            workers = os.cpu_count() or 1
        workers = max(1, min(int(workers), total))
        results = [None] * total
        if workers == 1:
            global _WORKER_FMU
            saved, _WORKER_FMU = _WORKER_FMU, handle
            try:
                for done, task in enumerate(tasks, 1):
                    index, row, hist = _run_task(task)
                    results[index] = (row, hist)
                    if progress:
                        progress(done, total, row)
            finally:
                _WORKER_FMU = saved
        else:
            with ProcessPoolExecutor(max_workers=workers, initializer=_init_worker,
                                     initargs=(str(handle.unzipdir),)) as pool:
                futures = [pool.submit(_run_task, t) for t in tasks]
                for done, fut in enumerate(as_completed(futures), 1):
                    index, row, hist = fut.result()
                    results[index] = (row, hist)
                    if progress:
                        progress(done, total, row)
    finally:
        if own:
            handle.close()

    rows = []
    param_names = list(dict.fromkeys(k for _, p in case_list for k in p))
    for (row, hist), (_, cname, params, *_rest) in zip(results, tasks):
        full = {"case": row["case"]}
        full.update({k: params.get(k) for k in param_names})
        full.update({k: v for k, v in row.items() if k != "case"})
        if histories:
            full["history"] = hist
        rows.append(full)
    columns = (["case"] + param_names + ["record", "scale", "overturned", "t_overturn",
                                         "peak_theta_over_alpha", "impacts", "zero_crossings",
                                         "t_end", "alpha",
                                         "thetaOv", "terminal", "wall_s", "cpu_s", "error"]
               + (["history"] if histories else []))
    return pd.DataFrame(rows, columns=columns)
