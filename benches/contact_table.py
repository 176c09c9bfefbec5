#!/usr/bin/env python3
"""fmi2DoStep with the tabulated contact against an FMU that solves every contact.

    .venv/bin/python benches/contact_table.py --before OLD.fmu [--after NEW.fmu] [--cases all] [--repeat 3]

OLD.fmu is a RockingBlock.fmu built before the contact table
(src/interface/table.rs) entered the integrator (e.g. from a checkout of an
earlier commit: `cargo xtask fmu`, then copy target/fmu/RockingBlock.fmu
aside); NEW.fmu defaults to target/fmu/RockingBlock.fmu. Both run each
Dharahara case (docs/model.md §4) under the KATNP stand-in at the case study's
tolerance (rtol 1e-11) through the native stepping loop (rocking.stepper),
alternately, in this one process, so the ratio is free of the machine's drift.

Printed per case: the CPU time per fmi2DoStep of each (min over --repeat), their
ratio, and how far the new run is from the old one: the largest difference of
theta / alpha along the run, the peak |theta| / alpha and the overturning time
of each (the case study's bars). How close the table's af is to the solve's at
the same rotation is tests/contact_table.rs's to show: along a run, the two
trajectories part at the level of the integrator's error, and af, steep in
theta on a stiff interface, magnifies that.
"""

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

from rocking import RockingFMU, stepper
from rocking import groundmotion as gm
from rocking.cases import dharahara_cases
from rocking.tables import markdown

RTOL = 1e-11
OUTPUTS = ("thetaOverAlpha",)
REPO = Path(__file__).resolve().parents[1]


def run(fmu, params, record):
    c0 = time.process_time()
    r = fmu.simulate(params, record=record, rtol=RTOL, outputs=OUTPUTS, loop="native")
    return time.process_time() - c0, r


def compare(before, after, name, params, record, repeat):
    best = {"before": np.inf, "after": np.inf}
    runs = {}
    for _ in range(repeat):
        for key, fmu in (("before", before), ("after", after)):
            cpu, runs[key] = run(fmu, params, record)
            best[key] = min(best[key], cpu)
    b, a = runs["before"], runs["after"]
    n = min(len(b.result), len(a.result))
    steps = max(n - 1, 1)
    dtheta = np.max(np.abs(b.result["thetaOverAlpha"][:n] - a.result["thetaOverAlpha"][:n]))
    tov = lambda r: f"{r.t_overturn:.6f} s" if r.overturned else "-"  # noqa: E731
    return [name, steps, f"{1e6 * best['before'] / steps:.2f}", f"{1e6 * best['after'] / steps:.2f}",
            f"{best['before'] / best['after']:.2f}", f"{dtheta:.1e}",
            f"{b.peak_theta_over_alpha:.6f}", f"{a.peak_theta_over_alpha:.6f}", tov(b), tov(a)], best


def table(header, rows):
    print(markdown(header, rows), flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", required=True, help="an FMU that solves every contact")
    ap.add_argument("--after", default=str(REPO / "target/fmu/RockingBlock.fmu"))
    ap.add_argument("--cases", default="all", help="comma-separated case ids, or all (49)")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    if stepper.library() is None:
        sys.exit(f"{stepper.library_path()} not built: run `cargo xtask fmu`")
    cases = dharahara_cases()
    names = list(cases) if args.cases == "all" else [c.strip() for c in args.cases.split(",")]
    unknown = [c for c in names if c not in cases]
    if unknown:
        sys.exit(f"unknown cases {unknown}; known: {', '.join(cases)}")
    record = gm.katnp_standin()
    print(f"load average at start: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; "
          f"{args.before} against {args.after}; CPU time, min of {args.repeat}\n")
    header = ["case", "steps", "before us/step", "after us/step", "ratio", "max |d theta/alpha|",
              "peak before", "peak after", "overturns before", "overturns after"]
    rows, total = [], {"before": 0.0, "after": 0.0}
    with RockingFMU(args.before) as before, RockingFMU(args.after) as after:
        for name in names:
            row, best = compare(before, after, name, cases[name], record, args.repeat)
            rows.append(row)
            for k in total:
                total[k] += best[k]
    table(header, rows)
    print(f"\nall {len(names)} cases: before {total['before']:.2f} s, after {total['after']:.2f} s CPU, "
          f"ratio {total['before'] / total['after']:.2f}; load average at end {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
