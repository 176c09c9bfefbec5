"""One RockingBlock.fmu, extracted once, simulated through fmpy.

    from rockingfmu import RockingFMU
    with RockingFMU() as fmu:                       # target/fmu/RockingBlock.fmu
        run = fmu.simulate({"shape": "solidRectangle", "B": 0.5, "theta": 0.1},
                           stop_time=5.0)
        run.overturned, run.t_overturn, run.peak_theta_over_alpha, run.impacts

Enumeration parameters (shape, massModel, interface, formulation, restitution)
may be given by item name ("hollowCircle") or by value; names are converted
with the FMU's own modelDescription.xml. The start values of `theta` and
`omega` are the initial conditions (MODEL.md §5).
"""

import math
import shutil
import time as _time
from dataclasses import dataclass, field
from pathlib import Path

import fmpy
import numpy as np
from numpy.lib.recfunctions import repack_fields

REPO = Path(__file__).resolve().parents[1]
#: Where `cargo xtask fmu` writes the FMU.
DEFAULT_FMU = REPO / "target" / "fmu" / "RockingBlock.fmu"

#: Outputs recorded by `simulate` unless told otherwise.
DEFAULT_OUTPUTS = ("theta", "omega", "thetaOverAlpha", "MR", "af", "regime", "impacts", "overturned")
#: Calculated parameters (MODEL.md §5), read once per run.
CALCULATED = ("mass", "weight", "R0", "alpha", "IO", "etaHousner", "thetaJo", "thetaC", "thetaOv")

_STATUS = ["OK", "WARNING", "DISCARD", "ERROR", "FATAL", "PENDING"]


class FMUError(RuntimeError):
    """An FMI call failed; the message carries what the FMU logged."""


@dataclass
class Run:
    """The result of one simulation.

    result                 structured array: 'time' and the recorded outputs
    overturned             the body overturned (the FMU discarded the step and
                           ended the run: MODEL.md §5)
    t_end                  time of the last row (the overturning time if overturned)
    t_overturn             t_end if overturned, else nan
    peak_theta_over_alpha  max |theta| / alpha over the recorded samples
    impacts                impacts at the end of the run
    calculated             the calculated parameters (alpha, thetaOv, ...)
    wall                   wall time of the run, s
    messages               what the FMU logged ("[STATUS] category: message")
    """

    result: np.ndarray
    overturned: bool
    t_end: float
    t_overturn: float
    peak_theta_over_alpha: float
    impacts: int
    calculated: dict
    wall: float
    messages: list = field(default_factory=list)


