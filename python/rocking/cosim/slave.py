"""One co-simulation FMU (RockingBlock or ShearFrame) behind fmpy's FMU2Slave,
addressed by variable name: the small layer the master (master.py) steps.

Values are set and read through the raw ctypes functions of FMU2Slave (no
per-call wrapper: a coupled run makes ~10 FMI calls per communication step).
Messages the FMU logs go to rocking.fmu's process-wide logger.
"""

import shutil
from ctypes import byref, c_double, c_int, c_uint32
from dataclasses import dataclass
from pathlib import Path

import fmpy
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2Discard, fmi2FMUstate, fmi2LastSuccessfulTime, fmi2Terminated

from .. import fmu as _fmu


@dataclass
class StepEnd:
    """How one step ended. time: where the FMU is now (s); terminated: the run is over
    (overturning); early: the step stopped before its end, at an event (FMI 3.0's
    early return); event: the FMU needs event mode (FMI 3.0, eventModeUsed)."""

    time: float
    terminated: bool = False
    early: bool = False
    event: bool = False


class Extracted:
    """An FMU's archive extracted and its model description read: what an FMI 2.0 and
    an FMI 3.0 slave share (variables by name, enumeration items, clean-up).

    path  the .fmu; extracted to a temporary folder deleted by `close`
    """

    def __init__(self, path):
        self.path = Path(path)
        if not self.path.is_file():
            raise FileNotFoundError(f"{self.path} does not exist: build it with `cargo xtask fmu`")
        self.unzipdir = Path(fmpy.extract(str(self.path)))
        md = self.model_description = fmpy.read_model_description(str(self.unzipdir))
        self.name = md.modelName
        self.variables = {v.name: v for v in md.modelVariables}
        self.enumerations = {v.name: {it.name: int(it.value) for it in v.declaredType.items}
                             for v in md.modelVariables
                             if v.type == "Enumeration" and v.declaredType is not None}
        self.capabilities = md.coSimulation
        self.component = None

    def close(self):
        self.free()
        try:
            self._slave.freeLibrary()
        except Exception:  # noqa: BLE001 - already unloaded
            pass
        shutil.rmtree(self.unzipdir, ignore_errors=True)

    def free(self):
        raise NotImplementedError

    def start_value(self, name, value):
        """(the variable `name`, `value` with an enumeration item's name replaced by its value)."""
        if name not in self.variables:
            raise KeyError(f"{name!r} is not a variable of {self.name}.fmu")
        return self.variables[name], _fmu.enumeration_value(name, value, self.enumerations)


