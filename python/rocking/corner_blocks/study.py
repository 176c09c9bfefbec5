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
from dataclasses import replace
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


#: Planes of the study's friction pyramid: 8, not lp.FACETS (32). The non-associative
#: analysis (nonassoc.py) solves two LPs per iteration for 40 or more iterations on the
#: paper's corner, 10-20 s CPU each with 8 planes and 5-10 times that with 32; the study's
#: LP stays on the same pyramid so that the two compare like with like. Section 2 of
#: docs/corner-blocks.md gives what 8 planes add: 1.3-6.3 % over 32 on these cases.
STUDY_FACETS = 8


def lp_case(specimen, alpha, facets=STUDY_FACETS):
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
        log=print, courses=9, blocks=7, start_fraction=None, workers=1, table_only=False):
    """Every case of the study into out/ (the paper's columns only make sense for the
    paper's 9 courses of 7 blocks); returns the table's columns. DEM cases run on a Dask
    LocalCluster of `workers` processes; with start_fraction, each DEM test starts at that
    fraction of the same case's LP multiplier (rounded down to the step; see dem_start).
    table_only: no case is computed; the table and plot show the cached ones (a study
    still running, or stopped), the others as "-"."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    alphas = [a for a, _ in ORIENTATIONS]
    columns = dict(PAPER) if (courses, blocks) == (9, 7) else {}
    if binary:
        for k in (0.3, 1.0):
            la = cached(out, f"la_k{k:g}", lambda k=k: {"lam": la_cases(binary, k, alphas, courses, blocks)})
            columns[f"LA k={k:g}"] = la["lam"]
    geometry = {"courses": courses, "blocks": blocks}
    suffix = "" if (courses, blocks) == (9, 7) else f"_{courses}x{blocks}"
    todo = [(m, e, i) for m in methods for e in ends for i in range(len(alphas))]
    results = {}

    def record(n, method, e, i, r, seconds):
        label = ORIENTATIONS[i][1]
        lam = r.get("lam")
        shown = f"lambda {lam:.4f}" if lam is not None and not math.isnan(lam) else f"no lambda ({r.get('skipped', 'not collapsed')})"
        log(f"[{n}/{len(todo)}] {method} ends={e} alpha={label}: {shown} "
            f"({seconds:.1f} s, {r.get('cpu_s', 0):.1f} s CPU when computed)")
        results.setdefault(f"{method.upper()} {e}", [None] * len(alphas))[i] = lam
        results.setdefault(f"_{method}_{e}", [None] * len(alphas))[i] = r

    lp_of = {}
    for e in ends:
        for i in range(len(alphas)):
            if "lp" in methods or (start_fraction and "dem" in methods):
                spec = Specimen(ends=e, mu=mu, **geometry)
                lp_of[e, i] = cached(out, f"lp_{e}_mu{mu:g}_{i}{suffix}", lambda spec=spec, i=i: lp_case(spec, alphas[i]))
    n = 0
    for method, e, i in todo:
        if method == "lp":
            n += 1
            record(n, method, e, i, lp_of[e, i], 0.0)
    dem_cases = [(e, i) for m, e, i in todo if m == "dem"]
    if dem_cases:
        protocol = dem_protocol or _default_protocol(courses, blocks)
        jobs = {}
        for e, i in dem_cases:
            name = f"dem_{e}_mu{mu:g}_{i}{suffix}"
            path = out / f"{name}.json"
            if path.is_file():
                n += 1
                record(n, "dem", e, i, json.loads(path.read_text()), 0.0)
                continue
            if not dem_supports(e, alphas[i]):
                r = {"lam": None, "skipped": "outOfPlane ends only at alpha = 0 or pi/2 in the DEM"}
                path.write_text(json.dumps(r))
                n += 1
                record(n, "dem", e, i, r, 0.0)
                continue
            start = dem_start(protocol, lp_of[e, i]["lam"], start_fraction) if start_fraction else protocol.start
            jobs[name] = (e, i, {"specimen": {"ends": e, "mu": mu, **geometry}}, replace(protocol, start=start))
        if table_only:
            for name, (e, i, _, _) in jobs.items():
                n += 1
                record(n, "dem", e, i, {"lam": None, "skipped": "not computed yet"}, 0.0)
            jobs = {}
        for name, (e, i, spec, proto), r, seconds in run_dem_jobs(jobs, alphas, workers):
            (out / f"{name}.json").write_text(json.dumps(r))
            n += 1
            record(n, "dem", e, i, r, seconds)
    for m in methods:  # the table's columns in the order of methods and ends, not of completion
        for e in ends:
            columns[f"{m.upper()} {e}"] = results[f"{m.upper()} {e}"]
    write_table(out / "table.md", columns)
    plot(out / "lambda_alpha.png", columns)
    for key, rs in results.items():
        if key.startswith("_lp_"):
            e = key[4:]
            for i in (0, 2, 4):
                spec = Specimen(ends=e, mu=mu, courses=courses, blocks=blocks)
                mechanism_figure(out / f"mechanism_lp_{e}_{i}.png", spec, rs[i],
                                 f"LP, ends {e}, alpha {ORIENTATIONS[i][1]}")
        if key.startswith("_dem_"):
            e = key[5:]
            for i, r in enumerate(rs):
                if r and r.get("corners"):
                    dem_figure(out / f"mechanism_dem_{e}_{i}.png", Specimen(ends=e, mu=mu, courses=courses,
                               blocks=blocks), r, f"DEM, ends {e}, alpha {ORIENTATIONS[i][1]}")
    return columns


def dem_figure(path, specimen, result, title):
    """The DEM's blocks a little after collapse (their corners as the run left them)."""
    import numpy as np

    a = Assembly.from_specimen(specimen)
    corners = [np.array(c) for c in result["corners"]]
    draw.figure(a.blocks, path, corners, result["moving"], title=title, fixed=a.fixed)


