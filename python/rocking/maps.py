"""Overturning maps: a body under a pulse family over a grid of frequency and amplitude, each
frequency's overturning intervals located by bisection. docs/maps.md.

    from rocking.maps import MapSpec, run_map, boundaries
    spec = MapSpec(params={...}, shape="one-sine", frequencies=[2, 4, 8], amplitudes=[1, 2, 3, 4],
                   dimensionless=True, tol=1e-3)
    runs = run_map(spec, fmu_path, workers=2)     # one row per run (pandas)
    bounds = boundaries(runs, spec)              # one row per overturning interval

Overturning (the one definition, docs/maps.md): the run overturned when the FMU's
`overturned` output became true, i.e. |theta| reached thetaOv, at any time during the pulse
or its free tail; how: without an impact (impacts = 0 then) or after n impacts (the FMU's
`impacts` output when it overturned). Outcome classes: SAFE, NO_IMPACT, AFTER_IMPACTS.

The runs go through `RockingFMU.simulate` (the native stepping loop where built), in the
process pool of `rocking.parametric` (one FMU extraction shared by the workers), one task per
frequency: its grid column, then the bisections between neighbours whose outcome differs.
"""

import math
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import asdict, dataclass, field

import numpy as np
import pandas as pd

from . import parametric
from .pulses import Pulse

SAFE, NO_IMPACT, AFTER_IMPACTS = 0, 1, 2
OUTCOMES = {SAFE: "no overturning", NO_IMPACT: "overturning without impact",
            AFTER_IMPACTS: "overturning after impacts"}

#: The first length of a tail run to find where the body can no longer overturn, in periods
#: 2 pi / p of the body; each next run's tail is twice as long, up to the stated tail.
FIRST_TAIL = 1.0

#: The communication step of a rigid block's tail run after its pulse, in periods 2 pi / p of
#: the body (or the pulse's own step if longer): the FMU locates overturning and impacts
#: itself, between communication points.
TAIL_STEP = 0.02

#: A bisection stops after this many runs per bracket whatever the tolerance (2^-40 of the step).
MAX_BISECTIONS = 40


@dataclass
class MapSpec:
    """What a map runs.

    params        the body's FMU parameters (enumerations by name)
    shape         a pulse shape of rocking.pulses.SHAPES; user: its (tau, value)
    frequencies   the grid's w_p: w_p / p when dimensionless, else rad/s
    amplitudes    the grid's a_p: a_p / (g tan alpha) when dimensionless, else m/s2
    dimensionless the grid in w_p / p and a_p / (g tan alpha) (p = sqrt(m g R0 / IO))
    tol           relative width to which each boundary is bisected (of the amplitude)
    tail          s of free motion (ag = 0) after the pulse, at most (cut_tail)
    per_period    samples of the pulse per period T_p
    cut_tail      end the tail once the body can no longer overturn (docs/maps.md, "The free
                  tail"); False: run every tail to its stated length
    """

    params: dict
    shape: str
    frequencies: list
    amplitudes: list
    dimensionless: bool = True
    tol: float = 1e-3
    tail: float = 10.0
    per_period: int = 400
    user: tuple = None
    cut_tail: bool = True
    scales: dict = field(default_factory=dict)  # p, alpha, g, thetaOv: filled by body_scales

    def check(self):
        for name in ("frequencies", "amplitudes"):
            values = np.asarray(getattr(self, name), dtype=float)
            if values.size == 0:
                raise ValueError(f"{name}: the grid is empty")
            if not np.all(np.isfinite(values)) or np.any(values <= 0):
                raise ValueError(f"{name}: every value must be finite and > 0 "
                                 f"(got {', '.join(f'{v:g}' for v in values if not v > 0 or not math.isfinite(v))})")
        if not (0 < self.tol < 1):
            raise ValueError(f"tol = {self.tol:g}: must be in (0, 1) (relative)")
        if not (math.isfinite(self.tail) and self.tail >= 0):
            raise ValueError(f"tail = {self.tail:g}: must be >= 0 s")


