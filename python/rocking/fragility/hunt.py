"""Hunt-and-scan after hunt-and-fill (Vamvatsikos & Cornell 2004, "Applied incremental
dynamic analysis"): the intensities at which one record is run, chosen from the outcomes
so far, to find the record's FIRST collapse intensity, and the first intensity at which
each damage state (a threshold on the peak |theta| / alpha) is reached.

    trace = hunt_and_fill(collapses, start=0.3, options=HuntOptions(), states={"DS1": 0.2})
    # collapses(im) -> (collapsed, peak); trace: [(im, collapsed, peak, phase), ...]

A run reaches a damage state when it overturns or its peak reaches the threshold, so the
states are nested: a run that reaches one reaches every lower one, and each state's first
intensity lies at or below overturning's.

1. hunt: from `start`, steps that grow by a fixed amount
   (im_k+1 = im_k + start (step + k grow)) until the first collapse, or `stop`
   (then the record is censored: no collapse up to the last intensity run);
   then, while the lowest run reached a state (overturned, or reached the lowest damage
   state), the intensity is halved below it, down to the floor start / 2^halvings;
2. scan: rocking is not monotonic in the intensity (a body may overturn at one
   intensity, stand at a higher one, and overturn again higher still), so the
   gaps (in log) between the runs below the lowest collapse found are halved,
   largest first, until none is wider than 1 + resolution; a scan run that
   overturns becomes the lowest collapse, and the scan goes on below it (the
   damage states' first intensities lie below it, so the scan covers them too);
3. bracket: for overturning, then each damage state, bisection (in log) between the
   highest run that did not reach it below the lowest that did and that run, until
   hi / lo < 1 + tol.

`capacity` gives a state's capacity from a trace: the bracket's geometric mean; censored
from above when no run reached it; from below (only an upper bound) when the lowest run
reached it. `interpolated` gives instead the intensity at which the IDA curve (peak
against intensity, linear between the runs) first reaches a damage state's threshold
(Vamvatsikos & Cornell 2002). `max_runs` caps the runs; `unresolved(trace, options, states)`
says what the budget left undone (the hunt short of `stop`, a state reached at every run
above the floor, a gap wider than the resolution, a bracket wider than tol). A collapse
window narrower than the resolution can still be missed: docs/fragility.md gives how often
on the shipped suite.
"""

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class HuntOptions:
    """max_runs per record; hunt steps in units of `start`; tol the bracket's relative width;
    stop the highest intensity tried, in units of `start`; halvings: the floor, the lowest
    intensity tried, is start / 2^halvings; resolution the widest relative gap left between
    runs below the first collapse."""

    max_runs: int = 80
    step: float = 1.0
    grow: float = 0.5
    tol: float = 0.05
    stop: float = 50.0
    halvings: int = 4
    resolution: float = 0.1


def reached(run, threshold):
    """Whether a trace entry (im, collapsed, peak, ...) reached a state: overturning
    (threshold None) or a peak |theta| / alpha of at least `threshold` (or overturned)."""
    return bool(run[1]) or (threshold is not None and run[2] >= threshold)


def _states(states):
    """[(name, threshold)] of the states searched: overturning first, then the damage states
    from the highest threshold down."""
    return [("overturning", None)] + sorted((states or {}).items(), key=lambda kv: -kv[1])


def bracket(trace, threshold=None):
    """(lo, hi) of a trace for a state: hi the lowest intensity that reached it (None if none
    did), lo the highest that did not below hi (None if none)."""
    hits = [t[0] for t in trace if reached(t, threshold)]
    hi = min(hits) if hits else None
    below = [t[0] for t in trace if not reached(t, threshold) and (hi is None or t[0] < hi)]
    return (max(below) if below else None), hi


def capacity(trace, threshold=None):
    """(capacity, censored, below) of a trace for a state (trace entries (im, collapsed,
    peak, ...); threshold None: overturning): the geometric mean of the bracket; the highest
    intensity run, censored (from above), if no run reached it; the lowest run that reached
    it, `below` (an upper bound: censored from below), if no run below it stood."""
    lo, hi = bracket(trace, threshold)
    if hi is None:
        return max(t[0] for t in trace), True, False
    if lo is None:
        return hi, False, True
    return math.sqrt(lo * hi), False, False


