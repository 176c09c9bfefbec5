"""`rocking spectrum`: rocking spectra of a record for a family of bodies -> DIR/spectrum.parquet,
DIR/runs.parquet, DIR/spectrum.png (docs/spectra.md)."""

import argparse
import math
import sys
import textwrap
import time
from dataclasses import dataclass, field
from pathlib import Path

from .common import FMU_HELP, CLIError, add_record_options, check_parameter, drop_unused, horizontal_record, open_fmu

#: This subcommand also takes any FMU parameter as `--NAME VALUE` (as `simulate` does).
TAKES_PARAMETERS = True

AGAINST = {"p": "p (rad/s)", "size": "R (m), the distance from the toe to the centre of mass",
           "ratio": "w_rec / p"}


@dataclass
class _Base:
    """The base body as cli.map._variant takes it (params, scales)."""

    params: dict
    scales: dict = field(default_factory=dict)


def read_bodies(fmu, path, base):
    """[(label, params)] of a JSON file: a list of objects, or an object of name -> object, of
    parameters over `base`; each checked against the FMU, CLIError naming the file and body."""
    import json

    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise CLIError(f"--bodies {path}: cannot read ({exc.strerror or exc})") from None
    except json.JSONDecodeError as exc:
        raise CLIError(f"--bodies {path}: not JSON ({exc.msg} at line {exc.lineno})") from None
    items = list(data.items()) if isinstance(data, dict) else list(enumerate(data)) if isinstance(data, list) else None
    if not items:
        raise CLIError(f"--bodies {path}: expected a non-empty list of objects (or name -> object) of parameters")
    bodies = []
    for name, values in items:
        if not isinstance(values, dict):
            raise CLIError(f"--bodies {path}: body {name}: expected an object of parameter name -> value")
        params = dict(base)
        for key, value in values.items():
            params[key] = check_parameter(fmu, key, value, f"--bodies {path}: body {name}: {key}")
        drop_unused(fmu, params)
        bodies.append((str(name) if isinstance(name, str) else f"body{name}", params))
    return bodies


def family(fmu, args, params):
    """The bodies of --p, --sizes or --bodies over the base `params`."""
    from .. import spectra
    from .map import parse_grid
    if args.bodies:
        return read_bodies(fmu, args.bodies, params)
    option = "--p" if args.p is not None else "--sizes"
    values = parse_grid(args.p if args.p is not None else args.sizes, option)
    try:
        bodies = spectra.rectangle_family(params, alpha=args.alpha, g=params.get("g", fmu.variables["g"].start),
                                          **({"p": values} if args.p is not None else {"sizes": values}))
    except ValueError as exc:
        raise CLIError(f"{option}: {exc}") from None
    for _, body in bodies:
        drop_unused(fmu, body)
    return bodies


