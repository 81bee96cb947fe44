"""The deflated Rayleigh-Lamb function :math:`G = F / \\Omega^2` and the evanescent scaling.

:func:`~dispersion.continuum.rayleigh_lamb.frequency_function` F vanishes at :math:`\\Omega = 0` for
every :math:`\\kappa`, and near that trivial root its two terms cancel: on A0 at small kappa
(:math:`\\Omega^2 \\sim \\kappa^4`) F loses its relative accuracy. Divided by
:math:`\\Omega^2` in exact algebra (:func:`deflated_frequency_function`) it keeps it, and
:func:`deflated_with_noise` bounds its rounding error, so a scan knows where the sign of G
carries information. Where :math:`P < 0` makes F grow like :math:`e^{2\\kappa}`,
:func:`evanescent_frequency_function` divides the growth out. These are the forms the scan in
kappa at a fixed frequency samples (:mod:`dispersion.continuum.frequency`); the tracer in Omega
uses the form scaled by its Mindlin bounds (:mod:`dispersion.continuum.scaled_frequency`).

>>> g, noise = deflated_with_noise("A", 0.05, 0.002, 0.3)
>>> bool(abs(g) > 1e6 * noise)          # A0 at small kappa: G far above its rounding bound
True
"""
from __future__ import annotations

import numpy as np

from dispersion.errors import InputError
from dispersion.continuum.numeric_frequency import (C_TAYLOR, S_TAYLOR, cos_sqrt, divided_difference,
                                                plate_arguments, sinc_sqrt)

__all__ = ["deflated_frequency_function", "deflated_with_noise", "evanescent_frequency_function"]

#: Terms of the series of the divided differences of C and S (|P|, |Q| <= 2: error < 1e-30).
_SERIES_TERMS = 24


def _sinc(x):
    return np.sinc(x / np.pi)


def _divided_differences(P, Q):
    """:math:`C[P,Q]` and :math:`S[P,Q]`, the divided differences, without cancellation.

    Near the origin by their power series; elsewhere by the half-angle forms
    :math:`C[P,Q] = -\\tfrac12 \\operatorname{sinc}\\frac{p+q}2 \\operatorname{sinc}\\frac{p-q}2`
    and :math:`S[P,Q] = (T[P,Q] - S(P)) / Q` with :math:`T(z) = z S(z) = p \\sin p`,
    where :math:`p = \\sqrt P, q = \\sqrt Q` (complex for negative arguments).
    """
    P, Q = np.broadcast_arrays(np.asarray(P, dtype=float), np.asarray(Q, dtype=float))
    small = (np.abs(P) <= 2) & (np.abs(Q) <= 2)
    dC, dS = np.empty(P.shape), np.empty(P.shape)
    dC[small] = divided_difference(C_TAYLOR, P[small], Q[small], _SERIES_TERMS)
    dS[small] = divided_difference(S_TAYLOR, P[small], Q[small], _SERIES_TERMS)
    big = ~small
    if np.any(big):
        Pb, Qb = P[big], Q[big]
        p, q = np.sqrt(Pb + 0j), np.sqrt(Qb + 0j)
        dC[big] = (-0.5 * _sinc((p + q) / 2) * _sinc((p - q) / 2)).real
        far = np.abs(Pb - Qb) > 1
        with np.errstate(divide="ignore", invalid="ignore"):
            direct = (sinc_sqrt(Pb) - sinc_sqrt(Qb)) / np.where(far, Pb - Qb, 1.0)
            T = ((p * np.cos((p + q) / 2) * _sinc((p - q) / 2) + np.sin(q)) / (p + q)).real
            viaT = (T - sinc_sqrt(Pb)) / np.where(far, 1.0, Qb)
        dS[big] = np.where(far, direct, viaT)
    return dC, dS


