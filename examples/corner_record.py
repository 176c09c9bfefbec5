"""The corner under a record: the block assembly in LMGC90 against the macroblock as
a one-sided rocking body through the FMU (docs/corner-record.md).

One record, Coalinga 1983 (CSMIP 36456, component 90), cut to its strong part
(6 s from the start of its 5-95 % Arias window), applied along the load direction
alpha = pi/2 (outwards from WX). Four cases:

- block: a free-standing 0.1 x 0.2 x 0.4 m block on a table (the DEM input's check
  against the planar rigid rocking FMU, two-sided);
- free, fixed: the small corner (3 courses, 3 blocks per wall) with free or clamped ends;
- free-restrained: free ends, WX held inwards above its first course by a slab that
  moves with the ground (the macroblock body's one-sided restraint).

For each, the record is scaled up to collapse: in the DEM by bracketing then
bisection (each run a fresh process, cached as JSON in OUT/runs), for the FMU
bodies (`rocking corner --body`, both kinds, one-sided; also two-sided) by
bisection. Prints a progress line per run, then the table; writes OUT/results.json
and the figure docs/img/corner_record.png.

    nice -n 10 .venv/bin/python examples/corner_record.py            # cached runs are reused
    .venv/bin/python examples/corner_record.py --out /tmp/record     # from scratch elsewhere
"""

import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from rocking import RockingFMU  # noqa: E402
from rocking import groundmotion as gm  # noqa: E402
from rocking.corner_blocks import dem, dynamics  # noqa: E402

G = 9.81
RECORD = ("csmip-coalinga-1983/ce36456p_CE36456.V2", "90")
WINDOW = 6.0  # s of record from the start of its 5-95 % Arias window
REL_WIDTH = 0.03  # the DEM's scale bracket is narrowed to this relative width
#: The FMU bodies each case is set against, the first drawn in the figure at both scales
CASE_BODIES = {"block": ["block"], "free": ["geometric", "geometric-twoSided"],
               "free-restrained": ["geometric", "geometric-e0"], "fixed": ["threshold", "geometric"]}
#: The DEM's first scale per case (then up or down by 15 % until the outcome changes):
#: near the FMU bodies' overturning scales, fixed so that the cached runs stay valid
GUESS = {"block": 1.1, "free": 2.0, "free-restrained": 2.1, "fixed": 2.4}
SMALL = {"courses": 3, "blocks": 3}
BLOCK = (0.1, 0.2, 0.4)  # m: along the motion, across, height
BLOCK_PARAMS = dict(shape="solidRectangle", B=BLOCK[0], L=BLOCK[1], H=BLOCK[2], rho=1876.0, interface="rigid",
                    restitution="housner", g=G)


def the_record():
    """(time, acc, provenance): the strong part of the record, from 0."""
    r = gm.read(gm.DATA_DIR / RECORD[0], component=RECORD[1])
    arias = np.cumsum(r.acc ** 2)
    arias /= arias[-1]
    t5 = float(r.time[np.searchsorted(arias, 0.05)])
    t95 = float(r.time[np.searchsorted(arias, 0.95)])
    t, a, t0 = dynamics.strong_part(r.time, r.acc, t5, WINDOW)
    inside = (r.time >= t0) & (r.time <= t0 + WINDOW + 1e-9)
    share = float(np.sum(r.acc[inside] ** 2) / np.sum(r.acc ** 2))
    prov = {"file": f"data/ground-motions/{RECORD[0]}", "component": RECORD[1], "station": r.name,
            "dt_s": float(r.dt), "record_s": float(r.time[-1]), "pga_g": float(np.max(np.abs(r.acc)) / G),
            "arias_5_95_s": [t5, t95], "window_s": [t0, t0 + float(t[-1])],
            "window_pga_g": float(np.max(np.abs(a)) / G), "window_arias_share": share,
            "direction": "the acceleration along the load direction d (outwards); the FMU's ag along +x"}
    return t, a, prov