def cmd_spectrum(args, params_given):
    from importlib.metadata import PackageNotFoundError, version

    import pandas as pd
    from tqdm import tqdm

    from .. import maps, paths, spectra
    from .map import _client, _variant, parse_grid
    from .simulate import gather_parameters

    if sum(x is not None for x in (args.p, args.sizes, args.bodies)) != 1:
        raise CLIError("give the family of bodies as one of --p P, --sizes R or --bodies FILE")
    if args.alpha is not None and not (0 < args.alpha < math.pi / 2):
        raise CLIError(f"--alpha {args.alpha:g}: must be in (0, pi/2) rad")
    scales = parse_grid(args.scales, "--scales")
    options = spectra.SpectrumOptions(scales=tuple(scales), hunt=not args.no_hunt, tol=args.tol,
                                      max_scale=args.max_scale, tail=args.tail)
    try:
        options.check()
    except ValueError as exc:
        raise CLIError(f"--{str(exc).replace('_', '-')}") from None
    rec, fmt = horizontal_record(args.record, args.component, args.units, args.fmt)
    if not rec.npts or not (abs(rec.acc).max() > 0):
        raise CLIError(f"{args.record}: the record has no acceleration (all zero)")
    out = Path(args.out)
    t0 = time.perf_counter()
    with open_fmu(args.fmu) as fmu:
        params, ignored, _ = gather_parameters(fmu, args, params_given)
        given = dict(params, **{name: v["value"] for name, v in ignored.items()})
        beds = [("body", params)] + [(text, _variant(fmu, _Base(params), given, text, maps).params)
                                     for text in args.beside or []]
        tables = []
        with _client(args) as client:
            for bed, base in beds:
                bodies = family(fmu, args, base)
                with tqdm(total=len(bodies), unit="body", desc=f"spectrum {bed}", file=sys.stderr,
                          dynamic_ncols=True, disable=args.quiet) as bar:
                    def progress(done, total, summary):
                        bar.update(1)
                    try:
                        runs, spectrum = spectra.run_spectrum(bodies, rec, fmu, options, workers=args.workers,
                                                              progress=progress, client=client)
                    except ValueError as exc:
                        raise CLIError(str(exc)) from None
                tables.append((bed, base, runs.assign(bed=bed), spectrum.assign(bed=bed)))
        guid = fmu.model_description.guid
    wall = time.perf_counter() - t0
    try:
        package = version("rocking")
    except PackageNotFoundError:
        package = "unknown"
    w_rec = args.record_frequency or 2 * math.pi / spectra.mean_period(rec)
    meta = {
        "record": {"path": str(args.record), "format": fmt, "name": rec.name, "component": rec.component,
                   "npts": rec.npts, "dt_s": rec.dt, "duration_s": rec.duration, "pga_m_s2": rec.pga,
                   "w_rec_rad_s": w_rec, "w_rec_from": "--record-frequency" if args.record_frequency
                   else "2 pi / T_m, the mean period of Rathje et al. 1998 (0.25-20 Hz)"},
        "family": {"p": args.p, "sizes": args.sizes, "bodies": args.bodies, "alpha": args.alpha},
        "params": params, "preset": args.preset, "ignored_parameters": ignored,
        "beds": {bed: base for bed, base, _, _ in tables},
        "scales": list(scales), "hunt": options.hunt, "tol": options.tol, "max_scale": options.max_scale,
        "tail": options.tail, "fmu_guid": guid, "rocking_version": package,
        "commit": paths.build_info()["commit"],
        "overturning": "the FMU's output overturned (|theta| reached thetaOv) at any time of the record or its "
                       "tail; least scale: the first collapse of the hunt-and-fill search (rocking.fragility.hunt)",
    }
    runs = pd.concat([t[2] for t in tables], ignore_index=True)
    spectrum = pd.concat([t[3] for t in tables], ignore_index=True)
    spectrum["w_rec_over_p"] = w_rec / spectrum["p"]
    out.mkdir(parents=True, exist_ok=True)
    maps.write_parquet(spectrum, out / "spectrum.parquet", meta)
    maps.write_parquet(runs, out / "runs.parquet", meta)
    if not args.no_plot:
        plot_spectrum(out / "spectrum.png", spectrum, meta, args.against)
    errors = int((runs["error"] != "").sum())
    print(f"record      {args.record} [{rec.component}], PGA {rec.pga:.4g} m/s2, w_rec {w_rec:.4g} rad/s")
    wide = max(len(b) for b in spectrum["bed"]) + 2
    print(f"{'bed':<{wide}}{'body':<14}{'p rad/s':>9}{'R m':>9}{'alpha':>8}"
          + "".join(f"{'peak @' + format(s, 'g'):>11}" for s in scales) + f"{'least scale':>13}")
    for (bed, body), g in spectrum.groupby(["bed", "body"], sort=False):
        first = g.iloc[0]
        peaks = "".join(f"{'overturned' if r.overturned else format(r.peak_theta_over_alpha, '.4f'):>11}"
                        for r in g.itertuples())
        least = ("-" if not options.hunt else f">{first.least_scale_lo:.4g}" if first.censored
                 else f"{first.least_scale:.4g}") + ("*" if first.unresolved else "")
        print(f"{bed:<{wide}}{body:<14}{first.p:>9.4g}{first.R:>9.4g}{first.alpha:>8.4f}{peaks}{least:>13}")
    print(f"runs        {len(runs)} in {wall:.1f} s"
          + (f", {errors} FAILED (their rows' error column)" if errors else "")
          + (", * unresolved (the spectrum's unresolved column)" if (spectrum["unresolved"] != "").any() else ""))
    print(f"wrote       {out / 'spectrum.parquet'}, {out / 'runs.parquet'}"
          + ("" if args.no_plot else f", {out / 'spectrum.png'}"))
    return 0


