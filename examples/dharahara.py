"""The Dharahara Tower case study (the paper's section 6; docs/model.md §4): the main job.

    .venv/bin/python examples/dharahara.py [--out DIR] [--record PATH] [--workers N]

1. Moment-rotation curves (the paper's Figs. 17 and 18) for the foundation and
   interface stiffnesses of Table 1, fm = 2, 5, 15 MPa and none, and the rigid
   interface: `cargo run --release --example dharahara_curves` (the physics
   crate, no FMU), plotted here.
2. Time histories through target/fmu/RockingBlock.fmu (the paper's Fig. 20)
   for the same cases under the KATNP north-south record, stopped at
   overturning, and the scale study (the record scaled), all in one pool of
   `rocking.run_grid` (the native stepping loop where built, docs/performance.md)
   while this process makes the curves and their plots; a summary table.
3. The paper's claims set against our numbers (printed and written).

The KATNP record itself could not be obtained: by default the synthetic
stand-in `rocking.groundmotion.katnp_standin()` is used, and every output says so.
`--record PATH` takes the real file (e.g. the CESMD download) instead.

Everything goes to one folder (default out/dharahara), named at the end.
"""

import argparse
import hashlib
import json
import math
import os
import subprocess
import sys
import sysconfig
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
STAMP = ".dharahara-inputs.json"  # in the output folder: what its outputs were made from


def log(msg):
    print(msg, flush=True)
    _LOG.append(msg)


_LOG = []  # what this run printed: shown again by a run that finds its outputs up to date


# --------------------------------------------------------------------------
# 0. up to date: the outputs of the same inputs are already there
# --------------------------------------------------------------------------

def _sha256(path):
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return "missing"


def _target():
    env = os.environ.get("CARGO_TARGET_DIR")
    return REPO / env if env else REPO / "target"  # an absolute $CARGO_TARGET_DIR stays itself


def inputs_digest(argv, fmu):
    """SHA-256 of everything the outputs are made from: this script and its arguments, the
    rocking package's sources, the FMU, the stepping loop, the curves' binary, the stand-in
    record, the Python packages installed (their dist-info names carry their versions), the
    interpreter and the environment variables the package reads. None with --record (a file
    of the user's, read by whatever reader fits: always run)."""
    if any(a == "--record" or a.startswith("--record=") for a in argv):
        return None
    import importlib.util
    spec = importlib.util.find_spec("rocking")
    if spec is None:  # not installed: the import below says so
        return None
    pkg = Path(spec.submodule_search_locations[0])
    files = [Path(__file__).resolve(), *sorted(pkg.rglob("*.py")),
             Path(fmu) if fmu else _target() / "fmu" / "RockingBlock.fmu",
             Path(os.environ.get("ROCKING_STEPPER") or _target() / "release" / "libfmu_stepper.so"),
             _target() / "release" / "examples" / "dharahara_curves",
             REPO / "data" / "ground-motions" / "katnp-standin" / "KATNP_NS_standin.csv"]
    dists = sorted({d for key in ("purelib", "platlib") if os.path.isdir(sysconfig.get_paths()[key])
                    for d in os.listdir(sysconfig.get_paths()[key]) if d.endswith(".dist-info")})
    env = sorted((k, v) for k, v in os.environ.items() if k.startswith(("ROCKING_", "CARGO_TARGET_DIR")))
    what = {"argv": argv, "python": [sys.executable, sys.version], "dists": dists, "env": env,
            "files": [[str(f), _sha256(f)] for f in files]}
    return hashlib.sha256(json.dumps(what, sort_keys=True).encode()).hexdigest()


def _outputs(out, since):
    """The outputs this run wrote (modified since `since`, s since the epoch): the folder may also hold
    those of a run with other arguments."""
    return {p.name: _sha256(p) for p in sorted(out.glob("dharahara_*")) if p.is_file() and p.stat().st_mtime >= since}


def replay_if_unchanged(out, inputs):
    """True (after printing the earlier run's log) when `out` holds the outputs of a run from the
    same `inputs`, each file as that run wrote it."""
    try:
        stamp = json.loads((out / STAMP).read_text())
    except (OSError, ValueError):
        return False
    if inputs is None or stamp.get("inputs") != inputs or not stamp.get("outputs"):
        return False
    if any(_sha256(out / name) != digest for name, digest in stamp["outputs"].items()):
        return False
    print(stamp["log"], flush=True)
    print(f"\n(unchanged: these are the outputs and the log of the run of {stamp['when']}, made from the "
          "same inputs: this script and its arguments, the rocking package, the FMU, the stepping loop, "
          "the curves' binary, the record, the Python packages; --force runs it again)", flush=True)
    return True


