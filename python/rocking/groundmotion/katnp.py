"""The KATNP record (NQ.KATNP, Kanti Path, Kathmandu; north-south component of the
2015 Gorkha earthquake), used for the Dharahara Tower, and its synthetic stand-in.

The real record could not be obtained for this project. `katnp()` returns the
real record when given the path of its file (any format `read` knows, e.g. the
CESMD download) and otherwise the synthetic stand-in, whose `notes` say so.
"""

import re

from .. import paths
from .detect import read_all, select

#: The ground-motion records shipped with the repository (data/ground-motions);
#: None when the package is not installed from the repository (see rocking.paths).
DATA_DIR = paths.REPO / "data" / "ground-motions" if paths.REPO is not None else None
#: The synthetic stand-in for the KATNP north-south record (CSV, m/s²).
STANDIN_PATH = DATA_DIR / "katnp-standin" / "KATNP_NS_standin.csv" if DATA_DIR is not None else None

STANDIN_NOTE = (
    "Synthetic stand-in for the KATNP north-south record of the 2015 Gorkha earthquake "
    "(NQ.KATNP, Kanti Path, Kathmandu), NOT the real record: a velocity pulse (period 5.24 s) "
    "plus band-limited noise, built to match the station's published PGA, PGV and spectral "
    "accelerations (see data/ground-motions/README.md). Results that use it must say so."
)

# Labels that mean north-south, after upper-casing and removing blanks.
_NORTH_SOUTH = {"0", "000", "360", "N", "NS", "N-S", "N00E", "N00W", "NORTH", "HNN", "HLN", "BHN"}


def katnp_standin():
    """The synthetic stand-in for the KATNP north-south record (acc in m/s², dt 0.01 s, 80 s).

    Its `notes` say plainly that it is a synthetic stand-in, not the real record.
    """
    record = read_all(paths.data_dir() / "katnp-standin" / "KATNP_NS_standin.csv", fmt="csv")[0]
    record.name = "KATNP (synthetic stand-in), 2015 Gorkha earthquake"
    record.component = "NS"
    record.notes = STANDIN_NOTE + "\nFile comments:\n" + record.notes
    return record


def katnp(path=None, component=None, units=None):
    """The KATNP north-south record: read from `path` if given (the real file, as a
    drop-in replacement for the stand-in), else `katnp_standin()`.

    component: which component of the file to take; by default the only one, or
    the one labelled north-south ("0", "360", "N", "NS", "N00E", "HNN", ...).
    """
    if path is None:
        return katnp_standin()
    records = read_all(path, units=units)
    if component is None and len(records) > 1:
        north = [r for r in records if re.sub(r"\s+", "", r.component).upper() in _NORTH_SOUTH]
        if len(north) != 1:
            raise ValueError(f"{path}: cannot tell the north-south component among "
                             + ", ".join(repr(r.component) for r in records) + "; pass component=")
        return north[0]
    return select(records, component, path)
