"""`rocking corner-blocks lp|dem|draw|study`: the corner block by block
(docs/corner-blocks.md). `rocking corner` stays the macroblock analysis (the Rust binary)."""

import argparse
from dataclasses import fields
import json
import math
import sys
from pathlib import Path

from ..corner_blocks.lp import FACETS
from ..corner_blocks.specimen import Specimen
from .common import CLIError

SPECIMEN_DEFAULTS = {f.name: f.default for f in fields(Specimen)}


#: The specimen's options, named as the fields of corner_blocks.specimen.Specimen (and as
#: rocking-corner's, so that `rocking corner --method la|lp|dem --t ...` means one thing).
SPECIMEN_OPTIONS = ("t", "l", "h", "rho", "mu", "courses", "blocks", "ends", "closers", "clamp")


def _specimen_fields(args):
    """The Specimen's fields from the options; l > t checked here so that the error names both."""
    if not args.l > args.t:
        raise CLIError(f"invalid --l: the block length must exceed its thickness --t = {args.t:g} m, got {args.l:g} m")
    # closers and clamp only when set: the default clamp is inf, which JSON cannot carry
    return {name: getattr(args, name) for name in SPECIMEN_OPTIONS
            if name not in ("closers", "clamp") or getattr(args, name) != SPECIMEN_DEFAULTS[name]}


def _specimen(args):
    from ..corner_blocks.specimen import Specimen
    try:
        return Specimen(**_specimen_fields(args))
    except ValueError as e:  # the combinations argparse cannot see (--clamp without --ends outOfPlane)
        raise CLIError(str(e).replace("invalid ", "invalid --", 1)) from None


def _alphas(args):
    alphas = args.alpha if args.alpha is not None else [math.pi / 4, math.pi / 2]
    for a in alphas:
        if not 0.0 <= a <= math.pi / 2 + 1e-9:
            raise CLIError(f"invalid --alpha: must be in [0, pi/2] rad, got {a}")
    return alphas


def cmd_lp(args, _params):
    from ..corner_blocks import draw, lp
    from ..corner_blocks.assembly import Assembly
    a = Assembly.from_specimen(_specimen(args))
    rows = []
    for alpha in _alphas(args):
        r = lp.solve(a, alpha, facets=args.facets)
        labels = [a.blocks[i].label() for i in r.moving]
        rows.append({"alpha": alpha, "lambda": r.lam, "moving": labels, "power_dead": r.power_dead,
                     "facets": args.facets, "specimen": _specimen_fields(args)})
        print(f"alpha {alpha:.6f}  lambda {r.lam:.4f}  moving {len(labels)} blocks"
              + ("" if args.json else f": {' '.join(labels)}"))
        if args.plot:
            out = Path(args.plot)
            name = out.with_name(f"{out.stem}_{alpha:.4f}{out.suffix or '.png'}")
            draw.figure(a.blocks, name, draw.mechanism_corners(a.blocks, r.velocity, 0.04), r.moving,
                        title=f"LP, ends {args.ends}, alpha {alpha:.4f}", fixed=a.fixed)
            print(f"wrote {name}")
    if args.json:
        print(json.dumps(rows))
    return 0


def _protocol(args):
    from ..corner_blocks.dem import SIZE_FACTOR, Protocol, rest_speed
    v_tol = args.v_tol if args.v_tol is not None else rest_speed(args.courses, args.blocks)
    return Protocol(step=args.step, collapse=args.collapse, hold=args.hold, start=args.start,
                    lam_max=args.lam_max, size_factor=args.size_factor or SIZE_FACTOR, dt=args.dt,
                    v_tol=v_tol, nlgs_tol=args.nlgs_tol or 0.0, nlgs_relax=args.nlgs_relax or 0.0)


