"""`rocking examples DIR`: the record folders and the example study files, copied where the user works.

    rocking examples my-study            # my-study/data/ground-motions/..., my-study/examples/...
    rocking examples my-study --force    # overwrite files that differ from the shipped ones

The copy is laid out as a clone is (data/ground-motions, examples/), so the
study files' relative record paths (`records = ["../data/ground-motions"]` in
examples/fragility.toml) and the README's commands run from DIR as written.
From a wheel the records are the sample it carries; in a clone, every folder
of data/ground-motions. Named after what it gives, the examples and the
records they run on; `init` would promise a configuration the other commands
read, and there is none.
"""

import filecmp
import shlex
import shutil
import textwrap
from pathlib import Path

from .. import paths
from ..groundmotion.files import NOT_RECORD_FOLDERS
from .common import CLIError

#: Suffixes of the example study files copied from examples/: studies and cases (.toml), a hazard
#: curve (.csv), bodies (.json), notes (.md). The scripts there (.py, .rs) need the clone.
STUDY_SUFFIXES = {".toml", ".csv", ".json", ".md"}

#: What to run next, from DIR: records and studies the wheel carries too.
NEXT = (
    "rocking simulate data/ground-motions/katnp-standin/KATNP_NS_standin.csv --preset dharahara-F170-fm5 "
    "--scale 1.5 --out out/sim",
    "rocking sweep examples/sweep.toml --records data/ground-motions/usgs-lomaprieta-1989 --scales 0.5:2:0.5 "
    "--out out/sweep.parquet",
    "rocking ida examples/fragility.toml --out out/fragility-ida",
    "rocking msa examples/fragility.toml --out out/fragility-msa",
    "rocking cosim examples/cosim/roof_block.toml --out out/cosim",
)


def _skipped(path, base):
    """Caches and hidden files: never copied."""
    return any(part.startswith(".") or part in NOT_RECORD_FOLDERS for part in path.relative_to(base).parts)


def planned():
    """[(source file, path relative to DIR)]: every file of data/ground-motions, and the study
    files of examples/. FileNotFoundError when this installation has neither."""
    root = paths.repo()
    plan = []
    records = paths.data_dir()
    for path in sorted(records.rglob("*")):
        if path.is_file() and not _skipped(path, records):
            plan.append((path, path.relative_to(root)))
    examples = paths.examples_dir()
    if examples.is_dir():
        for path in sorted(examples.rglob("*")):
            if path.is_file() and not _skipped(path, examples) and path.suffix.lower() in STUDY_SUFFIXES:
                plan.append((path, path.relative_to(root)))
    if not plan:
        raise FileNotFoundError(f"{root}: holds no records (data/ground-motions) nor examples to copy")
    return plan


def cmd_examples(args, _params):
    dest = Path(args.dir)
    if dest.exists() and not dest.is_dir():
        raise CLIError(f"{dest}: exists and is not a folder")
    try:
        plan = planned()
    except FileNotFoundError as exc:
        raise CLIError(str(exc)) from None
    differ = [rel for src, rel in plan if (dest / rel).exists() and not filecmp.cmp(src, dest / rel, shallow=False)]
    if differ and not args.force:
        shown = ", ".join(str(r) for r in differ[:5]) + (f" and {len(differ) - 5} more" if len(differ) > 5 else "")
        raise CLIError(f"{dest}: {len(differ)} file(s) exist and differ from the shipped ones ({shown}); "
                       "nothing written: --force overwrites them")
    wrote, same = [], 0
    for src, rel in plan:
        target = dest / rel
        if target.exists() and rel not in differ:
            same += 1
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, target)
        wrote.append(rel)
    print(f"rocking examples: {len(wrote)} file(s) written to {dest}"
          + (f" ({same} already there and the same)" if same else "")
          + (f", {len(differ)} overwritten (--force)" if differ else "") + ":")
    for line in _summary([rel for _, rel in plan]):
        print(f"  {line}")
    print(f"\nNext, from that folder (records and studies resolve relative to it):\n  cd {shlex.quote(str(dest))}")
    for command in NEXT:
        print(f"  {command}")
    return 0


def _summary(rels):
    """One line per record folder (its file count) and per study file."""
    lines, counted = [], {}
    for rel in rels:
        if rel.parts[:2] == ("data", "ground-motions") and len(rel.parts) > 3:
            folder = Path(*rel.parts[:3])
            if folder not in counted:
                counted[folder] = 0
                lines.append(folder)
            counted[folder] += 1
        else:
            lines.append(rel)
    return [f"{p.as_posix()}/ ({counted[p]} file{'' if counted[p] == 1 else 's'})" if p in counted else p.as_posix()
            for p in lines]


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    p = sub.add_parser(
        "examples", parents=[common], help="copy the records and the example studies into a folder",
        description=textwrap.fill(
            "Copy the record folders this installation carries (a wheel: a sample of data/ground-motions "
            "with its provenance README; a clone: all of it) and the example study files (examples/*.toml, "
            "cosim/, the illustrative hazard curve) into DIR, laid out as in the repository "
            "(DIR/data/ground-motions, DIR/examples), so that the study files' record paths and the "
            "README's commands run from DIR as written. Files already there and the same are left alone; "
            "files that differ are not overwritten without --force.", 100))
    p.add_argument("dir", metavar="DIR", help="the folder to copy into (created if needed)")
    p.add_argument("--force", action="store_true", help="overwrite files in DIR that differ from the shipped ones")
    p.set_defaults(func=cmd_examples)