class RockingFMU:
    """RockingBlock.fmu extracted once; `simulate` runs one case.

    path      the .fmu (default target/fmu/RockingBlock.fmu)
    unzipdir  an existing extraction to use instead (not deleted by `close`);
              this is how worker processes share one extraction
    """

    def __init__(self, path=None, unzipdir=None):
        if unzipdir is not None:
            self.unzipdir = Path(unzipdir)
            self.path = Path(path) if path else None
            self._owned = False
        else:
            self.path = Path(path) if path else DEFAULT_FMU
            if not self.path.is_file():
                raise FileNotFoundError(
                    f"{self.path} does not exist: build it with `cargo xtask fmu` (or tools/main.sh)")
            self.unzipdir = Path(fmpy.extract(str(self.path)))
            self._owned = True
        self.model_description = fmpy.read_model_description(str(self.unzipdir))
        self.variables = {v.name: v for v in self.model_description.modelVariables}
        self.enumerations = {}
        for v in self.model_description.modelVariables:
            if v.type == "Enumeration" and v.declaredType is not None:
                self.enumerations[v.name] = {it.name: int(it.value) for it in v.declaredType.items}
        missing = [n for n in ("ag", "theta", "thetaOverAlpha", "overturned", "impacts", "thetaOv")
                   if n not in self.variables]
        if missing:
            raise FMUError(f"{self.path or self.unzipdir}: variables missing from modelDescription.xml: {missing}")

    # context manager: delete the extraction we made
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self._owned and self.unzipdir.exists():
            shutil.rmtree(self.unzipdir, ignore_errors=True)

    def start_values(self, params):
        """`params` with enumeration item names replaced by their values; unknown names raise."""
        out = {}
        for name, value in params.items():
            if name not in self.variables:
                raise KeyError(f"{name!r} is not a variable of the FMU")
            if name in self.enumerations and isinstance(value, str):
                items = self.enumerations[name]
                if value not in items:
                    raise ValueError(f"{name} = {value!r}: not one of {sorted(items)}")
                value = items[value]
            elif isinstance(value, (np.floating, np.integer)):
                value = value.item()
            out[name] = value
        return out

    def simulate(self, params, record=None, scale=1.0, stop_time=None, output_interval=None,
                 rtol=None, outputs=DEFAULT_OUTPUTS, ag=None):
        """Run one case and return a `Run`.

        params           parameter and start values by name (MODEL.md §5)
        record           a groundmotion Record (acc in m/s²) or None (no ground motion)
        scale            factor applied to the record's acceleration
        ag               instead of `record`: (time, acc) arrays in s and m/s²
        stop_time        default: the record's last sample (10 s without a record)
        output_interval  default: the record's dt (0.01 s without one)
        rtol             the integrator's relative tolerance (default: the FMU's)
        """
        t0 = _time.perf_counter()
        if record is not None:
            t_in, a_in, dt = record.time, record.acc, record.dt
        elif ag is not None:
            t_in, a_in = (np.asarray(x, dtype=float) for x in ag)
            dt = float(np.median(np.diff(t_in)))
        else:
            t_in = a_in = None
            dt = 0.01
        if stop_time is None:
            stop_time = float(t_in[-1]) if t_in is not None else 10.0
        if output_interval is None:
            output_interval = dt
        signals = None
        if t_in is not None:
            tt, aa = np.asarray(t_in, dtype=float), scale * np.asarray(a_in, dtype=float)
            if stop_time > tt[-1] + 1e-12:  # free motion after the record ends
                tt = np.append(tt, [tt[-1] + dt, stop_time + dt])
                aa = np.append(aa, [0.0, 0.0])
            signals = np.zeros(len(tt), dtype=[("time", float), ("ag", float)])
            signals["time"], signals["ag"] = tt, aa
        messages = []

        def logger(_component, _instance, status, category, message):
            messages.append(f"[{_STATUS[status] if 0 <= status < 6 else status}] "
                            f"{category.decode(errors='replace')}: {message.decode(errors='replace')}")

        outs = list(dict.fromkeys(list(outputs) + ["thetaOverAlpha", "impacts", "overturned"]
                                  + [c for c in CALCULATED if c in self.variables]))
        try:
            result = fmpy.simulate_fmu(
                str(self.unzipdir), validate=False, model_description=self.model_description,
                start_values=self.start_values(params), input=signals, output=outs,
                stop_time=stop_time, output_interval=output_interval,
                relative_tolerance=rtol, set_input_derivatives=signals is not None,
                logger=logger)
        except Exception as exc:  # fmpy raises FMICallException and plain Exceptions
            detail = "; ".join(messages) or "no message logged"
            raise FMUError(f"{type(exc).__name__}: {exc} (FMU log: {detail})") from exc
        wall = _time.perf_counter() - t0
        calc = {c: float(result[c][0]) for c in CALCULATED if c in result.dtype.names}
        overturned = bool(result["overturned"][-1]) or (
            result["time"][-1] < stop_time - 0.5 * output_interval)
        t_end = float(result["time"][-1])
        keep = ["time"] + [o for o in outputs if o in result.dtype.names]
        return Run(
            result=repack_fields(result[keep]),
            overturned=overturned,
            t_end=t_end,
            t_overturn=t_end if overturned else math.nan,
            peak_theta_over_alpha=float(np.max(np.abs(result["thetaOverAlpha"]))),
            impacts=int(result["impacts"][-1]),
            calculated=calc,
            wall=wall,
            messages=messages,
        )

    def calculated(self, params):
        """The calculated parameters (MODEL.md §5) after initialization, without stepping."""
        run = self.simulate(params, stop_time=0.0, output_interval=1.0, outputs=("theta",))
        return run.calculated