def _default_protocol(courses, blocks):
    """The DEM's protocol with the corner's rest speed (dem.rest_speed: 10 mm/s on the
    paper's corner, whose standing levels creep at up to 1 mm/s)."""
    from .dem import Protocol, rest_speed
    return Protocol(v_tol=rest_speed(courses, blocks))


def reread(result, v_tol, collapse=None):
    """lambda_c of a DEM run (dem.run's result) under another collapse criterion (rest
    speed v_tol, m/s; displacement collapse, m, default the run's), from its level history
    without a new run: the first level whose end speed reaches v_tol or whose largest
    displacement passes collapse. None when the history cannot say: every level it ran
    stands under the new criterion (the run stopped where the new criterion goes on), or a
    level's hold was cut short at the run's displacement (checked every dem.CHECK s) below
    a larger new one, so its end speed and displacement are not those of a whole hold."""
    ran = result["protocol"]
    collapse = ran["collapse"] if collapse is None else collapse
    for lam, _rested, speed, disp, _steps in result["history"]:
        if disp > ran["collapse"] and collapse > ran["collapse"]:
            return None
        if not speed < v_tol or disp > collapse:
            return lam
    return None


def dem_supports(ends, alpha):
    """The DEM turns the assembly to load it along -x, and holds outOfPlane ends by rollers
    along a global axis: only where the walls stay on the axes."""
    return ends != "outOfPlane" or min(abs(alpha), abs(alpha - math.pi / 2)) < 1e-9


def dem_start(protocol, lam_lp, fraction):
    """The first load level: `fraction` of the LP's multiplier, rounded down to the step so
    the levels stay on the grid of a run from 0. A guess that saves levels, not a bound:
    the LP bounds the DEM's lambda_c from above, which says nothing about the levels below
    a start; what makes the start safe is dem_case, which reruns a test that collapses at
    its first level from half that level."""
    return math.floor(fraction * lam_lp / protocol.step + 1e-9) * protocol.step


