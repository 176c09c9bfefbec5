"""A small Jacobi master that couples RockingBlock.fmu to any structure.

This is the loop the three hosts of docs/cosimulation-hosts.md share (the
same scheme as the container FMU's runtime and the C host
fmu-rocking/tests/c_host/coupled.c): at each communication point t_k both
sides' outputs are read, then

    block.ag       <- structure's floor absolute acceleration a(t_k)
    structure's F  <- minus the block's support forces (-Fx, -Fz)(t_k)

and both step from t_k to t_k + h with these inputs held (`hold="constant"`)
or extrapolated linearly with the block's output derivatives and the floor
acceleration's last difference (`hold="linear"`). The structure is any object
with `floor_acceleration()` and `step(t, h, ag0, dag, fx, dfx, fz, dfz)`:
`ShearFrameFMU` below (ShearFrame.fmu through fmpy) or
`rocking.cosim.opensees.OpenSeesStructure`.

The ground motion reaches the structure as the record's samples at the
communication points with their slope (`ground="linear"`: piecewise linear,
exact for a record sampled at the communication step) or held
(`ground="constant"`: what a host without input derivatives does, such as
fmpy's simulate_fmu driving the container FMU).
"""

import shutil
import tempfile
from ctypes import c_double, c_int, c_uint32
from dataclasses import dataclass, field

import fmpy
import numpy as np
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2Discard, fmi2LastSuccessfulTime, fmi2Terminated)

from .. import paths


def shear_frame_fmu():
    """target/fmu/ShearFrame.fmu of the repository (`cargo xtask fmu` writes it)."""
    return paths.target_dir() / "fmu" / "ShearFrame.fmu"


class Slave:
    """One FMI 2.0 co-simulation instance through fmpy, with names for value references."""

    def __init__(self, fmu, name, parameters, tolerance=None, start=0.0):
        self.md = fmpy.read_model_description(str(fmu))
        self.var = {v.name: v for v in self.md.modelVariables}
        self.dir = tempfile.mkdtemp(prefix=name)
        fmpy.extract(str(fmu), unzipdir=self.dir)
        self.fmu = FMU2Slave(guid=self.md.guid, unzipDirectory=self.dir,
                             modelIdentifier=self.md.coSimulation.modelIdentifier, instanceName=name)
        self.fmu.instantiate()
        self.fmu.setupExperiment(tolerance=tolerance, startTime=start)
        self.fmu.enterInitializationMode()
        for key, value in parameters.items():
            self.set(key, value)
        self.fmu.exitInitializationMode()
        self.done = False

    def vr(self, name):
        return self.var[name].valueReference

    def set(self, name, value):
        v = self.var[name]
        if isinstance(value, str):  # an enumeration item by name
            items = [i.name for i in v.declaredType.items]
            value = items.index(value) + 1
        if v.type == "Real":
            self.fmu.setReal([v.valueReference], [float(value)])
        elif v.type in ("Integer", "Enumeration"):
            self.fmu.setInteger([v.valueReference], [int(value)])
        else:
            self.fmu.setBoolean([v.valueReference], [bool(value)])

    def get(self, *names):
        return self.fmu.getReal([self.vr(n) for n in names])

    def set_input(self, name, value, slope=None):
        vr = self.vr(name)
        self.fmu.setReal([vr], [float(value)])
        if slope is not None:
            self.fmu.setRealInputDerivatives([vr], [1], [float(slope)])

    def derivative(self, name, order=1):
        vr = (c_uint32 * 1)(self.vr(name))
        order_ = (c_int * 1)(order)
        out = (c_double * 1)()
        self.fmu.fmi2GetRealOutputDerivatives(self.fmu.component, vr, 1, order_, out)
        return out[0]

    def do_step(self, t, h):
        """True if the step succeeded; False when the FMU discarded it and terminated (overturning)."""
        try:
            status = self.fmu.fmi2DoStep(self.fmu.component, t, h, 1)
        except FMICallException as e:  # fmpy raises on any status but OK and Warning
            status = e.status
        if status == fmi2Discard:
            term = c_int()
            self.fmu.fmi2GetBooleanStatus(self.fmu.component, fmi2Terminated, term)
            if term.value:
                self.done = True
                return False
        if status != 0:
            raise RuntimeError(f"{self.fmu.instanceName}: fmi2DoStep at t = {t} returned status {status}")
        return True

    def last_successful_time(self):
        value = c_double()
        self.fmu.fmi2GetRealStatus(self.fmu.component, fmi2LastSuccessfulTime, value)
        return value.value

    def close(self):
        try:
            self.fmu.terminate()
        except Exception:  # an instance that discarded a step may refuse to terminate cleanly
            pass
        self.fmu.freeInstance()
        shutil.rmtree(self.dir, ignore_errors=True)


