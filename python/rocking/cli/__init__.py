"""The `rocking` command.

    rocking simulate [RECORD] [--scale 1.5] [--component LABEL] [--preset NAME]
                     [--PARAM VALUE ...] [--fmu PATH] --out DIR
    rocking sweep CASES.toml --records DIR [--scales 0.5:3:0.25] --out results.parquet
    rocking map [--preset NAME] [--PARAM VALUE ...] --frequencies F --amplitudes A --out DIR   (overturning maps)
    rocking space RECORD [--azimuth DEG] [--compare] [--preset NAME] --out DIR   (a round body in space)
    rocking ida|msa SUITE_OR_TOML [--preset NAME] [--im PGV] --out DIR   (fragility on Dask)
    rocking info [--presets]
    rocking record FILE [--plot out.png]
    rocking corner ARGS...          (the Rust binary rocking-corner)
    rocking corner-blocks lp|dem|draw|study ...   (the corner block by block)
    rocking cosim CASE.toml --out DIR   (a block on a floor of a shear frame, co-simulated)
    rocking examples DIR [--force]      (the records and the example studies, copied into DIR)

Errors are one line on stderr naming the file, the variable or the parameter,
with exit status 2; `--debug` shows the traceback instead.

One module per subcommand, named as the subcommand, with `register(sub, common)` that
adds its argparse subparser and `set_defaults(func=cmd_NAME)`, where
`cmd_NAME(args, params) -> exit status`. Optional module attributes:
`TAKES_PARAMETERS = True` passes `--NAME VALUE` pairs of FMU parameters to cmd_NAME as
`params`; `forward(argv)` takes the arguments untouched instead of argparse (`corner`).
Shared helpers (CLIError, the FMU, parameters, records) are in `common`; the parser and
`main` in `main`.
"""

#: The subcommands, in the order `rocking --help` lists them; each is a module of this
#: package. Registering a new subcommand is one line here (its module, e.g. "cosim").
COMMANDS = (
    "simulate",
    "sweep",
    "map",
    "spectrum",
    "space",
    "info",
    "record",
    "ida",  # registers both `ida` and `msa`
    "corner",
    "corner_blocks",  # `rocking corner-blocks`
    "cosim",
    "examples",
)

from .common import CLIError  # noqa: E402 - after COMMANDS, which .main reads
from .main import main  # noqa: E402

__all__ = ["COMMANDS", "CLIError", "main"]
