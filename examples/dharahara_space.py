"""The Dharahara tower in space (docs/dharahara.md, "The rigid tower in space" and "The tower in
space on flexible and crushing beds"): every shipped record set with two horizontal components,
x1 and x3, the tower in space under both components and the vertical against planar runs along
each component and along the worst azimuth. The runs are the Rust examples `dharahara_space`
(the rigid tower, 36 azimuths) and `dharahara_space_flexible` (`--flexible`: the 49 cases of
docs/model.md §4, 12 azimuths), the physics of src/spatial without the FMU; this script writes
their inputs and draws the page's figures and tables.

    .venv/bin/python examples/dharahara_space.py [--out DIR] [--scales 1,3] [--flexible]

Writes DIR/dharahara_space.json (every run), dharahara_space.md (the page's table),
dharahara_space_plan.png and dharahara_space_tilt.png; with --flexible
DIR/dharahara_space_flexible.json, dharahara_space_flexible.md (the page's tables),
dharahara_space_flexible_plan.png and dharahara_space_flexible_tilt.png. About 1 min on 2 cores;
--flexible about 5 min of CPU (11 min of wall time on a loaded 2-core machine; 392 runs in space and
4704 planar).
"""

import argparse
import json
import re
import statistics
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from rocking import groundmotion as gm  # noqa: E402
from rocking import paths  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SETS = ("csmip-coalinga-1983", "geonet-darfield-2010", "geonet-kaikoura-2016", "usgs-lomaprieta-1989")
SHORT = {"csmip": "Coalinga", "geonet-darfield": "Darfield DFHS", "geonet-kaikoura": "Kaikoura WTMC",
         "usgs-lomaprieta": "Loma Prieta"}


def short_name(folder):
    return next(v for k, v in SHORT.items() if folder.startswith(k))


def dump(out):
    """One input file per record set: `# name bearing_x`, dt, `agx agy av` per sample."""
    files = []
    for folder in SETS:
        base = paths.data_dir() / folder
        first = next(p for p in sorted(base.iterdir()) if gm.is_record_file(p))
        pair = gm.pair_of(first)
        name = short_name(folder)
        v = pair.vertical.acc if pair.vertical is not None else [0.0] * pair.npts
        path = out / (re.sub(r"\W+", "_", name) + ".txt")
        with open(path, "w") as f:
            f.write(f"# {name.replace(' ', '_')} {pair.bearing_x if pair.bearing_x is not None else 'none'}\n")
            f.write(f"{float(pair.dt)!r}\n")
            for x, y, z in zip(pair.x.acc, pair.y.acc, v):
                f.write(f"{float(x)!r} {float(y)!r} {float(z)!r}\n")
        files.append(path)
        print(f"{name}: x {pair.x.component}, y {pair.y.component}, bearing of x {pair.bearing_x}; "
              f"{pair.npts} samples; {pair.notes or ''}".replace("\n", "; "), file=sys.stderr)
    return files


def outcome(run):
    if run["overturned_at"] is not None:
        return f"overturns {run['overturned_at']:.2f} s"
    if run["lift_off_at"] is not None:
        return f"liftOff {run['lift_off_at']:.2f} s"
    return f"{run['peak_over_alpha']:.3f}"


def table(doc):
    rows = ["| record | x | in space (impacts) | in space, no av | planar x | planar y | worst azimuth | planar there (impacts) |",
            "|---|---|---|---|---|---|---|---|"]
    for r in doc["runs"]:
        rows.append(f"| {r['record']} | {r['scale']:g} | {outcome(r['space'])} ({r['space']['impacts']}) | "
                    f"{outcome(r['space_without_av'])} | {outcome(r['planar_x'])} | {outcome(r['planar_y'])} | "
                    f"{r['worst_azimuth_deg']:g} deg | {outcome(r['planar_worst'])} ({r['planar_worst']['impacts']}) |")
    return "\n".join(rows) + "\n"


