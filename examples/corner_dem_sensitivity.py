"""The DEM tilting test of the paper's corner under changes of its protocol and friction,
at one orientation and end condition (docs/corner-blocks.md, "Sensitivity"):

    .venv/bin/python examples/corner_dem_sensitivity.py [--out data/corner-blocks/sensitivity]
        [--alpha pi/2] [--ends fixed] [--workers 2]

and, with --numerics, the DEM's own numerics (time step, the contact solver's tolerance
and relaxation, hold, collapse criterion), one change at a time, on the 3 x 3 corner at
free ends pi/4 and fixed ends pi/2 (and with --paper on the paper's corner, fixed ends
pi/2), one case at a time in this process's order (run it under nice):

    nice -n 10 .venv/bin/python examples/corner_dem_sensitivity.py --numerics [--paper]
        [--out data/corner-blocks/numerics] [--only NAME,...]

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
from rocking.corner_blocks.study import dem_case, dem_start, lp_case, run_dem_jobs

#: (name, what changes, protocol fields, mu)
VARIANTS = [
    ("step0.02", "step 0.02", {"step": 0.02}, 0.66),
    ("collapse20mm", "collapse at 10 mm/s or 20 mm", {"collapse": 0.02, "v_tol": 0.01}, 0.66),
    ("mu0.50", "mu = 0.50", {}, 0.50),
    ("mu0.78", "mu = 0.78", {}, 0.78),
]


#: (name, what changes, protocol fields): the DEM's numerics, one change each from the base
#: (dt 1 ms, NLGS tol 1.666e-4 and relax 0.1, the wrapper's; hold 0.3 s; collapse at 1 mm/s or 5 mm)
NUMERICS = [
    ("base", "base", {}),
    ("dt0.5ms", "time step 0.5 ms", {"dt": 5e-4}),
    ("dt2ms", "time step 2 ms", {"dt": 2e-3}),
    ("dt0.25ms", "time step 0.25 ms", {"dt": 2.5e-4}),
    ("tol1e-5", "solver tol 1e-5", {"nlgs_tol": 1e-5}),
    ("tol1e-3", "solver tol 1e-3", {"nlgs_tol": 1e-3}),
    ("relax0.5", "solver relax 0.5", {"nlgs_relax": 0.5}),
    ("hold0.1", "hold 0.1 s", {"hold": 0.1}),
    ("hold1", "hold 1 s", {"hold": 1.0}),
    ("disp5mm", "collapse: 5 mm alone", {"v_tol": math.inf}),
    ("disp20mm", "collapse: 20 mm alone", {"v_tol": math.inf, "collapse": 0.02}),
    ("speed10", "collapse: 10 mm/s or 5 mm", {"v_tol": 1e-2}),
]

#: name -> (specimen fields, alpha, label, first level, size factor): the first level lies 6
#: steps of 0.01 below the study's DEM lambda_c of the case (docs/corner-blocks.md), to save
#: levels; the paper's case starts where the study's did, whose run is its base (STUDY_BASE)
NUMERICS_CASES = {
    "small_free_pi4": ({"ends": "free", "courses": 3, "blocks": 3}, math.pi / 4, "3 x 3, free, pi/4", 0.58, 8),
    "small_fixed_pi2": ({"ends": "fixed", "courses": 3, "blocks": 3}, math.pi / 2, "3 x 3, fixed, pi/2", 0.49, 8),
    "paper_fixed_pi2": ({"ends": "fixed"}, math.pi / 2, "paper, fixed, pi/2", 0.32, 16),
}


#: case -> the committed study's run of the same case and protocol, used as its base
STUDY_BASE = {"paper_fixed_pi2": "dem_fixed_mu0.66_4.json"}


def case_file(out, study, case, name):
    """The JSON of one numerics case: the study's own run for a base it already has."""
    path = Path(out) / f"{case}_{name}.json"
    if name == "base" and case in STUDY_BASE and not path.is_file():
        return Path(study) / STUDY_BASE[case]
    return path


def background(result):
    """(largest, median) speed (m/s) at the end of the levels that stood: the corner's
    background motion, which a rest threshold must sit above."""
    import statistics

    p = result["protocol"]
    speeds = [sp for lam, rested, sp, disp, _ in result["history"] if rested and disp <= p["collapse"]
              and lam < result["lam"] - 1e-9]
    return (max(speeds), statistics.median(speeds)) if speeds else (math.nan, math.nan)


def numerics(args):
    """Runs the missing numerics cases one at a time, then prints the table."""
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    cases = [c for c in NUMERICS_CASES if args.paper or not c.startswith("paper")]
    run_cases = set(args.cases.split(",")) if args.cases else set(cases)
    only = set(args.only.split(",")) if args.only else None
    for case in cases:
        fields, alpha, _label, start, factor = NUMERICS_CASES[case]
        for name, _what, change in NUMERICS:
            path = case_file(out, args.study, case, name)
            if path.is_file() or (only and name not in only) or case not in run_cases:
                continue
            protocol = replace(Protocol(step=0.01, start=start, size_factor=factor), **change)
            r = dem_case({"specimen": fields}, alpha, protocol)
            path.write_text(json.dumps(r))
            print(f"{case} {name}: lambda {r['lam']:.3f} ({r['cpu_s']:.0f} s CPU)", file=sys.stderr, flush=True)
    print("| case | change | DEM lambda_c | at 1 mm | largest / median speed at levels that stood (m/s) "
          "| v_tol / largest | displacement at the last level that stood (mm) | steps | CPU (s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for case in cases:
        for name, what, _ in NUMERICS:
            path = case_file(out, args.study, case, name)
            if not path.is_file():
                continue
            r = json.loads(path.read_text())
            top, median = background(r)
            v_tol = r["protocol"]["v_tol"]
            ratio = "-" if math.isinf(v_tol) or not top > 0 else f"{v_tol / top:.2g}"
            stood = [disp for lam, _, _, disp, _ in r["history"] if lam < r["lam"] - 1e-9]
            print(f"| {NUMERICS_CASES[case][2]} | {what} | {r['lam']:.2f} | {stricter(r, 0.001):.2f} | "
                  f"{top:.1e} / {median:.1e} | {ratio} | {stood[-1] * 1e3 if stood else math.nan:.2g} | {r['steps']} "
                  f"| {r['cpu_s']:.0f} |")
    return 0


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
    ap.add_argument("--numerics", action="store_true", help="the DEM's numerics on the 3 x 3 corner (NUMERICS)")
    ap.add_argument("--paper", action="store_true", help="with --numerics: also the paper's corner, fixed, pi/2")
    ap.add_argument("--only", help="with --numerics: these variants only (comma-separated names)")
    ap.add_argument("--cases", help="with --numerics: run these cases only (names of NUMERICS_CASES); the table "
                    "shows every case")
    args = ap.parse_args()
    if args.numerics:
        if args.out == "data/corner-blocks/sensitivity":
            args.out = "data/corner-blocks/numerics"
        return numerics(args)
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
