"""Summaries as strict JSON: NaN and infinities become null (JSON has neither, and
`json.dumps` would write the non-standard `NaN` that strict readers refuse), numpy
scalars and arrays plain numbers and lists."""

import json
import math
from pathlib import Path

import numpy as np


def plain(obj):
    """`obj` with every non-finite float replaced by None and numpy values by Python ones."""
    if isinstance(obj, dict):
        return {k: plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple, np.ndarray)):
        return [plain(v) for v in obj]
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def dumps(obj):
    """Strict JSON text of `obj`, indented, with a final newline."""
    return json.dumps(plain(obj), indent=2, allow_nan=False) + "\n"


def write(path, obj):
    """Writes `obj` to `path` as strict JSON."""
    Path(path).write_text(dumps(obj))
