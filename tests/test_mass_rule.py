"""Mass rules (dispersion.mass_rules.mass_rule): stated properties hold, refusals, user rules."""
from __future__ import annotations

import warnings

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from dispersion.errors import IndefiniteMassWarning, InputError
from dispersion.splines.bspline import SplineBasis1D, open_knot_vector
from dispersion.mass_rules.mass import contact_weights, redistribution_matrix
from dispersion.mass_rules.mass_check import MassProperties, check_mass
from dispersion.mass_rules.mass_rule import (
    RULE_NAMES,
    RULES,
    TranslationalMassWarning,
    gram_space,
    mass_matrix,
    user_rule,
    x_mass_coefficients,
)
from dispersion.mass_rules.mass_rule_file import rule_from_toml
from dispersion.symbolic.plate import bloch_coefficients, plate_patch
from dispersion.splines.spline_mass import lobatto_rule

TOML_RULE = '''
name = "far-quarter"
lumped = true
[weights]
"-1" = { "-2" = 0.75, "-3" = 0.25 }
'''


def _space(p, ne, rule):
    kv = open_knot_vector(p, ne, -1, 1)
    R = None
    if rule.redistributes:
        R = redistribution_matrix(kv.n, contact_weights(kv.n, "top", sympy.Rational(1, 3)))
    return gram_space(kv, R)


@settings(max_examples=25, deadline=None)
@given(p=st.integers(1, 4), ne=st.integers(1, 4), name=st.sampled_from(RULE_NAMES))
def test_every_rule_keeps_what_it_states(p, ne, name):
    # property search: on any open uniform space, the measured properties include the stated
    rule = RULES[name]
    if rule.redistributes and p + ne < 3:
        return
    space = _space(p, ne, rule)
    Mv = mass_matrix(rule, space, check=False)
    result = check_mass(rule, Mv, space.M)
    assert result.refused == () and result.warned == ()
    for prop in ("symmetric", "psd", "translational", "diagonal"):
        if getattr(rule.states, prop):
            assert getattr(result.measured, prop), prop
    assert result.measured.zero_rows == rule.redistributes


@pytest.mark.parametrize("p", [1, 2, 3, 4])
def test_lobatto_exact_matches_float_quadrature(p):
    # two independent computations: exact error-term formula (A&S 25.4.32) vs numpy's
    # Legendre roots and float B-splines at the points
    kv = open_knot_vector(p, 3, 0, 3)
    exact = np.array(mass_matrix("nodal-lobatto", gram_space(kv)).tolist(), float)
    basis = SplineBasis1D.from_knots(kv)
    x, w = lobatto_rule(p + 1)
    A = np.zeros_like(exact)
    for e, (a, b) in enumerate(basis.spans):
        pts = a + (x + 1) * (b - a) / 2
        N = np.zeros((len(pts), kv.n))
        for q, t in enumerate(pts):  # evaluate inside the span (its end belongs to it here)
            u = min(t, b - 1e-14 * (b - a)) if e < len(basis.spans) - 1 else t
            act, vals = basis.evaluate([u])
            N[q, act[0]] = vals[0]
        A += (b - a) / 2 * (N.T * w) @ N
    assert np.allclose(A, exact, rtol=0, atol=1e-13)


@pytest.mark.parametrize("p", [2, 3])
def test_greville_exact_matches_float_quadrature(p):
    kv = open_knot_vector(p, 4, 0, 1)
    exact = np.array(mass_matrix("nodal-greville", gram_space(kv)).tolist(), float)
    basis = SplineBasis1D.from_knots(kv)
    g = np.array([float(t) for t in kv.greville()])
    act, vals = basis.evaluate(g)
    N = np.zeros((len(g), kv.n))
    np.put_along_axis(N, act, vals, axis=1)
    w = np.array(gram_space(kv).M.tolist(), float).sum(axis=1)  # int N_i = row sums of Gram
    assert np.allclose((N.T * w) @ N, exact, atol=1e-14)


def test_p1_nodal_and_hrz_are_row_sum_lumping():
    kv = open_knot_vector(1, 3)
    lumped = mass_matrix("lumped", gram_space(kv))
    for name in ("hrz", "nodal-greville", "nodal-lobatto"):
        assert mass_matrix(name, gram_space(kv)) == lumped


