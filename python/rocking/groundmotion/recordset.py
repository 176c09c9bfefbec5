"""A record set: every component recorded at one station in one event, and its vertical.

Some formats hold the whole set in one file (CSMIP V2, GeoNet V2A); others
hold one component to a file and ship the set as sibling files (USGS SMC
`0111a.smc`, `0111b.smc`, `0111c.smc`; PEER AT2 triplets `..._ELC180.AT2`,
`..._ELCUP.AT2`; the Darfield ASCII `DFHS.000`, `.090`, `.ver`). The siblings of
a one-component file are the files of its folder with the same format whose
station/event, the record's name with its component label taken out, is the
same.

    recs = components("0111a.smc")            # 360, up, 270, each with .orientation
    up = vertical_of(gm.read("0111a.smc"))    # the matching vertical Record, or None
"""

from pathlib import Path

from .detect import detect_format, read_all
from .files import is_record_file
from .record import GroundMotionFormatError


def set_key(record):
    """The station/event a record belongs to: its name without its component label (any case)."""
    name = record.name
    label = str(record.component).strip()
    if label and name.upper().rstrip().endswith(label.upper()):
        name = name.rstrip()[: -len(label)]
    return " ".join(name.replace(",", " ").split()).upper()


def components(path, units=None, fmt=None):
    """All components of the record set of the file at `path` (Records, acc in m/s²).

    The file's own components first (file order), then those of its sibling
    files (sorted by file name) with the same station/event.
    """
    path = Path(path)
    fmt = fmt or detect_format(path)
    own = read_all(path, units=units, fmt=fmt)
    if len(own) > 1:
        return own
    key = set_key(own[0])
    found = list(own)
    for other in sorted(path.parent.iterdir()):
        if other == path or not other.is_file() or not is_record_file(other):
            continue
        try:
            if detect_format(other) != fmt:
                continue
            recs = read_all(other, units=units, fmt=fmt)
        except (GroundMotionFormatError, ValueError, UnicodeDecodeError, OSError):
            continue  # not a record of this format: not part of the set
        found += [r for r in recs if set_key(r) == key]
    return found


def with_vertical(record, units=None, fmt=None):
    """Copy of `record` whose `av_record` is its set's vertical component; ValueError when
    the set has none (one line naming the file)."""
    import dataclasses
    vertical = vertical_of(record, units=units, fmt=fmt)
    if vertical is None:
        raise ValueError(f"{record.source} [{record.component}]: no vertical component in its record set")
    return dataclasses.replace(record, av_record=vertical)


def vertical_of(record, units=None, fmt=None):
    """The vertical component of `record`'s set (same station and event), by orientation;
    None when the set has none. Raises ValueError when the set has several."""
    if record.vertical:
        return record
    if not record.source:
        return None
    verticals = [r for r in components(record.source, units=units, fmt=fmt) if r.vertical]
    if len(verticals) > 1:
        raise ValueError(f"{record.source}: the record set holds {len(verticals)} vertical components ("
                         + ", ".join(f"{r.source} [{r.component}]" for r in verticals) + "): name one")
    return verticals[0] if verticals else None