def deflated_frequency_function(kind: str, kappa, Omega, nu: float):
    """:math:`G = F / \\Omega^2`: the frequency function with its trivial root removed.

    :func:`~dispersion.continuum.rayleigh_lamb.frequency_function` vanishes at
    :math:`\\Omega = 0` for every :math:`\\kappa` (there P = Q and the two terms cancel). With :math:`a = Q - \\kappa^2`,
    :math:`s = (c_T/c_L)^2` and the divided difference
    :math:`D = (C(P)S(Q) - S(P)C(Q))/(P - Q) = S(P)C[P,Q] - C(P)S[P,Q]`, exact algebra gives

    .. math::

        G_S &= -(1-s)\\,a^2 D + (\\Omega^2 - 4(1-s)\\kappa^2)\\, S(P) C(Q), \\\\
        G_A &= (1-s)\\,a^2 D + \\Omega^2\\, C(P) S(Q),

    free of the cancellation that costs :math:`F` its relative accuracy on A0 at small
    :math:`\\kappa` (there :math:`\\Omega^2 \\sim \\kappa^4`). ``tests/test_deflated_frequency.py``
    checks :math:`\\Omega^2 G = F` against the defining equation in mpmath.

    >>> abs(float(deflated_frequency_function("A", 0.1, 0.0, 0.3))) > 0
    True
    """
    return deflated_with_noise(kind, kappa, Omega, nu)[0]


def _float_arguments(kappa, Omega, nu: float):
    """:func:`~dispersion.continuum.numeric_frequency.plate_arguments` of float arrays, with
    :math:`a^2 = (Q - \\kappa^2)^2` in place of a."""
    k2, W2, s, P, Q, a = plate_arguments(np.asarray(kappa, dtype=float),
                                         np.asarray(Omega, dtype=float), nu)
    return k2, W2, s, P, Q, a * a


def deflated_with_noise(kind: str, kappa, Omega, nu: float):
    """:func:`deflated_frequency_function` and a bound on its rounding error.

    The bound is :math:`64\\,\\epsilon` times the sum of the magnitudes of the two terms:
    where :math:`|G|` lies below it the sign of G carries no information, so a root tracer
    must not count sign changes there (they are round-off, not roots).

    >>> import math
    >>> g, noise = deflated_with_noise("S", 1e-8, math.pi, 0.3)
    >>> bool(abs(g) <= noise)
    True
    """
    k2, W2, s, P, Q, a2 = _float_arguments(kappa, Omega, nu)
    dC, dS = _divided_differences(P, Q)
    CP, SP, CQ, SQ = cos_sqrt(P), sinc_sqrt(P), cos_sqrt(Q), sinc_sqrt(Q)
    D = SP * dC - CP * dS
    Dscale = np.abs(SP * dC) + np.abs(CP * dS)
    if kind == "S":
        t1, t2 = -(1 - s) * a2 * D, (W2 - 4 * (1 - s) * k2) * SP * CQ
    elif kind == "A":
        t1, t2 = (1 - s) * a2 * D, W2 * CP * SQ
    else:
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    scale = (1 - s) * a2 * Dscale + np.abs(t2)
    return t1 + t2, 64 * np.finfo(float).eps * scale


def evanescent_frequency_function(kind: str, kappa, Omega, nu: float):
    """The frequency function scaled for the evanescent region :math:`P < 0` (no overflow).

    With :math:`T(z) = S(z)/C(z)` (:math:`\\tanh\\sqrt{-z}/\\sqrt{-z}` for z < 0) and
    :math:`c_Q = C(Q)` where :math:`Q < 0`, else 1,

    .. math::

        F_S / (C(P) c_Q) &= a^2 S(Q)/c_Q + 4\\kappa^2 P\\,T(P)\\,C(Q)/c_Q, \\\\
        F_A / (C(P) c_Q) &= a^2 T(P)\\,C(Q)/c_Q + 4\\kappa^2 Q\\,S(Q)/c_Q,

    which has the roots of F with :math:`P < 0` and stays of order one where F grows like
    :math:`e^{2\\kappa}`: the form a root is polished on at large :math:`\\kappa` (the
    Rayleigh-wave limit of S0 and A0).

    >>> f = [float(evanescent_frequency_function("A", 10.0, w, 0.3)) for w in (9.27, 9.28)]
    >>> f[0] * f[1] < 0      # A0 at kappa = 10 lies at Omega = 9.2711348522995...
    True
    """
    k2, W2, s, P, Q, a2 = _float_arguments(kappa, Omega, nu)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        TP = sinc_sqrt(P) / cos_sqrt(P)
        cq = np.where(Q < 0, cos_sqrt(Q), 1.0)
        SQ, CQ = sinc_sqrt(Q) / cq, cos_sqrt(Q) / cq
    if kind == "S":
        return a2 * SQ + 4 * k2 * P * TP * CQ
    if kind == "A":
        return a2 * TP * CQ + 4 * k2 * Q * SQ
    raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
