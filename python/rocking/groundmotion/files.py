"""Which files of a folder are records: the one rule every folder scan follows.

    record_files("data/ground-motions")    # sorted Paths, recursive
    is_record_file(path)                   # the same rule for one file

A record folder also holds what is evidently not a record: Python's caches
(`__pycache__/*.pyc`, which pip writes beside a shipped generator script),
hidden files and folders (`.DS_Store`, `.git/`), scripts, documentation
(README, licence and provenance notes), pictures, archives and results. Those
are passed over by name, and so is any file with a NUL byte in its first
kilobytes: every record format the readers know is text. Everything else is
given to the readers, so a file that looks like a record but cannot be read
raises the reader's error naming it instead of being dropped without a word.
"""

from pathlib import Path

#: Suffixes of files that are not records: code, documents, pictures, archives, tables of results
#: and configuration (a study's .toml, a body's .json). `.csv` and `.txt` are left to the readers:
#: records come as both.
NOT_RECORD_SUFFIXES = frozenset({
    ".py", ".pyc", ".pyo", ".pyd", ".ipynb", ".sh", ".bat", ".ps1", ".rs", ".c", ".h", ".m",
    ".md", ".rst", ".html", ".htm", ".pdf", ".doc", ".docx", ".odt", ".tex", ".bib",
    ".png", ".jpg", ".jpeg", ".gif", ".svg", ".tif", ".tiff", ".kml", ".kmz",
    ".zip", ".gz", ".tgz", ".bz2", ".xz", ".7z", ".tar", ".whl", ".fmu",
    ".toml", ".json", ".yaml", ".yml", ".ini", ".cfg", ".xml", ".parquet", ".xlsx", ".xls", ".log",
})

#: Folders whose contents are never records (caches, environments, version control).
NOT_RECORD_FOLDERS = frozenset({"__pycache__", "node_modules", "site-packages"})

#: File names (before the first dot, any case) of licence, provenance and readme texts.
NOT_RECORD_STEMS = frozenset({"readme", "license", "licence", "copying", "notice", "provenance",
                              "changelog", "authors", "citation", "manifest", "sha256sums", "md5sums"})

#: Bytes looked at for a NUL, which no text record holds.
_SNIFF = 4096


def is_record_file(path, base=None):
    """Whether the file at `path` may be a record: False for what the module's rule passes over.

    base: the folder scanned; the names of `path`'s folders below it count too (a hidden or a
    cache folder), those above it do not (a study kept under ~/.local is still scanned).
    """
    path = Path(path)
    parts = path.relative_to(base).parts if base is not None else (path.name,)
    if any(part.startswith(".") or part in NOT_RECORD_FOLDERS for part in parts):
        return False
    name = path.name
    if path.suffix.lower() in NOT_RECORD_SUFFIXES or name.split(".", 1)[0].lower() in NOT_RECORD_STEMS:
        return False
    if name.endswith("~"):  # an editor's backup
        return False
    try:
        with open(path, "rb") as handle:
            return b"\0" not in handle.read(_SNIFF)
    except OSError:
        return True  # let the reader say why it cannot be read, naming the file


def record_files(folder):
    """The files under `folder` (recursive, sorted by path) that `is_record_file` keeps."""
    folder = Path(folder)
    return sorted(p for p in folder.rglob("*") if p.is_file() and is_record_file(p, folder))
