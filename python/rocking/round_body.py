"""RoundBody.fmu, a round body in space on a rigid, elastic or crushing bed (docs/model.md §10, §11,
docs/round-body.md),
extracted once and run through fmpy's FMU2Slave under both horizontal components and the vertical.

    from rocking import groundmotion as gm
    from rocking.round_body import RoundBodyFMU
    pair = gm.pair_of("data/ground-motions/geonet-darfield-2010/3366146_DFHS_HN_20.090")
    with RoundBodyFMU() as fmu:                     # target/fmu/RoundBody.fmu
        run = fmu.simulate({"Ro": 0.5, "H": 3.0}, pair=pair, scale=3.0, azimuth=30.0)
        run.overturned, run.peak_theta_over_alpha, run.impacts, run.result["psi"]

The pair is turned by `azimuth` (degrees from its x toward its y, `HorizontalPair.rotated`):
the FMU's agx is the component along the azimuth, agy the one 90 degrees counterclockwise of
it, av the pair's vertical (unless `vertical=False`). Each input is given at the communication
points with its slope (fmi2SetRealInputDerivatives): the FMU sees the records' linear
interpolation exactly. Overturning, or the vertical reaching -g (liftOff), ends the run as in
`RockingFMU.simulate`.
"""

import math
import time as _time
from ctypes import c_double, c_int, c_uint32
from dataclasses import dataclass, field

import numpy as np
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2Discard, fmi2LastSuccessfulTime, fmi2Terminated

from . import fmu as _fmu
from . import paths
from .fmu import FMUError, RockingFMU

#: Outputs recorded unless told otherwise.
DEFAULT_OUTPUTS = ("theta", "psi", "thetaOverAlpha", "ex", "ey", "omegaX", "omegaY", "omegaZ", "xG", "yG",
                   "Fx", "Fy", "Fz", "frictionDemand", "regime", "impacts", "overturned")
#: Calculated parameters, read once per run after initialization.
CALCULATED = ("mass", "weight", "R0", "alpha", "IO", "etaHousner", "thetaOv")


@dataclass
class SpaceRun:
    """One run in space.

    result                 structured array: 'time', 'agx', 'agy', 'av' and the recorded outputs
    overturned             the body overturned (the run ended there)
    t_end                  time of the last row
    t_overturn             t_end if overturned, else nan
    peak_theta_over_alpha  max theta / alpha over the recorded samples
    impacts                returns of the base to the bed at the end (on a flexible bed, the
                           applications of the restitution rule: RockingBlock's zeroCrossings)
    terminal               the FMU's message when the vertical input took the body off the bed
                           (liftOff), else None
    calculated             the calculated parameters
    wall                   wall time, s
    messages               what the FMU logged
    """

    result: np.ndarray
    overturned: bool
    t_end: float
    t_overturn: float
    peak_theta_over_alpha: float
    impacts: int
    calculated: dict
    wall: float
    messages: list = field(default_factory=list)
    terminal: str = None