def body_scales(fmu, params):
    """{p (rad/s), alpha (rad), g (m/s2), thetaOv (rad), g_tan_alpha (m/s2)} of the body:
    p = sqrt(m g R0 / IO) from the FMU's calculated parameters (3 g / (4 R) for a rectangle)."""
    calc = fmu.calculated(params)
    g = float(params.get("g", fmu.variables["g"].start or 9.81))
    p = math.sqrt(calc["mass"] * g * calc["R0"] / calc["IO"])
    given = _item(fmu, params, "restitution") == "given"
    eta = float(params.get("eta", fmu.variables["eta"].start)) if given else calc["etaHousner"]
    # Housner's block (rigid, rocking both ways): its free energy after the pulse decides the tail
    rigid = _item(fmu, params, "interface") == "rigid"
    housner = rigid and _item(fmu, params, "restraint") in (None, "none")
    # free motion keeps its energy between zero crossings and loses some at each: the rigid law
    # (both formulations are Housner's) and shiftingPivot on any bed, not costa on a flexible one
    conservative = rigid or _item(fmu, params, "formulation") in (None, "shiftingPivot")
    return {"p": p, "alpha": calc["alpha"], "g": g, "thetaOv": calc["thetaOv"],
            "g_tan_alpha": g * math.tan(calc["alpha"]), "eta": eta, "housner": housner,
            "conservative": conservative}


def _item(fmu, params, name):
    """The enumeration item `name` of `params`, else the FMU's default (None if no such variable)."""
    if name not in fmu.variables:
        return None
    value = params.get(name)
    items = fmu.enumerations.get(name, {})
    if value is None:
        value = fmu.variables[name].start
    if isinstance(value, str) and value in items:
        return value
    return next((i for i, v in items.items() if str(v) == str(value)), None)


def free_rigid_fate(scales, theta, omega):
    """(can overturn, peak |theta| of the free motion) of Housner's rigid block released at
    (theta, omega) with no input: its energy omega^2/2 + p^2 cos(alpha - |theta|) is kept
    between impacts and multiplied, above p^2 cos(alpha), by eta^2 at each; it overturns only
    if the energy reaches p^2. The peak: of the excursion under way when it moves outward,
    else of the next one, after the impact."""
    p2, alpha, eta = scales["p"] ** 2, scales["alpha"], scales["eta"]
    energy = omega ** 2 / 2 + p2 * math.cos(alpha - abs(theta))
    outward = theta * omega > 0 or (theta == 0 and omega != 0)
    if not outward and theta != 0:
        energy = eta ** 2 * (energy - p2 * math.cos(alpha)) + p2 * math.cos(alpha)
    if energy >= p2 * (1 - 1e-9):  # overturns, or too close to say: the full run decides
        return True, math.nan
    peak = alpha - math.acos(min(1.0, energy / p2)) if energy > p2 * math.cos(alpha) else 0.0
    return False, max(peak, abs(theta))


def physical(spec, w, a):
    """(w_p rad/s, a_p m/s2) of the grid values (w, a)."""
    if spec.dimensionless:
        return w * spec.scales["p"], a * spec.scales["g_tan_alpha"]
    return w, a


def outcome(row):
    if not row["overturned"]:
        return SAFE
    return NO_IMPACT if row["impacts"] == 0 else AFTER_IMPACTS


def settled(result, t_free):
    """Index of the first row of `result` (time, theta, omega) at or after t_free (s, from
    which ag = 0) where the free body is known never to overturn, else None: at rest
    (theta = omega = 0, an equilibrium without input), or just past a turning point (omega
    changes sign between two free rows). At a turning point |theta_t| < thetaOv, and its
    energy V(theta_t) (V = W int_0^phi h_W, the bed's holonomic potential, largest on
    [0, thetaOv] at thetaOv) never grows again in free motion (kept between zero crossings,
    cut by each): the body cannot come back to thetaOv, and no later excursion exceeds
    |theta_t|."""
    time, theta, omega = result["time"], result["theta"], result["omega"]
    free = np.flatnonzero(time >= t_free - 1e-12)
    if free.size == 0:
        return None
    th, om = theta[free], omega[free]
    rest = (th == 0.0) & (om == 0.0)
    turn = np.zeros(free.size, dtype=bool)
    turn[1:] = om[:-1] * om[1:] < 0.0
    hit = np.flatnonzero(rest | turn)
    return int(free[hit[0]]) if hit.size else None


