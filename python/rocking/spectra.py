"""Rocking spectra of a record: for a family of bodies (one slenderness alpha, sizes varying,
or a user's list), the peak |theta| / alpha at given scale factors of the record and the
least scale factor that overturns each body, against the frequency parameter p or the size
(Makris & Konstantinidis 2003). docs/spectra.md.

    from rocking.spectra import rectangle_family, run_spectrum
    bodies = rectangle_family({"interface": "rigid"}, alpha=0.2, p=[1, 2, 4])
    runs, spectrum = run_spectrum(bodies, record, fmu, scales=[1.0], workers=2)

Overturning is the one definition of docs/maps.md: the FMU's `overturned` output (|theta|
reached thetaOv) at any time of the record or of its free tail. The least overturning scale
is the first collapse of the fragility code's hunt-and-fill search (rocking.fragility.hunt:
hunt up from the scale at which the record's PGA reaches g tan alpha, scan the gaps below the
first collapse, bisect to tol), so a scale that overturns below a safe one is still found, to
the hunt's resolution. The runs go through `RockingFMU.simulate` (the native stepping loop
where built) in the process pool of `rocking.parametric`, one task per body.
"""

import math
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import maps, parametric
from .fragility.hunt import HuntOptions, bracket, capacity, hunt_and_fill, unresolved


@dataclass
class SpectrumOptions:
    """scales   the record's scale factors at which the peak |theta| / alpha is reported
    hunt        also search each body's least overturning scale
    tol         relative width of that scale's bracket
    max_scale   the highest scale the search tries (None: 50 times the uplift scale, the hunt's
                default stop)
    tail        s of free motion (ag = 0) after the record
    """

    scales: tuple = (1.0,)
    hunt: bool = True
    tol: float = 0.01
    max_scale: float = None
    tail: float = 10.0

    def check(self):
        values = np.asarray(self.scales, dtype=float)
        if values.size == 0:
            raise ValueError("scales: the list is empty")
        if not np.all(np.isfinite(values)) or np.any(values <= 0):
            raise ValueError(f"scales: every scale factor must be finite and > 0 (got "
                             f"{', '.join(f'{v:g}' for v in values if not (math.isfinite(v) and v > 0))})")
        if not (0 < self.tol < 1):
            raise ValueError(f"tol = {self.tol:g}: must be in (0, 1) (relative)")
        if not (math.isfinite(self.tail) and self.tail >= 0):
            raise ValueError(f"tail = {self.tail:g}: must be >= 0 s")
        if self.max_scale is not None and not (math.isfinite(self.max_scale) and self.max_scale > 0):
            raise ValueError(f"max_scale = {self.max_scale:g}: must be > 0")


def rectangle_family(params, alpha=None, p=None, sizes=None, g=None):
    """[(label, params)] of solid rectangular prisms of one slenderness alpha (rad; default
    atan(B/H) of `params`), one per frequency parameter p (rad/s) or per size R (m, the
    half-diagonal), B = 2 R sin alpha, H = 2 R cos alpha, p = sqrt(3 g / (4 R)); the rest
    of `params` (interface, kn, fm, ...) kept. ValueError naming what does not fit."""
    shape = params.get("shape", "solidRectangle")
    mass = params.get("massModel", "prism")
    if shape not in ("solidRectangle", 0) or mass not in ("prism", 0):
        raise ValueError(f"a family by p or size is of solid rectangular prisms (shape = solidRectangle, "
                         f"massModel = prism), not shape = {shape}, massModel = {mass}: give the bodies as a list")
    if (p is None) == (sizes is None):
        raise ValueError("give either p (rad/s) or sizes (R, m) of the family")
    values = np.asarray(p if p is not None else sizes, dtype=float)
    what = "p" if p is not None else "sizes"
    if values.size == 0:
        raise ValueError(f"{what}: the list is empty")
    bad = [v for v in values if not (math.isfinite(v) and v > 0)]
    if bad:
        raise ValueError(f"{what}: every value must be > 0 (got {bad[0]:g})")
    g = float(g if g is not None else params.get("g", 9.81))
    if alpha is None:
        alpha = math.atan2(float(params.get("B", 0.5)) / 2, float(params.get("H", 2.5)) / 2)
    if not (0 < alpha < math.pi / 2):
        raise ValueError(f"alpha = {alpha:g} rad: must be in (0, pi/2)")
    out = []
    for v in dict.fromkeys(float(x) for x in values):  # a value given twice is one body (one label)
        R = 3 * g / (4 * v * v) if p is not None else float(v)
        body = dict(params, shape="solidRectangle", massModel="prism",
                    B=2 * R * math.sin(alpha), H=2 * R * math.cos(alpha))
        label = f"p={v:.6g}" if p is not None else f"R={v:.6g}"
        out.append((label, body))
    return out


