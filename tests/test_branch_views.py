"""Result objects in a notebook: short reprs (never whole arrays), HTML, DataFrames.

Checks dispersion/branch_views.py (mixed into DiscreteBranches and ExactBranches), the
repr and DataFrame of RingResult, Figures that display as PNG, and the lazy front door.
"""
from __future__ import annotations

import importlib
import pkgutil
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dispersion
from dispersion.errors import InputError
from dispersion.branch_views import DATAFRAME_EXTRA
from dispersion.discretization.discrete_branches import DiscreteBranches
from dispersion.continuum.exact_branches import ExactBranches


def _branches(kind, m, labels, seed):
    rng = np.random.default_rng(seed)
    kappa = np.linspace(0, 8, m)
    omega = {lab: np.where(rng.random(m) < 0.2, np.nan, rng.random(m) * 8) for lab in labels}
    if kind == "exact":
        return ExactBranches(kappa, omega, 0.3, 8.0)
    return DiscreteBranches(kappa, omega, {lab: lab[0] for lab in labels}, 1.57,
                            {lab: rng.random(m) for lab in labels})


LABELS = st.lists(st.sampled_from([f"{s}{i}" for s in "SA" for i in range(20)]), min_size=0,
                  max_size=40, unique=True)


@settings(max_examples=25, deadline=None)
@given(kind=st.sampled_from(["exact", "discrete"]), m=st.integers(1, 5000), labels=LABELS,
       seed=st.integers(0, 2**32 - 1))
def test_repr_is_short_whatever_the_grid(kind, m, labels, seed):
    b = _branches(kind, m, labels, seed)
    text = repr(b)
    assert len(text) < 300 and "\n" not in text and "array" not in text
    assert f"{m} kappa" in text
    frame = b.to_dataframe()
    # the table holds exactly the finite values of every branch, nothing else
    assert len(frame) == sum(int(np.isfinite(w).sum()) for w in b.omega.values())
    for lab, w in b.omega.items():
        got = frame.loc[frame["branch"] == lab, "Omega"].to_numpy()
        assert np.array_equal(got, w[np.isfinite(w)])
    assert "<table>" in b._repr_html_()


def test_to_dataframe_without_pandas_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(InputError, match=r"dataframe\]"):
        _branches("exact", 3, ["S0"], 0).to_dataframe()
    assert "dispersion-iga[dataframe]" in DATAFRAME_EXTRA


def test_patch_branches_with_group_velocity():
    b = dispersion.patch().branches(np.linspace(0.1, 1, 5), group=True)
    assert set(b.group) == set(b.omega)
    assert "c_g/c_T" in b.to_dataframe().columns


def test_ring_result_repr_and_dataframe():
    from dispersion.contact.scenario import Scenario
    from dispersion.contact.simulate import simulate_ring

    sc = Scenario().scaled(0.125)
    res = simulate_ring(sc.__class__(**{**sc.__dict__, "t_end": 4 * sc.dt}), "lumped")
    assert repr(res).startswith("<RingResult: lumped mass, kane, 5 steps") and len(repr(res)) < 200
    frame = res.to_dataframe()
    assert len(frame) == 5 and "t [s]" in frame.columns and "total [J/m]" in frame.columns


@pytest.mark.slow  # matplotlib's first import and draw: seconds on a shared machine
def test_plot_functions_return_figures_that_display():
    from dispersion.plotting.branches import plot_exact

    fig = plot_exact([0.0, 1.0], {"S0": [0.0, 1.6]}, 3.0)
    assert type(fig).__name__ == "Figure" and fig._repr_png_().startswith(b"\x89PNG")


def test_front_door_reaches_every_public_module():
    names = set()
    for info in pkgutil.walk_packages(dispersion.__path__, "dispersion."):
        short = info.name.rsplit(".", 1)[1]
        parts = info.name.split(".")
        # the top level, and the wings whose modules the front door names (a package such as
        # dispersion.contact, dispersion.report or dispersion.cli exports its own modules)
        if short.startswith("_") or short == "__main__" or (
                len(parts) == 3 and parts[1] not in ("splines", "materials", "mass_rules", "symbolic",
                                                 "continuum", "discretization", "time_stepping",
                                                 "answers", "claims", "studies")):
            continue
        names.add((short, info.name))
    for short, full in sorted(names):
        if short in dispersion._API:  # the API function of that name wins (exact_branches)
            continue
        target = getattr(dispersion, short, None)
        if target is None or not hasattr(target, "__name__"):
            pytest.fail(f"dispersion.{short} does not resolve ({full})")
        if target.__name__ != full:  # a short name shared by two modules resolves to one
            assert importlib.import_module(full)
