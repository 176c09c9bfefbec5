"""Fragility of rocking bodies: incremental dynamic analysis (each record's first collapse) and multiple-stripe
analysis over a suite of records, on dask.distributed, with lognormal fragility fits.

- `intensity`: PGA, PGV, SA(T) (5 %, exact for the piecewise-linear record), AvgSA(T1-T2),
  PGA / (g tan alpha), PGV / (g tan alpha / p);
- `suite`: the horizontal components of the records in folders;
- `hunt`: hunt, scan and bracket for each record's first collapse and the first intensity
  of each damage state, the IDA curve interpolated at a threshold, and what a spent run
  budget left unresolved;
- `fit`: lognormal fits by maximum likelihood (Baker 2015) or moments, `Undetermined` where the
  data fix none, a bootstrap over stations or records, goodness of fit;
- `risk`: hazard curve -> mean annual frequency of collapse (in closed form on each power-law
  piece of the curve), P in 50 years, margin ratio;
- `runner`: the runs in a worker (`run_once` is the one call of the FMU);
- `store`: the Parquet dataset of results, one file per finished task (resume by key);
- `cluster`: LocalCluster or a scheduler address, the FMU as a worker plugin, streaming;
- `study`: bodies x records -> tasks (batched), and the rows -> fragilities of overturning
  and damage states;
- `plots`: IDA curves and fragility curves.

The command is `rocking ida` / `rocking msa` (rocking.cli.ida); docs/fragility.md.
"""

from .fit import Fragility, Undetermined, fit_capacities, fit_stripes, ida_fragility, msa_fragility
from .hunt import HuntOptions, capacity, hunt_and_fill, interpolated, unresolved
from .intensity import IntensityMeasure, parse, spectral_acceleration
from .study import Study
from .suite import load_suite

__all__ = ["Fragility", "HuntOptions", "IntensityMeasure", "Study", "Undetermined", "capacity",
           "fit_capacities", "fit_stripes", "hunt_and_fill", "ida_fragility", "interpolated", "load_suite",
           "msa_fragility", "parse", "spectral_acceleration", "unresolved"]
