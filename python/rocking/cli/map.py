"""`rocking map`: where a body overturns under a pulse family, over a grid of frequency and
amplitude -> DIR/runs.parquet, DIR/boundaries.parquet, DIR/map.png (docs/maps.md)."""

import argparse
import math
import sys
import textwrap
import time
from pathlib import Path

from .common import FMU_HELP, CLIError, open_fmu

#: This subcommand also takes any FMU parameter as `--NAME VALUE` (as `simulate` does).
TAKES_PARAMETERS = True


def parse_grid(text, option):
    """START:STOP:N (N values, linear; START:STOP:N:log, geometric) or a list A,B,C; a
    CLIError naming `option` otherwise."""
    import numpy as np

    try:
        if ":" in text:
            parts = text.split(":")
            if len(parts) not in (3, 4) or (len(parts) == 4 and parts[3] != "log"):
                raise ValueError
            start, stop, n = float(parts[0]), float(parts[1]), int(parts[2])
            if n < 1:
                raise CLIError(f"{option} {text}: the grid is empty (N = {n})")
            if len(parts) == 4:
                if start <= 0 or stop <= 0:
                    raise CLIError(f"{option} {text}: a geometric grid needs START, STOP > 0")
                values = np.geomspace(start, stop, n)
            else:
                values = np.linspace(start, stop, n)
        else:
            values = np.array([float(v) for v in text.split(",") if v.strip()])
    except ValueError:
        raise CLIError(f"{option} {text!r}: expected START:STOP:N, START:STOP:N:log or A,B,C") from None
    if values.size == 0:
        raise CLIError(f"{option} {text!r}: the grid is empty")
    bad = [v for v in values if not (math.isfinite(v) and v > 0)]
    if bad:
        raise CLIError(f"{option} {text}: every value must be > 0 (got {bad[0]:g})")
    return [float(v) for v in values]


