"""`rocking --version`: the package version (pyproject.toml's), the GUID of the FMU it
drives (read here from the archive's modelDescription.xml) and the commit (git's HEAD)."""

import re
import subprocess
import tomllib
import zipfile

from lxml import etree

from test_cli import REPO, ok


def test_version_names_package_fmu_guid_and_commit(fmu_path):
    out = ok("--version").stdout.strip()
    version = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]
    with zipfile.ZipFile(fmu_path) as fmu:
        guid = etree.fromstring(fmu.read("modelDescription.xml")).get("guid")
    head = subprocess.run(["git", "-C", str(REPO), "rev-parse", "HEAD"], capture_output=True, text=True)
    assert out.startswith(f"rocking {version}, "), out
    assert f"GUID {guid} " in out, out
    match = re.search(r"commit (\S+)$", out)
    assert match, out
    expected = head.stdout.strip() if head.returncode == 0 else "unknown"
    assert match.group(1).removesuffix("-dirty") == expected, out


def test_version_says_unknown_commit_outside_git(tmp_path):
    """A folder git knows nothing of: the commit is "unknown", never an error."""
    from rocking import paths
    assert paths._git_commit(tmp_path) == "unknown"