def run_one(fmu, spec, w, a):
    """One run at grid values (w, a): a row. The tail ends at spec.tail s after the pulse, or
    once the body can no longer overturn (spec.cut_tail): for Housner's block by its energy at
    the pulse's end (no tail run; when it can still overturn, the tail is run from the pulse's
    last theta, omega), for other bodies whose free energy cannot grow (rigid, or
    shiftingPivot) at its first free turning point or rest (`settled`), found by running the
    tail in lengths doubling from FIRST_TAIL 2 pi / p."""
    w_p, a_p = physical(spec, w, a)
    pulse = Pulse(spec.shape, a_p, w_p, spec.user)
    t, ag = pulse.samples(spec.per_period)
    t0 = time.perf_counter()
    full_stop = pulse.duration + spec.tail
    row = dict(w=float(w), a=float(a), w_p=w_p, a_p=a_p, overturned=None, t_overturn=math.nan,
               impacts=-1, peak_theta_over_alpha=math.nan, pulse_end=pulse.duration, tail_skipped=False,
               tail_end="", tail_run=spec.tail, error="")
    cut = spec.cut_tail and spec.tail > 0
    try:
        run = None
        if cut and spec.scales.get("housner"):
            # the pulse alone; the tail only if the free energy at its end can still overturn
            # to the last sample (after the rectangular pulse's ramp down), where ag is 0
            run = fmu.simulate(spec.params, ag=(t, ag), stop_time=float(t[-1]),
                               outputs=("theta", "omega", "thetaOverAlpha", "impacts"), loop="auto")
            if not run.overturned:
                end = run.result[-1]
                theta, omega = float(end["theta"]), float(end["omega"])
                can, peak = free_rigid_fate(spec.scales, theta, omega)
                if can and theta != 0.0:
                    # the tail as a run of its own from the pulse's last state (the rigid
                    # block's state is theta, omega), communicating every TAIL_STEP periods
                    # of the body rather than at the pulse's samples
                    t_end = float(t[-1])
                    tail = fmu.simulate(dict(spec.params, theta=theta, omega=omega), stop_time=full_stop - t_end,
                                        output_interval=max(float(t[1] - t[0]),
                                                            TAIL_STEP * 2 * math.pi / spec.scales["p"]),
                                        outputs=("thetaOverAlpha", "impacts"), loop="auto")
                    row.update(overturned=bool(tail.overturned), t_overturn=t_end + tail.t_overturn,
                               impacts=run.impacts + tail.impacts, tail_end="overturned" if tail.overturned else "time",
                               peak_theta_over_alpha=max(run.peak_theta_over_alpha, tail.peak_theta_over_alpha),
                               tail_run=(t_end + tail.t_overturn if tail.overturned else full_stop) - pulse.duration)
                elif can:  # at theta = 0 (an impact's instant): the whole run decides
                    run = None
                else:
                    row.update(overturned=False, impacts=run.impacts, tail_skipped=True,
                               tail_end="cannot overturn", tail_run=0.0,
                               peak_theta_over_alpha=max(run.peak_theta_over_alpha, peak / spec.scales["alpha"]))
        elif cut and spec.scales.get("conservative"):
            chunk = FIRST_TAIL * 2 * math.pi / spec.scales["p"]
            while run is None or (not run.overturned and stop < full_stop):
                stop = min(full_stop, float(t[-1]) + chunk)
                run = fmu.simulate(spec.params, ag=(t, ag), stop_time=stop,
                                   outputs=("theta", "omega", "thetaOverAlpha", "impacts"), loop="auto")
                chunk *= 2
                if not run.overturned and settled(run.result, float(t[-1])) is not None:
                    row.update(overturned=False, impacts=run.impacts, tail_skipped=stop < full_stop,
                               tail_end="cannot overturn", tail_run=stop - pulse.duration,
                               peak_theta_over_alpha=run.peak_theta_over_alpha)
                    break
            if row["overturned"] is None:
                row["tail_run"] = stop - pulse.duration
        if run is None:
            run = fmu.simulate(spec.params, ag=(t, ag), stop_time=full_stop,
                               outputs=("thetaOverAlpha", "impacts"), loop="auto")
        if row["overturned"] is None:
            row.update(overturned=bool(run.overturned), t_overturn=run.t_overturn, impacts=run.impacts,
                       peak_theta_over_alpha=run.peak_theta_over_alpha,
                       tail_end="overturned" if run.overturned else "time")
            if run.overturned:
                row["tail_run"] = max(0.0, run.t_overturn - pulse.duration)
    except Exception as exc:  # noqa: BLE001 - the row says what failed
        row["error"] = " ".join(str(exc).split())[:500]
    row["wall_s"] = time.perf_counter() - t0
    return row


