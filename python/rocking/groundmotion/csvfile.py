"""CSV records: `time,acc` columns.

Lines starting with `#` are comments (they become the record's `notes`; a
comment "name: X" or "component: X", as `Record.to_csv` writes, sets that
field). The first other line is the header row; the acceleration column is the
first one whose name starts with "acc" (else the second), and its name may
carry the units: "acc_m/s2", "acc_m_s2", "acc[g]", "acc (cm/s^2)". The time
column (the first, in s) must be evenly spaced; the record's time is shifted to
start at 0.
"""

import re
from pathlib import Path

import numpy as np

from ._text import TextFile, choose_unit, make_record, parse_number

_ACC_NAME = re.compile(r"acc(?:el(?:eration)?)?[\s_\-]*(.*)", re.IGNORECASE)


def read_csv(path, units=None):
    """The one component of a `time,acc` CSV file, as a one-element list of
    Records (acc in m/s²). Units from `units` if given, else from the header."""
    tf = TextFile(path)
    comments, header, rows, row_lines = [], None, [], []
    while tf.peek() is not None:
        line = tf.next_line("a line").strip()
        if not line:
            continue
        if line.startswith("#"):
            comments.append(line.lstrip("#").strip())
        elif header is None:
            header, header_line = [name.strip() for name in line.split(",")], tf.lineno
            if len(header) < 2 or any(parse_number(name) is not None for name in header):
                raise tf.error(f"expected a header row of column names like 'time,acc[g]', found {line!r}")
        else:
            rows.append(_parse_row(tf, line, len(header)))
            row_lines.append(tf.lineno)
    if header is None or len(rows) < 2:
        raise tf.error("expected a header row 'time,acc' and at least 2 rows of data", tf.lineno)

    acc_col = next((i for i, name in enumerate(header) if _ACC_NAME.match(name)), 1)
    stated = _ACC_NAME.match(header[acc_col])
    stated = stated.group(1).strip() if stated else ""
    if units is None and not stated:
        raise tf.error(f"expected units in the acceleration column's name (e.g. 'acc[g]', 'acc_m/s2'), "
                       f"found {header[acc_col]!r}; or pass units=", header_line)
    unit = choose_unit(tf, units, stated, header_line)

    data = np.array(rows)
    time, raw = data[:, 0], data[:, acc_col]
    dt = (time[-1] - time[0]) / (len(time) - 1)
    off = np.abs(time - (time[0] + dt * np.arange(len(time))))
    if not dt > 0 or off.max() > 0.01 * dt:
        bad = int(np.argmax(off)) if dt > 0 else 1
        raise tf.error(f"expected evenly spaced times (step {dt:g} s from first and last), "
                       f"found {time[bad]:g}", row_lines[bad])

    meta, notes = {}, []
    for comment in comments:
        key, _, value = comment.partition(":")
        if key.strip() in ("name", "component", "source"):
            meta[key.strip()] = value.strip()
        else:
            notes.append(value.strip() if key.strip() == "notes" else comment)
    notes = "\n".join(notes)
    return [make_record(tf, raw, dt, unit, name=meta.get("name") or Path(tf.path).stem,
                        component=meta.get("component", ""), notes=notes)]


def _parse_row(tf, line, ncols):
    fields = line.split(",")
    values = [parse_number(f) for f in fields]
    if len(fields) != ncols or None in values:
        raise tf.error(f"expected {ncols} numbers separated by commas, found {line!r}")
    return values
