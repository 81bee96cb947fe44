"""The certificate of a root in kappa: a sign change of the exact function at kappa (1 +- delta).

A real root :math:`\\kappa^*` of a frequency function :math:`F(\\kappa)` (at a fixed
frequency) is *certified* to ``delta`` relative at the returned float :math:`\\kappa` when the
exact F has opposite signs at the floats :math:`\\kappa_\\pm = fl(\\kappa (1 \\pm \\delta))`:
then a root lies in :math:`(\\kappa_-, \\kappa_+)`, within :math:`\\delta (1 + 2^{-50})` of
:math:`\\kappa`. "Exact" is meant literally: each sign is decided either

- in floats, where :math:`|F| > B` for a *proven* bound B on the float evaluation's error
  (:func:`float_certified`; for the Rayleigh-Lamb function a running error analysis,
  :func:`dispersion.continuum.numeric_frequency.frequency_function_bound`, which takes
  numpy's cos, sin, cosh and sinh to be within
  :data:`~dispersion.continuum.numeric_frequency.LIBM_ULPS` ulps), or
- in ball arithmetic (python-flint ``arb``), where the ball of F excludes 0
  (:func:`arb_sign`, at a precision raised until it does or a ceiling is reached;
  :func:`dispersion.continuum.rayleigh_lamb.arb_frequency_function`).

Rounding cannot fake a sign change in either. A root that floats cannot certify (next to a
cut-off :math:`\\kappa^*` is tiny and F is flat in it; next to a zero-group-velocity point two
roots merge) is closed again in ball arithmetic from a bracket whose end signs are decided
there (:func:`refine_in_squares`): by the Illinois method in :math:`x = \\kappa^2`, in which a
frequency function even in kappa is analytic and a root next to a cut-off simple. Two roots of
a ZGV pair are certified each by its own sign change once the pair's bracket is split at a
point of the opposite sign: the ZGV point's kappa or the extremum of F between the roots
(:func:`extremum_in_squares`). A pair closer than the bracket (a frequency within about
1e-26 relative of a ZGV frequency) has no sign change per root and is not certified. What
neither certifies is the caller's to list as a failure.

The functions take the frequency function as arguments (a float form with its bound, a ball
form of :math:`x = \\kappa^2`), so every plate model with real roots in kappa and an even
frequency function can use them.

>>> from fractions import Fraction
>>> import numpy as np
>>> from dispersion.continuum.numeric_frequency import frequency_function_bound
>>> from dispersion.continuum.rayleigh_lamb import arb_frequency_function
>>> bound = lambda k: frequency_function_bound("S", k, np.full(k.shape, 2.0), 1 / 3, 2.0**-54)
>>> float_certified(bound, np.array([1.3, 1.3206549163561456]), 2.5e-13).tolist()
[False, True]
>>> F = lambda x, prec: arb_frequency_function("S", x, 2.0, Fraction(1, 3), prec)
>>> k = refine_in_squares(F, 0.5, 2.0, 128)
>>> k, arb_certified(F, k, 2.5e-13, 128)
(1.3206549163561456, True)

References
----------
F. Johansson, Arb: efficient arbitrary-precision midpoint-radius interval arithmetic, IEEE
Trans. Computers 66 (2017) 1281-1292; N. J. Higham, *Accuracy and stability of numerical
algorithms*, 2nd ed., SIAM 2002, sec. 3.3; M. Dowell, P. Jarratt, BIT 11 (1971) 168 (Illinois).
"""
from __future__ import annotations

import numpy as np

__all__ = ["MAX_DOUBLINGS", "arb_certified", "arb_sign", "bracket_points", "exact_square",
           "extremum_in_squares", "float_certified", "refine_in_squares"]

#: Doublings of the working precision over the caller's start before a sign is given up
#: (0: undecided). Rule: in the promise searches every sign was decided at its start (315
#: signs, starts of 96 to 192 bits; the start grows with kappa and next to cut-offs); four
#: doublings, 16 times the start, leave room for what they did not meet.
MAX_DOUBLINGS = 4


def bracket_points(kappa, delta: float):
    """The floats :math:`fl(\\kappa (1 - \\delta)), fl(\\kappa (1 + \\delta))` the certificate
    is decided at (one rounding each, so the bracket holds :math:`\\kappa (1 \\pm \\delta)` to
    an ulp).

    >>> bracket_points(1.0, 0.25)
    (0.75, 1.25)
    """
    return kappa * (1 - delta), kappa * (1 + delta)


def float_certified(float_bound, kappa: np.ndarray, delta: float) -> np.ndarray:
    """True where floats prove a sign change of the exact F at :func:`bracket_points`.

    ``float_bound(points)`` returns F at the float points (an array) and a proven bound on its
    error against the exact F there; a sign counts only where :math:`|F| > B`.
    """
    kappa = np.asarray(kappa, dtype=float)
    lo, hi = bracket_points(kappa, delta)
    with np.errstate(all="ignore"):
        f_lo, b_lo = float_bound(lo)
        f_hi, b_hi = float_bound(hi)
        return ((lo > 0) & (np.abs(f_lo) > b_lo) & (np.abs(f_hi) > b_hi)
                & (np.sign(f_lo) * np.sign(f_hi) < 0))


