#!/usr/bin/env python3
"""The main job run again with nothing changed (warm): tools/main.sh and each of its steps.

    .venv/bin/python benches/main_warm.py [--runs 5] [--force]

Runs tools/main.sh once (to build and write whatever is missing or stale), then
each step of it --runs times and the whole job --runs times, and prints wall and
CPU seconds (user + system of the step's processes) as min / median / max.
--force also times the steps that write their outputs again although nothing
changed (`cargo xtask fmu --force`, `examples/dharahara.py --force`): what a
changed input costs, without the builds it would start.

A warm run is meant to find everything up to date: `cargo xtask fmu` leaves an
archive whose entries and writer did not change as it is, and
examples/dharahara.py replays its log when its inputs and outputs did not
change. The load average is printed: on a shared machine the wall clock says
more about the neighbours than the CPU time does.
"""

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

STEPS = [
    ("tools/venv.sh", ["tools/venv.sh"]),
    ("tools/cross-deps.sh", ["tools/cross-deps.sh"]),
    ("cargo xtask fmu", ["cargo", "xtask", "fmu"]),
    ("cargo build --release -p corner", ["cargo", "build", "--release", "-p", "corner"]),
    ("examples/dharahara.py", [".venv/bin/python", "examples/dharahara.py"]),
]
FORCED = [
    ("cargo xtask fmu --force", ["cargo", "xtask", "fmu", "--force"]),
    ("examples/dharahara.py --force", [".venv/bin/python", "examples/dharahara.py", "--force"]),
]
WHOLE = ("tools/main.sh (whole)", ["tools/main.sh"])


def timed(cmd):
    """(wall s, CPU s, what it printed) of one run of `cmd` and its children."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run(cmd, cwd=REPO, check=True, capture_output=True, text=True).stdout
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), out


def up_to_date(name, out):
    """Whether a run found its outputs up to date, by what it printed (None: the step does not say).
    Another process changing the sources meanwhile (a shared work tree) makes a run do the work."""
    checks = []
    if "xtask" in name or "main.sh" in name:
        checks.append(out.count(", unchanged)") == 4)  # the four archives
    if "dharahara" in name or "main.sh" in name:
        checks.append("(unchanged:" in out)
    return all(checks) if checks else None


def spread(xs):
    return f"{min(xs):6.2f} {statistics.median(xs):6.2f} {max(xs):6.2f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5, help="timed runs of each step and of the whole job (default 5)")
    ap.add_argument("--force", action="store_true", help="also the steps made to write their outputs again")
    args = ap.parse_args()
    print(f"warming up: tools/main.sh once ({os.cpu_count()} CPUs, load average "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())})", flush=True)
    subprocess.run(["tools/main.sh"], cwd=REPO, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rows = []
    for name, cmd in STEPS + (FORCED if args.force else []) + [WHOLE]:
        runs = [timed(cmd) for _ in range(args.runs)]
        fresh = [up_to_date(name, out) for _, _, out in runs]
        said = "" if fresh[0] is None else f"{sum(fresh)}/{len(fresh)}"
        rows.append((name, [w for w, _, _ in runs], [c for _, c, _ in runs], said))
    width = max(len(r[0]) for r in rows)
    print(f"\n{'step (warm, ' + str(args.runs) + ' runs)':{width}}  {'wall s min/med/max':>20}  "
          f"{'CPU s min/med/max':>20}  up to date")
    for name, wall, cpu, said in rows:
        print(f"{name:{width}}  {spread(wall):>20}  {spread(cpu):>20}  {said}")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    sys.exit(main())
