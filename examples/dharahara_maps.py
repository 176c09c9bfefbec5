"""The Dharahara Tower's overturning maps under one-sine and symmetric Ricker pulses, on the
rigid interface and on its crushing foundation (docs/dharahara.md, "Overturning maps under
pulses"; the maps: docs/maps.md).

    .venv/bin/python examples/dharahara_maps.py [--out DIR] [--crushing PRESET] [--workers N]
                                                [--figure PNG] [--no-check]

For each pulse and body: `rocking.maps.run_map` over a dimensional grid (w_p in rad/s, a_p in
m/s2), boundaries bisected to 1e-3, a tail of 60 s at most (cut where the tower can no longer
overturn); its tables in DIR/<body>-<pulse>/ (runs.parquet, boundaries.parquet, the finished
columns in parts/: a rerun goes on where it stopped). Then the least overturning amplitudes
side by side (DIR/least_overturning.csv, printed as a Markdown table), one figure (default
DIR/dharahara-maps.png), and a check of the least overturning amplitudes at the case study's
tolerance: the bracket of each is run again at rtol 1e-11 (the FMU's default is 1e-9) with the
whole tail, and the outcomes that change are counted.
"""

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

from rocking import RockingFMU
from rocking.map_store import MapStore
from rocking.maps import MapSpec, boundaries, metadata, run_map, write_parquet
from rocking.presets import preset
from rocking.pulses import Pulse

PULSES = ("one-sine", "ricker")
FREQUENCIES = list(np.round(np.arange(0.5, 6.01, 0.25), 10))  # w_p, rad/s
AMPLITUDES = list(np.geomspace(0.5, 16.0, 41))  # a_p, m/s2: steps of 9 %
TAIL = 60.0  # s, at most
TOL = 1e-3


def least(bounds):
    """{w_p: (least overturning a_p, the end of its interval, below_grid)}."""
    out = {}
    for w, g in bounds.groupby("w_p"):
        first = g.sort_values("start").iloc[0]
        out[float(w)] = (float(first["start"]), float(first["end"]), bool(first["below_grid"]))
    return out


def check_brackets(fmu, spec, bounds, rtol=1e-11):
    """The first interval's bracket (a_from_lo safe, a_from_hi overturning) of each frequency
    run again at `rtol` through the whole tail: (brackets checked, outcomes changed)."""
    checked = changed = 0
    for _, b in bounds.sort_values("start").groupby("w_p").head(1).iterrows():
        for a, expected in ((b["a_from_lo"], False), (b["a_from_hi"], True)):
            if not math.isfinite(a):
                continue
            pulse = Pulse(spec.shape, a, b["w_p"])
            t, ag = pulse.samples(spec.per_period)
            run = fmu.simulate(spec.params, ag=(t, ag), stop_time=pulse.duration + spec.tail, rtol=rtol,
                               outputs=("thetaOverAlpha", "impacts"))
            checked += 1
            changed += bool(run.overturned) != expected
    return checked, changed


