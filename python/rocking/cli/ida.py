"""`rocking ida` and `rocking msa`: fragility studies over a suite of records on Dask.

    rocking ida SUITE_OR_TOML [--preset NAME ...] [--params FILE ...] [--im PGV] --out DIR
                [--scheduler ADDRESS | --workers N] [--max-runs 80] [--grid N] [--hazard CSV] ...
    rocking msa SUITE_OR_TOML ... --stripes 0.1:1.5:0.1 --out DIR

SUITE_OR_TOML is a folder of records (or one record file), with the bodies
from --preset/--params, or a study file (TOML; its format is STUDY_FILE_HELP
below, which `--help` prints).

Writes DIR/runs/ (Parquet dataset, one row per run), DIR/summary.json, the
plots DIR/ida-BODY.png (ida) and DIR/fragility.png; rerunning the same
command resumes (finished tasks are skipped by key).
"""

import argparse
import math
import re
import sys
import textwrap
import time
import tomllib
from pathlib import Path

from .. import jsonfile
from .common import FMU_HELP, CLIError, check_parameter, fmu_path, open_fmu
from .sweep import parse_scales

STUDY_FILE_HELP = """SUITE_OR_TOML: a folder of records (every horizontal component of every file the readers
know: PEER AT2, CSMIP V2, GeoNet V2A, USGS SMC, npts-dt ASCII, CSV), or a study file:
  records = ["../data/ground-motions"]    # folders or files, relative to the study file
  im = "PGV"             # PGA (g), PGV (m/s), SA(T) (g, 5 %), AvgSA(T1-T2), PGA/gtana, PGV/(gtana/p),
                         # RotD50, RotDnn(PGA), RotDnn(SA(T)) (g, of the record's two components)
  stripes = "0.2:2:0.2"                   # msa: target intensities (or a list)
  max_runs = 80                           # ida: runs per record at most
  resolution = 0.1                        # ida: widest gap left below the first collapse
  damage_states = { uplift = 0.05, DS1 = 0.2, DS2 = 0.5 }   # on peak |theta| / alpha
  damage_capacity = "bracket"             # ida: or "interpolate" (the IDA curve at the threshold)
  beta_modelling = 0.25                   # FEMA P-58 modelling dispersion (SRSS with beta)
  hazard = "hazard.csv"                   # intensity, annual frequency of exceedance
  mce = 0.9                               # the MCE intensity: collapse margin ratio
  vertical = true        # each record's matching vertical component as av, scaled alike
  [bodies.tower]
  preset = "dharahara-rigid"
  [bodies.block]
  preset = "fig15-alpha0.20-shiftingPivot"
  theta = 0.0
Options on the command line override the file's. --scheduler ADDRESS: workers started with
`dask worker ADDRESS --nthreads 1` in an environment with the rocking package."""

#: Study-file keys -> the command-line option of the same meaning.
OPTIONS = {"records": "--records", "im": "--im", "stripes": "--stripes", "max_runs": "--max-runs",
           "tol": "--tol", "resolution": "--resolution", "grid": "--grid", "tail": "--tail", "rtol": "--rtol",
           "chunk": "--chunk", "beta_estimator": "--beta-estimator", "beta_modelling": "--beta-modelling",
           "damage_states": "--damage-states", "damage_capacity": "--damage-capacity", "bootstrap": "--bootstrap",
           "hazard": "--hazard", "mce": "--mce", "years": "--years", "vertical": "--vertical"}
STUDY_KEYS = set(OPTIONS) | {"bodies"}