def dem_case(spec, alpha, protocol):
    """One DEM test; one that collapses at its first level is redone from half that level
    (the load reached in one time step from 0 is a blow, not a tilt), and says so."""
    from . import dem
    r = dem.run_isolated(spec, alpha, protocol)
    if r["collapsed"] and len(r["history"]) == 1 and protocol.start > 0:
        lower = math.floor(0.5 * protocol.start / protocol.step + 1e-9) * protocol.step
        r = dem.run_isolated(spec, alpha, replace(protocol, start=lower))
        r["restarted_from"] = protocol.start
    return r


def run_dem_jobs(jobs, alphas, workers):
    """Yields (name, job, result, wall seconds) as each DEM case ends, on a Dask LocalCluster
    (each case is one LMGC90 process of its own, so a worker needs one thread)."""
    if not jobs:
        return
    import dask
    from distributed import Client, LocalCluster, as_completed

    from ..fragility.cluster import QUIET

    with dask.config.set(QUIET), LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                              dashboard_address=None) as cluster, Client(cluster) as client:
        t0 = time.time()
        futures = {client.submit(dem_case, spec, alphas[i], proto, key=f"dem-{name}", pure=False): name
                   for name, (e, i, spec, proto) in jobs.items()}
        for future in as_completed(futures):
            name = futures[future]
            yield name, jobs[name], future.result(), time.time() - t0


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


#: The end boundaries of the boundary study (docs/corner-blocks.md, "Which boundary"): key
#: (in the cases' file names) -> (label, Specimen fields). The first three are the study's
#: end conditions, whose LP and DEM cases the study above committed.
BOUNDARIES = {
    "fixed": ("all 6 dofs held", {"ends": "fixed"}),
    "fixed-closersFree": ("all 6 dofs held, closing pieces free", {"ends": "fixed", "closers": "free"}),
    "outOfPlane": ("out of plane held", {"ends": "outOfPlane"}),
    "outOfPlane-closersFree": ("out of plane held, closing pieces free", {"ends": "outOfPlane", "closers": "free"}),
    "outOfPlane-clamp2": ("out of plane, reaction <= 2 W", {"ends": "outOfPlane", "clamp": 2.0}),
    "outOfPlane-clamp0.5": ("out of plane, reaction <= 0.5 W", {"ends": "outOfPlane", "clamp": 0.5}),
    "free": ("free", {"ends": "free"}),
}

#: The orientations of the boundary study: indices into ORIENTATIONS (pi/4, pi/2).
BOUNDARY_CASES = (0, 4)


def _suffix(geometry):
    """The cases' file name suffix of a corner other than the paper's 9 courses of 7 blocks."""
    c, b = geometry.get("courses", 9), geometry.get("blocks", 7)
    return "" if (c, b) == (9, 7) else f"_{c}x{b}"


def boundary_lp(out, key, i, mu=0.66, geometry=None):
    """The LP of one boundary at ORIENTATIONS[i], cached in out (as lp_case); geometry:
    courses and blocks, if not the paper's."""
    geometry = geometry or {}
    spec = Specimen(mu=mu, **BOUNDARIES[key][1], **geometry)
    return cached(out, f"lp_{key}_mu{mu:g}_{i}{_suffix(geometry)}", lambda: lp_case(spec, ORIENTATIONS[i][0]))


def boundary_nonassoc(out, key, i, mu=0.66, max_iter=40, tol=1e-4, relaxation=0.5, geometry=None):
    """The non-associative analysis (nonassoc.case) of one boundary, cached in out; an
    unconverged case is kept with converged false and its history."""
    from . import nonassoc

    geometry = geometry or {}
    spec = Specimen(mu=mu, **BOUNDARIES[key][1], **geometry)
    return cached(out, f"nonassoc_{key}_mu{mu:g}_{i}{_suffix(geometry)}",
                  lambda: {**nonassoc.case(spec, ORIENTATIONS[i][0], facets=STUDY_FACETS, max_iter=max_iter,
                                           tol=tol, relaxation=relaxation),
                           "max_iter": max_iter, "tol": tol, "relaxation": relaxation})


