"""The comparison of the three views of the corner at the paper's five orientations:
the experiments and the paper's 3DEC model (its Tables 1, 2, 4), the macroblock limit
analysis (`rocking-corner`, its Table 5 and ours at k = 0.3 and 1), the block LP and the
DEM for each end condition. Every case is cached as one JSON file in the output
directory, so a study resumes where it stopped; progress goes to stderr."""

import json
import math
import subprocess
import sys
import time
from pathlib import Path

from . import draw, lp
from .assembly import Assembly
from .specimen import ORIENTATIONS, Specimen

#: The paper's numbers at pi/4, 5pi/16, 3pi/8, 7pi/16, pi/2 (C. Colombo et al., Construction
#: and Building Materials, 2022: Table 1 experiments, Table 2 3DEC, Table 4 3DEC with
#: (kn, ks) x 0.5 and x 0.3, Table 5 its macroblock analysis at k = 0.3).
PAPER = {
    "experiment": [0.287, 0.270, 0.248, 0.239, 0.236],
    "3DEC": [0.315, 0.290, 0.270, 0.265, 0.270],
    "3DEC k x0.5": [0.300, 0.270, 0.255, 0.250, 0.255],
    "3DEC k x0.3": [0.280, 0.255, 0.240, 0.235, 0.240],
    "paper LA k=0.3": [0.290, 0.284, 0.263, 0.238, 0.229],
}


def cached(out, name, compute):
    """The JSON in out/name.json, else compute() written there first."""
    path = Path(out) / f"{name}.json"
    if path.is_file():
        return json.loads(path.read_text())
    t0 = time.process_time()
    result = compute()
    result.setdefault("cpu_s", time.process_time() - t0)
    path.write_text(json.dumps(result))
    return result


def lp_case(specimen, alpha, facets=8):
    """The block LP as a JSON-able dict (lambda, moving block labels, velocities)."""
    a = Assembly.from_specimen(specimen)
    r = lp.solve(a, alpha, facets=facets)
    return {"lam": r.lam, "moving": r.moving, "labels": [a.blocks[i].label() for i in r.moving],
            "velocity": r.velocity.tolist(), "power_dead": r.power_dead, "opening_min": r.opening_min,
            "status": r.status}


def la_cases(binary, k, alphas, courses=9, blocks=7):
    """lambda_alpha of the macroblock analysis (`rocking-corner --json`, grid optimum)."""
    args = ["--alpha", *[f"{min(a, 1.5707963):.7f}" for a in alphas], "--k", str(k), "--no-refine", "--json",
            "--courses", str(courses), "--blocks-x", str(blocks), "--blocks-y", str(blocks)]
    out = subprocess.run([binary, *args], capture_output=True, text=True, check=True).stdout
    rows = [json.loads(line) for line in out.splitlines() if line.strip()]
    return [r["lambda_alpha"] for r in rows]


def run(out, ends=("fixed", "free", "outOfPlane"), mu=0.66, methods=("lp",), binary=None, dem_protocol=None,
        log=print, courses=9, blocks=7):
    """Every case of the study into out/ (the paper's columns only make sense for the
    paper's 9 courses of 7 blocks); returns the table's columns."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    alphas = [a for a, _ in ORIENTATIONS]
    columns = dict(PAPER)
    if binary:
        for k in (0.3, 1.0):
            la = cached(out, f"la_k{k:g}", lambda k=k: {"lam": la_cases(binary, k, alphas, courses, blocks)})
            columns[f"LA k={k:g}"] = la["lam"]
    results = {}
    todo = [(m, e, i) for m in methods for e in ends for i in range(len(alphas))]
    for n, (method, e, i) in enumerate(todo, 1):
        label = ORIENTATIONS[i][1]
        geometry = {"courses": courses, "blocks": blocks}
        spec = Specimen(ends=e, mu=mu, **geometry)
        name = f"{method}_{e}_mu{mu:g}_{i}" + ("" if (courses, blocks) == (9, 7) else f"_{courses}x{blocks}")
        t0 = time.time()
        if method == "lp":
            r = cached(out, name, lambda: lp_case(spec, alphas[i]))
        else:
            from . import dem
            job = {"specimen": {"ends": e, "mu": mu, **geometry}}
            r = cached(out, name, lambda: dem.run_isolated(job, alphas[i], dem_protocol or dem.Protocol()))
        log(f"[{n}/{len(todo)}] {method} ends={e} alpha={label}: lambda {r['lam']:.4f} "
            f"({time.time() - t0:.1f} s, {r.get('cpu_s', 0):.1f} s CPU when computed)")
        results.setdefault(f"{method.upper()} {e}", [None] * len(alphas))[i] = r["lam"]
        results.setdefault(f"_{method}_{e}", [None] * len(alphas))[i] = r
    columns.update({k: v for k, v in results.items() if not k.startswith("_")})
    write_table(out / "table.md", columns)
    plot(out / "lambda_alpha.png", columns)
    for key, rs in results.items():
        if key.startswith("_lp_"):
            e = key[4:]
            for i in (0, 2, 4):
                spec = Specimen(ends=e, mu=mu, courses=courses, blocks=blocks)
                mechanism_figure(out / f"mechanism_lp_{e}_{i}.png", spec, rs[i],
                                 f"LP, ends {e}, alpha {ORIENTATIONS[i][1]}")
    return columns


def write_table(path, columns):
    labels = [lab for _, lab in ORIENTATIONS]
    lines = ["| alpha | " + " | ".join(columns) + " |", "|---" * (len(columns) + 1) + "|"]
    for i, lab in enumerate(labels):
        cells = [f"{v[i]:.3f}" if v[i] is not None and not math.isnan(v[i]) else "-" for v in columns.values()]
        lines.append(f"| {lab} | " + " | ".join(cells) + " |")
    path.write_text("\n".join(lines) + "\n")


def plot(path, columns):
    """lambda against alpha, as the paper's Fig. 10."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x = [a for a, _ in ORIENTATIONS]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name, ys in columns.items():
        style = "k-" if name == "experiment" else ("--" if name.startswith(("3DEC", "paper")) else "-")
        ax.plot(x, [float("nan") if y is None else y for y in ys], style, marker="o", ms=3, label=name)
    ax.set_xticks(x, [lab for _, lab in ORIENTATIONS])
    ax.set_xlabel("load orientation alpha")
    ax.set_ylabel("collapse multiplier lambda")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def mechanism_figure(path, specimen, result, title):
    """The LP's mechanism (blocks moved by the dual velocities), three views."""
    import numpy as np

    a = Assembly.from_specimen(specimen)
    velocity = np.array(result["velocity"])
    corners = draw.mechanism_corners(a.blocks, velocity, 0.04)
    draw.figure(a.blocks, path, corners, result["moving"], title=title, fixed=a.fixed)


def main(argv=None):
    import argparse

    p = argparse.ArgumentParser()
    p.add_argument("out")
    args = p.parse_args(argv)
    run(args.out, log=lambda s: print(s, file=sys.stderr, flush=True))


if __name__ == "__main__":
    main()
