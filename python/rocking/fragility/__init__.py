"""Fragility of rocking bodies: incremental dynamic analysis (hunt-and-fill) and multiple-stripe
analysis over a suite of records, on dask.distributed, with lognormal fragility fits.

- `intensity`: PGA, PGV, SA(T) (5 %, exact for the piecewise-linear record), PGA / (g tan alpha);
- `suite`: the horizontal components of the records in folders;
- `hunt`: hunt-and-fill (Vamvatsikos & Cornell 2004) and the collapse intensity of a trace;
- `fit`: lognormal fits by maximum likelihood (Baker 2015) and a bootstrap over records;
- `runner`: the runs in a worker (`run_once` is the one call of the FMU);
- `store`: the Parquet dataset of results, one file per finished task (resume by key);
- `cluster`: LocalCluster or a scheduler address, the FMU as a worker plugin, streaming;
- `study`: bodies x records -> tasks, and the rows -> fragilities;
- `plots`: IDA curves and fragility curves.

The command is `rocking ida` / `rocking msa` (rocking.cli.ida); docs/fragility.md.
"""

from .fit import Fragility, fit_capacities, fit_stripes, ida_fragility, msa_fragility
from .hunt import HuntOptions, capacity, hunt_and_fill
from .intensity import IntensityMeasure, parse, spectral_acceleration
from .study import Study
from .suite import load_suite

__all__ = ["Fragility", "HuntOptions", "IntensityMeasure", "Study", "capacity", "fit_capacities",
           "fit_stripes", "hunt_and_fill", "ida_fragility", "load_suite", "msa_fragility", "parse",
           "spectral_acceleration"]