def figure(path, results, labels, p, g_tan_alpha):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(PULSES), figsize=(7.6, 3.5), sharey=True)
    colors = {"rigid": "k", "crushing": "#d62728"}
    for ax, shape in zip(axes, PULSES):
        for body, label in labels.items():
            lo = results[body, shape]
            ws = sorted(lo)
            ax.plot(ws, [lo[w][0] for w in ws], lw=1.4, color=colors[body], label=f"{label}: overturning begins")
            ends = [(w, lo[w][1]) for w in ws if math.isfinite(lo[w][1])]
            if ends:
                ax.plot(*zip(*ends), "--", lw=1.0, color=colors[body], marker=".", ms=4,
                        label=f"{label}: and stops again (a safe window above)")
        ax.axhline(g_tan_alpha, color="0.5", lw=0.8, ls=":", label="rigid uplift, g tan(alpha)")
        ax.set_yscale("log")
        ax.set_xlim(FREQUENCIES[0], FREQUENCIES[-1])
        ax.set_ylim(AMPLITUDES[0], AMPLITUDES[-1])
        ax.text(0.97, 0.04, f"{shape} pulse", transform=ax.transAxes, ha="right", fontsize=9)
        ax.set_xlabel("w_p (rad/s)")
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        top = ax.secondary_xaxis("top", functions=(lambda w: w / p, lambda x: x * p))
        top.set_xlabel("w_p / p", fontsize=8)
        top.tick_params(labelsize=7)
    axes[0].set_ylabel("a_p (m/s2); no run above 16")
    handles, names = axes[1].get_legend_handles_labels()
    fig.legend(handles, names, loc="upper center", ncol=2, fontsize=7, frameon=False)
    fig.tight_layout(rect=(0, 0, 1, 0.84))
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/dharahara-maps", help="output folder (default out/dharahara-maps)")
    ap.add_argument("--crushing", default="dharahara-F170-fm2", help="the crushing bed's preset "
                    "(default dharahara-F170-fm2: foundation kn 170 MPa/m, fm 2 MPa)")
    ap.add_argument("--workers", type=int, default=None, help="processes (default one per core)")
    ap.add_argument("--figure", help="the figure's path (default OUT/dharahara-maps.png)")
    ap.add_argument("--no-check", action="store_true", help="no rerun of the brackets at rtol 1e-11")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    bodies = {"rigid": preset("dharahara-rigid"), "crushing": preset(args.crushing)}
    results, rows, scales = {}, [], {}
    with RockingFMU() as fmu:
        for body, params in bodies.items():
            for shape in PULSES:
                spec = MapSpec(params=params, shape=shape, frequencies=FREQUENCIES, amplitudes=AMPLITUDES,
                               dimensionless=False, tol=TOL, tail=TAIL)
                folder = out / f"{body}-{shape}"
                folder.mkdir(exist_ok=True)
                t0 = time.perf_counter()
                runs = run_map(spec, fmu, workers=args.workers, store=MapStore(folder / "parts"))
                wall = time.perf_counter() - t0
                bounds = boundaries(runs, spec)
                meta = metadata(spec, {"body": body, "preset": "dharahara-rigid" if body == "rigid" else args.crushing})
                write_parquet(runs, folder / "runs.parquet", meta)
                write_parquet(bounds, folder / "boundaries.parquet", meta)
                results[body, shape] = least(bounds)
                scales[body] = spec.scales
                tails = runs["tail_end"].value_counts().to_dict()
                line = (f"{body:<8} {shape:<9} {len(runs)} runs in {wall:.1f} s "
                        f"({runs.attrs['resumed']} columns read from parts/); tails: {tails}; "
                        f"thetaOv {spec.scales['thetaOv']:.4f} rad, alpha {spec.scales['alpha']:.4f}")
                if not args.no_check:
                    checked, changed = check_brackets(fmu, spec, bounds)
                    line += f"; at rtol 1e-11, {changed} of {checked} bracket runs change outcome"
                print(line, flush=True)
    p = scales["rigid"]["p"]
    for w in FREQUENCIES:
        row = {"w_p": w, "w_p_over_p": w / p}
        for shape in PULSES:
            for body in bodies:
                row[f"{shape} {body}"] = results[body, shape].get(w, (math.nan,))[0]
            row[f"{shape} change"] = row[f"{shape} crushing"] / row[f"{shape} rigid"] - 1
        rows.append(row)
    table = pd.DataFrame(rows)
    table.to_csv(out / "least_overturning.csv", index=False)
    print("\n| w_p (rad/s) | w_p/p | " + " | ".join(f"{s} rigid | {s} crushing | change" for s in PULSES) + " |")
    print("|---" * (2 + 3 * len(PULSES)) + "|")
    for r in rows:
        cells = [f"{r['w_p']:g}", f"{r['w_p_over_p']:.2f}"]
        for s in PULSES:
            cells += [f"{r[f'{s} rigid']:.3f}", f"{r[f'{s} crushing']:.3f}", f"{r[f'{s} change']:+.0%}"]
        print("| " + " | ".join(cells) + " |")
    path = Path(args.figure) if args.figure else out / "dharahara-maps.png"
    labels = {"rigid": "rigid", "crushing": args.crushing.removeprefix("dharahara-")}
    figure(path, results, labels, p, scales["rigid"]["g_tan_alpha"])
    print(f"\nwrote {out}/*/runs.parquet, boundaries.parquet, {out / 'least_overturning.csv'}, {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
