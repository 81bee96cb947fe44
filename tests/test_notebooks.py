"""Execute every notebook in ``notebooks/`` so none can rot.

Each ``notebooks/*.py`` (jupytext percent format) is converted to a notebook and run with
nbclient on the ``python3`` kernel in a temporary working directory; any cell error fails
its test. One test per notebook.
"""
from __future__ import annotations

from pathlib import Path

import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("*.py"))
CELL_TIMEOUT = 120  # seconds per cell; a notebook is meant to take < 30 s in total


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_executes(path, tmp_path):
    jupytext = pytest.importorskip("jupytext")
    nbclient = pytest.importorskip("nbclient")
    nb = jupytext.read(path)
    assert any(cell.cell_type == "code" for cell in nb.cells), f"{path.name} has no code"
    client = nbclient.NotebookClient(
        nb,
        timeout=CELL_TIMEOUT,
        kernel_name="python3",
        resources={"metadata": {"path": str(tmp_path)}},
    )
    client.execute()  # raises CellExecutionError on the first failing cell
    errors = [
        out
        for cell in nb.cells
        if cell.cell_type == "code"
        for out in cell.get("outputs", [])
        if out.get("output_type") == "error"
    ]
    assert not errors


def test_there_are_notebooks():
    # the issue asks for notebooks on the series, the errata, the branches and the ring
    assert len(NOTEBOOKS) >= 2