def figures(doc, out):
    """The path of the top in plan and the tilt against time for the run with the largest tilt
    in space that neither overturns nor leaves the model."""
    standing = [r for r in doc["runs"] if r["space"]["overturned_at"] is None and r["space"]["lift_off_at"] is None]
    r = max(standing, key=lambda r: r["space"]["peak_over_alpha"])
    hist = r["history"]
    alpha = doc["alpha"]
    title = f"{r['record']} x{r['scale']:g}"
    fig, ax = plt.subplots(figsize=(5.2, 5.0))
    for key, style, label in (("planar_x", "C1-", "planar along x"), ("planar_y", "C2-", "planar along y"),
                              ("planar_worst", "C3-", f"planar along {r['worst_azimuth_deg']:g} deg"),
                              ("space", "k-", "in space")):
        h = hist[key]
        ax.plot([p[2] for p in h], [p[3] for p in h], style, lw=0.9 if key == "space" else 0.7, label=label)
    ax.set_aspect("equal")
    ax.set_xlabel("top along x (m)")
    ax.set_ylabel("top along y (m)")
    ax.set_title(f"Path of the top in plan, {title}")
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(out / "dharahara_space_plan.png", dpi=90)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(7.5, 3.4))
    for key, style, label in (("planar_x", "C1-", "planar x"), ("planar_y", "C2-", "planar y"),
                              ("planar_worst", "C3-", f"planar {r['worst_azimuth_deg']:g} deg"),
                              ("space", "k-", "in space (theta >= 0)")):
        h = hist[key]
        ax.plot([p[0] for p in h], [abs(p[1]) / alpha for p in h], style, lw=0.8, label=label)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("|theta| / alpha")
    ax.set_title(f"Tilt, {title}")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(out / "dharahara_space_tilt.png", dpi=90)
    plt.close(fig)
    return title


def flexible_outcome(run):
    return f"{outcome(run)} ({run['crossings']})"


#: The page's families: case-id prefix and fm label.
FAMILIES = [("rigid", "rigid")] + [(f"{g}, {f}", (p, f)) for g, p in (("foundation", "F"), ("interface", "I"))
                                   for f in ("fm2", "fm5", "fm15", "elastic")]


def family_of(case):
    if case == "rigid":
        return "rigid"
    prefix, fm = case[0], case.split("_")[1]
    return next(name for name, key in FAMILIES if key == (prefix, fm))


def overturns(run):
    return run["overturned_at"] is not None


