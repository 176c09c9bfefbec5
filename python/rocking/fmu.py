"""One RockingBlock.fmu, extracted once, run through fmpy's FMU2Slave.

    from rocking import RockingFMU
    with RockingFMU() as fmu:                       # target/fmu/RockingBlock.fmu
        run = fmu.simulate({"shape": "solidRectangle", "B": 0.5, "theta": 0.1},
                           stop_time=5.0)
        run.overturned, run.t_overturn, run.peak_theta_over_alpha, run.impacts

Enumeration parameters (shape, massModel, interface, formulation, restitution)
may be given by item name ("hollowCircle") or by value; names are converted
with the FMU's own modelDescription.xml. The start values of `theta` and
`omega` are the initial conditions (docs/model.md §5).

The ground acceleration is passed as the record's samples at the
communication points together with its slope (fmi2SetRealInputDerivatives,
the FMU declares canInterpolateInputs): the FMU sees the record's piecewise
linear interpolation exactly. The loop is written here rather than with
`fmpy.simulate_fmu(..., set_input_derivatives=True)`, which fails in fmpy
0.3.32 for an FMI 2 FMU with one real input ("Can only assign sequence of same
size": its derivative buffer has a fixed length of 9), and which, with that
buffer sized, passes at most samples the slope of the segment that ends there
(docs/examples.md, "Input derivatives and fmpy"). Overturning: the FMU
returns fmi2Discard with fmi2Terminated true; the run ends at
fmi2LastSuccessfulTime, whose outputs are the last row.

The loop runs in native code (`rocking.stepper`, the fmu-stepper crate that
`cargo xtask fmu` builds) where built, else in Python (`loop="python"`, the
reference it is tested against bit for bit); docs/performance.md has the costs.
"""

import math
import re
import shutil
import time as _time
from ctypes import c_double, c_int, c_uint32
from dataclasses import dataclass, field
from pathlib import Path

import fmpy
import numpy as np
from numpy.lib.recfunctions import repack_fields
from fmpy.fmi1 import FMICallException, calloc, free
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, fmi2Discard,
                       fmi2LastSuccessfulTime, fmi2Terminated)

from . import paths, stepper

#: Where `cargo xtask fmu` writes the FMU (None when the package is not in the repository).
DEFAULT_FMU = paths.default_fmu() if paths.REPO is not None else None

#: Outputs recorded by `simulate` unless told otherwise.
DEFAULT_OUTPUTS = ("theta", "omega", "thetaOverAlpha", "MR", "af", "regime", "impacts", "overturned")
#: Calculated parameters (docs/model.md §5), read once per run after initialization.
CALCULATED = ("mass", "weight", "R0", "alpha", "IO", "etaHousner", "thetaJo", "thetaC", "thetaOv")

#: What the FMU reports for +inf (docs/model.md §5, "Values that stand for infinity").
UNBOUNDED = 1e60


def _infinite(x):
    """A calculated parameter as Python's tables keep it: the FMU's stand-in for +inf
    (`thetaC` of a law that never crushes) back to inf."""
    return math.inf if x >= UNBOUNDED else x


_STATUS = ["OK", "WARNING", "DISCARD", "ERROR", "FATAL", "PENDING"]


# The FMU's logger, one for the process and alive as long as it: the messages of
# the run in progress go to _MESSAGES (runs in one process are sequential).
# fmpy's C proxy (fmpy.logging.addLoggerProxy), which would format the variadic
# arguments, is not used: it keeps the last Python logger in one process-wide
# variable, so a second RockingFMU would take the first one's messages and a
# garbage-collected logger would leave it dangling for every other fmpy user.
# The FMU formats its messages itself; '%%' (FMI's escaped percent) is undone.
_MESSAGES = []


def _log(_component, _instance, status, category, message):
    label = _STATUS[status] if 0 <= status < len(_STATUS) else str(status)
    text = (message or b"").decode(errors="replace").replace("%%", "%")
    _MESSAGES.append(f"[{label}] {(category or b'').decode(errors='replace')}: {text}")


