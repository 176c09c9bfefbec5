"""What the subcommands share: the one-line error, where the FMU is, parameters by name
checked against its modelDescription, and reading records."""

import argparse
import math
import re
from pathlib import Path

from .. import paths

PROG = "rocking"
#: True for a wheel user and in a clone alike: paths.default_fmu() is the bundled FMU or the clone's.
FMU_HELP = ("the FMU (default: the RockingBlock.fmu an installed wheel carries; in a clone "
            "target/fmu/RockingBlock.fmu, written by `cargo xtask fmu`)")


class CLIError(Exception):
    """A mistake in what was asked: reported as one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    """argparse whose usage errors are one line (the CLIError handler prints it)."""

    def error(self, message):
        raise CLIError(f"{message} (`{self.prog} --help`)")


def seconds(minimum, strict):
    """An argparse type: a finite number of seconds above `minimum` (or at least it, if not
    `strict`); the usage error names the option and the bound."""
    def convert(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r}: not a number of seconds") from None
        if not math.isfinite(value) or value < minimum or (strict and value == minimum):
            raise argparse.ArgumentTypeError(f"{text!r}: must be {'>' if strict else '>='} {minimum:g} s")
        return value
    convert.__name__ = "seconds"
    return convert


# ---------------------------------------------------------------------------
# Where things are

def fmu_path(arg):
    """--fmu, else the wheel's bundled RockingBlock.fmu or the clone's target/fmu/RockingBlock.fmu."""
    if arg:
        path = Path(arg)
        if not path.is_file():
            raise CLIError(f"{path}: no such FMU file")
        return path
    if paths.REPO is None:
        raise CLIError("no --fmu given and " + paths._NOT_IN_REPO)
    path = paths.default_fmu()
    if not path.is_file():
        build = "this wheel does not carry it" if paths.BUNDLE is not None else "run `cargo xtask fmu` in the clone"
        raise CLIError(f"{path} does not exist: {build} (or pass --fmu PATH)")
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
        from ..fmu import did_you_mean
        raise CLIError(f"{where}: unknown parameter {name!r}{did_you_mean(name, list(table))} "
                       "(`rocking info` lists them)")
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


def parameters_of_items(fmu):
    """{enumeration parameter: {item: the parameters it uses}}, read from the enumeration's
    description in modelDescription.xml, e.g. "elastic no-tension Winkler bed (kn),
    elastoPlastic (kn, crushing at fm)": the settable names in the parentheses after an item."""
    names = set(settable(fmu))
    out = {}
    for enum, items in fmu.enumerations.items():
        text = fmu.variables[enum].description or ""
        spots = sorted((m.start(), m.end(), item) for item in items
                       for m in re.finditer(rf"\b{re.escape(item)}\b", text))
        uses = {}
        for k, (_, end, item) in enumerate(spots):
            segment = text[end:spots[k + 1][0] if k + 1 < len(spots) else len(text)]
            # a parenthesis after a blank: "sgn(theta)" in restraint's is a formula, not a list;
            # an enumeration named in one ("(restitution eRestraint)") is a word, not a use
            inner = re.search(r"(?:^|\s)\(([^)]*)\)", segment)
            words = set(re.findall(r"[A-Za-z]\w*", inner.group(1))) if inner else set()
            uses.setdefault(item, set()).update(words & names - set(fmu.enumerations))
        out[enum] = uses
    return out


def unused_parameters(fmu, params):
    """{name: why} of the parameters in `params` that the enumerations chosen (given, else the
    FMU's defaults) do not use, e.g. {"kn": "not used by interface = rigid"}."""
    unused = {}
    for enum, uses in parameters_of_items(fmu).items():
        chosen = params.get(enum)
        if chosen is None:
            start = fmu.variables[enum].start
            chosen = next((i for i, v in fmu.enumerations[enum].items() if str(v) == str(start)), None)
        if chosen not in uses:
            continue
        others = set().union(*uses.values()) - uses[chosen]
        unused.update({name: f"not used by {enum} = {chosen}" for name in params if name in others})
    return unused


def drop_unused(fmu, params, typed=None):
    """Take the parameters the chosen enumerations do not use out of `params` (so that they
    are neither set nor recorded as used): ({name: {"value", "why"}}, a note naming them as
    `typed` ({name: how the user wrote it}) does, or None)."""
    unused = unused_parameters(fmu, params)
    typed = typed or {}
    ignored = {name: {"value": params.pop(name), "why": why} for name, why in unused.items()}
    if not ignored:
        return ignored, None
    groups = {}
    for name, why in unused.items():
        groups.setdefault(why, []).append(typed.get(name, name))
    note = "; ".join(f"{', '.join(names)} ignored: {why}" for why, names in groups.items())
    return ignored, note + " (not set; recorded as ignored, not as used)"


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

