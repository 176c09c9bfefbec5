"""An OpenSees model (openseespy) as the structure carrying RockingBlock.fmu.

The user builds any model with a function `build(ops)` of the openseespy
module; the adapter then owns the time stepping. Conventions:

- `build(ops)` defines the whole model (nodes, masses, elements, constraints,
  damping) and, if it has any, applies the gravity loads and holds them with
  `ops.loadConst("-time", 0.0)`: the dynamic run starts at time 0 from the
  state `build` leaves. It must not leave an analysis half-defined; the
  adapter defines its own (`analysis`, below) after it returns.
- `floor_node`: the node the block stands on; `dof_x` its horizontal degree
  of freedom (the direction of the ground motion and of the block's rocking),
  `dof_z` its vertical one (None for a model without one, such as a 1-D shear
  building: the block's vertical force is then not applied).
- The ground motion is the adapter's: a `UniformExcitation` along `dof_x`
  with a `Path` time series of the record (t, ag), tags `GROUND_TAG`. With it
  OpenSees computes displacements, velocities and accelerations relative to
  the ground; the floor's absolute acceleration is `nodeAccel + ag(t)`.
- The block's forces on the floor are the opposite of its support forces:
  `-Fx` along `dof_x` and `-(Fz - W)` along `dof_z`, where W is the block's
  weight (its `Fz` at rest): the weight belongs in `build`'s gravity loads,
  the adapter adds only the dynamic part. Each communication step the two
  load patterns `FORCE_TAGS` are replaced by ones whose `Path` series are
  linear over the step (value and slope from the master).
- Each communication step h is `substeps` OpenSees steps of h / substeps.
  The default analysis is Newmark's average acceleration (unconditionally
  stable, second order) with Newton iterations on the displacement increment:
  pass `analysis(ops)` to choose another one.

Tags from 900001 upwards are the adapter's; `build` must not use them.
"""

import numpy as np

GROUND_TAG = 900001
FORCE_TAGS = (900002, 900003)


def default_analysis(ops):
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("NormDispIncr", 1e-10, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


class OpenSeesStructure:
    """Steps an OpenSees model built by `build(ops)`; the `couple` structure interface."""

    def __init__(self, build, floor_node, record_t, record_ag, dof_x=1, dof_z=None, block_weight=0.0,
                 substeps=10, analysis=default_analysis):
        import openseespy.opensees as ops

        self.ops = ops
        ops.wipe()
        build(ops)
        self.floor_node, self.dof_x, self.dof_z = floor_node, dof_x, dof_z
        self.ndf = len(ops.nodeDisp(floor_node))
        self.weight = block_weight
        self.substeps = substeps
        self.record_t = np.asarray(record_t, float)
        self.record_ag = np.asarray(record_ag, float)
        ops.timeSeries("Path", GROUND_TAG, "-time", *self.record_t, "-values", *self.record_ag)
        ops.pattern("UniformExcitation", GROUND_TAG, dof_x, "-accel", GROUND_TAG)
        self._patterns = False
        analysis(ops)

    def _force_pattern(self, tag, dof, t, h, f0, df):
        ops = self.ops
        if self._patterns:
            ops.remove("loadPattern", tag)
            ops.remove("timeSeries", tag)
        # the line over the step, continued a step either side so that round-off
        # in OpenSees' time never falls off the series' ends
        times = [t - h, t, t + h, t + 2 * h]
        values = [f0 + df * (s - t) for s in times]
        ops.timeSeries("Path", tag, "-time", *times, "-values", *values)
        ops.pattern("Plain", tag, tag)
        load = [0.0] * self.ndf
        load[dof - 1] = 1.0
        ops.load(self.floor_node, *load)

    def floor_acceleration(self):
        t = self.ops.getTime()
        return self.ops.nodeAccel(self.floor_node, self.dof_x) + float(np.interp(t, self.record_t, self.record_ag))

    def step(self, t, h, ag0, dag, fx, dfx, fz, dfz):
        """One communication step; fx, fz are the forces on the floor (the block's -Fx, -Fz).

        ag0, dag are ignored: the ground motion is the record's Path series.
        """
        self._force_pattern(FORCE_TAGS[0], self.dof_x, t, h, fx, dfx)
        if self.dof_z is not None:
            # -Fz - (-W): only the dynamic part, the weight is in build's gravity loads
            self._force_pattern(FORCE_TAGS[1], self.dof_z, t, h, fz + self.weight, dfz)
        self._patterns = True
        status = self.ops.analyze(self.substeps, h / self.substeps)
        if status != 0:
            raise RuntimeError(f"OpenSees analyze failed at t = {t} (status {status})")

    def node_response(self, node, dof):
        """Relative displacement (m) and absolute acceleration (m/s2) of a node along dof."""
        t = self.ops.getTime()
        return self.ops.nodeDisp(node, dof), self.ops.nodeAccel(node, dof) + float(
            np.interp(t, self.record_t, self.record_ag))

    def close(self):
        self.ops.wipe()


def shear_building(m, k, rayleigh=None, zeta=None):
    """A `build` function: the linear shear building of ShearFrame.fmu in OpenSees.

    Nodes 0 (the ground, fixed) to n on one horizontal degree of freedom, the
    floor masses m[i] (kg) on nodes 1..n, storey i a zeroLength spring of
    stiffness k[i] (N/m) between nodes i-1 and i; Rayleigh damping
    C = alpha M + beta K (rayleigh = (alpha 1/s, beta s)) or the modal
    damping ratio zeta in every mode (ShearFrame's `modal`, OpenSees'
    modalDamping over all n modes).
    """
    def build(ops):
        ops.model("basic", "-ndm", 1, "-ndf", 1)
        ops.node(0, 0.0)
        ops.fix(0, 1)
        for i, (mi, ki) in enumerate(zip(m, k), start=1):
            ops.node(i, 0.0)
            ops.mass(i, mi)
            ops.uniaxialMaterial("Elastic", i, ki)
            ops.element("zeroLength", i, i - 1, i, "-mat", i, "-dir", 1, "-doRayleigh", 1)
        if zeta is not None:
            ops.eigen("-fullGenLapack", len(m))
            ops.modalDamping(zeta)
        else:
            ops.rayleigh(rayleigh[0], 0.0, rayleigh[1], 0.0)

    return build