def cmd_map(args, params_given):
    from importlib.metadata import PackageNotFoundError, version

    from tqdm import tqdm

    from .. import maps, paths, pulses
    from ..map_store import MapStore
    from .simulate import gather_parameters

    user = None
    if args.pulse == "user":
        if not args.pulse_file:
            raise CLIError("--pulse user: give the shape as --pulse-file CSV (tau = t/T_p, value)")
        user = pulses.read_shape(args.pulse_file)
    elif args.pulse_file:
        raise CLIError(f"--pulse-file: only with --pulse user (not {args.pulse})")
    freqs = parse_grid(args.frequencies, "--frequencies")
    amps = parse_grid(args.amplitudes, "--amplitudes")
    out = Path(args.out)
    t0 = time.perf_counter()
    with open_fmu(args.fmu) as fmu:
        params, ignored, _ = gather_parameters(fmu, args, params_given)
        interface = params.get("interface")
        if interface is None:
            start = fmu.variables["interface"].start
            interface = next(i for i, v in fmu.enumerations["interface"].items() if str(v) == str(start))
        dimensionless = args.dimensionless if args.dimensionless is not None else interface == "rigid"
        spec = maps.MapSpec(params=params, shape=args.pulse, frequencies=freqs, amplitudes=amps,
                            dimensionless=dimensionless, tol=args.tol, tail=args.tail,
                            per_period=args.per_period, user=user)
        try:
            spec.check()
        except ValueError as exc:
            raise CLIError(str(exc)) from None
        spec.scales = maps.body_scales(fmu, params)
        # a variant starts from every parameter given, also those the body's interface does not use
        given = dict(params, **{name: v["value"] for name, v in ignored.items()})
        bodies = [("body", spec)] + [(text, _variant(fmu, spec, given, text, maps)) for text in args.beside or []]
        tables = []
        store = MapStore(out / "parts")
        with _client(args) as client:
            for label, sp in bodies:
                runs_done = [0]
                with tqdm(total=len(freqs), unit="frequency", desc=f"map {label}", file=sys.stderr,
                          dynamic_ncols=True, disable=args.quiet) as bar:
                    def progress(done, total, rows):
                        runs_done[0] += len(rows)
                        bar.set_postfix(runs=runs_done[0], refresh=False)
                        bar.update(done - bar.n)
                    runs = maps.run_map(sp, fmu, workers=args.workers, progress=progress, store=store,
                                        resume=not args.no_resume, client=client)
                tables.append((label, sp, runs, maps.boundaries(runs, sp)))
        guid = fmu.model_description.guid
    wall = time.perf_counter() - t0
    try:
        package = version("rocking")
    except PackageNotFoundError:
        package = "unknown"
    meta = maps.metadata(spec, {"preset": args.preset, "ignored_parameters": ignored,
                                "interface": interface, "fmu_guid": guid,
                                "rocking_version": package, "commit": paths.build_info()["commit"],
                                "overturning": "the FMU's output overturned (|theta| reached thetaOv) at any "
                                               "time of the pulse or its tail; how: impacts before it"})
    if len(tables) > 1:
        meta["bodies"] = {label: {"params": sp.params, "scales": sp.scales} for label, sp, _, _ in tables}
    runs = pd_concat([t[2].assign(body=t[0]) for t in tables])
    bounds = pd_concat([t[3].assign(body=t[0]) for t in tables])
    out.mkdir(parents=True, exist_ok=True)
    maps.write_parquet(runs, out / "runs.parquet", meta)
    maps.write_parquet(bounds, out / "boundaries.parquet", meta)
    if not args.no_plot:
        plot_map(out / "map.png", tables, meta)
    errors = int((runs["error"] != "").sum())
    unresolved = int((bounds["unresolved"] != "").sum())
    units = meta["units"]
    for label, sp, _, _ in tables:
        name = sp.params.get("interface", interface)
        print(f"{label:<11} p = {sp.scales['p']:.5g} rad/s, alpha = {sp.scales['alpha']:.5g} rad, "
              f"g tan alpha = {sp.scales['g_tan_alpha']:.5g} m/s2, thetaOv = {sp.scales['thetaOv']:.5g} rad "
              f"({name} interface)")
    print(f"grid        {len(freqs)} frequencies ({units['w']}) x {len(amps)} amplitudes ({units['a']}), "
          f"{args.pulse} pulse, boundaries to {args.tol:g} relative")
    resumed = sum(t[2].attrs.get("resumed", 0) for t in tables)
    if resumed:
        print(f"resumed     {resumed} of {len(freqs) * len(tables)} frequency columns read from {out / 'parts'} "
              "(finished by an earlier run of this map; --no-resume runs them again)")
    ran = len(runs) - sum(t[2].attrs.get("resumed_rows", 0) for t in tables)
    print(f"runs        {len(runs)}" + (f", {ran} of them run now" if resumed else "")
          + f" in {wall:.1f} s ({ran / wall:.1f} runs/s)"
          + (f", {errors} FAILED (their rows' error column)" if errors else ""))
    unsettled = int((runs["tail_end"] == "time").sum())
    print(f"tails       {int((runs['tail_end'] == 'cannot overturn').sum())} ended where the body could no longer "
          f"overturn, {int((runs['tail_end'] == 'overturned').sum())} by overturning"
          + (f", {unsettled} at --tail {args.tail:g} s not settled (a longer --tail decides them)"
             if unsettled else ""))
    print(f"intervals   {len(bounds)} overturning interval(s)"
          + (f", {unresolved} with something unresolved (their unresolved column)" if unresolved else ""))
    print(f"wrote       {out / 'runs.parquet'}, {out / 'boundaries.parquet'}"
          + ("" if args.no_plot else f", {out / 'map.png'}"))
    return 0


def add_dask_options(p, tasks, worth):
    """--dask and --scheduler of `p` (map, spectrum): `tasks` run on the fragility runner's Dask
    cluster (`_client`); `worth`: what it is worth starting a cluster for."""
    p.add_argument("--dask", action="store_true",
                   help=f"run {tasks} on a Dask LocalCluster of --workers processes (the fragility "
                        f"runner's; worth it for {worth}, it costs seconds to start)")
    p.add_argument("--scheduler", metavar="ADDRESS", help=f"run {tasks} on this Dask scheduler")


def _client(args):
    """A Dask client (rocking.fragility.cluster) for --dask or --scheduler, else nothing."""
    import contextlib
    if not (args.dask or args.scheduler):
        return contextlib.nullcontext()
    from ..fragility import cluster
    return cluster.open_client(args.scheduler, args.workers, quiet=args.quiet)


def pd_concat(frames):
    import pandas as pd
    return pd.concat(frames, ignore_index=True)


