#!/usr/bin/env python3
"""Reads valgrind memcheck XML (--xml=yes) of a host process (CPython with
numpy, fmpy...) and counts only the errors that concern the FMU: those with a
frame of the FMU's binary or crates in any of their stacks (the error's own
stack, and with --track-origins=yes the origin's). Everything else (CPython,
numpy, lxml, the dynamic loader) is tallied by kind and top object, not
counted.

    tools/memcheck_ours.py FILE.xml [FILE.xml ...]

Exit status 1 if any error or definite/indirect leak concerns the FMU.
"""

import collections
import re
import sys
import xml.etree.ElementTree as ET

# The FMU's binary (RockingBlock.so in the archive, libfmu_rocking.so) and
# its crates' symbols.
OURS = re.compile(r"RockingBlock|fmu_rocking|fmi2_export|\brocking::|model_description")
COUNTED = {"Leak_DefinitelyLost", "Leak_IndirectlyLost"}  # leak kinds that count


def frames(error):
    for stack in error.findall("stack"):
        for f in stack.findall("frame"):
            yield (f.findtext("obj") or "", f.findtext("fn") or "",
                   f.findtext("file") or "", f.findtext("line") or "")


def what(error):
    x = error.find("xwhat/text")
    return x.text if x is not None else error.findtext("what")


def main(paths):
    ours, others = [], collections.Counter()
    for path in paths:
        root = ET.parse(path).getroot()
        for e in root.iter("error"):
            kind = e.findtext("kind")
            fs = list(frames(e))
            mine = any(OURS.search(o) or OURS.search(fn) for o, fn, _, _ in fs)
            counted = not kind.startswith("Leak_") or kind in COUNTED
            if mine and counted:
                ours.append((kind, what(e), fs))
            else:
                top = next((o.rsplit("/", 1)[-1] for o, _, _, _ in fs
                            if o and "vgpreload" not in o), "?")
                others[(kind, top)] += 1
    print(f"errors concerning the FMU: {len(ours)}")
    for kind, w, fs in ours:
        print(f"\n{kind}: {w}")
        for o, fn, file, line in fs[:30]:
            print(f"      at {o.rsplit('/', 1)[-1]:<32} {fn} {file}:{line}")
    print(f"\nnot concerning the FMU (not counted): {sum(others.values())}")
    for (kind, top), n in sorted(others.items(), key=lambda x: -x[1]):
        print(f"  {n:5d}  {kind:<22} {top}")
    return 1 if ours else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
