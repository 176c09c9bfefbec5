"""Dump the two horizontal components and the vertical of the shipped records for
examples/spatial_record.rs (the cost of the round body in space against the planar run,
docs/performance.md): per record a file of the examples' record-pair format (examples/support/pair_file.rs): a line
`# name bearing_x`, the time step, then `agx agy av` per sample, m/s².

    .venv/bin/python benches/spatial_record.py --dump /tmp/spatial-records
    cargo run --release --example spatial_record -- /tmp/spatial-records/*.txt
"""

import argparse
import re
from pathlib import Path

from rocking import groundmotion as gm
from rocking import paths

RECORDS = ("geonet-darfield-2010/3366146_DFHS_HN_20.090", "geonet-kaikoura-2016", "usgs-lomaprieta-1989/0111a.smc")


def pairs():
    """(name, HorizontalPair) of the shipped records with two horizontal components."""
    base = paths.data_dir()
    for rel in RECORDS:
        path = base / rel
        if path.is_dir():
            path = next(p for p in sorted(path.iterdir()) if gm.is_record_file(p))
        pair = gm.pair_of(path)
        yield pair.name, pair


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dump", required=True, type=Path, help="folder for the record files")
    args = parser.parse_args()
    args.dump.mkdir(parents=True, exist_ok=True)
    for name, pair in pairs():
        v = pair.vertical.acc if pair.vertical is not None else [0.0] * pair.npts
        out = args.dump / (re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")[:40] + ".txt")
        with open(out, "w") as f:
            f.write(f"# {re.sub(r'[^A-Za-z0-9]+', '_', name).strip('_')[:40]} "
                    f"{pair.bearing_x if pair.bearing_x is not None else 'none'}\n")
            f.write(f"{float(pair.dt)!r}\n")
            for x, y, z in zip(pair.x.acc, pair.y.acc, v):
                f.write(f"{float(x)!r} {float(y)!r} {float(z)!r}\n")
        print(f"{out}: {pair.npts} samples at {pair.dt} s, PGA {pair.pga:.3f} m/s²")


if __name__ == "__main__":
    main()
