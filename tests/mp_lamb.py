"""The Rayleigh-Lamb equation in mpmath arithmetic, the reference of the float forms (tests only).

The defining equation :func:`dispersion.continuum.rayleigh_lamb.frequency_function` with mpmath's
own :math:`C(z) = \\cos\\sqrt z` and :math:`S(z) = \\operatorname{sinc}\\sqrt z`
(:func:`~dispersion.continuum.rayleigh_lamb.mpmath_frequency_function`); none of the float forms
(numeric, deflated, scaled) is used. Callers set the precision
(``mpmath.workdps``).
"""
from __future__ import annotations

import mpmath

from dispersion.continuum.rayleigh_lamb import mpmath_frequency_function


def mp_C(z):
    return mpmath.cos(mpmath.sqrt(z))


def mp_S(z):
    return mpmath.sinc(mpmath.sqrt(z))


def mp_F(kind, kappa, Omega, nu):
    """F(kappa, Omega) of the defining equation, real part, at the current mpmath precision."""
    return mpmath_frequency_function(kind, kappa, Omega, nu)
