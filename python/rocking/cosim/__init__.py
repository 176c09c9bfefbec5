"""Co-simulation of RockingBlock.fmu on a floor of ShearFrame.fmu (issue 13,
docs/cosimulation.md).

- `master`: `CoupledFMUs.run` (Jacobi / Gauss-Seidel, constant or extrapolated
  inputs, one- or two-way, step rejection) -> `CosimResult`; `frame_params`,
  `sine_ground`, `record_ground`;
- `reference`: the monolithic coupled equations of an elastic solid-rectangle
  block on the frame, one SciPy integrator at tight tolerance (independent of
  the FMUs) -> `Reference`;
- `study`: convergence and one-way/two-way sweeps, plots for the docs
  (`python -m rocking.cosim.study`);
- `command`: `rocking cosim CASE.toml`.
"""

from .master import (COUPLINGS, INPUTS, SCHEMES, CosimResult, CoupledFMUs, frame_params,
                     record_ground, sine_ground)

__all__ = ["COUPLINGS", "INPUTS", "SCHEMES", "CosimResult", "CoupledFMUs", "frame_params",
           "record_ground", "sine_ground"]
