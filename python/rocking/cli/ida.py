"""`rocking ida` and `rocking msa`: fragility studies over a suite of records on Dask.

    rocking ida SUITE_OR_TOML [--preset NAME ...] [--params FILE ...] [--im PGV] --out DIR
                [--scheduler ADDRESS | --workers N] [--max-runs 12] [--tail 5] ...
    rocking msa SUITE_OR_TOML ... --stripes 0.1:1.5:0.1 --out DIR

SUITE_OR_TOML is a folder of records (or one record file), with the bodies
from --preset/--params, or a study file (TOML; its format is STUDY_FILE_HELP
below, which `--help` prints).

Writes DIR/runs/ (Parquet dataset, one row per run), DIR/summary.json, the
plots DIR/ida-BODY.png (ida) and DIR/fragility.png; rerunning the same
command resumes (finished tasks are skipped by key).
"""

import argparse
import json
import math
import re
import sys
import textwrap
import time
import tomllib
from pathlib import Path

from .common import CLIError, check_parameter, fmu_path, open_fmu
from .sweep import parse_scales

STUDY_FILE_HELP = """SUITE_OR_TOML: a folder of records (every horizontal component of every file the readers
know: PEER AT2, CSMIP V2, GeoNet V2A, USGS SMC, npts-dt ASCII, CSV), or a study file:
  records = ["../data/ground-motions"]    # folders or files, relative to the study file
  im = "PGV"                              # PGA (g), PGV (m/s), SA(T) (g, 5 %), PGA/gtana
  stripes = "0.2:2:0.2"                   # msa: target intensities (or a list)
  max_runs = 12                           # ida: runs per record
  [bodies.tower]
  preset = "dharahara-rigid"
  [bodies.block]
  preset = "fig15-alpha0.20-shiftingPivot"
  theta = 0.0
Options on the command line override the file's. --scheduler ADDRESS: workers started with
`dask worker ADDRESS --nthreads 1` in an environment with the rocking package."""

STUDY_KEYS = {"records", "im", "stripes", "max_runs", "tol", "tail", "rtol", "chunk", "bodies"}


def register(sub, common):
    """Add the `ida` and `msa` subcommands to the subparsers `sub` of the `rocking` parser."""
    for method in ("ida", "msa"):
        what = ("incremental dynamic analysis: each record scaled by hunt-and-fill until the body overturns"
                if method == "ida" else "multiple stripes: every record at each target intensity")
        p = sub.add_parser(
            method, parents=[common], allow_abbrev=False, help=f"fragility by {what.split(':')[0]} (Dask)",
            description=textwrap.fill(
                f"Fragility study by {what}, on a Dask LocalCluster (one worker process per core) or the "
                "cluster of --scheduler; lognormal fit by maximum likelihood with a bootstrap interval. "
                "Writes DIR/runs/ (Parquet, one row per run), DIR/summary.json and plots; rerunning the "
                "same command resumes.", 100),
            epilog=STUDY_FILE_HELP, formatter_class=argparse.RawDescriptionHelpFormatter)
        p.add_argument("source", metavar="SUITE_OR_TOML", help="a folder of records, a record file, or a study .toml")
        p.add_argument("--records", action="append", metavar="DIR", help="more record folders or files (repeatable)")
        p.add_argument("--preset", action="append", metavar="NAME", help="a body by preset name (repeatable)")
        p.add_argument("--params", action="append", metavar="FILE",
                       help="a body from a JSON object of parameters (repeatable; named by the file)")
        p.add_argument("--im", help="intensity measure: PGA, PGV, SA(T) or PGA/gtana (default PGA/gtana)")
        if method == "msa":
            p.add_argument("--stripes", help="target intensities: start:stop:step or a,b,c")
            p.add_argument("--chunk", type=int, help="stripe runs per task (default 10)")
        else:
            p.add_argument("--max-runs", type=int, help="runs per record (default 12)")
            p.add_argument("--tol", type=float, help="relative width of the collapse bracket (default 0.05)")
        p.add_argument("--tail", type=float, help="seconds simulated after each record's end (default 5)")
        p.add_argument("--rtol", type=float, help="the integrator's relative tolerance (default: the FMU's)")
        p.add_argument("--out", required=True, metavar="DIR", help="output folder (resumed if it holds runs)")
        p.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler, e.g. tcp://host:8786")
        p.add_argument("--workers", type=int, help="LocalCluster worker processes (default: one per core)")
        p.add_argument("--boot", type=int, default=1000, help="bootstrap resamples (default 1000; 0: none)")
        p.add_argument("--fmu", metavar="PATH", help="the FMU (default: target/fmu/RockingBlock.fmu)")
        p.set_defaults(func=cmd_study, method=method)


# ---------------------------------------------------------------------------
# What is asked

