"""Wall and CPU time of the documented `rocking` commands, for the figures that README.md
and docs/examples.md quote: the README's sweep, the fragility IDA, one simulate run.

    .venv/bin/python benches/cli_timings.py [--only sweep,ida,simulate]

Each command runs once as a user would (a subprocess of .venv/bin/rocking, into a
temporary folder); the table gives its wall time, the CPU time of it and its children
(worker processes included), the runs it reports and the load average before it started
(on a shared machine the wall time follows the load; the CPU time much less).
"""

import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
ROCKING = str(Path(sys.executable).parent / "rocking")

COMMANDS = {
    "simulate": ["simulate", "data/ground-motions/katnp-standin/KATNP_NS_standin.csv",
                 "--preset", "dharahara-F170-fm5", "--scale", "1.5", "--out", "{out}/sim"],
    "sweep": ["sweep", "examples/sweep.toml", "--records", "data/ground-motions/usgs-lomaprieta-1989",
              "--scales", "0.5:3:0.25", "--out", "{out}/sweep.parquet"],
    "ida": ["ida", "examples/fragility.toml", "--out", "{out}/fragility-ida"],
}
#: How each command reports its runs (stderr or stdout): "88 runs in", "321 runs, 0 failed",
#: not the "23.78 runs/s" of a rate.
RUNS = re.compile(r"(?<![\d.])(\d+) runs(?!/s)")


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def measure(name, out):
    args = [a.format(out=out) for a in COMMANDS[name]]
    load = os.getloadavg()[0]
    cpu0, t0 = children_cpu(), time.perf_counter()
    proc = subprocess.run([ROCKING, *args], cwd=REPO, capture_output=True, text=True)
    wall, cpu = time.perf_counter() - t0, children_cpu() - cpu0
    if proc.returncode != 0:
        sys.exit(f"rocking {' '.join(args)}: exit {proc.returncode}\n{proc.stderr}")
    runs = RUNS.findall(proc.stderr + proc.stdout)
    return dict(command=f"rocking {name} {Path(args[1]).name} ...", wall=wall, cpu=cpu,
                runs=int(runs[-1]) if runs else 1, load=load)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", default=",".join(COMMANDS), help="commands, of " + ", ".join(COMMANDS))
    names = parser.parse_args().only.split(",")
    print(f"{os.cpu_count()} CPUs")
    print(f"| command | wall (s) | CPU (s) | runs | runs/s (wall) | load before |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as out:
        for name in names:
            r = measure(name, out)
            print(f"| `{r['command']}` | {r['wall']:.1f} | {r['cpu']:.1f} | {r['runs']} | "
                  f"{r['runs'] / r['wall']:.1f} | {r['load']:.1f} |", flush=True)


if __name__ == "__main__":
    main()
