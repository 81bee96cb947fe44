"""Selective mass scaling: artificial mass that leaves rigid translation untouched.

Selective mass scaling (SMS) adds a mass :math:`\\Lambda` to a (lumped) mass so that the
highest frequencies drop and the critical step of central differences grows, while the
translational (rigid-body) mass is kept: :math:`\\Lambda \\mathbf 1 = 0`
(Olovsson, Simonsson, Unosson 2005). The stiffness-proportional form keeps the eigenmodes
and makes the reduction computable (as reviewed by Tkachuk and Bischoff 2013); this toolkit
uses its scalar (Laplacian) version per direction,

.. math::

    M_\\beta = M_L + \\beta\\, h^2 \\int \\mathbf N' \\mathbf N'^T,

with :math:`M_L` the row-sum lumped mass, h the element length and :math:`\\beta \\ge 0` the
scaling parameter. On the Bloch plate the scaled masses multiply as a tensor product of the
thickness and x-directions (the patch's mass is a product :math:`m_x(\\theta) M_y`); this is
the toolkit's statement of the rule, not a claim that either paper's 2D element mass has this
form. On the periodic bar of unit elements it gives

.. math::  \\Omega^2 = \\frac{d(\\theta)}{1 + \\beta d(\\theta)} \\le \\frac{1}{\\beta},

so :math:`\\Omega_{max}^2 = d_{max} / (1 + \\beta d_{max})`: the step grows by
:math:`\\sqrt{1 + \\beta d_{max}}`, and the low branch is slowed by
:math:`\\Omega^2 \\approx \\theta^2 (1 - \\beta \\theta^2)`: a second-order error whatever p.

>>> scaled_row(1, "1/4")                      # lumped 1 plus beta * (-1, 2, -1)
{-1: -1/4, 0: 3/2, 1: -1/4}

References
----------
L. Olovsson, K. Simonsson, M. Unosson, "Selective mass scaling for explicit finite element
analyses", IJNME 63 (2005) 1436-1445, doi:10.1002/nme.1293.
A. Tkachuk, M. Bischoff, "Variational methods for selective mass scaling", Comput. Mech. 52
(2013) 563-570, doi:10.1007/s00466-012-0808-4. A. Tkachuk, M. Bischoff, "Local and global
strategies for optimal selective mass scaling", Comput. Mech. 53 (2014) 1197-1207,
doi:10.1007/s00466-013-0832-0 (its introduction reviews the stiffness-proportional and the
algebraic SMS of Olovsson et al.).
"""
from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING

from dispersion.errors import InputError

if TYPE_CHECKING:  # sympy is imported where the matrix is built
    import sympy

__all__ = ["SMS_BETA", "check_beta", "scaled_mass", "scaled_row"]

#: The registered rule's scaling parameter. Rule, stated before any result: the smallest
#: beta of the form 1/2^k that raises the p = 1 bar's critical step by half or more
#: (:math:`\\sqrt{1 + 4\\beta} \\ge 1.5 \\Leftrightarrow \\beta \\ge 5/16`): 1/2.
SMS_BETA = Fraction(1, 2)


def check_beta(beta) -> Fraction:
    """``beta`` as an exact rational in [0, 100] (a number or a "p/q" string), else
    :class:`InputError`."""
    from dispersion.reader import read_number

    try:
        if isinstance(beta, bool):
            raise TypeError
        # text by the whitelist (bounded digits and exponents), never Fraction("1e999999999")
        b = read_number(beta) if isinstance(beta, str) else \
            Fraction(repr(beta) if isinstance(beta, float) else str(beta))
    except (TypeError, ValueError, ZeroDivisionError):
        raise InputError(f"scaling parameter beta must be a rational number, got {beta!r}") \
            from None
    if not 0 <= b <= 100:
        raise InputError(f"scaling parameter beta must lie in [0, 100], got {b}")
    return b


def scaled_mass(kv, beta=SMS_BETA) -> sympy.ImmutableMatrix:
    """:math:`M_L + \\beta h^2 \\int N' N'^T` on knot vector ``kv`` (h: its largest element).

    >>> from dispersion.splines.bspline import open_knot_vector
    >>> scaled_mass(open_knot_vector(1, 1), 1).tolist()
    [[3/2, -1], [-1, 3/2]]
    """
    import sympy

    from dispersion.splines.derivative_gram import derivative_gram
    from dispersion.mass_rules.mass import row_sum_lump
    from dispersion.splines.spline_mass import gram_matrix

    beta = check_beta(beta)
    ks = list(kv.knots)
    h = max(b - a for a, b in zip(ks, ks[1:]))
    D = sympy.Matrix(derivative_gram(kv))
    return sympy.ImmutableMatrix(row_sum_lump(sympy.Matrix(gram_matrix(kv)))
                                 + sympy.Rational(beta.numerator, beta.denominator) * h**2 * D)


def scaled_row(p: int, beta=SMS_BETA) -> dict:
    """The periodic row :math:`\\delta_{L0} + \\beta c^{11}_L` on unit elements (sympy
    rationals)."""
    import sympy

    from dispersion.splines.derivative_gram import uniform_derivative_row

    beta = check_beta(beta)
    row = {L: beta * v for L, v in uniform_derivative_row(p).items()}
    row[0] = row.get(0, 0) + 1
    return {L: sympy.Rational(v.numerator, v.denominator) for L, v in sorted(row.items())
            if v != 0}
