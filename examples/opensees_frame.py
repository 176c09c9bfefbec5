"""A rocking block on the roof of a 3-storey steel frame with nonlinear columns (OpenSees).

The frame is built in OpenSees (openseespy) by `build` below and stepped by
`rocking.cosim.opensees.OpenSeesStructure`; RockingBlock.fmu (the default
masonry prism, 2250 kg) stands on the roof and is coupled two-way with the
Jacobi master of `rocking.cosim.hostloop`: the roof's absolute acceleration
drives the block, the block's support forces (opposite sign) load the roof.

Frame: one bay of 6 m, storeys of 3.5 m; columns are force-based beam-columns
with fibre sections (a W-shape of Steel02, fy = 355 MPa, with 1 % hardening)
and P-Delta; beams are elastic; each floor carries 30 t (lumped at the two
beam-column joints), the gravity loads are applied first and held; Rayleigh
damping of 5 % in the first two modes.

    python examples/opensees_frame.py [--scale 3.0] [--plot out.png]

prints the frame's periods, the peak roof acceleration, the peak drift, the
block's peak rotation and whether the columns yielded, for the frame with and
without the block (one-way: the block driven by the bare frame's roof).
"""

import argparse
import math

import numpy as np

from rocking import groundmotion as gm
from rocking.cosim import opensees as osa
from rocking.cosim.hostloop import couple, open_block

BAY, STOREY, FLOORS = 6.0, 3.5, 3
FLOOR_MASS = 30e3  # kg per floor
FY, E = 355e6, 200e9
G = 9.81
ROOF_NODE = 10 * FLOORS + 1  # the left joint of the roof: the block stands there


def w_section(ops, tag, d=0.3, bf=0.3, tf=0.015, tw=0.010):
    """A W-shape of Steel02 fibres, bent about its strong axis (m)."""
    ops.uniaxialMaterial("Steel02", tag, FY, E, 0.01, 20.0, 0.925, 0.15)
    ops.section("Fiber", tag)
    hw = d / 2 - tf
    ops.patch("rect", tag, 2, 12, -hw, -tw / 2, hw, tw / 2)
    ops.patch("rect", tag, 2, 4, hw, -bf / 2, d / 2, bf / 2)
    ops.patch("rect", tag, 2, 4, -d / 2, -bf / 2, -hw, bf / 2)


