"""The study's results on disk: a Parquet dataset, one file per finished task.

Each file is written whole under a temporary name and renamed into place, its
name fixed by the task's key: a crash or Ctrl-C leaves only finished tasks, a
task run twice (a worker lost after it finished) replaces its own file, and
`done()` is the set of keys a rerun skips.
"""

import hashlib
import json
import os
from pathlib import Path

import pyarrow as pa
import pyarrow.dataset as ds
import pyarrow.parquet as pq

#: Units of the columns (in the Parquet schema's field metadata, so the table stands alone);
#: im and im_record are in the unit of im_name (IM_UNITS).
UNITS = {"im_record": "unit of im_name", "alpha": "rad", "im": "unit of im_name", "scale": "1",
         "t_overturn": "s", "peak_theta_over_alpha": "1 (peak |theta| / alpha)", "wall_s": "s", "cpu_s": "s"}
IM_UNITS = {"PGA": "g", "PGV": "m/s", "SA(T)": "g", "AvgSA(T1-T2)": "g", "PGA/gtana": "1",
            "PGV/(gtana/p)": "1"}
_DESCRIPTION = {
    "phase": "hunt, scan, bracket (ida), grid (ida, dense grid) or stripe (msa)",
    "unresolved": "ida hunts: what the run budget left undone ('' if nothing)",
    "t_overturn": "time of overturning, nan if the body stood",
    "wall_s": "wall time of the run in its worker",
    "cpu_s": "CPU time of the run in its worker (process time)",
}


def _field(name, kind):
    meta = {}
    if name in UNITS:
        meta["unit"] = UNITS[name]
    if name in _DESCRIPTION:
        meta["description"] = _DESCRIPTION[name]
    return pa.field(name, kind, metadata=meta or None)


#: Columns of every row, in order (meta columns first).
SCHEMA = pa.schema([_field(n, k) for n, k in [
    ("task", pa.string()), ("method", pa.string()), ("body", pa.string()), ("record", pa.string()),
    ("im_name", pa.string()), ("im_record", pa.float64()), ("alpha", pa.float64()),
    ("im", pa.float64()), ("scale", pa.float64()), ("phase", pa.string()),
    ("overturned", pa.bool_()), ("t_overturn", pa.float64()), ("peak_theta_over_alpha", pa.float64()),
    ("error", pa.string()), ("unresolved", pa.string()), ("worker", pa.string()), ("wall_s", pa.float64()),
    ("cpu_s", pa.float64()),
]], metadata={"im_units": json.dumps(IM_UNITS)})


def _file_name(task):
    return f"part-{hashlib.sha1(task.encode()).hexdigest()[:20]}.parquet"


class ResultStore:
    """The dataset in folder `path` (created if missing)."""

    def __init__(self, path):
        self.path = Path(path)
        self.path.mkdir(parents=True, exist_ok=True)

    def files(self):
        return sorted(self.path.glob("part-*.parquet"))

    def finished(self, keys):
        """The keys among `keys` whose file is on disk (by name: no file is read)."""
        present = {f.name for f in self.files()}
        return {k for k in keys if _file_name(k) in present}

    def done(self):
        """Keys of the tasks whose rows are on disk, read from the files."""
        if not self.files():
            return set()
        keys = ds.dataset(self.files(), format="parquet", schema=SCHEMA).to_table(columns=["task"])
        return set(keys.column("task").to_pylist())

    def write(self, task, rows):
        """Write the rows of `task` (dicts with the SCHEMA's columns) as its file."""
        table = pa.Table.from_pylist([{k: r.get(k) for k in SCHEMA.names} for r in rows], schema=SCHEMA)
        final = self.path / _file_name(task)
        tmp = final.with_suffix(f".tmp{os.getpid()}")
        pq.write_table(table, tmp)
        os.replace(tmp, final)

    def read(self):
        """Every row, as a pandas DataFrame."""
        files = self.files()
        if not files:
            return SCHEMA.empty_table().to_pandas()
        return ds.dataset(files, format="parquet", schema=SCHEMA).to_table().to_pandas()