def add_record_options(parser):
    """--units and --fmt, for the files whose header does not say (the readers' units=, fmt=)."""
    from ..groundmotion.detect import READERS
    parser.add_argument("--units", help="units of the record's numbers, over what the file states "
                        "(g, m/s2, cm/s2, mm/s2 or a common spelling)")
    parser.add_argument("--fmt", choices=list(READERS), help="the record's format, when it cannot be "
                        "told from the file's first lines or extension")


def read_components(path, units=None, fmt=None):
    """(every component of `path` as Records, format name): gm.read_all with --units, --fmt."""
    from .. import groundmotion as gm
    fmt = fmt or gm.detect_format(path)
    try:
        return gm.read_all(path, units=units, fmt=fmt), fmt
    except ValueError as exc:
        if units is not None and "units" in str(exc) and not isinstance(exc, gm.GroundMotionFormatError):
            raise CLIError(f"--units {units}: {exc}") from None
        raise


def read_record(path, component=None, units=None, fmt=None):
    """(Record, format name) of `path`; component by label, else by index."""
    from ..groundmotion.detect import select
    path = Path(path)
    if not path.exists():
        raise CLIError(f"{path}: no such record file")
    if path.is_dir():
        raise CLIError(f"{path}: is a folder, not a record file")
    records, fmt = read_components(path, units, fmt)
    if component is None:
        return records[0], fmt
    try:
        return select(records, component, path), fmt
    except ValueError as exc:
        if re.fullmatch(r"-?\d+", component):
            try:
                return select(records, int(component), path), fmt
            except ValueError:
                pass
        if fmt == "csv":
            raise CLIError(f"{path}: no component {component!r}: a CSV record holds one component, "
                           f"the acceleration column of its header ({_csv_columns(path)}); "
                           "leave out --component") from None
        raise CLIError(str(exc)) from None


def _csv_columns(path):
    """The header row of a CSV record, for a message."""
    for line in Path(path).read_text(errors="replace").splitlines():
        if line.strip() and not line.startswith("#"):
            return "columns " + ", ".join(repr(c.strip()) for c in line.split(","))
    return "no header row"


def horizontal_record(path, component=None, units=None, fmt=None):
    """(Record, format name) as `read_record` (no component: the file's first horizontal one),
    refusing a vertical component in one line: the FMU's input ag is the horizontal ground
    acceleration."""
    rec, fmt = read_record(path, component, units, fmt)
    if rec.vertical:
        others = [r.component for r in read_components(path, units, fmt)[0] if not r.vertical]
        if component is None and others:
            return read_record(path, others[0], units, fmt)
        choose = (f"choose a horizontal one: --component {' or '.join(others)}" if others
                  else "the file holds no horizontal component")
        raise CLIError(f"{path} [{rec.component}]: a vertical component, and ag is the horizontal ground "
                       f"acceleration (a vertical component goes to the input av: simulate --vertical, "
                       f"vertical = true in cases and studies); {choose}")
    return rec, fmt


def vertical_record(spec, rec, units=None, fmt=None):
    """(Record, format name) of the vertical ground acceleration `av` that --vertical names.

    spec "auto": the vertical component of `rec`'s record set (same station and event, the
    file or its sibling files), by the orientation its header gives; "FILE[:COMPONENT]": that
    file's component, by default its vertical one (its only one for a one-component file).
    A component the file calls horizontal is refused, and so is "auto" without a vertical."""
    from .. import groundmotion as gm
    if spec == "auto":
        if rec is None:
            raise CLIError("--vertical auto: finds the vertical component of the RECORD's set: give a RECORD")
        try:
            found = gm.vertical_of(rec, units=units)
        except ValueError as exc:
            raise CLIError(f"--vertical auto: {exc}") from None
        if found is None:
            labels = ", ".join(r.component or "(unlabelled)" for r in gm.components(rec.source, units=units))
            raise CLIError(f"--vertical auto: {rec.source} has no vertical component in its record set "
                           f"({labels}); give one as --vertical FILE[:COMPONENT]")
        return found, gm.detect_format(found.source)
    path, component = spec, None
    if not Path(spec).exists() and ":" in spec:
        path, component = spec.rsplit(":", 1)
    if component is None:
        records, _ = read_components(path, units, fmt) if Path(path).is_file() else ([], None)
        verticals = [r.component for r in records if r.vertical]
        component = verticals[0] if verticals else None
    vert, vfmt = read_record(path, component, units, fmt)
    if not vert.vertical and str(vert.component).strip():
        raise CLIError(f"--vertical {spec}: {path} [{vert.component}] is a horizontal component by its "
                       "header; av is the vertical ground acceleration")
    return vert, vfmt


def record_facts(rec):
    return dict(npts=rec.npts, dt_s=rec.dt, duration_s=rec.duration, pga_m_s2=rec.pga,
                pga_g=rec.pga_g, t_pga_s=float(rec.time[int(abs(rec.acc).argmax())]),
                pgv_cm_s=rec.pgv * 100)