def cmd_dem(args, _params):
    from ..corner_blocks import dem, draw
    from ..corner_blocks.assembly import Assembly
    fields = _specimen_fields(args)
    spec = {"specimen": fields}
    a = Assembly.from_specimen(_specimen(args))
    if a.clamp != math.inf:
        raise CLIError("invalid --clamp: the DEM has no bounded restraint (the wrapper drives a velocity or a "
                       "force, no spring); `corner-blocks lp` takes it")
    rows = []
    for alpha in _alphas(args):
        r = dem.run_isolated(spec, alpha, _protocol(args))
        labels = [a.blocks[i].label() for i in r["moving"]]
        for lam, rested, speed, disp, steps in r["history"]:
            print(f"  lambda {lam:.4f}  {'stands    ' if rested and disp <= r['protocol']['collapse'] else 'collapses'}"
                  f"  speed {speed:.2e} m/s  displacement {disp * 1e3:.3f} mm  (step {steps})")
        shown = f"lambda {r['lam']:.4f}" if r["collapsed"] else f"no collapse up to {args.lam_max:g}"
        print(f"alpha {alpha:.6f}  {shown}  ({r['steps']} steps, {r['cpu_s']:.1f} s CPU)  "
              f"moving {len(labels)} blocks" + ("" if args.json else f": {' '.join(labels)}"))
        rows.append({"alpha": alpha, "lambda": r["lam"] if r["collapsed"] else None, "collapsed": r["collapsed"],
                     "moving": labels, "steps": r["steps"], "cpu_s": r["cpu_s"],
                     "history": [dict(zip(HISTORY, level)) for level in r["history"]],
                     "protocol": r["protocol"], "specimen": fields})
        if args.plot:
            import numpy as np
            out = Path(args.plot)
            name = out.with_name(f"{out.stem}_{alpha:.4f}{out.suffix or '.png'}")
            draw.figure(a.blocks, name, [np.array(c) for c in r["corners"]], r["moving"],
                        title=f"DEM, ends {args.ends}, alpha {alpha:.4f}", fixed=a.fixed)
            print(f"wrote {name}")
    if args.json:
        print(json.dumps(rows))
    return 0


#: The keys of a DEM level in `dem --json` (the tuple of dem.run's history): the level's
#: lambda; it stood (the fastest corner below v_tol at the end of its hold); that speed
#: (m/s); the largest block displacement since settling (m); time steps run so far.
HISTORY = ("lambda", "rested", "speed", "displacement", "steps")


def cmd_draw(args, _params):
    from ..corner_blocks import draw
    s = _specimen(args)
    draw.figure(s.layout(), args.out, title=f"{s.courses} courses, {s.blocks} blocks per wall, ends {s.ends}",
                fixed=[s.fixed(b) for b in s.layout()])
    print(f"wrote {args.out}")
    return 0


def cmd_study(args, _params):
    from ..corner_blocks import study
    from .corner import corner_binary
    if args.alpha is not None:
        raise CLIError("invalid --alpha: the study runs the paper's five orientations, pi/4 to pi/2; "
                       "`rocking corner-blocks lp|dem --alpha` runs others")
    methods = tuple(args.methods.split(","))
    for m in methods:
        if m not in ("lp", "dem"):
            raise CLIError(f"invalid --methods: lp and/or dem, got {m}")
    ends = tuple(args.study_ends.split(","))
    if args.start_fraction is not None and not 0.0 < args.start_fraction < 1.0:
        raise CLIError(f"invalid --start-fraction: must be in (0, 1), got {args.start_fraction}")
    if args.workers < 1:
        raise CLIError(f"invalid --workers: must be at least 1, got {args.workers}")
    for name in ("t", "l", "h", "rho", "closers", "clamp"):  # study.run lays out the paper's blocks only
        if getattr(args, name) != SPECIMEN_DEFAULTS[name]:
            raise CLIError(f"invalid --{name}: the study runs the paper's blocks (--{name} "
                           f"{SPECIMEN_DEFAULTS[name]}); `rocking corner-blocks lp|dem --{name}` or "
                           "`corner-blocks boundaries` runs others")
    study.run(args.out, ends=ends, mu=args.mu, methods=methods, binary=corner_binary(),
              dem_protocol=_protocol(args), log=lambda s: print(s, file=sys.stderr, flush=True),
              courses=args.courses, blocks=args.blocks, start_fraction=args.start_fraction, workers=args.workers,
              table_only=args.table_only)
    print(Path(args.out, "table.md").read_text())
    return 0


