"""USGS SMC ("strong-motion centroid") corrected accelerograms, one component per file.

Layout: 11 text lines (line 1 "2 CORRECTED ACCELEROGRAM"; line 6 "station = ...
component=  360"; line 7 "... pk = 104.4"), 48 integers (8 to a line, fields
of 10), 50 reals (5 to a line, fields of 15), as many comment lines as the
16th integer states, then as many values as the 17th integer states, 8 to a
line in fields of 10. The 2nd real is the sampling rate in samples/s. Missing
header values are -32768 (integers) and 1.7e38 (reals). Corrected SMC
accelerations are in cm/s² (the format defines it; the file does not state it).
"""

import re

from ._text import TextFile, check_peak, choose_unit, make_record

TEXT_LINES, INTEGERS, REALS = 11, 48, 50
MISSING_INT, MISSING_REAL = -32768, 1.7e38
_STATION = re.compile(r"station\s*=\s*(.*?)\s*component\s*=\s*(\S+)", re.IGNORECASE)
_PEAK = re.compile(r"\bpk\s*=\s*(\S+)")


def read_smc(path, units=None):
    """The one component of a USGS SMC file, as a one-element list of Records
    (acc in m/s²). `units` overrides the format's cm/s²."""
    tf = TextFile(path)
    text = [tf.next_line("the 11 lines of the SMC text header") for _ in range(TEXT_LINES)]
    if not re.match(r"\s*2 CORRECTED ACCELEROGRAM", text[0], re.IGNORECASE):
        raise tf.error(f"expected '2 CORRECTED ACCELEROGRAM' (this reader takes corrected SMC "
                       f"accelerations only), found {text[0].strip()!r}", 1)
    integers = tf.read_fixed(INTEGERS, 10, 8, "integer header").astype(int)
    int_line = tf.lineno
    reals = tf.read_fixed(REALS, 15, 5, "real header")
    ncomments, npts, rate = integers[15], integers[16], reals[1]
    if npts == MISSING_INT or npts < 1 or ncomments < 0:
        raise tf.error(f"expected the number of comment lines and of points as integers 16 and 17 "
                       f"of the integer header, found {ncomments} and {npts}", int_line - 3)
    if not 0 < rate < MISSING_REAL:
        raise tf.error(f"expected the sampling rate (samples/s) as real 2 of the real header, found {rate:g}",
                       int_line + 1)
    tf.skip_lines(ncomments, f"{ncomments} comment lines (integer 16 of the header)")
    unit = choose_unit(tf, units, "cm/s2")
    raw = tf.read_fixed(npts, 10, 8, "acceleration")
    tf.expect_end(f"the {npts} points the header states")

    peak = next(((i + 1, m.group(1)) for i, m in enumerate(map(_PEAK.search, text)) if m), None)
    if peak:
        check_peak(tf, raw, peak[1], peak[0])
    station = next((m for m in map(_STATION.search, text) if m), None)
    name = ", ".join(s for s in (station.group(1) if station else "", " ".join(text[3].split())) if s)
    notes = "USGS SMC corrected accelerogram (cm/s² by format)"
    return [make_record(tf, raw, 1.0 / rate, unit, name=name,
                        component=station.group(2) if station else "", notes=notes)]
