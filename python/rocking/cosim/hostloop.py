"""A small Jacobi master that couples RockingBlock.fmu to any structure.

The OpenSees adapter's loop (docs/cosimulation-hosts.md), and the scheme of
the container FMU's runtime and of the C host fmu-rocking/tests/c_host/coupled.c,
which reproduce it bit for bit: at each communication point t_k both sides'
outputs are read, then

    block.ag       <- structure's floor absolute acceleration a(t_k)
    structure's F  <- minus the block's support forces (-Fx, -Fz)(t_k)

and both step from t_k to t_k + h with these inputs held (`hold="constant"`)
or extrapolated linearly with the block's output derivatives and the floor
acceleration's last difference (`hold="linear"`). The structure is any object
with `floor_acceleration()` and `step(t, h, ag0, dag, fx, dfx, fz, dfz)`:
`ShearFrameFMU` below (ShearFrame.fmu through fmpy) or
`rocking.cosim.opensees.OpenSeesStructure`.

The ground motion reaches the structure as the record's samples at the
communication points with their slope (`ground_mode="linear"`: piecewise
linear, exact for a record sampled at the communication step) or held
(`ground_mode="constant"`: what a host without input derivatives does, such
as fmpy's simulate_fmu driving the container FMU).

The floor acceleration recorded at t_k is the structure's output before the
exchange (it carries the block's force of t_{k-1}), as in the container and
the C host.
"""

from dataclasses import dataclass, field

import numpy as np
from fmpy.fmi2 import fmi2Discard, fmi2LastSuccessfulTime, fmi2Terminated

from .. import paths
from .slave import Slave


def shear_frame_fmu():
    """target/fmu/ShearFrame.fmu of the repository (`cargo xtask fmu` writes it)."""
    return paths.target_dir() / "fmu" / "ShearFrame.fmu"


def open_block(parameters=None, fmu=None, rtol=1e-9):
    """RockingBlock.fmu instantiated with `parameters` and initialized, at t = 0 (a slave.Slave)."""
    block = Slave(fmu or paths.default_fmu())
    block.instantiate(parameters or {}, 0.0, None, rtol)
    block.exit_init()
    return block


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
        self.slave = Slave(fmu or shear_frame_fmu())
        self.slave.instantiate(params, 0.0, None)
        self.slave.exit_init()
        self.r_a = self.slave.refs([f"a[{floor}]"])
        self.r_in = self.slave.refs(["ag", f"Fx[{floor}]", f"Fz[{floor}]"])
        self.r_floors = self.slave.refs([f"a[{i}]" for i in range(1, len(m) + 1)])

    def floor_acceleration(self):
        return self.slave.get(self.r_a)[0]

    def step(self, t, h, ag0, dag, fx, dfx, fz, dfz):
        self.slave.set(self.r_in, [ag0, fx, fz], [dag, dfx, dfz])
        self.slave.do_step(t, h)

    def floors(self):
        """Every floor's absolute acceleration (m/s2)."""
        return np.array(self.slave.get(self.r_floors))

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
    """Jacobi coupling of `block` (RockingBlock.fmu, `open_block`) and `structure` (see module doc).

    Ends at t_end, or cleanly at the step where the block overturns (the
    structure keeps its state at the last communication point).
    `force_sign` is the factor from the block's forces to the floor's: -1,
    the physics; +1 only to reproduce a host that cannot change a sign
    (rocking.cosim.ssp, `signs="drop"`).
    """
    steps = int(round(t_end / h))
    r_out, r_force, r_ag = block.refs(["theta", "Fx", "Fz"]), block.refs(["Fx", "Fz"]), block.refs(["ag"])
    t_out, theta, af, fx_out = [], [], [], []
    a_prev = None
    overturned = False
    t = 0.0
    for k in range(steps + 1):
        t = k * h
        a = structure.floor_acceleration()
        th, fx, fz = block.get(r_out)
        t_out.append(t), theta.append(th), af.append(a), fx_out.append(fx)
        if k == steps:
            break
        if hold == "linear":
            da = 0.0 if a_prev is None else (a - a_prev) / h
            dfx, dfz = block.get_der(r_force)
        else:
            da = dfx = dfz = 0.0
        a_prev = a
        g0, dg = ground(record_t, record_ag, t, h, ground_mode)
        block.set(r_ag, [a], [da] if hold == "linear" else None)
        if block.do_step(t, h) == fmi2Discard and block.status(fmi2Terminated, boolean=True):
            overturned = True
            break
        sg = force_sign
        structure.step(t, h, g0, dg, sg * fx, sg * dfx, sg * fz, sg * dfz)
    return Coupled(np.array(t_out), np.array(theta), np.array(af), np.array(fx_out), overturned,
                   block.status(fmi2LastSuccessfulTime) if overturned else t)