def uplift_scale(fmu, params, record):
    """The scale at which the record's PGA reaches g tan alpha (the rigid block's uplift): no
    rigid block overturns below it, and the search starts there."""
    sc = maps.body_scales(fmu, params)
    return sc["g_tan_alpha"] / float(np.max(np.abs(record.acc)))


def mean_period(record, fmin=0.25, fmax=20.0):
    """Rathje et al.'s (1998) mean period T_m (s) of the record: sum(C_i^2 / f_i) / sum(C_i^2)
    over its Fourier amplitudes C_i between fmin and fmax Hz."""
    acc = np.asarray(record.acc, dtype=float)
    c = np.abs(np.fft.rfft(acc))
    f = np.fft.rfftfreq(acc.size, record.dt)
    keep = (f >= fmin) & (f <= fmax)
    if not keep.any():
        raise ValueError(f"{record.source or record.name}: no Fourier amplitude between {fmin} and {fmax} Hz")
    c2 = c[keep] ** 2
    return float(np.sum(c2 / f[keep]) / np.sum(c2))


def _run(fmu, params, record, scale, tail):
    t0 = time.perf_counter()
    row = dict(scale=float(scale), overturned=None, t_overturn=math.nan, peak_theta_over_alpha=math.nan,
               impacts=-1, error="")
    try:
        run = fmu.simulate(params, record=record, scale=scale, stop_time=record.duration + tail,
                           outputs=("thetaOverAlpha",))
        row.update(overturned=bool(run.overturned), t_overturn=run.t_overturn, impacts=run.impacts,
                   peak_theta_over_alpha=run.peak_theta_over_alpha)
    except Exception as exc:  # noqa: BLE001 - the row says what failed
        row["error"] = " ".join(str(exc).split())[:500]
    row["wall_s"] = time.perf_counter() - t0
    return row


class _RunFailed(Exception):
    pass


def run_body(label, params, record, options, fmu=None):
    """(rows, summary) of one body: a row per scale run (phase "asked" for options.scales, else
    the hunt's phase), and the least overturning scale's bracket (lo, hi), its estimate (their
    geometric mean), whether censored (no overturning up to max_scale) and what the search
    left unresolved. R: the distance R0 from the toe to the centre of mass (m), the size."""
    fmu = fmu or parametric._WORKER_FMU
    done = {}
    rows = []
    try:
        sc = maps.body_scales(fmu, params)
        size = float(fmu.calculated(params)["R0"])
    except Exception as exc:  # noqa: BLE001 - e.g. a bed that crushes at rest: this body's rows say so
        error = " ".join(str(exc).split())[:500]
        rows = [dict(scale=float(s), phase="asked", overturned=None, t_overturn=math.nan,
                     peak_theta_over_alpha=math.nan, impacts=-1, error=error, wall_s=0.0, body=label)
                for s in options.scales]
        return rows, dict(body=label, p=math.nan, alpha=math.nan, thetaOv=math.nan, R=math.nan,
                          uplift_scale=math.nan, least_scale=math.nan, least_scale_lo=math.nan,
                          least_scale_hi=math.nan, censored=False, unresolved=f"the body did not start: {error}")

    def at(scale, phase):
        if scale not in done:
            row = _run(fmu, params, record, scale, options.tail)
            row["phase"] = phase
            rows.append(row)
            done[scale] = row
        return done[scale]

    for s in options.scales:
        at(float(s), "asked")
    summary = dict(body=label, p=sc["p"], alpha=sc["alpha"], thetaOv=sc["thetaOv"],
                   R=size,
                   uplift_scale=sc["g_tan_alpha"] / float(np.max(np.abs(record.acc))),
                   least_scale=math.nan, least_scale_lo=math.nan, least_scale_hi=math.nan,
                   censored=False, unresolved="")
    if options.hunt:
        start = summary["uplift_scale"]
        stop = (options.max_scale / start) if options.max_scale else HuntOptions.stop
        hunt = HuntOptions(tol=options.tol, stop=max(stop, 1.0))

        def collapses(scale):
            row = at(scale, "hunt")
            if row["error"]:
                raise _RunFailed(row["error"])
            return row["overturned"], row["peak_theta_over_alpha"]

        try:
            trace = hunt_and_fill(collapses, start, hunt)
            phases = {t[0]: t[3] for t in trace}
            for row in rows:
                if row["phase"] == "hunt":
                    row["phase"] = phases.get(row["scale"], "hunt")
            lo, hi = bracket(trace)
            est, censored, _ = capacity(trace)
            summary.update(least_scale=est if not censored else math.nan,
                           least_scale_lo=lo if lo is not None else math.nan,
                           least_scale_hi=hi if hi is not None else math.nan,
                           censored=bool(censored), unresolved=unresolved(trace, hunt))
            # an asked scale the search did not run may overturn below its first collapse (a
            # window narrower than the hunt's resolution): said, not hidden
            missed = [r["scale"] for r in rows if r["phase"] == "asked" and r["overturned"]
                      and (hi is None or r["scale"] < hi)]
            if missed:
                summary["unresolved"] = "; ".join(x for x in (summary["unresolved"], (
                    f"overturned at the asked scale {min(missed):.6g}, below the search's first collapse")) if x)
        except _RunFailed as exc:
            summary["unresolved"] = f"the search stopped on a failed run: {exc}"
    for row in rows:
        row["body"] = label
    return rows, summary


