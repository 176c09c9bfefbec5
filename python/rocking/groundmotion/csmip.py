"""CSMIP / CESMD "V2" corrected accelerograms (California Strong Motion
Instrumentation Program, as distributed by CESMD).

A file holds one or more channels. Each channel has a text header (line 1
"CORRECTED ACCELEROGRAM ... CHAN  1:  90 DEG", a line "CHAN  1:  90 DEG", a line
"PEAK ACCELERATION =  -267.957    CM/SEC/SEC  AT   10.940   SEC."), integer and
real header blocks, then three data blocks, each introduced by a line like

     3251 POINTS OF ACCEL DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: CM/SEC/SEC)

(ACCEL, then VELOC, then DISPL), written 8 numbers to a line in fields of 10
characters, and ends with a line starting "/&". Only the acceleration block is
read; its count, step and units come from its own header line, and its peak is
checked against the PEAK ACCELERATION line.
"""

import re

from ._text import TextFile, check_peak, choose_unit, make_record

_ACCEL_LINE = re.compile(
    r"\s*(\d+)\s+POINTS OF ACCEL DATA EQUALLY SPACED AT\s+([\d.]+)\s+SEC\.?\s+\(UNITS:\s*([^)]+?)\s*\)")
_CHAN_LINE = re.compile(r"CHAN\s+(\d+):\s*(.*?)\s*$")
_PEAK_LINE = re.compile(r"\s*PEAK ACCELERATION\s*=\s*(\S+)\s+(\S+)")
_STATION_LINE = re.compile(r"\s*STATION NO\.\s*(\S+)")


def _is_block_line(line):
    """True for a data block's header or the end-of-channel line (not data)."""
    return "POINTS OF" in line or line.startswith("/&")


def read_csmip_v2(path, units=None):
    """All channels of a CSMIP/CESMD V2 file, in file order, as Records (acc in m/s²).

    `units` overrides the units the file states (normally CM/SEC/SEC).
    Components are labelled as the file does, without "DEG": "90", "UP", "0".
    """
    return TextFile(path).read_sections(lambda tf: _read_channel(tf, units),
                                        "a CSMIP V2 channel ('CORRECTED ACCELEROGRAM ...')")


def _read_channel(tf, units):
    first = tf.next_line("a channel header")
    start = tf.lineno
    if not first.lstrip().upper().startswith("CORRECTED ACCELEROGRAM"):
        raise tf.error(f"expected a channel header starting 'CORRECTED ACCELEROGRAM', found {first.strip()!r}")
    header = [first]
    while True:
        line = tf.next_line("a line 'N POINTS OF ACCEL DATA EQUALLY SPACED AT dt SEC. (UNITS: ...)'")
        if line.startswith("/&") or line.lstrip().upper().startswith("CORRECTED ACCELEROGRAM"):
            raise tf.error(f"expected a line 'N POINTS OF ACCEL DATA ...' in the channel header "
                           f"starting on line {start}, found {line.strip()!r}")
        if "POINTS OF ACCEL DATA" in line:
            break
        header.append(line)
    m = _ACCEL_LINE.match(line)
    if not m:
        raise tf.error(f"expected 'N POINTS OF ACCEL DATA EQUALLY SPACED AT dt SEC.  (UNITS: u)', "
                       f"found {line.strip()!r}")
    npts, dt, unit_text = int(m.group(1)), float(m.group(2)), m.group(3)
    unit_line = tf.lineno
    unit = choose_unit(tf, units, unit_text, unit_line)

    raw = tf.read_fixed(npts, 10, 8, "acceleration", block_end=_is_block_line)
    after = tf.peek()
    if after is not None and not _is_block_line(after):
        raise tf.error(f"expected the VELOC block header after the {npts} acceleration points "
                       f"the header states, found {after.strip()!r}", tf.lineno + 1)

    peak_line = next((start + i for i, h in enumerate(header) if _PEAK_LINE.match(h)), None)
    if peak_line is not None:
        stated, stated_unit = _PEAK_LINE.match(header[peak_line - start]).groups()
        if tf.unit(stated_unit, peak_line) != tf.unit(unit_text, unit_line):
            raise tf.error(f"the peak is stated in {stated_unit}, the data in {unit_text}", peak_line)
        check_peak(tf, raw, stated, peak_line)

    while not tf.next_line("the end-of-channel line '/&'").startswith("/&"):
        pass

    chan = next((m for m in map(_CHAN_LINE.match, header) if m), None)
    label = re.sub(r"\s*DEG$", "", chan.group(2)) if chan else ""
    station = next((m.group(1) for m in map(_STATION_LINE.match, header) if m), "")
    name = ", ".join(s for s in (_line(header, 6), f"station {station}" if station else "", _line(header, 2)) if s)
    notes = (f"CSMIP/CESMD V2 corrected accelerogram, channel {chan.group(1) if chan else '?'} "
             f"(header lines {start}-{unit_line}); peak checked against the header")
    return make_record(tf, raw, dt, unit, name=name, component=label, notes=notes)  # "UP": vertical


def _line(header, index):
    return header[index].strip() if index < len(header) else ""
