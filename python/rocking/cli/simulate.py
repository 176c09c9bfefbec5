"""`rocking simulate`: one run through the FMU -> time history CSV, summary JSON, plot."""

import argparse
import math
import re
import sys
import textwrap
from pathlib import Path

from .. import jsonfile
from ..fmu import FMUError
from .common import (FMU_HELP, CLIError, add_record_options, check_parameter, drop_unused, horizontal_record, open_fmu,
                     read_params_file, record_facts, seconds, unit_of, vertical_record)
from .plots import plot_simulation

#: This subcommand also takes any FMU parameter as `--NAME VALUE` (see `common.split_parameters`).
TAKES_PARAMETERS = True

#: Outputs written by `simulate`, in this order, when the FMU has them.
SIMULATE_OUTPUTS = ("theta", "omega", "thetaOverAlpha", "MR", "af", "contactLength", "regime",
                    "impacts", "zeroCrossings", "overturned")


def regime_names(fmu):
    """{value: name} of the `regime` output, from its description ("0 full contact, 1 ...")."""
    v = fmu.variables.get("regime")
    if v is None:
        return {}
    return {int(k): name.split(" (")[0].strip()  # "5 out of the model's range (liftOff, ...": its name
            for k, name in re.findall(r"(\d+)\s+([^,;]+)", v.description or "")}


def gather_parameters(fmu, args, params_given):
    """(start values: the preset's, under --params FILE's, under --NAME VALUE; {name: why} of
    the ones the chosen interface, shape, mass model or restitution do not use, left out)."""
    from .. import presets as presets_module
    params, typed, raw = {}, {}, {}
    if args.preset:
        try:
            preset_values = presets_module.preset(args.preset)
        except KeyError as exc:
            raise CLIError(f"--preset: {exc.args[0]}") from None
        for name, value in preset_values.items():
            params[name] = check_parameter(fmu, name, value, f"preset {args.preset}: {name}")
    if args.params:
        for name, value in read_params_file(args.params).items():
            params[name] = check_parameter(fmu, name, value, f"{args.params}: {name}")
            typed[name], raw[name] = f"{args.params}: {name} = {value!r}", str(value)
    for name, value in params_given:
        params[name] = check_parameter(fmu, name, value, f"--{name}")
        typed[name], raw[name] = f"--{name} {value}", value
    ignored, note = drop_unused(fmu, params, typed)
    if note:
        print(f"rocking {getattr(args, 'command', None) or 'simulate'}: note: {note}", file=sys.stderr)
    return params, ignored, raw


def chosen_outputs(fmu, text):
    """The time-history columns of --outputs ("theta,Fx,Fz", "all"; default SIMULATE_OUTPUTS)."""
    from ..fmu import did_you_mean
    available = [n for n, v in fmu.variables.items() if v.causality == "output"]
    if text is None:
        return [o for o in SIMULATE_OUTPUTS if o in fmu.variables]
    if text.strip() == "all":
        return available
    names = [n.strip() for n in text.split(",") if n.strip()]
    for name in names:
        if name not in available:
            raise CLIError(f"--outputs: {name!r} is not an output of the FMU{did_you_mean(name, available)} "
                           f"(outputs: {', '.join(available)})")
    if not names:
        raise CLIError("--outputs: expected output names separated by commas, or all")
    return list(dict.fromkeys(names))


def stop_time_of(args, rec):
    """--stop-time, or the record's end + --tail (the free motion after the record)."""
    if args.tail is None:
        return args.stop_time
    if rec is None:
        raise CLIError(f"--tail {args.tail:g}: the free motion after a record needs a RECORD "
                       "(without one, give --stop-time)")
    if args.stop_time is not None:
        raise CLIError(f"--tail {args.tail:g} and --stop-time {args.stop_time:g}: give one of them")
    return rec.duration + args.tail