def cmd_boundaries(args, _params):
    from ..corner_blocks import study
    methods = tuple(args.methods.split(","))
    for m in methods:
        if m not in ("lp", "nonassoc", "dem"):
            raise CLIError(f"invalid --methods: lp, nonassoc and/or dem, got {m}")
    keys = tuple(args.boundaries.split(",")) if args.boundaries else None
    for k in keys or ():
        if k not in study.BOUNDARIES:
            raise CLIError(f"invalid --boundaries: each one of {', '.join(study.BOUNDARIES)}, got {k}")
    study.run_boundaries(args.out, methods=methods, keys=keys, study=args.study, nonassoc_iter=args.max_iter,
                         log=lambda s: print(s, file=sys.stderr, flush=True), courses=args.courses,
                         blocks=args.blocks, table_only=args.table_only)
    suffix = "" if (args.courses, args.blocks) == (9, 7) else f"_{args.courses}x{args.blocks}"
    print(Path(args.out, f"table{suffix}.md").read_text())
    return 0


def register(sub, common):
    p = sub.add_parser("corner-blocks", parents=[common],
                       help="the corner block by block: block limit analysis (LP), DEM tilting test, drawings")
    acts = p.add_subparsers(dest="action", metavar="ACTION", required=True)
    spec = _specimen_parser()
    lp = acts.add_parser("lp", parents=[common, spec], help="the block LP's multiplier and mechanism")
    lp.add_argument("--facets", type=_at_least(3), default=FACETS,
                    help=f"planes of the friction pyramid, circumscribed about the cone (default {FACETS}; "
                         "docs/corner-blocks.md section 2)")
    lp.add_argument("--json", action="store_true")
    lp.add_argument("--plot", help="PNG of the mechanism, one per alpha (suffixed)")
    lp.set_defaults(func=cmd_lp)
    dem = acts.add_parser("dem", parents=[common, spec, _protocol_parser()], help="the LMGC90 tilting test")
    dem.add_argument("--json", action="store_true", help="after the text, one line of JSON: per alpha, "
                     "lambda_c and every level's history (lambda, rested, speed m/s, displacement m, steps)")
    dem.add_argument("--plot", help="PNG of the blocks after collapse, one per alpha (suffixed)")
    dem.set_defaults(func=cmd_dem)
    dr = acts.add_parser("draw", parents=[common, spec], help="a PNG of the specimen")
    dr.add_argument("--out", required=True)
    dr.set_defaults(func=cmd_draw)
    st = acts.add_parser("study", parents=[common, spec, _protocol_parser()],
                         help="the five orientations beside the paper's tables (cached, resumable)")
    st.add_argument("--out", required=True, help="directory: one JSON per case, table.md, PNGs")
    st.add_argument("--methods", default="lp", help="lp,dem (default lp)")
    st.add_argument("--study-ends", default="fixed,free,outOfPlane")
    st.add_argument("--start-fraction", type=float, default=None,
                    help="DEM: start each test at this fraction of the case's LP multiplier (its upper bound), "
                         "instead of --start; a test that collapses at its first level is redone from half of it")
    st.add_argument("--workers", type=int, default=1, help="DEM cases at once, on a Dask LocalCluster (default 1)")
    st.add_argument("--table-only", action="store_true",
                    help="compute no DEM case: the table and plot of those already in --out, the others as -")
    st.set_defaults(func=cmd_study)
    bd = acts.add_parser("boundaries", parents=[common],
                         help="the paper's corner with each end boundary at pi/4 and pi/2 (cached, resumable)")
    bd.add_argument("--out", required=True, help="directory: one JSON per case, table.md, table.json")
    bd.add_argument("--methods", default="lp", help="lp,nonassoc,dem (default lp)")
    bd.add_argument("--boundaries", default=None, help="comma-separated keys of study.BOUNDARIES (default all)")
    bd.add_argument("--study", default="data/corner-blocks",
                    help="the study's folder, whose DEM cases of fixed, free and outOfPlane ends are read, not rerun")
    bd.add_argument("--max-iter", type=int, default=40, help="non-associative iterations (default 40)")
    bd.add_argument("--courses", type=_at_least(2), default=9, help="courses (default 9, the paper's)")
    bd.add_argument("--table-only", action="store_true",
                    help="compute no non-associative or DEM case: the table of those already cached, the others as -")
    bd.add_argument("--blocks", type=_at_least(2), default=7, help="full blocks per wall (default 7, the paper's)")
    bd.set_defaults(func=cmd_boundaries)