def body(kind):
    """The macroblock of the small corner at pi/2 as FMU parameters (`rocking corner --body`)."""
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "body.json"
        out = subprocess.run([sys.executable, "-m", "rocking", "corner", "--courses", "3", "--blocks-x", "3",
                              "--blocks-y", "3", "--alpha", "1.570796", "--body", str(path), "--body-kind", kind],
                             check=True, capture_output=True, text=True)
        info = [x for x in out.stderr.splitlines() if x.startswith("rocking-corner:")]
        return json.loads(path.read_text()), (info[-1].split(" -> ")[0] if info else "")


def cases():
    """name -> (DEM spec, alpha, tracked blocks, theta_ov)."""
    out = {"block": ({"boxes": [[[0, 0, 0], list(BLOCK)]], "mu": 0.66}, 0.0, [1], math.atan(BLOCK[0] / BLOCK[2]))}
    for name, ends, inner in (("free", "free", False), ("free-restrained", "free", True), ("fixed", "fixed", False)):
        spec = {"specimen": dict(SMALL, ends=ends)}
        if inner:
            spec["inner_restraint"] = True
        asm = dynamics.assembly_of(spec)
        track = [i for i, b in enumerate(asm.blocks) if b.wall == "WX" and b.course >= 1 and not asm.fixed[i]]
        out[name] = (spec, math.pi / 2, track, None)
    return out


def dem_run(out, name, spec, alpha, track, theta_ov, t, a, scale):
    path = out / "runs" / name / f"s{scale:.4f}.json"
    if path.is_file():
        r = json.loads(path.read_text())
        note = "cached"
        if r["collapsed"]:  # the definition of dynamics.collapse, also for runs made before it
            side, when = dynamics.collapse(r["time"], r["rotation_max"], r["rotation_min"], theta_ov)
            if (side, json.dumps(when)) != (r["fall_side"], json.dumps(r["t_collapse"])):  # keep the file current
                r["fall_side"], r["t_collapse"] = side, when
                path.write_text(json.dumps(r) + "\n")
    else:
        protocol = dynamics.Protocol(theta_ov=theta_ov)
        r = dynamics.run_isolated(spec, alpha, t, a, scale, track, protocol, timeout=3600)
        for key in ("time", "rotation", "rotation_max", "rotation_min"):
            r[key] = [round(x, 6) for x in r[key]]
        if r["collapsed"]:  # on the rounded series, as a reader of the file finds it
            r["fall_side"], r["t_collapse"] = dynamics.collapse(r["time"], r["rotation_max"], r["rotation_min"],
                                                                theta_ov)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(r) + "\n")
        note = f"{r['cpu_s']:.0f} s CPU"
    print(f"[{name}] DEM scale {scale:.4f}: {'collapses' if r['collapsed'] else 'stands'}, peak rotation "
          f"{r['peak_rotation']:.4f} rad, least {r['least_rotation']:.4f} rad"
          + (f", collapse at {r['t_collapse']:.3f} s ({'out' if r['fall_side'] > 0 else 'in'}wards)"
             if r["collapsed"] else "") + f" ({note})", flush=True)
    return r


def bracket(run, guess, rel_width, grow=1.15):
    """(largest scale that stands, smallest that collapses) by run(scale) -> collapsed:
    from `guess`, up or down by `grow` until the outcome changes, then bisection."""
    s = round(guess, 4)
    if run(s):
        hi = s
        while run(s := round(s / grow, 4)):
            hi = s
        lo = s
    else:
        lo = s
        while not run(s := round(s * grow, 4)):
            lo = s
        hi = s
    while hi / lo - 1 > rel_width:
        mid = round(math.sqrt(lo * hi), 4)
        if run(mid):
            hi = mid
        else:
            lo = mid
    return lo, hi


def fmu_run(fmu, params, t, a, scale):
    return fmu.simulate(params, ag=(t, a), scale=scale, stop_time=float(t[-1]) + 1.0, output_interval=0.005)