def cmd_simulate(args, params_given):
    import numpy as np
    import pandas as pd

    out = Path(args.out)
    with open_fmu(args.fmu) as fmu:
        params, ignored, raw = gather_parameters(fmu, args, params_given)
        rec = fmt = None
        if args.record:
            rec, fmt = horizontal_record(args.record, args.component, args.units, args.fmt)
        vert = vfmt = None
        if args.vertical:
            vert, vfmt = vertical_record(args.vertical, rec, args.units, args.fmt)
        columns = chosen_outputs(fmu, args.outputs)
        extra = ("frictionDemand", "apparentWeight") if vert is not None else ("frictionDemand",)
        outputs = list(dict.fromkeys([o for o in (*SIMULATE_OUTPUTS, *extra) if o in fmu.variables]
                                     + columns))
        stop_time = stop_time_of(args, rec)
        try:
            run = fmu.simulate(params, record=rec, scale=args.scale, stop_time=stop_time,
                               output_interval=args.output_interval, rtol=args.rtol, outputs=outputs,
                               vertical=vert)
        except FMUError as exc:
            raise (exc.with_value(raw[exc.parameter]) if exc.parameter in raw else exc) from None
        regimes = regime_names(fmu)
        units = {name: unit_of(fmu.variables[name]) for name in columns}
        guid = fmu.model_description.guid

    res = run.result
    t = res["time"]
    ag = (args.scale * np.interp(t, rec.time, rec.acc, right=0.0)) if rec is not None else np.zeros(len(t))
    table = pd.DataFrame({"time": t, "ag": ag})
    inputs = ["time", "ag"]
    if vert is not None:  # the same --scale as ag
        table["av"] = args.scale * np.interp(t, vert.time, vert.acc, right=0.0)
        inputs.append("av")
    for name in outputs:
        column = res[name]
        table[name] = column.astype(int) if column.dtype == bool else column
    out.mkdir(parents=True, exist_ok=True)
    csv_path, json_path, png_path = out / "timehistory.csv", out / "summary.json", out / "plot.png"
    table.to_csv(csv_path, index=False, columns=[*inputs, *columns])

    theta = res["theta"]
    k_peak = int(np.argmax(np.abs(theta)))
    last = res[-1]
    summary = {
        "fmu": str(fmu.path), "guid": guid,
        "record": None if rec is None else {
            "path": str(args.record), "format": fmt, "name": rec.name, "component": rec.component,
            **record_facts(rec), "scale": args.scale, "scaled_pga_g": abs(args.scale) * rec.pga_g,
            "synthetic_stand_in": "stand-in" in rec.notes.lower()},
        "vertical": None if vert is None else vertical_summary(args, vert, vfmt, res, run),
        "preset": args.preset,
        "parameters": params,
        "ignored_parameters": ignored,
        "calculated": run.calculated,
        "stop_time_s": float(t[-1]) if run.overturned or run.terminal else (stop_time or float(t[-1])),
        "tail_s": args.tail,
        "rows": int(len(t)),
        "peak_theta_rad": float(abs(theta[k_peak])),
        "t_peak_theta_s": float(t[k_peak]),
        "peak_theta_over_alpha": run.peak_theta_over_alpha,
        "overturned": bool(run.overturned),
        "t_overturn_s": run.t_overturn if run.overturned else None,
        "impacts": int(last["impacts"]) if "impacts" in outputs else run.impacts,
    }
    if "frictionDemand" in outputs:
        summary["friction"] = friction_summary(t, res["frictionDemand"], params.get("mu", 0.0))
    if "zeroCrossings" in outputs:
        summary["zeroCrossings"] = int(last["zeroCrossings"])
    if "regime" in outputs:
        reached = sorted({int(r) for r in res["regime"]})
        summary["regimes_reached"] = [regimes.get(r, str(r)) for r in reached]
    summary["terminal"] = run.terminal
    summary["columns"] = [*inputs, *columns]
    summary["units"] = {"time": "s", "ag": "m/s2", **({"av": "m/s2"} if vert is not None else {}), **units}
    summary["wall_s"] = run.wall
    summary["files"] = {"timehistory": csv_path.name, "plot": png_path.name}
    jsonfile.write(json_path, summary)
    plot_simulation(png_path, table, summary, regimes, rec, args)  # plots.py
    print(summary_text(summary, out))
    return 0


