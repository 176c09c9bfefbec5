"""Helpers for driving the RockingBlock FMU through fmpy's low-level API."""

import csv
import io
import subprocess
import tempfile
from ctypes import byref, c_void_p, cast

import numpy as np
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2OK,
)
from fmpy.logging import addLoggerProxy

from ctypes import CDLL

_libc = CDLL(None)
_calloc = _libc.calloc
_free = _libc.free

OK, WARNING, DISCARD, ERROR, FATAL = 0, 1, 2, 3, 4

# Callbacks handed to an FMU must outlive every instance that may call them
# (and fmpy's C logger proxy keeps the last one in a process-wide variable):
# keep them for the life of the process.
_KEEP_ALIVE = []


def _restore_fmpy_logger():
    """Points fmpy's process-wide proxy back at fmpy's own printing logger."""
    from fmpy.fmi2 import printLogMessage

    restore = fmi2CallbackFunctions()
    restore.logger = fmi2CallbackLoggerTYPE(printLogMessage)
    addLoggerProxy(byref(restore))
    _KEEP_ALIVE.append(restore)


class Host:
    """One instance with its own logger that records (status, category, message)."""

    def __init__(self, fmu_path, unzipped, name="instance", logging_on=False, environment=None,
                 proxy=False):
        self.md = read_model_description(fmu_path)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.var = {v.name: v for v in self.md.modelVariables}
        self.messages = []
        self.environments = []
        self.names = []

        def log(env, instance_name, status, category, message):
            text = message.decode()
            if not proxy:
                # printf-safe: every % doubled, no conversion left
                assert "%" not in text.replace("%%", ""), text
                text = text.replace("%%", "%")
            self.environments.append(env)
            self.names.append(instance_name.decode() if instance_name else None)
            self.messages.append((status, category.decode(), text))

        self._log = fmi2CallbackLoggerTYPE(log)
        self.proxy = proxy
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = self._log
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(_calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(_free)
        if environment is not None:
            self.callbacks.componentEnvironment = cast(environment, c_void_p)
        if proxy:
            # fmpy's C proxy formats the message with vsnprintf, as a C host
            # would (it keeps one logger per process: one such host at a time)
            addLoggerProxy(byref(self.callbacks))
        _KEEP_ALIVE.append((self._log, self.callbacks))
        self.fmu = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=unzipped,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        self.fmu.instantiate(callbacks=self.callbacks, loggingOn=logging_on)

    # raw calls: return the status instead of raising
    def raw(self, function, *args):
        return self.fmu._functions[function](self.fmu.component, *args)

    def status(self, call, *args):
        try:
            call(*args)
            return OK
        except FMICallException as e:
            return e.status

    def set(self, **values):
        for name, x in values.items():
            v = self.var[name]
            if v.type == "Real":
                self.fmu.setReal([v.valueReference], [float(x)])
            elif v.type in ("Integer", "Enumeration"):
                if isinstance(x, str):
                    x = next(i.value for i in v.declaredType.items if i.name == x)
                self.fmu.setInteger([v.valueReference], [int(x)])
            elif v.type == "Boolean":
                self.fmu.setBoolean([v.valueReference], [bool(x)])

    def get(self, name):
        v = self.var[name]
        if v.type == "Real":
            return self.fmu.getReal([v.valueReference])[0]
        if v.type in ("Integer", "Enumeration"):
            return self.fmu.getInteger([v.valueReference])[0]
        return bool(self.fmu.getBoolean([v.valueReference])[0])

    def init(self, start=0.0, tolerance=None, stop=None, **values):
        self.fmu.setupExperiment(tolerance=tolerance, startTime=start, stopTime=stop)
        self.set(**values)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()

    def errors(self):
        return [m for s, c, m in self.messages if s >= ERROR]

    def free(self):
        self.fmu.freeInstance()
        if self.proxy:
            _restore_fmpy_logger()


def fmpy_steps(t, ag, start, stop, interval, derivatives):
    """The (t_end, ag, dag) of every step fmpy's simulate_fmu makes with input
    arrays (t, ag), replaying its loop and its interpolation."""
    from fmpy.simulation import Input
    from math import isclose

    table = np.asarray([ag], dtype=float)
    t = np.asarray(t, dtype=float)
    steps = []
    time, n = start, 0
    while not (time > stop or isclose(time, stop)):
        nxt = start + (n + 1) * interval
        if nxt > stop and not isclose(nxt, stop):
            nxt = stop
        v, d = Input.interpolate(time=time, t=t, table=table, discrete=False, after_event=True)
        steps.append((nxt, float(v[0]), float(d[0]) if derivatives else 0.0))
        time = nxt
        if isclose(time, start + (n + 1) * interval):
            n += 1
    return steps


COLUMNS = ["theta", "omega", "angularAcceleration", "af", "contactLength", "MR",
           "regime", "impacts", "zeroCrossings", "overturned", "Fx", "Fz"]


def run_direct(path, params, steps, start=0.0, tolerance=None):
    """Runs the Rust engine directly; returns a structured array like fmpy's."""
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        f.write("t_end,ag,dag\n")
        for te, a, d in steps:
            f.write(f"{te!r},{a!r},{d!r}\n")
        name = f.name
    args = [path, "--steps", name, "--start", repr(start)]
    if tolerance is not None:
        args += ["--tolerance", repr(tolerance)]
    args += [f"{k}={v}" for k, v in params.items()]
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    rows = list(csv.reader(io.StringIO(out)))
    header, data = rows[0], rows[1:]
    return {h: np.array([float(r[i]) for r in data]) for i, h in enumerate(header)}


ENUMS = {
    "shape": ["solidRectangle", "hollowRectangle", "solidCircle", "hollowCircle"],
    "massModel": ["prism", "lumped"],
    "interface": ["rigid", "elastic", "elastoPlastic"],
    "formulation": ["costa", "shiftingPivot"],
    "restitution": ["housner", "given"],
}


def start_values(params):
    """fmpy start values: enumeration items as their (1-based) numbers."""
    return {k: (ENUMS[k].index(v) + 1 if k in ENUMS and isinstance(v, str) else v) for k, v in params.items()}
