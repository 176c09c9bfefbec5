"""Render the site's main pages in Debian's headless chromium and check what they show.

    python tools/docs_browser_check.py target/site [--install] [--pages=a.html,b.html]

Each page is copied with a probe script appended (the site itself is not
changed) which, once the page has loaded and MathJax has typeset, writes into
the DOM: every image's natural width (0: not shown), every equation of the page
(arithmatex) against MathJax's rendered ones, and whether MathJax itself loaded
from the site. chromium prints that DOM (--dump-dom); a missing image, an
unrendered equation, or a main page without its equations (code or TeX) fails.
Every page with a plot is rendered besides the main pages.
Without chromium (and without --install, which installs Debian's with apt), it
says so and exits 0.
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

#: The main pages: (file, the least images it must show, whether it must show equations).
PAGES = [("index.html", 0, False), ("model.html", 0, True), ("interface.html", 1, True),
         ("dynamics.html", 1, True), ("dharahara.html", 1, True), ("corner.html", 4, True),
         ("fragility.html", 2, True), ("cosimulation.html", 1, True), ("cli.html", 0, False),
         ("python-api.html", 0, False)]

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run", "--allow-file-access-from-files",
         "--virtual-time-budget=15000", "--dump-dom"]

PROBE = """<script>
window.addEventListener("load", function () {
  function report() {
    var imgs = Array.prototype.map.call(document.images, function (i) {
      return [i.getAttribute("src"), i.complete ? i.naturalWidth : 0]; });
    var tex = document.querySelectorAll(".arithmatex").length;
    var rendered = document.querySelectorAll(".arithmatex mjx-container").length;
    var formulas = Array.prototype.filter.call(document.querySelectorAll("article code"), function (c) {
      return c.offsetHeight > 0 && /[=\\u00b2\\u00b3\\u221a\\u03b1-\\u03c9]/.test(c.textContent); }).length;
    var out = document.createElement("pre");
    out.id = "probe";
    out.textContent = JSON.stringify({images: imgs, tex: tex, rendered: rendered, formulas: formulas,
                                      mathjax: !!(window.MathJax && window.MathJax.version)});
    document.body.appendChild(out);
  }
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
    MathJax.startup.promise.then(report, report);
  } else { report(); }
});
</script>"""


def chromium(install):
    for name in ("chromium", "chromium-browser"):
        if shutil.which(name):
            return shutil.which(name)
    if not install:
        return None
    sudo = [] if os.geteuid() == 0 or not shutil.which("sudo") else ["sudo"]
    try:
        subprocess.run([*sudo, "apt-get", "update", "-qq"], check=True)
        subprocess.run([*sudo, "env", "DEBIAN_FRONTEND=noninteractive", "apt-get", "install", "-y", "-qq",
                        "chromium"], check=True)
    except (OSError, subprocess.CalledProcessError) as exc:
        print(f"docs browser check: apt-get could not install chromium ({exc})")
    return shutil.which("chromium")


def probe(browser, page, profile):
    out = subprocess.run([browser, *FLAGS, f"--user-data-dir={profile}", page.as_uri()], capture_output=True,
                         text=True, timeout=120)
    match = re.search(r'<pre id="probe">(.*?)</pre>', out.stdout, re.S)
    if not match:
        return None
    return json.loads(match.group(1).replace("&quot;", '"').replace("&amp;", "&").replace("&lt;", "<")
                      .replace("&gt;", ">"))


def main():
    site = Path(sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else "target/site")
    browser = chromium("--install" in sys.argv)
    if browser is None:
        print("docs browser check: skipped: chromium is not installed (--install installs Debian's with apt)")
        return 0
    only = next((a.split("=", 1)[1] for a in sys.argv if a.startswith("--pages=")), None)
    # the main pages, and every other page that has a plot
    pages = PAGES + [(p.name, 1, False) for p in sorted(site.glob("*.html"))
                     if "<img" in p.read_text() and p.name not in {name for name, _, _ in PAGES}]
    pages = [p for p in pages if only is None or p[0] in only.split(",")]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        copy = Path(tmp) / "site"
        shutil.copytree(site, copy)
        for name, min_images, equations in pages:
            page = copy / name
            page.write_text(page.read_text().replace("</body>", PROBE + "</body>"))
            result = probe(browser, page, Path(tmp) / f"profile-{name}")
            if result is None:
                failures.append(f"{name}: the probe did not report (the page did not load)")
                continue
            hidden = [src for src, width in result["images"] if width == 0]
            shown = len(result["images"]) - len(hidden)
            print(f"{name}: {shown} images shown, {result['formulas']} formulas in code, "
                  f"{result['rendered']}/{result['tex']} TeX equations rendered, MathJax loaded: {result['mathjax']}")
            if hidden:
                failures.append(f"{name}: images not shown: {hidden}")
            if shown < min_images:
                failures.append(f"{name}: {shown} images shown, expected at least {min_images}")
            if result["rendered"] != result["tex"]:
                failures.append(f"{name}: {result['tex'] - result['rendered']} TeX equations not rendered")
            if equations and result["formulas"] + result["rendered"] == 0:
                failures.append(f"{name}: no equations shown")
            if not result["mathjax"]:
                failures.append(f"{name}: MathJax did not load from the site")
    for failure in failures:
        print(f"docs browser check: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
