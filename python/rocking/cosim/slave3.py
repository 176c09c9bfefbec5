"""One FMI 3.0 co-simulation FMU behind fmpy's FMU3Slave, addressed by variable
name: slave.Slave's calls for the 3.0 archives (target/fmu/fmi3/), so that the
master (master.py) steps either standard.

What differs from 2.0, and what the master must know:
- 3.0 has no fmi2SetRealInputDerivatives: `set` passes an input's slope in
  its der(x) input (a Float64 input whose `derivative` attribute names the
  input, docs/fmi3.md "Input derivatives"), set in the same fmi3SetFloat64
  call; `takes_rate` says whether the FMU declares one;
- `step` returns a `StepEnd` from fmi3DoStep's flags: with
  `early_return=True` (eventModeUsed and earlyReturnAllowed at instantiation)
  RockingBlock stops at the first impact, uplift, rest or overturning inside
  the step, and `handle_event` runs the event mode that follows;
- overturning ends the run with terminateSimulation (2.0: fmi2Discard);
- ShearFrame's per-floor variables are arrays sized by the structural
  parameter `n` (`Fx` for 2.0's `Fx[1]` ... `Fx[n]`): `refs` takes the 2.0
  names and the calls get or set the arrays whole; `n` is set in
  configuration mode, before initialization.
"""

import os
import re

from fmpy.fmi3 import (FMU3Slave, fmi3Boolean, fmi3Float64, fmi3InstanceEnvironment, fmi3Int32,
                       fmi3IntermediateUpdateCallback, fmi3LogMessageCallback, fmi3ValueReference)

from .. import fmu as _fmu
from .slave import Extracted, StepEnd


def _log(_env, status, category, message):
    _fmu._MESSAGES.append(f"[{status}] {(category or b'').decode(errors='replace')}: "
                          f"{(message or b'').decode(errors='replace')}")


# One logger for the process, alive as long as it (as rocking.fmu's for 2.0): the
# callback must outlive every instance that holds it, which fmpy's
# FMU3Slave.instantiate (a new ctypes callback at each call) does not ensure.
_LOGGER = fmi3LogMessageCallback(_log)
_NO_UPDATE = fmi3IntermediateUpdateCallback()


