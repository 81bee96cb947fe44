"""Tests of dispersion/studies/paper_studies.py (studies beyond the paper), its renderer and its plots."""
from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from dispersion.errors import InputError
from dispersion.symbolic.plate import numeric_pencil, plate_patch
from dispersion.studies import paper_studies as studies
from dispersion.discretization.discrete_branches import fundamental_branches
from dispersion.discretization.pencil_frequencies import pencil_frequencies
from dispersion.time_stepping.timestep import critical_time_step
from dispersion.continuum.exact_branches import exact_fundamental

NU = 0.3


def _finite_generalized(K, M):
    """Finite Omega of one pencil by scipy's QZ (independent of the condensation)."""
    w = scipy.linalg.eigvals(K, M)
    w = w[np.isfinite(w)]
    w = w[np.abs(w) < 1e8].real
    return np.sort(np.sqrt(np.clip(w, 0, None)))


@pytest.mark.parametrize("mass", ["consistent", "lumped", "singular", "singular-lumped"])
def test_condensation_keeps_exactly_the_finite_roots(mass):
    patch = plate_patch(2, 3, "bloch", 2, mass=mass, contact="top", gamma_s=0.5)
    kappa = np.array([0.3, 1.1])
    K, M = numeric_pencil(patch, NU, kappa)
    W = pencil_frequencies(K, M, patch.massless)
    # singular masses: 2 massless DOFs (u_x, u_y of the top point) -> 6 - 2 finite branches
    assert W.shape == (2, 6 - len(patch.massless))
    K, M = numeric_pencil(patch, NU, kappa)
    for i in range(kappa.size):
        np.testing.assert_allclose(W[i], _finite_generalized(K[i], M[i]), rtol=1e-8)


def test_exact_branch_matches_eqs_14_15_at_small_kappa():
    # Reference: the long-wave series of the paper, eqs (14) and (15) (Amirkulova 2011),
    # truncated after kappa^6; the neglected term is O(kappa^8).
    k = np.array([0.02, 0.05])
    nu = NU
    s0 = 2 / (1 - nu) * k**2 - 2 * nu**2 / (3 * (1 - nu) ** 3) * k**4 \
        + 2 * nu**2 * (7 * nu**2 + 10 * nu - 6) / (45 * (1 - nu) ** 5) * k**6
    a0 = 2 / (3 * (1 - nu)) * k**4 + 2 * (7 * nu - 17) / (45 * (1 - nu) ** 2) * k**6
    np.testing.assert_allclose(exact_fundamental("S", k, nu) ** 2, s0, rtol=1e-9)
    rel = np.abs(exact_fundamental("A", k, nu) ** 2 / a0 - 1)
    # A0 starts at kappa^4, so the O(kappa^8) remainder is a kappa^4 relative error
    assert rel[1] < 1e-4
    assert 3.5 < np.log(rel[1] / rel[0]) / np.log(k[1] / k[0]) < 4.5


def test_branch_frequencies_converge_to_exact_with_a_rate():
    # Both discrete S0 and A0 tend to the exact branches as kappa -> 0, with a relative
    # error that falls at least like kappa^2 (the S0 series of CMM first differs at
    # kappa^6 per eq 17, so the relative Omega error is O(kappa^4)).
    patch = plate_patch(2, 3, "bloch", 2, mass="consistent")
    k = np.array([0.1, 0.05])
    num = fundamental_branches(patch, NU, k)
    for branch in ("S0", "A0"):
        err = np.abs(num[branch] / exact_fundamental(branch[0], k, NU) - 1)
        assert err[1] < err[0] < 1e-2
        rate = np.log(err[0] / err[1]) / np.log(2)
        assert rate > 1.9, (branch, rate)