def register(sub, common):
    """Add the `ida` and `msa` subcommands to the subparsers `sub` of the `rocking` parser."""
    for method in ("ida", "msa"):
        what = ("incremental dynamic analysis: each record's first collapse, by a hunt, a scan below it and a bracket"
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
        p.add_argument("--im", help="intensity measure: PGA, PGV, SA(T), AvgSA(T1-T2), PGA/gtana, "
                                    "PGV/(gtana/p), or of both horizontal components RotDnn (of PGA) and "
                                    "RotDnn(SA(T)), e.g. RotD50 (default PGA/gtana)")
        if method == "msa":
            p.add_argument("--stripes", help="target intensities: start:stop:step or a,b,c")
        else:
            p.add_argument("--max-runs", type=int, help="runs per record at most (default 80)")
            p.add_argument("--tol", type=float, help="relative width of the collapse bracket (default 0.05)")
            p.add_argument("--resolution", type=float,
                           help="widest relative gap left between runs below the first collapse (default 0.1)")
            p.add_argument("--grid", type=int, metavar="N",
                           help="dense-grid IDA: every record at N intensities (geometric, from the uplift "
                                "intensity to 50 times it) instead of the hunt")
            p.add_argument("--beta-estimator", choices=("mle", "moments"),
                           help="beta of the IDA fit: mle (1/n, default) or moments (n-1, Baker)")
            p.add_argument("--damage-capacity", choices=("bracket", "interpolate"),
                           help="a damage state's capacity: bracket (searched for as overturning is, default) "
                                "or interpolate (the IDA curve at the threshold, Vamvatsikos & Cornell 2002)")
        p.add_argument("--chunk", type=int,
                       help="runs per task of stripes or grid (default: about half a second of runs a task)")
        p.add_argument("--tail", type=float, help="seconds simulated after each record's end (default 5)")
        p.add_argument("--rtol", type=float, help="the integrator's relative tolerance (default: the FMU's)")
        p.add_argument("--damage-states", metavar="NAME=T,...",
                       help="limit states on peak |theta| / alpha fitted beside overturning, e.g. DS1=0.2,DS2=0.5")
        p.add_argument("--beta-modelling", type=float,
                       help="modelling dispersion combined with beta as FEMA P-58 does (SRSS; default 0)")
        p.add_argument("--bootstrap", choices=("stations", "records"),
                       help="what the bootstrap resamples (default stations: a station's components together)")
        p.add_argument("--hazard", metavar="CSV", help="hazard curve: intensity, annual frequency of exceedance")
        p.add_argument("--mce", type=float, help="the MCE intensity, for the collapse margin ratio")
        p.add_argument("--years", type=float, help="years of the collapse probability (default 50)")
        p.add_argument("--vertical", action="store_const", const=True, default=None,
                       help="run each record with its set's vertical component as av (the FMU's input), "
                            "scaled by the same factor as the horizontal one")
        p.add_argument("--out", required=True, metavar="DIR", help="output folder (resumed if it holds runs)")
        p.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler, e.g. tcp://host:8786")
        p.add_argument("--workers", type=int, help="LocalCluster worker processes (default: one per core)")
        p.add_argument("--boot", type=int, default=1000, help="bootstrap resamples (default 1000; 0: none)")
        p.add_argument("--fmu", metavar="PATH", help=FMU_HELP)
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


def gather(args, fmu, source, data, base):
    """(bodies, suite) from the command line and the study file (`_source`)."""
    from ..fragility.suite import load_suite
    from .common import read_params_file

    recs = data.get("records", [])
    sources = [base / r for r in ([recs] if isinstance(recs, str) else recs)]
    sources += [Path(r) for r in args.records or []]
    if source.suffix.lower() != ".toml":
        sources.insert(0, source)
    if not sources:
        raise CLIError(f"{source}: no records: give `records = [...]` or --records DIR")
    try:
        suite = load_suite(sources)
    except (FileNotFoundError, ValueError) as exc:
        raise CLIError(str(exc)) from None
    vertical, where = _pick(args, data, "vertical", source)
    if vertical is not None and not isinstance(vertical, bool):
        raise CLIError(f"{where}: expected true or false, found {vertical!r}")
    if vertical:
        suite = with_verticals(suite, where)

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
    return bodies, suite


def with_verticals(suite, where):
    """{name: Record carrying its set's vertical component as av_record}; CLIError naming the
    first record that has none (the IM stays the horizontal one's)."""
    from .. import groundmotion as gm
    try:
        return {name: gm.with_vertical(rec) for name, rec in suite.items()}
    except ValueError as exc:
        raise CLIError(f"{where}: {exc}") from None


def _source(args):
    """(source path, study-file data, base folder for its relative paths)."""
    source = Path(args.source)
    if source.suffix.lower() == ".toml":
        if not source.is_file():
            raise CLIError(f"{source}: no such study file")
        data = _read_study_file(source)
        records = data.get("records", [])
        if not (isinstance(records, str) or (isinstance(records, list) and all(isinstance(r, str) for r in records))):
            raise CLIError(f"{source}: records: expected a folder or file name, or a list of them")
        return source, data, source.parent
    if not source.exists():
        raise CLIError(f"{source}: no such record folder, record file or study file")
    return source, {}, Path.cwd()


def _pick(args, data, key, source):
    """(value, name): the option's value if given, else the study file's; name says where."""
    value = getattr(args, key, None)
    if value is not None:
        return value, OPTIONS[key]
    return data.get(key), f"{source}: {key}"


def _number(value, name, kind=float, minimum=None, open_min=False, maximum=None):
    """`value` as a finite `kind` within the bounds; CLIError naming `name` otherwise."""
    ok = isinstance(value, (int, float)) and not isinstance(value, bool)
    if ok and kind is int and isinstance(value, float):
        ok = value.is_integer()
    if ok:
        value = kind(value)
        ok = math.isfinite(value) and (minimum is None or (value > minimum if open_min else value >= minimum)) \
            and (maximum is None or value < maximum)
    if not ok:
        what = "an integer" if kind is int else "a finite number"
        bounds = []
        if minimum is not None:
            bounds.append(f"{'>' if open_min else '>='} {minimum:g}")
        if maximum is not None:
            bounds.append(f"< {maximum:g}")
        raise CLIError(f"{name} {value!r}: expected {what}{' ' + ' and '.join(bounds) if bounds else ''}")
    return value


def _intensities(value, name):
    """Target intensities from 'start:stop:step', 'a,b,c' or a list: finite, positive, at least one."""
    if isinstance(value, str):
        try:
            values = parse_scales(value)
        except CLIError:
            raise CLIError(f"{name} {value!r}: expected start:stop:step (step > 0, stop >= start), "
                           "a list a,b,c or one number") from None
    elif isinstance(value, list):
        values = value
    else:
        raise CLIError(f"{name}: expected a list of intensities or 'start:stop:step'")
    if not values:
        raise CLIError(f"{name}: no intensities")
    return tuple(_number(v, name, float, 0.0, open_min=True) for v in values)


def _damage_states(value, name):
    """{state: threshold on peak |theta| / alpha} from 'A=0.2,B=0.5' or a TOML table."""
    if isinstance(value, str):
        table = {}
        for part in filter(None, (p.strip() for p in value.split(","))):
            key, eq, number = part.partition("=")
            if not eq or not key.strip():
                raise CLIError(f"{name} {part!r}: expected NAME=THRESHOLD, e.g. DS1=0.2")
            try:
                table[key.strip()] = float(number)
            except ValueError:
                raise CLIError(f"{name} {part!r}: the threshold is not a number") from None
    elif isinstance(value, dict):
        table = value
    else:
        raise CLIError(f"{name}: expected a table of NAME = threshold on peak |theta| / alpha")
    states = {}
    for key, thr in table.items():
        if key == "overturning":
            raise CLIError(f"{name}: 'overturning' is always fitted; name the damage states otherwise")
        states[key] = _number(thr, f"{name}.{key}", float, 0.0, open_min=True)
    return states


def study_options(args, data, source):
    """The study's options, each checked: CLIError naming the option (or the study file's key)."""
    from ..fragility import intensity, risk

    im_value, im_name = _pick(args, data, "im", source)
    try:
        im = intensity.parse(str(im_value if im_value is not None else "PGA/gtana"))
    except ValueError as exc:
        raise CLIError(f"{im_name}: {exc}") from None

    def pick(key, default, *check, **bounds):
        value, name = _pick(args, data, key, source)
        return default if value is None else (check[0](value, name, **bounds) if check else value)

    opts = dict(im=im, tail=pick("tail", 5.0, _number, minimum=0.0),
                rtol=pick("rtol", None, _number, minimum=0.0, open_min=True, maximum=1.0),
                chunk=pick("chunk", 0, _number, kind=int, minimum=1),
                beta_modelling=pick("beta_modelling", 0.0, _number, minimum=0.0),
                damage_states=pick("damage_states", {}, _damage_states),
                years=pick("years", 50.0, _number, minimum=0.0, open_min=True),
                mce=pick("mce", None, _number, minimum=0.0, open_min=True))
    boot, name = _pick(args, data, "bootstrap", source)
    if boot not in (None, "stations", "records"):
        raise CLIError(f"{name} {boot!r}: expected 'stations' or 'records'")
    opts["by_station"] = boot != "records"
    hazard, name = _pick(args, data, "hazard", source)
    opts["hazard"] = None
    if hazard is not None:
        path = Path(hazard) if name.startswith("--") else source.parent / str(hazard)
        try:
            opts["hazard"] = risk.read_hazard(path)
        except ValueError as exc:
            raise CLIError(f"{name}: {exc}") from None
    if args.method == "msa":
        stripes, name = _pick(args, data, "stripes", source)
        if stripes is None:
            raise CLIError("msa: give the target intensities, --stripes start:stop:step or `stripes = [...]`")
        opts["stripes"] = _intensities(stripes, name)
    else:
        opts["max_runs"] = pick("max_runs", 80, _number, kind=int, minimum=2)
        opts["tol"] = pick("tol", 0.05, _number, minimum=0.0, open_min=True)
        opts["resolution"] = pick("resolution", 0.1, _number, minimum=0.0, open_min=True)
        opts["grid"] = pick("grid", 0, _number, kind=int, minimum=2)
        est, name = _pick(args, data, "beta_estimator", source)
        if est not in (None, "mle", "moments"):
            raise CLIError(f"{name} {est!r}: expected 'mle' or 'moments'")
        opts["estimator"] = est or "mle"
        how, name = _pick(args, data, "damage_capacity", source)
        if how not in (None, "bracket", "interpolate"):
            raise CLIError(f"{name} {how!r}: expected 'bracket' or 'interpolate'")
        opts["damage_capacity"] = how or "bracket"
    if args.workers is not None:
        _number(args.workers, "--workers", int, 1)
    _number(args.boot, "--boot", int, 0)
    return opts


# ---------------------------------------------------------------------------
# The command

def cmd_study(args, _params):
    from ..fragility import cluster
    from ..fragility.hunt import HuntOptions
    from ..fragility.store import ResultStore
    from ..fragility.study import Study

    out = Path(args.out)
    source, data, base = _source(args)
    opts = study_options(args, data, source)  # every option checked before anything runs
    im = opts["im"]
    path = fmu_path(args.fmu)
    with open_fmu(args.fmu) as fmu:
        bodies, suite = gather(args, fmu, source, data, base)
        study = Study(bodies=bodies, suite=suite, im=im, method=args.method, tail=opts["tail"], rtol=opts["rtol"],
                      chunk=opts["chunk"], beta_modelling=opts["beta_modelling"],
                      damage_states=opts["damage_states"], by_station=opts["by_station"])
        if args.method == "msa":
            study.stripes = opts["stripes"]
        else:
            study.hunt = HuntOptions(max_runs=opts["max_runs"], tol=opts["tol"], resolution=opts["resolution"])
            study.grid, study.estimator = opts["grid"], opts["estimator"]
            study.damage_capacity = opts["damage_capacity"]
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
    summary = write_outputs(out, study, df, result, args, opts)
    print(summary)
    return 0 if not failures else 1


def run_tasks(args, fmu_file, todo, store):
    """Run `todo` on the cluster with a progress bar; {key: error} of the tasks that failed."""
    from tqdm import tqdm

    from ..fragility import cluster

    with cluster.open_client(args.scheduler, args.workers) as client:
        cluster.register_fmu(client, fmu_file)
        t0 = time.perf_counter()
        with tqdm(file=sys.stderr, dynamic_ncols=True, mininterval=0.5, smoothing=0.1,
                  **progress_counts(todo, args.method)) as bar:
            _, runs, failures = cluster.execute(client, todo, store, progress_callback(bar, todo))
        wall = time.perf_counter() - t0
    print(f"{args.method}: {runs} runs in {wall:.1f} s ({runs / wall if wall else 0:.2f} runs/s)"
          + (f"; {len(failures)} task(s) failed, rerun the command to retry them" if failures else ""),
          file=sys.stderr)
    for key, err in list(failures.items())[:3]:
        print(f"  {key}: {err}", file=sys.stderr)
    return failures


def _searches(todo):
    """Whether `todo` are IDA searches, whose runs are known only when each ends (the 4th item
    of a task, max_runs, is a bound), not runs at fixed intensities (exact counts)."""
    from ..fragility import runner
    return any(t[1] is runner.run_hunt for t in todo)


def progress_counts(todo, method):
    """tqdm's total, unit and description for `todo`: the runs of tasks at fixed intensities
    (known in advance), or the records of IDA searches (each one's runs known when it ends)."""
    if _searches(todo):
        return dict(total=len(todo), unit="record", desc=f"{method} (records searched)")
    return dict(total=sum(t[3] for t in todo), unit="run", desc=method)


def progress_callback(bar, todo):
    """progress(rows, expected) for cluster.execute that advances `bar` (progress_counts) by a
    record per search and shows the runs so far, or by the runs of a task at fixed intensities."""
    if not _searches(todo):
        return lambda rows, _expected: bar.update(rows)
    runs = [0]

    def progress(rows, _expected):
        runs[0] += rows
        bar.set_postfix_str(f"{runs[0]} runs", refresh=False)
        bar.update(1)
    return progress


def _safe(name):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name)