def plot_spectrum(path, spectrum, meta, against="p"):
    """Peak |theta| / alpha (overturned runs marked at 1) and the least overturning scale, against
    p, R or w_rec / p; one colour per bed, one line style per scale."""
    import numpy as np

    from .plots import _pyplot
    plt = _pyplot()
    x_of = {"p": "p", "size": "R", "ratio": "w_rec_over_p"}[against]
    hunt = meta["hunt"]
    fig, axes = plt.subplots(2 if hunt else 1, 1, figsize=(6.4, 6.4 if hunt else 3.8), sharex=True, squeeze=False)
    ax = axes[0][0]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    styles = ["-", "--", ":", "-."]
    beds = list(dict.fromkeys(spectrum["bed"]))
    marked = False
    for i, bed in enumerate(beds):
        b = spectrum[spectrum["bed"] == bed]
        name = "" if len(beds) == 1 else _bed_name(bed, meta)
        for j, (s, g) in enumerate(b.groupby("scale")):
            g = g.sort_values(x_of)
            over = g["overturned"].eq(True).to_numpy()
            y = np.where(over, np.nan, g["peak_theta_over_alpha"])
            label = ", ".join(x for x in (name, f"scale {s:g}") if x)
            ax.plot(g[x_of], y, styles[j % 4], marker=".", color=colors[i % len(colors)], label=label)
            if over.any():
                ax.plot(g[x_of][over], np.ones(int(over.sum())), "x", color=colors[i % len(colors)], ms=7)
                marked = True
    if marked:
        ax.plot([], [], "x", color="k", label="overturned (drawn at 1)")
    ax.axhline(1.0, color="k", lw=0.6)
    ax.set_ylabel("peak |theta| / alpha")
    ax.set_ylim(0, 1.08)
    ax.legend(fontsize=7, frameon=False)
    rec = meta["record"]
    ax.set_title(f"{Path(rec['path']).name} [{rec['component']}], PGA {rec['pga_m_s2']:.3g} m/s2, "
                 f"alpha = {spectrum['alpha'].iloc[0]:.3g} rad", fontsize=9)
    if hunt:
        ax2 = axes[1][0]
        for i, bed in enumerate(beds):
            b = spectrum[spectrum["bed"] == bed].drop_duplicates("body").sort_values(x_of)
            ok = ~b["censored"]
            lo, hi, est = b["least_scale_lo"], b["least_scale_hi"], b["least_scale"]
            ax2.errorbar(b[x_of][ok], est[ok], yerr=[(est - lo)[ok], (hi - est)[ok]], fmt="-o", ms=3,
                         color=colors[i % len(colors)], label=_bed_name(bed, meta) if len(beds) > 1 else None)
            if (~ok).any():
                ax2.plot(b[x_of][~ok], lo[~ok], "^", color=colors[i % len(colors)],
                         label="no overturning up to this scale")
        ax2.axhline(1.0, color="k", lw=0.6)  # the record as recorded
        ax2.set_yscale("log")
        _log_ticks(ax2.yaxis)
        ax2.set_ylabel("least scale factor that overturns")
        if ax2.get_legend_handles_labels()[0]:
            ax2.legend(fontsize=7, frameon=False)
    axes[-1][0].set_xscale("log")
    _log_ticks(axes[-1][0].xaxis)
    axes[-1][0].set_xlabel(AGAINST[against])
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _log_ticks(axis):
    """Plain numbers on a log axis (0.5, 1, 2, 5, 10), not powers of ten."""
    from matplotlib.ticker import FuncFormatter

    def label(v, _):
        return f"{v:g}" if v > 0 and round(v / 10 ** math.floor(math.log10(v) + 1e-9)) in (1, 2, 5) else ""
    axis.set_major_formatter(FuncFormatter(label))
    axis.set_minor_formatter(FuncFormatter(label))


