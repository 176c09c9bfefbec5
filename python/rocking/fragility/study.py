"""A study: bodies x records, by incremental dynamic analysis (a search for each record's
first collapse) or by multiple stripes (records x target intensities); its tasks, and its
results read back.

    study = Study(bodies={"block": params}, suite=load_suite([folder]), im=parse("PGV"),
                  method="ida")
    tasks = study.tasks(fmu, digest)            # [(key, function, args, expected runs)]
    df = store.read(); result = study.analyse(df)

Task keys name the body (with a hash of its parameters), the record (with a
hash of its samples), the intensity measure and the options that change a
run's outcome: rerunning a changed study never reuses stale rows.
"""

import hashlib
import json
import math
import re
from dataclasses import dataclass, field

import numpy as np

from . import runner
from .fit import ida_fragility, msa_fragility
from .hunt import HuntOptions, capacity, interpolated

#: How an IDA locates a damage state's capacity: "bracket", as overturning (the search
#: brackets the first run that reaches it to the tolerance); "interpolate", where the IDA
#: curve, linear between the runs, first reaches the threshold (Vamvatsikos & Cornell 2002).
DAMAGE_CAPACITY = ("bracket", "interpolate")


#: Largest task of runs at fixed intensities (chunk 0), in integration steps: about a third
#: of a second of runs (a run of the shipped suite, 9800 steps on average, costs about 10.6 ms of
#: CPU on an idle core: 1.1 us a step; runs that overturn stop early and cost less).
STEPS_PER_TASK = 300_000

#: Smallest task (chunk 0), in integration steps: about 0.04 s of runs (4 of the shipped
#: suite). The last tasks are this small, so that two workers finish within about that of each
#: other however far the runs' real costs stray from their steps (overturning runs stop early).
SMALLEST_TASK = 40_000

#: Each task (chunk 0) takes this share of the steps not yet in a task, between SMALLEST_TASK
#: and STEPS_PER_TASK: the tasks shrink as the study goes, the largest submitted first (a
#: guided schedule). On the measured costs of the 144-run study, list scheduling on 2 workers
#: is then 0.96-0.98 efficient with 11 tasks, against 0.93 with 8 of equal steps. A constant,
#: not the cluster's size: the tasks, and so the keys a resume finds, depend on the study only.
SHARE = 1 / 4


def shrinking_batches(units, cost):
    """units cut, in order, into batches whose cost is SHARE of the cost not yet batched,
    bounded by SMALLEST_TASK and STEPS_PER_TASK (a batch ends at the first unit that reaches
    its target): large batches first, small ones last."""
    remaining = sum(cost(u) for u in units)
    batches, current, size = [], [], 0
    target = _target(remaining)
    for unit in units:
        current.append(unit)
        size += cost(unit)
        if size >= target:
            batches.append(current)
            remaining -= size
            current, size = [], 0
            target = _target(remaining)
    if current:
        batches.append(current)
    return batches


def _target(remaining):
    return max(SMALLEST_TASK, min(STEPS_PER_TASK, remaining * SHARE))


def _hash(obj):
    return hashlib.sha1(json.dumps(obj, sort_keys=True, default=str).encode()).hexdigest()[:10]


def record_id(name, record):
    """name#hash of the record's samples (and of its vertical av, when it carries one: a study
    with `vertical = true` does not resume from the runs without it)."""
    digest = hashlib.sha1(record.acc.tobytes())
    if record.av_record is not None:
        digest.update(b"av" + record.av_record.acc.tobytes())
    return f"{name}#{digest.hexdigest()[:8]}"


_COMPONENT = re.compile(r"([._-](000|090|180|270|360|H1|H2|HN1|HN2|HNE|HNN|HE|HN|NS|EW|N|E|L|T)"
                        r"|(?<=\d)[a-c])$", re.IGNORECASE)


def station_of(name):
    """The station of a record component named by load_suite ('FILE[COMPONENT]' or 'FILE'):
    the file for a multi-component file, else the file name without its extension and a
    trailing component tag (GeoNet's .000/.090, _H1/_H2, USGS SMC's 0111a/0111c)."""
    base = name.split("[", 1)[0] if name.endswith("]") else name
    if name.endswith("]") and not re.search(r"\.(at2|000|090|180|270|360|smc)$", base, re.IGNORECASE):
        return base
    folder, _, file = base.rpartition("/")
    stem = re.sub(r"\.(at2|smc|csv|txt|dat|asc|acc)$", "", file, flags=re.IGNORECASE)
    stem = _COMPONENT.sub("", stem)
    return f"{folder}/{stem}" if folder else stem