def boundary_dem(out, key, i, lam_lp, mu=0.66, fraction=0.6, geometry=None):
    """The DEM of one boundary (the study's protocol: step 0.01 from fraction x the LP),
    cached in out; None where the DEM cannot hold that boundary (a finite clamp, or
    outOfPlane ends away from pi/2)."""
    fields = BOUNDARIES[key][1]
    if "clamp" in fields or not dem_supports(fields["ends"], ORIENTATIONS[i][0]):
        return None
    from .dem import SIZE_FACTOR, Protocol, rest_speed

    geometry = geometry or {}
    # the 3 x 3 corner runs with 8 (docs/corner-blocks.md, "The DEM on the corner")
    factor = SIZE_FACTOR if not _suffix(geometry) else 8
    rest = rest_speed(geometry.get("courses", 9), geometry.get("blocks", 7))
    protocol = Protocol(step=0.01, size_factor=factor, v_tol=rest)
    protocol = replace(protocol, start=dem_start(protocol, lam_lp, fraction))
    return cached(out, f"dem_{key}_mu{mu:g}_{i}{_suffix(geometry)}",
                  lambda: dem_case({"specimen": {"mu": mu, **fields, **geometry}}, ORIENTATIONS[i][0], protocol))


def run_boundaries(out, methods=("lp",), keys=None, cases=BOUNDARY_CASES, study="data/corner-blocks",
                   nonassoc_iter=40, log=print, courses=9, blocks=7, table_only=False):
    """Every boundary of BOUNDARIES (or keys) at the orientations `cases` with each method
    (lp, nonassoc, dem), cached in out; the DEM of the study's own end conditions is read
    from the study's folder (not rerun), and so is its non-associative case where
    study/nonassoc has it. Writes out/table[_CxB].md and .json and returns the rows (one
    per boundary and orientation); the experiments' and 3DEC's columns only for the
    paper's 9 courses of 7 blocks. table_only: nonassoc and DEM cases not cached are
    left out ("-"), none is computed."""
    geometry = {} if (courses, blocks) == (9, 7) else {"courses": courses, "blocks": blocks}
    suffix = _suffix(geometry)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for key in keys or BOUNDARIES:
        fields = BOUNDARIES[key][1]
        for i in cases:
            row = {"key": key, "boundary": BOUNDARIES[key][0], "i": i, "alpha": ORIENTATIONS[i][1],
                   "experiment": None if geometry else PAPER["experiment"][i],
                   "3DEC": None if geometry else PAPER["3DEC"][i]}
            if "lp" in methods or "dem" in methods:
                row["lp"] = boundary_lp(out, key, i, geometry=geometry)["lam"]
                log(f"{key} {ORIENTATIONS[i][1]}: LP {row['lp']:.4f}")
            if "nonassoc" in methods:
                committed = Path(study) / "nonassoc" / f"nonassoc_{key}_mu0.66_{i}{suffix}.json"
                mine = out / f"nonassoc_{key}_mu0.66_{i}{suffix}.json"
                if committed.is_file() and not mine.is_file():
                    r = json.loads(committed.read_text())
                    row["nonassoc_source"] = str(committed)
                elif table_only and not mine.is_file():
                    r = None
                else:
                    r = boundary_nonassoc(out, key, i, max_iter=nonassoc_iter, geometry=geometry)
                if r is not None:
                    row["nonassoc"], row["nonassoc_converged"] = r["lam"], r["converged"]
                    row["nonassoc_iterations"] = r["iterations"]
                    log(f"{key} {ORIENTATIONS[i][1]}: non-associative {r['lam']:.4f} ({r['status']})")
                    if not r["converged"]:
                        row.update(certified_states(Path(study) / "nonassoc", key, i, courses, blocks))
            if "dem" in methods:
                committed = Path(study) / f"dem_{fields['ends']}_mu0.66_{i}{suffix}.json"
                if key in ("fixed", "free", "outOfPlane") and committed.is_file():
                    r = json.loads(committed.read_text())
                    row["dem_source"] = str(committed)
                elif table_only and not (out / f"dem_{key}_mu0.66_{i}{suffix}.json").is_file():
                    r = None
                else:
                    r = boundary_dem(out, key, i, row["lp"], geometry=geometry)
                row["dem"] = r["lam"] if r and r.get("collapsed") else None
                log(f"{key} {ORIENTATIONS[i][1]}: DEM {row['dem']}")
            rows.append(row)
    (out / f"table{suffix}.json").write_text(json.dumps(rows, indent=1))
    (out / f"table{suffix}.md").write_text(boundary_table(rows))
    return rows