class ShearFrameFMU:
    """ShearFrame.fmu as the structure of `couple`: floor `floor` carries the block."""

    def __init__(self, m, k, floor, rayleigh=None, zeta=None, fmu=None):
        params = {"n": len(m)}
        for i, (mi, ki) in enumerate(zip(m, k), start=1):
            params[f"m[{i}]"], params[f"k[{i}]"] = mi, ki
        if rayleigh is not None:
            params.update(damping="rayleigh", rayleighAlpha=rayleigh[0], rayleighBeta=rayleigh[1])
        else:
            params.update(damping="modal", zeta=0.05 if zeta is None else zeta)
        self.slave = Slave(fmu or shear_frame_fmu(), "frame", params)
        self.floor = floor

    def floor_acceleration(self):
        return self.slave.get(f"a[{self.floor}]")[0]

    def step(self, t, h, ag0, dag, fx, dfx, fz, dfz):
        self.slave.set_input("ag", ag0, dag)
        self.slave.set_input(f"Fx[{self.floor}]", fx, dfx)
        self.slave.set_input(f"Fz[{self.floor}]", fz, dfz)
        self.slave.do_step(t, h)

    def floors(self):
        """Every floor's absolute acceleration (m/s2)."""
        n = int(self.slave.fmu.getInteger([self.slave.vr("n")])[0])
        return np.array(self.slave.get(*[f"a[{i}]" for i in range(1, n + 1)]))

    def close(self):
        self.slave.close()


@dataclass
class Coupled:
    """Time histories of a coupled run at the communication points."""
    t: np.ndarray
    theta: np.ndarray
    a_floor: np.ndarray  # absolute acceleration of the floor carrying the block (m/s2)
    fx: np.ndarray       # the block's support force Fx (N)
    overturned: bool = False
    t_end: float = field(default=float("nan"))


def ground(record_t, record_ag, t, h, mode):
    """The ground acceleration at t and its slope over [t, t + h] (0 when held)."""
    a0 = float(np.interp(t, record_t, record_ag))
    if mode == "constant":
        return a0, 0.0
    return a0, (float(np.interp(t + h, record_t, record_ag)) - a0) / h


def couple(structure, block, record_t, record_ag, h, t_end, hold="constant", ground_mode="linear", force_sign=-1.0):
    """Jacobi coupling of `block` (a Slave of RockingBlock.fmu) and `structure` (see module doc).

    Ends at t_end, or cleanly at the step where the block overturns (the
    structure keeps its state at the last communication point).
    `force_sign` is the factor from the block's forces to the floor's: -1,
    the physics; +1 only to reproduce a host that cannot change a sign
    (rocking.cosim.ssp, `signs="drop"`).
    """
    steps = int(round(t_end / h))
    t_out, theta, af, fx_out = [], [], [], []
    a_prev = None
    overturned = False
    t = 0.0
    for k in range(steps + 1):
        t = k * h
        a = structure.floor_acceleration()
        th, fx, fz = block.get("theta", "Fx", "Fz")
        t_out.append(t), theta.append(th), af.append(a), fx_out.append(fx)
        if k == steps:
            break
        if hold == "linear":
            da = 0.0 if a_prev is None else (a - a_prev) / h
            dfx, dfz = block.derivative("Fx"), block.derivative("Fz")
        else:
            da = dfx = dfz = 0.0
        a_prev = a
        g0, dg = ground(record_t, record_ag, t, h, ground_mode)
        block.set_input("ag", a, da if hold == "linear" else None)
        if not block.do_step(t, h):
            overturned = True
            break
        sg = force_sign
        structure.step(t, h, g0, dg, sg * fx, sg * dfx, sg * fz, sg * dfz)
    return Coupled(np.array(t_out), np.array(theta), np.array(af), np.array(fx_out), overturned,
                   block.last_successful_time() if overturned else t)
