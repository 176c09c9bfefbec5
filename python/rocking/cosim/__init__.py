"""Co-simulation of RockingBlock.fmu on a floor of ShearFrame.fmu (issue 13,
docs/cosimulation.md).

- `master`: `CoupledFMUs.run` (Jacobi / Gauss-Seidel, constant or extrapolated
  inputs, one- or two-way, step rejection; FMI 2.0 or 3.0 FMUs, early return
  with 3.0) -> `CosimResult`; `frame_params`, `sine_ground`, `record_ground`;
- `slave` / `slave3`: one FMI 2.0 / 3.0 co-simulation FMU by variable name;
- `reference`: the monolithic coupled equations of an elastic solid-rectangle
  block on the frame, one SciPy integrator at tight tolerance (independent of
  the FMUs) -> `Reference`;
- `study`: convergence and one-way/two-way sweeps, plots for the docs
  (`python -m rocking.cosim.study`);
- the command `rocking cosim CASE.toml` is rocking/cli/cosim.py.
"""

__all__ = ["COUPLINGS", "INPUTS", "SCHEMES", "CosimResult", "CoupledFMUs", "frame_params",
           "record_ground", "sine_ground"]


def __getattr__(name):
    # lazy: rocking.cosim.reference and .study are usable without loading fmpy
    if name in __all__:
        from . import master
        return getattr(master, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
