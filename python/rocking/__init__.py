"""RockingBlock from Python: drive RockingBlock.fmu (target/fmu/RockingBlock.fmu,
built by `cargo xtask fmu`) through fmpy, read strong-motion records, and the
`rocking` command line.

    from rocking import RockingFMU, run_grid, dharahara_cases
    from rocking import groundmotion as gm
    df = run_grid(dharahara_cases(), records=[gm.katnp_standin()], workers=2)

- `groundmotion`: readers for strong-motion records (CSMIP V2, GeoNet V2A, USGS SMC,
  PEER AT2, plain ASCII, CSV) -> `Record` (acc in m/s²);
- `fmu`: `RockingFMU` (one extraction, enumeration names, `simulate` -> `Run`);
- `parametric`: `run_grid` (cases x records x scales -> pandas DataFrame);
- `cases`: the Dharahara Tower (docs/model.md §4) and the blocks of the paper's Fig. 15;
- `presets`: those cases by name (`dharahara-F170-fm5`, `fig15-alpha0.20-costa`, ...);
- `fragility`: IDA (hunt-and-fill) and multiple stripes on Dask, lognormal fragility fits;
- `cli`: the `rocking` command (simulate, sweep, ida, msa, info, record, corner);
- `paths`: where the repository's records and FMU are.
"""

from . import groundmotion
from .cases import dharahara_cases, dharahara_tower, fig15_block
from .fmu import DEFAULT_FMU, DEFAULT_OUTPUTS, FMUError, RockingFMU, Run
from .parametric import run_grid

__all__ = ["DEFAULT_FMU", "DEFAULT_OUTPUTS", "FMUError", "RockingFMU", "Run", "dharahara_cases",
           "dharahara_tower", "fig15_block", "groundmotion", "run_grid"]