def _body_task(args):
    label, params, record, options = args
    return run_body(label, params, record, options)


def _dask_body(digest, job, options):
    """run_body in a Dask worker of rocking.fragility.cluster (its FMU by digest, the record
    sent once per call: job {"label", "params", "record"})."""
    from .fragility import runner
    job = runner._with_record(job)
    with runner._LOCK:  # one run at a time per process (RockingFMU is not thread-safe)
        return run_body(job["label"], job["params"], job["record"], options, runner._FMUS[digest])


def run_spectrum(bodies, record, fmu, options=SpectrumOptions(), workers=None, progress=None, client=None):
    """Every body [(label, params)] under `record`: (runs, spectrum) DataFrames; runs one row per
    body and scale run, spectrum one row per body and asked scale (its peak there, and the
    body's least overturning scale). fmu: a RockingFMU (its extraction shared with the
    workers); progress(bodies done, bodies, summary) after each body. client: a
    dask.distributed Client (rocking.fragility.cluster.open_client) to run the bodies on, one
    task each (rocking.maps.on_dask), instead of the process pool."""
    options.check()
    if not bodies:
        raise ValueError("the family of bodies is empty")
    workers = max(1, min(int(workers or os.cpu_count() or 1), len(bodies)))
    results = {}
    if client is not None:
        def got(label, result):
            results[label] = result
            if progress:
                progress(len(results), len(bodies), result[1])
        maps.on_dask(client, fmu, [(label, _dask_body, ({"label": label, "params": params, "record": record},
                                                        options), 1) for label, params in bodies],
                     got, "spectrum bodies")
    elif workers == 1:
        for k, (label, params) in enumerate(bodies, 1):
            results[label] = run_body(label, params, record, options, fmu)
            if progress:
                progress(k, len(bodies), results[label][1])
    else:
        with ProcessPoolExecutor(max_workers=workers, initializer=parametric._init_worker,
                                 initargs=(str(fmu.unzipdir),)) as pool:
            futures = [pool.submit(_body_task, (label, params, record, options)) for label, params in bodies]
            for k, fut in enumerate(as_completed(futures), 1):
                rows, summary = fut.result()
                results[summary["body"]] = (rows, summary)
                if progress:
                    progress(k, len(bodies), summary)
    runs, spectrum = [], []
    for label, params in bodies:
        rows, summary = results[label]
        extra = {k: summary[k] for k in ("p", "R", "alpha", "thetaOv")}
        runs += [dict(row, **extra) for row in rows]
        by_scale = {r["scale"]: r for r in rows}
        for s in options.scales:
            r = by_scale[float(s)]
            spectrum.append(dict(summary, scale=float(s), peak_theta_over_alpha=r["peak_theta_over_alpha"],
                                 overturned=r["overturned"], t_overturn=r["t_overturn"], impacts=r["impacts"],
                                 error=r["error"]))
    run_cols = ["body", "p", "R", "alpha", "thetaOv", "scale", "phase", "overturned", "t_overturn",
                "peak_theta_over_alpha", "impacts", "wall_s", "error"]
    runs = pd.DataFrame(runs, columns=run_cols).sort_values(["p", "scale"], kind="stable").reset_index(drop=True)
    spec_cols = ["body", "p", "R", "alpha", "thetaOv", "scale", "peak_theta_over_alpha", "overturned", "t_overturn",
                 "impacts", "uplift_scale", "least_scale", "least_scale_lo", "least_scale_hi", "censored",
                 "unresolved", "error"]
    return runs, pd.DataFrame(spectrum, columns=spec_cols)
