"""PEER NGA ".AT2" acceleration records.

Four header lines, e.g.

    PEER NGA STRONG MOTION DATABASE RECORD
    IMPERIAL VALLEY 10/15/79 2319, EL CENTRO ARRAY #6, 230
    ACCELERATION TIME SERIES IN UNITS OF G
    NPTS=  3930, DT=   .0100 SEC

then the values in g, 5 to a line, separated by blanks. The older layout of
line 4, "3930    0.0100    NPTS, DT", is read too. Line 2 gives the name; its
last comma-separated part, the component.
"""

import re

from ._text import TextFile, choose_unit, make_record, parse_number

_NPTS_DT = re.compile(r"NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*(\S+)", re.IGNORECASE)
_OLD_NPTS_DT = re.compile(r"\s*(\d+)\s+(\S+)\s+NPTS\s*,\s*DT", re.IGNORECASE)
_UNITS = re.compile(r"UNITS OF\s+(\S+)", re.IGNORECASE)


def read_peer_at2(path, units=None):
    """The one component of a PEER .AT2 file, as a one-element list of Records
    (acc in m/s²). Units from line 3 ("IN UNITS OF G"), g if it names none;
    `units` overrides."""
    tf = TextFile(path)
    head = [tf.next_line("the 4 header lines of an AT2 file") for _ in range(4)]
    m = _NPTS_DT.search(head[3]) or _OLD_NPTS_DT.match(head[3])
    dt = parse_number(m.group(2).rstrip(",")) if m else None
    if dt is None or dt <= 0:
        raise tf.error(f"expected 'NPTS=  n, DT=   dt SEC', found {head[3].strip()!r}", 4)
    stated = _UNITS.search(head[2])
    unit = choose_unit(tf, units, stated.group(1) if stated else "g", 3)
    raw = tf.read_free(int(m.group(1)), "acceleration")
    tf.expect_end(f"the {m.group(1)} points of line 4")
    name = head[1].strip()
    component = name.rsplit(",", 1)[1].strip() if "," in name else ""
    notes = f"PEER NGA AT2 record: {head[0].strip()}"
    return [make_record(tf, raw, dt, unit, name=name, component=component, notes=notes)]