def run_column(spec, w, fmu=None):
    """Rows of frequency w: the grid's amplitudes, then bisections (to spec.tol relative)
    between neighbours whose outcome differs, every transition inside each bracket followed."""
    fmu = fmu or parametric._WORKER_FMU
    rows = []

    def at(a, phase):
        row = run_one(fmu, spec, w, a)
        row["phase"] = phase
        rows.append(row)
        return row

    grid = [at(a, "grid") for a in sorted(spec.amplitudes)]

    def refine(lo, hi, depth):
        if lo["error"] or hi["error"] or outcome(lo) == outcome(hi):
            return
        if hi["a"] - lo["a"] <= spec.tol * hi["a"] or depth >= MAX_BISECTIONS:
            return
        mid = at(0.5 * (lo["a"] + hi["a"]), "bisect")
        refine(lo, mid, depth + 1)
        refine(mid, hi, depth + 1)

    for lo, hi in zip(grid, grid[1:]):
        refine(lo, hi, 0)
    return rows


def _column_task(args):
    spec, w = args
    return run_column(spec, w)


def _dask_column(digest, spec, w):
    """run_column in a Dask worker of rocking.fragility.cluster (its FMU by digest)."""
    from .fragility import runner
    with runner._LOCK:  # one run at a time per process (RockingFMU is not thread-safe)
        return run_column(spec, w, runner._FMUS[digest])


def spec_digest(spec, salt=""):
    """A hash of what decides a column's rows besides its frequency: the body, the pulse, the
    amplitudes, tol, tail, samples, units, and `salt` (`code_salt`)."""
    import hashlib
    import json
    d = metadata(spec)
    keep = {k: d[k] for k in ("params", "shape", "amplitudes", "dimensionless", "tol", "tail", "per_period",
                              "user", "cut_tail")}
    text = json.dumps(keep, sort_keys=True, default=str) + "|" + str(salt)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


def code_salt(fmu):
    """The FMU's GUID and a hash of the modules that make a map's rows (this one, the pulses,
    the FMU's driver): a stored column is not reused once any of them changed."""
    import hashlib
    from pathlib import Path

    from . import fmu as fmu_module, pulses
    digest = hashlib.sha1()
    for module in (fmu_module, pulses):
        digest.update(Path(module.__file__).read_bytes())
    digest.update(Path(__file__).read_bytes())
    return f"{fmu.model_description.guid}|{digest.hexdigest()[:16]}"


def column_key(spec, w, salt=""):
    """The store's key of the column of frequency w (grid units)."""
    return f"map-{spec_digest(spec, salt)}|w={float(w)!r}"


def run_map(spec, fmu, workers=None, progress=None, store=None, resume=True, client=None, salt=None):
    """Every column of `spec` (spec.scales filled from the FMU): a DataFrame, one row per run,
    sorted by w then a. fmu: a RockingFMU (its extraction shared with the workers).
    progress(columns done, columns, rows of the column) after each column.
    store: a rocking.map_store.MapStore: each column written there as it finishes (unless a
    run of it failed), and, with `resume`, the columns already there read instead of run.
    client: a dask.distributed Client (rocking.fragility.cluster.open_client) to run the
    columns on instead of the process pool. salt: what else keys the stored columns (default:
    `code_salt`). The table's attrs["resumed"], ["resumed_rows"]: the columns and rows read."""
    spec.check()
    if not spec.scales:
        spec.scales = body_scales(fmu, spec.params)
    columns = sorted(float(w) for w in spec.frequencies)
    if salt is None:
        salt = code_salt(fmu)
    keys = {w: column_key(spec, w, salt) for w in columns}
    finished = store.finished(keys.values()) if store is not None and resume else set()
    todo = [w for w in columns if keys[w] not in finished]
    rows = store.read_tasks([keys[w] for w in columns if keys[w] in finished]) if finished else []
    count = [len(columns) - len(todo)]
    resumed_rows = len(rows)

    def got(w, new):
        if store is not None and not any(r["error"] for r in new):
            store.write(keys[w], new)
        rows.extend(new)
        count[0] += 1
        if progress:
            progress(count[0], len(columns), new)

    workers = max(1, min(int(workers or os.cpu_count() or 1), max(1, len(todo))))
    if client is not None and todo:
        _run_on_dask(client, fmu, spec, todo, keys, store, got)
    elif workers == 1:
        for w in todo:
            got(w, run_column(spec, w, fmu))
    elif todo:
        with ProcessPoolExecutor(max_workers=workers, initializer=parametric._init_worker,
                                 initargs=(str(fmu.unzipdir),)) as pool:
            futures = {pool.submit(_column_task, (spec, w)): w for w in todo}
            for fut in as_completed(futures):
                got(futures[fut], fut.result())
    table = pd.DataFrame(rows)
    table["outcome"] = [OUTCOMES[outcome(r)] if not r["error"] else "error" for r in rows]
    over = table["overturned"].fillna(False).astype(bool)
    table["overturned_in"] = np.where(over, np.where(table["t_overturn"] <= table["pulse_end"], "pulse", "tail"), "")
    table["w_p_over_p"] = table["w_p"] / spec.scales["p"]
    table["a_p_over_g_tan_alpha"] = table["a_p"] / spec.scales["g_tan_alpha"]
    table.insert(0, "shape", spec.shape)
    table = table.sort_values(["w", "a"], kind="stable").reset_index(drop=True)
    table.attrs["resumed"] = len(columns) - len(todo)
    table.attrs["resumed_rows"] = resumed_rows
    return table


