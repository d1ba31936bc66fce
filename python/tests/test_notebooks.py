"""The notebooks of python/examples/, executed from a clean kernel (nbclient) so that they cannot
rot: each asserts its own physics (critical rates, window convergence, the fitted rate, the
settled node count). The notebooks choose no backend (Jupyter shows their figures inline); the
test picks Agg and points WHIRL_NOTEBOOK_OUT at a temporary directory, where they save their
figures; nothing is written into python/examples."""
import os

import nbformat
import pytest
from nbclient import NotebookClient

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "examples")
NOTEBOOKS = sorted(f for f in os.listdir(EXAMPLES) if f.endswith(".ipynb"))


def test_there_are_four_notebooks():
    assert len(NOTEBOOKS) == 4


@pytest.mark.parametrize("name", NOTEBOOKS)
def test_notebook_runs(name, tmp_path, monkeypatch):
    monkeypatch.setenv("WHIRL_NOTEBOOK_OUT", str(tmp_path))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the debugger's start-up notes
    nb = nbformat.read(os.path.join(EXAMPLES, name), as_version=4)
    for cell in nb.cells:
        assert not cell.get("outputs"), "%s: outputs are committed" % name
        assert "matplotlib.use" not in cell.source, "%s forces a backend" % name
    before = sorted(os.listdir(EXAMPLES))
    NotebookClient(nb, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": EXAMPLES}}).execute()
    assert any(f.endswith(".png") for f in os.listdir(tmp_path))
    assert sorted(os.listdir(EXAMPLES)) == before
