"""Plain "npts dt" ASCII records (as in the GeoNet Darfield files *.000, *.090, *.ver).

Line 1: station and component ("DFHS       000"); line 2: the number of points
and the time step in s, possibly followed by more numbers
("19707  5.00000e-03 0 0  0.00000e+00 ..."); then the values separated by
blanks, any number to a line. The values are in g; the file does not say so,
so pass `units=` for files written in other units.
"""

from ._text import TextFile, choose_unit, make_record, parse_number


def read_npts_dt(path, units=None):
    """The one component of an "npts dt" file, as a one-element list of Records
    (acc in m/s²). Values are taken to be in g unless `units` says otherwise."""
    tf = TextFile(path)
    words = tf.next_line("the station and component").split()
    if not words or parse_number(words[0]) is not None:
        raise tf.error(f"expected the station and component, found {' '.join(words)!r}")
    station, component = words[0], " ".join(words[1:])
    fields = tf.next_line("'npts dt'").split()
    npts = fields[0] if fields else ""
    dt = parse_number(fields[1]) if len(fields) > 1 else None
    if not npts.isdigit() or dt is None or dt <= 0:
        raise tf.error(f"expected 'npts dt' (an integer number of points and a positive time "
                       f"step in s), found {' '.join(fields[:2])!r}")
    unit = choose_unit(tf, units, "g")
    raw = tf.read_free(int(npts), "acceleration")
    tf.expect_end(f"the {npts} points of line 2")
    notes = "plain 'npts dt' ASCII record; units not stated in the file: " + (
        f"read as {unit} (units= given)" if units is not None else "g by the format's convention")
    return [make_record(tf, raw, dt, unit, name=station, component=component, notes=notes)]