def _read_study_file(path):
    try:
        data = tomllib.loads(path.read_text())
    except OSError as exc:
        raise CLIError(f"{path}: cannot read ({exc.strerror or exc})") from None
    except tomllib.TOMLDecodeError as exc:
        raise CLIError(f"{path}: not valid TOML: {exc}") from None
    unknown = set(data) - STUDY_KEYS
    if unknown:
        raise CLIError(f"{path}: unknown key(s) {', '.join(sorted(unknown))}: expected {', '.join(sorted(STUDY_KEYS))}")
    return data


def _body(fmu, table, where):
    from .. import presets as presets_module
    params = {}
    preset_name = table.get("preset")
    if preset_name is not None:
        try:
            params.update(presets_module.preset(str(preset_name)))
        except KeyError as exc:
            raise CLIError(f"{where}.preset: {exc.args[0]}") from None
    for name, value in table.items():
        if name != "preset":
            params[name] = value
    return {name: check_parameter(fmu, name, value, f"{where}.{name}") for name, value in params.items()}


def gather(args, fmu):
    """(bodies, suite, im, options) from the command line and the study file."""
    from ..fragility import intensity
    from ..fragility.suite import load_suite
    from .common import read_params_file

    source = Path(args.source)
    data, base = {}, Path.cwd()
    sources = []
    if source.suffix.lower() == ".toml":
        if not source.is_file():
            raise CLIError(f"{source}: no such study file")
        data, base = _read_study_file(source), source.parent
        recs = data.get("records", [])
        sources = [base / r for r in ([recs] if isinstance(recs, str) else recs)]
    elif source.exists():
        sources = [source]
    else:
        raise CLIError(f"{source}: no such record folder, record file or study file")
    sources += [Path(r) for r in args.records or []]
    if not sources:
        raise CLIError(f"{source}: no records: give `records = [...]` or --records DIR")
    try:
        suite = load_suite(sources)
    except (FileNotFoundError, ValueError) as exc:
        raise CLIError(str(exc)) from None

    bodies = {}
    for name, table in (data.get("bodies") or {}).items():
        if not isinstance(table, dict):
            raise CLIError(f"{source}: bodies.{name}: expected a table of parameters")
        bodies[name] = _body(fmu, table, f"{source}: bodies.{name}")
    for name in args.preset or []:
        bodies[name] = _body(fmu, {"preset": name}, "--preset")
    for file in args.params or []:
        bodies[Path(file).stem] = _body(fmu, read_params_file(file), str(file))
    if not bodies:
        raise CLIError("no body: give --preset NAME, --params FILE or [bodies.NAME] tables in a study file")

    try:
        im = intensity.parse(str(args.im or data.get("im", "PGA/gtana")))
    except ValueError as exc:
        raise CLIError(f"--im: {exc}") from None
    opts = dict(tail=_pick(args, data, "tail", 5.0), rtol=_pick(args, data, "rtol", None))
    if args.method == "msa":
        stripes = args.stripes or data.get("stripes")
        if stripes is None:
            raise CLIError("msa: give the target intensities, --stripes start:stop:step or `stripes = [...]`")
        opts["stripes"] = tuple(parse_scales(stripes) if isinstance(stripes, str) else map(float, stripes))
        if min(opts["stripes"]) <= 0:
            raise CLIError("--stripes: target intensities must be positive")
        opts["chunk"] = _pick(args, data, "chunk", 10)
    else:
        opts["max_runs"] = _pick(args, data, "max_runs", 12)
        opts["tol"] = _pick(args, data, "tol", 0.05)
    return bodies, suite, im, opts


def _pick(args, data, name, default):
    value = getattr(args, name, None)
    return value if value is not None else data.get(name, default)


# ---------------------------------------------------------------------------
# The command

def cmd_study(args, _params):
    from ..fragility import cluster
    from ..fragility.hunt import HuntOptions
    from ..fragility.store import ResultStore
    from ..fragility.study import Study

    out = Path(args.out)
    path = fmu_path(args.fmu)
    with open_fmu(args.fmu) as fmu:
        bodies, suite, im, opts = gather(args, fmu)
        study = Study(bodies=bodies, suite=suite, im=im, method=args.method, tail=opts["tail"], rtol=opts["rtol"])
        if args.method == "msa":
            study.stripes, study.chunk = opts["stripes"], opts["chunk"]
        else:
            study.hunt = HuntOptions(max_runs=opts["max_runs"], tol=opts["tol"])
        store = ResultStore(out / "runs")
        try:
            tasks = study.tasks(fmu, cluster.fmu_digest(path))
        except ValueError as exc:
            raise CLIError(str(exc)) from None
        done = store.finished(t[0] for t in tasks)
        todo = [t for t in tasks if t[0] not in done]
        print(f"{args.method}: {len(bodies)} body(ies) x {len(suite)} record(s), IM {im.name}: "
              f"{len(tasks)} tasks, {len(tasks) - len(todo)} already in {store.path} (skipped)",
              file=sys.stderr, flush=True)
        failures = {}
        if todo:
            failures = run_tasks(args, path, todo, store)

    df = store.read()
    df = df[df["task"].isin({t[0] for t in tasks})]
    result = study.analyse(df, n_boot=args.boot)
    summary = write_outputs(out, study, df, result, args)
    print(summary)
    return 0 if not failures else 1