def write_stamp(out, inputs, since):
    if inputs is not None:
        (out / STAMP).write_text(json.dumps({
            "inputs": inputs, "when": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "outputs": _outputs(out, since),
            "log": "\n".join(_LOG)}, indent=1))


def build_curves():
    """The curves' binary, built (as `cargo run` would) before its digest is taken."""
    subprocess.run(["cargo", "build", "--release", "--quiet", "--example", "dharahara_curves"], cwd=REPO,
                   check=True)


def parser():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(REPO / "out" / "dharahara"), help="output folder (default out/dharahara)")
    ap.add_argument("--record", help="the real KATNP record (e.g. the CESMD file) instead of the stand-in")
    ap.add_argument("--component", help="component of --record to use (default: the north-south one)")
    ap.add_argument("--workers", type=int, default=2, help="worker processes for the FMU runs (default 2)")
    ap.add_argument("--fmu", default=None, help="the FMU (default target/fmu/RockingBlock.fmu)")
    ap.add_argument("--stop-time", type=float, default=None, help="end of the time histories (default: the record's)")
    ap.add_argument("--scales", default="0.99,1.01,1.5,2",
                    help="scale factors of the scale study (default 0.99,1.01,1.5,2: robustness of the unscaled "
                         "outcomes and stronger shaking; '' to skip it)")
    ap.add_argument("--cases", help="comma-separated case ids to simulate (default: all 49)")
    ap.add_argument("--rtol", type=float, default=1e-11,
                    help="the FMU's relative tolerance (default 1e-11: converged outcomes, see docs/dharahara.md; "
                         "the FMU's own default is looser)")
    ap.add_argument("--hg", type=float, help="height of G, m, instead of R0 cos(alpha) = 30.20 (sensitivity)")
    ap.add_argument("--ic", type=float, help="inertia about G, kg m2, instead of the hollow cylinder of height 2 hG")
    ap.add_argument("--curves-only", action="store_true", help="moment-rotation curves only (no FMU)")
    ap.add_argument("--force", action="store_true",
                    help="run even when the output folder holds the outputs of the same inputs")
    return ap


def unchanged(argv):
    """Whether the outputs are up to date (their log printed again), and the inputs' digest."""
    args, _ = parser().parse_known_args(argv)
    build_curves()
    inputs = inputs_digest([a for a in argv if a != "--force"], args.fmu)
    return (not args.force and replay_if_unchanged(Path(args.out).resolve(), inputs)), inputs


if __name__ == "__main__":
    _UNCHANGED, _INPUTS = unchanged(sys.argv[1:])
    if _UNCHANGED:
        sys.exit(0)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from rocking import groundmotion as gm  # noqa: E402
from rocking import RockingFMU, run_grid  # noqa: E402
from rocking.cases import (FM_MPA, FOUNDATION_KN_MPA, HG, INTERFACE_KN_GPA,  # noqa: E402
                           case_info, dharahara_cases, dharahara_tower)

STANDIN_LABEL = "KATNP N-S SYNTHETIC STAND-IN, not the real record"
FM_COLORS = {2: "C3", 5: "C1", 15: "C2", math.inf: "C0"}


def fm_text(fm_pa):
    return "no crushing (fm = inf)" if math.isinf(fm_pa) else f"fm = {fm_pa / 1e6:g} MPa"


# --------------------------------------------------------------------------
# 1. moment-rotation curves
# --------------------------------------------------------------------------

