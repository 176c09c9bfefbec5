"""`rocking space`: a round body in space under both horizontal components of a record and its
vertical, through RoundBody.fmu (docs/model.md §10) -> time history CSV, summary JSON, plot;
with --compare, the planar runs (RockingBlock.fmu) along x, y and the worst of an azimuth sweep."""

import argparse
import math
import sys
import textwrap
from pathlib import Path

from .. import jsonfile
from ..fmu import FMUError
from .common import CLIError, add_record_options, check_parameter, read_params_file, seconds

#: This subcommand also takes any RoundBody.fmu parameter as `--NAME VALUE`.
TAKES_PARAMETERS = True

#: RockingBlock parameters a preset may carry that RoundBody.fmu does not have (the bed's interface,
#: kn, fm and formulation it takes with the same names and meanings).
PLANAR_ONLY = ("B", "L", "t", "theta", "omega", "restraint", "side", "eRestraint")


def round_fmu_path(arg):
    from ..round_body import RoundBodyFMU
    if arg:
        path = Path(arg)
        if not path.is_file():
            raise CLIError(f"{path}: no such FMU file")
        return path
    path = RoundBodyFMU.default_path()
    if path is None or not path.is_file():
        raise CLIError(f"{path}: RoundBody.fmu not built: `cargo xtask fmu` (or give --fmu PATH)")
    return path


def gather(fmu, args, params_given):
    """(RoundBody start values, notes): the preset's (its planar-only names left out), under
    --params FILE's, under --NAME VALUE; a lumped body without
    IcAxial gets its cylinder's m (Ro² + Ri²)/2 (Ri = 0 for a solid circle), noted."""
    from .. import presets as presets_module
    params, notes = {}, []
    if args.preset:
        try:
            values = presets_module.preset(args.preset)
        except KeyError as exc:
            raise CLIError(f"--preset: {exc.args[0]}") from None
        dropped = sorted(n for n in values if n in PLANAR_ONLY)
        if dropped:
            notes.append(f"preset {args.preset}: {', '.join(dropped)} left out (planar only)")
        for name, value in values.items():
            if name not in PLANAR_ONLY:
                params[name] = check_parameter(fmu, name, value, f"preset {args.preset}: {name}")
    if args.params:
        for name, value in read_params_file(args.params).items():
            params[name] = check_parameter(fmu, name, value, f"{args.params}: {name}")
    for name, value in params_given:
        params[name] = check_parameter(fmu, name, value, f"--{name}")
    if params.get("massModel") == "lumped" and "IcAxial" not in params:
        w, g = float(params.get("W", 1e5)), float(params.get("g", 9.81))
        ro = float(params.get("Ro", 0.5))
        ri = float(params.get("Ri", 0.3)) if params.get("shape") == "hollowCircle" else 0.0
        params["IcAxial"] = w / g * (ro * ro + ri * ri) / 2.0
        notes.append(f"IcAxial not given: the cylinder's m (Ro^2 + Ri^2)/2 = {params['IcAxial']:.6g} kg m2")
    return params, notes


def planar_params(rocking_fmu, params):
    """The same body on the same bed for RockingBlock.fmu: RoundBody's interface starts at rigid,
    RockingBlock's does not."""
    out = {n: v for n, v in params.items() if n in rocking_fmu.variables and rocking_fmu.variables[n].causality
           == "parameter"}
    out.setdefault("interface", "rigid")
    return out


def read_pair(args):
    from .. import groundmotion as gm
    path = Path(args.record)
    if not path.exists():
        raise CLIError(f"{path}: no such record file")
    try:
        return gm.pair_of(path, units=args.units, fmt=args.fmt)
    except (ValueError, gm.GroundMotionFormatError) as exc:
        raise CLIError(str(exc).splitlines()[0]) from None