def interpolated(trace, threshold):
    """(capacity, censored, below) of a damage state by the IDA curve (Vamvatsikos & Cornell
    2002): the runs sorted by intensity, peak |theta| / alpha linear in the intensity between
    neighbours, the capacity where it first reaches `threshold` (an overturned run counts at
    least the threshold). Censored as `capacity` is when no run, or the lowest, reaches it."""
    runs = sorted(trace, key=lambda t: t[0])
    for k, t in enumerate(runs):
        if reached(t, threshold):
            if k == 0:
                return t[0], False, True
            a = runs[k - 1]
            pa, pb = a[2], max(t[2], threshold) if t[1] else t[2]
            if not (math.isfinite(pa) and math.isfinite(pb) and pb > pa):
                return math.sqrt(a[0] * t[0]), False, False
            return a[0] + (threshold - pa) / (pb - pa) * (t[0] - a[0]), False, False
    return runs[-1][0], True, False


def hunt_and_fill(collapses, start, options=HuntOptions(), states=None):
    """Run `collapses(im) -> (collapsed, peak)` at the intensities the search (hunt, scan,
    bracket) chooses for overturning and the damage `states` {name: threshold on peak
    |theta| / alpha}; return the trace [(im, collapsed, peak, phase)] in the order run."""
    if not start > 0:
        raise ValueError(f"hunt start must be positive, got {start}")
    o = options
    order = _states(states)
    lowest = order[-1][1]  # the lowest threshold (None: overturning only): reached first
    floor = start / 2 ** o.halvings
    trace = []

    def run(im, phase):
        collapsed, peak = collapses(im)
        trace.append((im, bool(collapsed), peak, phase))
        return collapsed

    # 1. hunt up for overturning, then down while the lowest run reaches a state
    im, k = start, 0
    if not run(im, "hunt"):
        top = o.stop * start
        while len(trace) < o.max_runs and im < top * (1 - 1e-12):
            im = min(im + start * (o.step + k * o.grow), top)  # the last step lands on `stop`
            k += 1
            if run(im, "hunt"):
                break
    while len(trace) < o.max_runs:
        first = min(trace, key=lambda t: t[0])
        if not (reached(first, lowest) and first[0] > floor * (1 + 1e-12)):
            break
        run(max(first[0] / 2, floor), "hunt")
    # 2. scan below the lowest collapse, 3. bracket each state
    while len(trace) < o.max_runs:
        gap = widest_gap(trace)
        if gap and gap[0] >= 1 + o.resolution:
            run(math.sqrt(gap[1] * gap[2]), "scan")
            continue
        for _, thr in order:
            lo, hi = bracket(trace, thr)
            if lo is not None and hi is not None and hi / lo >= 1 + o.tol:
                run(math.sqrt(lo * hi), "bracket")
                break
        else:
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


def unresolved(trace, options, states=None):
    """What the run budget left undone, in words ('' if nothing): the hunt short of
    `stop` without a collapse, a state reached at every run down to one above the floor,
    a gap below the first collapse wider than the resolution, or a state's bracket wider than
    tol (damage states named). The trace's first run is the hunt's start."""
    o = options
    start = trace[0][0]
    floor = start / 2 ** o.halvings
    why = []
    _, hi = bracket(trace)
    top = max(t[0] for t in trace)
    if hi is None and top < o.stop * start * (1 - 1e-9):
        why.append(f"no collapse up to {top:.4g}, short of the hunt's stop {o.stop * start:.4g}")
    gap = widest_gap(trace)
    if gap and gap[0] >= 1 + o.resolution:
        why.append(f"a gap of {100 * (gap[0] - 1):.0f} % unscanned below the collapse ({gap[1]:.4g} to {gap[2]:.4g})")
    for name, thr in _states(states):
        lo, hi = bracket(trace, thr)
        label = "" if thr is None else f"{name}: "
        verb = "overturned" if thr is None else "reached"
        if hi is not None and lo is None and hi > floor * (1 + 1e-9):
            why.append(f"{label}{verb} at every intensity run, down to {hi:.4g} (floor {floor:.4g})")
        if lo is not None and hi is not None and hi / lo >= 1 + o.tol:
            why.append(f"{label}bracket {100 * (hi / lo - 1):.1f} % wide (tol {100 * o.tol:g} %)")
    return "; ".join(why)
