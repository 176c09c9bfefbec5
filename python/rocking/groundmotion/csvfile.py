"""CSV records: `time,acc` columns.

Lines starting with `#` are comments (they become the record's `notes`; a
comment "name: X" or "component: X", as `Record.to_csv` writes, sets that
field). The first other line is the header row; the acceleration column is the
first one whose name has a word starting with "acc" (else the second), and its
name may carry the units: "acc_m/s2", "acc_m_s2", "acc[g]", "acc (cm/s^2)". The time
column (the first, in s) must be evenly spaced; the record's time is shifted to
start at 0 (with a note and a GroundMotionWarning when it did not). The
component is vertical when its `# component:` label or a word of the
acceleration column's name says so ("acc_UD[g]", "HNZ", "up").
"""

import re
import warnings
from pathlib import Path

import numpy as np

from ._text import TextFile, choose_unit, make_record, parse_number
from .orientation import is_vertical_label
from .record import GroundMotionWarning

_ACC_NAME = re.compile(r"\bacc(?:el(?:eration)?)?", re.IGNORECASE)
_BRACKETED = re.compile(r"[\[(](.*?)[\])]")


def _unit_and_words(name):
    """(the units an acceleration column's name states, its other words): the units in
    brackets ("acc_UD[g]", "acc (cm/s^2)"), else what follows "acc" ("acc_m/s2")."""
    bracket = _BRACKETED.search(name)
    if bracket:
        unit, rest = bracket.group(1).strip(), name[:bracket.start()] + " " + name[bracket.end():]
    else:
        acc = _ACC_NAME.search(name)
        unit, rest = (name[acc.end():].strip(" _-"), name[:acc.end()]) if acc else ("", name)
    return unit, [w for w in re.split(r"[^A-Za-z0-9]+", rest) if w]


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

    acc_col = next((i for i, name in enumerate(header) if _ACC_NAME.search(name)), 1)
    stated, words = _unit_and_words(header[acc_col])
    if units is None and not stated:
        raise tf.error(f"expected units in the acceleration column's name (e.g. 'acc[g]', 'acc_m/s2'), "
                       f"found {header[acc_col]!r}; or give the units (units= in Python, --units on the command line)",
                       header_line)
    unit = choose_unit(tf, units, stated, header_line)

    data = np.array(rows)
    time, raw = data[:, 0], data[:, acc_col]
    dt = _even_step(tf, time, row_lines)

    meta, notes = {}, []
    for comment in comments:
        key, _, value = comment.partition(":")
        if key.strip() in ("name", "component", "source"):
            meta[key.strip()] = value.strip()
        else:
            notes.append(value.strip() if key.strip() == "notes" else comment)
    if time[0] != 0:
        shift = f"the time column starts at {time[0]:g} s (line {row_lines[0]}): shifted to start at 0"
        notes.append(shift)
        warnings.warn(f"{tf.path}: {shift}", GroundMotionWarning, stacklevel=3)
    notes = "\n".join(notes)
    component = meta.get("component", "")
    vertical = any(map(is_vertical_label, words))
    return [make_record(tf, raw, dt, unit, header_text="vertical" if vertical else "",
                        name=meta.get("name") or Path(tf.path).stem, component=component, notes=notes)]


def _even_step(tf, time, row_lines):
    """The time step of an evenly spaced time column; else the error names the first line
    whose step differs from the first step by more than 1 %, or where the times drift."""
    steps = np.diff(time)
    first = steps[0]
    if not first > 0:
        raise tf.error(f"expected increasing times, found {time[1]:g} after {time[0]:g}", row_lines[1])
    uneven = np.flatnonzero(np.abs(steps - first) > 0.01 * first)
    if uneven.size:
        k = int(uneven[0]) + 1
        raise tf.error(f"expected evenly spaced times (step {first:g} s, from the first two rows), found "
                       f"{time[k]:g} after {time[k - 1]:g} (a step of {steps[k - 1]:g} s)", row_lines[k])
    dt = (time[-1] - time[0]) / (len(time) - 1)
    off = np.abs(time - (time[0] + dt * np.arange(len(time))))
    if off.max() > 0.01 * dt:
        k = int(np.flatnonzero(off > 0.01 * dt)[0])
        raise tf.error(f"expected evenly spaced times (step {dt:g} s from first and last), found "
                       f"{time[k]:g}, {off[k]:g} s off", row_lines[k])
    return dt


def _parse_row(tf, line, ncols):
    fields = line.split(",")
    values = [parse_number(f) for f in fields]
    if len(fields) != ncols or None in values:
        raise tf.error(f"expected {ncols} numbers separated by commas, found {line!r}")
    return values
