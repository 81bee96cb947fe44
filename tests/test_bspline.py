"""Properties of dispersion.splines.bspline: partition of unity, positivity, continuity, Greville."""
import numpy as np
import pytest
import sympy

from dispersion.splines import bspline
from dispersion.errors import InputError

x = sympy.Symbol("x")


@pytest.mark.parametrize("p,n_el", [(1, 3), (2, 1), (2, 4), (3, 3), (4, 2)])
def test_partition_of_unity_and_nonnegativity(p, n_el):
    kv = bspline.open_knot_vector(p, n_el, -1, 1)
    assert kv.n == p + n_el
    for (a, b), polys, active in bspline.basis_polynomials(kv, x, local=False):
        assert sympy.expand(sum(polys) - 1) == 0
        for f in polys:
            vals = [f.subs(x, a + (b - a) * sympy.Rational(k, 7)) for k in range(8)]
            assert min(vals) >= 0


@pytest.mark.parametrize("p", [1, 2, 3, 4])
def test_cardinal_spline_is_c_p_minus_1_across_uniform_knots(p):
    pieces = bspline.cardinal_pieces(p, x)  # local coordinate on each unit span
    for j in range(p):
        left, right = pieces[j], pieces[j + 1]
        for r in range(p):  # derivatives 0..p-1 agree at the shared knot
            assert sympy.diff(left, x, r).subs(x, 1) == sympy.diff(right, x, r).subs(x, 0)
        assert sympy.diff(left, x, p).subs(x, 1) != sympy.diff(right, x, p).subs(x, 0)
    # integral of the cardinal B-spline is 1 (unit knot spacing)
    assert sum(sympy.integrate(f, (x, 0, 1)) for f in pieces) == 1


def test_greville_abscissae_reproduce_linear_function():
    # sum_i g_i N_i(x) = x (linear precision; Piegl & Tiller) is the defining property
    kv = bspline.open_knot_vector(3, 4, 0, 2)
    g = kv.greville()
    for (a, b), polys, active in bspline.basis_polynomials(kv, x, local=False):
        assert sympy.expand(sum(g[i] * f for i, f in zip(active, polys)) - x) == 0


def test_knot_insertion_keeps_the_curve():
    kv = bspline.open_knot_vector(2, 2)
    P = sympy.Matrix([3, -1, 2, 5])
    new, A = bspline.insert_knot(kv, sympy.Rational(1, 4))
    Q = A * P

    def curve(k, coeffs, xv):
        for (a, b), polys, active in bspline.basis_polynomials(k, x, local=False):
            if a <= xv <= b:
                return sum(coeffs[i] * f.subs(x, xv) for i, f in zip(active, polys))

    for xv in [sympy.Rational(k, 9) for k in range(10)]:
        assert curve(kv, P, xv) == curve(new, Q, xv)


def test_bernstein_numeric_derivative_matches_finite_difference():
    u, h = np.array([0.2, 0.7]), 1e-6
    fd = (bspline.bernstein_numeric(3, u + h) - bspline.bernstein_numeric(3, u - h)) / (2 * h)
    assert np.allclose(bspline.bernstein_numeric(3, u, 1), fd, atol=1e-8)


def test_bad_input():
    with pytest.raises(InputError, match="degree p"):
        bspline.open_knot_vector(0, 2)
    with pytest.raises(InputError, match="outside"):
        bspline.insert_knot(bspline.open_knot_vector(2, 1), 2)


def test_spline_basis_1d_matches_the_exact_extraction():
    # the float twin (SplineBasis1D) against the exact sympy polynomials of the same knots
    import numpy as np
    import sympy

    from dispersion.splines.bspline import SplineBasis1D, basis_polynomials, open_knot_vector

    kv = open_knot_vector(3, 4, -1, 1)
    basis = SplineBasis1D.from_knots(kv)
    x = sympy.Symbol("x")
    for (a, b), polys, active in basis_polynomials(kv, x, local=False):
        pts = np.linspace(float(a), float(b), 5)[1:-1]
        act, N = basis.evaluate(pts)
        assert act[0].tolist() == list(active)
        ref = np.array([[float(f.subs(x, p)) for f in polys] for p in pts])
        assert np.allclose(N, ref, atol=1e-14)
        assert np.allclose(N.sum(axis=1), 1.0)  # partition of unity


def test_open_knot_vector_bounds_the_number_of_elements():
    with pytest.raises(InputError, match=f"in \\[1, {bspline.MAX_ELEMENTS}\\]"):
        bspline.open_knot_vector(2, bspline.MAX_ELEMENTS + 1)
