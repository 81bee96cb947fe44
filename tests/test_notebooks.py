"""Execute every notebook in ``notebooks/`` so none can rot.

Each ``notebooks/*.py`` (jupytext percent format) is converted to a notebook and run with
nbclient on the ``python3`` kernel in a temporary working directory; any cell error fails
its test. One test per notebook.
"""
from __future__ import annotations

from pathlib import Path

import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parents[1] / "notebooks").glob("*.py"))
# A notebook is meant to take seconds; the limit only catches a hang, so a loaded machine
# cannot trip it while the work is small.
CELL_TIMEOUT = 900
#: The notebooks the README promises (series, errata, branches, ring, verify).
EXPECTED = {"01_series", "02_errata", "03_branches", "04_ring", "05_verify"}


#: Each notebook starts its own kernel and takes seconds to tens of seconds on 2 cores: they
#: run in the slow run, but the shortest, 05_verify, which keeps the machinery (jupytext,
#: the kernel, inline output, nothing left behind) checked in the default run.
SLOW = {"01_series", "02_errata", "03_branches", "04_ring"}


@pytest.mark.parametrize("path", [pytest.param(p, marks=[pytest.mark.slow] * (p.stem in SLOW),
                                               id=p.stem) for p in NOTEBOOKS])
def test_notebook_executes(path, tmp_path):
    import jupytext
    import nbclient

    nb = jupytext.read(path)
    assert any(cell.cell_type == "code" for cell in nb.cells), f"{path.name} has no code"
    client = nbclient.NotebookClient(
        nb,
        timeout=CELL_TIMEOUT,
        kernel_name="python3",
        resources={"metadata": {"path": str(tmp_path)}},
    )
    client.execute()  # raises CellExecutionError on the first failing cell
    # a user runs it from notebooks/ in the checkout: it leaves nothing in its folder
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    errors = [
        out
        for cell in nb.cells
        if cell.cell_type == "code"
        for out in cell.get("outputs", [])
        if out.get("output_type") == "error"
    ]
    assert not errors
    # a notebook runs clean: no warning on stderr (e.g. tqdm's "IProgress not found")
    warnings = [out.get("text", "") for cell in nb.cells if cell.cell_type == "code"
                for out in cell.get("outputs", [])
                if out.get("output_type") == "stream" and out.get("name") == "stderr"
                and "Warning" in out.get("text", "")]
    assert not warnings, warnings[:3]
    source = path.read_text()
    if "plotting" in source or "plot_" in source:  # a notebook that draws shows its figures
        images = [out for cell in nb.cells if cell.cell_type == "code"
                  for out in cell.get("outputs", []) if "image/png" in out.get("data", {})]
        assert images, f"{path.name} draws figures but shows none inline"


def test_every_promised_notebook_exists():
    assert {p.stem for p in NOTEBOOKS} == EXPECTED