def build(ops, weight_on_roof=0.0):
    """The frame, gravity applied and held at time 0; node 10 j + 1 is floor j's left joint."""
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    for j in range(FLOORS + 1):
        for side, x in ((1, 0.0), (2, BAY)):
            ops.node(10 * j + side, x, j * STOREY)
            if j == 0:
                ops.fix(10 * j + side, 1, 1, 1)
            else:
                ops.mass(10 * j + side, FLOOR_MASS / 2, FLOOR_MASS / 2, 0.0)
    w_section(ops, 1)
    ops.geomTransf("PDelta", 1)
    ops.geomTransf("Linear", 2)
    ops.beamIntegration("Lobatto", 1, 1, 5)
    for j in range(1, FLOORS + 1):
        for side in (1, 2):
            ops.element("forceBeamColumn", 100 * j + side, 10 * (j - 1) + side, 10 * j + side, 1, 1)
        # beams: a stiff elastic W-shape (A, E, I)
        ops.element("elasticBeamColumn", 100 * j + 9, 10 * j + 1, 10 * j + 2, 0.02, E, 5e-4, 2)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for j in range(1, FLOORS + 1):
        for side in (1, 2):
            extra = weight_on_roof if (j == FLOORS and side == 1) else 0.0
            ops.load(10 * j + side, 0.0, -FLOOR_MASS / 2 * G - extra, 0.0)
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("UmfPack")
    ops.test("NormDispIncr", 1e-10, 20)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    if ops.analyze(10) != 0:
        raise RuntimeError("the gravity analysis failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()
    omega2 = ops.eigen(2)
    w1, w2 = math.sqrt(omega2[0]), math.sqrt(omega2[1])
    zeta = 0.05
    ops.rayleigh(2 * zeta * w1 * w2 / (w1 + w2), 0.0, 0.0, 2 * zeta / (w1 + w2))
    build.periods = [2 * math.pi / w1, 2 * math.pi / w2]


def column_yielded(ops):
    """True if any column fibre has strained past yield (eps > fy / E)."""
    for j in range(1, FLOORS + 1):
        for side in (1, 2):
            for ip in (1, 5):
                d = ops.eleResponse(100 * j + side, "section", ip, "deformation")
                # axial strain and curvature at the extreme fibre (d/2 = 0.15 m)
                if abs(d[0]) + 0.15 * abs(d[1]) > FY / E:
                    return True
    return False


class PeakTracker:
    """Wraps the structure to record the roof drift and whether the columns yield."""

    def __init__(self, inner):
        self.inner, self.peak_drift, self.yielded = inner, 0.0, False

    def floor_acceleration(self):
        return self.inner.floor_acceleration()

    def step(self, *args):
        self.inner.step(*args)
        ops = self.inner.ops
        self.peak_drift = max(self.peak_drift, abs(ops.nodeDisp(ROOF_NODE, 1)) / (FLOORS * STOREY))
        self.yielded = self.yielded or column_yielded(ops)


def run(scale=3.0, h=0.01, t_end=20.0, two_way=True, fmu=None):
    """One coupled run; returns (Coupled, PeakTracker, periods)."""
    rec = gm.katnp()
    keep = rec.time <= t_end + 1e-9
    record_t, record_ag = rec.time[keep], scale * rec.acc[keep]
    block = open_block(fmu=fmu)
    weight = block.get(block.refs(["weight"]))[0]

    def frame(ops):
        build(ops, weight_on_roof=weight if two_way else 0.0)

    tracker = PeakTracker(osa.OpenSeesStructure(frame, ROOF_NODE, record_t, record_ag, dof_x=1,
                                                dof_z=2 if two_way else None, block_weight=weight,
                                                substeps=4))
    result = couple(tracker if two_way else _OneWay(tracker), block, record_t, record_ag, h, t_end)
    block.close()
    tracker.inner.close()
    return result, tracker, build.periods


class _OneWay:
    """The frame without the block's forces (one-way coupling)."""

    def __init__(self, tracker):
        self.tracker = tracker

    def floor_acceleration(self):
        return self.tracker.floor_acceleration()

    def step(self, t, h, ag0, dag, *_forces):
        self.tracker.step(t, h, ag0, dag, 0.0, 0.0, 0.0, 0.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scale", type=float, default=3.0, help="factor on the KATNP stand-in record")
    parser.add_argument("--t-end", type=float, default=20.0, help="end time (s)")
    parser.add_argument("--plot", help="write a plot of both runs to this PNG file")
    args = parser.parse_args()
    runs = {}
    for two_way in (True, False):
        result, tracker, periods = run(args.scale, t_end=args.t_end, two_way=two_way)
        label = "two-way" if two_way else "one-way"
        runs[label] = result
        print(f"{label}: periods {periods[0]:.3f} s, {periods[1]:.3f} s; peak roof acceleration "
              f"{np.abs(result.a_floor).max():.2f} m/s2; peak roof drift ratio {tracker.peak_drift:.4f}; "
              f"columns yielded: {tracker.yielded}; peak |theta| {np.abs(result.theta).max():.4f} rad; "
              f"overturned: " + (f"at {result.t_end:.2f} s" if result.overturned else "no"))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(8, 5.5))
        for label, r in runs.items():
            ax1.plot(r.t, r.a_floor, lw=0.8, label=label)
            ax2.plot(r.t, r.theta, lw=0.8, label=label)
        ax1.set_ylabel("roof acceleration (m/s2)")
        ax2.set_ylabel("block rotation theta (rad)")
        ax2.set_xlabel("t (s)")
        ax1.legend()
        ax1.set_title(f"3-storey steel frame (OpenSees, nonlinear columns) + RockingBlock, KATNP x {args.scale}")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)


if __name__ == "__main__":
    main()
