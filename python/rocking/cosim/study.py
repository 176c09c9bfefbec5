"""The co-simulation studies of docs/cosimulation.md: convergence of each scheme
against the monolithic reference, and when two-way coupling matters.

    python -m rocking.cosim.study [--out docs/img] [--quick] [--workers 2]

writes cosim_convergence.png and cosim_coupling.png to --out and prints the
tables of docs/cosimulation.md (markdown) and a JSON of every figure to
--out/cosim_study.json. Takes ~2 min on 2 cores (--quick: a smaller grid).
"""

import argparse
import json
import math
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from .master import CoupledFMUs, frame_params, sine_ground
from .reference import ElasticRectangle, Reference

#: The block of both studies: the FMU's default prism (0.5 m x 1 m x 2.5 m, 2250 kg)
#: on an elastic bed of 1e8 Pa/m (thetaJo = 1.8e-3 rad).
BLOCK = {"interface": "elastic", "kn": 1e8}


def convergence_case():
    """3 storeys of 1e4 kg and 4e6 N/m (T1 = 0.71 s), 2 % modal damping, the block on the
    roof (block/floor mass 0.225), 3 cycles of a 2 Hz, 4 m/s2 ground sine, 3 s."""
    return dict(frame=frame_params([1e4] * 3, [4e6] * 3, zeta=0.02), block=dict(BLOCK), floor=3,
                ground=sine_ground(4.0, 2.0, cycles=3), stop_time=3.0)


#: (scheme, inputs, reject) of the convergence study.
VARIANTS = [("jacobi", "constant", True), ("gauss-seidel", "constant", True),
            ("jacobi", "extrapolate", True), ("gauss-seidel", "extrapolate", True),
            ("jacobi", "extrapolate", False), ("gauss-seidel", "extrapolate", False)]
STEPS = [0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625]
#: The orders are fitted where the error is asymptotic: h <= FIT_BELOW.
FIT_BELOW = 0.005


def errors(res, ref):
    """Relative errors of a run against the reference: max over the communication points
    of theta and of the floor's acceleration (each over the reference's peak), and of
    the peaks themselves (the run's sampled peak against the reference's true one)."""
    r = ref.at(res.time)
    pth, pa = ref.peak("theta"), ref.peak("a_floor")
    return {"theta": float(np.max(np.abs(res.theta - r["theta"])) / pth),
            "a_floor": float(np.max(np.abs(res.a_floor - r["a_floor"])) / pa),
            "peak_theta": float(abs(np.max(np.abs(res.theta)) - pth) / pth),
            "peak_a_floor": float(abs(np.max(np.abs(res.a_floor)) - pa) / pa)}


def slope(h, err, below=None):
    """Fitted order: the slope of log(err) against log(h) (over h <= below if given)."""
    h, err = np.asarray(h, float), np.asarray(err, float)
    keep = h <= below * (1 + 1e-9) if below else np.ones(len(h), bool)
    return float(np.polyfit(np.log(h[keep]), np.log(err[keep]), 1)[0])


def convergence(steps=STEPS, variants=VARIANTS, fmus=None):
    """Rows of (scheme, inputs, reject, step, errors...) for the convergence case."""
    case = convergence_case()
    ref = Reference(**case)
    own = fmus is None
    fmus = fmus or CoupledFMUs()
    rows = []
    try:
        for scheme, inputs, reject in variants:
            for h in steps:
                res = fmus.run(**case, step=h, scheme=scheme, inputs=inputs, reject=reject)
                rows.append(dict(scheme=scheme, inputs=inputs, reject=reject, step=h,
                                 rejected=res.rejected, wall=res.wall, **errors(res, ref)))
    finally:
        if own:
            fmus.close()
    return rows


def step_for(rows, key, target=0.01):
    """The largest step of each variant whose error `key`, and every smaller step's, is
    below target (nan if none)."""
    out = {}
    for v in {(r["scheme"], r["inputs"], r["reject"]) for r in rows}:
        sel = sorted((r for r in rows if (r["scheme"], r["inputs"], r["reject"]) == v),
                     key=lambda r: r["step"])
        ok = math.nan
        for r in sel:
            if r[key] >= target:
                break
            ok = r["step"]
        out[v] = ok
    return out


# -- when does two-way coupling matter -----------------------------------------------

def sweep_case(mass_ratio, freq_ratio, amplitude=None):
    """One storey carrying the block: floor mass = block mass / mass_ratio, period
    T1 = freq_ratio / p (p = sqrt(W R0 / IO), the block's rocking frequency parameter),
    5 % damping; ground: a sine at 1/T1 for max(3 T1, 2 s), then 2 s more."""
    body = ElasticRectangle(BLOCK)
    p = math.sqrt(body.W * body.R0 / body.IO)
    T1 = freq_ratio / p
    m1 = body.m / mass_ratio
    k1 = m1 * (2 * math.pi / T1) ** 2
    cycles = max(3, math.ceil(2.0 / T1))
    amp = 1.0 if amplitude is None else amplitude
    return dict(frame=frame_params([m1], [k1], zeta=0.05), block=dict(BLOCK), floor=1,
                ground=sine_ground(amp, 1.0 / T1, cycles=cycles), stop_time=cycles * T1 + 2.0)


