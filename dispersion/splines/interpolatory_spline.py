"""Interpolatory spline basis with nodal quadrature, written in the B-spline basis.

The interpolatory (cardinal) basis :math:`L_i` of a spline space interpolates at points
:math:`x_q`: :math:`L_i(x_q) = \\delta_{iq}`. With the collocation matrix
:math:`T_{qj} = N_j(x_q)`, :math:`L = T^{-T} N` (as column vectors of functions), and the
quadrature with nodes :math:`x_q` that is exact on the spline space has the weights
:math:`w = \\int L = T^{-T} \\int N`. Nodal quadrature in the interpolatory basis gives the
diagonal mass :math:`W = \\operatorname{diag}(w)`; written in B-spline coordinates
(:math:`u_L = T c`), the same mass is

.. math::  M = T^T W T = \\sum_q w_q \\mathbf N(x_q) \\mathbf N(x_q)^T,

congruent to :math:`W`: the pencils :math:`(K_B, M)` and :math:`(T^{-T} K_B T^{-1}, W)` have
the same eigenvalues, so the dispersion is derived exactly in B-spline coordinates while
the explicit step runs with a diagonal mass and the interpolatory basis's *dense* stiffness
(the cardinal splines have global support, decaying away from their node).

Points: the Greville abscissae (the interpolation points of this toolkit; the nodes of
Voet and Sande's study may differ: their text was not accessible here). On a uniform
periodic mesh every weight equals the element length, so the periodic row equals that of
``nodal-greville``; the two rules differ at the boundary, where ``nodal-greville`` takes
:math:`\\int N_q` and this rule the interpolatory weights.

>>> from dispersion.splines.bspline import open_knot_vector
>>> [str(w) for w in interpolatory_weights(open_knot_vector(2, 2))]   # exact on splines
['1/18', '4/9', '4/9', '1/18']

References
----------
Y. Voet, E. Sande, "On the prospects of interpolatory spline bases for accurate mass lumping
strategies in isogeometric analysis", arXiv:2510.13510 (2025).
C. de Boor, *A Practical Guide to Splines*, Springer 2001 (spline interpolation at the
Greville points, Schoenberg-Whitney condition).
"""
from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

import numpy as np
import sympy

__all__ = ["collocation_matrix", "interpolatory_weights", "interpolatory_mass"]


def _frac(x) -> Fraction:
    return Fraction(int(x.p), int(x.q))


@lru_cache(maxsize=64)
def collocation_matrix(kv) -> sympy.ImmutableMatrix:
    """:math:`T_{qj} = N_j(g_q)` at the Greville points (exact).

    >>> from dispersion.splines.bspline import open_knot_vector
    >>> collocation_matrix(open_knot_vector(2, 2)).tolist()
    [[1, 0, 0, 0], [1/4, 5/8, 1/8, 0], [0, 1/8, 5/8, 1/4], [0, 0, 0, 1]]
    """
    from dispersion.splines.spline_mass import _bernstein_at, _elements

    n, p = kv.n, kv.p
    g = [_frac(x) for x in kv.greville()]
    last = _frac(kv.knots[-1])
    T = np.full((n, n), Fraction(0), dtype=object)
    for a, b, act, C in _elements(kv):
        for q, gq in enumerate(g):
            if a <= gq < b or (gq == b == last):
                T[q, list(act)] = C.dot(_bernstein_at(p, (gq - a) / (b - a)))
    return sympy.ImmutableMatrix(n, n, lambda i, j: sympy.Rational(T[i, j].numerator,
                                                                   T[i, j].denominator))


@lru_cache(maxsize=64)
def interpolatory_weights(kv) -> tuple[sympy.Rational, ...]:
    """Weights :math:`w = T^{-T} \\int N` of the spline-exact quadrature at the Greville points."""
    from dispersion.splines.spline_mass import gram_matrix

    b = sympy.Matrix(gram_matrix(kv)) * sympy.ones(kv.n, 1)  # int N_i (partition of unity)
    w = sympy.Matrix(collocation_matrix(kv)).T.LUsolve(b)
    return tuple(sympy.nsimplify(v) for v in w)


@lru_cache(maxsize=64)
def interpolatory_mass(kv) -> sympy.ImmutableMatrix:
    """:math:`M = T^T W T` (module docstring), exact.

    >>> from dispersion.splines.bspline import open_knot_vector
    >>> interpolatory_mass(open_knot_vector(1, 2)).tolist()     # p = 1: the lumped mass
    [[1/4, 0, 0], [0, 1/2, 0], [0, 0, 1/4]]
    """
    T = sympy.Matrix(collocation_matrix(kv))
    W = sympy.diag(*interpolatory_weights(kv))
    return sympy.ImmutableMatrix(T.T * W * T)