def test_fundamental_branches_are_the_two_lowest_roots_at_small_kappa():
    # the block solve of a symmetric mass (CMM) labels S0 and A0; below the first cut-off they
    # are the two lowest roots of the whole pencil, A0 (Omega ~ kappa^2) below S0 (~ kappa)
    patch = plate_patch(2, 3, "bloch", 2, mass="consistent")
    k = np.array([0.2, 0.4])
    blocks = fundamental_branches(patch, NU, k)
    K, M = numeric_pencil(patch, NU, k)
    W = pencil_frequencies(K, M, patch.massless)
    np.testing.assert_allclose(blocks["A0"], W[:, 0], rtol=1e-9)
    np.testing.assert_allclose(blocks["S0"], W[:, 1], rtol=1e-9)


def test_critical_time_step_properties():
    dt = {m: critical_time_step(plate_patch(2, 3, "bloch", 2, mass=m, contact="top"), NU,
                                n_theta=33) for m in ("consistent", "lumped", "singular")}
    # Row-sum lumping lowers the highest frequency: larger stable step than CMM
    # (Cottrell et al. 2006, sec. 5; Hughes, The Finite Element Method, sec. 9.3).
    assert dt["lumped"] > dt["consistent"]
    # Independent computation: 2 / largest finite generalized eigenvalue at the zone edge
    # and zone centre, by QZ; the grid maximum includes both, so it can only be larger.
    for mass, value in dt.items():
        patch = plate_patch(2, 3, "bloch", 2, mass=mass, contact="top")
        K, M = numeric_pencil(patch, NU, [0.0, np.pi / 2])
        wmax = max(_finite_generalized(K[i], M[i]).max() for i in range(2))
        assert value <= 2 / wmax + 1e-12
    # a finer zone grid can only find a higher maximum frequency
    fine = critical_time_step(plate_patch(2, 3, "bloch", 2), NU, n_theta=129)
    assert fine <= dt["consistent"] + 1e-12
    with pytest.raises(InputError, match="n_theta"):
        critical_time_step(plate_patch(2, 3, "bloch", 2), NU, n_theta=1)


def test_series_helpers():
    k = np.array([0.1, 0.2, 0.4])
    assert studies.series_frequency({2: 4.0, 4: 100.0}, k, order=2) == pytest.approx(2 * k)
    # departure: relative deviation 0, 0.05, 0.2 -> first above 0.1 at kappa = 0.4
    ref = np.ones(3)
    assert studies.departure_kappa(k, ref, [1.0, 1.05, 1.2], 0.1) == 0.4
    assert studies.departure_kappa(k, ref, ref, 0.1) is None
    import sympy

    nu = sympy.Symbol("nu")
    assert studies.order_of_accuracy({2: 2 / (1 - nu), 4: nu}, {2: 2 / (1 - nu), 4: 0}) == 4
    assert studies.order_of_accuracy({2: (1 - nu**2) / (1 + nu)}, {2: 1 - nu}) is None


def test_gamma_figure_draws_every_weight():
    from dispersion.plotting.studies import figure_gamma

    rows = [{"gamma_s": g, "S0": {"4": -g}, "A0": {"6": g}, "S0_error": [0.1 + g],
             "A0_error": [0.2 + g]} for g in (0.0, 0.5, 1.0)]
    fig = figure_gamma(rows, kappas=[0.5])
    coeff_ax, err_ax = fig.axes
    assert [len(line.get_xdata()) for line in coeff_ax.get_lines()[:2]] == [3, 3]
    assert len(err_ax.get_lines()) == 3  # S0, A0 and the zero line
    assert err_ax.get_yscale() == "symlog"  # signed errors, not |error|


def test_orders_of_accuracy_match_the_paper_claims():
    # Paper, end of section 2: with p = 2, n = 3 the A0 error term is kappa^6 for CMM (eq 18
    # vs eq 15) and for the singular mass (eq 20 vs 15); S0 errs at kappa^6 with CMM (eq 17
    # vs 14) but already at kappa^4 with the singular mass (eq 19 vs 14): "4th vs 2nd order".
    cmm = studies._order_case((2, 3, "consistent"), order=6)
    sing = studies._order_case((2, 3, "singular"), order=6)
    assert (cmm["S0_order"], cmm["A0_order"]) == (6, 6)
    assert (sing["S0_order"], sing["A0_order"]) == (4, 6)
    # the leading coefficients are the exact ones (eqs 14-15 at nu = 0.3)
    nu = 0.3
    for row in (cmm, sing):
        assert row["S0"]["2"] == pytest.approx(2 / (1 - nu))
        assert row["A0"]["4"] == pytest.approx(2 / (3 * (1 - nu)))