def flexible_tables(doc, detail=("Darfield DFHS", 3.0)):
    """The page's tables: per record and scale, the cases that overturn in space, planar along x,
    y and at the worst azimuth, and where space and planar disagree; then every case under the
    record and scale `detail`."""
    rows = ["| record | x | overturn in space | planar x | planar y | any planar azimuth | "
            "in space, not along x | along x, not in space | in space, at no azimuth | "
            "space peak / worst azimuth's (median, range; both stand) |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    keys = sorted({(r["record"], r["scale"]) for r in doc["runs"]})
    for rec, scale in keys:
        runs = [r for r in doc["runs"] if r["record"] == rec and r["scale"] == scale]
        sp = [r for r in runs if overturns(r["space"])]
        any_planar = [r for r in runs if overturns(r["planar_worst"])]
        space_only = [r["case"] for r in sp if not overturns(r["planar_worst"])]
        not_x = sum(not overturns(r["planar_x"]) for r in sp)
        x_only = sum(overturns(r["planar_x"]) and not overturns(r["space"]) for r in runs)
        lift = [r for r in runs if r["space"]["lift_off_at"] is not None]
        stand = [r["space"]["peak_over_alpha"] / r["planar_worst"]["peak_over_alpha"] for r in runs
                 if not overturns(r["space"]) and not overturns(r["planar_worst"])
                 and r["space"]["lift_off_at"] is None and r["planar_worst"]["peak_over_alpha"] > 0]
        ratio = (f"{statistics.median(stand):.2f} ({min(stand):.2f} to {max(stand):.2f})" if stand else "")
        if lift and len(lift) == len(runs):
            ratio = f"liftOff in every run ({min(r['space']['lift_off_at'] for r in lift):.2f} s)"
        rows.append(f"| {rec} | {scale:g} | {len(sp)} | {sum(overturns(r['planar_x']) for r in runs)} | "
                    f"{sum(overturns(r['planar_y']) for r in runs)} | {len(any_planar)} | "
                    f"{not_x} | {x_only} | {', '.join(space_only) or '-'} | {ratio} |")
    detail_rows = ["| case | in space (crossings) | planar x (crossings) | planar y (crossings) | worst azimuth | "
                   "planar there (crossings) |", "|---|---|---|---|---|---|"]
    for r in doc["runs"]:
        if (r["record"], r["scale"]) != detail:
            continue
        detail_rows.append(f"| {r['case']} | {flexible_outcome(r['space'])} | {flexible_outcome(r['planar_x'])} | "
                           f"{flexible_outcome(r['planar_y'])} | {r['worst_azimuth_deg']:g} deg | "
                           f"{flexible_outcome(r['planar_worst'])} |")
    return "\n".join(rows) + "\n", "\n".join(detail_rows) + "\n"


def telling(doc):
    """Two crushing cases for the pictures: the one with the largest peak in space among those
    that overturn planar along x and stand in space, and the one that overturns last in space
    among those that stand planar along x and along y."""
    crushing = [r for r in doc["runs"] if "_fm" in r["case"]]
    stands = [r for r in crushing if overturns(r["planar_x"]) and not overturns(r["space"])
              and r["space"]["lift_off_at"] is None]
    falls = [r for r in crushing if overturns(r["space"]) and not overturns(r["planar_x"])
             and not overturns(r["planar_y"])]
    picks = []
    if stands:
        picks.append(max(stands, key=lambda r: r["space"]["peak_over_alpha"]))
    if falls:
        picks.append(max(falls, key=lambda r: r["space"]["overturned_at"]))
    return picks


def flexible_figures(hdoc, out):
    runs = hdoc["runs"]
    alpha = hdoc["alpha"]
    fig, axes = plt.subplots(1, len(runs), figsize=(5.0 * len(runs), 5.0), squeeze=False)
    for ax, r in zip(axes[0], runs):
        hist = r["history"]
        for key, style, label in (("planar_x", "C1-", "planar along x"), ("planar_y", "C2-", "planar along y"),
                                  ("planar_worst", "C3-", f"planar along {r['worst_azimuth_deg']:g} deg"),
                                  ("space", "k-", "in space")):
            h = hist[key]
            ax.plot([p[2] for p in h], [p[3] for p in h], style, lw=0.9 if key == "space" else 0.7, label=label)
        ax.set_aspect("equal")
        ax.set_xlabel("top along x, from the base's centre (m)")
        ax.set_ylabel("top along y (m)")
        ax.set_title(f"{r['case']}, {r['record']} x{r['scale']:g}", fontsize=10)
        ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(out / "dharahara_space_flexible_plan.png", dpi=80)
    plt.close(fig)
    fig, axes = plt.subplots(len(runs), 1, figsize=(7.5, 2.8 * len(runs)), squeeze=False)
    for ax, r in zip(axes[:, 0], runs):
        hist = r["history"]
        for key, style, label in (("planar_x", "C1-", "planar x"), ("planar_y", "C2-", "planar y"),
                                  ("planar_worst", "C3-", f"planar {r['worst_azimuth_deg']:g} deg"),
                                  ("space", "k-", "in space")):
            h = hist[key]
            ax.plot([p[0] for p in h], [abs(p[1]) / alpha for p in h], style, lw=0.8, label=label)
        ax.set_ylabel("|theta| / alpha")
        ax.set_title(f"{r['case']}, {r['record']} x{r['scale']:g}", fontsize=10)
        ax.legend(fontsize=7, ncol=4)
    axes[-1, 0].set_xlabel("t (s)")
    fig.tight_layout()
    fig.savefig(out / "dharahara_space_flexible_tilt.png", dpi=80)
    plt.close(fig)


def run_flexible(args, files):
    example = ["cargo", "run", "--release", "-q", "--example", "dharahara_space_flexible", "--"]
    result = subprocess.run([*example, args.scales, *map(str, files)], cwd=ROOT, check=True,
                            capture_output=True, text=True)
    doc = json.loads(result.stdout)
    (args.out / "dharahara_space_flexible.json").write_text(json.dumps(doc))
    summary, detail = flexible_tables(doc)
    picks = telling(doc)
    (args.out / "dharahara_space_flexible.md").write_text(summary + "\n" + detail)
    print(summary + "\n" + detail)
    if picks:
        wanted = ",".join(f"{r['case']}@{r['record'].replace(' ', '_')}@{r['scale']:g}" for r in picks)
        result = subprocess.run([*example, "--history", wanted, args.scales, *map(str, files)], cwd=ROOT,
                                check=True, capture_output=True, text=True)
        hdoc = json.loads(result.stdout)
        order = [(r["case"], r["record"], r["scale"]) for r in picks]
        hdoc["runs"].sort(key=lambda r: order.index((r["case"], r["record"], r["scale"])))
        flexible_figures(hdoc, args.out)
        print(f"figures: {wanted}; {args.out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "dharahara_space")
    parser.add_argument("--scales", default="1,3")
    parser.add_argument("--flexible", action="store_true",
                        help="the 49 cases of docs/model.md §4 (dharahara_space_flexible) instead of the rigid study")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    inputs = args.out / "inputs"
    inputs.mkdir(exist_ok=True)
    files = dump(inputs)
    if args.flexible:
        run_flexible(args, files)
        return
    cmd = ["cargo", "run", "--release", "-q", "--example", "dharahara_space", "--", args.scales, *map(str, files)]
    result = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True)
    sys.stderr.write(result.stderr)
    doc = json.loads(result.stdout)
    (args.out / "dharahara_space.json").write_text(json.dumps(doc))
    (args.out / "dharahara_space.md").write_text(table(doc))
    title = figures(doc, args.out)
    print(table(doc))
    print(f"figures: {title}; {args.out}")


if __name__ == "__main__":
    main()