@dataclass
class Study:
    """bodies {name: params}; suite {name: Record}; im an IntensityMeasure; method 'ida' or
    'msa'; stripes the target intensities (msa); hunt the HuntOptions (ida); grid > 0: IDA on
    a dense grid of that many intensities per record (geometric, the hunt's start to its
    stop) instead of the hunt; tail s simulated after each record's end; chunk runs per task
    of stripes or grid (0: shrinking_batches, a third of a second of runs down to 0.04 s); estimator of
    beta ('mle' or 'moments', IDA); beta_modelling the FEMA P-58 modelling dispersion;
    damage_states {name: threshold on peak |theta| / alpha}, each searched for (IDA) and
    fitted beside overturning; damage_capacity one of DAMAGE_CAPACITY; by_station: the
    bootstrap resamples stations (station_of)."""

    bodies: dict
    suite: dict
    im: object
    method: str = "ida"
    stripes: tuple = ()
    hunt: HuntOptions = field(default_factory=HuntOptions)
    tail: float = 5.0
    rtol: float = None
    chunk: int = 0
    grid: int = 0
    estimator: str = "mle"
    beta_modelling: float = 0.0
    damage_states: dict = field(default_factory=dict)
    damage_capacity: str = "bracket"
    by_station: bool = True

    def __post_init__(self):
        if self.damage_capacity not in DAMAGE_CAPACITY:
            raise ValueError(f"damage_capacity {self.damage_capacity!r}: expected one of {', '.join(DAMAGE_CAPACITY)}")

    def opts(self):
        return {"tail": self.tail, "rtol": self.rtol}

    def body_facts(self, fmu):
        """{body: (alpha, g, p)} from the FMU's calculated parameters."""
        facts = {}
        for name, params in self.bodies.items():
            try:
                calc = fmu.calculated(params)
            except Exception as exc:  # noqa: BLE001 - FMUError: name the body
                raise ValueError(f"body {name}: {exc}") from None
            p = math.sqrt(calc["weight"] * calc["R0"] / calc["IO"])
            facts[name] = (calc["alpha"], calc["weight"] / calc["mass"], p)
        return facts

    def jobs(self, facts):
        """One job per (body, record): (key tag, params, record and the row's meta columns, g);
        facts as `body_facts` returns them."""
        out = []
        for bname, params in self.bodies.items():
            alpha, g, p = facts[bname]
            for rname, rec in self.suite.items():
                im_rec = self.im.of(rec, alpha=alpha, g=g, p=p)
                if not im_rec > 0:
                    raise ValueError(f"record {rname}: its {self.im.name} is {im_rec:g}; it cannot be scaled")
                meta = dict(method=self.method, body=bname, record=rname, im_name=self.im.name,
                            im_record=im_rec, alpha=alpha)
                tag = f"{bname}#{_hash(params)}|{record_id(rname, rec)}|{self.im.name}"
                out.append((tag, dict(params=params, record=rec, meta=meta), g))
        return out

    def tasks(self, fmu, digest, fmu_path=None):
        """[(key, function, args, expected runs)] of the study."""
        opts = dict(self.opts(), fmu_path=None if fmu_path is None else str(fmu_path))
        salt = _hash(self.opts())
        out, fixed = [], []
        for tag, job, g in self.jobs(self.body_facts(fmu)):
            meta = job["meta"]
            if self.method == "ida":
                hunt = dict(vars(self.hunt))
                # first run where the rigid body would just uplift: PGA = g tan(alpha)
                start = meta["im_record"] * g * math.tan(meta["alpha"]) / job["record"].pga
                if self.grid:
                    fixed.append((tag, job, [float(x) for x in np.geomspace(start, start * self.hunt.stop, self.grid)]))
                    continue
                states = dict(self.damage_states)
                # the damage states steer the search: their thresholds are in the key
                key = f"ida|{tag}|{_hash(dict(hunt, damage_states=states) if states else hunt)}|{salt}"
                meta["task"] = key
                out.append((key, runner.run_hunt, (digest, job, start, hunt, opts, states), self.hunt.max_runs))
            else:
                fixed.append((tag, job, [float(x) for x in self.stripes]))
        return out + self._batches(fixed, digest, opts, salt)

    def _batches(self, fixed, digest, opts, salt):
        """Tasks of the runs at fixed intensities [(tag, job, intensities)]: `chunk` runs each,
        or (chunk 0) shrinking_batches of the integration steps, across records and bodies,
        largest first. Deterministic: a rerun finds the same keys."""
        phase = "grid" if self.method == "ida" else "stripe"
        units = [(tag, job, im, self._steps(job)) for tag, job, ims in fixed for im in ims]
        if self.chunk:
            batches = [units[i:i + self.chunk] for i in range(0, len(units), self.chunk)]
        else:
            batches = shrinking_batches(units, lambda u: u[3])
        out = []
        for batch in batches:
            parts, tags = {}, {}
            for tag, job, im, _ in batch:
                parts.setdefault(tag, (job, []))[1].append(im)
            key = f"{self.method}|{_hash([(t, ims) for t, (_, ims) in parts.items()])}|{salt}|{phase}"
            args = [(dict(job, meta=dict(job["meta"], task=key)), ims) for job, ims in parts.values()]
            out.append((key, runner.run_batch, (digest, args, opts, phase), len(batch)))
        return out

    def _steps(self, job):
        """Integration steps of one run of `job`: the record and the tail at the record's dt."""
        rec = job["record"]
        return int((rec.duration + self.tail) / rec.dt)

    # ------------------------------------------------------------------ results
    def states(self):
        """[(name, threshold)] of the limit states fitted: the damage states, then overturning
        (threshold None)."""
        return sorted(self.damage_states.items(), key=lambda kv: kv[1]) + [("overturning", None)]

    def analyse(self, df, n_boot=1000, seed=0):
        """{body: {"fragility": Fragility or None, "error": text, "records": {...},
        "states": {state: {"fragility", "error"}}}} from the rows of this study's method (failed
        runs left out); "fragility" and "error" are those of overturning."""
        df = df[df["method"] == self.method]
        failed = df[df["error"] != ""]
        df = df[df["error"] == ""]
        out = {}
        for body in self.bodies:
            rows = df[df["body"] == body]
            if self.method == "ida":
                entry = self._analyse_ida(rows, failed[failed["body"] == body], n_boot, seed)
            else:
                entry = self._analyse_msa(rows, n_boot, seed)
            entry["fragility"] = entry["states"]["overturning"]["fragility"]
            entry["error"] = entry["states"]["overturning"]["error"]
            out[body] = entry
        return out

    def _fit(self, fitter, *args, **kw):
        try:
            return dict(fragility=fitter(*args, **kw), error="")
        except ValueError as exc:
            return dict(fragility=None, error=str(exc))

    def _stations(self, names):
        return [station_of(n) for n in names] if self.by_station else None

    def _analyse_ida(self, rows, failed, n_boot, seed):
        entry = {"records": {}, "states": {}}
        broken = failed.groupby("record")["error"].first()
        for rname, err in broken.items():  # a hunt that stopped on an error
            entry["records"][rname] = dict(capacity=math.nan, censored=True, below=False, runs=0, error=err)
        per_state = {name: ([], [], []) for name, _ in self.states()}
        names = []
        for rname, r in rows[~rows["record"].isin(broken.index)].groupby("record"):
            ims = r["im"].to_numpy(float)
            over = r["overturned"].to_numpy(bool)
            peak = r["peak_theta_over_alpha"].to_numpy(float)
            why = r["unresolved"].dropna() if "unresolved" in r else []
            info = dict(runs=len(r), unresolved=str(why.iloc[0]) if len(why) else "")
            trace = list(zip(ims, over, peak))
            for name, thr in self.states():
                locate = interpolated if thr is not None and self.damage_capacity == "interpolate" else capacity
                cap, cens, below = locate(trace, thr)
                for column, value in zip(per_state[name], (cap, cens, below)):
                    column.append(value)
                if thr is None:
                    info.update(capacity=cap, censored=cens, below=below)
                else:
                    info.setdefault("damage_states", {})[name] = dict(capacity=cap, censored=cens, below=below)
            entry["records"][rname] = info
            names.append(rname)
        for name, (caps, cens, below) in per_state.items():
            entry["states"][name] = (self._fit(ida_fragility, caps, cens, n_boot=n_boot, seed=seed,
                                               estimator=self.estimator, beta_modelling=self.beta_modelling,
                                               stations=self._stations(names), below=below)
                                     if caps else dict(fragility=None, error="no runs"))
        return entry

    def _analyse_msa(self, rows, n_boot, seed):
        entry = {"records": {}, "states": {}}
        stripes = np.array(sorted(set(float(x) for x in self.stripes)))
        tables = {name: [] for name, _ in self.states()}
        names = []
        for rname, r in rows.groupby("record"):
            keys = np.round(r["im"].to_numpy(float), 12)
            over = r["overturned"].to_numpy(bool)
            peak = r["peak_theta_over_alpha"].to_numpy(float)
            for name, thr in self.states():
                hit = (over if thr is None else over | (peak >= thr)).astype(float)
                by_im = dict(zip(keys, hit))
                tables[name].append([by_im.get(round(x, 12), np.nan) for x in stripes])
            entry["records"][rname] = dict(collapsed=int(np.nansum(tables["overturning"][-1])), runs=len(r))
            names.append(rname)
        for name, table in tables.items():
            event = "overturned" if name == "overturning" else f"reached {name}"
            entry["states"][name] = (self._fit(msa_fragility, stripes, table, n_boot=n_boot, seed=seed,
                                               beta_modelling=self.beta_modelling,
                                               stations=self._stations(names), event=event)
                                     if table else dict(fragility=None, error="no runs"))
        return entry