class Slave3(Extracted):
    """An extracted FMI 3.0 FMU, loaded once; `instantiate` / `free` around each run."""

    fmi_version = 3

    def __init__(self, path, instance_name=None):
        super().__init__(path)
        md = self.model_description
        if md.fmiVersion != "3.0" or md.coSimulation is None:
            raise _fmu.FMUError(f"{self.path}: not an FMI 3.0 co-simulation FMU")
        self._slave = FMU3Slave(guid=md.instantiationToken, unzipDirectory=str(self.unzipdir),
                                modelIdentifier=md.coSimulation.modelIdentifier,
                                instanceName=instance_name or md.modelName)
        self.event_mode = False
        # arrays by name, and the structural parameter that sizes them (ShearFrame: n)
        self.arrays = {v.name: v for v in md.modelVariables if v.dimensions}
        self._array_vrs = {v.valueReference for v in self.arrays.values()}
        sizes = {d.valueReference for v in self.arrays.values() for d in v.dimensions}
        self.size_name = next((v.name for v in md.modelVariables if v.valueReference in sizes), None)
        self.size = int(self.variables[self.size_name].start) if self.size_name else 1
        #: value reference of an input -> that of its der(x) input
        self._rate_of = {v.derivative.valueReference: v.valueReference for v in md.modelVariables
                         if v.causality == "input" and v.derivative is not None}

    # -- life of an instance ------------------------------------------------
    def instantiate(self, params, start_time, stop_time, rtol=None, early_return=False):
        """Instantiate (with event mode and early return if asked), enter initialization
        mode and set `params` (enumerations by item name or value); `exit_init` leaves it."""
        _fmu._MESSAGES.clear()
        self.event_mode = bool(early_return)
        flag = fmi3Boolean(self.event_mode)
        self.component = self._slave.fmi3InstantiateCoSimulation(
            self._slave.instanceName.encode(), self._slave.guid.encode(),
            (os.path.join(str(self.unzipdir), "resources") + os.path.sep).encode(), fmi3Boolean(False),
            fmi3Boolean(False), flag, flag, (fmi3ValueReference * 0)(), 0, fmi3InstanceEnvironment(),
            _LOGGER, _NO_UPDATE)
        if not self.component:
            raise _fmu.FMUError(f"{self.path}: fmi3InstantiateCoSimulation failed (FMU log: "
                                f"{'; '.join(_fmu._MESSAGES) or 'no message logged'})")
        self._slave.component = self.component
        params = dict(params)
        if self.size_name is not None:
            self.size = int(params.pop(self.size_name, self.variables[self.size_name].start))
            self._call("fmi3EnterConfigurationMode", self._slave.enterConfigurationMode)
            self._call(f"setting {self.size_name}", self._slave.setUInt64,
                       [self.variables[self.size_name].valueReference], [self.size])
            self._call("fmi3ExitConfigurationMode", self._slave.exitConfigurationMode)
        self._call("fmi3EnterInitializationMode", self._slave.enterInitializationMode,
                   tolerance=rtol, startTime=start_time, stopTime=stop_time)
        elements = {name: value for name, value in params.items() if name not in self.variables}
        for name, value in params.items():
            if name in self.variables:
                self.set_start(name, value)
        if elements:
            self.set(self.refs(list(elements)), [float(x) for x in elements.values()])

    def exit_init(self):
        """Leave initialization mode; with event mode, through it to step mode."""
        self._call("fmi3ExitInitializationMode", self._slave.exitInitializationMode)
        if self.event_mode:
            self._update_and_step()

    def free(self):
        if self.component is not None:
            # not FMU3Slave.freeInstance: it also unloads the library, and the next
            # instantiation would call into unmapped code
            self._slave.fmi3FreeInstance(self.component)
            self._slave.component = None
            self.component = None

    def set_start(self, name, value):
        v, value = self.start_value(name, value)
        setter = {"Float64": self._slave.setFloat64, "Int32": self._slave.setInt32,
                  "Int64": self._slave.setInt64, "Enumeration": self._slave.setInt64,
                  "Boolean": self._slave.setBoolean}.get(v.type)
        if setter is None:
            raise TypeError(f"{name}: cannot set a {v.type}")
        cast = float if v.type == "Float64" else bool if v.type == "Boolean" else int
        self._call(f"setting {name}", setter, [v.valueReference], [cast(value)])

    # -- values by name -----------------------------------------------------
    def refs(self, names):
        """(value reference, element index or None) of each name; `x[i]` names element
        i of the array `x` (1-based, as 2.0's scalar)."""
        return [self._ref(n) for n in names]

    def _ref(self, name):
        if name in self.variables and name not in self.arrays:
            return self.variables[name].valueReference, None
        m = re.fullmatch(r"(.+)\[(\d+)\]", name)
        if m and m[1] in self.arrays and int(m[2]) >= 1:
            return self.arrays[m[1]].valueReference, int(m[2]) - 1
        raise KeyError(f"{name!r} is not a variable of {self.name}.fmu")

    def _layout(self, refs):
        """The distinct value references of `refs`, their values' total count, and the
        position of each ref's value among them."""
        vrs = list(dict.fromkeys(vr for vr, _ in refs))
        past = [i + 1 for _, i in refs if i is not None and i >= self.size]
        if past:
            raise KeyError(f"{self.name}: element {past[0]} of an array of {self.size} ({self.size_name})")
        first, n = {}, 0
        for vr in vrs:
            first[vr] = n
            n += self.size if vr in self._array_vrs else 1
        return vrs, n, [first[vr] + (i or 0) for vr, i in refs]

    def get(self, refs):
        vrs, n, at = self._layout(refs)
        flat = self._call("fmi3GetFloat64", self._slave.getFloat64, vrs, nValues=n)
        return [flat[k] for k in at]

    def get_der(self, refs, order=1):
        vrs, n, at = self._layout(refs)
        values = (fmi3Float64 * n)()
        self._call("fmi3GetOutputDerivatives", self._slave.fmi3GetOutputDerivatives, self.component,
                   (fmi3ValueReference * len(vrs))(*vrs), len(vrs), (fmi3Int32 * len(vrs))(*[order] * len(vrs)),
                   values, n)
        return [values[k] for k in at]

    def set(self, refs, values, slopes=None):
        """Set Float64 inputs and, when given, their first derivatives through their der(x)
        inputs in the same call (the input is then linear over the next step, as with
        2.0's fmi2SetRealInputDerivatives); an array element by setting its array whole.
        Without slopes only the values are set: the master sets an input with its slope at
        every step or never in a run, so a held input's der(x) stays 0."""
        refs, values = list(refs), [float(x) for x in values]
        if slopes is not None:
            refs += [(self._rate_of[vr], i) for vr, i in refs]
            values += [float(x) for x in slopes]
        vrs, n, at = self._layout(refs)
        flat = self._call("fmi3GetFloat64", self._slave.getFloat64, vrs, nValues=n) if n > len(refs) else [0.0] * n
        for k, x in zip(at, values):
            flat[k] = x
        self._call("fmi3SetFloat64", self._slave.setFloat64, vrs, flat)

    def takes_rate(self, name):
        """The input `name` (an array element: its array) has a der(x) input."""
        return self._ref(name)[0] in self._rate_of

    def get_int(self, name):
        return self._call("fmi3GetInt32", self._slave.getInt32, [self.variables[name].valueReference])[0]

    def step(self, t, h):
        """fmi3DoStep from t over h -> StepEnd."""
        event, terminate, early, last = self._call("fmi3DoStep", self._slave.doStep, t, h, True)
        if terminate:
            return StepEnd(last, terminated=True)
        if early:
            return StepEnd(last, early=True, event=self.event_mode)
        return StepEnd(t + h, event=bool(event and self.event_mode))

    def handle_event(self):
        """The event mode after an early return (or an event met at a step's end)."""
        self._call("fmi3EnterEventMode", self._slave.enterEventMode)
        self._update_and_step()

    def _update_and_step(self):
        for _ in range(100):
            if not self._call("fmi3UpdateDiscreteStates", self._slave.updateDiscreteStates)[0]:
                break
        self._call("fmi3EnterStepMode", self._slave.enterStepMode)

    def get_state(self):
        return self._call("fmi3GetFMUState", self._slave.getFMUState)

    def set_state(self, state):
        self._call("fmi3SetFMUState", self._slave.setFMUState, state)

    def free_state(self, state):
        self._slave.freeFMUState(state)

    def serialize(self, state):
        return bytes(self._slave.serializeFMUState(state))

    def _call(self, what, fn, *args, **kw):
        try:
            return fn(*args, **kw)
        except Exception as exc:  # fmpy's FMICallException: add the FMU's own log
            detail = "; ".join(_fmu._MESSAGES) or "no message logged"
            raise _fmu.FMUError(f"{self.name}: {what} failed: {exc} (FMU log: {detail})") from exc