def test_gamma_case_series_agrees_with_its_numeric_branch():
    # one quantity two ways: the series' Omega at small kappa vs the patch's eigenvalue
    res = studies._gamma_case(0.5, order=6, kappas=(0.05, 0.1))
    patch = plate_patch(2, 3, "bloch", 2, mass="singular", contact="top", gamma_s=0.5)
    num = fundamental_branches(patch, NU, [0.05])
    for branch in ("S0", "A0"):
        coeffs = {int(j): v for j, v in res[branch].items()}
        series = studies.series_frequency(coeffs, [0.05])
        # truncation after kappa^6 leaves a relative remainder O(kappa^4) (A0) or O(kappa^6)
        assert series[0] == pytest.approx(num[branch][0], rel=5e-5)
        assert len(res[f"{branch}_error"]) == 2


def test_render_from_json_alone(tmp_path):
    # measure once (a small fake result built from real rows), store, render from the JSON
    import json
    import re

    from dispersion.report.studies import render
    from dispersion.results import dumps

    rows = [studies._gamma_case(g, order=4, kappas=(0.25,)) for g in (0, 1)]
    data = {"quick": True, "nu": NU, "r": 2, "kappas": [0.25], "gamma": rows,
            "orders": [studies._order_case((2, 3, "consistent"), order=6)],
            "dt_crit": [studies._dt_case((2, 3, "lumped"), n_theta=9)], "tol": 1e-3,
            "kappa_grid": [0.1, 0.2],
            "radius": [studies._radius_case(("exact", "S0", 4), np.array([0.1, 0.2]), 1e-3)],
            "bar": [studies._bar_case(("kane", "singular"), n_elements=6)]}
    md = render(json.loads(dumps(data)), tmp_path)
    links = re.findall(r"\]\(([^)]+)\)", md)
    assert {"studies_gamma.png", "studies_radius.png"} <= set(links)
    for link in links:
        if link.endswith(".png"):
            assert (tmp_path / link).stat().st_size > 0
    for heading in ("(a)", "(b)", "(c)"):
        assert f"### {heading}" in md
    assert "signed error" in md


def test_bar_case_singular_mass_is_insensitive_to_the_contact_modification():
    # Paper, sec. 1.2: with zero mass on the contact DOFs the contact force drops out of the
    # inertia terms (eqs 11-12), so Kane's modification changes nothing; the exact bar impact
    # (Graff 1991, sec. 1.2) conserves energy, so the change must be small.
    kane = studies._bar_case(("kane", "singular"), n_elements=10)
    std = studies._bar_case(("standard", "singular"), n_elements=10)
    assert kane["energy_change_percent"] == pytest.approx(std["energy_change_percent"], abs=1e-9)
    assert abs(kane["energy_change_percent"]) < 1.0


def test_exact_branch_against_an_independent_bracket_and_bisect():
    # Independent computation: the first sign change of the entire-function frequency
    # equation (dispersion.continuum.rayleigh_lamb.frequency_function, Rose 2004 ch. 8) on a fine
    # Omega grid, closed by Brent's method.
    from scipy.optimize import brentq

    from dispersion.continuum.rayleigh_lamb import frequency_function

    def C(z):
        return np.cos(np.emath.sqrt(z)).real

    def S(z):
        return np.sinc(np.emath.sqrt(z) / np.pi).real

    for kind in ("S", "A"):
        for k in (0.5, 1.0, 1.5):
            def f(w):
                return frequency_function(kind, k * k, np.asarray(w) ** 2, NU, C, S)

            grid = np.linspace(1e-6, 3 * k + 0.1, 4000)
            vals = f(grid)
            i = np.nonzero(np.sign(vals[:-1]) != np.sign(vals[1:]))[0][0]
            ref = brentq(f, grid[i], grid[i + 1], xtol=1e-15, rtol=1e-14)
            assert exact_fundamental(kind, [k], NU)[0] == pytest.approx(ref, rel=1e-11)
    with pytest.raises(InputError, match="kind"):
        exact_fundamental("X", [0.1], NU)