class _Collect:
    """A store for rocking.fragility.cluster.execute that hands each task's result to `got`."""

    def __init__(self, got):
        self.got = got

    def finished(self, keys):
        return set()

    def write(self, key, result):
        self.got(key, result)


def on_dask(client, fmu, tasks, got, what, hint=""):
    """Run `tasks` [(key, function, args, expected runs)] as tasks of rocking.fragility.cluster.
    execute (its FMU plugin, records sent once, its submission window): function(digest, *args)
    on a worker, the FMU there `rocking.fragility.runner._FMUS[digest]`; got(key, result) as
    each finishes. A task lost or failed is a RuntimeError naming `what` (the map's columns,
    a spectrum's bodies) and ending with `hint`, once the others are done."""
    from .fragility import cluster
    if fmu.path is None:
        raise ValueError("client: the FMU must be opened from its .fmu file to send it to Dask workers")
    digest = cluster.register_fmu(client, fmu.path)
    _, _, failures = cluster.execute(client, [(key, fn, (digest, *args), n) for key, fn, args, n in tasks],
                                     _Collect(got))
    if failures:
        key, err = next(iter(failures.items()))
        raise RuntimeError(f"{len(failures)} {what} failed on Dask, e.g. {key}: {err}" + (f" ({hint})" if hint else ""))


def _run_on_dask(client, fmu, spec, todo, keys, store, got):
    """The columns `todo` as Dask tasks (`on_dask`); a column lost or failed is an error here
    (rerun the map: the columns done are in the store)."""
    by_key = {keys[w]: w for w in todo}
    on_dask(client, fmu, [(keys[w], _dask_column, (spec, w), len(spec.amplitudes)) for w in todo],
            lambda key, rows: got(by_key[key], rows),
            "map column(s)", "the finished columns are in the store: run the map again" if store is not None else "")