def start_moment_rotation(out, hg=None, ic=None):
    """Start the Rust example that writes the curves (a process of its own)."""
    cmd = ["cargo", "run", "--release", "--quiet", "--example", "dharahara_curves", "--", str(out)]
    if hg is not None or ic is not None:
        cmd += [repr(hg if hg is not None else HG)] + ([repr(ic)] if ic is not None else [])
    log("[1/3] moment-rotation curves: " + " ".join(cmd))
    proc = subprocess.Popen(cmd, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    proc.started = time.perf_counter()
    return proc


def finish_moment_rotation(proc, out):
    """Wait for the example; return (curves DataFrame, cases DataFrame)."""
    stdout, stderr = proc.communicate()
    if proc.returncode != 0:
        sys.exit(f"dharahara_curves failed:\n{stdout}\n{stderr}")
    (out / "dharahara_mr_log.txt").write_text(stdout)
    head = stdout.split("\n\n")[0]
    log("\n".join("      " + line for line in head.splitlines()))
    log(f"      done in {time.perf_counter() - proc.started:.1f} s")
    curves = pd.read_csv(out / "dharahara_mr_curves.csv", comment="#")
    cases = pd.read_csv(out / "dharahara_mr_cases.csv").set_index("case")
    return curves, cases


def _mr_axes(ax, title, logx=False):
    ax.axhline(0, color="k", lw=0.5)
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(r"$\theta/\alpha$" + ("  (log scale)" if logx else ""))
    ax.set_ylabel(r"$M_R$ (MN m)")
    if logx:
        ax.set_xscale("log")
        ax.set_xlim(1e-7, 1.05)
    else:
        ax.set_xlim(0, 1.02)
    ax.set_ylim(-25, 105)
    ax.grid(alpha=0.3)


def plot_fig17(curves, cases, out):
    x = curves["theta_over_alpha"]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True, sharey=True)
    cmap = plt.get_cmap("viridis")
    for ax, fm in zip(axes.flat, FM_MPA):
        for j, kn in enumerate(FOUNDATION_KN_MPA):
            cid = f"F{kn:g}_{'elastic' if math.isinf(fm) else f'fm{fm:g}'}"
            color = cmap(j / (len(FOUNDATION_KN_MPA) - 1))
            ax.plot(x, curves[cid] / 1e6, color=color, lw=1.3, label=f"kn = {kn:g} MPa/m")
            tc = cases.loc[cid, "thetaC"] / cases.loc[cid, "alpha"]
            if tc < cases.loc[cid, "thetaOv_over_alpha"]:
                y = np.interp(tc, x, curves[cid] / 1e6)
                ax.plot(tc, y, "o", ms=4, mfc="none", color=color)
        ax.plot(x, curves["rigid"] / 1e6, "k--", lw=1.2, label="rigid (Housner)")
        _mr_axes(ax, f"foundation stiffness, {fm_text(fm * 1e6)}")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Dharahara Tower: moment-rotation curves, foundation stiffnesses (cf. paper Fig. 17)\n"
                 r"o: crushing starts ($\theta_c$); $\alpha$ = %.4f, hG = %.2f m (see docs/dharahara.md)"
                 % (cases.loc["rigid", "alpha"], 3.99 / math.tan(cases.loc["rigid", "alpha"])), fontsize=10)
    fig.tight_layout()
    path = out / "dharahara_fig17_foundation.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_fig18(curves, cases, out):
    x = curves["theta_over_alpha"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    cmap = plt.get_cmap("viridis")
    for j, kn in enumerate(INTERFACE_KN_GPA):
        axes[0].plot(x, curves[f"I{kn:g}_elastic"] / 1e6, color=cmap(j / 5), lw=1.3,
                     label=f"kn = {kn:g} GPa/m")
    axes[0].plot(x, curves["rigid"] / 1e6, "k--", lw=1.2, label="rigid")
    _mr_axes(axes[0], "(a) interface stiffnesses, no crushing")
    axes[0].legend(fontsize=7)
    for ax, logx in ((axes[1], False), (axes[2], True)):
        for fm in FM_MPA[:3]:
            for j, kn in enumerate(INTERFACE_KN_GPA):
                ax.plot(x, curves[f"I{kn:g}_fm{fm:g}"] / 1e6, color=FM_COLORS[fm], lw=0.6 + 0.25 * j,
                        alpha=0.8, label=f"fm = {fm:g} MPa" if j == 0 else None)
        ax.plot(x, curves["rigid"] / 1e6, "k--", lw=1.2, label="rigid")
        _mr_axes(ax, "(c) = (b), log scale: small rotations" if logx
                 else "(b) with crushing, kn = 2 .. 1500 GPa/m (thicker: stiffer)", logx=logx)
    axes[1].legend(fontsize=7)
    fig.suptitle("Dharahara Tower: moment-rotation curves, interface stiffnesses (cf. paper Fig. 18)",
                 fontsize=10)
    fig.tight_layout()
    path = out / "dharahara_fig18_interface.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


# --------------------------------------------------------------------------
# 2. time histories through the FMU
# --------------------------------------------------------------------------

def fmu_runs(record, rec_label, fmu, workers, stop_time, only=None, scales=(), hg=None, ic=None, rtol=None,
             meanwhile=None):
    """Every case under the record (its history kept: thetaOverAlpha, the one output the study
    plots) and under the record scaled by `scales`, in one pool. `meanwhile()` is called as runs
    finish, while the pool works on (this process's work overlapped with the runs). Returns
    (time histories, scale study rows without the unscaled ones, wall time)."""
    cases = dharahara_cases(hg=hg, ic=ic)
    if only:
        unknown = [c for c in only if c not in cases]
        if unknown:
            sys.exit(f"unknown cases {unknown}; known: {', '.join(cases)}")
        cases = {c: cases[c] for c in only}
    extra = [s for s in scales if s != 1.0]
    log(f"[2/3] time histories through the FMU: {len(cases)} cases under {rec_label}"
        + (f", and scaled by {', '.join(f'{s:g}' for s in extra)}" if extra else "")
        + f" ({len(cases) * (1 + len(extra))} runs), {workers} worker process(es), relative tolerance "
        f"{rtol if rtol else 'the FMU default'}")
    t0 = time.perf_counter()

    def progress(done, total, row):
        if meanwhile:
            meanwhile()
        if row["error"]:
            log(f"      {row['case']} x{row['scale']:g}: error: {row['error'][:120]}")
        if done % 50 == 0 or done == total:
            log(f"      {done}/{total} runs ({time.perf_counter() - t0:.1f} s)")

    df = run_grid(cases, records={rec_label: record}, scales=[1.0] + extra, workers=workers, fmu=fmu,
                  rtol=rtol, stop_time=stop_time, histories=lambda _c, _r, scale: scale == 1.0,
                  progress=progress, outputs=("thetaOverAlpha",))
    wall = time.perf_counter() - t0
    log(f"      {len(df)} runs in {wall:.1f} s ({len(df) / wall:.2f} runs/s)")
    info = [case_info(c) for c in df["case"]]
    df.insert(1, "group", [i[0] for i in info])
    df["kn_Pa_per_m"] = [i[1] for i in info]
    df["fm_Pa"] = [i[2] for i in info]
    unscaled = df["scale"] == 1.0
    th = df[unscaled].reset_index(drop=True)
    scaled = df[~unscaled].drop(columns=["history"]).reset_index(drop=True)
    return th, scaled, wall


def log_histories(th):
    for _, row in th.iterrows():
        state = (f"OVERTURNED at {row['t_overturn']:6.2f} s" if row["overturned"]
                 else "error: " + row["error"][:80] if row["error"]
                 else f"stands, peak |theta|/alpha = {row['peak_theta_over_alpha']:.3g}")
        log(f"      {row['case']:14s} {state:42s} ({row['wall_s']:.2f} s)")


def write_histories(df, record, rec_label, standin, out):
    dt = record.dt
    t_max = max(h["time"][-1] for h in df["history"])
    tgrid = np.round(np.arange(0.0, t_max + 0.5 * dt, dt), 10)
    cols = {"time": tgrid}
    for cid, h in zip(df["case"], df["history"]):
        cols[cid] = np.interp(tgrid, h["time"], h["thetaOverAlpha"], right=np.nan)
    table = pd.DataFrame(cols)
    path = out / "dharahara_time_histories.csv"
    with open(path, "w") as f:
        f.write("# Dharahara Tower: theta/alpha against time (s), one column per case "
                "(empty after overturning); RockingBlock.fmu through fmpy\n")
        f.write(f"# record: {rec_label}\n")
        for line in record.notes.splitlines()[:1 if standin else 3]:
            f.write(f"# record notes: {line}\n")
        table.to_csv(f, index=False, float_format="%.6g")
    return path


def plot_histories(df, record, rec_label, group, out):
    sub = df[df["group"].isin([group, "rigid"])]
    fms = FM_MPA
    fig, axes = plt.subplots(len(fms) + 1, 1, figsize=(11, 12), sharex=True)
    axes[0].plot(record.time, record.acc / 9.80665, "k", lw=0.5)
    axes[0].set_ylabel(r"$a_g$ (g)")
    axes[0].set_title(f"ground motion: {rec_label}", fontsize=9)
    kns = FOUNDATION_KN_MPA if group == "foundation" else INTERFACE_KN_GPA
    unit = "MPa/m" if group == "foundation" else "GPa/m"
    cmap = plt.get_cmap("viridis")
    rigid = sub[sub["case"] == "rigid"].iloc[0] if (sub["case"] == "rigid").any() else None
    t_end = record.time[-1]
    for ax, fm in zip(axes[1:], (math.inf, 2, 5, 15)):
        for j, kn in enumerate(kns):
            cid = f"{'F' if group == 'foundation' else 'I'}{kn:g}_{'elastic' if math.isinf(fm) else f'fm{fm:g}'}"
            if not (sub["case"] == cid).any():
                continue
            row = sub[sub["case"] == cid].iloc[0]
            h = row["history"]
            color = cmap(j / (len(kns) - 1))
            lab = f"kn = {kn:g} {unit}"
            if row["overturned"]:
                lab += f" (overturns {row['t_overturn']:.2f} s)"
            ax.plot(h["time"], h["thetaOverAlpha"], color=color, lw=0.9, label=lab)
            if row["overturned"]:
                ax.plot(h["time"][-1], h["thetaOverAlpha"][-1], "x", color=color, ms=7)
        if rigid is not None:
            hr = rigid["history"]
            ax.plot(hr["time"], hr["thetaOverAlpha"], "k--", lw=1.0,
                    label="rigid" + (f" (overturns {rigid['t_overturn']:.2f} s)" if rigid["overturned"]
                                     else f" (peak {rigid['peak_theta_over_alpha']:.3f})"))
        ax.axhline(0, color="k", lw=0.4)
        ax.set_ylabel(r"$\theta/\alpha$")
        ax.set_ylim(-1.05, 1.05)
        ax.set_title(f"{group} stiffnesses, {fm_text(fm * 1e6)}", fontsize=9)
        if ax.lines:
            ax.legend(fontsize=6.5, loc="upper right", ncol=2, framealpha=0.9)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("time (s)")
    axes[-1].set_xlim(0, max(t_end, max(h["time"][-1] for h in sub["history"])))
    fig.suptitle(f"Dharahara Tower time histories through RockingBlock.fmu (cf. paper Fig. 20), "
                 f"x = overturning\nrecord: {rec_label}", fontsize=10)
    fig.tight_layout()
    path = out / f"dharahara_fig20_{group}.png"
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def family(group, fm_pa):
    if group == "rigid":
        return "rigid"
    return f"{group}, " + ("no crushing" if math.isinf(fm_pa) else f"fm = {fm_pa / 1e6:g} MPa")


def robustness(th, study):
    """Per case of th: does the outcome (overturned or not) stay the same with the record
    scaled by 0.99 and 1.01? None when the study has no such scales."""
    near = study[study["scale"].between(0.985, 1.015)]
    if not (near["scale"] != 1.0).any():
        return [None] * len(th)
    same = near.groupby("case")["overturned"].agg(lambda v: v.astype(bool).nunique() == 1)
    return [bool(same.get(c, True)) for c in th["case"]]


def scale_study(th, scaled, standin, out, rec_label):
    """The cases with the record scaled: how many overturn, per family (table and CSV)."""
    base = th.drop(columns=["history"]).copy()
    allrows = pd.concat([base, scaled], ignore_index=True)
    allrows["family"] = [family(g, f) for g, f in zip(allrows["group"], allrows["fm_Pa"])]
    allrows["overturned"] = allrows["overturned"].fillna(False).astype(bool)
    table = allrows.pivot_table(index="family", columns="scale", values="overturned",
                                aggfunc=lambda v: f"{int(v.sum())}/{len(v)}", sort=False)
    table.columns = [f"scale {c:g}" for c in table.columns]
    path = out / "dharahara_scale_study.csv"
    with open(path, "w") as f:
        f.write(f"# Dharahara Tower, record {rec_label} scaled; one row per run\n")
        if standin:
            f.write("# THE RECORD IS A SYNTHETIC STAND-IN for KATNP N-S, not the real record\n")
        allrows.drop(columns=["family"]).to_csv(f, index=False, float_format="%.6g")
    log("[2b/3] overturned cases per family and scale factor" + (" (STAND-IN record)" if standin else ""))
    log("\n".join("      " + line for line in table.to_string().splitlines()))
    return allrows, table


# --------------------------------------------------------------------------
# 3. claims
# --------------------------------------------------------------------------

def check_invalid_foundation(fmu, mr_cases, hg=None, ic=None):
    """What the FMU (a RockingFMU) does when kn Is > W hG fails (90 % of the limiting kn)."""
    is_ = math.pi * (3.99 ** 4 - 2.12 ** 4) / 4
    tower = dharahara_tower(hg, ic)
    kn_lim = tower["W"] * tower["hG"] / is_
    params = dharahara_tower(hg, ic, interface="elastic", kn=0.9 * kn_lim)
    try:
        fmu.simulate(params, stop_time=0.01)
        return kn_lim, "UNEXPECTED: the FMU accepted it"
    except Exception as exc:  # noqa: BLE001
        return kn_lim, str(exc)


def claims(mr, th, standin, study=None):
    """Rows (claim, paper, ours, verdict)."""
    rows = []
    a = mr.loc["rigid", "alpha"]
    fm2 = mr[(mr["fm_Pa"] == 2e6)]
    def loss(col):
        lo, hi = 100 * (1 - fm2[col].max()), 100 * (1 - fm2[col].min())
        return f"{lo:.0f} %" if round(lo) == round(hi) else f"{lo:.0f}-{hi:.0f} %"

    rows.append((
        "fm = 2 MPa cuts the dynamic capacity by about 40 % vs rigid (Fig. 17)",
        "about 40 %",
        (f"thetaOv (our capacity measure): {loss('thetaOv_ratio_to_rigid')}; "
         f"peak MR: {loss('MR_peak_ratio_to_rigid')}; overturning energy: {loss('E_ov_ratio_to_rigid')} "
         f"(all 12 stiffnesses)"),
        ""))
    el = []
    for kn in FOUNDATION_KN_MPA:
        r = mr.loc[f"F{kn:g}_fm15"]
        el.append(f"{kn:g}: {'elastic' if not r['crushes_before_overturning'] else 'crushes at theta/alpha = %.2f' % (r['thetaC'] / a)}")
    rows.append(("fm = 15 MPa: foundations 85, 170 MPa/m stay elastic (Fig. 17)",
                 "85 and 170 elastic, stiffer ones crush", "; ".join(el), ""))
    if th is not None and (th["case"] == "rigid").any():
        rig = th[th["case"] == "rigid"].iloc[0]
        rows.append(("rigid interface barely rocks under KATNP N-S (Fig. 20)", "very small rotations",
                     (f"peak abs(theta)/alpha = {rig['peak_theta_over_alpha']:.3g}"
                      + (f", OVERTURNS at {rig['t_overturn']:.2f} s" if rig["overturned"] else "")
                      + (" (stand-in record)" if standin else "")), ""))
    if th is not None:
        ov = th[th["overturned"].fillna(False).astype(bool) & (th["fm_Pa"] < math.inf)]
        if len(ov):
            rows.append(("lower fm: faster overturning; for one fm, flexible and stiff interfaces overturn "
                         "within about 0.5 s of each other (Fig. 20b)",
                         "fm controls more than kn",
                         "; ".join(f"fm = {f / 1e6:g} MPa: {len(g)} overturn between {g['t_overturn'].min():.2f} "
                                   f"and {g['t_overturn'].max():.2f} s" for f, g in ov.groupby("fm_Pa"))
                         + (" (stand-in record)" if standin else ""), ""))
        crush = th[th["fm_Pa"] < math.inf]
        n_ov = int(crush["overturned"].fillna(False).astype(bool).sum())
        more = ""
        if study is not None:
            sc = study[(study["fm_Pa"] < math.inf) & (study["scale"] != 1.0)]
            more = "; record scaled: " + ", ".join(
                f"x{s:g}: {int(g['overturned'].astype(bool).sum())} of {len(g)}" for s, g in sc.groupby("scale"))
        rows.append(("with crushing every case overturns (Fig. 20b)", "all overturn",
                     f"{n_ov} of {len(crush)} crushing cases overturn" + more
                     + (" (stand-in record)" if standin else ""), ""))
        el = th[(th["group"] == "interface") & (th["fm_Pa"] == math.inf)]
        rows.append(("no crushing: overturns for kn <= 15 GPa/m, negligible response above "
                     "(except 500 GPa/m) (Fig. 20a)", "2, 5, 15 overturn; 200, 1500 negligible",
                     "; ".join(f"{case_info(c)[1] / 1e9:g}: "
                               + (f"overturns {t:.2f} s" if o else f"peak {p:.3g}")
                               for c, o, t, p in zip(el["case"], el["overturned"], el["t_overturn"],
                                                     el["peak_theta_over_alpha"])), ""))
    return rows


def _md_table(df):
    cols = list(df.columns)
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    lines += ["| " + " | ".join(str(v) for v in row) + " |" for row in df.itertuples(index=False)]
    return "\n".join(lines)


def write_markdown(out, mr, th, study, claim_rows, rec_label, standin):
    """dharahara_results.md: the tables of docs/dharahara.md, regenerated by every run."""
    parts = ["# Dharahara results (generated by examples/dharahara.py)\n"]
    cap = mr[["thetaOv_over_alpha", "MR_peak_ratio_to_rigid", "E_ov_ratio_to_rigid", "thetaC",
              "crushes_before_overturning"]].copy()
    cap.insert(0, "case", cap.index)
    cap["thetaC"] = cap["thetaC"].map(lambda v: "inf" if math.isinf(v) else f"{v:.3g}")
    for c in ("thetaOv_over_alpha", "MR_peak_ratio_to_rigid", "E_ov_ratio_to_rigid"):
        cap[c] = cap[c].map(lambda v: f"{v:.3f}")
    parts += ["## Moment-rotation curves: capacities relative to the rigid interface\n", _md_table(cap), ""]
    if th is not None:
        t = th[["case", "overturned", "t_overturn", "peak_theta_over_alpha", "impacts", "zero_crossings",
                "wall_s"]
               + (["robust_1pct"] if "robust_1pct" in th else [])].copy()
        if "robust_1pct" in t:
            t["robust_1pct"] = t["robust_1pct"].map(lambda v: "" if v is None else ("yes" if v else "NO"))
        t["t_overturn"] = t["t_overturn"].map(lambda v: "" if math.isnan(v) else f"{v:.2f}")
        t["peak_theta_over_alpha"] = t["peak_theta_over_alpha"].map(lambda v: f"{v:.3g}")
        t["wall_s"] = t["wall_s"].map(lambda v: f"{v:.2f}")
        t["overturned"] = t["overturned"].map(lambda v: "yes" if v else "no")
        parts += [f"## Time histories, record: {rec_label}\n", _md_table(t), ""]
    if study is not None:
        tab = study.assign(family=[family(g, f) for g, f in zip(study["group"], study["fm_Pa"])]).pivot_table(
            index="family", columns="scale", values="overturned",
            aggfunc=lambda v: f"{int(v.astype(bool).sum())}/{len(v)}", sort=False)
        tab.columns = [f"x{c:g}" for c in tab.columns]
        tab.insert(0, "family", tab.index)
        parts += ["## Overturned cases per family and scale factor" + (" (stand-in record)" if standin else "")
                  + "\n", _md_table(tab), ""]
    parts += ["## Claims\n", _md_table(pd.DataFrame(claim_rows, columns=["claim", "paper", "ours", "note"])
                                       .drop(columns="note")), ""]
    (out / "dharahara_results.md").write_text("\n".join(parts))


# --------------------------------------------------------------------------

def main(argv=None, inputs=None):
    """The study; `inputs` (the digest of `inputs_digest`) is written beside the outputs at the end."""
    args = parser().parse_args(argv)
    t_start, since = time.perf_counter(), time.time() - 1  # mtimes may lag the clock by a tick
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    (out / STAMP).unlink(missing_ok=True)

    th = study = None
    standin = args.record is None
    scales = [float(x) for x in args.scales.split(",") if x.strip()]
    # the curves (a Rust process) and their plots are made while the FMU runs go on
    mr_proc = start_moment_rotation(out, args.hg, args.ic)
    mr_result = []

    def curves_and_plots():
        if not mr_result and mr_proc.poll() is not None:
            mr_result.extend(finish_moment_rotation(mr_proc, out))
            p17, p18 = plot_fig17(*mr_result, out), plot_fig18(*mr_result, out)
            log(f"      wrote {p17.name}, {p18.name}")

    if not args.curves_only:
        record = gm.katnp(args.record, component=args.component)
        rec_label = STANDIN_LABEL if standin else f"{record.name} {record.component} ({record.source})"
        log(f"      record: {rec_label}: {record.npts} samples, dt = {record.dt:g} s, "
            f"PGA = {record.pga_g:.3f} g, PGV = {100 * record.pgv:.1f} cm/s")
        only = [c.strip() for c in args.cases.split(",") if c.strip()] if args.cases else None
        fmu = RockingFMU(args.fmu)
        th, scaled, wall = fmu_runs(record, rec_label, fmu, args.workers, args.stop_time, only, scales,
                                    args.hg, args.ic, args.rtol, meanwhile=curves_and_plots)
    mr_proc.wait()
    curves_and_plots()
    mr = mr_result[1]

    if not args.curves_only:
        log_histories(th)
        # the FMU's thetaOv against the moment-rotation curves' (two codes paths: Rust example vs FMU)
        dev = max((abs(r["thetaOv"] / mr.loc[r["case"], "thetaOv"] - 1) for _, r in th.iterrows()
                   if not r["error"]), default=float("nan"))
        log(f"      FMU thetaOv vs moment-rotation thetaOv: max relative difference {dev:.1e}")
        hp = write_histories(th, record, rec_label, standin, out)
        f1 = plot_histories(th, record, rec_label, "interface", out)
        f2 = plot_histories(th, record, rec_label, "foundation", out)
        log(f"      wrote {hp.name}, {f1.name}, {f2.name}")
        study = None
        if scales:
            study, _ = scale_study(th, scaled, standin, out, rec_label)
            th["robust_1pct"] = robustness(th, study)
        summary = th[["case", "group", "kn_Pa_per_m", "fm_Pa", "overturned", "t_overturn",
                      "peak_theta_over_alpha", "impacts", "zero_crossings", "thetaOv", "wall_s", "error"]
                     + (["robust_1pct"] if "robust_1pct" in th else [])].copy()
        summary.insert(4, "thetaOv_over_alpha", summary["thetaOv"] / mr["alpha"].iloc[0])
        summary = summary.drop(columns="thetaOv")
        spath = out / "dharahara_summary.csv"
        with open(spath, "w") as f:
            f.write(f"# Dharahara Tower time histories through RockingBlock.fmu; record: {rec_label}\n")
            if standin:
                f.write("# THE RECORD IS A SYNTHETIC STAND-IN for KATNP N-S, not the real record: "
                        "results are indicative only\n")
            f.write(f"# total wall time {wall:.1f} s with {args.workers} worker(s); relative tolerance "
                    f"{args.rtol}; peak |theta|/alpha over 0.01 s samples\n")
            summary.to_csv(f, index=False, float_format="%.6g")
        log("\n[summary] record: " + rec_label)
        with pd.option_context("display.width", 200, "display.max_rows", 100):
            show = summary.drop(columns=["group", "error"]).copy()
            show["kn_Pa_per_m"] = show["kn_Pa_per_m"].map(lambda v: f"{v:.3g}")
            show["fm_Pa"] = show["fm_Pa"].map(lambda v: "inf" if math.isinf(v) else f"{v / 1e6:g} MPa")
            show = show.rename(columns={"fm_Pa": "fm", "kn_Pa_per_m": "kn (Pa/m)"})
            log(show.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
        if standin:
            log("  (record: SYNTHETIC STAND-IN for KATNP N-S, not the real record)")

        kn_lim, msg = check_invalid_foundation(fmu, mr, args.hg, args.ic)
        fmu.close()
        log(f"\n[stability] kn Is > W hG holds for every case (softest foundation 85 MPa/m: "
            f"margin {mr.loc['F85_elastic', 'stability_margin_knIs_over_WhG']:.1f}x; "
            f"limit kn = {kn_lim / 1e6:.3f} MPa/m). With kn = 0.9 x the limit the FMU refuses: {msg}")
        (out / "dharahara_stability.txt").write_text(
            f"limit kn = W hG / Is = {kn_lim:.6e} Pa/m; the softest foundation (85 MPa/m) has a margin of "
            f"{mr.loc['F85_elastic', 'stability_margin_knIs_over_WhG']:.2f}x.\n"
            f"FMU with kn = 0.9 x the limit: {msg}\n")

    rows = claims(mr, th, standin, study)
    cpath = out / "dharahara_claims.csv"
    pd.DataFrame(rows, columns=["claim", "paper", "ours", "note"]).to_csv(cpath, index=False)
    log("\n[3/3] the paper's claims and our numbers" + (" (time histories: STAND-IN record)" if standin else ""))
    for claim, paper, ours, _ in rows:
        log(f"  - {claim}\n      paper: {paper}\n      ours:  {ours}")
    write_markdown(out, mr, th, study, rows, rec_label if th is not None else None, standin)
    log(f"\nall outputs in {out}  ({time.perf_counter() - t_start:.1f} s)")
    write_stamp(out, inputs, since)


if __name__ == "__main__":
    main(inputs=_INPUTS)
