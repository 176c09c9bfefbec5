"""The DEM tilting test of the paper's corner under changes of its protocol and friction,
at one orientation and end condition (docs/corner-blocks.md, "Sensitivity"):

    .venv/bin/python examples/corner_dem_sensitivity.py [--out data/corner-blocks/sensitivity]
        [--alpha pi/2] [--ends fixed] [--workers 2]

The base is the study's own case; each variant changes one thing of its protocol (step 0.01 from 0.6 x the LP
bound, hold 0.3 s, collapse at 1 mm/s or 5 mm, mu = 0.66). Cases are cached as JSON in
--out (a rerun resumes), run on a Dask LocalCluster, and the table is printed as
Markdown. A stricter collapse criterion needs no run: the base case's level history
gives it (the first level whose largest displacement passed 1 mm)."""

import argparse
import json
import math
import sys
from dataclasses import replace
from pathlib import Path

from rocking.corner_blocks.dem import Protocol
from rocking.corner_blocks.specimen import ORIENTATIONS, Specimen
from rocking.corner_blocks.study import dem_start, lp_case, run_dem_jobs

#: (name, what changes, protocol fields, mu)
VARIANTS = [
    ("step0.02", "step 0.02", {"step": 0.02}, 0.66),
    ("collapse20mm", "collapse at 10 mm/s or 20 mm", {"collapse": 0.02, "v_tol": 0.01}, 0.66),
    ("mu0.50", "mu = 0.50", {}, 0.50),
    ("mu0.78", "mu = 0.78", {}, 0.78),
]


def stricter(result, displacement):
    """The last level standing had collapse been a displacement above `displacement` (m):
    from the level history (lambda, rested, speed, largest displacement, steps)."""
    for lam, rested, _speed, disp, _steps in result["history"]:
        if not rested or disp > displacement:
            return lam
    return math.nan


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--study", default="data/corner-blocks",
                    help="the study's folder, whose case at --alpha and --ends is the base (rocking corner-blocks study)")
    ap.add_argument("--out", default="data/corner-blocks/sensitivity")
    ap.add_argument("--alpha", default="pi/2", choices=[lab for _, lab in ORIENTATIONS])
    ap.add_argument("--ends", default="fixed", choices=["fixed", "free"])
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    alpha = dict((lab, a) for a, lab in ORIENTATIONS)[args.alpha]
    index = [lab for _, lab in ORIENTATIONS].index(args.alpha)
    base_file = Path(args.study) / f"dem_{args.ends}_mu0.66_{index}.json"
    if not base_file.is_file():
        sys.exit(f"{base_file}: not found; run `rocking corner-blocks study --methods lp,dem "
                 "--start-fraction 0.6 --step 0.01` first")
    jobs, lp_bound = {}, {}
    results = {"base": json.loads(base_file.read_text())}
    for name, _, fields, mu in VARIANTS:
        path = out / f"{args.ends}_{args.alpha.replace('/', '')}_{name}.json"
        if path.is_file():
            results[name] = json.loads(path.read_text())
            continue
        if mu not in lp_bound:
            lp_bound[mu] = lp_case(Specimen(ends=args.ends, mu=mu), alpha)["lam"]
        lam_lp = lp_bound[mu]
        protocol = replace(Protocol(step=0.01), **fields)
        protocol = replace(protocol, start=dem_start(protocol, lam_lp, 0.6))
        jobs[path.name] = (args.ends, 0, {"specimen": {"ends": args.ends, "mu": mu}}, protocol)
    names = {f"{args.ends}_{args.alpha.replace('/', '')}_{n}.json": n for n, *_ in VARIANTS}
    for file, _job, r, seconds in run_dem_jobs(jobs, [alpha], args.workers):
        (out / file).write_text(json.dumps(r))
        results[names[file]] = r
        print(f"{names[file]}: lambda {r['lam']:.3f} ({r['cpu_s']:.0f} s CPU, {seconds:.0f} s)", file=sys.stderr)
    print(f"| ends {args.ends}, alpha {args.alpha} | DEM lambda_c | blocks moving | steps | CPU (s) |")
    print("|---|---|---|---|---|")
    for name, what, _, _ in [("base", "the study's protocol", None, None)] + VARIANTS:
        r = results[name]
        print(f"| {what} | {r['lam']:.3f} | {len(r['moving'])} | {r['steps']} | {r['cpu_s']:.0f} |")
    base = results["base"]
    print(f"| collapse at 1 mm (from the base case's history) | {stricter(base, 0.001):.3f} | - | - | - |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
