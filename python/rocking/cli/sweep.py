"""`rocking sweep`: cases x records x scales in parallel processes -> parquet or CSV."""

import argparse
import math
import os
import sys
import textwrap
import time
import tomllib
from pathlib import Path

from ..groundmotion.files import record_files
from .common import (FMU_HELP, CLIError, add_record_options, check_parameter, drop_unused, horizontal_record,
                     open_fmu, read_components, seconds)

#: How a case's parameters are put together (the help and docs/examples.md say it).
PRECEDENCE = ("CASES.toml: an optional [defaults] table, then one [cases.NAME] table per case. A case's "
              "parameters: [defaults] first, its preset (`preset = \"...\"`, or [defaults]' preset) over "
              "them, the case's own keys over both: a preset is a whole body, which a default does not "
              "change; only the case's own keys do.")

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
    from .. import presets as presets_module
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
    if not isinstance(defaults, dict):
        raise CLIError(f"{path}: defaults: expected a table of parameters")
    cases = {}
    for cname, table in cases_in.items():
        if not isinstance(table, dict):
            raise CLIError(f"{path}: cases.{cname}: expected a table of parameters")
        cases[cname] = _case_parameters(fmu, path, cname, defaults, table, presets_module)
    return cases


def _case_parameters(fmu, path, cname, defaults, table, presets_module):
    """Start values of one case, in the order of PRECEDENCE: [defaults] first, the
    preset over them, the case's own keys over both (a preset is a whole body: a
    default must not turn the tower of `dharahara-F170-fm5` rigid)."""
    preset_name = table.get("preset", defaults.get("preset"))
    preset_values = {}
    if preset_name is not None:
        try:
            preset_values = presets_module.preset(str(preset_name))
        except KeyError as exc:
            raise CLIError(f"{path}: cases.{cname}.preset: {exc.args[0]}") from None
    vertical = table.get("vertical", defaults.get("vertical", False))
    if not isinstance(vertical, bool):
        raise CLIError(f"{path}: cases.{cname}.vertical: expected true or false (use each record's vertical "
                       f"component as av), found {vertical!r}")
    keys = ("preset", "vertical")
    layers = ((f"{path}: defaults.{{}}", {k: v for k, v in defaults.items() if k not in keys}),
              (f"{path}: cases.{cname} (preset {preset_name}): {{}}", preset_values),
              (f"{path}: cases.{cname}.{{}}", {k: v for k, v in table.items() if k not in keys}))
    params = {}
    for where, values in layers:
        for name, value in values.items():
            params[name] = check_parameter(fmu, name, value, where.format(name))
    _, note = drop_unused(fmu, params)
    if note:
        print(f"sweep: note: cases.{cname}: {note}", file=sys.stderr)
    if vertical:
        params["vertical"] = True  # not an FMU parameter: run_grid gives the record's vertical as av
    return params


def collect_records(sources, component, units=None, fmt=None):
    """({name: Record} of every horizontal component (or the one named) of each record file
    among `sources` (files, or folders searched recursively), [names of the vertical
    components left out]). ag is the horizontal ground acceleration: a vertical
    component as ag would be another analysis."""
    records, vertical = {}, []
    for source in sources:
        source = Path(source)
        if not source.exists():
            raise CLIError(f"{source}: no such record file or folder")
        if source.is_dir():
            files = record_files(source)
            base = source
        else:
            files, base = [source], source.parent
        for file in files:
            label = str(file.relative_to(base))
            if component is not None:
                found = [horizontal_record(file, component, units, fmt)[0]]
            else:
                found = read_components(file, units, fmt)[0]
            named = {f"{label}[{rec.component}]" if len(found) > 1 or component is not None else label: rec
                     for rec in found}
            records.update({name: rec for name, rec in named.items() if not rec.vertical})
            vertical += [name for name, rec in named.items() if rec.vertical]
    if not records:
        raise CLIError(f"{', '.join(map(str, sources))}: no horizontal record components found"
                       + (f" ({len(vertical)} vertical left out)" if vertical else ""))
    return records, vertical


def attach_verticals(records, units=None):
    """{name: Record with its set's vertical as av_record}; a record without one says so on
    stderr (its runs of the `vertical = true` cases fail with that message in the row)."""
    from .. import groundmotion as gm
    out = {}
    for name, rec in records.items():
        try:
            out[name] = gm.with_vertical(rec, units=units)
        except ValueError as exc:
            print(f"sweep: {exc}", file=sys.stderr)
            out[name] = rec
    return out


def cmd_sweep(args, _params):
    from tqdm import tqdm

    from ..parametric import run_grid

    scales = parse_scales(args.scales)
    out = Path(args.out)
    if out.suffix.lower() not in (".parquet", ".csv"):
        raise CLIError(f"--out {out}: expected a .parquet or .csv file name")
    with open_fmu(args.fmu) as fmu:
        cases = load_cases(args.cases, fmu)
        records, vertical = collect_records(args.records, args.component, args.units, args.fmt)
        if any(p.get("vertical") for p in cases.values()):
            records = attach_verticals(records, args.units)
        if vertical:
            print(f"sweep: {len(vertical)} vertical component(s) left out (ag is horizontal): "
                  f"{', '.join(vertical)}", file=sys.stderr)
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


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    from ..presets import NAMING

    p = sub.add_parser(
        "sweep", parents=[common], allow_abbrev=False, help="cases x records x scales in parallel -> parquet",
        description=textwrap.fill(
            "Every case of CASES.toml under every horizontal record component of --records, at every scale, "
            "in parallel processes; one row per run (case, parameters, record, scale, overturned, "
            "t_overturn, peak_theta_over_alpha, impacts, ..., error).", 100),
        epilog=textwrap.fill(PRECEDENCE, 100) + "\n"
               "e.g.\n  [cases.soft]\n  preset = \"dharahara-F170-fm5\"\n  [cases.block]\n  shape = \"solidRectangle\"\n"
               "  B = 0.5\n  H = 2.5\n  interface = \"rigid\"\n"
               + textwrap.fill(f"presets: {NAMING}.", 100),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("cases", metavar="CASES.toml")
    p.add_argument("--records", action="append", required=True, metavar="DIR",
                   help="a folder (searched recursively; every horizontal component of every file) or a record "
                        "file; repeatable. Vertical components are left out (the FMU's ag is horizontal)")
    p.add_argument("--component", help="only this horizontal component of each file (label or index)")
    add_record_options(p)
    p.add_argument("--scales", default="1", help="start:stop:step (stop included), a,b,c or one number (default 1)")
    p.add_argument("--out", required=True, metavar="FILE", help="results, .parquet or .csv")
    p.add_argument("--workers", type=int, help="processes (default: the CPU count)")
    p.add_argument("--stop-time", type=seconds(0, strict=False), metavar="S", help="default: each record's end")
    p.add_argument("--rtol", type=float, help="the integrator's relative tolerance (default: the FMU's)")
    p.add_argument("--fmu", metavar="PATH", help=FMU_HELP)
    p.set_defaults(func=cmd_sweep)
