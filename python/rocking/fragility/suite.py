"""A suite of ground motions: every horizontal component of every record file in folders.

    records = load_suite(["data/ground-motions"])   # {name: Record}

A file with several components (CSMIP V2, GeoNet V2A) gives one ground motion
per horizontal component; files of one component each (PEER AT2, GeoNet's
.000/.090, USGS SMC) give one each. Vertical components (`Record.orientation`,
read from the file's header: labels UP, UD, V, VER, VERT, VERTICAL, Z, HNZ, ...)
are left out: the body rocks in a vertical plane under a horizontal ground
acceleration. Names are the file's path
relative to the folder, with the component in brackets.
"""

from pathlib import Path

from .. import groundmotion as gm
from ..groundmotion.files import record_files
from ..groundmotion.orientation import is_vertical_label

is_vertical = is_vertical_label  # the name this module gave it first


def load_suite(sources):
    """{name: Record} of the horizontal components of the record files in `sources`
    (folders, searched recursively, or files). A file no reader knows raises the reader's
    error naming it; ValueError if nothing is found."""
    suite = {}
    for source in map(Path, sources):
        if not source.exists():
            raise FileNotFoundError(f"{source}: no such record file or folder")
        files, base = (record_files(source), source) if source.is_dir() else ([source], source.parent)
        for path in files:
            components = gm.read_all(path)
            label = path.relative_to(base).as_posix()
            for rec in components:
                if rec.vertical:
                    continue
                suite[f"{label}[{rec.component}]" if rec.component else label] = rec
    if not suite:
        raise ValueError(f"{', '.join(map(str, sources))}: no horizontal record components found")
    return suite
