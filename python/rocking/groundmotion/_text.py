"""Reading text files line by line with line numbers in every error: the parts
shared by all readers (fixed-width and blank-separated numbers, units)."""

import re
import warnings
from pathlib import Path

import numpy as np

from .orientation import orientation
from .record import GroundMotionFormatError, GroundMotionWarning, Record
from .units import TO_M_S2, canonical_unit

# A Fortran-style real: 12, -3.5, .041, 1.5057E+0, 0.17D+39 (no inf, nan or underscores).
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][+-]?\d+)?")


def parse_number(text):
    """The float written in `text` (surrounding blanks allowed), or None if it is not a number."""
    s = text.strip()
    if not _NUMBER.fullmatch(s):
        return None
    return float(s.replace("D", "E").replace("d", "e"))


def _show(text, limit=60):
    text = text.strip()
    return repr(text if len(text) <= limit else text[:limit] + "...")


class TextFile:
    """The lines of a text file and a cursor; errors name the file and the line.

    Line ends may be LF or CRLF; DOS end-of-file marks (Ctrl-Z) are dropped.
    `lineno` is the 1-based number of the line most recently read.
    """

    def __init__(self, path):
        self.path = str(path)
        text = Path(path).read_bytes().decode("latin-1").replace("\x1a", "")
        self.lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
        if self.lines and self.lines[-1] == "":
            self.lines.pop()
        self.lineno = 0

    def error(self, message, line=None):
        """A GroundMotionFormatError at `line` (default: the line last read)."""
        return GroundMotionFormatError(message, self.path, self.lineno if line is None else line)

    def peek(self):
        """The next line without consuming it, or None at the end of the file."""
        return self.lines[self.lineno] if self.lineno < len(self.lines) else None

    def next_line(self, expected):
        """Consume and return the next line; at the end of the file raise an error
        saying that `expected` was expected there."""
        if self.lineno >= len(self.lines):
            raise self.error(f"expected {expected}, found the end of the file", self.lineno + 1)
        self.lineno += 1
        return self.lines[self.lineno - 1]

    def skip_blank(self):
        """Skip blank lines; True if the file ends there."""
        while self.peek() is not None and not self.peek().strip():
            self.lineno += 1
        return self.peek() is None

    def read_sections(self, read_one, what):
        """Every section of the file, each read by `read_one(self)` after the blank lines
        before it, to the end; an empty file is an error saying that `what` was expected."""
        sections = []
        while not self.skip_blank():
            sections.append(read_one(self))
        if not sections:
            raise self.error(f"expected {what}, found an empty file", 1)
        return sections

    def expect_end(self, what):
        """Only blank lines may follow; `what` describes what was read up to here."""
        if not self.skip_blank():
            raise self.error(f"expected the end of the file after {what}, found {_show(self.peek())}",
                             self.lineno + 1)

    def skip_lines(self, count, what):
        """Skip `count` lines (`what` they hold, for the error at an early end of file)."""
        for _ in range(count):
            self.next_line(what)

    def unit(self, text, line=None):
        """Canonical name of the units written as `text` on `line` (error there if unknown)."""
        try:
            return canonical_unit(text)
        except ValueError as exc:
            raise self.error(str(exc), line) from None

    def read_fixed(self, count, width, per_line, what="data", block_end=None):
        """Read `count` numbers written `per_line` to a line in fields of `width` characters.

        Every line but the last holds exactly `per_line` numbers, the last one the
        rest. Data ending early (end of file, a short line, or a line for which
        `block_end(line)` is true, i.e. the next section's header) is an error
        naming both counts.
        """
        values = []
        while len(values) < count:
            want = min(per_line, count - len(values))
            expected = f"{want} numbers of width {width}"
            got = len(values)
            if self.peek() is None or (block_end is not None and block_end(self.peek())):
                found = "the end of the file" if self.peek() is None else _show(self.peek())
                raise self.error(f"expected {expected} ({what}), found {found}: the header states "
                                 f"{count} points, the data ends after {got}", self.lineno + 1)
            line = self.next_line(expected).rstrip()
            fields = [line[i:i + width] for i in range(0, min(len(line), want * width), width)]
            for k, field in enumerate(fields):
                value = parse_number(field)
                if value is None:
                    raise self.error(f"expected {expected} ({what}), found {_show(field)} "
                                     f"in columns {k * width + 1}-{(k + 1) * width}")
                values.append(value)
            if len(fields) < want:
                raise self.error(f"expected {expected} ({what}), found {len(fields)}: the header "
                                 f"states {count} points, the data ends after {len(values)}")
            if line[want * width:].strip():
                raise self.error(f"expected {expected} ({what}), found more: {_show(line[want * width:])}; "
                                 f"the header states {count} points, which leave {want} for this line")
        return np.array(values)

    def read_free(self, count, what="data"):
        """Read `count` numbers separated by blanks, any number to a line."""
        values = []
        while len(values) < count:
            if self.peek() is None:
                raise self.error(f"expected more numbers ({what}), found the end of the file: "
                                 f"the header states {count} points, the data ends after {len(values)}",
                                 self.lineno + 1)
            for token in self.next_line("numbers").split():
                value = parse_number(token)
                if value is None:
                    raise self.error(f"expected numbers separated by blanks ({what}), found {_show(token)}")
                values.append(value)
            if len(values) > count:
                raise self.error(f"found {len(values)} numbers ({what}) by this line, "
                                 f"more than the {count} points the header states")
        return np.array(values)


def choose_unit(tf, explicit, stated, line=None):
    """Units of the numbers in `tf`: the explicit `units=` argument if given (it
    overrides the file; ValueError if unknown), else the units the file states
    (`stated`, written on `line`; GroundMotionFormatError there if unknown)."""
    if explicit is not None:
        return canonical_unit(explicit)
    return tf.unit(stated, line)


def make_record(tf, raw, dt, unit, header_text="", **meta):
    """Record from the numbers `raw` as written in file `tf`, which are in canonical `unit`;
    its orientation from the component label and `header_text` (the header's words about
    the component)."""
    meta.setdefault("orientation", orientation(meta.get("component", ""), header_text))
    record = Record.from_samples(raw * TO_M_S2[unit], dt, units_in_file=unit, source=tf.path, **meta)
    why = record.implausible()
    if why:
        record.notes = f"{record.notes}\n{why}" if record.notes else why
        label = f" [{record.component}]" if record.component else ""
        warnings.warn(f"{tf.path}{label}: {why}", GroundMotionWarning, stacklevel=4)
    return record


def check_peak(tf, raw, stated, line, what="peak acceleration"):
    """The data's peak |raw| must equal the header's `stated` peak (its text as
    printed, in the data's units, on `line`) to the header's printed precision."""
    decimals = len(stated.split(".")[1]) if "." in stated else 0
    peak = float(np.max(np.abs(raw)))
    tolerance = 0.5 * 10.0 ** -decimals + 1e-4 * abs(float(stated))
    if abs(peak - abs(float(stated))) > tolerance:
        raise tf.error(f"the header states {what} {stated}, but the data's peak is {peak:g}", line)


def lines_for(count, per_line):
    """Number of lines that `count` values take at `per_line` to a line."""
    return -(-count // per_line)