_CALLBACKS = fmi2CallbackFunctions()
_CALLBACKS.logger = fmi2CallbackLoggerTYPE(_log)
_CALLBACKS.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
_CALLBACKS.freeMemory = fmi2CallbackFreeMemoryTYPE(free)


def did_you_mean(name, names):
    """"; did you mean A, B?" with the `names` close to `name` (or differing in case), or ""."""
    import difflib
    close = difflib.get_close_matches(name, names, n=3, cutoff=0.5)
    close += [n for n in names if n.lower() == name.lower() and n not in close]
    return f"; did you mean {', '.join(close)}?" if close else ""


def enumeration_value(name, value, enumerations):
    """`value` of the variable `name`, an enumeration item's name replaced by its value
    (`enumerations`: variable name -> {item name: value})."""
    if name in enumerations and isinstance(value, str):
        items = enumerations[name]
        if value not in items:
            raise ValueError(f"{name} = {value!r}: not one of {sorted(items)}")
        return items[value]
    return value


def check_times(stop_time, output_interval):
    """ValueError naming the argument unless stop_time >= 0 and output_interval > 0 (finite, s)."""
    if not (math.isfinite(stop_time) and stop_time >= 0):
        raise ValueError(f"stop_time = {stop_time:g}: must be a time >= 0 s")
    if not (math.isfinite(output_interval) and output_interval > 0):
        raise ValueError(f"output_interval = {output_interval:g}: must be a time > 0 s")


def communication_grid(stop_time, h, output_interval):
    """(communication points from 0 to stop_time, every how many steps a row is sampled,
    the output times when they are not every `every`-th point, else None). h: the record's
    dt (the FMU sees its linear interpolation exactly when the points include its samples)."""
    ratio = output_interval / h
    n_steps = int(math.ceil(stop_time / h - 1e-9))
    grid = np.arange(n_steps + 1) * h
    if n_steps and grid[-1] > stop_time:
        grid[-1] = stop_time
    if abs(ratio - round(ratio)) <= 1e-9 * ratio and round(ratio) >= 1:
        return grid, int(round(ratio)), None
    outputs = np.arange(int(math.floor(stop_time / output_interval + 1e-9)) + 1) * output_interval
    merged = np.unique(np.concatenate((grid, outputs[outputs <= stop_time])))
    close = np.diff(merged) <= 1e-9 * min(h, output_interval)  # one point where two coincide
    return merged[np.concatenate(([True], ~close))], 1, outputs


def output_rows(times, outputs):
    """Mask of the sampled `times` that are output times (to 1e-9 s), the first and the last."""
    k = np.clip(np.searchsorted(outputs, times), 0, len(outputs) - 1)
    nearest = np.minimum(np.abs(times - outputs[k]), np.abs(times - outputs[np.maximum(k - 1, 0)]))
    keep = nearest <= 1e-9
    keep[0] = keep[-1] = True
    return keep


def _input_line(grid, t_in, a_in, scale):
    """(values, slopes) on `grid` of `scale` x the record (t_in, a_in), zero after its end
    (the ground at rest) and everywhere without one; slopes of the linear interpolation."""
    if t_in is not None:
        acc = scale * np.interp(grid, t_in, a_in, right=0.0)
    else:
        acc = np.zeros(len(grid))
    slope = np.zeros(len(grid))
    if len(grid) > 1:
        slope[:-1] = np.diff(acc) / np.diff(grid)
    return acc, slope


def _set_input(set_real, set_der, component, line, k):
    """Set input `line` = (value reference, values, slopes) at grid index k; the worse status."""
    vr, val, order = (c_uint32 * 1)(line[0]), (c_double * 1)(line[1][k]), (c_int * 1)(1)
    status = set_real(component, vr, 1, val)
    val[0] = line[2][k]
    return max(status, set_der(component, vr, 1, order, val))