def vertical_summary(args, vert, fmt, res, run):
    """The vertical record (av, scaled by --scale like ag) and the least apparent weight N / W."""
    weight = run.calculated.get("weight")
    n_min = float(min(res["apparentWeight"])) if len(res) else float("nan")
    return {"path": str(vert.source), "given_as": args.vertical, "format": fmt, "name": vert.name,
            "component": vert.component, **record_facts(vert), "scale": args.scale,
            "scaled_pga_g": abs(args.scale) * vert.pga_g,
            "min_apparent_weight_over_W": n_min / weight if weight else None}


def friction_summary(t, demand, mu):
    """The peak friction demand |Fx|/Fz over the samples, and whether it exceeds the base's
    coefficient `mu` (0: not checked) and first when (docs/model.md §5, "Friction demand")."""
    import numpy as np

    k = int(np.argmax(demand))
    s = {"peak_demand": float(demand[k]), "t_peak_s": float(t[k]), "mu": float(mu) if mu else None,
         "exceeds_mu": None, "t_first_exceeds_s": None}
    if mu:
        over = np.flatnonzero(demand > mu)
        s["exceeds_mu"] = bool(over.size)
        s["t_first_exceeds_s"] = float(t[over[0]]) if over.size else None
    return s




def summary_text(s, out):
    lines = []
    if s["record"]:
        r = s["record"]
        comp = f" [{r['component']}]" if r["component"] else ""
        lines.append(f"record      {r['path']}{comp} ({r['format']}), {r['npts']} points, "
                     f"dt = {r['dt_s']:g} s, PGA = {r['pga_g']:.3f} g x {r['scale']:g} "
                     f"= {r['scaled_pga_g']:.3f} g" + ("  (SYNTHETIC STAND-IN)" if r["synthetic_stand_in"] else ""))
    else:
        lines.append("record      none (free rocking from the initial conditions)")
    if s["vertical"]:
        v = s["vertical"]
        lines.append(f"vertical    {v['path']} [{v['component']}] as av, PGA = {v['pga_g']:.3f} g x {v['scale']:g} "
                     f"= {v['scaled_pga_g']:.3f} g; least apparent weight N/W = "
                     f"{v['min_apparent_weight_over_W']:.4g}")
    if s["preset"]:
        lines.append(f"preset      {s['preset']}")
    calc = s["calculated"]
    lines.append(f"body        alpha = {calc.get('alpha', math.nan):.5g} rad, "
                 f"thetaOv = {calc.get('thetaOv', math.nan):.5g} rad")
    if s["terminal"]:
        lines.append(f"result      OUT OF THE MODEL'S RANGE (regime 5): {s['terminal']}")
    elif s["overturned"]:
        lines.append(f"result      OVERTURNED at t = {s['t_overturn_s']:.4f} s")
    else:
        lines.append(f"result      stands until t = {s['stop_time_s']:g} s")
    lines.append(f"peak        |theta| = {s['peak_theta_rad']:.6g} rad at t = {s['t_peak_theta_s']:.4f} s "
                 f"(|theta|/alpha = {s['peak_theta_over_alpha']:.4g})")
    counts = f"impacts = {s['impacts']}"
    if "zeroCrossings" in s:
        counts += f", zeroCrossings = {s['zeroCrossings']}"
    lines.append(f"counts      {counts}")
    if "regimes_reached" in s:
        lines.append(f"regimes     {', '.join(s['regimes_reached'])}")
    if "friction" in s:
        lines.append(f"friction    {friction_text(s['friction'])}")
    lines.append(f"wrote       {out / s['files']['timehistory']}, {out / 'summary.json'}, "
                 f"{out / s['files']['plot']}  ({s['rows']} rows, {s['wall_s']:.2f} s)")
    return "\n".join(lines)