def sweep_planar(rocking_fmu, params, pair, args, stop_time):
    """Planar runs along 0, step, 2 step, ... < 180 degrees (each with the vertical unless
    --no-vertical): [(azimuth, Run)], and the worst (the earliest overturning, else the
    largest peak)."""
    from tqdm import tqdm
    runs = []
    step = args.sweep
    azimuths = [k * step for k in range(int(math.ceil(180.0 / step - 1e-9)))]
    with_v = pair.vertical is not None and not args.no_vertical
    for az in tqdm(azimuths, unit="run", desc="planar azimuths", file=sys.stderr, dynamic_ncols=True,
                   mininterval=0.5):
        rec = pair.along(args.azimuth + az, with_vertical=with_v)
        run = rocking_fmu.simulate(planar_params(rocking_fmu, params), record=rec, scale=args.scale,
                                   stop_time=stop_time, rtol=args.rtol, vertical=rec.av_record if with_v else None)
        runs.append((az, run))
    worst = min(runs, key=lambda r: (r[1].t_overturn if r[1].overturned else math.inf,
                                     -r[1].peak_theta_over_alpha))
    return runs, worst


def summary_of_planar(az, run):
    return {"azimuth_deg": az, "peak_theta_over_alpha": run.peak_theta_over_alpha, "overturned": run.overturned,
            "t_overturn_s": None if not run.overturned else run.t_overturn, "impacts": run.impacts,
            "zero_crossings": run.zero_crossings, "terminal": run.terminal}


def cmd_space(args, params_given):
    import numpy as np
    import pandas as pd

    from ..round_body import RoundBodyFMU

    out = Path(args.out)
    pair = read_pair(args)
    stop_time = args.stop_time if args.tail is None else pair.npts * pair.dt + args.tail
    with RoundBodyFMU(round_fmu_path(args.fmu)) as fmu:
        params, notes = gather(fmu, args, params_given)
        for note in notes:
            print(f"rocking space: note: {note}", file=sys.stderr)
        try:
            run = fmu.simulate(params, pair=pair, scale=args.scale, azimuth=args.azimuth,
                               vertical=not args.no_vertical, stop_time=stop_time,
                               output_interval=args.output_interval, rtol=args.rtol)
        except FMUError as exc:
            raise CLIError(str(exc)) from None
        guid = fmu.model_description.guid
    compare = None
    if args.compare:
        from ..fmu import RockingFMU
        from .common import fmu_path
        with RockingFMU(fmu_path(args.planar_fmu)) as rfmu:
            sweep, (worst_az, worst) = sweep_planar(rfmu, params, pair, args, stop_time)
            along = dict(sweep)
            # x and y of the turned pair: azimuth 0 and 90 of the sweep when it has them
            for az in (0.0, 90.0):
                if az not in along:
                    rec = pair.along(args.azimuth + az, with_vertical=pair.vertical is not None and not args.no_vertical)
                    along[az] = rfmu.simulate(planar_params(rfmu, params), record=rec, scale=args.scale,
                                              stop_time=stop_time, rtol=args.rtol,
                                              vertical=rec.av_record if not args.no_vertical else None)
        compare = {"x": along[0.0], "y": along[90.0], "worst": worst, "worst_azimuth": worst_az, "sweep": sweep}

    out.mkdir(parents=True, exist_ok=True)
    res = run.result
    pd.DataFrame({n: res[n] for n in res.dtype.names}).to_csv(out / "timehistory.csv", index=False)
    alpha = run.calculated["alpha"]
    k = int(np.argmax(res["thetaOverAlpha"]))
    summary = {
        "record": {"name": pair.name, "x": pair.x.component, "y": pair.y.component, "bearing_x_deg": pair.bearing_x,
                   "vertical": None if pair.vertical is None or args.no_vertical else pair.vertical.component,
                   "notes": pair.notes},
        "azimuth_deg": args.azimuth, "bearing_of_agx_deg": pair.bearing_of(args.azimuth), "scale": args.scale,
        "peak_theta_over_alpha": run.peak_theta_over_alpha, "t_peak_s": float(res["time"][k]),
        "psi_at_peak_deg": math.degrees(float(res["psi"][k])),
        "overturned": run.overturned, "t_overturn_s": None if not run.overturned else run.t_overturn,
        "impacts": run.impacts, "terminal": run.terminal, "t_end_s": run.t_end,
        "peak_friction_demand": float(np.max(res["frictionDemand"])) if "frictionDemand" in res.dtype.names else None,
        "calculated": run.calculated, "parameters": params, "fmu_guid": guid, "notes": notes,
    }
    if compare is not None:
        summary["planar"] = {"x": summary_of_planar(0.0, compare["x"]), "y": summary_of_planar(90.0, compare["y"]),
                             "worst": summary_of_planar(compare["worst_azimuth"], compare["worst"]),
                             "sweep": [summary_of_planar(az, r) for az, r in compare["sweep"]]}
    jsonfile.write(out / "summary.json", summary)
    # on a flexible bed the body in space counts as impacts every application of the restitution
    # rule (docs/model.md §11.3), which RockingBlock counts as zeroCrossings
    flexible = params.get("interface", "rigid") not in ("rigid", 0)
    plot_space(out / "plot.png", run, compare, alpha, pair, args, flexible)
    word = f"overturns at {run.t_overturn:.3f} s" if run.overturned else (
        run.terminal or f"stands, peak theta/alpha {run.peak_theta_over_alpha:.3f}")
    counted = "crossings" if flexible else "impacts"
    print(f"in space: {word}, {run.impacts} {counted} ({out})")
    if compare is not None:
        for label in ("x", "y", "worst"):
            r = compare[label]
            at = f" ({compare['worst_azimuth']:g} deg)" if label == "worst" else ""
            w = f"overturns at {r.t_overturn:.3f} s" if r.overturned else f"peak {r.peak_theta_over_alpha:.3f}"
            print(f"planar along {label}{at}: {w}, {r.zero_crossings if flexible else r.impacts} {counted}")
    return 0


