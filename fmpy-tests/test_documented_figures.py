"""What the README and docs quote about the examples, against the examples themselves:
the fragility study snippet against examples/fragility.toml, the README sweep's count
of runs against the cases file, the record headers and the scales (counted here, not
by the package), and docs/examples.md's list of run_grid's columns against a grid.
Timings are not tested: benches/cli_timings.py prints them."""

import re
import tomllib
from pathlib import Path

from rocking import run_grid

REPO = Path(__file__).resolve().parents[1]


def test_fragility_snippet_is_the_example():
    """docs/fragility.md showed 2 bodies of the example's 3 (issue 25)."""
    text = (REPO / "docs" / "fragility.md").read_text()
    start = text.index("The study file (`examples/fragility.toml`):")
    block = text[text.index("```toml", start) + len("```toml"):text.index("```", text.index("```toml", start) + 7)]
    assert tomllib.loads(block) == tomllib.loads((REPO / "examples" / "fragility.toml").read_text())


def test_readme_sweep_counts_its_runs():
    """README: 'the sweep above (C cases x R records x S scales = N runs)': C from the cases
    file, R the horizontal components of the folder (the SMC headers' `component=` lines,
    the vertical `up` left out), S from 0.5:3:0.25."""
    readme = (REPO / "README.md").read_text()
    command = re.search(r"\$R sweep (\S+) --records (\S+) --scales (\S+)", readme)
    cases_file, folder, scales = command.groups()
    cases = len(tomllib.loads((REPO / cases_file).read_text())["cases"])
    components = [re.search(r"component=\s*(\S+)", (f.read_text(encoding="latin-1").splitlines()[5])).group(1)
                  for f in sorted((REPO / folder).glob("*.smc"))]
    records = sum(1 for c in components if c.lower() != "up")
    start, stop, step = map(float, scales.split(":"))
    n_scales = round((stop - start) / step) + 1
    quoted = re.search(r"the sweep\s+above \((\d+) cases x (\d+) records x (\d+) scales = (\d+) runs",
                       " ".join(readme.split()))
    assert quoted, "README: the sweep's count of runs"
    assert tuple(map(int, quoted.groups())) == (cases, records, n_scales, cases * records * n_scales)


def test_documented_columns_are_run_grids(fmu_path):
    """docs/examples.md lists run_grid's columns (it had lost zero_crossings): the list, read
    from the doc, against the columns of a one-run grid."""
    text = (REPO / "docs" / "examples.md").read_text()
    block = text[text.index("# case, <parameters>"):text.index("(+ history with histories=True)")]
    documented = [c.strip() for c in block.replace("#", " ").split(",") if c.strip()]
    params = {"shape": "solidRectangle", "B": 0.5}
    df = run_grid({"a": params}, workers=1, fmu=fmu_path, stop_time=0.01)
    columns = [c for c in df.columns if c not in params]
    assert columns[0] == "case"
    assert documented == ["case", "<parameters>"] + columns[1:]