def _fit_line(f, unit, study):
    """(fit, interval) in words: median, beta and estimator; the bootstrap's intervals and how
    many resamples could not be fitted ('' without a bootstrap)."""
    est = "moments, n-1" if f.estimator == "moments" else "MLE"
    text = f"median {f.median:.4g} {unit}, beta {f.beta:.3f} ({est})"
    if f.beta_modelling:
        text += f", beta_total {f.beta_total:.3f} with beta_modelling {f.beta_modelling:g}"
    boot = ""
    if math.isfinite(f.median_ci[0]):
        from ..fragility.study import station_of
        groups = (f"{len({station_of(n) for n in study.suite})} stations" if study.by_station
                  else f"{len(study.suite)} records")
        boot = (f"{f.level:.0%} bootstrap over {groups}: median [{f.median_ci[0]:.4g}, {f.median_ci[1]:.4g}], "
                f"beta [{f.beta_ci[0]:.3f}, {f.beta_ci[1]:.3f}]")
        if f.boot_undetermined:
            total = len(f.boot[0]) + f.boot_undetermined
            boot += f" ({f.boot_undetermined} of {total} resamples undetermined, left out"
            boot += "; the interval is unreliable)" if f.boot_undetermined > 0.1 * total else ")"
    return text, boot


def _censored_words(f, never):
    """', 2 censored (no collapse up to their last run), 1 at the floor (...)' of a Fragility."""
    text = f", {f.censored} censored ({never} up to their last run)" if f.censored else ""
    if f.censored_below:
        text += (f", {f.censored_below} censored from below (reached already at the lowest run, "
                 "the search's floor)")
    return text