@pytest.mark.parametrize("p", [1, 2, 3])
def test_x_coefficients_of_consistent_and_lumped(p):
    assert dict(x_mass_coefficients("consistent", p)) == {
        L: v for L, v in bloch_coefficients(p)["00"].items() if v != 0}
    assert x_mass_coefficients("lumped", p) == ((0, 1),)
    for name in ("hrz", "nodal-greville", "nodal-lobatto"):  # translational mass per cell
        assert sum(v for _, v in x_mass_coefficients(name, p)) == 1


def test_refusals_name_the_reason():
    kv = open_knot_vector(2, 2)
    asym = user_rule("asym", lambda s: s.M + sympy.Matrix(s.n, s.n, lambda i, j: 1 if i > j else 0))
    with pytest.raises(InputError, match="not symmetric"):
        mass_matrix(asym, gram_space(kv))
    claims_diag = user_rule("fake-diag", lambda s: s.M, states=MassProperties(diagonal=True))
    with pytest.raises(InputError, match="states diagonal"):
        mass_matrix(claims_diag, gram_space(kv))
    # a singular direction that is no zero row cannot be condensed by the explicit scheme
    ones = user_rule("rank-one", lambda s: sympy.ones(s.n, s.n) * sum(s.M) / s.n**2)
    with pytest.raises(InputError, match="not zero rows"):
        mass_matrix(ones, gram_space(kv))


def test_warnings_for_scaled_and_indefinite_masses():
    kv = open_knot_vector(1, 2)
    doubled = user_rule("doubled", lambda s: 2 * s.M)
    with pytest.warns(TranslationalMassWarning, match="translational"):
        mass_matrix(doubled, gram_space(kv))
    neg = user_rule("neg", lambda s: s.M - sympy.eye(s.n) / 4,
                    states=MassProperties(psd=False, translational=False))
    with pytest.warns(IndefiniteMassWarning), pytest.warns(TranslationalMassWarning):
        mass_matrix(neg, gram_space(kv))


def test_toml_rule_is_read_as_data_and_checked():
    rule = rule_from_toml(TOML_RULE)
    M = mass_matrix(rule, gram_space(open_knot_vector(2, 2)))
    assert M.is_diagonal() and M[3, 3] == 0 and sum(M) == 1  # [0, 1] has mass 1
    for bad, match in [('name = "x"\n[weights]\n"-1" = {"-2" = "a"}', "finite number"),
                       ('name = "x"\nexec = 1\n[weights]\n"0" = {"1" = 1}', "unknown keys"),
                       ('name = "lumped"\n[weights]\n"0" = {"1" = 1}', "new non-empty"),
                       ('name = "x"\n[weights]\n"0" = {"1" = 0.5}', "sum to 1"),
                       ("name = ", "TOML")]:
        with pytest.raises(InputError, match=match):
            mass_matrix(rule_from_toml(bad), gram_space(open_knot_vector(2, 2)))


def test_plate_patch_takes_every_rule_and_user_rules():
    for name in RULE_NAMES:
        bloch = RULES[name].basis == "bspline"  # C0 Lagrange rules: x-exact, n = 2 e + 1
        patch = plate_patch(2, 4 if bloch else 5, "bloch" if bloch else "x-exact",
                            2 if bloch else None, name)
        assert patch.mass == name and patch.My.is_symmetric()
    half = user_rule("half-lumped", lambda s: (s.M + sympy.diag(*[sum(s.M.row(i))
                                                                  for i in range(s.n)])) / 2)
    patch = plate_patch(2, 3, "bloch", 2, half)
    assert patch.mass == "half-lumped" and not patch.x_lumped
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        plate_patch(2, 3, "bloch", 2, rule_from_toml(TOML_RULE))


@pytest.mark.parametrize("name", ["hrz", "nodal-greville", "nodal-lobatto"])
def test_series_leading_term_is_exact_for_rules_keeping_translational_mass(name):
    # Omega^2 = 2 kappa^2 / (1 - nu) + ... (plate velocity, Rayleigh-Lamb long-wave limit):
    # the leading term needs only the static stiffness and the translational mass
    from dispersion.symbolic.power_balance import discrete_series

    s = discrete_series("S0", 4, nu=sympy.Rational(3, 10), mass=name, p=2, n=3)
    assert s[2] == sympy.Rational(20, 7)


