"""The `rocking` command.

    rocking simulate [RECORD] [--scale 1.5] [--component LABEL] [--preset NAME]
                     [--PARAM VALUE ...] [--fmu PATH] --out DIR
    rocking sweep CASES.toml --records DIR [--scales 0.5:3:0.25] --out results.parquet
    rocking ida|msa SUITE_OR_TOML [--preset NAME] [--im PGV] --out DIR   (rocking.ida_cli)
    rocking info [--presets]
    rocking record FILE [--plot out.png]
    rocking corner ARGS...          (the Rust binary rocking-corner)

Errors are one line on stderr naming the file, the variable or the parameter,
with exit status 2; `--debug` shows the traceback instead.
"""

import argparse
import difflib
import json
import math
import os
import re
import shutil
import subprocess
import sys
import textwrap
import time
import tomllib
from pathlib import Path

from . import paths

PROG = "rocking"

#: Outputs written by `simulate`, in this order, when the FMU has them.
SIMULATE_OUTPUTS = ("theta", "omega", "thetaOverAlpha", "MR", "af", "contactLength", "regime",
                    "impacts", "zeroCrossings", "overturned")
#: Files that `--records DIR` passes over (documentation, scripts, results).
NOT_RECORDS = {".md", ".py", ".toml", ".json", ".png", ".pdf", ".svg", ".parquet", ".zip", ".gz"}


