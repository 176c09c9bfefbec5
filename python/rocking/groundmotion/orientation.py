"""Which way a component points: vertical or horizontal, from what its file says.

The body rocks in a vertical plane under a horizontal ground acceleration `ag`;
a vertical component given as `ag` would be a different analysis, silently. So
each Record carries `orientation`, read from its file's header:

- the component's label: UP, DOWN, DWN, UD, V, VER, VERT, VERTICAL, Z, and
  SEED channel codes ending in Z (HNZ, HHZ, BNZ, ...) name the vertical;
  azimuths (90, 360, N28W, S62W), NS, EW and codes ending in N, E, 1, 2 the
  horizontal;
- the header's own words about the component, e.g. GeoNet V2A's "Component Up
  Vertical Accelerometer Axis".

A component whose file says nothing about it (an unlabelled CSV column) is taken
as horizontal, the only motion a one-column record of this model can be.
"""

import re

VERTICAL, HORIZONTAL = "vertical", "horizontal"

_VERTICAL_LABEL = re.compile(r"^(UP|DOWN|DWN|DN|UD|V|VER|VERT|VERTICAL|Z|[A-Z]{2}Z|HN?Z)$")
_VERTICAL_WORDS = re.compile(r"\bvertical\b", re.IGNORECASE)


def is_vertical_label(label):
    """Whether a component label (blanks, '_' and '-' ignored, any case) names the vertical."""
    return bool(_VERTICAL_LABEL.match(re.sub(r"[\s_-]+", "", str(label)).upper()))


def orientation(label, header_text=""):
    """VERTICAL if the label or the header's words about the component say so, else HORIZONTAL."""
    if is_vertical_label(label) or _VERTICAL_WORDS.search(header_text or ""):
        return VERTICAL
    return HORIZONTAL
