"""`rocking sweep`: cases x records x scales in parallel processes -> parquet or CSV."""

import argparse
import math
import os
import sys
import textwrap
import time
import tomllib
from pathlib import Path

from .common import FMU_HELP, CLIError, check_parameter, open_fmu, read_record

#: Files that `--records DIR` passes over (documentation, scripts, results).
NOT_RECORDS = {".md", ".py", ".toml", ".json", ".png", ".pdf", ".svg", ".parquet", ".zip", ".gz"}


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
    from .. import groundmotion as gm
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

    from ..parametric import run_grid

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


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    from ..presets import NAMING

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
    p.add_argument("--fmu", metavar="PATH", help=FMU_HELP)
    p.set_defaults(func=cmd_sweep)