def boundaries(runs, spec):
    """The overturning intervals of each frequency: one row per interval of amplitudes in which
    the body overturns, its ends bracketed by runs (a_from_lo < start <= a_from_hi, a_to_lo <=
    end < a_to_hi). An interval that begins at the grid's lowest amplitude says so
    (below_grid), one that reaches its highest (above_grid, a_to_* nan); windows of safety
    above the first overturning are the gaps between a frequency's intervals. `unresolved`
    names what the runs leave open: a bracket wider than tol (a failed run, or the bisection
    budget), and a change of overturning mode with no safe run between (a safe window narrower
    than tol may lie there). Windows narrower than the grid's step between two grid runs of the
    same outcome are not seen (the grid's resolution, in the file's metadata)."""
    out = []
    for w, col in runs.groupby("w", sort=True):
        col = col.sort_values("a")
        recs = col.to_dict("records")
        classes = [outcome(r) if not r["error"] else None for r in recs]
        k = 0
        n = len(recs)
        while k < n:
            if classes[k] in (None, SAFE):
                k += 1
                continue
            start = k
            notes = []
            modes = {classes[k]}
            while k + 1 < n and classes[k + 1] not in (None, SAFE):
                if classes[k + 1] != classes[k]:
                    notes.append(f"mode changes at a = {recs[k]['a']:.6g}..{recs[k + 1]['a']:.6g} "
                                 "with no safe run between")
                modes.add(classes[k + 1])
                k += 1
            end = k
            lo = recs[start - 1] if start > 0 else None
            hi = recs[end + 1] if end + 1 < n else None
            for a, b in ((lo, recs[start]), (recs[end], hi)):
                if a is None or b is None:
                    continue
                if a["error"] or b["error"]:
                    notes.append(f"failed run near a = {a['a']:.6g}..{b['a']:.6g}")
                elif b["a"] - a["a"] > spec.tol * b["a"] * (1 + 1e-9):
                    notes.append(f"bracket {a['a']:.6g}..{b['a']:.6g} wider than tol")
            first = recs[start]
            out.append(dict(
                w=w, w_p=first["w_p"], w_p_over_p=first["w_p_over_p"],
                a_from_lo=lo["a"] if lo else math.nan, a_from_hi=first["a"],
                a_to_lo=recs[end]["a"], a_to_hi=hi["a"] if hi else math.nan,
                start=(0.5 * (lo["a"] + first["a"])) if lo else first["a"],
                end=(0.5 * (recs[end]["a"] + hi["a"])) if hi else math.inf,
                mode_at_start=OUTCOMES[classes[start]],
                modes=", ".join(OUTCOMES[m] for m in sorted(modes)),
                impacts_at_start=int(first["impacts"]),
                below_grid=lo is None, above_grid=hi is None,
                unresolved="; ".join(notes)))
            k += 1
    columns = ["w", "w_p", "w_p_over_p", "start", "end", "a_from_lo", "a_from_hi", "a_to_lo", "a_to_hi",
               "mode_at_start", "modes", "impacts_at_start", "below_grid", "above_grid", "unresolved"]
    table = pd.DataFrame(out, columns=columns)
    numbers = ["w", "w_p", "w_p_over_p", "start", "end", "a_from_lo", "a_from_hi", "a_to_lo", "a_to_hi"]
    return table.astype({**{c: float for c in numbers}, "impacts_at_start": int, "below_grid": bool,
                         "above_grid": bool, "mode_at_start": str, "modes": str, "unresolved": str})


def mode_changes(runs):
    """Where the overturning mode changes between neighbouring runs of a frequency with no safe
    run between: one row per change (w, a_lo, a_hi, below: the mode under it, above)."""
    out = []
    for w, col in runs.sort_values("a").groupby("w", sort=True):
        recs = [r for r in col.to_dict("records") if not r["error"]]
        for lo, hi in zip(recs, recs[1:]):
            c_lo, c_hi = outcome(lo), outcome(hi)
            if SAFE not in (c_lo, c_hi) and c_lo != c_hi:
                out.append(dict(w=w, a_lo=lo["a"], a_hi=hi["a"], below=OUTCOMES[c_lo], above=OUTCOMES[c_hi]))
    return pd.DataFrame(out, columns=["w", "a_lo", "a_hi", "below", "above"])


def first_overturning(bounds):
    """{w: the least overturning amplitude (grid units)}: the first interval's start."""
    return {w: float(g["start"].min()) for w, g in bounds.groupby("w")}


def metadata(spec, extra=None):
    """The map's inputs as a JSON-able dict (the Parquet files' metadata)."""
    d = asdict(spec)
    d["user"] = None if spec.user is None else [list(map(float, x)) for x in spec.user]
    d["frequencies"] = [float(x) for x in spec.frequencies]
    d["amplitudes"] = [float(x) for x in spec.amplitudes]
    a = np.sort(np.asarray(spec.amplitudes, dtype=float))
    d["grid_resolution"] = float(np.max(np.diff(a) / a[1:])) if a.size > 1 else None
    d["units"] = ({"w": "w_p / p", "a": "a_p / (g tan alpha)"} if spec.dimensionless
                  else {"w": "rad/s", "a": "m/s2"})
    d.update(extra or {})
    return d


def write_parquet(table, path, meta):
    """`table` to `path` with `meta` (JSON) under the schema's metadata key b"rocking"."""
    import json

    import pyarrow as pa
    import pyarrow.parquet as pq

    arrow = pa.Table.from_pandas(table, preserve_index=False)
    arrow = arrow.replace_schema_metadata({**(arrow.schema.metadata or {}),
                                           b"rocking": json.dumps(meta).encode()})
    pq.write_table(arrow, path)


def read_metadata(path):
    import json

    import pyarrow.parquet as pq
    return json.loads(pq.read_schema(path).metadata[b"rocking"])