def _fit_json(entry, risk_of=None):
    f = entry["fragility"]
    if f is None:
        return dict(median=None, beta=None, error=entry["error"])
    out = dict(median=f.median, beta=f.beta, estimator=f.estimator, beta_modelling=f.beta_modelling,
               beta_total=f.beta_total, median_ci=list(f.median_ci), beta_ci=list(f.beta_ci), level=f.level, n=f.n,
               censored=f.censored, censored_below=f.censored_below, bootstrap_fits=len(f.boot[0]),
               bootstrap_undetermined=f.boot_undetermined,
               goodness_of_fit=f.gof, error="")
    if risk_of is not None:
        out["risk"] = risk_of(f)
    return out


def write_outputs(out, study, df, result, args, opts):
    """summary.json, the plots; returns the printed summary."""
    from ..fragility import plots, risk

    failed = df[df["error"] != ""]
    lines, bodies_json, fits = [], {}, {}
    im = study.im
    mode = f"dense grid of {study.grid}" if study.method == "ida" and study.grid else ""
    lines.append(f"{study.method.upper()}{' (' + mode + ')' if mode else ''} over {len(study.suite)} record(s), "
                 f"IM = {im.name} ({im.unit}); {len(df)} runs, {len(failed)} failed")
    hazard = opts.get("hazard")

    def risk_of(f):
        if hazard is None:  # the margin ratio needs no hazard curve
            return None if opts.get("mce") is None else dict(cmr=risk.margin_ratio(f.median, opts["mce"]))
        return risk.risk(f, hazard, opts.get("mce"), opts.get("years", 50.0))

    for body, entry in result.items():
        f = entry["fragility"]
        rows = df[df["body"] == body]
        if f is None:
            lines.append(f"  {body}: no fit: {entry['error']}")
        else:
            cens = _censored_words(f, "no collapse")
            text, boot = _fit_line(f, im.unit, study)
            lines.append(f"  {body}: {text}, n = {f.n}{cens}")
            if boot:
                lines.append(f"    {boot}")
            lines.append(f"    goodness of fit: {f.gof.get('text', 'not tested')}")
            r = risk_of(f)
            if r is not None and "maf" not in r:
                lines.append(f"    collapse margin ratio {r['cmr']:.3g} (median over the MCE intensity {opts['mce']:g})")
            elif r is not None:
                lines.append(f"    risk: MAF of collapse {r['maf']:.3g} /yr, P(collapse in {r['years']:g} yr) "
                             f"{100 * r['p_years']:.3g} %" + (f", CMR {r['cmr']:.3g}" if r["cmr"] is not None else "")
                             + (f" ({100 * r['outside']:.2g} % of the fragility beyond the hazard curve, "
                                "extended as a power law)" if r["outside"] > 0.01 else ""))
        for name, thr in study.states()[:-1]:
            st = entry["states"][name]
            g = st["fragility"]
            text = (_fit_line(g, im.unit, study)[0] + _censored_words(g, "not reached") if g is not None
                    else f"no fit: {st['error']}")
            if g is not None and g.boot_undetermined > 0.1 * (len(g.boot[0]) + g.boot_undetermined):
                text += (f"; bootstrap unreliable ({g.boot_undetermined} of "
                         f"{len(g.boot[0]) + g.boot_undetermined} resamples undetermined)")
            lines.append(f"    {name} (peak |theta| / alpha >= {thr:g}): {text}")
        unresolved = {r: v["unresolved"] for r, v in entry["records"].items() if v.get("unresolved")}
        if unresolved:
            lines.append(f"    {len(unresolved)} record(s) UNRESOLVED (run budget spent; --max-runs):")
            lines += [f"      {r}: {why}" for r, why in list(unresolved.items())[:6]]
            if len(unresolved) > 6:
                lines.append(f"      ... and {len(unresolved) - 6} more (summary.json)")
        bodies_json[body] = dict(
            _fit_json(dict(fragility=f, error=entry["error"]), risk_of),
            alpha=float(rows["alpha"].iloc[0]) if len(rows) else None, parameters=study.bodies[body],
            damage_states={name: dict(_fit_json(entry["states"][name]), threshold=thr)
                           for name, thr in study.states()[:-1]},
            records=entry["records"], unresolved_records=len(unresolved), runs=int(len(rows)))
        if study.method == "ida":
            fine = [r for r in entry["records"].values() if "error" not in r]
            caps = [r["capacity"] for r in fine if not (r["censored"] or r.get("below"))]
            cens_n = sum(bool(r["censored"] or r.get("below")) for r in fine)
            fits[body] = (f, (caps, cens_n))
            plots.plot_ida(out / f"ida-{_safe(body)}.png", rows, entry, im, f"IDA: {body}")
        else:
            ok = rows[rows["error"] == ""]
            g = ok.groupby(ok["im"].round(12))["overturned"]
            fits[body] = (f, (g.mean().index.to_numpy(), g.mean().to_numpy(float), g.count().to_numpy()))
    states = {body: {name: entry["states"][name]["fragility"] for name, _ in study.states()[:-1]}
              for body, entry in result.items()}
    plots.plot_fragility(out / "fragility.png", fits, im, f"Fragility ({study.method.upper()}, "
                         f"{len(study.suite)} record components)", study.method, states)
    stand_in = [n for n, r in study.suite.items() if "stand-in" in (r.notes or "").lower()]
    from ..fragility.study import station_of
    options = dict(tail=study.tail, rtol=study.rtol, chunk=study.chunk, beta_modelling=study.beta_modelling,
                   damage_states=study.damage_states, bootstrap="stations" if study.by_station else "records",
                   boot=args.boot, mce=opts.get("mce"), years=opts.get("years"))
    if study.method == "ida":
        options.update(vars(study.hunt), grid=study.grid, beta_estimator=study.estimator,
                       damage_capacity=study.damage_capacity)
    else:
        options.update(stripes=list(study.stripes))
    summary = dict(method=study.method, im=im.name, im_unit=im.unit, records=list(study.suite),
                   stations={n: station_of(n) for n in study.suite}, synthetic_records=stand_in, options=options,
                   runs=int(len(df)), failed_runs=int(len(failed)), bodies=bodies_json,
                   vertical={n: f"{r.av_record.source} [{r.av_record.component}]"
                             for n, r in study.suite.items() if r.av_record is not None} or None)
    jsonfile.write(out / "summary.json", summary)
    lines.append(f"wrote {out / 'runs'}/, {out / 'summary.json'}, {out / 'fragility.png'}"
                 + (", ida-*.png" if study.method == "ida" else ""))
    return "\n".join(lines)


