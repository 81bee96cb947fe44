"""The Rayleigh-Lamb frequency function in floating point: C, S, F and the slope of a root.

The equation is :func:`dispersion.continuum.rayleigh_lamb.frequency_function`, written for any
arithmetic that supplies the two entire functions :math:`C(z) = \\cos\\sqrt z` and
:math:`S(z) = \\sin\\sqrt z / \\sqrt z`. This module supplies them for real numpy arrays
(:func:`cos_sqrt`, :func:`sinc_sqrt`), evaluates F with them
(:func:`numeric_frequency_function`) and the slope :math:`d\\Omega/d\\kappa` of a root in
closed form (:func:`frequency_slope`). It also holds the Taylor coefficients of C and S and
the divided difference of a power series, which the deflated and the scaled forms
(:mod:`dispersion.continuum.deflated_frequency`, :mod:`dispersion.continuum.scaled_frequency`) build on,
and F with a proven bound on its rounding error (:func:`frequency_function_bound`), the float
half of the certificate of a root (:mod:`dispersion.continuum.root_certificate`).

>>> abs(float(numeric_frequency_function("S", 0.0, math.pi, 0.3))) < 1e-12
True

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, Cambridge University Press 2004, ch. 8.
"""
from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from dispersion.errors import InputError
from dispersion.continuum.rayleigh_lamb import frequency_function, speed_ratio_squared

__all__ = [
    "C_TAYLOR", "LIBM_ULPS", "S_TAYLOR", "cos_sqrt", "divided_difference", "frequency_function_bound",
    "frequency_slope", "numeric_frequency_function", "plate_arguments", "sinc_sqrt",
    "sinc_sqrt_prime", "taylor_sum",
]

_N_TAYLOR = 32
#: Taylor coefficients in z of C(z) = cos sqrt(z) and S(z) = sin sqrt(z) / sqrt(z), exact.
C_TAYLOR = tuple(Fraction((-1) ** k, math.factorial(2 * k)) for k in range(_N_TAYLOR))
S_TAYLOR = tuple(Fraction((-1) ** k, math.factorial(2 * k + 1)) for k in range(_N_TAYLOR))
_S_FLOAT = [float(c) for c in S_TAYLOR]


def plate_arguments(kappa, Omega, nu: float):
    """:math:`\\kappa^2, \\Omega^2, s = (c_T/c_L)^2, P = s\\Omega^2 - \\kappa^2,
    Q = \\Omega^2 - \\kappa^2` and :math:`a = Q - \\kappa^2`, in the arithmetic of the
    arguments (float or complex arrays).

    >>> plate_arguments(1.0, 2.0, 0.25)
    (1.0, 4.0, 0.3333333333333333, 0.33333333333333326, 3.0, 2.0)
    """
    k2, W2 = kappa * kappa, Omega * Omega
    s = speed_ratio_squared(nu)
    P, Q = s * W2 - k2, W2 - k2
    return k2, W2, s, P, Q, Q - k2


def taylor_sum(coef, z, terms: int):
    """:math:`\\sum_{k < terms} c_k z^k` by Horner's rule (float or complex z).

    >>> float(taylor_sum(C_TAYLOR, 0.25, 12)) == math.cos(0.5)
    True
    """
    out = float(coef[terms - 1]) + 0 * z
    for c in coef[terms - 2::-1]:
        out = out * z + float(c)
    return out


def divided_difference(coef, P, Q, terms: int = 28):
    """:math:`f[P, Q] = (f(P) - f(Q)) / (P - Q)` of :math:`f = \\sum_k c_k z^k`, without
    cancellation: :math:`\\sum_k c_k h_{k-1}(P, Q)`, h the complete homogeneous polynomials.

    >>> d = divided_difference(S_TAYLOR, 0.3, 0.1)
    >>> abs(float(d) - float((sinc_sqrt(0.3) - sinc_sqrt(0.1)) / 0.2)) < 1e-15
    True
    """
    h, qk = 1 + 0 * P, 1 + 0 * Q
    out = 0 * P
    for k in range(1, terms):
        out = out + float(coef[k]) * h
        qk = qk * Q
        h = P * h + qk
    return out


def cos_sqrt(z):
    """:math:`C(z) = \\cos\\sqrt z` for real arrays (``cosh`` of :math:`\\sqrt{-z}` for z < 0).

    >>> float(cos_sqrt(-1.0)) == math.cosh(1.0)
    True
    """
    z = np.asarray(z, dtype=float)
    t = np.sqrt(np.abs(z))
    return np.where(z >= 0, np.cos(t), np.cosh(t))


def sinc_sqrt(z):
    """:math:`S(z) = \\sin\\sqrt z / \\sqrt z` for real arrays, equal to 1 at z = 0.

    >>> float(sinc_sqrt(0.0)), float(sinc_sqrt(math.pi**2)) < 1e-16
    (1.0, True)
    """
    z = np.asarray(z, dtype=float)
    t = np.sqrt(np.abs(z))
    safe = np.where(t == 0, 1.0, t)
    return np.where(t == 0, 1.0, np.where(z >= 0, np.sin(safe), np.sinh(safe)) / safe)