class RoundBodyFMU(RockingFMU):
    """RoundBody.fmu extracted once; `simulate` runs one case in space."""

    REQUIRED = ("agx", "agy", "av", "theta", "psi", "thetaOverAlpha", "overturned", "impacts", "thetaOv")

    @classmethod
    def default_path(cls):
        return None if paths.REPO is None and paths.BUNDLE is None else paths.target_dir() / "fmu" / "RoundBody.fmu"

    def simulate(self, params, pair=None, scale=1.0, azimuth=0.0, vertical=True, stop_time=None,
                 output_interval=None, rtol=None, outputs=DEFAULT_OUTPUTS):
        """Run one case and return a `SpaceRun`.

        params           parameter values by name (docs/round-body.md); enumeration items by name
        pair             a groundmotion HorizontalPair (m/s²) or None (no ground motion)
        scale            factor on every component
        azimuth          degrees from the pair's x toward its y: agx is the component along it
        vertical         the pair's vertical as av (when it has one)
        stop_time        default: the pair's last sample (10 s without one); the ground is at
                         rest after it
        output_interval  s, > 0; default: the pair's dt (0.01 s without one)
        rtol             the integrator's relative tolerance (default: the FMU's)
        """
        t_start = _time.perf_counter()
        lines = {}
        if pair is not None:
            turned = pair.rotated(azimuth) if azimuth else pair
            t_in, dt = np.asarray(turned.time, float), float(turned.dt)
            lines = {"agx": turned.x.acc, "agy": turned.y.acc}
            if vertical and turned.vertical is not None:
                lines["av"] = turned.vertical.acc
        else:
            t_in, dt = None, None
        if stop_time is None:
            stop_time = float(t_in[-1]) if t_in is not None else 10.0
        if output_interval is None:
            output_interval = dt if dt is not None else 0.01
        _fmu.check_times(stop_time, output_interval)
        grid, every, rows = _fmu.communication_grid(stop_time, dt if dt is not None else output_interval,
                                                    output_interval)
        inputs = {name: _fmu._input_line(grid, t_in, np.asarray(acc, float), scale)
                  for name, acc in lines.items()}
        for name in ("agx", "agy", "av"):
            inputs.setdefault(name, _fmu._input_line(grid, None, None, scale))
        names = ("agx", "agy", "av")
        vr_in = (c_uint32 * 3)(*[self.variables[n].valueReference for n in names])
        values = np.stack([inputs[n][0] for n in names], axis=1)
        slopes = np.stack([inputs[n][1] for n in names], axis=1)

        reals = [o for o in outputs if self.variables[o].type == "Real"]
        if "thetaOverAlpha" not in reals:
            reals.append("thetaOverAlpha")
        ints = [o for o in outputs if self.variables[o].type in ("Integer", "Enumeration")]
        bools = [o for o in outputs if self.variables[o].type == "Boolean"]
        calc = [c for c in CALCULATED if c in self.variables]
        start_values = self.start_values(params)
        slave = self._library()
        _fmu._MESSAGES.clear()
        component = None
        try:
            slave.instantiate(callbacks=self._callbacks)
            component = slave.component
            slave.setupExperiment(tolerance=rtol, startTime=0.0, stopTime=stop_time)
            self._set(slave, start_values)
            slave.enterInitializationMode()
            slave.fmi2SetReal(component, vr_in, 3, (c_double * 3)(*values[0]))
            slave.exitInitializationMode()
            calculated = {n: _fmu._infinite(x) for n, x in
                          zip(calc, slave.getReal([self.variables[n].valueReference for n in calc]))}
            times, rows_r, rows_i, rows_b, ended = self._loop(slave, component, grid, values, slopes, vr_in,
                                                              reals, ints, bools, every)
            impacts = slave.getInteger([self.variables["impacts"].valueReference])[0]
            overturned_flag = slave.getBoolean([self.variables["overturned"].valueReference])[0]
            slave.terminate()
        except Exception as exc:  # noqa: BLE001 - FMICallException and instantiation errors
            if isinstance(exc, FMUError):
                raise
            raise FMUError.from_log(exc, _fmu._MESSAGES) from exc
        finally:
            if component is not None:
                slave.fmi2FreeInstance(component)
                slave.component = None

        dtype = ([("time", float), ("agx", float), ("agy", float), ("av", float)] + [(n, float) for n in reals]
                 + [(n, np.int64) for n in ints] + [(n, bool) for n in bools])
        result = np.empty(len(times), dtype=dtype)
        result["time"] = times
        for j, name in enumerate(names):
            result[name] = np.interp(times, grid, values[:, j])
        for j, n in enumerate(reals):
            result[n] = rows_r[:, j]
        for j, n in enumerate(ints):
            result[n] = rows_i[:, j]
        for j, n in enumerate(bools):
            result[n] = rows_b[:, j]
        terminal = None if overturned_flag else _fmu.terminal_message(_fmu._MESSAGES) if ended else None
        overturned = bool(overturned_flag)
        if rows is not None:
            result = result[_fmu.output_rows(result["time"], rows)]
        keep = ["time", "agx", "agy", "av"] + [o for o in outputs if o not in names]
        t_end = float(result["time"][-1])
        return SpaceRun(result=result[keep], overturned=overturned, t_end=t_end,
                        t_overturn=t_end if overturned else math.nan,
                        peak_theta_over_alpha=float(np.max(np.abs(result["thetaOverAlpha"]))),
                        impacts=int(impacts), calculated=calculated, wall=_time.perf_counter() - t_start,
                        messages=list(_fmu._MESSAGES), terminal=terminal)

    def _loop(self, slave, component, grid, values, slopes, vr_in, reals, ints, bools, every):
        """The stepping loop: the three inputs and their slopes at each communication point,
        rows every `every` steps, the last, and at fmi2LastSuccessfulTime when the FMU ended
        the run (overturning, liftOff). Returns (times, reals, ints, bools, ended)."""
        raw = slave._functions
        set_real, set_der, do_step = raw["fmi2SetReal"], raw["fmi2SetRealInputDerivatives"], raw["fmi2DoStep"]
        order = (c_int * 3)(1, 1, 1)
        val = (c_double * 3)()
        vr = {kind: [self.variables[n].valueReference for n in names]
              for kind, names in (("r", reals), ("i", ints), ("b", bools))}
        out_t, out_r, out_i, out_b = [], [], [], []

        def sample(t):
            out_t.append(t)
            out_r.append(slave.getReal(vr["r"]))
            out_i.append(slave.getInteger(vr["i"]) if vr["i"] else [])
            out_b.append(slave.getBoolean(vr["b"]) if vr["b"] else [])

        sample(grid[0])
        ended = False
        n_steps = len(grid) - 1
        for k in range(n_steps):
            val[:] = values[k]
            status = set_real(component, vr_in, 3, val)
            val[:] = slopes[k]
            status = max(status, set_der(component, vr_in, 3, order, val))
            if status > 1:
                raise FMICallException("fmi2SetReal/fmi2SetRealInputDerivatives", status)
            status = do_step(component, grid[k], grid[k + 1] - grid[k], 1)
            if status > 1:
                if status == fmi2Discard and slave.getBooleanStatus(fmi2Terminated):
                    sample(slave.getRealStatus(fmi2LastSuccessfulTime))
                    ended = True
                    break
                raise FMICallException("fmi2DoStep", status)
            if (k + 1) % every == 0 or k + 1 == n_steps:
                sample(grid[k + 1])
        shape = lambda rows, n: np.asarray(rows, dtype=float).reshape(len(out_t), n)  # noqa: E731
        return (np.asarray(out_t), shape(out_r, len(reals)), shape(out_i, len(ints)).astype(np.int64),
                shape(out_b, len(bools)).astype(bool), ended)
