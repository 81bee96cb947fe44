"""The Rayleigh-Lamb frequency equation of a plate of thickness 2h, in entire-function form.

Dimensionless: :math:`\\Omega = \\omega h / c_T`, :math:`\\kappa = k h`,
:math:`P = (ph)^2 = \\Omega^2 (c_T/c_L)^2 - \\kappa^2`, :math:`Q = (qh)^2 = \\Omega^2 - \\kappa^2`,
:math:`(c_T/c_L)^2 = (1-2\\nu) / (2(1-\\nu))` (plane strain). With
:math:`C(z) = \\cos\\sqrt z` and :math:`S(z) = \\sin\\sqrt z / \\sqrt z`, both entire in z,
the standard equations (Rose 2004, eqs 8.21-8.22) multiplied out free of tan poles read

.. math::

    F_S &= (Q - \\kappa^2)^2 \\, C(P) S(Q) + 4 \\kappa^2 P \\, S(P) C(Q) = 0
        \\quad \\text{(symmetric)}, \\\\
    F_A &= (Q - \\kappa^2)^2 \\, S(P) C(Q) + 4 \\kappa^2 Q \\, C(P) S(Q) = 0
        \\quad \\text{(antisymmetric)}.

The paper's eq (13) prints :math:`(p^2 - q^2)^2` in place of :math:`(q^2 - k^2)^2`;
``form="printed"`` gives that equation, for the errata.

:func:`frequency_function` takes the two entire functions as arguments, so the same formula
serves truncated power series (:mod:`dispersion.power_balance`) and floating point.

>>> import mpmath
>>> C = lambda z: mpmath.cos(mpmath.sqrt(z))
>>> S = lambda z: mpmath.sinc(mpmath.sqrt(z))
>>> abs(frequency_function("A", 0, 0, mpmath.mpf("0.3"), C, S)) < 1e-30
True

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, Cambridge University Press 2004, ch. 8.
"""
from __future__ import annotations

from .errors import InputError

__all__ = ["frequency_function", "speed_ratio_squared"]


def speed_ratio_squared(nu):
    """:math:`(c_T / c_L)^2 = (1 - 2\\nu) / (2 (1 - \\nu))` in plane strain."""
    return (1 - 2 * nu) / (2 * (1 - nu))


def frequency_function(kind: str, kappa2, Omega2, nu, C, S, form: str = "standard"):
    """Entire-function Rayleigh-Lamb characteristic function :math:`F(\\kappa^2, \\Omega^2)`.

    Parameters
    ----------
    kind : ``"S"`` or ``"A"``
        Symmetric or antisymmetric modes.
    kappa2, Omega2 :
        :math:`\\kappa^2` and :math:`\\Omega^2` in any arithmetic (numbers, series, arrays).
    nu :
        Poisson's ratio.
    C, S : callables
        :math:`C(z) = \\cos\\sqrt z` and :math:`S(z) = \\sin\\sqrt z/\\sqrt z` in that arithmetic.
    form : ``"standard"`` or ``"printed"``
        ``"printed"`` replaces :math:`(Q - \\kappa^2)^2` by :math:`(P - Q)^2` as in eq (13).
    """
    P = speed_ratio_squared(nu) * Omega2 - kappa2
    Q = Omega2 - kappa2
    if form == "standard":
        a = Q - kappa2
    elif form == "printed":
        a = P - Q
    else:
        raise InputError(f"form must be 'standard' or 'printed', got {form!r}")
    if kind == "S":
        return a * a * C(P) * S(Q) + 4 * kappa2 * P * S(P) * C(Q)
    if kind == "A":
        return a * a * S(P) * C(Q) + 4 * kappa2 * Q * C(P) * S(Q)
    raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