def _specimen_parser():
    from ..corner_blocks.specimen import CLOSERS, ENDS
    d = SPECIMEN_DEFAULTS
    p = argparse_parent()
    p.add_argument("--alpha", type=float, nargs="+", default=None,
                   help="load orientations (rad), docs/corner.md's convention (default pi/4 pi/2)")
    p.add_argument("--ends", choices=ENDS, default="fixed", help="the walls' free ends (default fixed)")
    p.add_argument("--closers", choices=CLOSERS, default="held",
                   help="the closing pieces (the butting courses' end blocks): as the other ends, or free "
                        "(default held)")
    p.add_argument("--clamp", type=_non_negative("block weights"), default=math.inf,
                   help="LP, --ends outOfPlane: the largest out-of-plane reaction of an end block, in units of its "
                        "weight (default inf: a rigid roller)")
    p.add_argument("--t", type=_positive("m"), default=d["t"],
                   help=f"block thickness = wall thickness, m (default {d['t']:g})")
    p.add_argument("--l", type=_positive("m"), default=d["l"], help=f"block length, m (default {d['l']:g})")
    p.add_argument("--h", type=_positive("m"), default=d["h"], help=f"block height, m (default {d['h']:g})")
    p.add_argument("--rho", type=_positive("kg/m3"), default=d["rho"], help=f"density, kg/m3 (default {d['rho']:g})")
    p.add_argument("--mu", type=_positive(""), default=d["mu"], help=f"joint friction (default {d['mu']:g})")
    p.add_argument("--courses", type=_at_least(2), default=d["courses"], help=f"courses (default {d['courses']})")
    p.add_argument("--blocks", type=_at_least(2), default=d["blocks"],
                   help=f"full blocks per wall (default {d['blocks']})")
    return p


def _positive(unit, infinite=False):
    """An argparse type: a finite number > 0 (or inf, if infinite); argparse names the option in the error."""
    def convert(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r}: not a number") from None
        if not ((math.isfinite(value) or (infinite and value == math.inf)) and value > 0):
            where = f" ({unit})" if unit else ""
            raise argparse.ArgumentTypeError(f"{text!r}: must be positive and finite{where}")
        return value
    convert.__name__ = "positive"
    return convert


def _non_negative(unit):
    """An argparse type: a number >= 0 (inf allowed)."""
    def convert(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r}: not a number") from None
        if not value >= 0:
            raise argparse.ArgumentTypeError(f"{text!r}: must be >= 0 ({unit})")
        return value
    convert.__name__ = "non-negative"
    return convert


def _at_least(least):
    """An argparse type: an integer >= least."""
    def convert(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r}: not an integer") from None
        if value < least:
            raise argparse.ArgumentTypeError(f"{text!r}: must be at least {least}")
        return value
    convert.__name__ = "integer"
    return convert


def _protocol_parser():
    p = argparse_parent()
    p.add_argument("--step", type=float, default=0.005, help="DEM: lambda step (default 0.005)")
    p.add_argument("--collapse", type=float, default=0.005, help="DEM: collapse displacement, m (default 0.005)")
    p.add_argument("--hold", type=float, default=0.3, help="DEM: seconds per load level (default 0.3)")
    p.add_argument("--start", type=float, default=0.0, help="DEM: first lambda (default 0)")
    p.add_argument("--lam-max", type=float, default=1.5, help="DEM: last lambda (default 1.5)")
    p.add_argument("--size-factor", type=int, default=0, help="DEM: the engine's contact room (default 16; 8 for the 3 x 3 corner)")
    p.add_argument("--dt", type=_positive("s"), default=1e-3, help="DEM: time step, s (default 0.001)")
    p.add_argument("--v-tol", type=_positive("m/s", infinite=True), default=None,
                   help="DEM: rest speed, m/s; inf: collapse by the displacement alone (default 0.01 for the "
                        "paper's corner of 9 courses x 7 blocks or larger, 0.001 for smaller ones)")
    p.add_argument("--nlgs-tol", type=_positive(""), default=None,
                   help="DEM: the contact solver's tolerance (default the wrapper's, 1.666e-4)")
    p.add_argument("--nlgs-relax", type=_positive(""), default=None,
                   help="DEM: the contact solver's relaxation (default the wrapper's, 0.1)")
    return p


def argparse_parent():
    from .common import _Parser
    return _Parser(add_help=False)