def run_tasks(args, fmu_file, todo, store):
    """Run `todo` on the cluster with a progress bar; {key: error} of the tasks that failed."""
    from tqdm import tqdm

    from ..fragility import cluster

    with cluster.open_client(args.scheduler, args.workers) as client:
        cluster.register_fmu(client, fmu_file)
        t0 = time.perf_counter()
        with tqdm(total=sum(t[3] for t in todo), unit="run", desc=args.method, file=sys.stderr,
                  dynamic_ncols=True, mininterval=0.5, smoothing=0.1) as bar:
            def progress(rows, expected):
                if rows != expected:
                    bar.total -= expected - rows
                bar.update(rows)
            _, runs, failures = cluster.execute(client, todo, store, progress)
        wall = time.perf_counter() - t0
    print(f"{args.method}: {runs} runs in {wall:.1f} s ({runs / wall if wall else 0:.2f} runs/s)"
          + (f"; {len(failures)} task(s) failed, rerun the command to retry them" if failures else ""),
          file=sys.stderr)
    for key, err in list(failures.items())[:3]:
        print(f"  {key}: {err}", file=sys.stderr)
    return failures


def _safe(name):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name)


def write_outputs(out, study, df, result, args):
    """summary.json, the plots; returns the printed summary."""
    from ..fragility import plots

    failed = df[df["error"] != ""]
    lines, bodies_json, fits = [], {}, {}
    im = study.im
    lines.append(f"{study.method.upper()} over {len(study.suite)} record(s), IM = {im.name} ({im.unit}); "
                 f"{len(df)} runs, {len(failed)} failed")
    for body, entry in result.items():
        f = entry["fragility"]
        rows = df[df["body"] == body]
        if f is None:
            lines.append(f"  {body}: no fragility ({entry['error']})")
        else:
            ci = (f" ({f.level:.0%} bootstrap: median [{f.median_ci[0]:.4g}, {f.median_ci[1]:.4g}], "
                  f"beta [{f.beta_ci[0]:.3f}, {f.beta_ci[1]:.3f}])" if math.isfinite(f.median_ci[0]) else "")
            cens = f", {f.censored} record(s) did not overturn up to their last run" if f.censored else ""
            lines.append(f"  {body}: median {f.median:.4g} {im.unit}, beta {f.beta:.3f}{ci}, n = {f.n}{cens}")
        bodies_json[body] = dict(
            median=None if f is None else f.median, beta=None if f is None else f.beta,
            median_ci=None if f is None else list(f.median_ci), beta_ci=None if f is None else list(f.beta_ci),
            level=None if f is None else f.level, n=None if f is None else f.n, error=entry["error"],
            alpha=float(rows["alpha"].iloc[0]) if len(rows) else None, parameters=study.bodies[body],
            records=entry["records"], runs=int(len(rows)))
        if study.method == "ida":
            fine = [r for r in entry["records"].values() if "error" not in r]
            caps = [r["capacity"] for r in fine if not r["censored"]]
            cens_n = sum(r["censored"] for r in fine)
            fits[body] = (f, (caps, cens_n))
            plots.plot_ida(out / f"ida-{_safe(body)}.png", rows, entry, im, f"IDA: {body}")
        else:
            ok = rows[rows["error"] == ""]
            g = ok.groupby(ok["im"].round(12))["overturned"]
            fits[body] = (f, (g.mean().index.to_numpy(), g.mean().to_numpy(float), g.count().to_numpy()))
    plots.plot_fragility(out / "fragility.png", fits, im, f"Fragility ({study.method.upper()}, "
                         f"{len(study.suite)} record components)", study.method)
    stand_in = [n for n, r in study.suite.items() if "stand-in" in (r.notes or "").lower()]
    summary = dict(method=study.method, im=im.name, im_unit=im.unit, records=list(study.suite),
                   synthetic_records=stand_in, options=dict(tail=study.tail, rtol=study.rtol,
                   **(dict(vars(study.hunt)) if study.method == "ida" else dict(stripes=list(study.stripes)))),
                   runs=int(len(df)), failed_runs=int(len(failed)), bodies=bodies_json)
    (out / "summary.json").write_text(json.dumps(summary, indent=2, default=_json) + "\n")
    lines.append(f"wrote {out / 'runs'}/, {out / 'summary.json'}, {out / 'fragility.png'}"
                 + (", ida-*.png" if study.method == "ida" else ""))
    return "\n".join(lines)


def _json(value):
    if hasattr(value, "item"):
        return value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    raise TypeError(type(value).__name__)