def _sweep_point(args):
    mass_ratio, freq_ratio, amplitude = args
    out = {"mass_ratio": mass_ratio, "freq_ratio": freq_ratio}
    for coupling in ("one-way", "two-way"):
        ref = Reference(**sweep_case(mass_ratio, freq_ratio, amplitude), coupling=coupling, rtol=1e-10)
        out[coupling] = {"peak_theta": ref.peak("theta"), "peak_a_floor": ref.peak("a_floor"),
                         "overturned": ref.overturned}
    return out


def _calibrate(freq_ratio, target):
    """The ground amplitude (m/s2) for which the one-way peak theta is target * thetaOv:
    bisection between a shake that stays below and one that goes beyond or overturns."""
    def peak(amp):
        ref = Reference(**sweep_case(1e-4, freq_ratio, amp), coupling="one-way", rtol=1e-8)
        return 1.0 if ref.overturned else ref.peak("theta") / ref.body.thetaOv
    lo, hi = 0.0, 1.0
    while peak(hi) < target:
        lo, hi = hi, 2 * hi
    for _ in range(7):  # to 1/128 of the bracket: the target is a scale, not a precise value
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if peak(mid) < target else (lo, mid)
    return lo


def coupling_sweep(mass_ratios, freq_ratios, theta_target=0.5, intensity=0.9, workers=2):
    """The one-way and two-way reference at each (mass ratio, frequency ratio). At each
    frequency ratio the ground amplitude is `intensity` times the one at which the
    one-way block reaches theta_target * thetaOv. Below 1: where the frame is slow
    against the block (T1 p >= 3) the peak rotation jumps from small rocking to
    overturning within a few per cent of amplitude, and at the brink any difference,
    two-way or not, changes the outcome."""
    from tqdm import tqdm
    with ProcessPoolExecutor(workers) as pool:
        brink = pool.map(_calibrate, freq_ratios, [theta_target] * len(freq_ratios))
        amps = {fr: intensity * a for fr, a in zip(freq_ratios, brink)}
        jobs = [(mr, fr, amps[fr]) for fr in freq_ratios for mr in mass_ratios]
        rows = list(tqdm(pool.map(_sweep_point, jobs), total=len(jobs), desc="coupling sweep",
                         file=sys.stderr))
    for r in rows:
        one, two = r["one-way"], r["two-way"]
        r["amplitude"] = amps[r["freq_ratio"]]
        r["d_theta"] = abs(two["peak_theta"] - one["peak_theta"]) / one["peak_theta"]
        r["d_a_floor"] = abs(two["peak_a_floor"] - one["peak_a_floor"]) / one["peak_a_floor"]
    return rows


# -- plots -------------------------------------------------------------------------

def plot_convergence(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharex=True)
    styles = {("jacobi", "constant"): ("C0", "o"), ("gauss-seidel", "constant"): ("C1", "s"),
              ("jacobi", "extrapolate"): ("C2", "^"), ("gauss-seidel", "extrapolate"): ("C3", "v")}
    for ax, key, title in ((axes[0], "theta", "block rotation theta"),
                           (axes[1], "a_floor", "floor absolute acceleration a[j]")):
        for (scheme, inputs, reject) in dict.fromkeys((r["scheme"], r["inputs"], r["reject"]) for r in rows):
            sel = [r for r in rows if (r["scheme"], r["inputs"], r["reject"]) == (scheme, inputs, reject)]
            h = np.array([r["step"] for r in sel])
            e = np.array([r[key] for r in sel])
            color, marker = styles[(scheme, inputs)]
            label = f"{scheme}, {inputs}{'' if reject else ', no rejection'} (slope {slope(h, e, FIT_BELOW):.2f})"
            ax.loglog(h, e, color=color, marker=marker, ls="-" if reject else ":", label=label)
        h = np.array(STEPS)
        ax.loglog(h, 0.1 * h / h[0], "k--", lw=0.8)
        ax.loglog(h, 0.1 * (h / h[0]) ** 2, "k-.", lw=0.8)
        ax.axhline(0.01, color="grey", lw=0.6)
        _label(ax, f"error in {title}", "communication step h (s)", "max |co-sim - reference| / reference peak", 7)
    fig.suptitle("Co-simulation error against the monolithic reference (dashed: slope 1, dash-dot: slope 2; "
                 f"grey: 1 %; slopes fitted for h <= {FIT_BELOW:g} s)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _label(ax, title, xlabel, ylabel, legend_size):
    """Title, axis labels, a log grid and the legend of one panel."""
    ax.set_title(title)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=legend_size)


