"""The rigid Dharahara tower in space (docs/dharahara.md, "The rigid tower in space"): every
shipped record set with two horizontal components, x1 and x3, the tower in space under both
components and the vertical against planar runs along each component and along the worst of 36
azimuths. The runs are the Rust example `dharahara_space` (the physics of src/spatial, no FMU);
this script writes its inputs and draws the page's figures and table.

    .venv/bin/python examples/dharahara_space.py [--out DIR] [--scales 1,3]

Writes DIR/dharahara_space.json (every run), dharahara_space.md (the page's table),
dharahara_space_plan.png and dharahara_space_tilt.png. About 1 min on 2 cores.
"""

import argparse
import json
import re
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


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "dharahara_space")
    parser.add_argument("--scales", default="1,3")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    inputs = args.out / "inputs"
    inputs.mkdir(exist_ok=True)
    files = dump(inputs)
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
