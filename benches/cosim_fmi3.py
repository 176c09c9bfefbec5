"""What FMI 3.0's early return does to the coupled run (docs/cosimulation.md §4b).

    python benches/cosim_fmi3.py [--out docs/img] [--part elastic|rigid|all]

elastic: the convergence case of docs/cosimulation.md §4 (the elastic block on the
  roof of 3 storeys, 3 s) against the monolithic reference, with the FMI 2.0
  master's held and extrapolated schemes (step rejection) beside the FMI 3.0
  master's (inputs held at their start or at their extrapolation's midpoint,
  with the midpoint of the ground's chord; and extrapolated with their rates in
  the der(x) inputs, with the ground's chord, as the 2.0 master; with and
  without early return). Errors as in rocking.cosim.study.errors, plus
  the error at the impacts: the largest error in a[j] at the communication
  points within one step of a reference impact, and the largest difference
  between the reference's impact times and the run's (the zero crossings of
  theta, linear between communication points, exact at an early return).
  Writes cosim_fmi3.png and prints the table. ~5 min on the loaded machine.
rigid: the same case with a rigid block (no closed-form reference: the FMI 2.0
  master, Jacobi, extrapolated, rejection, at 62.5 us is the reference), errors
  in theta at the communication step's grid points (not at early returns: the
  reference is linear between its samples) over [0, 2] s and (2, 3] s for the
  hosts that hold their inputs
  (hostloop.couple, the scheme of the container FMU and the C host), the 2.0
  master and the 3.0 master with early return. ~3.5 min. `--interface NAME`
  and `--stop-time T` run it with another interface law or duration.
Both write their figures to --out/cosim_fmi3.json.
"""

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from rocking.cosim import CoupledFMUs
from rocking.cosim.hostloop import ShearFrameFMU, couple, open_block
from rocking.cosim.reference import Reference
from rocking.cosim.study import FIT_BELOW, STEPS, convergence_case, errors, slope

#: (fmi, inputs, reject, early_return), all Jacobi. The 3.0 master's held and midpoint
#: inputs get the midpoint of the ground's chord, its extrapolated inputs the
#: chord through der(ag) as 2.0's.
VARIANTS = [(2, "constant", True, False), (2, "extrapolate", True, False),
            (3, "constant", False, False), (3, "constant", False, True),
            (3, "midpoint", False, False), (3, "midpoint", False, True),
            (3, "midpoint", True, True),
            (3, "extrapolate", True, False), (3, "extrapolate", False, True),
            (3, "extrapolate", True, True)]
MARKERS = "osv^<>DPXh"
RIGID_STEPS = [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]
RIGID_REFERENCE_STEP = 6.25e-5


def run_options(v):
    """The keyword arguments of CoupledFMUs.run for a variant."""
    fmi, inputs, reject, early = v
    kw = dict(inputs=inputs, reject=reject)
    if fmi == 3:
        kw.update(early_return=early, ground_input="chord" if inputs == "extrapolate" else "midpoint")
    return kw


def label(v):
    fmi, inputs, reject, early = v
    held = {"constant": "held", "midpoint": "midpoint",
            "extrapolate": "extrapolated" if fmi == 2 else "der(x)"}[inputs]
    extras = [x for x, on in (("rejection", reject), ("early return", early)) if on]
    return f"FMI {fmi}.0, {held}" + (", " + " + ".join(extras) if extras else "")


def crossings(time, theta):
    """Times where theta passes through 0: the samples that reach exactly 0 from a
    nonzero one (an early return at an impact; not a block at rest) and linear
    interpolation between samples of opposite signs."""
    t, th = time[1:], theta[1:]
    exact = t[(th == 0.0) & (theta[:-1] != 0.0)]
    k = np.nonzero(th[:-1] * th[1:] < 0)[0]
    between = t[k] - th[k] * (t[k + 1] - t[k]) / (th[k + 1] - th[k])
    return np.sort(np.concatenate([exact, between]))


#: A reference impact counts as found when the run crosses theta = 0 within this time.
FOUND_WITHIN = 0.01  # s


def impact_errors(res, ref, h):
    """(error in a[j] within one step of the reference's impacts / peak, the largest
    difference in impact time over the impacts the run has (s), how many of the
    reference's impacts it has)."""
    near = np.zeros(len(res.time), bool)
    for ti in ref.impact_times:
        near |= np.abs(res.time - ti) <= h * (1 + 1e-9)
    r = ref.at(res.time[near])
    e_a = float(np.max(np.abs(res.a_floor[near] - r["a_floor"]))) / ref.peak("a_floor") if near.any() else 0.0
    got = crossings(res.time, res.theta)
    d = np.array([np.min(np.abs(got - ti)) if len(got) else np.inf for ti in ref.impact_times])
    found = d < FOUND_WITHIN
    return e_a, float(d[found].max()) if found.any() else float("nan"), int(found.sum())


