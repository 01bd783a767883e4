"""The README keeps exactly two set-up commands, and .ci/run runs the test one verbatim."""

import re
import sys
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]


def _setup_commands() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Set up", 1)[1].split("\n## ", 1)[0]
    return [b.strip() for b in re.findall(r"```bash\n(.*?)```", section, flags=re.S)]


def test_readme_has_exactly_two_setup_commands():
    cmds = _setup_commands()
    assert len(cmds) == 2, cmds
    assert cmds[0].endswith("iik verify") and 'pip install ".[verify]"' in cmds[0]
    assert '".[test]"' in cmds[1] and cmds[1].endswith("pytest")


def test_readme_extras_are_the_distributions():
    """The extras the README names are pyproject's, and the main job's extra installs what
    ``iik verify`` imports (``verification`` checks the ``verify`` extra when imported)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    extras = set(declared["project"]["optional-dependencies"])
    named = set(re.findall(r'"\.\[(\w+)\]"', text))
    assert named and named <= extras, named - extras
    assert {"planning", "viewer", "hardware", "verify", "test", "all"} <= named
    assert "iik[planning,viewer,hardware]" in declared["project"]["optional-dependencies"]["verify"]


def test_ci_runs_the_readme_test_command_verbatim():
    ci_lines = (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    assert _setup_commands()[1] in ci_lines


def test_readme_documents_the_limit_filter_of_solve():
    """`iik.solve(T, arm)` drops solutions outside the limits by default: the README says so where it
    shows it."""
    text = (ROOT / "README.md").read_text()
    default = [ln for ln in text.splitlines() if re.search(r"iik\.solve\(T, arm\)\s+#", ln)]
    assert default and all("within the joint limits" in ln for ln in default), default
    assert re.search(r"iik\.solve\(T, arm, within_limits=False\)", text)


def test_files_the_docs_point_to_are_in_the_repository():
    """Every `docs/*.md` the README or the code names exists, and nothing points into `../shared`
    at run time (the project copies what it needs from there, naming the source)."""
    code = (p for d in ("iik", "hardware", "verification") for p in ROOT.glob(f"{d}/**/*.py"))
    sources = [ROOT / "README.md", *code]
    named = {m for p in sources for m in re.findall(r"docs/[A-Za-z_]+\.md", p.read_text())}
    assert {"docs/POWERCUBE.md", "docs/ARM.md"} <= named
    assert all((ROOT / n).is_file() for n in named), sorted(n for n in named if not (ROOT / n).is_file())


def test_slow_marker_selects_the_long_sweeps():
    """The README's `pytest -m slow` runs something: the marker is registered and used."""
    text = (ROOT / "pyproject.toml").read_text()
    assert re.search(r'"slow:', text)
    marked = [p for p in ROOT.glob("tests/**/*.py") if "@pytest.mark.slow" in p.read_text()]
    assert marked