def certified_states(folder, key, i, courses=9, blocks=7):
    """The collapse states certified along an unconverged non-associative iteration
    (`python -m rocking.corner_blocks.nonassoc --diagnose --certify`: folder/diagnose_{key}_{i}
    _{courses}x{blocks}_*_certify.json, the first such file by name): {} when there is none,
    else certified_iterations (how many iterations' mechanisms were tried) and, where one
    was completed into a collapse state, certified ([least, largest] lambda of that
    mechanism's collapse states, from the iteration whose least is lowest) and
    certified_iteration. The least bounds the least collapse multiplier from above, where
    the iterate itself (the iteration's lambda) is no collapse state."""
    files = sorted(Path(folder).glob(f"diagnose_{key}_{i}_{courses}x{blocks}_*_certify.json"))
    if not files:
        return {}
    rows = json.loads(files[0].read_text())
    found = [r for r in rows if all(math.isfinite(v) for v in r["certified"])]
    out = {"certified_iterations": len(rows), "certified_source": str(files[0])}
    if found:
        best = min(found, key=lambda r: r["certified"][0])
        out.update(certified=best["certified"], certified_iteration=best["iteration"])
    return out


def boundary_table(rows):
    """The boundary study as Markdown: each method against the experiments and 3DEC."""
    def cell(v, digits=3):
        return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.{digits}f}"

    def ratio(a, b):
        return "-" if a is None or b is None or (isinstance(a, float) and math.isnan(a)) else f"{a / b:.2f}"

    paper = any(r["experiment"] is not None for r in rows)
    head = (["boundary", "alpha", "experiment", "3DEC", "LP", "LP / exp.", "LP / 3DEC", "non-assoc.", "iterations",
             "non-assoc. / exp.", "DEM", "DEM / exp.", "DEM / 3DEC"] if paper else
            ["boundary", "alpha", "LP", "non-assoc.", "iterations", "DEM"])
    lines = ["| " + " | ".join(head) + " |", "|---" * len(head) + "|"]
    for r in rows:
        na = r.get("nonassoc")
        its = "-" if na is None else f"{r['nonassoc_iterations']}" + ("" if r["nonassoc_converged"] else " (not conv.)")
        shown, against = cell(na), ratio(na, r["experiment"])
        if "certified" in r:  # an unconverged iterate is no collapse state: the certified ones instead
            lo, hi = r["certified"]
            shown, its = f"{lo:.3f}-{hi:.3f}", f"{r['certified_iteration']} (certified)"
            against = "-" if r["experiment"] is None else f"{ratio(lo, r['experiment'])}-{ratio(hi, r['experiment'])}"
        elif "certified_iterations" in r:
            n = r["nonassoc_iterations"]
            nth = f"{n}{'th' if 10 <= n % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(n % 10, 'th')}"
            shown = f"- ({cell(na)}: {nth} iterate)"
            its, against = f"{r['certified_iterations']} certified: none", "-"
        if paper:
            cells = [r["boundary"], r["alpha"], cell(r["experiment"]), cell(r["3DEC"]), cell(r.get("lp")),
                     ratio(r.get("lp"), r["experiment"]), ratio(r.get("lp"), r["3DEC"]), shown, its,
                     against, cell(r.get("dem"), 2), ratio(r.get("dem"), r["experiment"]),
                     ratio(r.get("dem"), r["3DEC"])]
        else:
            cells = [r["boundary"], r["alpha"], cell(r.get("lp")), shown, its, cell(r.get("dem"), 2)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    import argparse

    p = argparse.ArgumentParser()
    p.add_argument("out")
    args = p.parse_args(argv)
    run(args.out, log=lambda s: print(s, file=sys.stderr, flush=True))


if __name__ == "__main__":
    main()
