"""The parser of the `rocking` command, built from the subcommand modules that
`COMMANDS` (in this package's __init__) names, and `main`: one line per error."""

import argparse
import importlib
import os
import sys
import warnings

from .common import PROG, CLIError, _Parser, split_parameters


def commands():
    """{subcommand name: its module}, in the order of COMMANDS."""
    from . import COMMANDS
    return {name: importlib.import_module(f".{name}", __package__) for name in COMMANDS}


def build_parser(modules=None):
    common = _Parser(add_help=False)
    common.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                        help="show the traceback of an error instead of one line")

    parser = _Parser(prog=PROG, description="RockingBlock: a rigid body rocking on a flexible, crushing "
                     "interface (an FMI 2.0 FMU), from the command line.",
                     epilog="`rocking COMMAND --help` for each command. Errors: one line on stderr, exit status 2.")
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error instead of one line")
    parser.add_argument("--version", action=_Version, help="the package version, the FMU's GUID and the commit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for module in (commands() if modules is None else modules).values():
        module.register(sub, common)
    return parser


def version_text():
    """`rocking VERSION, RockingBlock.fmu GUID {...} (PATH), commit SHA`: what --version prints."""
    from importlib.metadata import PackageNotFoundError, version
    from zipfile import BadZipFile, ZipFile
    from xml.etree import ElementTree

    from .. import paths
    try:
        package = version("rocking")
    except PackageNotFoundError:
        package = "unknown"
    try:
        fmu = paths.default_fmu()
        with ZipFile(fmu) as archive:
            guid = ElementTree.fromstring(archive.read("modelDescription.xml")).get("guid")
        fmu_text = f"RockingBlock.fmu GUID {guid} ({fmu})"
    except (OSError, KeyError, BadZipFile, ElementTree.ParseError) as exc:
        fmu_text = f"RockingBlock.fmu not found ({_one_line(exc)})"
    return f"{PROG} {package}, {fmu_text}, commit {paths.build_info()['commit']}"


class _Version(argparse.Action):
    """--version: computed when asked (it opens the FMU and may ask git), then exit 0."""

    def __init__(self, option_strings, dest, **kwargs):
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        print(version_text())
        parser.exit(0)


def _one_line(exc):
    text = str(exc) if not isinstance(exc, KeyError) or not exc.args else str(exc.args[0])
    return " ".join(text.split()) or type(exc).__name__


def _warnings_in_one_line(where):
    """Warnings (an implausible record, a shifted time column) as one line each on stderr."""
    def show(message, category, filename, lineno, file=None, line=None):
        print(f"{where}: warning: {' '.join(str(message).split())}", file=sys.stderr)
    warnings.showwarning = show


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    command = next((a for a in argv if not a.startswith("-")), None)
    _warnings_in_one_line(f"{PROG} {command}" if command else PROG)
    try:
        modules = commands()
        module = modules.get(command)
        if hasattr(module, "forward"):
            return module.forward(argv[argv.index(command) + 1:])
        parser = build_parser(modules)
        params = []
        if getattr(module, "TAKES_PARAMETERS", False):
            own = parser._subparsers._group_actions[0].choices[command]
            known = set(own._option_string_actions) | set(parser._option_string_actions)
            argv, params = split_parameters(argv, known)
        args = parser.parse_args(argv)
        if args.command is None:
            parser.print_help()
            return 2
        return args.func(args, params)
    except BrokenPipeError:  # e.g. `rocking info | head`: the reader went away
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    except SystemExit:
        raise
    except BaseException as exc:  # noqa: BLE001 - every error is one line unless --debug
        if debug:
            raise
        where = f"{PROG} {command}" if command else PROG
        kind = "" if isinstance(exc, (CLIError, OSError, ValueError, KeyError)) else f"{type(exc).__name__}: "
        if type(exc).__name__ == "FMUError":
            kind = ""  # it leads with the parameter and says it was the FMU
        if isinstance(exc, OSError) and exc.filename and str(exc.filename) not in str(exc):
            kind = f"{exc.filename}: "
        print(f"{where}: error: {kind}{_one_line(exc)}", file=sys.stderr)
        return 2