def fmu_scale(fmu, params, t, a, pga_g, step=1.01, width=1e-3):
    """(largest standing, smallest overturning) scale: a scan up by `step` from 0.9 x the
    uplift scale tan(alpha) g / PGA to the first overturning scale, then bisection to
    `width`. Rocking is not monotone in the scale: this is the least overturning scale
    of the scan, and a larger scale may stand."""
    lo = round(0.9 * params["B"] / 2 / params.get("hG", params.get("H", 0) / 2) / pga_g, 4)
    assert not fmu_run(fmu, params, t, a, lo).overturned
    hi = lo * step
    while not fmu_run(fmu, params, t, a, hi).overturned:
        lo, hi = hi, hi * step
    while hi - lo > width:
        mid = 0.5 * (lo + hi)
        if fmu_run(fmu, params, t, a, mid).overturned:
            hi = mid
        else:
            lo = mid
    return lo, hi


def summary(run):
    th = run.result["theta"]
    return {"overturned": bool(run.overturned), "t_overturn": float(run.t_overturn),
            "peak_rotation": float(th.max()), "least_rotation": float(th.min())}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(REPO / "data" / "corner-blocks" / "record"))
    ap.add_argument("--img", default=str(REPO / "docs" / "img" / "corner_record.png"))
    args = ap.parse_args()
    out = Path(args.out)
    t, a, prov = the_record()
    pga = prov["window_pga_g"]
    print(f"record: {prov['file']} {prov['component']}, {prov['window_s'][0]:.2f}-{prov['window_s'][1]:.2f} s "
          f"(PGA {pga:.3f} g, {100 * prov['window_arias_share']:.1f} % of the Arias intensity)", flush=True)
    bodies = {"block": (dict(BLOCK_PARAMS), "free-standing block, two-sided")}
    for kind in ("geometric", "threshold"):
        bodies[kind] = body(kind)
    geo = bodies["geometric"][0]
    theta_u = math.atan(geo["B"] / 2 / geo["hG"])
    results = {"record": prov, "bodies": {k: {"params": v[0], "info": v[1]} for k, v in bodies.items()}, "cases": {}}
    with RockingFMU() as fmu:
        fmu_rows = {}
        variants = {"block": BLOCK_PARAMS, "geometric": geo, "threshold": bodies["threshold"][0],
                    "geometric-twoSided": {k: v for k, v in geo.items()
                                           if k not in ("restraint", "side", "eRestraint")},
                    "geometric-e0": dict(geo, eRestraint=0.0)}
        for name, params in variants.items():
            lo, hi = fmu_scale(fmu, params, t, a, pga)
            fmu_rows[name] = {"params": params, "stands": lo, "collapses": hi,
                              "at_stands": summary(fmu_run(fmu, params, t, a, lo)),
                              "at_collapses": summary(fmu_run(fmu, params, t, a, hi))}
            print(f"[FMU {name}] stands at {lo:.4f}, overturns at {hi:.4f} "
                  f"(t = {fmu_rows[name]['at_collapses']['t_overturn']:.3f} s)", flush=True)
        results["fmu"] = fmu_rows
        for name, (spec, alpha, track, theta_ov) in cases().items():
            theta_ov = theta_ov if theta_ov is not None else theta_u
            runs = {}

            def collapsed(scale, name=name, spec=spec, alpha=alpha, track=track, theta_ov=theta_ov):
                runs[scale] = dem_run(out, name, spec, alpha, track, theta_ov, t, a, scale)
                return runs[scale]["collapsed"]

            lo, hi = bracket(collapsed, GUESS[name], REL_WIDTH)
            compared = {b: {"at_dem_stands": summary(fmu_run(fmu, variants[b], t, a, lo)),
                            "at_dem_collapses": summary(fmu_run(fmu, variants[b], t, a, hi))}
                        for b in CASE_BODIES[name]}
            results["cases"][name] = {
                "spec": spec, "alpha": alpha, "track": track, "theta_ov": theta_ov,
                "runs": {f"{s:.4f}": dict({k: r[k] for k in ("collapsed", "t_collapse", "t_fall", "fall_side",
                                                             "peak_rotation", "least_rotation", "steps", "cpu_s")},
                                          bodies={b: summary(fmu_run(fmu, variants[b], t, a, s))
                                                  for b in CASE_BODIES[name]})
                         for s, r in sorted(runs.items())},
                "dem": {"stands": lo, "collapses": hi, "t_collapse": runs[hi]["t_collapse"],
                        "fall_side": runs[hi]["fall_side"], "peak_rotation_stands": runs[lo]["peak_rotation"],
                        "least_rotation_stands": runs[lo]["least_rotation"]},
                "bodies": compared}
    (out / "results.json").write_text(json.dumps(results, indent=1) + "\n")
    table(results)
    figure(results, out, t, a, Path(args.img))


