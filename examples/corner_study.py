"""Limit analysis of a masonry corner over load orientations (docs/corner.md).

Runs the corner binary `rocking-corner` (corner crate) for the paper's specimen or
a user's corner, prints a table, and draws
- lambda against alpha over 0..pi/2, with the paper's Table 1 (experiments) and
  Table 5 (limit analysis, k = 0.3) when the specimen is the paper's;
- the optimal macroblock of each requested orientation: elevation of both walls,
  unfolded at the corner (WY left, WX right), blocks of the moving parts shaded;
- with --beyond, lambda(alpha) for walls of unequal length.

    python examples/corner_study.py                      # the paper's five orientations
    python examples/corner_study.py --k 0.6 --mu 0.7 --alpha 0.785398 1.570796
    python examples/corner_study.py --blocks-y 10 --out out/corner

Figures go to --out (default docs/img, the ones docs/corner.md shows).
"""

import argparse
import json
import math
import pathlib
import shutil
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
PAPER_ALPHAS = [math.pi * i / 16 for i in range(4, 9)]
TABLE1 = [0.287, 0.270, 0.248, 0.239, 0.236]  # experiments, mean of five tests
TABLE5 = [0.290, 0.284, 0.263, 0.238, 0.229]  # the paper's limit analysis, k = 0.3
SPECIMEN = dict(t=0.0573, l=0.1149, h=0.0703, rho=1876.0, mu=0.66, courses=9,
                blocks_x=7, blocks_y=7)


def binary():
    built = ROOT / "target" / "release" / "rocking-corner"
    if built.is_file():
        return [str(built)]
    if shutil.which("cargo"):
        return ["cargo", "run", "--quiet", "--release", "-p", "corner", "--bin",
                "rocking-corner", "--"]
    raise SystemExit("build the corner binary first: cargo build --release -p corner")


def corner(alphas, spec, m=1, k=0.3, preset="paper", refine=True):
    """One record per orientation, from `rocking-corner --json`."""
    args = ["--alpha", *map(repr, alphas), "--m", str(m), "--k", repr(k), "--preset", preset,
            "--json"]
    for name, value in spec.items():
        args += ["--" + name.replace("_", "-"), repr(value) if isinstance(value, float)
                 else str(value)]
    if not refine:
        args.append("--no-refine")
    out = subprocess.run(binary() + args, check=True, capture_output=True, text=True).stdout
    return [json.loads(line) for line in out.splitlines()]


def is_paper(spec):
    return all(abs(spec[k] - v) < 1e-12 for k, v in SPECIMEN.items())


