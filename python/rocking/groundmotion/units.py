"""Acceleration units: canonical names and conversion to m/s².

Four units are known, under their canonical names:

    "g"      standard gravity, g = 9.80665 m/s² (the exact conventional value,
             3rd CGPM 1901; used for every g <-> m/s² conversion in this package)
    "m/s2"   metres per second squared
    "cm/s2"  centimetres per second squared (= gal)
    "mm/s2"  millimetres per second squared

`canonical_unit` accepts the spellings found in strong-motion files and CSV
headers: "cm/sec/sec", "cm/s/s", "cm/s^2", "cm/s²", "cm_s2", "gal", "mm/s/s",
"m/s**2", "ms-2", "G", ... (case and blanks ignored).
"""

import re

import numpy as np

#: Standard gravity in m/s² (exact by definition); used for all conversions from g.
G = 9.80665

#: Factor from each canonical unit to m/s².
TO_M_S2 = {"g": G, "m/s2": 1.0, "cm/s2": 0.01, "mm/s2": 0.001}

_NAMES = {"g": "g", "gs": "g", "g's": "g", "gal": "cm/s2", "gals": "cm/s2"}
_LENGTH_PER_S2 = re.compile(r"(mm|cm|m)(?:/s2|/s/s|\.?s-2)")


def canonical_unit(text):
    """Canonical name ("g", "m/s2", "cm/s2", "mm/s2") of an acceleration unit.

    Raises ValueError for anything else.
    """
    s = re.sub(r"\s+", "", str(text).lower()).replace("²", "2")
    s = s.strip("[]()")
    if s in _NAMES:
        return _NAMES[s]
    s = s.replace("sec", "s").replace("**2", "2").replace("^2", "2").replace("_", "/")
    m = _LENGTH_PER_S2.fullmatch(s)
    if m:
        return m.group(1) + "/s2"
    raise ValueError(
        f"unknown acceleration units {text!r}: expected g, m/s2, cm/s2 or mm/s2 "
        "(or a common spelling of them such as cm/sec/sec, cm/s^2, gal, mm/s/s)"
    )


def to_m_s2(values, unit):
    """Values given in `unit` (any spelling `canonical_unit` accepts) converted to m/s²."""
    return np.asarray(values, dtype=float) * TO_M_S2[canonical_unit(unit)]
