"""Hunt-and-scan after hunt-and-fill (Vamvatsikos & Cornell 2004, "Applied incremental
dynamic analysis"): the intensities at which one record is run, chosen from the outcomes
so far, to find the record's FIRST collapse intensity.

    trace = hunt_and_fill(collapses, start=0.3, options=HuntOptions())
    # collapses(im) -> (collapsed, peak); trace: [(im, collapsed, peak, phase), ...]

1. hunt: from `start`, steps that grow by a fixed amount
   (im_k+1 = im_k + start (step + k grow)) until the first collapse, or `stop`
   (then the record is censored: no collapse up to the last intensity run);
   if the very first run collapses, the intensity is halved until one does not;
2. scan: rocking is not monotonic in the intensity (a body may overturn at one
   intensity, stand at a higher one, and overturn again higher still), so the
   gaps (in log) between the runs below the lowest collapse found are halved,
   largest first, until none is wider than 1 + resolution; a scan run that
   overturns becomes the lowest collapse, and the scan goes on below it;
3. bracket: bisection (in log) between the highest non-collapse below the
   lowest collapse and that collapse, until hi / lo < 1 + tol.

`max_runs` caps the runs; `unresolved(trace, options)` says what the budget left
undone (the hunt short of `stop`, a gap wider than the resolution, a bracket
wider than tol). A collapse window narrower than the resolution can still be
missed: docs/fragility.md gives how often on the shipped suite.
"""

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class HuntOptions:
    """max_runs per record; hunt steps in units of `start`; tol the bracket's relative width;
    stop the highest intensity tried, in units of `start`; halvings at most when the first run
    collapses; resolution the widest relative gap left between runs below the first collapse."""

    max_runs: int = 60
    step: float = 1.0
    grow: float = 0.5
    tol: float = 0.05
    stop: float = 50.0
    halvings: int = 4
    resolution: float = 0.1


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
    """Run `collapses(im) -> (collapsed, peak)` at the intensities the search (hunt, scan, bracket) chooses;
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
        top = o.stop * start
        while len(trace) < o.max_runs and im < top * (1 - 1e-12):
            im = min(im + start * (o.step + k * o.grow), top)  # the last step lands on `stop`
            k += 1
            if run(im, "hunt"):
                break
    # 2. scan below the lowest collapse, 3. bracket it
    while len(trace) < o.max_runs:
        gap = widest_gap(trace)
        if gap and gap[0] >= 1 + o.resolution:
            run(math.sqrt(gap[1] * gap[2]), "scan")
            continue
        lo, hi = bracket(trace)
        if lo is not None and hi is not None and hi / lo >= 1 + o.tol:
            run(math.sqrt(lo * hi), "bracket")
            continue
        break
    return trace


def widest_gap(trace):
    """(ratio, a, b) of the widest gap (in log) between intensities run below the lowest
    collapse (all of them if none collapsed), None if fewer than two."""
    lo, hi = bracket(trace)
    ims = sorted({t[0] for t in trace if hi is None or t[0] < hi})
    if len(ims) < 2:
        return None
    return max((b / a, a, b) for a, b in zip(ims, ims[1:]))


def unresolved(trace, options):
    """What the run budget left undone, in words ('' if nothing): the hunt short of
    `stop` without a collapse, a gap below the first collapse wider than the
    resolution, or a bracket wider than tol. The trace's first run is the hunt's start."""
    o = options
    lo, hi = bracket(trace)
    top = max(t[0] for t in trace)
    why = []
    if hi is None and top < o.stop * trace[0][0] * (1 - 1e-9):
        why.append(f"no collapse up to {top:.4g}, short of the hunt's stop {o.stop * trace[0][0]:.4g}")
    elif hi is not None and lo is None:
        why.append(f"overturned at every intensity run, down to {hi:.4g}")
    gap = widest_gap(trace)
    if gap and gap[0] >= 1 + o.resolution:
        why.append(f"a gap of {100 * (gap[0] - 1):.0f} % unscanned below the collapse ({gap[1]:.4g} to {gap[2]:.4g})")
    if lo is not None and hi is not None and hi / lo >= 1 + o.tol:
        why.append(f"bracket {100 * (hi / lo - 1):.1f} % wide (tol {100 * o.tol:g} %)")
    return "; ".join(why)