def _variant(fmu, spec, given, text, maps):
    """The map of --beside NAME=VALUE[,NAME=VALUE...]: the body with those parameters changed
    (those the changed enumerations no longer use left out), the same grid in the same units."""
    import dataclasses

    from .common import check_parameter, drop_unused
    changed = {}
    for item in text.split(","):
        name, eq, value = item.partition("=")
        if not eq or not name.strip():
            raise CLIError(f"--beside {text!r}: expected NAME=VALUE[,NAME=VALUE...], e.g. interface=elastic,kn=2e9")
        changed[name.strip()] = check_parameter(fmu, name.strip(), value.strip(), f"--beside {text}: {name.strip()}")
    params = dict(given, **changed)
    drop_unused(fmu, params)
    variant = dataclasses.replace(spec, params=params, scales={})
    variant.scales = maps.body_scales(fmu, params)
    return variant


def plot_map(path, tables, meta):
    """One panel per body [(label, spec, runs, boundaries)]: regions by outcome (the grid's
    runs as cells) and the boundaries."""
    from .plots import _pyplot
    plt = _pyplot()
    n = len(tables)
    fig, axes = plt.subplots(1, n, figsize=(6.4 if n == 1 else 4.2 * n, 4.8), sharex=True, sharey=True,
                             squeeze=False)
    for k, (ax, (label, spec, runs, bounds)) in enumerate(zip(axes[0], tables)):
        handles, labels = _panel(ax, spec, runs, bounds)
        if n > 1:
            ax.set_title(label if label != "body" else f"body: interface={meta['interface']}", fontsize=9)
        ax.text(0.98, 0.03, f"{spec.shape} pulse\nalpha = {spec.scales['alpha']:.3g} rad, "
                f"p = {spec.scales['p']:.3g} rad/s\nthetaOv = {spec.scales['thetaOv']:.3g} rad",
                transform=ax.transAxes, ha="right", va="bottom", fontsize=7)
        ax.set_xlabel(meta["units"]["w"] if spec.dimensionless else "w_p (rad/s)")
        if k == 0:
            ax.set_ylabel(meta["units"]["a"] if spec.dimensionless else "a_p (m/s2)")
    fig.legend(handles, labels, loc="upper center", ncol=3 if n > 1 else 2, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0, 1, 0.86 if n > 1 else 0.84))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _panel(ax, spec, runs, bounds):
    import numpy as np
    from matplotlib.colors import ListedColormap
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    from ..maps import AFTER_IMPACTS, NO_IMPACT, OUTCOMES, SAFE, mode_changes
    colors = {SAFE: "#dddddd", NO_IMPACT: "#d62728", AFTER_IMPACTS: "#ff9f40"}
    grid = runs[runs["phase"] == "grid"]
    classes = np.where(~grid["overturned"].fillna(False).astype(bool), SAFE,
                       np.where(grid["impacts"] == 0, NO_IMPACT, AFTER_IMPACTS))
    ws, as_ = np.sort(grid["w"].unique()), np.sort(grid["a"].unique())
    if len(ws) > 1 and len(as_) > 1:
        cell = np.full((len(as_), len(ws)), np.nan)
        for w, a, c in zip(grid["w"], grid["a"], classes):
            cell[np.searchsorted(as_, a), np.searchsorted(ws, w)] = c
        ax.pcolormesh(ws, as_, cell, cmap=ListedColormap([colors[k] for k in (SAFE, NO_IMPACT, AFTER_IMPACTS)]),
                      vmin=-0.5, vmax=2.5, shading="nearest")
    else:
        ax.scatter(grid["w"], grid["a"], c=[colors[c] for c in classes], s=30, marker="s")
    for _, g in bounds.groupby(bounds.groupby("w").cumcount()):
        g = g.sort_values("w")
        ax.plot(g["w"], g["start"], "k-", lw=1.2)
        finite = g[np.isfinite(g["end"])]
        if len(finite):
            ax.plot(finite["w"], finite["end"], "k--", lw=1.0)
    modes = mode_changes(runs)
    if len(modes):
        ax.plot(modes["w"], 0.5 * (modes["a_lo"] + modes["a_hi"]), "k:", lw=1.0)
    handles = [Line2D([], [], color="k", lw=1.2), Line2D([], [], color="k", lw=1.0, ls="--"),
               Line2D([], [], color="k", lw=1.0, ls=":")]
    labels = ["overturning begins", "safe window above", "mode changes (no safe run between)"]
    handles += [Patch(color=colors[c]) for c in (SAFE, NO_IMPACT, AFTER_IMPACTS)]
    labels += [OUTCOMES[c] for c in (SAFE, NO_IMPACT, AFTER_IMPACTS)]
    return handles, labels


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    from ..presets import NAMING
    from ..pulses import SHAPES

    p = sub.add_parser(
        "map", parents=[common], allow_abbrev=False,
        help="overturning map of a body under a pulse family (frequency x amplitude)",
        usage="rocking map [--preset NAME] [--params FILE] [--PARAM VALUE ...] [--pulse SHAPE]\n"
              "                   [--pulse-file CSV] --frequencies F --amplitudes A [--tol R]\n"
              "                   [--tail S] [--dimensionless | --dimensional] [--workers N] --out DIR",
        description=textwrap.fill(
            "Run the body (a preset, --params FILE and/or --NAME VALUE, as `simulate` takes them) under a "
            "pulse at every frequency and amplitude of the grid, then bisect each frequency's boundaries "
            "(no overturning / overturning without impact / after impacts) to --tol. Overturning: |theta| "
            "reached the body's overturning limit thetaOv during the pulse or its free tail (docs/maps.md). "
            "Writes DIR/runs.parquet (one row per run), DIR/boundaries.parquet (one row per interval of "
            "amplitudes in which the body overturns) and DIR/map.png; the inputs, the package version and "
            "the FMU's GUID are in both files' metadata (key 'rocking'). Each finished frequency column is "
            "kept in DIR/parts: the same map run again (interrupted, or with more frequencies) reads them "
            "instead of running them.", 100),
        epilog=textwrap.fill(f"Grids: START:STOP:N (linear), START:STOP:N:log, or A,B,C. Dimensionless (the "
                             "default for interface = rigid): w_p / p and a_p / (g tan alpha), p = sqrt(m g R0 / "
                             f"IO); dimensional: rad/s and m/s2. presets: {NAMING}.", 100),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--preset", metavar="NAME", help="start from a named parameter set")
    p.add_argument("--params", metavar="FILE", help="parameters from a JSON object of name -> value")
    p.add_argument("--fmu", metavar="PATH", help=FMU_HELP)
    p.add_argument("--pulse", choices=SHAPES, default="one-sine", help="the pulse family (default one-sine)")
    p.add_argument("--pulse-file", metavar="CSV", help="--pulse user: its shape, columns tau = t/T_p, value")
    p.add_argument("--frequencies", required=True, metavar="F", help="the grid's w_p (w_p/p dimensionless)")
    p.add_argument("--amplitudes", required=True, metavar="A",
                   help="the grid's a_p (a_p/(g tan alpha) dimensionless)")
    units = p.add_mutually_exclusive_group()
    units.add_argument("--dimensionless", dest="dimensionless", action="store_true", default=None,
                       help="grid in w_p/p and a_p/(g tan alpha) (default for a rigid interface)")
    units.add_argument("--dimensional", dest="dimensionless", action="store_false",
                       help="grid in rad/s and m/s2 (default for a flexible interface)")
    p.add_argument("--beside", action="append", metavar="NAME=VALUE[,...]",
                   help="also map the body with these parameters changed, in a panel beside it and as "
                        "rows of body NAME=VALUE in the tables (repeatable), e.g. --beside interface=rigid "
                        "--beside interface=elastic; the same grid and units")
    p.add_argument("--tol", type=float, default=1e-3, help="relative width of each boundary's bracket "
                   "(default 1e-3)")
    p.add_argument("--tail", type=float, default=10.0,
                   help="s of free motion after the pulse at most: a tail ends earlier once the body "
                        "can no longer overturn (docs/maps.md) (default 10)")
    p.add_argument("--per-period", type=int, default=400, help="samples of the pulse per period (default 400)")
    p.add_argument("--workers", type=int, help="processes (default: one per core)")
    add_dask_options(p, "the frequency columns", "large grids")
    p.add_argument("--no-resume", action="store_true",
                   help="run every column again, not reading those a previous run of this map left in "
                        "DIR/parts")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--no-plot", action="store_true", help="no DIR/map.png")
    p.add_argument("--out", required=True, metavar="DIR", help="folder of the tables and the plot")
    p.set_defaults(func=cmd_map)
