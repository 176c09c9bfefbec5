"""Does a level of the paper's corner that stands at 10 mm/s but ended its 0.3 s hold above
1 mm/s come to rest under a longer hold? (docs/corner-blocks.md, "The longer hold"):

    nice -n 10 .venv/bin/python examples/corner_dem_long_hold.py --ends free --index 2
        [--long 0.9] [--from-lam LAM] [--out data/corner-blocks/numerics]

reruns the study's committed DEM case (data/corner-blocks/dem_{ends}_mu0.66_{index}.json, its
own protocol and start) with every level from --from-lam on (default: the first that stood
at the case's rest speed but ended faster than 1 mm/s) held --long seconds instead of the
study's hold; the levels below keep theirs, so the run repeats the committed one up to that
level. Besides dem.run's result it records, at every check of the collapse displacement
(dem.CHECK, 0.05 s), the fastest block corner's speed over the last step (dem.run's speed)
and the largest displacement (the blocks' corners are left out). One LMGC90 run in this
process (it spends the process)."""

import argparse
import json
import math
import os
import sys
from pathlib import Path

import numpy as np

from rocking.corner_blocks import dem

AMBIGUOUS = 1e-3  # m/s: the old rest speed; a level that stood above it is the question


def first_ambiguous(history):
    """The first level that stood but ended its hold at AMBIGUOUS m/s or faster."""
    for lam, rested, speed, _disp, _steps in history:
        if rested and speed >= AMBIGUOUS:
            return lam
    raise SystemExit("no level stood above 1 mm/s in the committed case: nothing to rerun")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--ends", required=True, choices=("fixed", "free"))
    p.add_argument("--index", type=int, required=True, help="orientation index 0..4 (pi/4 .. pi/2)")
    p.add_argument("--long", type=float, default=0.9, help="hold from --from-lam on, s (default 0.9)")
    p.add_argument("--from-lam", type=float,
                   help="first level held --long (default: the first ambiguous one)")
    p.add_argument("--study", default="data/corner-blocks", help="folder of the committed case")
    p.add_argument("--out", default="data/corner-blocks/numerics")
    a = p.parse_args(argv)
    source = Path(a.study) / f"dem_{a.ends}_mu0.66_{a.index}.json"
    base = json.loads(source.read_text())
    protocol = dem.Protocol(**base["protocol"])
    short = protocol.hold
    from_lam = a.from_lam if a.from_lam is not None else first_ambiguous(base["history"])
    spec = {"specimen": {"ends": a.ends, "mu": 0.66, "courses": 9, "blocks": 7}}
    assembly = dem.assembly_of(spec)
    n = len(assembly.blocks)
    reach = np.array([np.linalg.norm(b.size) / 2 for b in assembly.blocks])
    trace, now = [], {"lam": None, "t": 0.0, "speed": math.nan, "prev": None}

    levels, state, displacements = dem.levels, dem.state, dem._displacements

    def levels_held(proto):
        # run reads proto.hold afresh at every level: set it before the level starts
        for lam in levels(proto):
            proto.hold = a.long if lam >= from_lam - 1e-9 else short
            now["lam"], now["t"] = lam, 0.0
            yield lam

    def state_traced(result, count):
        c, f = state(result, count)
        if now["prev"] is not None:  # dem.run's own speed of the step (its `advance`)
            pc, pf = now["prev"]
            omega = np.linalg.norm((f - pf).reshape(count, -1), axis=1)
            now["speed"] = float(np.max(np.linalg.norm(c - pc, axis=1) + omega / math.sqrt(2) * reach)
                                 / protocol.dt)
        now["prev"] = (c, f)
        return c, f

    def displacements_traced(*args):
        d = displacements(*args)
        if now["lam"] is not None:
            slices = max(1, int(round(protocol.hold / dem.CHECK)))
            now["t"] += protocol.hold / slices
            trace.append([round(now["lam"], 10), round(now["t"], 6), now["speed"], float(d.max())])
        return d

    dem.levels, dem.state, dem._displacements = levels_held, state_traced, displacements_traced
    result = dem.run(assembly, base["alpha"], protocol, log=lambda s: print(s, file=sys.stderr, flush=True))
    result["protocol"]["hold"] = short
    del trace[-1]  # run's last look, 0.1 s after the collapse, belongs to no hold
    del result["corners"]  # the mechanism's drawing (study.dem_figure), not needed here
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    name = f"paper_{a.ends}_{a.index}_hold{a.long:g}"
    record = {
        "command": "nice -n 10 .venv/bin/python examples/corner_dem_long_hold.py "
                   + " ".join(argv if argv is not None else sys.argv[1:]),
        "source": str(source), "long_hold": a.long, "from_lam": from_lam, "short_hold": short,
        "trace_columns": ["lambda", "t in the level's hold (s)", "speed (m/s)", "displacement (m)"],
        "trace": trace, **result}
    (out / f"{name}.json").write_text(json.dumps(record))
    print(json.dumps({k: record[k] for k in ("lam", "collapsed", "cpu_s")}), flush=True)
    os._exit(0)  # the engine's teardown corrupts the heap (dem.main)


if __name__ == "__main__":
    main()