@pytest.mark.parametrize("name", ["hrz", "nodal-greville", "nodal-lobatto"])
def test_periodic_bar_dispersion_takes_any_rule(name):
    # the float dispersion of the bar against the exact rational function of cos(theta)
    from dispersion.discretization.bar_dispersion import bar_frequency
    from dispersion.time_stepping.timestep import bar_omega_squared

    theta = np.linspace(0.1, np.pi, 7)
    f = sympy.lambdify(sympy.Symbol("z"), bar_omega_squared(name, 3), "numpy")
    assert np.allclose(bar_frequency(3, name, theta) ** 2, f(np.cos(theta)), rtol=1e-12)
    with pytest.raises(InputError, match="contact boundary"):
        bar_frequency(2, "singular", theta)


@pytest.mark.parametrize("name", ["consistent", "hrz", "nodal-greville", "nodal-lobatto"])
def test_closed_periodic_rows_equal_the_mesh_rows(name):
    # a user rule with the same builder takes the general path (middle row of an open mesh)
    twin = user_rule(f"twin-{name}", RULES[name].build, states=RULES[name].states)
    for p in (2, 3):
        assert x_mass_coefficients(twin, p) == x_mass_coefficients(name, p)


def test_ring_patch_takes_hrz_and_refuses_nodal_with_the_reason():
    # HRZ from the ring's own (rational, 2D) element matrices: diagonal, positive, and the
    # translational mass rho * area = rho * pi (R^2 - r^2) / 4 of the quarter ring kept
    from dispersion.contact.assembly import discretize, patch_mass
    from dispersion.contact.nurbs import quarter_ring

    disc = discretize(quarter_ring(1.0, 2.0, 2, 1))
    M = patch_mass(disc, 3.0, "hrz").toarray()
    assert np.count_nonzero(M - np.diag(np.diag(M))) == 0 and np.all(np.diag(M) > 0)
    assert M.sum() / 2 == pytest.approx(3.0 * np.pi * 3 / 4, rel=1e-6)  # 2 components
    with pytest.raises(InputError, match="1D B-spline space"):
        patch_mass(disc, 3.0, "nodal-greville")


def test_large_float_masses_are_checked_sparse_like_small_ones():
    # the sparse inertia path (n > DENSE_CHECK_MAX) against the dense one on the same matrices
    import scipy.sparse as sp

    from dispersion.mass_rules import mass_check

    n = mass_check.DENSE_CHECK_MAX + 1
    lap = sp.diags([np.full(n - 1, 1.0), np.full(n, 4.0), np.full(n - 1, 1.0)], [-1, 0, 1])
    cases = {"spd": lap.tocsr(), "indefinite": (lap - 5.5 * sp.eye(n)).tocsr()}
    rule = user_rule("as-given", lambda s: s.M,
                     states=MassProperties(psd=False, translational=True))
    for name, A in cases.items():
        big = check_mass(rule, A, A)
        small = check_mass(rule, A[:50, :50].toarray(), A[:50, :50].toarray())
        assert big.measured == small.measured, name
        assert big.measured.psd == (name == "spd")


@pytest.mark.parametrize("name", ["nodal-lobatto"] + [pytest.param(n, marks=pytest.mark.slow)
                                                      for n in RULE_NAMES if n != "nodal-lobatto"])
def test_float_pencil_equals_the_exact_dynamic_stiffness(name):
    # the fast float pencil (discrete branches) and the exact K - Omega^2 M share the x-mass
    from dispersion.symbolic.plate import dynamic_stiffness, numeric_pencil

    k, nu = sympy.Rational(7, 10), sympy.Rational(3, 10)
    bloch = RULES[name].basis == "bspline"  # C0 Lagrange rules: the x-exact patch
    patch = plate_patch(2, 3, "bloch" if bloch else "x-exact", 1 if bloch else None, name)
    K, M = numeric_pencil(patch, 0.3, [0.7])
    K0 = np.array(dynamic_stiffness(patch, k, 0, nu).evalf(), float)
    K1 = np.array(dynamic_stiffness(patch, k, 1, nu).evalf(), float)
    assert np.allclose(K[0], K0, atol=1e-13) and np.allclose(M[0], K0 - K1, atol=1e-13)
