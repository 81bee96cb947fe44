"""Data flows once: ``dispersion branches --figure --csv`` traces and solves each branch set once
(issue 22 item 3, issue 23 item 5). Counted by wrapping the solvers wherever they are imported."""
from __future__ import annotations

import pytest

from dispersion.cli import main


@pytest.fixture
def counted(monkeypatch):
    import dispersion.studies.branch_study as study
    import dispersion.discretization.discrete_branches as disc
    import dispersion.continuum.exact_branches as exact
    import dispersion.continuum.velocities as vel

    calls = {"trace_branches": 0, "discrete_branches": 0, "exact_velocities": 0}

    def wrap(name, fn):
        def inner(*args, **kwargs):
            calls[name] += 1
            return fn(*args, **kwargs)
        return inner

    for module, name in ((exact, "trace_branches"), (study, "trace_branches"),
                         (disc, "discrete_branches"), (study, "discrete_branches"),
                         (vel, "exact_velocities"), (study, "exact_velocities")):
        original = getattr(disc if name == "discrete_branches" else
                           exact if name == "trace_branches" else vel, name)
        monkeypatch.setattr(module, name, wrap(name, original))
    return calls


def test_branches_figure_and_csv_compute_each_branch_set_once(tmp_path, counted):
    pytest.importorskip("matplotlib")
    code = main(["branches", "--kappa-max", "2", "--count", "9",
                 "--omega-max", "4", "--figure", str(tmp_path / "f.png"),
                 "--csv", str(tmp_path / "b.csv")])
    assert code == 0
    assert (tmp_path / "f.png").stat().st_size > 0 and (tmp_path / "b.csv").stat().st_size > 0
    # one exact trace, one velocity evaluation, one discrete solve per mass
    assert counted == {"trace_branches": 1, "discrete_branches": 2, "exact_velocities": 1}
