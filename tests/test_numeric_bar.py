"""The 1D bar's numeric path (issue 23: no sympy, no scipy for a small bar) against the exact
and the sparse paths it replaces."""
from __future__ import annotations

import re
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.contact.bar import Bar, assemble_bar
from dispersion.contact.newmark import integrate
from dispersion.contact.newmark_scheme import newmark_for
from dispersion.contact.redistribution import float_redistribution
from dispersion.splines.bspline import SplineBasis1D, open_knot_vector
from dispersion.errors import InputError
from dispersion.mass_rules.mass import contact_weights, redistribution_matrix


@settings(max_examples=10, deadline=None)
@given(st.integers(1, 6), st.integers(1, 12))
def test_uniform_float_basis_equals_the_exact_extraction(p, n_el):
    exact = SplineBasis1D.from_knots(open_knot_vector(p, n_el))
    fast = SplineBasis1D.uniform(p, n_el)
    assert np.array_equal(exact.active, fast.active) and fast.kv.n == exact.kv.n
    assert np.allclose(fast.spans, exact.spans, rtol=0, atol=1e-15)
    assert np.allclose(fast.C, exact.C, rtol=0, atol=1e-12)
    g_exact = np.array([float(g) for g in exact.kv.greville()])
    assert np.allclose(fast.kv.greville(), g_exact, rtol=0, atol=1e-15)


@settings(max_examples=30, deadline=None)
@given(st.integers(3, 9), st.sampled_from(["top", "bottom", "both"]),
       st.fractions(0, 1, max_denominator=16))
def test_float_redistribution_equals_the_exact_matrix(n, contact, gamma):
    try:
        exact = redistribution_matrix(n, contact_weights(n, contact, gamma))
    except InputError as exc:  # what the exact path refuses, the float path refuses too
        with pytest.raises(InputError, match=re.escape(str(exc))):
            float_redistribution(n, contact, float(gamma))
        return
    # 1 - float(gamma) may differ from float(1 - gamma) in the last bit
    assert np.allclose(float_redistribution(n, contact, float(gamma)),
                       np.array(exact.tolist(), dtype=float), rtol=0, atol=2e-16)


def _sparse_twin(prob):
    """The same problem handed to the solver as scipy.sparse matrices (the large-bar path)."""
    return replace(prob, M=sp.csr_matrix(prob.M), G=sp.csr_matrix(prob.G),
                   K=sp.csr_matrix(prob.K))


@pytest.mark.parametrize("mass,scheme", [("singular", "central"), ("singular", "kane"),
                                         ("consistent", "kane"), ("lumped", "central")])
def test_dense_and_sparse_solver_paths_agree(mass, scheme):
    model = assemble_bar(Bar(20, 1, 1.0, 1.0, 1.0, mass, clamped=("right",), contact="left"))
    dense = model.problem
    assert isinstance(dense.M, np.ndarray)  # a small bar is assembled as numpy arrays
    sparse = _sparse_twin(dense)
    u0 = model.coefficients(lambda x: 0.5 * (1 - x))
    # up to t = 0.9: no contact yet, so no chatter amplifies the round-off of either path
    runs = [integrate(prob, u0, np.zeros(prob.n), 0.002, 450, newmark_for(scheme),
                      keep_states=True) for prob in (dense, sparse)]
    a, b = (np.array([s.u for s in h.states]) for h in runs)
    assert np.allclose(a, b, rtol=0, atol=1e-12)
    assert np.allclose(runs[0].total, runs[1].total, rtol=1e-12, atol=0)


@settings(max_examples=25, deadline=None)
@given(st.integers(1, 4), st.integers(2, 12), st.sampled_from(["consistent", "lumped",
                                                               "singular", "singular-lumped"]),
       st.sampled_from(["left", "right"]))
def test_float_mass_rules_equal_the_exact_rules(p, n_el, mass, contact):
    # issue 23: the numeric bar applies the rules in floats (no sympy); the exact route is
    # the rule on the exact Gram matrix of the same knots with the exact redistribution
    # (gamma_s = 1/2). Rule stated first: every entry within 1e-15 (entries are <= 1 on L = 1).
    import sympy

    from dispersion.contact.bar import NUMERIC_RULES
    from dispersion.mass_rules.mass_rule import gram_space, mass_matrix

    assert mass in NUMERIC_RULES
    model = assemble_bar(Bar(n_el, p, mass=mass, contact=contact))
    assert isinstance(model.problem.M, np.ndarray)  # the numpy route, not scipy.sparse
    n = n_el + p
    side = "bottom" if contact == "left" else "top"
    R = redistribution_matrix(n, contact_weights(n, side, sympy.Rational(1, 2)))
    exact = mass_matrix(mass, gram_space(open_knot_vector(p, n_el, 0, 1), R))
    diff = np.abs(model.problem.M - np.array(exact.tolist(), dtype=float)).max()
    assert diff <= 1e-15, diff


@pytest.mark.parametrize("mass", ["singular", "lumped", pytest.param("hrz", marks=pytest.mark.slow)])
def test_large_bar_is_assembled_sparse_and_equals_the_dense_assembly(mass, monkeypatch):
    # above DENSE_DOFS functions the bar is assembled with scipy.sparse; the same bar
    # assembled dense (the bound lifted) must give the same matrices
    from dispersion.contact import bar as bar_module

    b = Bar(bar_module.DENSE_DOFS, 1, mass=mass, clamped=("right",))
    big = assemble_bar(b).problem
    assert sp.issparse(big.M) and sp.issparse(big.K)
    monkeypatch.setattr(bar_module, "DENSE_DOFS", 10 * bar_module.DENSE_DOFS)
    small = assemble_bar(b).problem
    assert isinstance(small.M, np.ndarray)
    for A, B in ((big.M, small.M), (big.K, small.K), (big.G, small.G)):
        assert np.allclose(sp.csr_matrix(A).toarray(), B, rtol=0, atol=1e-12)
