"""GeoNet (New Zealand) "V2A" corrected accelerograms.

A file holds one station's components one after the other. Each component is
16 text lines (among them "Number of points  8192    Duration 163.82 sec",
"Instrument corrected data at 0.020 sec intervals", "Component N28W ...",
"Acceleration:  peak  -9733.1 mm/s/s at  44.88 sec ..."), 4 lines of 10 integers
and 6 lines of 10 reals (fields of 8 characters), then the acceleration,
velocity and displacement blocks, 10 numbers to a line in fields of 8
characters, with no line between them. The integer header's 4th line gives the
three blocks' lengths (its 4th-6th numbers). Only the acceleration is read; its
peak is checked against the "Acceleration: peak" line.
"""

import re

from ._text import TextFile, check_peak, choose_unit, lines_for, make_record

TEXT_LINES, INTEGERS, REALS, WIDTH, PER_LINE = 16, 40, 60, 8, 10
_FIRST_LINE = "corrected accelerogram"
_TEXT_FIELDS = {
    "npts": re.compile(r"Number of points\s+(\d+)"),
    "dt": re.compile(r"data at\s+([\d.]+)\s+sec intervals"),
    "component": re.compile(r"Component\s+(\S+)"),
    "peak": re.compile(r"Acceleration:\s+peak\s+(\S+)\s+(\S+)"),
    "site": re.compile(r"Site\s+(\S+)"),
}


def _is_component_start(line):
    return line.strip().lower().startswith(_FIRST_LINE)


def read_geonet_v2a(path, units=None):
    """All components of a GeoNet V2A file, in file order, as Records (acc in m/s²).

    `units` overrides the units the header states (normally mm/s/s).
    """
    return TextFile(path).read_sections(lambda tf: _read_component(tf, units),
                                        "a V2A component ('Corrected accelerogram ...')")


def _read_component(tf, units):
    start = tf.lineno + 1
    text = [tf.next_line("the 16 lines of a V2A text header") for _ in range(TEXT_LINES)]
    if not _is_component_start(text[0]):
        raise tf.error(f"expected a component header starting 'Corrected accelerogram', found {text[0].strip()!r}",
                       start)
    found = {}
    for key, pattern in _TEXT_FIELDS.items():
        hit = next(((i, m) for i, m in enumerate(map(pattern.search, text)) if m), None)
        if hit is None and key != "site":
            raise tf.error(f"expected {pattern.pattern!r} in the text header (lines {start}-{start + 15})", start)
        found[key] = hit
    npts = int(found["npts"][1].group(1))
    dt = float(found["dt"][1].group(1))
    peak_line = start + found["peak"][0]
    stated_peak, stated_unit = found["peak"][1].groups()
    unit = choose_unit(tf, units, stated_unit, peak_line)

    integers = tf.read_fixed(INTEGERS, WIDTH, PER_LINE, "integer header").astype(int)
    if integers[33] != npts:
        raise tf.error(f"the integer header gives {integers[33]} acceleration points, the text header "
                       f"{npts} (line {start + found['npts'][0]})", tf.lineno)
    tf.read_fixed(REALS, WIDTH, PER_LINE, "real header")

    raw = tf.read_fixed(npts, WIDTH, PER_LINE, "acceleration", block_end=_is_component_start)
    check_peak(tf, raw, stated_peak, peak_line)
    tf.skip_lines(lines_for(integers[34], PER_LINE), f"{integers[34]} velocity points")
    tf.skip_lines(lines_for(integers[35], PER_LINE), f"{integers[35]} displacement points")

    site = found["site"][1].group(1) if found["site"] else ""
    name = ", ".join(" ".join(s.split()) for s in (f"{site} {text[2]}", text[7]) if s.strip())
    notes = f"GeoNet V2A corrected accelerogram (header lines {start}-{start + 25}); peak checked against the header"
    component_line = text[found["component"][0]]  # "Component Up    Vertical Accelerometer Axis"
    return make_record(tf, raw, dt, unit, header_text=component_line, name=name,
                       component=found["component"][1].group(1), notes=notes)