def planar_top(run, flexible):
    """The top's horizontal displacement (at 2 hG up the axis, m) of a planar run of
    RockingBlock.fmu at its outputs: G's, xG, plus hG sin(theta). On the rigid bed the body turns
    about its toe, xG = s b (1 - cos theta) + hG sin(theta) (b = R0 sin(alpha)); on a flexible one
    about the resultant, af from the toe, so xG' = hg(phi) omega with hg = R0 cos(alpha - phi) -
    af sin(phi) (docs/model.md §3, "Support forces"), integrated in theta by trapezoids from
    upright over the output samples (hG at theta = 0)."""
    import numpy as np

    res = run.result
    r0, alpha = run.calculated["R0"], run.calculated["alpha"]
    hg, th = r0 * math.cos(alpha), res["theta"]
    if not flexible:
        return r0 * math.sin(alpha) * np.sign(th) * (1 - np.cos(th)) + 2 * hg * np.sin(th)
    phi = np.abs(th)
    lever = np.concatenate([[hg], r0 * np.cos(alpha - phi) - res["af"] * np.sin(phi)])
    xg = np.cumsum(0.5 * (lever[1:] + lever[:-1]) * np.diff(th, prepend=0.0))
    return xg + hg * np.sin(th)


def plot_space(path, run, compare, alpha, pair, args, flexible=False):
    """The path of the top (at 2 hG up the axis) in plan and theta/alpha against time, with
    the planar runs when compared (on the same bed: `flexible` if not rigid)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    res = run.result
    hg = run.calculated["R0"] * math.cos(alpha)
    fig, (plan, tilt) = plt.subplots(1, 2, figsize=(11, 4.4), gridspec_kw={"width_ratios": [1, 1.6]})
    if compare is not None:
        for label, style in (("x", "C1-"), ("y", "C2-"), ("worst", "C3-")):
            r = compare[label].result
            az = math.radians(args.azimuth + (0.0 if label == "x" else 90.0 if label == "y" else compare["worst_azimuth"]))
            lean = planar_top(compare[label], flexible)
            name = f"planar {label}" + (f" ({compare['worst_azimuth']:g} deg)" if label == "worst" else "")
            # in the turned frame of the run in space: the azimuth from its x
            rel = az - math.radians(args.azimuth)
            plan.plot(lean * math.cos(rel), lean * math.sin(rel), style, lw=0.7, label=name)
            tilt.plot(r["time"], np.abs(r["thetaOverAlpha"]), style, lw=0.7, label=name)
    plan.plot(res["xG"] + hg * res["ex"], res["yG"] + hg * res["ey"], "k-", lw=0.9, label="in space")
    tilt.plot(res["time"], res["thetaOverAlpha"], "k-", lw=0.9, label="in space")
    plan.set_aspect("equal")
    bearing = pair.bearing_of(args.azimuth)
    plan.set_xlabel("top along agx (m)" + ("" if bearing is None else f", bearing {bearing:g} deg"))
    plan.set_ylabel("top along agy (m)")
    plan.set_title("path of the top in plan")
    tilt.set_xlabel("t (s)")
    tilt.set_ylabel("theta / alpha")
    tilt.set_title(f"{pair.name} x{args.scale:g}, azimuth {args.azimuth:g} deg")
    for ax in (plan, tilt):
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def register(sub, common):
    p = sub.add_parser(
        "space", parents=[common], allow_abbrev=False,
        help="a round body in space under both horizontal components (RoundBody.fmu)",
        usage="rocking space RECORD [--scale S] [--azimuth DEG] [--no-vertical] [--units U] [--fmt F]\n"
              "                     [--preset NAME] [--params FILE] [--PARAM VALUE ...] [--fmu PATH]\n"
              "                     [--stop-time S | --tail S] [--output-interval S] [--rtol R]\n"
              "                     [--compare [--sweep DEG] [--planar-fmu PATH]] --out DIR",
        description=textwrap.fill(
            "Run a round body (solidCircle or hollowCircle) in space on the rigid, elastic or crushing bed "
            "(interface, kn, fm, formulation as RockingBlock's) under both horizontal components of RECORD's set "
            "and its vertical, through RoundBody.fmu (docs/model.md §10, §11), and write "
            "DIR/timehistory.csv (time, agx, agy, av and the outputs), DIR/summary.json and DIR/plot.png (the "
            "path of the top in plan, the tilt against time). agx is the component along --azimuth (degrees "
            "from the set's x toward its y), agy the one 90 degrees counterclockwise of it. --compare adds "
            "planar runs through RockingBlock.fmu along x, y and every --sweep degrees, and the worst of them. "
            "Any RoundBody.fmu parameter can be given by name (--Ro 3.99 --theta0 0.05 --psi0 1.2).", 100),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("record", metavar="RECORD", help="a record file of a set with two horizontal components")
    p.add_argument("--scale", type=float, default=1.0, help="factor on every component (default 1)")
    p.add_argument("--azimuth", type=float, default=0.0, help="degrees from the set's x toward its y (default 0)")
    p.add_argument("--no-vertical", action="store_true", help="leave out the set's vertical component")
    add_record_options(p)
    p.add_argument("--preset", metavar="NAME", help="a parameter set of `rocking info --presets` (its "
                   "planar-only names are left out)")
    p.add_argument("--params", metavar="FILE", help="parameters from a JSON object of name -> value")
    p.add_argument("--fmu", metavar="PATH", help="RoundBody.fmu (default: the one an installed wheel carries; "
                   "in a clone target/fmu/RoundBody.fmu, written by `cargo xtask fmu`)")
    p.add_argument("--planar-fmu", metavar="PATH", help="RockingBlock.fmu for --compare (default as simulate's)")
    p.add_argument("--stop-time", type=seconds(0, strict=False), metavar="S", help="default: the record's end")
    p.add_argument("--tail", type=seconds(0, strict=False), metavar="S", help="run S seconds past the record")
    p.add_argument("--output-interval", type=seconds(0, strict=True), metavar="S")
    p.add_argument("--rtol", type=float, help="the integrator's relative tolerance (default the FMU's, 1e-9)")
    p.add_argument("--compare", action="store_true", help="planar runs along x, y and an azimuth sweep too")
    p.add_argument("--sweep", type=float, default=15.0, metavar="DEG",
                   help="the planar sweep's step in degrees (default 15)")
    p.add_argument("--out", required=True, metavar="DIR")
    p.set_defaults(func=cmd_space)