def elastic(fmus):
    case = convergence_case()
    ref = Reference(**case)
    rows = []
    for v in VARIANTS:
        fmi, inputs, reject, early = v
        for h in STEPS:
            res = fmus[fmi].run(**case, step=h, **run_options(v))
            e_a, dt, n_imp = impact_errors(res, ref, h)
            rows.append(dict(fmi=fmi, inputs=inputs, reject=reject, early_return=early, step=h,
                             steps=res.steps, rejected=res.rejected, early_returns=len(res.early_returns),
                             wall=res.wall, a_at_impacts=e_a, impact_time=dt, impacts_found=n_imp,
                             **errors(res, ref)))
            print(f"{label(v)}, h = {h:g}: theta {rows[-1]['theta']:.2e}, a {rows[-1]['a_floor']:.2e}, "
                  f"a at impacts {e_a:.2e}, impact time {dt:.1e} s ({n_imp} of {len(ref.impact_times)})",
                  file=sys.stderr)
    return dict(rows=rows, impacts=list(ref.impact_times))


def _variant_rows(rows, v):
    return sorted((r for r in rows if (r["fmi"], r["inputs"], r["reject"], r["early_return"]) == v),
                  key=lambda r: -r["step"])


def table_elastic(rows):
    lines = ["| master | order theta | order a[j] | theta at 5 / 1.25 ms | a[j] at 5 / 1.25 ms "
             "| a[j] at impacts, 5 / 1.25 ms | impact time at 5 / 1.25 ms (s) (impacts found) "
             "| steps, rejected, early returns at 1.25 ms |",
             "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for v in VARIANTS:
        sel = _variant_rows(rows, v)
        h = [r["step"] for r in sel]
        order = [slope(h, [r[k] for r in sel], FIT_BELOW) for k in ("theta", "a_floor")]
        at = {r["step"]: r for r in sel}
        a, b = at[0.005], at[0.00125]
        lines.append(f"| {label(v)} | {order[0]:.2f} | {order[1]:.2f} | {a['theta']:.1e} / {b['theta']:.1e} "
                     f"| {a['a_floor']:.1e} / {b['a_floor']:.1e} | {a['a_at_impacts']:.1e} / {b['a_at_impacts']:.1e} "
                     f"| {a['impact_time']:.1e} ({a['impacts_found']}) / {b['impact_time']:.1e} ({b['impacts_found']}) "
                     f"| {b['steps']}, {b['rejected']}, {b['early_returns']} |")
    return "\n".join(lines)


def plot_elastic(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), sharex=True)
    panels = (("theta", "error in theta (history)"), ("a_floor", "error in a[j] (history)"),
              ("a_at_impacts", "error in a[j] within one step of an impact"))
    for ax, (key, title) in zip(axes, panels):
        for i, v in enumerate(VARIANTS):
            sel = _variant_rows(rows, v)
            h = np.array([r["step"] for r in sel])
            e = np.maximum([r[key] for r in sel], 1e-12)
            ax.loglog(h, e, marker=MARKERS[i], color=f"C{i}", ls="-" if v[0] == 3 else "--",
                      label=f"{label(v)} ({slope(h, e, FIT_BELOW):.2f})")
        h = np.array(STEPS)
        ax.loglog(h, 0.1 * h / h[0], "k:", lw=0.8)
        ax.loglog(h, 0.1 * (h / h[0]) ** 2, "k-.", lw=0.8)
        ax.set_title(title)
        ax.set_xlabel("communication step h (s)")
        ax.set_ylabel("max |co-sim - reference| / reference peak")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6.5)
    fig.suptitle("Jacobi co-simulation against the monolithic reference: FMI 2.0 master (dashed) and FMI 3.0 "
                 f"master (solid); fitted slopes for h <= {FIT_BELOW:g} s in brackets (dotted: slope 1, "
                 "dash-dot: slope 2)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# -- the rigid block -------------------------------------------------------------------

RIGID_VARIANTS = [("hosts (held inputs, held ground)", None), ("FMI 2.0, held", (2, "constant", False, False)),
                  ("FMI 2.0, held + rejection", (2, "constant", True, False)),
                  ("FMI 2.0, extrapolated + rejection", (2, "extrapolate", True, False)),
                  ("FMI 3.0, held + early return", (3, "constant", False, True)),
                  ("FMI 3.0, midpoint + early return", (3, "midpoint", False, True)),
                  ("FMI 3.0, midpoint + rejection + early return", (3, "midpoint", True, True)),
                  ("FMI 3.0, der(x) + early return", (3, "extrapolate", False, True)),
                  ("FMI 3.0, der(x) + rejection + early return", (3, "extrapolate", True, True))]
WINDOWS_SPLIT = 2.0  # s: the errors are given over [0, 2] s and (2 s, stop time]


def rigid(fmus, interface="rigid", stop_time=3.0):
    case = convergence_case()
    case["block"] = {"interface": interface}
    case["stop_time"] = stop_time
    windows = ((0.0, WINDOWS_SPLIT), (WINDOWS_SPLIT, stop_time))
    ref = fmus[2].run(**case, step=RIGID_REFERENCE_STEP)
    half = fmus[2].run(**case, step=2 * RIGID_REFERENCE_STEP)
    peak = float(np.max(np.abs(ref.theta)))

    def window_errors(time, theta):
        e = np.abs(theta - np.interp(time, ref.time, ref.theta)) / peak
        return [float(e[(time >= lo) & (time <= hi)].max()) for lo, hi in windows]

    rows = []
    for name, v in RIGID_VARIANTS:
        for h in RIGID_STEPS:
            if v is None:
                n = int(round(case["stop_time"] / h))
                t = np.arange(n + 1) * h
                frame = ShearFrameFMU([1e4] * 3, [4e6] * 3, floor=3, zeta=0.02)
                block = open_block(case["block"])
                try:
                    res = couple(frame, block, t, case["ground"](t), h, case["stop_time"], hold="constant",
                                 ground_mode="constant")
                finally:
                    frame.close()
                    block.close()
                time, theta = res.t, res.theta
            else:
                res = fmus[v[0]].run(**case, step=h, **run_options(v))
                # on the grid only: the reference, sampled every 62.5 us, is linear between
                # its samples, and an early return puts a sample at an impact, where theta
                # has a kink (1e-5 of the peak off at this sampling, whatever h)
                grid = ~np.isin(res.time, res.early_returns)
                time, theta = res.time[grid], res.theta[grid]
            rows.append(dict(master=name, step=h, errors=window_errors(time, theta)))
    zc = crossings(ref.time, ref.theta)
    return dict(rows=rows, peak_theta=peak, impacts=[float(x) for x in zc], interface=interface,
                stop_time=stop_time, reference_self=window_errors(half.time, half.theta))


def table_rigid(data):
    end = f"{data['stop_time']:g}"
    lines = ["| master | " + " | ".join(f"h = {h * 1e3:g} ms" for h in RIGID_STEPS)
             + f" | order [0, 2] s | order (2, {end}] s |",
             "|---|" + "---:|" * (len(RIGID_STEPS) + 2)]
    for name, _ in RIGID_VARIANTS:
        sel = [r for r in data["rows"] if r["master"] == name]
        cells = [f"{r['errors'][0]:.1e} / {r['errors'][1]:.1e}" for r in sel]
        orders = [slope(RIGID_STEPS, [r["errors"][w] for r in sel]) for w in range(2)]
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {orders[0]:.2f} | {orders[1]:.2f} |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="docs/img")
    ap.add_argument("--part", choices=("elastic", "rigid", "all"), default="all")
    ap.add_argument("--interface", default="rigid", help="the block's interface in the rigid part")
    ap.add_argument("--stop-time", type=float, default=3.0, help="the rigid part's stop time (s)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    store = out / "cosim_fmi3.json"
    data = json.loads(store.read_text()) if store.is_file() else {}
    fmus = {2: CoupledFMUs(), 3: CoupledFMUs(fmi=3)}
    try:
        if args.part in ("elastic", "all"):
            data["elastic"] = elastic(fmus)
            plot_elastic(data["elastic"]["rows"], out / "cosim_fmi3.png")
            print(table_elastic(data["elastic"]["rows"]))
        if args.part in ("rigid", "all"):
            key = "rigid" if (args.interface, args.stop_time) == ("rigid", 3.0) else \
                f"rigid-{args.interface}-{args.stop_time:g}s"
            data[key] = got = rigid(fmus, args.interface, args.stop_time)
            print(table_rigid(got))
            print(f"reference (62.5 us) against 125 us: {got['reference_self']}; peak theta "
                  f"{got['peak_theta']:.4f} rad; impacts at {np.round(got['impacts'], 3)}")
    finally:
        for f in fmus.values():
            f.close()
    store.write_text(json.dumps(data, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
