"""Parametric runs through RockingBlock.fmu: cases x records x scale factors in
parallel processes (`rocking.run_grid`), one table row per run.

    .venv/bin/python examples/parametric.py [--cases rigid,I5_fm5,...] [--records katnp,lomaprieta]
        [--scales 0.5,1,2] [--workers 2] [--out DIR] [--bench]

Cases are the Dharahara cases of `rocking.cases.dharahara_cases()` (ids as in
examples/dharahara_curves.rs: rigid, F<kn MPa/m>_<fm..>, I<kn GPa/m>_<fm..>).
Records (shipped with the repository, see data/ground-motions/README.md):

    katnp        KATNP N-S SYNTHETIC STAND-IN (not the real record), 80 s, 0.174 g
    lomaprieta   1989 Loma Prieta, USGS 1295 Shafter, 360 (public domain), 30 s, 0.106 g
    coalinga     1983 Coalinga, CSMIP 36456, 90 (CGS/CESMD), 65 s, 0.273 g
    darfield     2010 Darfield, GeoNet DFHS, 000 (CC BY 3.0 NZ), 98.5 s, 0.445 g
    kaikoura     2016 Kaikoura, GeoNet WTMC, N28W (CC BY 3.0 NZ), 164 s, 0.992 g
    or a path to any file rocking.groundmotion reads (its first component)

Writes DIR/parametric.csv (default out/parametric). `--bench` runs the grid
with 1 and then 2 workers and prints the throughput (runs per second).

Use from Python:

    from rocking import run_grid, dharahara_cases
    df = run_grid(dharahara_cases(), records=[gm.katnp_standin()], scales=[0.5, 1.0], workers=2)
"""

import argparse
import sys
import time
from pathlib import Path

import pandas as pd

REPO = Path(__file__).resolve().parents[1]

from rocking import groundmotion as gm  # noqa: E402
from rocking import RockingFMU, dharahara_cases, run_grid  # noqa: E402

RECORDS = {
    "katnp": (None, None),
    "lomaprieta": ("usgs-lomaprieta-1989/0111a.smc", "360"),
    "coalinga": ("csmip-coalinga-1983/ce36456p_CE36456.V2", "90"),
    "darfield": ("geonet-darfield-2010/3366146_DFHS_HN_20.000", None),
    "kaikoura": ("geonet-kaikoura-2016/20161113_110259_WTMC_20.V2A", "N28W"),
}


def load_record(key):
    """(name, Record) for a key of RECORDS or a file path."""
    if key == "katnp":
        return "KATNP N-S synthetic stand-in", gm.katnp_standin()
    if key in RECORDS:
        rel, comp = RECORDS[key]
        rec = gm.read(gm.DATA_DIR / rel, component=comp)
        return f"{key} {rec.component}", rec
    rec = gm.read(key)
    if rec.vertical:  # ag is the horizontal ground acceleration
        raise SystemExit(f"{key}: its first component, {rec.component}, is the vertical one: "
                         "give a file whose first component is horizontal")
    return f"{Path(key).name} {rec.component}", rec


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="rigid,I5_elastic,I5_fm5,F340_fm15", help="case ids or 'all' (49)")
    ap.add_argument("--records", default="katnp,lomaprieta,coalinga")
    ap.add_argument("--scales", default="0.5,1,2")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", default=str(REPO / "out" / "parametric"))
    ap.add_argument("--fmu", default=None)
    ap.add_argument("--bench", action="store_true", help="run with 1 and with 2 workers; print runs/s")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    all_cases = dharahara_cases()
    names = (list(all_cases) if args.cases == "all"
             else [c.strip() for c in args.cases.split(",") if c.strip()])
    unknown = [c for c in names if c not in all_cases]
    if unknown:
        sys.exit(f"unknown cases {unknown}; known: {', '.join(all_cases)}")
    cases = {c: all_cases[c] for c in names}
    records = dict(load_record(k.strip()) for k in args.records.split(",") if k.strip())
    scales = [float(s) for s in args.scales.split(",")]
    n = len(cases) * len(records) * len(scales)
    print(f"{len(cases)} cases x {len(records)} records x {len(scales)} scales = {n} runs", flush=True)
    if any("stand-in" in r for r in records):
        print("note: 'KATNP N-S synthetic stand-in' is NOT the real KATNP record", flush=True)

    with RockingFMU(args.fmu) as fmu:  # one extraction, shared by every worker
        timings = {}
        for workers in ((1, 2) if args.bench else (args.workers,)):
            t0 = time.perf_counter()
            df = run_grid(cases, records, scales, workers=workers, fmu=fmu, progress=lambda d, t, r: print(
                f"  {d}/{t} runs" if d % 10 == 0 or d == t else "", end="\r" if d < t else "\n", flush=True))
            timings[workers] = time.perf_counter() - t0
            print(f"\r  {n} runs, {workers} worker(s): {timings[workers]:.2f} s, "
                  f"{n / timings[workers]:.2f} runs/s (sum over runs: wall {df['wall_s'].sum():.2f} s, "
                  f"CPU {df['cpu_s'].sum():.2f} s)",
                  flush=True)
    cols = ["case", "interface", "kn", "fm", "record", "scale", "overturned", "t_overturn",
            "peak_theta_over_alpha", "impacts", "wall_s", "cpu_s", "error"]
    table = df[[c for c in cols if c in df.columns]]
    path = out / "parametric.csv"
    with open(path, "w") as f:
        if any("stand-in" in r for r in records):
            f.write("# record 'KATNP N-S synthetic stand-in' is NOT the real KATNP record\n")
        table.to_csv(f, index=False, float_format="%.6g")
    with pd.option_context("display.width", 200, "display.max_rows", 200):
        print(table.drop(columns=["error"]).to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    if args.bench and len(timings) == 2:
        print(f"throughput: 1 worker {n / timings[1]:.2f} runs/s, 2 workers {n / timings[2]:.2f} runs/s "
              f"(speed-up {timings[1] / timings[2]:.2f})")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