def table(results):
    f = results["fmu"]
    print("\n| case | DEM stands / collapses (scale) | DEM collapse at (s), side | body | body stands / overturns "
          "(scale) | body overturns at (s) | peak rotation at the DEM's standing scale, DEM / body (rad) |")
    print("|---|---|---|---|---|---|---|")
    for name, c in results["cases"].items():
        d = c["dem"]
        side = "out" if d["fall_side"] > 0 else "in"
        for body_name, at in c["bodies"].items():
            b = f[body_name]
            print(f"| {name} | {d['stands']:.4f} / {d['collapses']:.4f} | {d['t_collapse']:.3f}, {side}wards "
                  f"| {body_name} | {b['stands']:.4f} / {b['collapses']:.4f} | {b['at_collapses']['t_overturn']:.3f} "
                  f"| {d['peak_rotation_stands']:.4f} / {at['at_dem_stands']['peak_rotation']:.4f} |")
    print("\nEvery DEM run against the bodies at the same scale (collapse time in s, or the peak rotation in rad):")
    for name, c in results["cases"].items():
        for s, r in c["runs"].items():
            dem_cell = f"{r['t_collapse']:.3f} s" if r["collapsed"] else f"stands, {r['peak_rotation']:.4f} rad"
            cells = [f"{b}: " + (f"{x['t_overturn']:.3f} s" if x["overturned"]
                                 else f"stands, {x['peak_rotation']:.4f} rad") for b, x in r["bodies"].items()]
            print(f"| {name} | {s} | {dem_cell} | " + " | ".join(cells) + " |")


def figure(results, out, t, a, img):
    names = list(results["cases"])
    fig, axes = plt.subplots(len(names), 1, figsize=(7.5, 2.3 * len(names)), sharex=True)
    with RockingFMU() as fmu:
        for ax, name in zip(axes, names):
            c = results["cases"][name]
            first, *others = c["bodies"]
            for key, style in (("stands", "-"), ("collapses", "--")):
                s = c["dem"][key]
                r = json.loads((out / "runs" / name / f"s{s:.4f}.json").read_text())
                ax.plot(r["time"], r["rotation"], style, color="C0", lw=1, label=f"DEM, scale {s:.3f} ({key})")
                run = fmu_run(fmu, results["fmu"][first]["params"], t, a, s).result
                ax.plot(run["time"], run["theta"], style, color="C3", lw=1, label=f"{first} body, scale {s:.3f}")
            for other in others:
                s = c["dem"]["collapses"]
                run = fmu_run(fmu, results["fmu"][other]["params"], t, a, s).result
                ax.plot(run["time"], run["theta"], ":", color="C2", lw=1, label=f"{other} body, scale {s:.3f}")
            ax.set_ylim(-0.5, 0.5)
            ax.set_ylabel("rotation (rad)")
            ax.set_title(name, fontsize=9)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=6, loc="lower left", ncol=2)
    axes[-1].set_xlabel("time from the window's start (s)")
    axes[-1].set_xlim(2.5, float(t[-1]) + 1.0)
    fig.tight_layout()
    img.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(img, dpi=120)
    print("wrote", img)


if __name__ == "__main__":
    main()
