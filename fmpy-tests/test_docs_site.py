"""The browser check of the documentation site (tools/docs_browser_check.py) sees what it claims to.

Run on a copy of the site that tools/docs.sh built (the test command builds it
before this suite): an image removed must be reported as not shown, and a TeX
equation added to a page must come out typeset by the site's own MathJax (the
browser runs with no network). Skipped where chromium or the site is missing.
"""

import shutil
import subprocess
import sys

import pytest

from test_cli import REPO

SITE = REPO / "target" / "site"
CHECK = REPO / "tools" / "docs_browser_check.py"


@pytest.fixture
def site_copy(tmp_path):
    if shutil.which("chromium") is None:
        pytest.skip("chromium is not installed (tools/docs.sh --check installs it)")
    if not (SITE / "corner.html").is_file():
        pytest.skip("the site is not built (tools/docs.sh)")
    copy = tmp_path / "site"
    shutil.copytree(SITE, copy)
    return copy


def check(site, page):
    return subprocess.run([sys.executable, CHECK, site, f"--pages={page}"], capture_output=True, text=True,
                          timeout=600)


def test_a_missing_image_fails_the_check(site_copy):
    (site_copy / "img" / "corner_rocking.png").unlink()
    out = check(site_copy, "corner.html")
    assert out.returncode == 1
    assert "corner.html: images not shown: ['img/corner_rocking.png']" in out.stderr, out.stderr


def test_tex_is_typeset_by_the_sites_mathjax(site_copy):
    page = site_copy / "model.html"
    tex = '<p><span class="arithmatex">\\(M_R = W\\,h_W(\\phi)\\)</span></p>'
    html = page.read_text()
    n = html.count('class="arithmatex"') + 1  # the page's own equations and the one added
    page.write_text(html.replace("<h1", tex + "<h1", 1))
    out = check(site_copy, "model.html")
    assert out.returncode == 0, out.stderr
    assert "model.html: 0 images shown" in out.stdout and f" {n}/{n} TeX equations rendered" in out.stdout, out.stdout
