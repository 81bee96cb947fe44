"""The report section finite_patches (dispersion/studies/finite_patches.py, measured;
dispersion/report/finite_patches.py, rendered from the stored JSON alone)."""
from __future__ import annotations

import json

import pytest

from dispersion.results import jsonable


@pytest.mark.slow
def test_the_quick_study_measures_and_renders_from_its_json(tmp_path):
    from dispersion.report.finite_patches import FIGURES, headline, render
    from dispersion.studies.finite_patches import finite_patches

    data = json.loads(json.dumps(jsonable(finite_patches(quick=True))))
    # the table: the open mesh never below the lattice with free ends
    for row in data["table"]:
        assert row["free"] >= row["lattice"] * (1 - 1e-9) and row["free_count"] >= 1
    # an outlier count and its ratio agree: outliers exactly where the mesh tops the lattice
    for row in data["bar"]:
        assert (row["count"] > 0) == (row["outlier_ratio"] > 1 + 1e-9), row["mass"]
    # the removal methods: every constraints row of the consistent mass is outlier-free
    assert all(r["count"] == 0 for r in data["removal"]
               if r["method"] == "constraints" and r["mass"] == "consistent")
    md = render(data, tmp_path)
    assert all((tmp_path / f).is_file() for f in FIGURES)
    assert "omega_max h / c of the bar" in md and headline(data).startswith("finite patches")
