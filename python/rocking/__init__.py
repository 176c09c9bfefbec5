"""Drive RockingBlock.fmu (target/fmu/RockingBlock.fmu, built by `cargo xtask fmu`)
from Python through fmpy: single runs, parametric grids in parallel processes,
and the parameter sets of the paper's examples.

    from rockingfmu import RockingFMU, run_grid, dharahara_cases
    import groundmotion as gm
    df = run_grid(dharahara_cases(), records=[gm.katnp_standin()], workers=2)

- `fmu`: `RockingFMU` (one extraction, enumeration names, `simulate` -> `Run`);
- `parametric`: `run_grid` (cases x records x scales -> pandas DataFrame);
- `cases`: the Dharahara Tower (docs/model.md §4) and the blocks of the paper's Fig. 15.
"""

from .cases import dharahara_cases, dharahara_tower, fig15_block
from .fmu import DEFAULT_FMU, DEFAULT_OUTPUTS, FMUError, RockingFMU, Run
from .parametric import run_grid

__all__ = ["DEFAULT_FMU", "DEFAULT_OUTPUTS", "FMUError", "RockingFMU", "Run", "dharahara_cases",
           "dharahara_tower", "fig15_block", "run_grid"]