def test_gamma_study_titles_state_the_patch_its_rows_stored():
    # issue 22 item 2: "Singular mass (top contact)" and "quadratic splines, n = 3" were typed;
    # rows whose stored patch says otherwise (p = 3, n = 6, r = 5/2, contact bottom: values no
    # code path types) must be titled with those
    from dispersion.plotting.studies import figure_gamma
    from dispersion.report.studies import _markdown

    patch = {"p": 3, "n": 6, "model": "bloch", "r": "5/2", "mass": "singular",
             "contact": "bottom", "gamma_s": "0", "weights": None, "nu": None}
    rows = [{"gamma_s": g, "patch": dict(patch, gamma_s=str(g)), "S0": {"4": -g},
             "A0": {"6": g}, "S0_error": [0.1 + g], "A0_error": [0.2 + g]} for g in (0, 1)]
    want = "singular mass (contact bottom), Bloch r = b/h = 5/2, p = 3, n = 6"
    title = figure_gamma(rows, kappas=[0.5], nu=0.3, r=2)._suptitle.get_text()
    assert title.startswith("S" + want[1:]) and "top" not in title and "r = b/h = 2" not in title
    data = {"quick": True, "nu": NU, "r": 2, "kappas": [0.5], "gamma": rows, "orders": [],
            "dt_crit": [], "tol": 1e-3, "kappa_grid": [], "radius": [], "bar": []}
    md = _markdown(data)
    head, a = md.split("### (b)")[0].split("### (a)")
    assert "contact on the bottom surface" in head and "top" not in head
    assert want in a and "top" not in a and "quadratic" not in a
    bar = [{"scheme": "kane", "mass": "singular", "n_elements": 6, "p": 4, "courant": 0.35,
            "energy_change_percent": 0.0, "force_oscillation": 0.0, "duration_error": 0.0,
            "rebound_error": 0.0}]
    md = _markdown(dict(data, bar=bar))
    assert "B-spline bar of degree 4 at Courant number 0.35" in md
    assert "quadratic" not in md and "0.5)" not in md
    stored = studies._gamma_case(0.5, order=4, kappas=(0.25,))["patch"]
    assert (stored["mass"], stored["contact"], stored["gamma_s"]) == ("singular", "top", "1/2")


def test_order_and_time_step_tables_state_the_patch_each_row_stored():
    # issue 22 item 2: the (b) and (c) tables named only the mass; a singular row must state
    # the contact set and gamma_s its stored patch was computed with (values no code path
    # types: contact bottom, gamma_s = 3/7)
    from dispersion.report.studies import _markdown
    from dispersion.symbolic.patch import Patch

    spec = Patch(p=3, n=5, r=2, mass="singular", contact="bottom", gamma_s="3/7")
    row = {"p": 3, "n": 5, "mass": "singular", "patch": spec.as_dict()}
    data = {"quick": True, "nu": NU, "r": 2, "kappas": [0.5], "gamma": [],
            "orders": [dict(row, order=6, S0_order=4, A0_order=None, S0={}, A0={})],
            "dt_crit": [dict(row, dt_crit=0.25)], "tol": 1e-3, "kappa_grid": [],
            "radius": [], "bar": []}
    md = _markdown(data)
    assert md.count("| 3 | 5 | singular (contact bottom, gamma_s = 3/7) |") == 2
    assert "contact on the bottom surface" in md.split("### (a)")[0] and "top" not in md
    stored = studies._order_case((2, 3, "singular"), order=4)["patch"]
    assert Patch.from_dict(stored) == Patch(r=2, mass="singular", contact="top")
    assert studies._dt_case((2, 3, "lumped"), n_theta=9)["patch"]["mass"] == "lumped"
