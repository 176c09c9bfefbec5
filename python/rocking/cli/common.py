"""What the subcommands share: the one-line error, where the FMU is, parameters by name
checked against its modelDescription, and reading records."""

import argparse
import difflib
import math
import re
from pathlib import Path

from .. import paths

PROG = "rocking"
FMU_HELP = "the FMU (default: target/fmu/RockingBlock.fmu of the repository, built by `cargo xtask fmu`)"


class CLIError(Exception):
    """A mistake in what was asked: reported as one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    """argparse whose usage errors are one line (the CLIError handler prints it)."""

    def error(self, message):
        raise CLIError(f"{message} (`{self.prog} --help`)")


# ---------------------------------------------------------------------------
# Where things are

def fmu_path(arg):
    """--fmu, else target/fmu/RockingBlock.fmu of the repository."""
    if arg:
        path = Path(arg)
        if not path.is_file():
            raise CLIError(f"{path}: no such FMU file")
        return path
    if paths.REPO is None:
        raise CLIError("no --fmu given and " + paths._NOT_IN_REPO)
    path = paths.default_fmu()
    if not path.is_file():
        raise CLIError(f"{path} does not exist: run `cargo xtask fmu` (or pass --fmu PATH)")
    return path


def open_fmu(arg):
    from ..fmu import RockingFMU
    return RockingFMU(fmu_path(arg))


# ---------------------------------------------------------------------------
# Parameters by name, checked against the FMU's modelDescription

def settable(fmu):
    """{name: variable} of what a user may give: the parameters, and the outputs whose
    start value is the initial condition (theta, omega)."""
    return {name: v for name, v in fmu.variables.items()
            if v.causality == "parameter" or (v.causality == "output" and v.initial == "exact")}


def unit_of(v):
    return v.unit or (v.declaredType.unit if v.declaredType is not None else None) or ""


def read_params_file(path):
    """Parameters from a JSON file of name -> value (enumerations by item name), as
    `rocking-corner --body FILE` writes them; CLIError naming the file otherwise."""
    import json

    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise CLIError(f"{path}: cannot read ({exc.strerror or exc})") from None
    except json.JSONDecodeError as exc:
        raise CLIError(f"{path}: not JSON ({exc.msg} at line {exc.lineno})") from None
    if not isinstance(data, dict):
        raise CLIError(f"{path}: expected a JSON object of parameter name -> value")
    return data


def check_parameter(fmu, name, value, where):
    """`value` (a string from the command line, or a TOML value) converted for the FMU
    variable `name`; CLIError naming `where` (e.g. '--kn' or 'cases.soft.kn') if the name or
    the value does not fit. Enumerations are returned by item name."""
    table = settable(fmu)
    if name not in table:
        if name in fmu.variables:
            v = fmu.variables[name]
            raise CLIError(f"{where}: {name} is a{'n' if v.causality[0] in 'aeiou' else ''} "
                           f"{v.causality} of the FMU, not something that can be set")
        close = difflib.get_close_matches(name, table, n=3, cutoff=0.5)
        close += [n for n in table if n.lower() == name.lower() and n not in close]
        hint = f"; did you mean {', '.join(close)}?" if close else ""
        raise CLIError(f"{where}: unknown parameter {name!r}{hint} (`rocking info` lists them)")
    v = table[name]
    text = value if isinstance(value, str) else None
    unit = unit_of(v)
    what = f"{name} is a {v.type} {v.causality}" + (f" in {unit}" if unit else "")
    if v.type == "Enumeration":
        items = fmu.enumerations.get(name, {})
        if isinstance(value, bool):
            raise CLIError(f"{where} {value!r}: {what}, one of {', '.join(items)}")
        if isinstance(value, int):
            by_value = {val: item for item, val in items.items()}
            if value in by_value:
                return by_value[value]
        elif text is not None:
            if text in items:
                return text
            if text.strip().lstrip("-").isdigit() and int(text) in items.values():
                return next(item for item, val in items.items() if val == int(text))
            folded = [item for item in items if item.lower() == text.lower()]
            if folded:
                return folded[0]
        raise CLIError(f"{where} {value!r}: not one of {', '.join(items)} ({name})")
    if v.type == "Real":
        if isinstance(value, bool):
            raise CLIError(f"{where} {value!r}: not a number ({what})")
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise CLIError(f"{where} {value!r}: not a number ({what})") from None
        if math.isnan(number):
            raise CLIError(f"{where} {value!r}: not a number ({what})")
        return number
    if v.type == "Integer":
        try:
            if isinstance(value, bool) or (isinstance(value, float) and not value.is_integer()):
                raise ValueError
            return int(value)
        except (TypeError, ValueError):
            raise CLIError(f"{where} {value!r}: not an integer ({what})") from None
    if v.type == "Boolean":
        if isinstance(value, bool):
            return value
        if text is not None and text.lower() in ("true", "1", "yes", "false", "0", "no"):
            return text.lower() in ("true", "1", "yes")
        raise CLIError(f"{where} {value!r}: not true or false ({what})")
    raise CLIError(f"{where}: cannot set a {v.type} variable")


def split_parameters(argv, known_options):
    """Take the `--NAME VALUE` (or `--NAME=VALUE`) pairs whose NAME is not an option of the
    command out of argv: (the rest of argv, [(NAME, VALUE), ...])."""
    rest, pairs = [], []
    i = 0
    while i < len(argv):
        token = argv[i]
        head = token.split("=", 1)[0]
        if token.startswith("--") and len(token) > 2 and head not in known_options:
            name = head[2:]
            if "=" in token:
                value = token.split("=", 1)[1]
                i += 1
            else:
                if i + 1 >= len(argv):
                    raise CLIError(f"--{name}: a value is needed")
                value = argv[i + 1]
                i += 2
            pairs.append((name, value))
        else:
            rest.append(token)
            i += 1
    return rest, pairs


# ---------------------------------------------------------------------------
# Records

def read_record(path, component=None):
    """(Record, format name) of `path`; component by label, else by index."""
    from .. import groundmotion as gm
    from ..groundmotion.detect import select
    path = Path(path)
    if not path.exists():
        raise CLIError(f"{path}: no such record file")
    if path.is_dir():
        raise CLIError(f"{path}: is a folder, not a record file")
    fmt = gm.detect_format(path)
    records = gm.read_all(path, fmt=fmt)
    if component is None:
        return records[0], fmt
    try:
        return select(records, component, path), fmt
    except ValueError:
        if re.fullmatch(r"-?\d+", component):
            try:
                return select(records, int(component), path), fmt
            except ValueError:
                pass
        raise


def record_facts(rec):
    return dict(npts=rec.npts, dt_s=rec.dt, duration_s=rec.duration, pga_m_s2=rec.pga,
                pga_g=rec.pga_g, t_pga_s=float(rec.time[int(abs(rec.acc).argmax())]),
                pgv_cm_s=rec.pgv * 100)

