#!/usr/bin/env python3
"""Work-precision figure of the dynamics bench.

Reads target/bench-dynamics/work_precision.csv (written by
`cargo bench -p rocking --bench dynamics`) and writes
docs/img/dynamics_work_precision.png:

    .venv/bin/python benches/plot_dynamics.py
"""

import csv
import math
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
SRC = ROOT / "target" / "bench-dynamics" / "work_precision.csv"
OUT = ROOT / "docs" / "img" / "dynamics_work_precision.png"

STYLE = {
    "Dop853": ("C0", "o", "DOP853 (this crate)"),
    "Dp5": ("C1", "s", "DP5 (this crate)"),
    "RK4": ("C2", "^", "fixed-step RK4"),
    "SciPy": ("C3", "D", "SciPy solve_ivp DOP853"),
}
TITLES = {
    "rigid": "(a) rigid free rocking, 10 impacts vs exact",
    "dharahara": "(b) Dharahara, fm 2 MPa, 0.16 g pulse, 100 Hz",
}


def main():
    rows = list(csv.DictReader(SRC.open()))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, case in zip(axes, ["rigid", "dharahara"]):
        for solver, (color, marker, label) in STYLE.items():
            pts = [
                (float(r["error"]), float(r["seconds"]))
                for r in rows
                if r["case"] == case and r["solver"] == solver
            ]
            pts = [(e, t) for e, t in pts if math.isfinite(e) and e > 0 and t > 0]
            if not pts:
                continue
            # in the order of the runs (tolerance or step decreasing); the
            # error of the references themselves is about 1e-14
            e, t = zip(*pts)
            ax.loglog([max(x, 1e-15) for x in e], t, marker=marker, color=color, label=label,
                      linewidth=0.8)
        ax.set_xlabel("max relative error of the compared quantities")
        ax.set_ylabel("wall time per run, s")
        ax.set_title(TITLES[case], fontsize=10)
        ax.invert_xaxis()
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    OUT.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT, dpi=120)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
