"""Independent references for the evanescent modes (tests only): the textbook Rayleigh-Lamb
equations in entire form at complex kappa, at 40 digits, their roots in a rectangle by
findroot from a dense grid of starts, and the number of roots in a rectangle by the
argument principle (the increments of arg f summed along the boundary, sampled until each
is below an eighth of a turn), in mpmath.

Units of the Rayleigh-Lamb code: kappa = k h, Omega = omega h / c_T, h half the thickness,
:math:`P^2 = \\Omega^2 / r^2 - \\kappa^2`, :math:`Q^2 = \\Omega^2 - \\kappa^2`,
:math:`r = c_L / c_T`. The symmetric and antisymmetric equations (Achenbach 1973, eqs
6.111-6.112; Graff 1975, eq. 8.1.22)

.. math::

    (Q^2 - \\kappa^2)^2 \\cos P \\sin Q + 4\\kappa^2 P Q \\sin P \\cos Q = 0, \\qquad
    (Q^2 - \\kappa^2)^2 \\sin P \\cos Q + 4\\kappa^2 P Q \\cos P \\sin Q = 0

divided by Q and P respectively, so that both are entire in kappa (even functions of P, Q);
SH: :math:`Q \\sin Q = 0` (SH_0, SH_2, ...) and :math:`\\cos Q = 0` (SH_1, SH_3, ...).
"""
from __future__ import annotations

import mpmath

DPS = 40


def _sinc(a2):
    """sin(a) / a, entire in a^2."""
    a = mpmath.sqrt(a2)
    return mpmath.mpf(1) if a2 == 0 else mpmath.sin(a) / a


def rayleigh_lamb(family: str, nu, Omega):
    """The entire function f(kappa) of ``family`` (S, A, SHS, SHA) of an isotropic plate
    with Poisson's ratio ``nu`` at ``Omega``, in mpmath."""
    nu, Omega = mpmath.mpf(nu), mpmath.mpf(Omega)
    r2 = 2 * (1 - nu) / (1 - 2 * nu)

    def f(kap):
        k2 = kap**2
        P2, Q2 = Omega**2 / r2 - k2, Omega**2 - k2
        P, Q = mpmath.sqrt(P2), mpmath.sqrt(Q2)
        if family == "S":
            return ((Q2 - k2)**2 * mpmath.cos(P) * _sinc(Q2)
                    + 4 * k2 * P2 * _sinc(P2) * mpmath.cos(Q))
        if family == "A":
            return ((Q2 - k2)**2 * _sinc(P2) * mpmath.cos(Q)
                    + 4 * k2 * mpmath.cos(P) * Q2 * _sinc(Q2))
        if family == "SHS":
            return Q2 * _sinc(Q2)
        return mpmath.cos(Q)
    return f


def count_in_rectangle(f, re_max, im_lo, im_hi, first: int = 200, max_evals: int = 200000):
    """Zeros of ``f`` inside the rectangle [-re_max, re_max] x [im_lo, im_hi] (argument
    principle, samples refined until each step of arg f is below pi/4).

    The bottom edge runs im_lo above the real axis, where the propagating roots are: its
    first samples are at most im_lo apart, so that a pair of real roots closer together
    than im_lo (S0 at kappa = +-0.0014 at Omega = 0.002), whose arguments make a whole turn
    within about im_lo along the edge, is never stepped over (a CI draw: nu = 0, Omega =
    0.002, 200 first samples, counted 7 roots for 6)."""
    with mpmath.workdps(20):
        corners = [mpmath.mpc(-re_max, im_lo), mpmath.mpc(re_max, im_lo),
                   mpmath.mpc(re_max, im_hi), mpmath.mpc(-re_max, im_hi)]
        per = [max(8, int(first * abs(b - a) / (2 * re_max + 2 * (im_hi - im_lo))))
               for a, b in zip(corners, corners[1:] + corners[:1])]
        per[0] = max(per[0], int(mpmath.ceil(2 * re_max / im_lo)))
        pts = [a + (b - a) * j / n for (a, b), n in
               zip(zip(corners, corners[1:] + corners[:1]), per) for j in range(n)]
        evals = [0]

        def arg(z):
            evals[0] += 1
            assert evals[0] < max_evals, "the count did not resolve (a zero on the contour?)"
            return mpmath.arg(f(z))

        def step(a, b, pa, pb, depth=0):
            d = (pb - pa + mpmath.pi) % (2 * mpmath.pi) - mpmath.pi
            if abs(d) <= mpmath.pi / 4:
                return d
            assert depth < 40, "a zero on the contour"
            c = (a + b) / 2
            pc = arg(c)
            return step(a, c, pa, pc, depth + 1) + step(c, b, pc, pb, depth + 1)

        args = [arg(z) for z in pts]
        total = sum(step(a, b, pa, pb) for a, b, pa, pb in
                    zip(pts, pts[1:] + pts[:1], args, args[1:] + args[:1]))
        return int(mpmath.nint(total / (2 * mpmath.pi)))


def _polished(f, z0):
    """A zero of f near z0 at 40 digits, or None: the secant method from z0 at 15 digits,
    then at 40; accepted when |f| there is below 1e-25 of |f| a relative 1e-3 away (a zero,
    not a point where the iteration stalled)."""
    try:
        with mpmath.workdps(15):
            z = mpmath.findroot(f, z0, tol=1e-24, maxsteps=25, verify=False)
        with mpmath.workdps(DPS):
            z = mpmath.findroot(f, mpmath.mpc(z), tol=mpmath.mpf(10)**(-2 * DPS + 10),
                                maxsteps=20, verify=False)
            if not abs(f(z)) <= mpmath.mpf(10)**-25 * abs(f(z * (1 + mpmath.mpf(10)**-3))):
                return None
    except (ValueError, ZeroDivisionError):
        return None
    return mpmath.mpc(abs(z.real), abs(z.imag))   # its mirror image in the quadrant


def roots_in_rectangle(f, re_max, im_lo, im_hi, n_re: int = 8, n_im: int = 5):
    """Zeros of ``f`` with 0 <= Re <= re_max, im_lo < Im <= im_hi: findroot (secant) from a
    grid of starts, each polished at 40 digits (:func:`_polished`), the distinct ones sorted
    by Im. Starts: real parts 0 and (i + 1/2) re_max / n_re, i < n_re; imaginary parts
    im_lo + (j + 1/2) (im_hi - im_lo) / n_im, j < n_im, and im_hi 10^-m, m = 1, 2, 3 (roots
    near kappa = 0: the flexural evanescent root at low frequency)."""
    res = [mpmath.mpf(0)] + [re_max * (i + mpmath.mpf(1) / 2) / n_re for i in range(n_re)]
    ims = [im_lo + (im_hi - im_lo) * (j + mpmath.mpf(1) / 2) / n_im for j in range(n_im)]
    ims += [im_hi * mpmath.mpf(10) ** -m for m in (1, 2, 3) if im_hi * 10 ** -m > im_lo]
    found = []
    for x in res:
        for y in ims:
            z = _polished(f, mpmath.mpc(x, y))
            if z is None or not (im_lo < z.imag <= im_hi and z.real <= re_max):
                continue
            if all(abs(z - q) > 1e-20 * abs(z) for q in found):
                found.append(z)
    return sorted(found, key=lambda z: (z.imag, z.real))


def is_zero_near(f, k, rtol):
    """Whether a 40-digit zero of f lies within rtol |k| of k (the secant method from k)."""
    z = _polished(f, mpmath.mpc(k))
    return z is not None and abs(complex(z) - complex(abs(k.real), abs(k.imag))) <= rtol * abs(k)