def _bed_name(bed, meta):
    """The body given is named by its interface beside its --beside variants."""
    return f"interface={meta['beds'][bed].get('interface', 'default')}" if bed == "body" else bed


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    from .map import add_dask_options

    p = sub.add_parser(
        "spectrum", parents=[common], allow_abbrev=False,
        help="rocking spectrum of a record: peak theta/alpha and least overturning scale against p or size",
        usage="rocking spectrum RECORD [--preset NAME] [--params FILE] [--PARAM VALUE ...]\n"
              "                   (--p P | --sizes R | --bodies FILE) [--alpha A] [--scales S] [--tol R]\n"
              "                   [--max-scale S] [--beside NAME=VALUE] [--against p|size|ratio] --out DIR",
        description=textwrap.fill(
            "Run a family of bodies under the record: solid rectangular prisms of one slenderness (--alpha, "
            "default atan(B/H) of the body given) at each frequency parameter p = sqrt(3 g / (4 R)) of --p or "
            "size R of --sizes, or the bodies of a JSON file (--bodies, each over the body given). For each "
            "body: the peak |theta| / alpha at every scale factor of --scales, and the least scale factor "
            "that overturns it (the IDA's hunt-and-fill search from the scale at which the PGA reaches "
            "g tan alpha, bisected to --tol). Overturning: |theta| reached thetaOv during the record or its "
            "free tail (docs/maps.md). Writes DIR/spectrum.parquet (one row per body and scale), "
            "DIR/runs.parquet (every run) and DIR/spectrum.png; the inputs, the package version and the "
            "FMU's GUID are in both files' metadata (key 'rocking').", 100),
        epilog=textwrap.fill("Lists: START:STOP:N (linear), START:STOP:N:log, or A,B,C. docs/spectra.md.", 100),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("record", metavar="RECORD", help="the ground-motion record (its first horizontal component)")
    p.add_argument("--component", help="the record's component by label or index")
    add_record_options(p)
    p.add_argument("--preset", metavar="NAME", help="start from a named parameter set")
    p.add_argument("--params", metavar="FILE", help="parameters from a JSON object of name -> value")
    p.add_argument("--fmu", metavar="PATH", help=FMU_HELP)
    p.add_argument("--p", metavar="P", help="the family's frequency parameters p (rad/s)")
    p.add_argument("--sizes", metavar="R", help="the family's sizes R (m, half the rectangle's diagonal)")
    p.add_argument("--bodies", metavar="FILE", help="the bodies: a JSON list of objects (or name -> object) of "
                   "parameters over the body given")
    p.add_argument("--alpha", type=float, help="the family's slenderness (rad; default atan(B/H) of the body)")
    p.add_argument("--scales", default="1", metavar="S", help="scale factors of the record at which the peak "
                   "is reported (default 1)")
    p.add_argument("--no-hunt", action="store_true", help="no search of the least overturning scale")
    p.add_argument("--tol", type=float, default=0.01, help="relative width of the least overturning scale's "
                   "bracket (default 0.01)")
    p.add_argument("--max-scale", type=float, help="the highest scale the search tries (default 50 times the "
                   "scale at which the PGA reaches g tan alpha)")
    p.add_argument("--tail", type=float, default=10.0, help="s of free motion after the record (default 10)")
    p.add_argument("--beside", action="append", metavar="NAME=VALUE[,...]",
                   help="also the family with these parameters changed, e.g. --beside interface=elastic,kn=1e9 "
                        "(repeatable): rows of bed NAME=VALUE, a line each in the plot")
    p.add_argument("--against", choices=list(AGAINST), default="p", help="the plot's abscissa: p, size R, or "
                   "w_rec / p (default p)")
    p.add_argument("--record-frequency", type=float, metavar="W", help="w_rec (rad/s) of --against ratio "
                   "(default 2 pi / T_m, the record's mean period)")
    p.add_argument("--workers", type=int, help="processes (default: one per core)")
    add_dask_options(p, "the bodies (one task each)", "large families or long records")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--no-plot", action="store_true", help="no DIR/spectrum.png")
    p.add_argument("--out", required=True, metavar="DIR", help="folder of the tables and the plot")
    p.set_defaults(func=cmd_spectrum)