def sinc_sqrt_prime(z):
    """:math:`S'(z) = (C(z) - S(z)) / (2z)`, by its power series near 0.

    >>> float(sinc_sqrt_prime(0.0)) == -1 / 6
    True
    """
    z = np.asarray(z, dtype=float)
    small = np.abs(z) < 0.5
    with np.errstate(divide="ignore", invalid="ignore"):
        out = (cos_sqrt(z) - sinc_sqrt(z)) / (2 * np.where(small, 1.0, z))
    ser = np.zeros_like(z)
    zk = np.ones_like(z)
    for k in range(1, 14):
        ser += k * _S_FLOAT[k] * zk
        zk = zk * z
    return np.where(small, ser, out)


def numeric_frequency_function(kind: str, kappa, Omega, nu: float, form: str = "standard"):
    """:func:`~dispersion.continuum.rayleigh_lamb.frequency_function` evaluated in floating point
    (numpy arrays broadcast).

    >>> abs(float(numeric_frequency_function("A", 0.0, math.pi / 2, 0.3))) < 1e-12
    True
    """
    kappa, Omega = np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float)
    return frequency_function(kind, kappa**2, Omega**2, nu, cos_sqrt, sinc_sqrt, form)


def frequency_slope(kind: str, kappa, Omega, nu: float):
    """Slope :math:`d\\Omega/d\\kappa = -F_\\kappa / F_\\Omega` of a root of F (implicit function).

    With :math:`C'(z) = -S(z)/2` and :math:`S'(z) = (C(z) - S(z))/(2z)` the partial derivatives
    of :func:`~dispersion.continuum.rayleigh_lamb.frequency_function` in :math:`(\\kappa^2, P, Q)`
    are closed forms, and

    .. math::

        \\frac{d\\Omega}{d\\kappa} = -\\frac{\\kappa\\,(F_{\\kappa^2} - F_P - F_Q)}
                                         {\\Omega\\,(s F_P + F_Q)},

    the dimensionless group velocity :math:`c_g / c_T` when :math:`(\\kappa, \\Omega)` lies
    on a branch. Meaningful only at roots (elsewhere it is the slope of a level set).

    >>> cp = math.sqrt(2 / (1 - 0.3))   # plate speed / c_T: the S0 slope at kappa -> 0
    >>> W = float(cp * 0.01)
    >>> abs(float(frequency_slope("S", 0.01, W, 0.3)) - cp) < 1e-4
    True
    """
    kappa, Omega = np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float)
    k2, W2, s, P, Q, a = plate_arguments(kappa, Omega, nu)
    CP, SP, CQ, SQ = cos_sqrt(P), sinc_sqrt(P), cos_sqrt(Q), sinc_sqrt(Q)
    dCP, dCQ = -SP / 2, -SQ / 2
    dSP, dSQ = sinc_sqrt_prime(P), sinc_sqrt_prime(Q)
    if kind == "S":
        Fk = -2 * a * CP * SQ + 4 * P * SP * CQ
        FP = a * a * dCP * SQ + 4 * k2 * (SP + P * dSP) * CQ
        FQ = 2 * a * CP * SQ + a * a * CP * dSQ + 4 * k2 * P * SP * dCQ
    elif kind == "A":
        Fk = -2 * a * SP * CQ + 4 * Q * CP * SQ
        FP = a * a * dSP * CQ + 4 * k2 * Q * dCP * SQ
        FQ = 2 * a * SP * CQ + a * a * SP * dCQ + 4 * k2 * (CP * SQ + Q * CP * dSQ)
    else:
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    with np.errstate(divide="ignore", invalid="ignore"):
        return -kappa * (Fk - FP - FQ) / (Omega * (s * FP + FQ))


#: Accuracy assumed of numpy's cos, sin, cosh, sinh and sqrt: within this many units of
#: :math:`2^{-53}` relative to the exact result (glibc documents 1-2 ulp for these, numpy's
#: own SIMD loops are validated to 4; twice that). :func:`frequency_function_bound` rests on it.
LIBM_ULPS = 8
_U = 2.0**-53


def _mul(x, ex, y, ey):
    """Running error of a product: |X Y - fl(x y)| for |X - x| <= ex, |Y - y| <= ey."""
    v = x * y
    return v, np.abs(x) * ey + np.abs(y) * ex + ex * ey + _U * np.abs(v)


def _add(x, ex, y, ey):
    v = x + y
    return v, ex + ey + _U * np.abs(v)