def plot_sweep(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharex=True)
    freqs = sorted({r["freq_ratio"] for r in rows})
    for ax, key, title in ((axes[0], "d_theta", "peak block rotation"),
                           (axes[1], "d_a_floor", "peak floor acceleration")):
        for i, fr in enumerate(freqs):
            sel = sorted((r for r in rows if r["freq_ratio"] == fr), key=lambda r: r["mass_ratio"])
            mu = np.array([r["mass_ratio"] for r in sel])
            d = np.maximum([r[key] for r in sel], 1e-12)
            ax.loglog(mu, d, marker="o", color=f"C{i}", label=f"T1 p = {fr:g}")
            ov = [k for k, r in enumerate(sel) if r["one-way"]["overturned"] or r["two-way"]["overturned"]]
            if ov:
                ax.loglog(mu[ov], d[ov], "kx", ms=9)
        ax.axhline(0.05, color="grey", lw=0.6)
        _label(ax, f"two-way vs one-way: {title}", "block mass / floor mass", "|two-way - one-way| / one-way", 8)
    fig.suptitle("One storey carrying the block, ground sine at the frame's frequency, 0.9 x the amplitude at which "
                 "the one-way block reaches thetaOv / 2 (x: overturned; grey: 5 %)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _table_convergence(rows):
    lines = ["| scheme | inputs | rejection | order theta | order a[j] | 1 % peak theta | 1 % peak a[j] "
             "| 1 % theta history | 1 % a[j] history |", "|---|---|---|---:|---:|---:|---:|---:|---:|"]
    need = [step_for(rows, k) for k in ("peak_theta", "peak_a_floor", "theta", "a_floor")]
    for v in dict.fromkeys((r["scheme"], r["inputs"], r["reject"]) for r in rows):
        sel = [r for r in rows if (r["scheme"], r["inputs"], r["reject"]) == v]
        h = [r["step"] for r in sel]
        orders = [slope(h, [r[k] for r in sel], FIT_BELOW) for k in ("theta", "a_floor")]
        lines.append(f"| {v[0]} | {v[1]} | {'yes' if v[2] else 'no'} | {orders[0]:.2f} | {orders[1]:.2f} | "
                     + " | ".join(f"{n[v]:g}" for n in need) + " |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m rocking.cosim.study", description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="docs/img", help="folder for the plots and cosim_study.json")
    ap.add_argument("--quick", action="store_true", help="a smaller sweep grid")
    ap.add_argument("--part", choices=("all", "convergence", "sweep"), default="all",
                    help="run one study only (the other's figures in cosim_study.json are kept)")
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    store = out / "cosim_study.json"
    data = json.loads(store.read_text()) if store.is_file() else {}
    if args.part in ("all", "convergence"):
        print("convergence ...", file=sys.stderr)
        data["convergence"] = convergence()
        plot_convergence(data["convergence"], out / "cosim_convergence.png")
        print(_table_convergence(data["convergence"]))
    if args.part in ("all", "sweep"):
        mass = [1e-4, 1e-3, 1e-2, 0.05, 0.2, 0.5] if args.quick else \
            [1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 0.03, 0.1, 0.2, 0.5]
        freq = [0.3, 1.0, 3.0] if args.quick else [0.1, 0.3, 1.0, 3.0, 10.0]
        data["sweep"] = sweep = coupling_sweep(mass, freq, workers=args.workers)
        plot_sweep(sweep, out / "cosim_coupling.png")
        _print_sweep(sweep, mass, freq)
    store.write_text(json.dumps(data, indent=1))
    return 0


def _print_sweep(sweep, mass, freq):
    print("\n| T1 p | " + " | ".join(f"mu = {m:g}" for m in mass) + " |")
    print("|---|" + "---:|" * len(mass))
    for fr in freq:
        sel = sorted((r for r in sweep if r["freq_ratio"] == fr), key=lambda r: r["mass_ratio"])
        print(f"| {fr:g} | " + " | ".join(f"{r['d_theta']:.2g} / {r['d_a_floor']:.2g}" for r in sel) + " |")
    theta_ov = ElasticRectangle(BLOCK).thetaOv
    print("\none-way peak theta / thetaOv and ground amplitude (m/s2): " + ", ".join(
        f"T1 p = {fr:g}: {r['one-way']['peak_theta'] / theta_ov:.3f}, {r['amplitude']:.3g}"
        for fr in freq for r in sweep if r["freq_ratio"] == fr and r["mass_ratio"] == mass[0]))


if __name__ == "__main__":
    sys.exit(main())