class Slave(Extracted):
    """An extracted FMI 2.0 FMU, loaded once; `instantiate` / `free` around each run.

    path  the .fmu; extracted to a temporary folder deleted by `close`
    """

    fmi_version = 2

    def __init__(self, path, instance_name=None):
        super().__init__(path)
        md = self.model_description
        self._slave = FMU2Slave(guid=md.guid, unzipDirectory=str(self.unzipdir),
                                modelIdentifier=md.coSimulation.modelIdentifier,
                                instanceName=instance_name or md.modelName)
        raw = self._slave._functions
        self._get_real, self._set_real = raw["fmi2GetReal"], raw["fmi2SetReal"]
        self._set_der, self._get_der = raw["fmi2SetRealInputDerivatives"], raw["fmi2GetRealOutputDerivatives"]
        self._do_step = raw["fmi2DoStep"]

    # -- life of an instance ------------------------------------------------
    def instantiate(self, params, start_time, stop_time, rtol=None):
        """Instantiate, set `params` (enumerations by item name or value) and enter
        initialization mode; `exit_init` leaves it."""
        _fmu._MESSAGES.clear()
        self._slave.instantiate(callbacks=_fmu._CALLBACKS)
        self.component = self._slave.component
        self._slave.setupExperiment(tolerance=rtol, startTime=start_time, stopTime=stop_time)
        for name, value in params.items():
            self.set_start(name, value)
        self._slave.enterInitializationMode()

    def exit_init(self):
        self._slave.exitInitializationMode()

    def free(self):
        if self.component is not None:
            self._slave.fmi2FreeInstance(self.component)
            self._slave.component = None
            self.component = None

    def set_start(self, name, value):
        v, value = self.start_value(name, value)
        vr = [v.valueReference]
        if v.type == "Real":
            self._slave.setReal(vr, [float(value)])
        elif v.type in ("Integer", "Enumeration"):
            self._slave.setInteger(vr, [int(value)])
        elif v.type == "Boolean":
            self._slave.setBoolean(vr, [bool(value)])
        else:
            raise TypeError(f"{name}: cannot set a {v.type}")

    # -- values by name -----------------------------------------------------
    def refs(self, names):
        """A ctypes array of value references, to pass to get/set below."""
        return (c_uint32 * len(names))(*[self.variables[n].valueReference for n in names])

    def get(self, refs):
        buf = (c_double * len(refs))()
        self._check(self._get_real(self.component, refs, len(refs), buf), "fmi2GetReal")
        return list(buf)

    def get_der(self, refs, order=1):
        buf = (c_double * len(refs))()
        orders = (c_int * len(refs))(*([order] * len(refs)))
        self._check(self._get_der(self.component, refs, len(refs), orders, buf), "fmi2GetRealOutputDerivatives")
        return list(buf)

    def set(self, refs, values, slopes=None):
        """Set real inputs and, when given, their first derivatives (the input is then
        linear over the next step)."""
        n = len(refs)
        self._check(self._set_real(self.component, refs, n, (c_double * n)(*values)), "fmi2SetReal")
        if slopes is not None:
            self._check(self._set_der(self.component, refs, n, (c_int * n)(*([1] * n)),
                                      (c_double * n)(*slopes)), "fmi2SetRealInputDerivatives")

    def takes_rate(self, name):
        """The input `name` takes a first derivative (fmi2SetRealInputDerivatives: every
        real input of an FMU that canInterpolateInputs, which CoupledFMUs checks)."""
        return self.variables[name].type == "Real"

    def get_int(self, name):
        return self._slave.getInteger([self.variables[name].valueReference])[0]

    def get_bool(self, name):
        return self._slave.getBoolean([self.variables[name].valueReference])[0]

    def do_step(self, t, h):
        """fmi2DoStep; returns its status (0 OK, 1 warning, 2 discard); errors raise."""
        status = self._do_step(self.component, c_double(t), c_double(h), 1)
        if status > 2:
            self._check(status, "fmi2DoStep")
        return status

    def step(self, t, h):
        """fmi2DoStep -> StepEnd: the block's overturning (fmi2Discard with fmi2Terminated)
        ends the run at fmi2LastSuccessfulTime; any other discard raises."""
        status = self.do_step(t, h)
        if status != fmi2Discard:
            return StepEnd(t + h)
        if self.status(fmi2Terminated, boolean=True):
            return StepEnd(self.status(fmi2LastSuccessfulTime), terminated=True)
        raise _fmu.FMUError(f"{self.name}: fmi2DoStep discarded a step without terminating")

    def handle_event(self):
        """FMI 2.0 co-simulation has no event mode: nothing to do."""

    def get_state(self):
        state = fmi2FMUstate()
        self._check(self._slave.fmi2GetFMUstate(self.component, byref(state)), "fmi2GetFMUstate")
        return state

    def set_state(self, state):
        self._check(self._slave.fmi2SetFMUstate(self.component, state), "fmi2SetFMUstate")

    def free_state(self, state):
        self._slave.fmi2FreeFMUstate(self.component, byref(state))

    def serialize(self, state):
        return bytes(self._slave.serializeFMUstate(state))

    def status(self, kind, boolean=False):
        return self._slave.getBooleanStatus(kind) if boolean else self._slave.getRealStatus(kind)

    def _check(self, status, call):
        if status > 1:
            detail = "; ".join(_fmu._MESSAGES) or "no message logged"
            raise _fmu.FMUError(f"{self.name}: {call} returned {status} (FMU log: {detail})")
