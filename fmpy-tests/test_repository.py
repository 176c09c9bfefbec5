"""The repository stands alone: a fresh clone has everything it refers to.

- No tracked text file refers to a folder beside the repository or to a path
  of one particular machine (a user's clone has neither).
- Every relative link of the Markdown pages points to a file that a clone
  contains.

Needs git (the list of tracked files); skipped with the reason otherwise.
"""

import pathlib
import re
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Written in pieces so that this file does not match its own patterns.
FORBIDDEN = {
    ".." + "/shared": "the sibling folder beside the repository",
    "/" + "work/": "an absolute path of one machine",
    "/" + "root/": "an absolute path of one machine",
    "/" + "home/": "an absolute path of one machine",
    "/" + "Users/": "an absolute path of one machine",
    "C:" + "\\": "an absolute Windows path",
}

# Generated fuzzing inputs: arbitrary bytes, not project text.
EXCLUDED_PREFIXES = ("fuzz/corpus/",)


def _tracked_files() -> list[str]:
    if shutil.which("git") is None:
        pytest.skip("git is not installed: cannot list the tracked files")
    try:
        out = subprocess.run(
            ["git", "ls-files", "-z"],
            cwd=ROOT,
            capture_output=True,
            check=True,
        ).stdout
    except subprocess.CalledProcessError as e:
        pytest.skip(f"not a git checkout ({e.stderr.decode(errors='replace').strip()})")
    return [p for p in out.decode().split("\0") if p]


@pytest.fixture(scope="module")
def tracked() -> list[str]:
    return _tracked_files()


def _text(path: pathlib.Path) -> str | None:
    """The file's text, or None for a binary file (a NUL byte, or not UTF-8)."""
    data = path.read_bytes()
    if b"\0" in data:
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return None


def test_no_reference_outside_the_repository(tracked):
    hits = []
    scanned = 0
    for rel in tracked:
        if rel.startswith(EXCLUDED_PREFIXES):
            continue
        path = ROOT / rel
        if not path.is_file():  # deleted in the work tree, or a submodule
            continue
        text = _text(path)
        if text is None:
            continue
        scanned += 1
        for lineno, line in enumerate(text.splitlines(), 1):
            for pattern, what in FORBIDDEN.items():
                if pattern in line:
                    hits.append(f"{rel}:{lineno}: {pattern!r} ({what}): {line.strip()[:160]}")
    assert scanned > 50, f"only {scanned} text files scanned: is the file list right?"
    assert not hits, "tracked files refer to something a clone does not have:\n" + "\n".join(hits)


# [text](target) and ![alt](target), target up to whitespace or ')'.
LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")


def _links(text: str):
    """(line number, target) of the Markdown links outside code."""
    in_fence = False
    for lineno, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        line = re.sub(r"`[^`]*`", "", line)  # inline code
        for m in LINK.finditer(line):
            yield lineno, m.group(1)


def _is_relative(target: str) -> bool:
    return not (
        target.startswith("#")
        or re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target)  # http:, https:, mailto:, ...
    )


def test_markdown_links_point_to_tracked_files(tracked):
    tracked_set = set(tracked)
    tracked_dirs = {str(pathlib.PurePosixPath(p).parent) for p in tracked}
    # every ancestor folder of a tracked file is in a clone too
    for d in list(tracked_dirs):
        for parent in pathlib.PurePosixPath(d).parents:
            tracked_dirs.add(str(parent))
    pages = ["README.md"] + sorted(
        p for p in tracked if p.startswith("docs/") and p.endswith(".md") and "/" not in p[5:]
    )
    assert len(pages) > 3, f"Markdown pages found: {pages}"
    broken = []
    checked = 0
    for page in pages:
        text = (ROOT / page).read_text(encoding="utf-8")
        base = pathlib.PurePosixPath(page).parent
        for lineno, target in _links(text):
            if not _is_relative(target):
                continue
            file_part = target.split("#", 1)[0].split("?", 1)[0]
            if not file_part:
                continue
            if file_part.startswith("/"):
                broken.append(f"{page}:{lineno}: {target}: absolute link")
                continue
            # normalise a/b/../c without touching the file system
            parts: list[str] = []
            for part in (base / file_part).parts:
                if part == "..":
                    if not parts:
                        parts.append("..")  # leaves the repository
                    else:
                        parts.pop()
                elif part != ".":
                    parts.append(part)
            resolved = "/".join(parts) or "."
            checked += 1
            if resolved.startswith(".."):
                broken.append(f"{page}:{lineno}: {target}: points outside the repository")
            elif resolved not in tracked_set and resolved not in tracked_dirs:
                why = "exists but is not tracked" if (ROOT / resolved).exists() else "no such file"
                broken.append(f"{page}:{lineno}: {target}: {why}")
    assert checked > 10, f"only {checked} relative links found in {pages}"
    assert not broken, "broken relative links:\n" + "\n".join(broken)


def test_every_fmu_variable_is_documented_in_the_model_page():
    """Every variable of the FMU's one definition (fmu-rocking/src/description.rs, with the
    entries it shares with RoundBody in model-description/src/rigid_body.rs), as the built
    archive's modelDescription.xml declares it, has a row in docs/model.md §5, so the page
    cannot silently fall behind the FMU."""
    import zipfile
    from xml.etree import ElementTree

    from rocking import paths
    with zipfile.ZipFile(paths.default_fmu()) as fmu:
        md = ElementTree.fromstring(fmu.read("modelDescription.xml"))
    defined = {v.get("name") for v in md.iter("ScalarVariable")}
    assert {"theta", "ag", "Fx", "thetaOv"} <= defined, sorted(defined)

    page = (ROOT / "docs" / "model.md").read_text(encoding="utf-8")
    section = page.split("\n## 5.", 1)[1]
    documented = set()
    for line in section.splitlines():
        if line.startswith("| `"):
            first_cell = line.split("|")[1]
            # names, and the state derivatives der(name) of Model Exchange
            documented |= set(re.findall(r"`([A-Za-z][A-Za-z0-9]*|der\([A-Za-z][A-Za-z0-9]*\))`", first_cell))
    missing = sorted(defined - documented)
    assert not missing, f"FMU variables without a row in docs/model.md §5: {missing}"
