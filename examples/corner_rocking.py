"""From a corner's limit analysis to a rocking run (docs/corner.md, section 10).

For one load orientation, `rocking-corner --body` writes the optimal macroblock
as RockingBlock FMU parameters, for both bodies (geometric: B = 2b, uplift at
lambda_rock g; threshold-matched: B = 2 b_eq, uplift at the limit-analysis
lambda g). Each body is then rocked under one of the shipped records, scaled
up until it overturns: a scan of scale factors finds the first overturning
one, bisection narrows it. Rocking is not monotone in the scale (a stronger
record can fail to overturn a block a weaker one overturns), so the result is
the smallest overturning scale the scan found, not a proven threshold.

    python examples/corner_rocking.py                          # pi/2, Coalinga 1983 (CSMIP 36456, 90)
    python examples/corner_rocking.py --alpha 0.785398 --record lomaprieta --out out/corner

Prints a table and writes OUT/corner_rocking.png (default docs/img) with the
rotation histories just below and at the overturning scale. Needs the packaged
FMU (`cargo xtask fmu`) and the corner binary (`cargo build --release -p corner`).
"""

import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from rocking import RockingFMU  # noqa: E402
from rocking import groundmotion as gm  # noqa: E402

G = 9.81
RECORDS = {
    "coalinga": ("csmip-coalinga-1983/ce36456p_CE36456.V2", "90"),
    "lomaprieta": ("usgs-lomaprieta-1989/0111a.smc", None),
    "kaikoura": ("geonet-kaikoura-2016/20161113_110259_WTMC_20.V2A", "N28W"),
}


def corner_binary():
    built = REPO / "target" / "release" / "rocking-corner"
    if built.is_file():
        return [str(built)]
    return ["cargo", "run", "--quiet", "--release", "-p", "corner", "--bin", "rocking-corner", "--"]


def body(alpha, kind, extra):
    """(FMU parameters, the stderr line saying where they come from)."""
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "body.json"
        out = subprocess.run(corner_binary() + ["--alpha", repr(alpha), "--no-refine", "--body",
                                                str(path), "--body-kind", kind, *extra],
                             check=True, capture_output=True, text=True)
        return json.loads(path.read_text()), out.stderr.strip()


def load(key):
    if key in RECORDS:
        rel, comp = RECORDS[key]
        return gm.read(gm.DATA_DIR / rel, component=comp)
    return gm.read(key)


def overturning_scale(fmu, params, record, scales, bisections=6):
    """(last scale that did not overturn, first that did) from the scan, then bisected."""
    below = None
    for s in scales:
        run = fmu.simulate(params, record=record, scale=s)
        if run.overturned:
            lo, hi = (below if below is not None else 0.0), s
            for _ in range(bisections):
                mid = 0.5 * (lo + hi)
                if fmu.simulate(params, record=record, scale=mid).overturned:
                    hi = mid
                else:
                    lo = mid
            return lo, hi
        below = s
    return below, math.inf


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--alpha", type=float, default=math.pi / 2)
    ap.add_argument("--record", default="coalinga", help="coalinga, lomaprieta, kaikoura or a file")
    ap.add_argument("--out", default=str(REPO / "docs" / "img"))
    ap.add_argument("corner_args", nargs="*", help="more rocking-corner options, after --")
    a = ap.parse_args()
    record = load(a.record)
    pga = float(max(abs(record.acc))) / G
    print(f"record: {record.name} {record.component}, PGA {pga:.3f} g, {record.time[-1]:.1f} s")
    scales = [x / pga for x in (0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.4, 0.6, 0.8, 1.0, 1.5, 2.0)]
    rows, histories = [], []
    with RockingFMU() as fmu:
        for kind in ("geometric", "threshold"):
            params, info = body(a.alpha, kind, a.corner_args)
            print(info)
            lo, hi = overturning_scale(fmu, params, record, scales)
            tan_alpha = params["B"] / 2 / params["hG"]
            rows.append((kind, tan_alpha, lo * pga, hi * pga))
            for s in (lo, hi):
                if s is not None and math.isfinite(s):
                    run = fmu.simulate(params, record=record, scale=s)
                    histories.append((kind, s * pga, run))
    print(f"\n{'body':>10} {'uplift at (g)':>14} {'no overturning at PGA (g)':>26} {'overturning at PGA (g)':>23}")
    for kind, ta, lo, hi in rows:
        print(f"{kind:>10} {ta:>14.4f} {lo:>26.4f} {hi:>23.4f}")
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(2, 1, figsize=(7.5, 5.5), sharex=True)
    for ax, kind in zip(axes, ("geometric", "threshold")):
        for k, p, run in histories:
            if k != kind:
                continue
            r = run.result
            label = f"PGA {p:.3f} g" + (f" (overturns at {run.t_overturn:.2f} s)" if run.overturned else "")
            ax.plot(r["time"], r["thetaOverAlpha"], lw=0.9, label=label)
        ax.set_ylabel("theta / alpha")
        ax.set_title(f"{kind} body", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    ends = [run.t_overturn for _, _, run in histories if run.overturned]
    if ends:
        axes[-1].set_xlim(0, min(float(record.time[-1]), max(ends) + 8.0))
    axes[-1].set_xlabel("time (s)")
    fig.suptitle(f"corner macroblock, alpha = {math.degrees(a.alpha):.2f} deg, "
                 f"{record.name} {record.component} scaled", fontsize=9)
    fig.tight_layout()
    fig.savefig(out / "corner_rocking.png", dpi=130)
    print("wrote", out / "corner_rocking.png")


if __name__ == "__main__":
    main()
