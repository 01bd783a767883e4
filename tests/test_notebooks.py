"""The notebooks that draw figures show them inline (issue 20, item 14).

nbmake runs every notebook for errors; this test runs the plotting ones once more with
nbclient and reads what a reader would see: every code cell that draws a figure must
carry an ``image/png`` output (a non-interactive backend such as ``Agg`` leaves none).
It also holds the rule that notebooks are committed without outputs.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"
DRAWS = re.compile(r"plt\.(show|subplots|figure)\(|plot_scene\(|plot_joints\(")


def _cells(path: Path) -> list[dict]:
    return json.loads(path.read_text())["cells"]


@pytest.mark.parametrize("path", sorted(NOTEBOOKS.glob("*.ipynb")), ids=lambda p: p.stem)
def test_notebooks_are_committed_without_outputs_and_never_pick_a_hidden_backend(path):
    for cell in _cells(path):
        if cell["cell_type"] != "code":
            continue
        assert not cell.get("outputs"), f"{path.name}: committed with outputs"
        src = "".join(cell["source"])
        assert "matplotlib.use(" not in src, f"{path.name}: matplotlib.use hides the figures"


@pytest.mark.parametrize("name", ["02_inverse_kinematics", "05_hardware_run"])
def test_figures_appear_inline(name):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(NOTEBOOKS / f"{name}.ipynb", as_version=4)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(NOTEBOOKS)}}).execute()
    drawing = [i for i, c in enumerate(nb.cells) if c.cell_type == "code" and DRAWS.search(c.source)]
    assert drawing, "the notebook draws no figure: nothing to check"
    shown = [i for i in drawing if any("image/png" in o.get("data", {}) for o in nb.cells[i].outputs)]
    assert shown == drawing, f"cells {sorted(set(drawing) - set(shown))} draw a figure that is not shown"