def exact_square(kappa: float, prec: int = 128):
    """:math:`\\kappa^2` of a float as an exact ``arb`` (a float's square has at most 106 bits).

    >>> exact_square(0.1, 64).is_exact()
    True
    """
    import flint

    with flint.ctx.workprec(max(prec, 128)):
        k = flint.arb(float(kappa))
        return k * k


def arb_sign(arb_value, x, prec: int, max_prec: int | None = None) -> int:
    """Sign of the exact F at :math:`x = \\kappa^2` (an ``arb``): +1 or -1 once the ball
    ``arb_value(x, prec)`` excludes 0, the precision doubling from ``prec`` up to
    ``max_prec`` (default :data:`MAX_DOUBLINGS` doublings); 0 if it never does (F is 0
    there, or too close to it).

    >>> import flint
    >>> arb_sign(lambda x, prec: x - flint.arb(1) / 3, flint.arb(0.25), 64)
    -1
    """
    max_prec = prec << MAX_DOUBLINGS if max_prec is None else max_prec
    while prec <= max_prec:
        v = arb_value(x, prec)
        if v > 0:
            return 1
        if v < 0:
            return -1
        prec *= 2
    return 0


def arb_certified(arb_value, kappa: float, delta: float, prec: int,
                  max_prec: int | None = None) -> bool:
    """True where ball arithmetic proves a sign change of the exact F at
    :func:`bracket_points` of ``kappa`` (a float); ``arb_value(x, prec)`` encloses F at
    :math:`x = \\kappa^2`."""
    lo, hi = bracket_points(float(kappa), delta)
    if not 0 < lo < hi:
        return False
    s_lo = arb_sign(arb_value, exact_square(lo, prec), prec, max_prec)
    s_hi = arb_sign(arb_value, exact_square(hi, prec), prec, max_prec) if s_lo else 0
    return s_lo * s_hi < 0


def refine_in_squares(arb_value, a: float, b: float, prec: int, *,
                      max_prec: int | None = None, rtol: float = 1e-17,
                      max_iter: int = 400) -> float | None:
    """A root of the exact F in :math:`(a, b)`, :math:`0 \\le a < b` floats, as the float
    nearest to it; None if the ends' signs (decided in ball arithmetic) are not opposite or
    the iteration does not close.

    The Illinois method (:mod:`dispersion.continuum.illinois`) in :math:`x = \\kappa^2` on ball
    midpoints at ``prec`` bits, the precision doubled whenever F's ball at an iterate holds 0;
    it stops when the bracket in x is ``rtol`` relative (the root in kappa to half that). The
    result is not certified here: :func:`arb_certified` decides.
    """
    import flint

    max_prec = prec << MAX_DOUBLINGS if max_prec is None else max_prec
    xa, xb = exact_square(a, prec), exact_square(b, prec)
    sa = arb_sign(arb_value, xa, prec, max_prec)
    sb = arb_sign(arb_value, xb, prec, max_prec)
    if sa * sb >= 0:
        return None
    fa, fb = arb_value(xa, prec).mid(), arb_value(xb, prec).mid()
    side = 0
    for _ in range(max_iter):
        with flint.ctx.workprec(prec):
            if (xb - xa) <= rtol * xb:
                break
            c = ((xa * fb - xb * fa) / (fb - fa)).mid() if fb != fa else ((xa + xb) / 2).mid()
            if not (xa < c < xb):
                c = ((xa + xb) / 2).mid()
        fc = arb_value(c, prec)
        if fc.contains(0):
            if prec * 2 > max_prec:
                xa = xb = c
                break
            prec *= 2
            continue
        fc = fc.mid()
        if (fc > 0) == (sa > 0):
            xa, fa = c, fc
            if side == 1:
                fb = fb / 2
            side = 1
        else:
            xb, fb = c, fc
            if side == -1:
                fa = fa / 2
            side = -1
    else:
        return None
    with flint.ctx.workprec(prec):
        return float(((xa + xb) / 2).sqrt().mid())


def extremum_in_squares(arb_value, kappa: float, prec: int, steps: int = 12):
    """The kappa^2 (an ``arb`` midpoint) of the extremum of F next to ``kappa``: where two
    roots merge (a ZGV point) F has a local extremum between them, and its sign there tells
    whether the pair exists at this frequency.

    Newton's method on :math:`F'(x)` in :math:`x = \\kappa^2`, both derivatives by
    difference quotients of step :math:`x\\,2^{-p/3}` on ball midpoints at ``prec`` bits:
    the extremum to about a third of the working digits. Not a certificate: the sign at the
    point found is decided by :func:`arb_sign`, and a sign change at it brackets each root.

    >>> import flint
    >>> x = extremum_in_squares(lambda x, prec: (x - flint.arb(2)) ** 2 + 1, 1.3, 128)
    >>> abs(float(x) - 2) < 1e-20
    True
    """
    import flint

    x = exact_square(kappa, prec)
    with flint.ctx.workprec(prec):
        for _ in range(steps):
            h = (x * flint.arb(2) ** (-(prec // 3))).mid()
            f0, fp, fm = (arb_value(x + d, prec).mid() for d in (0, h, -h))
            second = (fp - 2 * f0 + fm) / (h * h)
            if second == 0:
                break
            step = ((fp - fm) / (2 * h) / second).mid()
            x = (x - step).mid()
            if abs(step) <= abs(x) * flint.arb(2) ** (-(prec // 3)):
                break
    return x