class CLIError(Exception):
    """A mistake in what was asked: reported as one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    """argparse whose usage errors are one line (the CLIError handler prints it)."""

    def error(self, message):
        raise CLIError(f"{message} (`{self.prog} --help`)")


# ---------------------------------------------------------------------------
# Where things are

def fmu_path(arg):
    """--fmu, else target/fmu/RockingBlock.fmu of the repository."""
    if arg:
        path = Path(arg)
        if not path.is_file():
            raise CLIError(f"{path}: no such FMU file")
        return path
    if paths.REPO is None:
        raise CLIError("no --fmu given and " + paths._NOT_IN_REPO)
    path = paths.default_fmu()
    if not path.is_file():
        raise CLIError(f"{path} does not exist: run `cargo xtask fmu` (or pass --fmu PATH)")
    return path


def open_fmu(arg):
    from .fmu import RockingFMU
    return RockingFMU(fmu_path(arg))


# ---------------------------------------------------------------------------
# Parameters by name, checked against the FMU's modelDescription

def settable(fmu):
    """{name: variable} of what a user may give: the parameters, and the outputs whose
    start value is the initial condition (theta, omega)."""
    return {name: v for name, v in fmu.variables.items()
            if v.causality == "parameter" or (v.causality == "output" and v.initial == "exact")}


def unit_of(v):
    return v.unit or (v.declaredType.unit if v.declaredType is not None else None) or ""


def read_params_file(path):
    """Parameters from a JSON file of name -> value (enumerations by item name), as
    `rocking-corner --body FILE` writes them; CLIError naming the file otherwise."""
    import json

    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise CLIError(f"{path}: cannot read ({exc.strerror or exc})") from None
    except json.JSONDecodeError as exc:
        raise CLIError(f"{path}: not JSON ({exc.msg} at line {exc.lineno})") from None
    if not isinstance(data, dict):
        raise CLIError(f"{path}: expected a JSON object of parameter name -> value")
    return data


def check_parameter(fmu, name, value, where):
    """`value` (a string from the command line, or a TOML value) converted for the FMU
    variable `name`; CLIError naming `where` (e.g. '--kn' or 'cases.soft.kn') if the name or
    the value does not fit. Enumerations are returned by item name."""
    table = settable(fmu)
    if name not in table:
        if name in fmu.variables:
            v = fmu.variables[name]
            raise CLIError(f"{where}: {name} is a{'n' if v.causality[0] in 'aeiou' else ''} "
                           f"{v.causality} of the FMU, not something that can be set")
        close = difflib.get_close_matches(name, table, n=3, cutoff=0.5)
        close += [n for n in table if n.lower() == name.lower() and n not in close]
        hint = f"; did you mean {', '.join(close)}?" if close else ""
        raise CLIError(f"{where}: unknown parameter {name!r}{hint} (`rocking info` lists them)")
    v = table[name]
    text = value if isinstance(value, str) else None
    unit = unit_of(v)
    what = f"{name} is a {v.type} {v.causality}" + (f" in {unit}" if unit else "")
    if v.type == "Enumeration":
        items = fmu.enumerations.get(name, {})
        if isinstance(value, bool):
            raise CLIError(f"{where} {value!r}: {what}, one of {', '.join(items)}")
        if isinstance(value, int):
            by_value = {val: item for item, val in items.items()}
            if value in by_value:
                return by_value[value]
        elif text is not None:
            if text in items:
                return text
            if text.strip().lstrip("-").isdigit() and int(text) in items.values():
                return next(item for item, val in items.items() if val == int(text))
            folded = [item for item in items if item.lower() == text.lower()]
            if folded:
                return folded[0]
        raise CLIError(f"{where} {value!r}: not one of {', '.join(items)} ({name})")
    if v.type == "Real":
        if isinstance(value, bool):
            raise CLIError(f"{where} {value!r}: not a number ({what})")
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise CLIError(f"{where} {value!r}: not a number ({what})") from None
        if math.isnan(number):
            raise CLIError(f"{where} {value!r}: not a number ({what})")
        return number
    if v.type == "Integer":
        try:
            if isinstance(value, bool) or (isinstance(value, float) and not value.is_integer()):
                raise ValueError
            return int(value)
        except (TypeError, ValueError):
            raise CLIError(f"{where} {value!r}: not an integer ({what})") from None
    if v.type == "Boolean":
        if isinstance(value, bool):
            return value
        if text is not None and text.lower() in ("true", "1", "yes", "false", "0", "no"):
            return text.lower() in ("true", "1", "yes")
        raise CLIError(f"{where} {value!r}: not true or false ({what})")
    raise CLIError(f"{where}: cannot set a {v.type} variable")


def split_parameters(argv, known_options):
    """Take the `--NAME VALUE` (or `--NAME=VALUE`) pairs whose NAME is not an option of the
    command out of argv: (the rest of argv, [(NAME, VALUE), ...])."""
    rest, pairs = [], []
    i = 0
    while i < len(argv):
        token = argv[i]
        head = token.split("=", 1)[0]
        if token.startswith("--") and len(token) > 2 and head not in known_options:
            name = head[2:]
            if "=" in token:
                value = token.split("=", 1)[1]
                i += 1
            else:
                if i + 1 >= len(argv):
                    raise CLIError(f"--{name}: a value is needed")
                value = argv[i + 1]
                i += 2
            pairs.append((name, value))
        else:
            rest.append(token)
            i += 1
    return rest, pairs


# ---------------------------------------------------------------------------
# Records

def read_record(path, component=None):
    """(Record, format name) of `path`; component by label, else by index."""
    from . import groundmotion as gm
    from .groundmotion.detect import select
    path = Path(path)
    if not path.exists():
        raise CLIError(f"{path}: no such record file")
    if path.is_dir():
        raise CLIError(f"{path}: is a folder, not a record file")
    fmt = gm.detect_format(path)
    records = gm.read_all(path, fmt=fmt)
    if component is None:
        return records[0], fmt
    try:
        return select(records, component, path), fmt
    except ValueError:
        if re.fullmatch(r"-?\d+", component):
            try:
                return select(records, int(component), path), fmt
            except ValueError:
                pass
        raise


def record_facts(rec):
    return dict(npts=rec.npts, dt_s=rec.dt, duration_s=rec.duration, pga_m_s2=rec.pga,
                pga_g=rec.pga_g, t_pga_s=float(rec.time[int(abs(rec.acc).argmax())]),
                pgv_cm_s=rec.pgv * 100)


# ---------------------------------------------------------------------------
# rocking simulate

def regime_names(fmu):
    """{value: name} of the `regime` output, from its description ("0 full contact, 1 ...")."""
    v = fmu.variables.get("regime")
    if v is None:
        return {}
    return {int(k): name.strip() for k, name in re.findall(r"(\d+)\s+([^,;]+)", v.description or "")}


def cmd_simulate(args, params_given):
    import numpy as np
    import pandas as pd

    from . import presets as presets_module

    out = Path(args.out)
    with open_fmu(args.fmu) as fmu:
        params = {}
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
        for name, value in params_given:
            params[name] = check_parameter(fmu, name, value, f"--{name}")

        rec = fmt = None
        if args.record:
            rec, fmt = read_record(args.record, args.component)
        outputs = [o for o in SIMULATE_OUTPUTS if o in fmu.variables]
        run = fmu.simulate(params, record=rec, scale=args.scale, stop_time=args.stop_time,
                           output_interval=args.output_interval, rtol=args.rtol, outputs=outputs)
        regimes = regime_names(fmu)
        units = {name: unit_of(fmu.variables[name]) for name in outputs}
        guid = fmu.model_description.guid

    res = run.result
    t = res["time"]
    ag = (args.scale * np.interp(t, rec.time, rec.acc, right=0.0)) if rec is not None else np.zeros(len(t))
    table = pd.DataFrame({"time": t, "ag": ag})
    for name in outputs:
        column = res[name]
        table[name] = column.astype(int) if column.dtype == bool else column
    out.mkdir(parents=True, exist_ok=True)
    csv_path, json_path, png_path = out / "timehistory.csv", out / "summary.json", out / "plot.png"
    table.to_csv(csv_path, index=False)

    theta = res["theta"]
    k_peak = int(np.argmax(np.abs(theta)))
    last = res[-1]
    summary = {
        "fmu": str(fmu.path), "guid": guid,
        "record": None if rec is None else {
            "path": str(args.record), "format": fmt, "name": rec.name, "component": rec.component,
            **record_facts(rec), "scale": args.scale, "scaled_pga_g": abs(args.scale) * rec.pga_g,
            "synthetic_stand_in": "stand-in" in rec.notes.lower()},
        "preset": args.preset,
        "parameters": params,
        "calculated": run.calculated,
        "stop_time_s": float(t[-1]) if run.overturned else (args.stop_time or float(t[-1])),
        "rows": int(len(t)),
        "peak_theta_rad": float(abs(theta[k_peak])),
        "t_peak_theta_s": float(t[k_peak]),
        "peak_theta_over_alpha": run.peak_theta_over_alpha,
        "overturned": bool(run.overturned),
        "t_overturn_s": run.t_overturn if run.overturned else None,
        "impacts": int(last["impacts"]) if "impacts" in outputs else run.impacts,
    }
    if "zeroCrossings" in outputs:
        summary["zeroCrossings"] = int(last["zeroCrossings"])
    if "regime" in outputs:
        reached = sorted({int(r) for r in res["regime"]})
        summary["regimes_reached"] = [regimes.get(r, str(r)) for r in reached]
    summary["units"] = {"time": "s", "ag": "m/s2", **units}
    summary["wall_s"] = run.wall
    summary["files"] = {"timehistory": csv_path.name, "plot": png_path.name}
    json_path.write_text(json.dumps(summary, indent=2, default=_json_default) + "\n")
    plot_simulation(png_path, table, summary, regimes, rec, args)
    print(summary_text(summary, out))
    return 0


def _json_default(value):
    if hasattr(value, "item"):
        return value.item()
    raise TypeError(type(value).__name__)


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
    if s["preset"]:
        lines.append(f"preset      {s['preset']}")
    calc = s["calculated"]
    lines.append(f"body        alpha = {calc.get('alpha', math.nan):.5g} rad, "
                 f"thetaOv = {calc.get('thetaOv', math.nan):.5g} rad")
    if s["overturned"]:
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
    lines.append(f"wrote       {out / s['files']['timehistory']}, {out / 'summary.json'}, "
                 f"{out / s['files']['plot']}  ({s['rows']} rows, {s['wall_s']:.2f} s)")
    return "\n".join(lines)


def plot_simulation(path, table, s, regimes, rec, args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import EngFormatter

    g = 9.80665
    t = table["time"].to_numpy()
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(10, 9), height_ratios=(1.1, 1.6, 1.1, 0.8))
    title = s["preset"] or f"RockingBlock ({s['parameters'].get('shape', 'default shape')})"
    if rec is not None:
        comp = f" [{rec.component}]" if rec.component else ""
        title += f" under {rec.name or Path(args.record).name}{comp} x {args.scale:g}"
        if s["record"]["synthetic_stand_in"]:
            title += " (synthetic stand-in)"
    outcome = (f"overturned at {s['t_overturn_s']:.2f} s" if s["overturned"]
               else f"stands; peak |theta|/alpha = {s['peak_theta_over_alpha']:.3g}")
    fig.suptitle(f"{title}\n{outcome}", fontsize=11)

    ax = axes[0]
    if rec is not None:
        t_rec = rec.time[rec.time <= t[-1] + rec.dt]
        ax.plot(t_rec, args.scale * rec.acc[:len(t_rec)] / g, lw=0.6, color="0.3")
    else:
        ax.plot(t, table["ag"] / g, lw=0.6, color="0.3")
    ax.set_ylabel("ground acc. ag (g)")

    ax = axes[1]
    ax.plot(t, table["thetaOverAlpha"], lw=0.9, color="C0")
    ax.axhline(0, color="0.6", lw=0.5)
    for sign in (1, -1):
        ax.axhline(sign, color="C1", lw=0.7, ls="--", label="theta = ±alpha" if sign > 0 else None)
    alpha, theta_ov = s["calculated"].get("alpha"), s["calculated"].get("thetaOv")
    if alpha and theta_ov and math.isfinite(theta_ov):
        for sign in (1, -1):
            ax.axhline(sign * theta_ov / alpha, color="C3", lw=0.7, ls=":",
                       label="overturning thetaOv" if sign > 0 else None)
    ax.set_ylabel("theta / alpha")
    ax.legend(loc="upper left", fontsize=8)

    ax = axes[2]
    ax.plot(t, table["MR"], lw=0.9, color="C2")
    ax.yaxis.set_major_formatter(EngFormatter(unit="N·m"))
    ax.set_ylabel("restoring moment MR")

    ax = axes[3]
    if "regime" in table:
        ax.step(t, table["regime"], where="post", lw=0.9, color="C4")
        values = sorted(regimes) or sorted(set(table["regime"]))
        ax.set_yticks(values, [regimes.get(v, str(v)) for v in values], fontsize=7)
        ax.set_ylim(min(values) - 0.5, max(values) + 0.5)
    ax.set_ylabel("regime")
    ax.set_xlabel("time (s)")

    if s["overturned"]:
        for ax in axes:
            ax.axvline(s["t_overturn_s"], color="C3", lw=1.2)
        axes[1].annotate(f"overturned\n{s['t_overturn_s']:.2f} s", xy=(s["t_overturn_s"], 0),
                         xytext=(-6, 0), textcoords="offset points", ha="right", color="C3", fontsize=9)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------
# rocking sweep

def parse_scales(text):
    """'0.5:3:0.25' (start:stop:step, stop included), '0.5,1,2' or '1.5' -> list of floats."""
    try:
        if ":" in text:
            parts = [float(p) for p in text.split(":")]
            if len(parts) != 3 or not parts[2] > 0 or parts[1] < parts[0]:
                raise ValueError
            start, stop, step = parts
            n = int(math.floor((stop - start) / step + 1e-9)) + 1
            return [round(start + i * step, 12) for i in range(n)]
        values = [float(p) for p in text.split(",") if p.strip()]
        if not values:
            raise ValueError
        return values
    except ValueError:
        raise CLIError(f"--scales {text!r}: expected start:stop:step (step > 0, stop >= start), "
                       "a list a,b,c or one number") from None


def load_cases(path, fmu):
    """{case name: start values} from CASES.toml: optional [defaults], then [cases.NAME]
    tables, each with an optional `preset` and parameters by name."""
    from . import presets as presets_module
    path = Path(path)
    if not path.is_file():
        raise CLIError(f"{path}: no such cases file")
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise CLIError(f"{path}: not valid TOML: {exc}") from None
    unknown = set(data) - {"defaults", "cases"}
    if unknown:
        raise CLIError(f"{path}: unknown table(s) {', '.join(sorted(unknown))}: expected [defaults] and [cases.NAME]")
    cases_in = data.get("cases")
    if not isinstance(cases_in, dict) or not cases_in:
        raise CLIError(f"{path}: no cases: add tables [cases.NAME] with parameters or a preset")
    defaults = data.get("defaults", {})
    cases = {}
    for cname, table in cases_in.items():
        if not isinstance(table, dict):
            raise CLIError(f"{path}: cases.{cname}: expected a table of parameters")
        params = {}
        preset_name = table.get("preset", defaults.get("preset"))
        if preset_name is not None:
            try:
                params.update(presets_module.preset(str(preset_name)))
            except KeyError as exc:
                raise CLIError(f"{path}: cases.{cname}.preset: {exc.args[0]}") from None
        merged = {**{k: v for k, v in defaults.items() if k != "preset"},
                  **{k: v for k, v in table.items() if k != "preset"}}
        for name, value in {**params, **merged}.items():
            where = f"{path}: cases.{cname}.{name}" if name in merged else f"{path}: cases.{cname} (preset {preset_name}): {name}"
            params[name] = check_parameter(fmu, name, value, where)
        cases[cname] = params
    return cases


def collect_records(sources, component):
    """{name: Record} of every component (or the one named) of each record file among
    `sources` (files, or folders searched recursively)."""
    from . import groundmotion as gm
    records = {}
    for source in sources:
        source = Path(source)
        if not source.exists():
            raise CLIError(f"{source}: no such record file or folder")
        if source.is_dir():
            files = sorted(p for p in source.rglob("*") if p.is_file() and not p.name.startswith(".")
                           and p.suffix.lower() not in NOT_RECORDS)
            base = source
        else:
            files, base = [source], source.parent
        for file in files:
            label = str(file.relative_to(base))
            if component is not None:
                rec, _ = read_record(file, component)
                found = [rec]
            else:
                found = gm.read_all(file)
            for rec in found:
                records[f"{label}[{rec.component}]" if len(found) > 1 or component is not None else label] = rec
    if not records:
        raise CLIError(f"{', '.join(map(str, sources))}: no record files found")
    return records


def cmd_sweep(args, _params):
    from tqdm import tqdm

    from .parametric import run_grid

    scales = parse_scales(args.scales)
    out = Path(args.out)
    if out.suffix.lower() not in (".parquet", ".csv"):
        raise CLIError(f"--out {out}: expected a .parquet or .csv file name")
    with open_fmu(args.fmu) as fmu:
        cases = load_cases(args.cases, fmu)
        records = collect_records(args.records, args.component)
        total = len(cases) * len(records) * len(scales)
        workers = args.workers or min(os.cpu_count() or 1, total)
        print(f"sweep: {len(cases)} case(s) x {len(records)} record(s) x {len(scales)} scale(s) = {total} runs, "
              f"{workers} worker process(es)", file=sys.stderr, flush=True)
        t0 = time.perf_counter()
        with tqdm(total=total, unit="run", desc="sweep", file=sys.stderr, dynamic_ncols=True,
                  mininterval=0.5, smoothing=0.1) as bar:
            def progress(done, _total, row):
                bar.update(done - bar.n)
            df = run_grid(cases, records=records, scales=scales, workers=workers, fmu=fmu,
                          stop_time=args.stop_time, rtol=args.rtol, progress=progress)
        wall = time.perf_counter() - t0
    failed = df[df["error"] != ""]
    out.parent.mkdir(parents=True, exist_ok=True)
    if out.suffix.lower() == ".parquet":
        df.to_parquet(out, index=False)
    else:
        df.to_csv(out, index=False)
    overturned = int((df["overturned"] == True).sum())  # noqa: E712 - None for failed runs
    print(f"sweep: {total} runs in {wall:.1f} s ({total / wall:.2f} runs/s): {overturned} overturned, "
          f"{len(failed)} failed -> {out}", file=sys.stderr)
    if len(failed) == total:
        raise CLIError(f"every run failed; the first: {failed.iloc[0]['case']}, {failed.iloc[0]['record']}: "
                       f"{failed.iloc[0]['error']}")
    if len(failed):
        first = failed.iloc[0]
        print(f"sweep: first failure: {first['case']}, {first['record']} x {first['scale']:g}: {first['error']}",
              file=sys.stderr)
    return 0


# ---------------------------------------------------------------------------
# rocking info

def cmd_info(args, _params):
    from . import presets as presets_module
    if args.presets:
        table = presets_module.presets()
        width = max(map(len, table))
        print(f"{len(table)} presets (rocking simulate --preset NAME; `preset = \"NAME\"` in a sweep's CASES.toml):")
        for name, (text, _) in table.items():
            print(f"  {name:<{width}}  {text}")
        return 0
    with open_fmu(args.fmu) as fmu:
        md = fmu.model_description
        enums = fmu.enumerations
        print(f"FMU          {fmu.path}")
        print(f"model        {md.modelName}, FMI {md.fmiVersion}, GUID {md.guid}")
        if md.generationTool:
            print(f"generated by {md.generationTool}")
        if md.defaultExperiment is not None:
            de = md.defaultExperiment
            print(f"default      start {de.startTime}, stop {de.stopTime} s, tolerance {de.tolerance}, "
                  f"step {de.stepSize}")
        rows = []
        for v in md.modelVariables:
            start = v.start
            if v.type == "Enumeration" and start is not None:
                by_value = {val: item for item, val in enums.get(v.name, {}).items()}
                start = by_value.get(int(start), start)
            rows.append((v.name, v.causality, v.variability, v.type, "" if start is None else str(start),
                         unit_of(v), (v.description or "")))
        heads = ("name", "causality", "variability", "type", "start", "unit", "description")
        widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(heads[:-1])]
        print(f"\n{len(rows)} variables (set a parameter with `rocking simulate --NAME VALUE`):")
        print("  ".join(h.ljust(w) for h, w in zip(heads, widths)) + "  description")
        for r in rows:
            print("  ".join(c.ljust(w) for c, w in zip(r, widths)) + "  " + r[-1])
        if enums:
            print("\nenumerations:")
            for name, items in enums.items():
                print(f"  {name}: " + ", ".join(f"{item} = {val}" for item, val in items.items()))
    return 0


# ---------------------------------------------------------------------------
# rocking record

def cmd_record(args, _params):
    from . import groundmotion as gm
    path = Path(args.file)
    if not path.exists():
        raise CLIError(f"{path}: no such record file")
    if args.component is not None:
        rec, fmt = read_record(path, args.component)
        records = [rec]
    else:
        fmt = gm.detect_format(path)
        records = gm.read_all(path, fmt=fmt)
    print(f"file        {path}")
    print(f"format      {fmt}")
    print(f"components  {len(records)}: {', '.join(r.component for r in records)}")
    for rec in records:
        f = record_facts(rec)
        print(f"\n[{rec.component}] {rec.name}")
        print(f"  units in file  {rec.units_in_file}")
        print(f"  npts           {f['npts']}")
        print(f"  dt             {f['dt_s']:g} s")
        print(f"  duration       {f['duration_s']:g} s")
        print(f"  PGA            {f['pga_g']:.4f} g = {f['pga_m_s2']:.4f} m/s2 at t = {f['t_pga_s']:g} s")
        print(f"  PGV            {f['pgv_cm_s']:.2f} cm/s (trapezoidal integral of acc from rest, no baseline correction)")
        if rec.notes:
            note = rec.notes.splitlines()[0]
            print(f"  notes          {note[:160]}{'...' if len(note) > 160 else ''}")
    if args.plot:
        plot_records(Path(args.plot), records, path)
        print(f"\nwrote {args.plot}")
    return 0


def plot_records(path, records, source):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    g = 9.80665
    fig, axes = plt.subplots(len(records), 2, figsize=(11, 2.4 * len(records) + 0.8), squeeze=False,
                             sharex=True)
    for (ax_a, ax_v), rec in zip(axes, records):
        f = record_facts(rec)
        ax_a.plot(rec.time, rec.acc / g, lw=0.5, color="0.25")
        ax_a.plot(f["t_pga_s"], rec.acc[int(abs(rec.acc).argmax())] / g, "o", color="C3", ms=4)
        ax_a.set_ylabel(f"[{rec.component}] acc (g)")
        ax_a.set_title(f"PGA {f['pga_g']:.3f} g at {f['t_pga_s']:.2f} s", fontsize=9)
        vel = rec.velocity * 100
        ax_v.plot(rec.time, vel, lw=0.7, color="C0")
        ax_v.set_ylabel("vel. (cm/s)")
        ax_v.set_title(f"PGV {f['pgv_cm_s']:.1f} cm/s (integrated from rest)", fontsize=9)
        for ax in (ax_a, ax_v):
            ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("time (s)")
    name = records[0].name or source.name
    fig.suptitle(f"{source.name}: {name}\n{records[0].npts} points, dt = {records[0].dt:g} s", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------
# rocking corner

def corner_binary():
    """target/release/rocking-corner of the repository, else rocking-corner on PATH, else None."""
    if paths.REPO is not None:
        local = paths.target_dir() / "release" / "rocking-corner"
        if local.is_file() and os.access(local, os.X_OK):
            return str(local)
    return shutil.which("rocking-corner")


def cmd_corner(argv):
    exe = corner_binary()
    if exe is None:
        raise CLIError("rocking-corner not found (target/release of the repository, PATH): "
                       "build it with `cargo build --release -p corner`")
    return subprocess.call([exe, *argv])


# ---------------------------------------------------------------------------
# The parser

def build_parser():
    from .presets import NAMING
    common = _Parser(add_help=False)
    common.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                        help="show the traceback of an error instead of one line")

    parser = _Parser(prog=PROG, description="RockingBlock: a rigid body rocking on a flexible, crushing "
                     "interface (an FMI 2.0 FMU), from the command line.",
                     epilog="`rocking COMMAND --help` for each command. Errors: one line on stderr, exit status 2.")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error instead of one line")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    fmu_help = "the FMU (default: target/fmu/RockingBlock.fmu of the repository, built by `cargo xtask fmu`)"

    p = sub.add_parser(
        "simulate", parents=[common], allow_abbrev=False,
        help="one run: time history CSV, summary, plot",
        usage="rocking simulate [RECORD] [--scale S] [--component C] [--preset NAME] [--PARAM VALUE ...]\n"
              "                        [--fmu PATH] [--stop-time S] [--output-interval S] [--rtol R] --out DIR",
        description=textwrap.fill(
            "Run one case through the FMU and write DIR/timehistory.csv (time, ag and the outputs), "
            "DIR/summary.json (peak theta, overturning and its time, impacts, regimes, PGA) and "
            "DIR/plot.png. Any FMU parameter can be given by its name, e.g. --shape hollowCircle "
            "--Ro 3.99 --kn 2e9 (theta and omega set the initial conditions); they override the preset's.", 100),
        epilog=textwrap.fill(f"presets: {NAMING}. `rocking info --presets` lists them; `rocking info` lists "
                             "the parameters, their units and defaults.", 100),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("record", nargs="?", metavar="RECORD",
                   help="ground-motion file (any format `rocking record` reads); none: free rocking")
    p.add_argument("--scale", type=float, default=1.0, help="factor on the record's acceleration (default 1)")
    p.add_argument("--component", help="the record's component, by label (e.g. N28W, 090, UP) or index; default the first")
    p.add_argument("--preset", metavar="NAME", help="start from a named parameter set (see below)")
    p.add_argument("--params", metavar="FILE",
                   help="parameters from a JSON object of name -> value (e.g. rocking-corner --body FILE); "
                        "over the preset's, under --NAME VALUE")
    p.add_argument("--fmu", metavar="PATH", help=fmu_help)
    p.add_argument("--stop-time", type=float, metavar="S", help="default: the record's end (10 s without one)")
    p.add_argument("--output-interval", type=float, metavar="S", help="default: the record's dt (0.01 s without one)")
    p.add_argument("--rtol", type=float, help="the integrator's relative tolerance (default: the FMU's)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.set_defaults(func=cmd_simulate)

    p = sub.add_parser(
        "sweep", parents=[common], allow_abbrev=False, help="cases x records x scales in parallel -> parquet",
        description=textwrap.fill(
            "Every case of CASES.toml under every record component of --records, at every scale, "
            "in parallel processes; one row per run (case, parameters, record, scale, overturned, "
            "t_overturn, peak_theta_over_alpha, impacts, ..., error).", 100),
        epilog="CASES.toml: an optional [defaults] table (parameters for every case), then one table per case, "
               "e.g.\n  [cases.soft]\n  preset = \"dharahara-F170-fm5\"\n  [cases.block]\n  shape = \"solidRectangle\"\n"
               "  B = 0.5\n  H = 2.5\n  interface = \"rigid\"\n"
               + textwrap.fill(f"presets: {NAMING}.", 100),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("cases", metavar="CASES.toml")
    p.add_argument("--records", action="append", required=True, metavar="DIR",
                   help="a folder (searched recursively; every component of every file) or a record file; repeatable")
    p.add_argument("--component", help="only this component of each file (label or index)")
    p.add_argument("--scales", default="1", help="start:stop:step (stop included), a,b,c or one number (default 1)")
    p.add_argument("--out", required=True, metavar="FILE", help="results, .parquet or .csv")
    p.add_argument("--workers", type=int, help="processes (default: the CPU count)")
    p.add_argument("--stop-time", type=float, metavar="S", help="default: each record's end")
    p.add_argument("--rtol", type=float, help="the integrator's relative tolerance (default: the FMU's)")
    p.add_argument("--fmu", metavar="PATH", help=fmu_help)
    p.set_defaults(func=cmd_sweep)

    p = sub.add_parser("info", parents=[common], help="the FMU's variables, units, defaults; --presets",
                       description="The FMU's variables from its modelDescription.xml: causality, variability, "
                                   "type, start value, unit, description.")
    p.add_argument("--presets", action="store_true", help="list the presets instead")
    p.add_argument("--fmu", metavar="PATH", help=fmu_help)
    p.set_defaults(func=cmd_info)

    p = sub.add_parser("record", parents=[common], help="what the reader sees in a ground-motion file",
                       description="Format, components, npts, dt, duration, PGA, PGV of a ground-motion file "
                                   "as the readers of rocking.groundmotion see it.")
    p.add_argument("file", metavar="FILE")
    p.add_argument("--component", help="only this component (label or index)")
    p.add_argument("--plot", metavar="PNG", help="plot acceleration and velocity of each component")
    p.set_defaults(func=cmd_record)

    from .ida_cli import register as register_studies
    register_studies(sub, common)

    sub.add_parser("corner", help="forward the arguments to the Rust binary rocking-corner", add_help=False)
    return parser


def _one_line(exc):
    text = str(exc) if not isinstance(exc, KeyError) or not exc.args else str(exc.args[0])
    return " ".join(text.split()) or type(exc).__name__


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    command = next((a for a in argv if not a.startswith("-")), None)
    try:
        if command == "corner":
            rest = argv[argv.index("corner") + 1:]
            return cmd_corner(rest)
        parser = build_parser()
        params = []
        if command == "simulate":
            sim = parser._subparsers._group_actions[0].choices["simulate"]
            known = set(sim._option_string_actions) | set(parser._option_string_actions)
            argv, params = split_parameters(argv, known)
        args = parser.parse_args(argv)
        if args.command is None:
            parser.print_help()
            return 2
        return args.func(args, params)
    except BrokenPipeError:  # e.g. `rocking info | head`: the reader went away
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    except SystemExit:
        raise
    except BaseException as exc:  # noqa: BLE001 - every error is one line unless --debug
        if debug:
            raise
        where = f"{PROG} {command}" if command else PROG
        kind = "" if isinstance(exc, (CLIError, OSError, ValueError, KeyError)) else f"{type(exc).__name__}: "
        if type(exc).__name__ == "FMUError":
            kind = "the FMU: "
        if isinstance(exc, OSError) and exc.filename and str(exc.filename) not in str(exc):
            kind = f"{exc.filename}: "
        print(f"{where}: error: {kind}{_one_line(exc)}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