#: The FMU's names of the out-of-range conditions that end a run under av (regime 5).
TERMINAL_CONDITIONS = ("liftOff", "baseCrushing", "restUnstable")


def terminal_message(messages):
    """The FMU's message about the out-of-range condition that ended a run, or None."""
    for message in reversed(messages):
        if any(c in message for c in TERMINAL_CONDITIONS) and " av = " in message:
            text = message.split(": ", 1)[-1] if message.startswith("[") else message
            return re.sub(r"^fmi2\w+: ", "", text)
    return None


class FMUError(RuntimeError):
    """An FMI call failed; the message leads with what the FMU logged, e.g. "kn = -1000000000:
    must be finite and > 0 (the FMU refused it in fmi2ExitInitializationMode)".

    parameter, value, condition  the variable the FMU names, its value as the FMU printed
                                 it, and what it must be (None when the message names none)
    call                         the FMI function that failed
    log                          everything the FMU logged during the call
    """

    parameter = value = condition = call = None
    log = ()

    @classmethod
    def from_log(cls, exc, messages):
        """The error of a failed FMI call `exc`, from the FMU's `messages` ("[STATUS] category: text")."""
        errors = [m for m in messages if m.startswith(("[ERROR]", "[FATAL]"))] or list(messages)
        if not errors:
            return cls(f"{exc} (no message logged)")
        text = errors[-1].split(": ", 1)[-1]  # without "[ERROR] logStatusError"
        call = re.match(r"(fmi2\w+): ", text)
        if call:
            text = text[call.end():]
        text = re.sub(r"^invalid parameters?: ", "", text)
        where = call.group(1) if call else str(exc).split(" ", 1)[0]
        refused = re.fullmatch(r"([A-Za-z_]\w*) = (\S+): (.+)", text)
        if refused:
            error = cls(f"{text} (the FMU refused it in {where})")
            error.parameter, error.value, error.condition = refused.groups()
        else:
            error = cls(f"{text} (the FMU, in {where})")
        error.call, error.log = where, tuple(messages)
        return error

    def with_value(self, typed):
        """The same error with the parameter's value as the user wrote it (`typed`)."""
        error = type(self)(f"{self.parameter} = {typed}: {self.condition} (the FMU refused it in {self.call})")
        error.parameter, error.value, error.condition = self.parameter, typed, self.condition
        error.call, error.log = self.call, self.log
        return error


@dataclass
class Run:
    """The result of one simulation.

    result                 structured array: 'time' and the recorded outputs
    overturned             the body overturned (the FMU discarded the step and
                           ended the run: docs/model.md §5)
    t_end                  time of the last row (the overturning time if overturned)
    t_overturn             t_end if overturned, else nan
    peak_theta_over_alpha  max |theta| / alpha over the recorded samples
    impacts                impacts at the end of the run (returns to theta = 0
                           after the joint opened)
    zero_crossings         zero crossings of theta at the end of the run (every
                           crossing, also in full contact)
    terminal               when the vertical input took the body out of the model's range
                           (regime 5: liftOff, baseCrushing, restUnstable; docs/model.md §6.5):
                           the FMU's message ("liftOff at t = ...: av = ..."), else None; the
                           run ends there and is not an overturning
    calculated             the calculated parameters (alpha, thetaOv, ...)
    wall                   wall time of the run, s
    messages               what the FMU logged ("[STATUS] category: message")
    """

    result: np.ndarray
    overturned: bool
    t_end: float
    t_overturn: float
    peak_theta_over_alpha: float
    impacts: int
    zero_crossings: int
    calculated: dict
    wall: float
    messages: list = field(default_factory=list)
    terminal: str = None


