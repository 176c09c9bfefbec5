"""The cost of the vertical input on a real record (docs/performance.md, "The host loop with a
vertical input"): six Dharahara cases under DFHS 090 x3 of data/ground-motions, with and without
the Darfield station's vertical component as the FMU's av, through RockingFMU.simulate (the
native stepping loop), rtol 1e-11, 5 s past the record. CPU time of this process, best of
--repeats interleaved runs; prints a table.

    .venv/bin/python benches/vertical_record.py [--fmu path/to/RockingBlock.fmu] [--repeats 3]

--dump PATH writes the two components (unscaled) for examples/vertical_record.rs instead: the
time step, then `ag av` per sample, m/s².
"""

import argparse
import time

from rocking import RockingFMU, paths
from rocking import groundmotion as gm
from rocking.cases import dharahara_cases

CASES = ("rigid", "I5_elastic", "I15_elastic", "F170_fm5", "F85_fm2", "I15_fm2")
SCALE = 3.0
RTOL = 1e-11


def darfield_dfhs():
    """The DFHS 090 component and its station's vertical."""
    path = next(p for p in paths.data_dir().rglob("*DFHS*") if p.is_file())
    rec = next(r for r in gm.read_all(path) if r.component == "090")
    return rec, gm.vertical_of(rec)


def dump(rec, vertical, path):
    """The time step, then `ag av` per sample (m/s², shortest's length)."""
    if vertical.dt != rec.dt:
        raise SystemExit(f"{path}: the components' time steps differ ({rec.dt}, {vertical.dt})")
    with open(path, "w") as f:
        f.write(f"{rec.dt!r}\n")
        for a, b in zip(rec.acc, vertical.acc):
            f.write(f"{float(a)!r} {float(b)!r}\n")
    print(f"{path}: {min(len(rec.acc), len(vertical.acc))} samples at {rec.dt} s")


def outcome(run):
    if run.overturned:
        return f"overturns at {run.t_overturn:.2f} s"
    return f"peak {run.peak_theta_over_alpha:.3f} alpha"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fmu", default=None, help="default: target/fmu/RockingBlock.fmu")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--dump", metavar="PATH", help="write the record for examples/vertical_record.rs")
    args = ap.parse_args()
    rec, vertical = darfield_dfhs()
    if args.dump:
        dump(rec, vertical, args.dump)
        return
    cases = dharahara_cases()
    fmu = RockingFMU(args.fmu)
    print(f"{rec.name} [{rec.component}] x{SCALE:g}, av: [{vertical.component}]")
    print("| case | av = 0 | with av | CPU av = 0 (s) | CPU with av (s) | ratio |")
    print("|---|---|---|---|---|---|")
    for name in CASES:
        best, seen = {}, {}
        for _ in range(args.repeats):
            for tag, av in (("without", None), ("with", vertical)):
                c0 = time.process_time()
                run = fmu.simulate(dict(cases[name]), record=rec, scale=SCALE,
                                   stop_time=rec.duration + 5.0, rtol=RTOL,
                                   outputs=("thetaOverAlpha",), vertical=av)
                best[tag] = min(best.get(tag, float("inf")), time.process_time() - c0)
                seen[tag] = outcome(run)
        print(f"| {name} | {seen['without']} | {seen['with']} | {best['without']:.3f} | "
              f"{best['with']:.3f} | {best['with'] / best['without']:.2f} |")


if __name__ == "__main__":
    main()
