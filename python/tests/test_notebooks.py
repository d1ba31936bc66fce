"""The notebooks of python/examples/, executed from a clean kernel (nbclient) so that they cannot
rot: each asserts its own physics (critical rates, window convergence, the fitted rate, the
settled node count). They run as a user's copy would: copied to a folder outside the source tree,
with this tree's package on PYTHONPATH (an installed whirl, to them), finding or writing the data
they read. The notebooks choose no backend (Jupyter shows their figures inline); the test picks
Agg and points WHIRL_NOTEBOOK_OUT at a temporary directory, where they save their figures;
nothing is written into python/examples. Inside the tree they import an installed whirl, and the
tree's only when none is installed."""
import os
import shutil
import subprocess
import sys

import nbformat
import pytest
from nbclient import NotebookClient

PYTHON = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))
EXAMPLES = os.path.join(PYTHON, "examples")
PROBE = "import whirl; print(whirl.__file__)"
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
    copy = tmp_path / "copy"
    copy.mkdir()
    shutil.copyfile(os.path.join(EXAMPLES, name), copy / name)
    monkeypatch.setenv("PYTHONPATH", PYTHON)  # the tree's package, as if installed
    nb.cells.append(nbformat.v4.new_code_cell(PROBE))
    NotebookClient(nb, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": str(copy)}}).execute()
    assert nb.cells[-1].outputs[0]["text"].strip() == os.path.join(PYTHON, "whirl",
                                                                    "__init__.py")
    assert any(f.endswith(".png") for f in os.listdir(tmp_path))
    assert sorted(os.listdir(EXAMPLES)) == before


def _whirl_seen(cell, path):
    """The whirl a notebook's first cell imports, run in ``path``."""
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(cell),
                                         nbformat.v4.new_code_cell(PROBE)])
    NotebookClient(nb, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": path}}).execute()
    return nb.cells[-1].outputs[0]["text"].strip()


def test_notebooks_import_an_installed_whirl_before_the_trees(tmp_path, monkeypatch):
    firsts = {[c for c in nbformat.read(os.path.join(EXAMPLES, name), as_version=4).cells
               if c.cell_type == "code"][0].source for name in NOTEBOOKS}
    installed = tmp_path / "site"
    shutil.copytree(os.path.join(PYTHON, "whirl"), installed / "whirl",
                    ignore=shutil.ignore_patterns("__pycache__"))
    for cell in firsts:
        # an installed whirl (another copy): the notebook in the tree takes it
        monkeypatch.setenv("PYTHONPATH", str(installed))
        assert _whirl_seen(cell, EXAMPLES) == str(installed / "whirl" / "__init__.py")
        # none installed: the tree's, in the tree (or the one this system has installed)
        monkeypatch.delenv("PYTHONPATH")
        assert _whirl_seen(cell, EXAMPLES) == (_system_whirl()
                                               or os.path.join(PYTHON, "whirl", "__init__.py"))


def _system_whirl():
    """The whirl this system's Python imports outside the tree, if any (make python's)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run([sys.executable, "-c", PROBE], cwd="/", env=env, capture_output=True,
                          text=True)
    return done.stdout.strip() if done.returncode == 0 else None