class RockingFMU:
    """RockingBlock.fmu extracted once; `simulate` runs one case.

    path      the .fmu (default target/fmu/RockingBlock.fmu)
    unzipdir  an existing extraction to use instead (not deleted by `close`);
              this is how worker processes share one extraction
    """

    #: Variables this class drives and reads: an FMU without them is refused.
    REQUIRED = ("ag", "theta", "thetaOverAlpha", "overturned", "impacts", "thetaOv")

    @classmethod
    def default_path(cls):
        """The FMU `cargo xtask fmu` writes (None when the package is not in the repository)."""
        return DEFAULT_FMU

    def __init__(self, path=None, unzipdir=None):
        if unzipdir is not None:
            self.unzipdir = Path(unzipdir)
            self.path = Path(path) if path else None
            self._owned = False
        else:
            self.path = Path(path) if path else self.default_path()
            if self.path is None:
                raise FileNotFoundError("no FMU given and " + paths._NOT_IN_REPO)
            if not self.path.is_file():
                raise FileNotFoundError(
                    f"{self.path} does not exist: build it with `cargo xtask fmu` (or tools/main.sh)")
            self.unzipdir = Path(fmpy.extract(str(self.path)))
            self._owned = True
        md = self.model_description = fmpy.read_model_description(str(self.unzipdir))
        self.variables = {v.name: v for v in md.modelVariables}
        self.enumerations = {}
        for v in md.modelVariables:
            if v.type == "Enumeration" and v.declaredType is not None:
                self.enumerations[v.name] = {it.name: int(it.value) for it in v.declaredType.items}
        missing = [n for n in self.REQUIRED if n not in self.variables]
        if missing:
            raise FMUError(f"{self.path or self.unzipdir}: variables missing from modelDescription.xml: {missing}")
        self._slave = None

    # context manager: delete the extraction we made
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self._slave is not None:
            try:
                self._slave.freeLibrary()
            except Exception:  # noqa: BLE001
                pass
            self._slave = None
        if self._owned and self.unzipdir.exists():
            shutil.rmtree(self.unzipdir, ignore_errors=True)

    def __getstate__(self):
        raise TypeError(f"{type(self).__name__} is not picklable: pass its unzipdir to the worker processes")

    def start_values(self, params):
        """`params` with enumeration item names replaced by their values; unknown names raise."""
        out = {}
        for name, value in params.items():
            if name not in self.variables:
                raise KeyError(f"{name!r} is not a variable of the FMU{self._close_names(name)}")
            value = enumeration_value(name, value, self.enumerations)
            if isinstance(value, (np.floating, np.integer)):
                value = value.item()
            out[name] = value
        return out

    def _close_names(self, name):
        names = [n for n, v in self.variables.items()
                 if v.causality == "parameter" or (v.causality == "output" and v.initial == "exact")]
        return did_you_mean(name, names)

    # -- the library, loaded once per process --------------------------------
    def _library(self):
        if self._slave is None:
            md = self.model_description
            slave = FMU2Slave(guid=md.guid, unzipDirectory=str(self.unzipdir),
                              modelIdentifier=md.coSimulation.modelIdentifier,
                              instanceName=md.modelName)
            self._callbacks = _CALLBACKS
            self._slave = slave
        return self._slave

    def _set(self, slave, values):
        for name, value in values.items():
            v = self.variables[name]
            vr = (c_uint32 * 1)(v.valueReference)
            if v.type == "Real":
                slave.fmi2SetReal(slave.component, vr, 1, (c_double * 1)(float(value)))
            elif v.type in ("Integer", "Enumeration"):
                slave.fmi2SetInteger(slave.component, vr, 1, (c_int * 1)(int(value)))
            elif v.type == "Boolean":
                slave.fmi2SetBoolean(slave.component, vr, 1, (c_int * 1)(int(bool(value))))
            else:
                raise TypeError(f"{name}: cannot set a {v.type}")

    def simulate(self, params, record=None, scale=1.0, stop_time=None, output_interval=None,
                 rtol=None, outputs=DEFAULT_OUTPUTS, ag=None, loop="auto", vertical=None, av=None):
        """Run one case and return a `Run`.

        params           parameter and start values by name (docs/model.md §5)
        record           a groundmotion Record (acc in m/s²) or None (no ground motion)
        scale            factor applied to the record's acceleration
        ag               instead of `record`: (time, acc) arrays in s and m/s², equally spaced
        vertical         a groundmotion Record of the vertical ground acceleration (m/s², up),
                         the FMU's input `av`, scaled by the same `scale`; zero after its end;
                         default: `record.av_record` (None: av = 0)
        av               instead of `vertical`: (time, acc) arrays in s and m/s²
        stop_time        default: the record's last sample (10 s without a record);
                         after the record ends the ground is at rest
        output_interval  s, > 0; default: the record's dt (0.01 s without one). Rows at 0,
                         interval, 2 interval, ... and at the end (and at overturning).
                         The communication points are the record's samples (the output
                         interval without a record) and, when the interval is not a
                         multiple of the record's dt, the output times too: the FMU
                         still sees the record's linear interpolation exactly
        rtol             the integrator's relative tolerance (default: the FMU's)
        loop             "native": the stepping loop of fmu-stepper (rocking.stepper), "python":
                         the loop in Python (the reference), "auto" (default): native when built
        """
        t_start = _time.perf_counter()
        if record is not None:
            t_in, a_in, dt = np.asarray(record.time, float), np.asarray(record.acc, float), float(record.dt)
        elif ag is not None:
            t_in, a_in = (np.asarray(x, dtype=float) for x in ag)
            dt = float(t_in[1] - t_in[0])
        else:
            t_in = a_in = None
            dt = None
        if vertical is None and av is None and record is not None:
            vertical = record.av_record  # the record's own vertical companion, if it carries one
        if vertical is not None:
            av = (vertical.time, vertical.acc)
        if av is not None and t_in is None:  # av alone: its samples set the steps and the end
            av = tuple(np.asarray(x, dtype=float) for x in av)
            dt = float(av[0][1] - av[0][0])
            if stop_time is None:
                stop_time = float(av[0][-1])
        if stop_time is None:
            stop_time = float(t_in[-1]) if t_in is not None else 10.0
        if output_interval is None:
            output_interval = dt if dt is not None else 0.01
        check_times(stop_time, output_interval)
        grid, every, rows = communication_grid(stop_time, dt if dt is not None else output_interval,
                                               output_interval)
        acc, slope = _input_line(grid, t_in, a_in, scale)
        vertical_input = None
        if av is not None:
            v_acc, v_slope = _input_line(grid, *(np.asarray(x, dtype=float) for x in av), scale)
            vertical_input = (self.variables["av"].valueReference, v_acc, v_slope)

        reals = [o for o in outputs if self.variables[o].type == "Real"]
        ints = [o for o in outputs if self.variables[o].type in ("Integer", "Enumeration")]
        bools = [o for o in outputs if self.variables[o].type == "Boolean"]
        if "thetaOverAlpha" not in reals:  # for the peak
            reals.append("thetaOverAlpha")
        calc = [c for c in CALCULATED if c in self.variables]
        vr_r = [self.variables[n].valueReference for n in reals]
        vr_i = [self.variables[n].valueReference for n in ints]
        vr_b = [self.variables[n].valueReference for n in bools]
        vr_ag = (c_uint32 * 1)(self.variables["ag"].valueReference)
        val = (c_double * 1)()
        if loop not in ("auto", "native", "python"):
            raise ValueError(f"loop = {loop!r}: not one of 'auto', 'native', 'python'")
        native = loop == "native" or (loop == "auto" and stepper.library() is not None)
        if native and stepper.library() is None:
            raise FileNotFoundError(f"loop='native': {stepper.library_path()} not built "
                                    "(cargo build --release -p fmu-stepper, or cargo xtask fmu)")
        inputs = (acc, slope) if t_in is not None or vertical_input is not None else (None, None)

        start_values = self.start_values(params)  # unknown names: KeyError before the FMU
        slave = self._library()
        _MESSAGES.clear()
        component = None
        try:
            slave.instantiate(callbacks=self._callbacks)
            component = slave.component
            slave.setupExperiment(tolerance=rtol, startTime=0.0, stopTime=stop_time)
            self._set(slave, start_values)
            slave.enterInitializationMode()
            val[0] = acc[0]
            slave.fmi2SetReal(component, vr_ag, 1, val)
            if vertical_input is not None:
                val[0] = vertical_input[1][0]
                slave.fmi2SetReal(component, (c_uint32 * 1)(vertical_input[0]), 1, val)
            slave.exitInitializationMode()
            vr_c = (c_uint32 * len(calc))(*[self.variables[n].valueReference for n in calc])
            buf_c = (c_double * len(calc))()
            slave.fmi2GetReal(component, vr_c, len(calc), buf_c)
            calculated = {n: _infinite(x) for n, x in zip(calc, buf_c)}

            if native:
                times, rows_r, rows_i, rows_b, overturned = self._native_loop(
                    slave, component, grid, *inputs, vr_ag[0], vr_r, vr_i, vr_b, every, vertical_input)
            else:
                times, rows_r, rows_i, rows_b, overturned = self._python_loop(
                    slave, component, grid, *inputs, vr_ag[0], vr_r, vr_i, vr_b, every, vertical_input)
            final = {}
            for name in ("impacts", "zeroCrossings", "overturned"):
                v = self.variables[name]
                final[name] = (slave.getInteger([v.valueReference])[0] if v.type == "Integer"
                               else slave.getBoolean([v.valueReference])[0])
            slave.terminate()
        except Exception as exc:  # noqa: BLE001 - FMICallException and instantiation errors
            if isinstance(exc, FMUError):
                raise
            raise FMUError.from_log(exc, _MESSAGES) from exc
        finally:
            if component is not None:
                slave.fmi2FreeInstance(component)
                slave.component = None

        dtype = [("time", float)] + [(n, float) for n in reals] + [(n, np.int64) for n in ints] \
            + [(n, bool) for n in bools]
        result = np.empty(len(times), dtype=dtype)
        result["time"] = times
        for j, n in enumerate(reals):
            result[n] = rows_r[:, j]
        for j, n in enumerate(ints):
            result[n] = rows_i[:, j]
        for j, n in enumerate(bools):
            result[n] = rows_b[:, j]
        terminal = None if final["overturned"] else terminal_message(_MESSAGES) if overturned else None
        overturned = (overturned and terminal is None) or bool(final["overturned"])
        if rows is not None:  # the output grid is not the communication grid: its rows only
            result = result[output_rows(result["time"], rows)]
        keep = ["time"] + list(outputs)
        t_end = float(result["time"][-1])
        return Run(
            result=repack_fields(result[keep]),
            overturned=overturned,
            t_end=t_end,
            t_overturn=t_end if overturned else math.nan,
            peak_theta_over_alpha=float(np.max(np.abs(result["thetaOverAlpha"]))),
            impacts=int(final["impacts"]),
            zero_crossings=int(final["zeroCrossings"]),
            calculated=calculated,
            wall=_time.perf_counter() - t_start,
            messages=list(_MESSAGES),
            terminal=terminal,
        )

    @staticmethod
    def _native_loop(slave, component, grid, acc, slope, vr_ag, vr_r, vr_i, vr_b, every, vertical=None):
        """The stepping loop in fmu-stepper (rocking.stepper): the calls of `_python_loop`, natively."""
        fns = stepper.functions(slave._functions)
        out, times, reals, ints, bools = stepper.step(fns, component, grid, acc, slope, vr_ag,
                                                      vr_r, vr_i, vr_b, every, second=vertical)
        if out.failed_call:
            raise FMICallException(stepper.CALLS.get(out.failed_call, "?"), out.status)
        return times, reals, ints.astype(np.int64), bools.astype(bool), bool(out.terminated)

    @staticmethod
    def _python_loop(slave, component, grid, acc, slope, vr_ag, vr_r, vr_i, vr_b, every, vertical=None):
        """The stepping loop in Python: the reference for the native one (same calls, same order).

        Returns (times, reals, integers, booleans, terminated): the rows sampled at grid[0],
        after every `every` steps and after the last, and at fmi2LastSuccessfulTime when the
        FMU discarded a step and terminated (overturned, or out of range under av).
        vertical: None, or (value reference of av, its values and slopes on the grid)."""
        raw = slave._functions  # the ctypes functions: no per-call wrapper in the loop
        get_real, get_int, get_bool = raw["fmi2GetReal"], raw["fmi2GetInteger"], raw["fmi2GetBoolean"]
        set_real, set_der, do_step = raw["fmi2SetReal"], raw["fmi2SetRealInputDerivatives"], raw["fmi2DoStep"]
        n_r, n_i, n_b = len(vr_r), len(vr_i), len(vr_b)
        vr_r, vr_i, vr_b = (c_uint32 * n_r)(*vr_r), (c_uint32 * n_i)(*vr_i), (c_uint32 * n_b)(*vr_b)
        buf_r, buf_i, buf_b = (c_double * n_r)(), (c_int * n_i)(), (c_int * n_b)()
        vr_in, val, order = (c_uint32 * 1)(vr_ag), (c_double * 1)(), (c_int * 1)(1)
        n_steps = len(grid) - 1
        n_rows = n_steps // every + 2
        rows_r = np.empty((n_rows, n_r))
        rows_i = np.empty((n_rows, n_i), dtype=np.int64)
        rows_b = np.empty((n_rows, n_b), dtype=bool)
        times = np.empty(n_rows)
        nrec = 0
        overturned = False

        def sample(t):
            nonlocal nrec
            status = get_real(component, vr_r, n_r, buf_r)
            if n_i:
                status = max(status, get_int(component, vr_i, n_i, buf_i))
                rows_i[nrec] = buf_i
            if n_b:
                status = max(status, get_bool(component, vr_b, n_b, buf_b))
                rows_b[nrec] = buf_b
            if status > 1:
                raise FMICallException("fmi2Get*", status)
            rows_r[nrec] = buf_r
            times[nrec] = t
            nrec += 1

        sample(grid[0])
        with_input = acc is not None
        for k in range(n_steps):
            t = grid[k]
            if with_input:
                val[0] = acc[k]
                status = set_real(component, vr_in, 1, val)
                val[0] = slope[k]
                status = max(status, set_der(component, vr_in, 1, order, val))
                if status > 1:
                    raise FMICallException("fmi2SetReal/fmi2SetRealInputDerivatives", status)
            if vertical is not None:
                status = _set_input(set_real, set_der, component, vertical, k)
                if status > 1:
                    raise FMICallException("fmi2SetReal/fmi2SetRealInputDerivatives (av)", status)
            status = do_step(component, t, grid[k + 1] - t, 1)
            if status > 1:
                if status == fmi2Discard and slave.getBooleanStatus(fmi2Terminated):
                    sample(slave.getRealStatus(fmi2LastSuccessfulTime))
                    overturned = True
                    break
                raise FMICallException("fmi2DoStep", status)
            if (k + 1) % every == 0 or k + 1 == n_steps:
                sample(grid[k + 1])
        return times[:nrec], rows_r[:nrec], rows_i[:nrec], rows_b[:nrec], overturned

    def calculated(self, params):
        """The calculated parameters (docs/model.md §5) after initialization, without stepping."""
        return self.simulate(params, stop_time=0.0, outputs=("theta",)).calculated
