"""Truncated-series kernel: arithmetic, Bareiss determinant, branch solve, each checked independently."""
from __future__ import annotations

import random

import flint
import pytest
import sympy

from dispersion.errors import DispersionError
from dispersion.symbolic.series_kernel import Series, branch_coefficients, context, determinant, entire

CTX = context(("nu",))
W, NU_G = CTX.gens()
t_sym, w_sym, nu_sym = sympy.symbols("t w nu")


def to_sympy(series: Series) -> sympy.Expr:
    out = 0
    for k, c in enumerate(series.coeffs):
        for mon, v in c.to_dict().items():
            out += sympy.Rational(int(v.p), int(v.q)) * w_sym ** mon[0] * nu_sym ** mon[1] * t_sym**k
    return sympy.expand(out)


def truncate(expr: sympy.Expr, D: int) -> sympy.Expr:
    poly = sympy.Poly(sympy.expand(expr), t_sym)
    return sympy.expand(sum(c * t_sym**m[0] for m, c in poly.terms() if m[0] <= D))


def test_entire_functions_match_taylor_series_of_cos_and_sinc():
    D = 6
    t = Series.gen_t(CTX, D)
    z = t * (2 * NU_G) + t * t * W  # any series without constant term
    x = sympy.Symbol("x")
    zs = to_sympy(z)
    for kind, f in (("C", sympy.cos(sympy.sqrt(x))), ("S", sympy.sin(sympy.sqrt(x)) / sympy.sqrt(x))):
        taylor = sympy.series(f, x, 0, D + 1).removeO()
        expected = truncate(taylor.subs(x, zs), D)
        assert sympy.expand(to_sympy(entire(z, kind)) - expected) == 0


def random_series(rng, D):
    coeffs = [rng.randint(-3, 3) + rng.randint(-2, 2) * NU_G + rng.randint(-1, 1) * W
              for _ in range(D + 1)]
    return Series(CTX, coeffs, D)


@pytest.mark.parametrize("seed,n,singular", [(1, 3, False), pytest.param(2, 4, True, marks=pytest.mark.slow),
                                             pytest.param(3, 4, True, marks=pytest.mark.slow)])
def test_determinant_equals_sympy_det_truncated(seed, n, singular):
    # Bareiss over truncated series against sympy's Matrix.det of the same polynomial matrix;
    # `singular` makes A(t=0) rank deficient (rows 0 and 1 equal at t = 0), which forces the
    # Sylvester finish on the trailing block
    rng = random.Random(seed)
    D = 3 if n == 3 else 2
    rows = [[random_series(rng, D) for _ in range(n)] for _ in range(n)]
    if singular:
        for j in range(n):
            rows[1][j] = Series(CTX, [rows[0][j].coeffs[0]] + rows[1][j].coeffs[1:], D)
    ours = to_sympy(determinant(rows))
    M = sympy.Matrix(n, n, lambda i, j: to_sympy(rows[i][j]))
    assert sympy.expand(ours - truncate(M.det(method="berkowitz"), D)) == 0


def test_branch_solve_recovers_a_known_root_series():
    # F = ((1 - 2 nu) w - (1 - 2 nu) a(t)) w with a(t) = 1 + nu t + t^2 / (1 - 2 nu): the
    # non-zero simple root at t = 0 is w0 = 1, then w = a(t) exactly (w = 0 is the trivial root)
    D = 5
    one = CTX.from_dict({}) + 1
    a = Series(CTX, [(1 - 2 * NU_G), NU_G * (1 - 2 * NU_G), one], D)  # (1 - 2 nu) a(t)
    w = Series(CTX, [W], D)
    F = (w * (1 - 2 * NU_G) - a) * w
    nums, dens = branch_coefficients(F, 3)
    values = [sympy.cancel(to_sympy(Series(CTX, [n], 0)) / to_sympy(Series(CTX, [d], 0)))
              for n, d in zip(nums, dens)]
    assert values == [1, nu_sym, sympy.cancel(1 / (1 - 2 * nu_sym)), 0]


def test_double_root_is_refused():
    D = 3
    w = Series(CTX, [W], D)
    F = (w - 1) * (w - 1) + Series.gen_t(CTX, D)
    with pytest.raises(DispersionError, match="no unique simple non-zero root"):
        branch_coefficients(F, 2)


def test_exact_division_is_checked():
    with pytest.raises(Exception):
        Series(CTX, [W + 1], 1) / (NU_G + 3)
    assert isinstance(flint.fmpq(1, 2), flint.fmpq)
