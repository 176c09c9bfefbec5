"""A study: bodies x records, by incremental dynamic analysis (hunt-and-fill per record) or
by multiple stripes (records x target intensities); its tasks, and its results read back.

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
from dataclasses import dataclass, field

import numpy as np

from . import runner
from .fit import ida_fragility, msa_fragility
from .hunt import HuntOptions, capacity


def _hash(obj):
    return hashlib.sha1(json.dumps(obj, sort_keys=True, default=str).encode()).hexdigest()[:10]


def record_id(name, record):
    return f"{name}#{hashlib.sha1(record.acc.tobytes()).hexdigest()[:8]}"


@dataclass
class Study:
    """bodies {name: params}; suite {name: Record}; im an IntensityMeasure; method 'ida' or
    'msa'; stripes the target intensities (msa); hunt the HuntOptions (ida); tail s simulated
    after each record's end; chunk stripe runs per task (msa)."""

    bodies: dict
    suite: dict
    im: object
    method: str = "ida"
    stripes: tuple = ()
    hunt: HuntOptions = field(default_factory=HuntOptions)
    tail: float = 5.0
    rtol: float = None
    chunk: int = 10

    def opts(self):
        return {"tail": self.tail, "rtol": self.rtol}

    def body_facts(self, fmu):
        """{body: (alpha, g)} from the FMU's calculated parameters."""
        facts = {}
        for name, params in self.bodies.items():
            try:
                calc = fmu.calculated(params)
            except Exception as exc:  # noqa: BLE001 - FMUError: name the body
                raise ValueError(f"body {name}: {exc}") from None
            facts[name] = (calc["alpha"], calc["weight"] / calc["mass"])
        return facts

    def jobs(self, facts):
        """One job per (body, record): (key tag, params, record and the row's meta columns, g);
        facts as `body_facts` returns them."""
        out = []
        for bname, params in self.bodies.items():
            alpha, g = facts[bname]
            for rname, rec in self.suite.items():
                im_rec = self.im.of(rec, alpha=alpha, g=g)
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
        out = []
        for tag, job, g in self.jobs(self.body_facts(fmu)):
            meta = job["meta"]
            if self.method == "ida":
                hunt = dict(vars(self.hunt))
                # first run where the rigid body would just uplift: PGA = g tan(alpha)
                start = meta["im_record"] * g * math.tan(meta["alpha"]) / job["record"].pga
                key = f"ida|{tag}|{_hash(hunt)}|{salt}"
                meta["task"] = key
                out.append((key, runner.run_hunt, (digest, job, start, hunt, opts), self.hunt.max_runs))
            else:
                for i in range(0, len(self.stripes), self.chunk):
                    part = [float(x) for x in self.stripes[i:i + self.chunk]]
                    key = f"msa|{tag}|{_hash(part)}|{salt}"
                    job_i = dict(job, meta=dict(meta, task=key))
                    out.append((key, runner.run_stripes, (digest, job_i, part, opts), len(part)))
        return out

    # ------------------------------------------------------------------ results
    def analyse(self, df, n_boot=1000, seed=0):
        """{body: {"fragility": Fragility or None, "error": text, "records": {...}}} from the
        rows of this study's method (failed runs left out)."""
        df = df[df["method"] == self.method]
        failed = df[df["error"] != ""]
        df = df[df["error"] == ""]
        out = {}
        for body in self.bodies:
            rows = df[df["body"] == body]
            entry = {"fragility": None, "error": "", "records": {}}
            try:
                if self.method == "ida":
                    caps, cens = [], []
                    broken = failed[failed["body"] == body].groupby("record")["error"].first()
                    for rname, err in broken.items():  # a hunt that stopped on an error
                        entry["records"][rname] = dict(capacity=math.nan, censored=True, runs=0, error=err)
                    for rname, r in rows[~rows["record"].isin(broken.index)].groupby("record"):
                        trace = list(zip(r["im"], r["overturned"].astype(bool)))
                        cap, censored = capacity(trace)
                        entry["records"][rname] = dict(capacity=cap, censored=censored, runs=len(r))
                        caps.append(cap)
                        cens.append(censored)
                    if not caps:
                        raise ValueError("no runs")
                    entry["fragility"] = ida_fragility(caps, cens, n_boot=n_boot, seed=seed)
                else:
                    stripes = np.array(sorted(set(float(x) for x in self.stripes)))
                    table = []
                    for rname, r in rows.groupby("record"):
                        by_im = dict(zip(np.round(r["im"], 12), r["overturned"].astype(float)))
                        table.append([by_im.get(round(x, 12), np.nan) for x in stripes])
                        entry["records"][rname] = dict(collapsed=int(np.nansum(table[-1])), runs=len(r))
                    if not table:
                        raise ValueError("no runs")
                    entry["fragility"] = msa_fragility(stripes, table, n_boot=n_boot, seed=seed)
            except ValueError as exc:
                entry["error"] = str(exc)
            out[body] = entry
        return out
