"""Hunt-and-fill (Vamvatsikos & Cornell 2004, "Applied incremental dynamic analysis"):
the intensities at which one record is run, chosen from the outcomes so far.

    trace = hunt_and_fill(collapses, start=0.3, options=HuntOptions())
    # collapses(im) -> (collapsed, peak); trace: [(im, collapsed, peak, phase), ...]

1. hunt: from `start`, steps that grow by a fixed amount
   (im_k+1 = im_k + start (step + k grow)) until the first collapse, or `stop`
   (then the record is censored: no collapse up to the last intensity run);
   if the very first run collapses, the intensity is halved until one does not;
2. bracket: bisection (in log) between the highest non-collapse below the
   lowest collapse and that collapse, until hi / lo < 1 + tol;
3. fill: the runs left of the budget go in the largest gaps (in log) below the
   bracket, for the shape of the IDA curve; a fill run that overturns makes a new,
   lower bracket, which is narrowed first.

A rocking body may overturn at one intensity and stand at a higher one; the
bracket is always the first collapse found from below (the "first flatline").
"""

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class HuntOptions:
    """max_runs per record; hunt steps in units of `start`; tol the bracket's relative width;
    stop the highest intensity tried, in units of `start`; halvings at most when the first run collapses."""

    max_runs: int = 12
    step: float = 1.0
    grow: float = 0.5
    tol: float = 0.05
    stop: float = 50.0
    halvings: int = 4


def bracket(trace):
    """(lo, hi) of a trace: hi the lowest intensity that collapsed (None if none did), lo the
    highest that did not below hi (None if none)."""
    fails = [im for im, collapsed, *_ in trace if collapsed]
    hi = min(fails) if fails else None
    below = [im for im, collapsed, *_ in trace if not collapsed and (hi is None or im < hi)]
    return (max(below) if below else None), hi


def capacity(trace):
    """(collapse intensity, censored) of a trace: the geometric mean of the bracket; the lowest
    collapse if no run below it stood; the highest intensity run, censored, if none collapsed."""
    lo, hi = bracket(trace)
    if hi is None:
        return max(im for im, *_ in trace), True
    return (hi if lo is None else math.sqrt(lo * hi)), False


def hunt_and_fill(collapses, start, options=HuntOptions()):
    """Run `collapses(im) -> (collapsed, peak)` at the intensities hunt-and-fill chooses;
    return the trace [(im, collapsed, peak, phase)] in the order run."""
    if not start > 0:
        raise ValueError(f"hunt start must be positive, got {start}")
    o = options
    trace = []

    def run(im, phase):
        collapsed, peak = collapses(im)
        trace.append((im, bool(collapsed), peak, phase))
        return collapsed

    # 1. hunt
    im, k = start, 0
    if run(im, "hunt"):
        for _ in range(o.halvings):
            if len(trace) >= o.max_runs:
                break
            im /= 2
            if not run(im, "hunt"):
                break
    else:
        while len(trace) < o.max_runs:
            im = im + start * (o.step + k * o.grow)
            k += 1
            if im > o.stop * start * (1 + 1e-12):
                break
            if run(im, "hunt"):
                break
    # 2. bracket, 3. fill: the bracket first, also when a fill run collapsed below it
    while len(trace) < o.max_runs:
        lo, hi = bracket(trace)
        if lo is not None and hi is not None and hi / lo >= 1 + o.tol:
            run(math.sqrt(lo * hi), "bracket")
            continue
        top = lo if hi is not None else None
        ims = sorted({t[0] for t in trace if top is None or t[0] <= top})
        if len(ims) < 2:
            break
        ratio, a, b = max((b / a, a, b) for a, b in zip(ims, ims[1:]))
        if ratio < 1 + o.tol:
            break
        run(math.sqrt(a * b), "fill")
    return trace