def friction_text(f):
    text = f"peak |Fx|/Fz = {f['peak_demand']:.4g} at t = {f['t_peak_s']:.4f} s"
    if f["mu"] is None:
        return text + " (no sliding check: give --mu)"
    if f["exceeds_mu"]:
        return (text + f"; EXCEEDS mu = {f['mu']:g} from t = {f['t_first_exceeds_s']:.4f} s: the base would "
                "slide, which the model does not represent")
    return text + f"; below mu = {f['mu']:g}: no sliding"


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    from ..presets import NAMING

    p = sub.add_parser(
        "simulate", parents=[common], allow_abbrev=False,
        help="one run: time history CSV, summary, plot",
        usage="rocking simulate [RECORD] [--scale S] [--component C] [--vertical FILE[:C]|auto]\n"
              "                        [--units U] [--fmt F]\n"
              "                        [--preset NAME] [--params FILE] [--PARAM VALUE ...]\n"
              "                        [--fmu PATH] [--stop-time S | --tail S] [--output-interval S]\n"
              "                        [--outputs A,B,...] [--rtol R] --out DIR",
        description=textwrap.fill(
            "Run one case through the FMU and write DIR/timehistory.csv (time, ag and the outputs), "
            "DIR/summary.json (peak theta, overturning and its time, impacts, regimes, PGA, "
            "the peak friction demand |Fx|/Fz against --mu) and "
            "DIR/plot.png. Any FMU parameter can be given by its name, e.g. --shape hollowCircle "
            "--Ro 3.99 --kn 2e9 (theta and omega set the initial conditions); they override the preset's.", 100),
        epilog=textwrap.fill(f"presets: {NAMING}. `rocking info --presets` lists them; `rocking info` lists "
                             "the parameters, their units and defaults.", 100),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("record", nargs="?", metavar="RECORD",
                   help="ground-motion file (any format `rocking record` reads); none: free rocking")
    p.add_argument("--scale", type=float, default=1.0,
                   help="factor on the record's acceleration, ag and av alike (default 1)")
    p.add_argument("--component", help="the record's horizontal component, by label (e.g. N28W, 090) or "
                        "index; default the first horizontal one")
    p.add_argument("--vertical", metavar="FILE[:COMPONENT] | auto",
                   help="the vertical ground acceleration av (m/s2, up), scaled by the same --scale: a file's "
                        "component (default its vertical one), or auto: the vertical component of RECORD's "
                        "set (the file, or its sibling files of the same station and event)")
    add_record_options(p)
    p.add_argument("--preset", metavar="NAME", help="start from a named parameter set (see below)")
    p.add_argument("--params", metavar="FILE",
                   help="parameters from a JSON object of name -> value (e.g. rocking-corner --body FILE); "
                        "over the preset's, under --NAME VALUE")
    p.add_argument("--fmu", metavar="PATH", help=FMU_HELP)
    p.add_argument("--stop-time", type=seconds(0, strict=False), metavar="S",
                   help="default: the record's end (10 s without one)")
    p.add_argument("--output-interval", type=seconds(0, strict=True), metavar="S",
                   help="rows every S seconds (and at the end); default: the record's dt (0.01 s without "
                        "one). The FMU still steps at the record's samples, and at the output times between them")
    p.add_argument("--tail", type=seconds(0, strict=False), metavar="S",
                   help="simulate S seconds of free motion after the record's end (the ground at rest); "
                        "instead of --stop-time")
    p.add_argument("--outputs", metavar="A,B,...",
                   help="the time-history columns after time and ag, e.g. theta,MR,Fx,Fz, or all (default: "
                        + ",".join(SIMULATE_OUTPUTS) + ")")
    p.add_argument("--rtol", type=float, help="the integrator's relative tolerance (default: the FMU's)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.set_defaults(func=cmd_simulate)