def _c_s_bound(z, ez):
    """C(z), S(z) in floats and bounds on their errors against C, S at any exact point
    within ``ez`` of z: the evaluation at z (:data:`LIBM_ULPS` per function, the rounding of
    :math:`t = \\sqrt{|z|}`) plus ``ez`` times a bound on |C'|, |S'| over [z - ez, z + ez].

    The derivative bounds: for :math:`z \\ge 0`, :math:`|C'| = |\\sin t|/(2t) \\le
    \\min(1/2, 1/(2t))` and, since :math:`\\sin t - t\\cos t = \\int_0^t r \\sin r\\,dr`,
    :math:`|S'| = |\\sin t - t \\cos t| / (2t^3) \\le \\min(1/6, (1+t)/(2t^3))`; for
    :math:`z < 0` both grow with |z| (series of positive terms), so their value at the most
    negative point bounds them (1/2 and 1/6 at z = 0 included).
    """
    L = LIBM_ULPS * _U
    t = np.sqrt(np.abs(z))
    pos = z >= 0
    safe = np.where(t == 0, 1.0, t)
    with np.errstate(over="ignore", invalid="ignore"):
        sn = np.where(pos, np.sin(t), np.sinh(t))
        C = np.where(pos, np.cos(t), np.cosh(t))
        S = np.where(t == 0, 1.0, sn / safe)
        # at z: the functions' own error and the rounding of t (u/2 relative) through dC/dt
        # = -sin t (sinh t) and t dS/dt = C - S
        eC = L * np.abs(C) + 0.5 * _U * t * np.abs(sn)
        eS = (L + _U) * np.abs(S) + 0.5 * _U * np.abs(C - S) + L * np.abs(sn) / safe
        lo = z - ez
        t_lo = np.sqrt(np.maximum(lo, 0.0)) * (1 - 4 * _U)
        t_hi = np.sqrt(np.maximum(-lo, 0.0)) * (1 + 4 * _U)
        inv = np.where(t_lo > 0, 1 / np.where(t_lo > 0, t_lo, 1.0), np.inf)
        dC_pos = np.minimum(0.5, 0.5 * inv)
        dS_pos = np.minimum(1 / 6, 0.5 * (1 + t_lo) * inv**3)
        th = np.where(t_hi > 0, t_hi, 1.0)
        dC_neg = np.where(t_hi > 1e-3, np.sinh(th) / (2 * th), 0.5 * (1 + t_hi * t_hi))
        dS_neg = np.where(t_hi > 1, (np.cosh(th) - np.sinh(th) / th) / (2 * th * th), 0.19)
        dC = np.where(lo >= 0, dC_pos, dC_neg) * (1 + 1e-9)
        dS = np.where(lo >= 0, dS_pos, np.maximum(dS_neg, 1 / 6)) * (1 + 1e-9)
    return C, eC + dC * ez, S, eS + dS * ez


def frequency_function_bound(kind: str, kappa, Omega, ratio: float, ratio_error: float = 0.0):
    """F of :func:`~dispersion.continuum.rayleigh_lamb.frequency_function` in floats and a proven
    bound on its error against F in exact arithmetic at the same kappa and Omega.

    ``kappa`` and ``Omega`` are taken as exact (float arrays); ``ratio`` is
    :math:`s = (c_T/c_L)^2` in floats, within ``ratio_error`` of the exact s (the float
    nearest to a rational s: half an ulp). The bound is a running error analysis (Higham 2002,
    sec. 3.3): every product and sum adds its rounding to the propagated errors of its
    operands, and C, S add their own (:data:`LIBM_ULPS`) and their derivative bounds times the
    error of their argument; the sum of the bound's own terms is inflated by 1e-6 relative, far
    more than its rounding. Where :math:`|F| > B` the sign of the exact F is that of the float:
    the float half of a root's certificate (:mod:`dispersion.continuum.root_certificate`).

    >>> F, B = frequency_function_bound("S", np.array([1.0]), np.array([2.0]), 1 / 3, 2**-54)
    >>> bool(0 < B[0] < 1e-14 * abs(F[0]))
    True

    References
    ----------
    N. J. Higham, *Accuracy and stability of numerical algorithms*, 2nd ed., SIAM 2002,
    sec. 3.3 (running error analysis).
    """
    k = np.asarray(kappa, dtype=float)
    W = np.asarray(Omega, dtype=float)
    k2, ek2 = _mul(k, 0.0, k, 0.0)
    W2, eW2 = _mul(W, 0.0, W, 0.0)
    sW2, esW2 = _mul(ratio, ratio_error, W2, eW2)
    P, eP = _add(sW2, esW2, -k2, ek2)
    Q, eQ = _add(W2, eW2, -k2, ek2)
    a, ea = _add(Q, eQ, -k2, ek2)
    a2, ea2 = _mul(a, ea, a, ea)
    CP, eCP, SP, eSP = _c_s_bound(P, eP)
    CQ, eCQ, SQ, eSQ = _c_s_bound(Q, eQ)
    k4, ek4 = 4 * k2, 4 * ek2           # exact scaling
    if kind == "S":
        t1, e1 = _mul(*_mul(a2, ea2, CP, eCP), SQ, eSQ)
        t2, e2 = _mul(*_mul(*_mul(k4, ek4, P, eP), SP, eSP), CQ, eCQ)
    elif kind == "A":
        t1, e1 = _mul(*_mul(a2, ea2, SP, eSP), CQ, eCQ)
        t2, e2 = _mul(*_mul(*_mul(k4, ek4, Q, eQ), CP, eCP), SQ, eSQ)
    else:
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    F, eF = _add(t1, e1, t2, e2)
    return F, eF * (1 + 1e-6)
