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


# --- the textbook equation by itself, and its roots next to cut-offs and ZGV points --------
# Written here from Rose (2004) eqs 8.21-8.22 in p = sqrt(P), q = sqrt(Q), multiplied out of
# the tangents and divided by q (S) or p (A): none of the package's forms is used, so these
# are references for the package's float and ball forms alike.

def textbook_F(kind, kappa2, W, nu):
    """F at kappa^2 = ``kappa2`` (any sign: a root next to a cut-off is analytic in it),
    Omega = W, Poisson ratio nu (mpf), at the current precision; real."""
    s = (1 - 2 * nu) / (2 * (1 - nu))
    P, Q = s * W**2 - kappa2, W**2 - kappa2
    p, q = mpmath.sqrt(mpmath.mpc(P)), mpmath.sqrt(mpmath.mpc(Q))
    a = (Q - kappa2) ** 2
    if kind == "S":
        return mpmath.re(a * mpmath.cos(p) * mpmath.sinc(q)
                         + 4 * kappa2 * p * mpmath.sin(p) * mpmath.cos(q))
    return mpmath.re(a * mpmath.sinc(p) * mpmath.cos(q)
                     + 4 * kappa2 * q * mpmath.sin(q) * mpmath.cos(p))


def mp_exact(value):
    """An exact rational (``fractions.Fraction``) or a float as an mpf."""
    from fractions import Fraction

    value = Fraction(value)
    return mpmath.mpf(value.numerator) / value.denominator


def _bisect(f, a, b, fa, rel):
    for _ in range(2000):
        m = (a + b) / 2
        fm = f(m)
        if fm == 0:
            return m
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
        if b - a <= rel * abs(b):
            break
    return (a + b) / 2


def roots_between(f, points):
    """Roots of f bracketed by sign changes between consecutive ``points`` (sorted), each
    closed by bisection to 1e-(dps - 8) relative."""
    vals = [f(x) for x in points]
    rel = mpmath.mpf(10) ** (-mpmath.mp.dps + 8)
    out = []
    for x0, x1, f0, f1 in zip(points, points[1:], vals, vals[1:]):
        if f0 == 0:
            out.append(x0)
        elif f0 * f1 < 0:
            out.append(_bisect(f, x0, x1, f0, rel))
    return out


def cutoffs_mp(kind, nu, count):
    """The first ``count`` cut-offs (Omega > 0) of a Lamb class at kappa = 0, sorted: F_S(0) =
    W^4 cos(sqrt(s) W) sin(W) / W and F_A(0) = W^4 sin(sqrt(s) W) cos(W) / (sqrt(s) W)."""
    rs = mpmath.sqrt((1 - 2 * nu) / (2 * (1 - nu)))
    out = []
    for m in range(count):
        if kind == "S":
            out += [(m + 1) * mpmath.pi, (2 * m + 1) * mpmath.pi / (2 * rs)]
        else:
            out += [(2 * m + 1) * mpmath.pi / 2, (m + 1) * mpmath.pi / rs]
    return sorted(out)[:count]


def roots_near_zero(kind, W, nu, kappa_max, per_decade=16):
    """Every root with kappa in (1e-20, kappa_max) of the textbook equation at W: sign
    changes of F on x = kappa^2 sampled ``per_decade`` per decade, then bisection in x."""
    top = 2 * mpmath.log10(kappa_max)
    n = int((top + 40) * per_decade)
    xs = [mpmath.mpf(10) ** (-40 + (top + 40) * i / n) for i in range(n + 1)]
    return [mpmath.sqrt(x) for x in roots_between(lambda x: textbook_F(kind, x, W, nu), xs)]


def roots_in_window(kind, W, nu, centre, width, count=200):
    """Every root with kappa in centre (1 +- width) of the textbook equation at W: samples
    geometric towards the centre on both sides (a ZGV pair straddles it), then bisection."""
    ts = [width * mpmath.mpf(10) ** (-12 * i / count) for i in range(count + 1)]
    ks = sorted([centre * (1 - t) for t in ts] + [centre] + [centre * (1 + t) for t in ts])
    f = lambda k: textbook_F(kind, k * k, W, nu)   # noqa: E731
    return roots_between(f, ks)


def zgv_mp(kind, kappa, W, nu):
    """The ZGV point (kappa, Omega) near a guess: F = 0 and dF/dkappa = 0, by mpmath's
    multidimensional Newton at the current precision."""
    def system(k, w):
        return [textbook_F(kind, k * k, w, nu),
                mpmath.diff(lambda x: textbook_F(kind, x * x, w, nu), k)]

    k, w = mpmath.findroot(system, (mpmath.mpf(kappa), mpmath.mpf(W)))
    assert abs(system(k, w)[0]) < mpmath.mpf(10) ** (-mpmath.mp.dps + 15)
    return k, w


def group_velocity_mp(kind, kappa, W, nu):
    """c_g / c_T = dOmega/dkappa = -F_kappa / F_Omega of the textbook equation at a root."""
    F = lambda k, w: textbook_F(kind, k * k, w, nu)   # noqa: E731
    return -mpmath.diff(lambda k: F(k, W), kappa) / mpmath.diff(lambda w: F(kappa, w), W)
