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
serves truncated power series (:mod:`dispersion.continuum.exact_series`) and floating point. This
module holds the equation and its closed-form roots at :math:`\\kappa = 0`; the forms that
evaluate it in floating point live beside it, each named for what it holds:

- :mod:`dispersion.continuum.numeric_frequency`: C, S and F in floating point, and the slope
  :math:`d\\Omega/d\\kappa` of a root of F;
- :mod:`dispersion.continuum.deflated_frequency`: :math:`G = F/\\Omega^2` with its rounding bound
  and the evanescent scaling (the kappa scan of :mod:`dispersion.continuum.frequency`);
- :mod:`dispersion.continuum.scaled_frequency`: F scaled by its Mindlin bounds, with an exact root
  count (the tracer :mod:`dispersion.continuum.exact_branches`, the group velocities of
  :mod:`dispersion.continuum.velocities`).

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

import math

from dispersion.errors import InputError, check_nu, check_real_in_range

__all__ = ["OMEGA_MAX", "arb_frequency_function", "cutoff_frequencies", "frequency_function",
           "mpmath_frequency_function", "speed_ratio_squared"]


#: Largest Omega of :func:`cutoff_frequencies` (and so of the tracer). Rule: the cut-off list
#: holds about Omega_max / 2 entries; at 1e6 that is 5e5 tuples, ~50 MB and 0.2 s (measured on
#: this 2-core machine), while 1e12 would ask for ~50 TB.
OMEGA_MAX = 1e6


def speed_ratio_squared(nu):
    """:math:`(c_T / c_L)^2 = (1 - 2\\nu) / (2 (1 - \\nu))` in plane strain."""
    return (1 - 2 * nu) / (2 * (1 - nu))


def frequency_function(kind: str, kappa2, Omega2, nu, C, S, form: str = "standard", ratio=None):
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
    ratio : optional
        :math:`(c_T/c_L)^2` given directly (e.g. as a polynomial-ring generator); then ``nu``
        is not used.
    """
    P = (speed_ratio_squared(nu) if ratio is None else ratio) * Omega2 - kappa2
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


def mpmath_frequency_function(kind: str, kappa, Omega, nu):
    """:func:`frequency_function` in mpmath at the current precision (``mpmath.workdps``),
    real part, with mpmath's :math:`\\cos\\sqrt z` and :math:`\\operatorname{sinc}\\sqrt z`:
    the extended-precision reference of every float form.

    >>> import mpmath
    >>> with mpmath.workdps(30):
    ...     bool(abs(mpmath_frequency_function("S", 0, mpmath.pi, "0.3")) < 1e-25)
    True
    """
    import mpmath

    F = frequency_function(kind, mpmath.mpf(kappa) ** 2, mpmath.mpf(Omega) ** 2, mpmath.mpf(nu),
                           lambda z: mpmath.cos(mpmath.sqrt(z)),
                           lambda z: mpmath.sinc(mpmath.sqrt(z)))
    return mpmath.re(F)


def _arb_C(z):
    """:math:`C(z) = \\cos\\sqrt z` of a real ball z (``cosh`` of :math:`\\sqrt{-z}` for z < 0);
    a ball holding 0, where the square root has no useful enclosure, by :math:`{}_0F_1`."""
    import flint

    if z.contains(0):
        return (-z / 4).hypgeom_0f1(flint.arb(1) / 2)
    return flint.acb(z).sqrt().cos().real


def _arb_S(z):
    """:math:`S(z) = \\sin\\sqrt z / \\sqrt z` of a real ball z (see :func:`_arb_C`)."""
    import flint

    if z.contains(0):
        return (-z / 4).hypgeom_0f1(flint.arb(3) / 2)
    return flint.acb(z).sqrt().sinc().real


def arb_frequency_function(kind: str, kappa2, Omega, ratio, prec: int):
    """:func:`frequency_function` as a python-flint ``arb`` ball at ``prec`` bits: an enclosure
    of the exact F, so a ball that excludes 0 decides the sign of F.

    ``kappa2`` is :math:`\\kappa^2` (an ``arb``, or a float taken as exact), ``Omega`` a float
    (exact) and ``ratio`` :math:`s = (c_T/c_L)^2` a rational (``fractions.Fraction``, exact;
    a float is its exact binary value). C and S are arb's cos, sinc of the complex square root
    (``cosh``, ``sinh`` on the negative axis), and :math:`{}_0F_1` where the argument's ball
    holds 0: every operation encloses its exact result (Johansson 2017), whatever ``prec``.

    >>> from fractions import Fraction
    >>> F = arb_frequency_function("A", 0.0, 3.141592653589793 / 2, Fraction(1, 3), 128)
    >>> bool(abs(F) < 1e-15) and not F.contains(0)   # A1's cut-off pi/2, less a float's rounding
    True

    References
    ----------
    F. Johansson, Arb: efficient arbitrary-precision midpoint-radius interval arithmetic,
    IEEE Trans. Computers 66 (2017) 1281-1292.
    """
    import flint
    from fractions import Fraction

    q = Fraction(ratio)
    with flint.ctx.workprec(prec):
        x = kappa2 if isinstance(kappa2, flint.arb) else flint.arb(float(kappa2))
        W = flint.arb(float(Omega))
        s = flint.arb(flint.fmpq(q.numerator, q.denominator))
        return frequency_function(kind, x, W * W, None, _arb_C, _arb_S, ratio=s)


def cutoff_frequencies(kind: str, nu: float, omega_max: float) -> list[tuple[float, str]]:
    """Roots of the frequency equation at :math:`\\kappa = 0`, sorted, with their family.

    At :math:`\\kappa = 0`, :math:`F_S = \\Omega^4 C(s\\Omega^2) S(\\Omega^2)` and
    :math:`F_A = \\Omega^4 S(s\\Omega^2) C(\\Omega^2)`, :math:`s = (c_T/c_L)^2`, so

    - symmetric: :math:`\\Omega = m\\pi` (thickness-shear, ``"T"``) and
      :math:`\\Omega = (2m+1)\\pi / (2\\sqrt s)` (thickness-stretch, ``"L"``);
    - antisymmetric: :math:`\\Omega = (2m+1)\\pi/2` (``"T"``) and :math:`\\Omega = m\\pi/\\sqrt s`
      (``"L"``);

    plus S0 and A0 at :math:`\\Omega = 0` (family ``"0"``). Coinciding cut-offs (e.g. the
    symmetric ones at :math:`\\nu = 1/3`, where :math:`c_L = 2 c_T`) are listed twice.

    >>> [round(w, 6) for w, _ in cutoff_frequencies("A", 0.3, 6.0)]
    [0.0, 1.570796, 4.712389, 5.877382]
    """
    nu = float(check_nu(nu))
    check_real_in_range("omega_max", omega_max, 0, OMEGA_MAX, lo_open=True)
    rs = math.sqrt(speed_ratio_squared(nu))
    out = [(0.0, "0")]
    m = 0
    while True:
        if kind == "S":
            t, l_ = (m + 1) * math.pi, (2 * m + 1) * math.pi / (2 * rs)
        elif kind == "A":
            t, l_ = (2 * m + 1) * math.pi / 2, (m + 1) * math.pi / rs
        else:
            raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
        if t > omega_max and l_ > omega_max:
            break
        out += [(w, f) for w, f in ((t, "T"), (l_, "L")) if w <= omega_max]
        m += 1
    return sorted(out)
