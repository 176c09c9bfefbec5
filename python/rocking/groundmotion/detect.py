"""Format detection and the `read` / `read_all` entry points."""

import re
from pathlib import Path

from ._text import TextFile, parse_number
from .csmip import read_csmip_v2
from .csvfile import read_csv
from .geonet import read_geonet_v2a
from .nptsdt import read_npts_dt
from .peer import read_peer_at2
from .record import GroundMotionFormatError
from .smc import read_smc

#: Format name -> reader; each reader takes (path, units=None) and returns a list of Records.
READERS = {
    "csmip_v2": read_csmip_v2,
    "geonet_v2a": read_geonet_v2a,
    "smc": read_smc,
    "npts_dt": read_npts_dt,
    "peer_at2": read_peer_at2,
    "csv": read_csv,
}
_ALIASES = {"v2": "csmip_v2", "cesmd": "csmip_v2", "csmip": "csmip_v2", "v2a": "geonet_v2a",
            "geonet": "geonet_v2a", "at2": "peer_at2", "peer": "peer_at2", "darfield": "npts_dt"}
_EXTENSIONS = {".v2": "csmip_v2", ".v2a": "geonet_v2a", ".smc": "smc", ".at2": "peer_at2", ".csv": "csv"}


def detect_format(path):
    """Name of the format of the file at `path` (a key of READERS), from its
    first lines, else from its extension."""
    tf = TextFile(path)
    head = [line.strip() for line in tf.lines[:5]] + [""] * 5
    first = head[0].lower()
    if first.startswith("corrected accelerogram"):
        return "csmip_v2" if "chan" in first else "geonet_v2a"
    if re.match(r"[12] (un)?corrected accelerogram", first):
        return "smc"
    if re.search(r"NPTS\s*=.*DT\s*=|NPTS\s*,\s*DT", head[3], re.IGNORECASE):
        return "peer_at2"
    suffix = Path(path).suffix.lower()
    if suffix in _EXTENSIONS:
        return _EXTENSIONS[suffix]
    if head[0].startswith("#") or ("," in head[0] and "," in head[1]):
        return "csv"
    words = head[1].split()
    if len(words) >= 2 and words[0].isdigit() and parse_number(words[1]) is not None:
        return "npts_dt"
    raise GroundMotionFormatError(
        "cannot tell the format from the first lines or the extension; give it (fmt= in Python, "
        "--fmt on the command line) as one of " + ", ".join(READERS), path)


def read_all(path, units=None, fmt=None):
    """All components in the file at `path`, in file order, as Records (acc in m/s²).

    fmt: a READERS key (or "v2", "v2a", "at2", "darfield"); detected if None.
    units: units of the numbers in the file, overriding what the file states.
    """
    fmt = detect_format(path) if fmt is None else _ALIASES.get(fmt.lower(), fmt.lower())
    if fmt not in READERS:
        raise ValueError(f"unknown format {fmt!r}: expected one of {', '.join(READERS)}")
    return READERS[fmt](path, units=units)


def read(path, units=None, component=None, fmt=None):
    """One component of the file at `path` as a Record (acc in m/s²).

    component: None for the first; an int index; or the label, e.g. "N28W", "360",
    "UP" (case and blanks ignored). Other arguments as for `read_all`.
    """
    records = read_all(path, units=units, fmt=fmt)
    return select(records, component, path)


def select(records, component, path=""):
    """The record of `records` that `component` names (see `read`)."""
    if component is None:
        return records[0]
    if isinstance(component, int):
        if -len(records) <= component < len(records):
            return records[component]
    else:
        for record in records:
            if _label(record.component) == _label(component):
                return record
    raise ValueError(f"{path}: no component {component!r}; the file holds "
                     + ", ".join(repr(r.component) for r in records))


def _label(text):
    return re.sub(r"\s+", "", str(text)).upper()