def plot_lambda(spec, m, k, preset, records, path):
    sweep = [math.pi / 2 * i / 32 for i in range(33)]
    fig, ax = plt.subplots(figsize=(7.0, 5.0))
    curves = [(m, k, "-", f"this model, m = {m}, k = {k}")]
    if is_paper(spec):
        curves += [(1, 0.6, "--", "m = 1, k = 0.6"), (0, k, ":", "m = 0 (rocking-sliding)")]
    for mm, kk, style, label in curves:
        rs = corner(sweep, spec, mm, kk, preset, refine=False)
        ax.plot([math.degrees(r["alpha"]) for r in rs], [r["lambda_alpha"] for r in rs],
                style, color="C0" if mm == m and kk == k else "0.45", label=label)
    ax.plot([math.degrees(r["alpha"]) for r in records], [r["lambda_alpha"] for r in records],
            "o", color="C0", label="requested orientations (joint-aligned optimum)")
    if is_paper(spec):
        deg = [math.degrees(a) for a in PAPER_ALPHAS]
        ax.plot(deg, TABLE1, "s", mfc="none", color="C3", label="paper, Table 1 (experiment)")
        ax.plot(deg, TABLE5, "^", mfc="none", color="C2", label="paper, Table 5 (LA, k = 0.3)")
        ax.axvspan(0, 45, color="0.93", zorder=0)
        ax.text(22.5, ax.get_ylim()[1] - 0.004, "not tested (symmetric specimen:\nthe mirror of 45..90 deg)",
                ha="center", va="top", fontsize=8, color="0.4")
    ax.set_xlabel("load orientation alpha (deg from the x axis)")
    ax.set_ylabel("collapse multiplier lambda_alpha")
    ax.set_xlim(0, 90)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def plot_unequal(spec, m, k, preset, path):
    sweep = [math.pi / 2 * i / 32 for i in range(33)]
    fig, ax = plt.subplots(figsize=(7.0, 4.0))
    for by, style in [(4, "--"), (spec["blocks_y"], "-"), (10, ":")]:
        s = dict(spec, blocks_y=by)
        rs = corner(sweep, s, m, k, preset, refine=False)
        ax.plot([math.degrees(r["alpha"]) for r in rs], [r["lambda_alpha"] for r in rs], style,
                label=f"WX {spec['blocks_x']} blocks, WY {by} blocks")
    ax.set_xlabel("load orientation alpha (deg from the x axis)")
    ax.set_ylabel("collapse multiplier lambda_alpha")
    ax.set_xlim(0, 90)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(f"walls of unequal length (m = {m}, k = {k}): model prediction, untested",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def wall_blocks(spec, length):
    """Blocks of one wall's elevation: (s0, s1, z0, z1), head joints alternating per course."""
    v, h = spec["l"] / 2, spec["h"]
    out = []
    for c in range(spec["courses"]):
        edges = [0.0]
        s = 2 * v if c % 2 == 0 else v
        while s < length - 1e-9:
            edges.append(s)
            s += 2 * v
        edges.append(length)
        out += [(a, b, c * h, (c + 1) * h) for a, b in zip(edges, edges[1:])]
    return out


def inside(poly, p):
    """Point in convex counter-clockwise polygon."""
    n = len(poly)
    for i in range(n):
        (ax_, ay), (bx, by) = poly[i], poly[(i + 1) % n]
        if (bx - ax_) * (p[1] - ay) - (by - ay) * (p[0] - ax_) < -1e-12:
            return False
    return True


def draw_wall(ax, spec, g, wall, sign, in_plane, m, wedge_green=True):
    """One wall's elevation; s runs along `sign` (WY drawn leftwards from the corner)."""
    H = spec["courses"] * spec["h"]
    length = spec["l"] * spec["blocks_x" if wall == "X" else "blocks_y"]
    if wall == "X":
        green, red, base = g["X1"], g["X2"], g["X3"]
    else:
        green, red, base = g["Y2"], g["Y1"], g["Y3"]
    z1 = g["Z1"]
    g_poly = [(0, z1), (base, z1), (green if m == 1 else green + red, H), (0, H)]
    r_poly = [(base, z1), (green + red, H), (green, H)]
    for s0, s1, z0, zz in wall_blocks(spec, length):
        c = ((s0 + s1) / 2, (z0 + zz) / 2)
        color = "white"
        if inside(g_poly, c):
            color = "#9ccf8f"
        elif m == 1 and red > 0 and inside(r_poly, c):
            # [A3]: the red part of the in-plane wall stays at rest in the flexural mechanism.
            color = "#eeeeee" if (in_plane and wedge_green) else "#e59a8c"
        ax.add_patch(Rectangle((sign * s0 if sign > 0 else sign * s1, z0), s1 - s0, zz - z0,
                               facecolor=color, edgecolor="0.55", lw=0.4))
    for poly, col in [(g_poly, "#2f7d1f"), (r_poly, "#b2341c")]:
        if col == "#b2341c" and (m == 0 or red <= 0):
            continue
        ax.add_patch(Polygon([(sign * x, z) for x, z in poly], closed=True, fill=False,
                             edgecolor=col, lw=1.2))


def draw_macroblocks(spec, records, m, path):
    n = len(records)
    fig, axes = plt.subplots(n, 1, figsize=(8.0, 1.9 * n), squeeze=False)
    for ax, r in zip(axes[:, 0], records):
        g = r["geometry"]
        direction_y = r["alpha"] >= math.pi / 4
        draw_wall(ax, spec, g, "Y", -1, in_plane=direction_y, m=m)
        draw_wall(ax, spec, g, "X", +1, in_plane=not direction_y, m=m)
        ax.axvline(0, color="k", lw=0.8)
        ax.set_aspect("equal")
        ax.set_xlim(-spec["l"] * spec["blocks_y"], spec["l"] * spec["blocks_x"])
        ax.set_ylim(0, spec["courses"] * spec["h"])
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(
            f"alpha = {math.degrees(r['alpha']):.2f} deg: lambda = {r['lambda_alpha']:.4f} "
            f"(lambda_X {r['lambda_X']:.3f}, lambda_Y {r['lambda_Y']:.3f})   "
            f"<- WY | WX ->", fontsize=8)
    fig.text(0.5, 0.005, "green: green parts (move with the hinge axis); red: red triangles "
             "(out-of-plane flexure); grey: red part of the in-plane wall, at rest [A3]",
             ha="center", fontsize=7)
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--alpha", type=float, nargs="+", default=PAPER_ALPHAS)
    p.add_argument("--m", type=int, default=1)
    p.add_argument("--k", type=float, default=0.3)
    p.add_argument("--preset", default="paper", choices=["paper", "literal"])
    for name, value in SPECIMEN.items():
        p.add_argument("--" + name.replace("_", "-"), type=type(value), default=value)
    p.add_argument("--out", default=str(ROOT / "docs" / "img"))
    p.add_argument("--beyond", action="store_true", help="also plot walls of unequal length")
    a = p.parse_args()
    spec = {name: getattr(a, name) for name in SPECIMEN}
    records = corner(a.alpha, spec, a.m, a.k, a.preset)
    print(f"{'alpha':>8} {'lambda':>8} {'lam_X':>8} {'lam_Y':>8} {'NM':>8}   geometry (mm)")
    for r in records:
        g = r["geometry"]
        nm = r["refined"]["lambda_alpha"] if r["refined"] else float("nan")
        print(f"{r['alpha']:8.5f} {r['lambda_alpha']:8.4f} {r['lambda_X']:8.4f} "
              f"{r['lambda_Y']:8.4f} {nm:8.4f}   "
              + " ".join(f"{k}={1e3 * g[k]:.1f}" for k in ["X1", "X2", "X3", "Y1", "Y2", "Y3", "Z1"]))
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    plot_lambda(spec, a.m, a.k, a.preset, records, out / "corner_lambda_alpha.png")
    draw_macroblocks(spec, records, a.m, out / "corner_macroblocks.png")
    written = ["corner_lambda_alpha.png", "corner_macroblocks.png"]
    if a.beyond:
        plot_unequal(spec, a.m, a.k, a.preset, out / "corner_unequal_walls.png")
        written.append("corner_unequal_walls.png")
    print("wrote", ", ".join(str(out / w) for w in written))


if __name__ == "__main__":
    main()
