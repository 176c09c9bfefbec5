"""Readers for strong-motion accelerogram files.

    from rocking import groundmotion as gm
    rec = gm.read("…/ce36456p_CE36456.V2", component="UP")   # one Record, acc in m/s²
    recs = gm.read_all("…/20161113_110259_WTMC_20.V2A")       # every component, file order
    kat = gm.katnp()          # the KATNP stand-in (synthetic!) or gm.katnp("real file")

Formats (one module each): CSMIP/CESMD V2 (`csmip`), GeoNet V2A (`geonet`),
USGS SMC (`smc`), plain "npts dt" ASCII (`nptsdt`), PEER NGA AT2 (`peer`),
`time,acc` CSV (`csvfile`). Accelerations are converted to m/s² with
g = 9.80665 m/s². Each Record says whether it is the vertical component
(`rec.orientation`, `rec.vertical`, from the file's header); `components(path)` gives
the whole record set (sibling files too) and `vertical_of(rec)` its vertical;
`record_files(folder)` the files of a folder that may be records (`files`: caches,
scripts and READMEs are passed over). `pair_of(path)` gives a set's two horizontal
components (and its vertical) as one `HorizontalPair` on one time base, which
`rotated(azimuth)` turns and `along(azimuth)` reduces to one Record (`pair`). Malformed files raise `GroundMotionFormatError` (a
ValueError) naming the file, the line and what was expected there.
"""

from .csmip import read_csmip_v2
from .csvfile import read_csv
from .detect import READERS, detect_format, read, read_all
from .files import is_record_file, record_files
from .geonet import read_geonet_v2a
from .katnp import DATA_DIR, STANDIN_PATH, katnp, katnp_standin
from .nptsdt import read_npts_dt
from .pair import HorizontalPair, bearing, pair_of
from .peer import read_peer_at2
from .orientation import HORIZONTAL, VERTICAL
from .recordset import components, set_key, vertical_of, with_vertical
from .record import PLAUSIBLE_PGA_G, GroundMotionFormatError, GroundMotionWarning, Record
from .smc import read_smc
from .units import G, canonical_unit, to_m_s2

__all__ = [
    "G", "DATA_DIR", "HORIZONTAL", "VERTICAL", "PLAUSIBLE_PGA_G", "GroundMotionFormatError",
    "GroundMotionWarning", "READERS", "Record", "STANDIN_PATH",
    "canonical_unit", "detect_format", "katnp", "katnp_standin", "read", "read_all",
    "read_csmip_v2", "read_csv", "read_geonet_v2a", "read_npts_dt", "read_peer_at2",
    "read_smc", "to_m_s2", "components", "set_key", "vertical_of", "with_vertical",
    "is_record_file", "record_files", "HorizontalPair", "bearing", "pair_of",
]
