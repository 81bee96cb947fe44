"""Group velocities of the discrete branches certified in ball arithmetic, where floats cannot.

On the polynomial path (:mod:`dispersion.discretization.pencil_polynomial`) a root :math:`\\mu` of
:math:`P(u, \\mu)` moves with :math:`d\\mu/du = -P_u / P_\\mu`, and with
:math:`\\Omega^2 = \\mu / m_x(u)`

.. math::

    \\frac{d\\Omega}{d\\kappa} = \\frac{\\mu_u m_x - \\mu m_x'}{2\\,\\Omega\\, m_x^2}\\,
    \\frac{du}{d\\kappa}.

The float evaluation (:func:`~dispersion.discretization.pencil_polynomial.slopes`) carries a running
bound that is often a few times 1e-12 relative (a slope near zero, S1 near kappa = 0; the
mixed block of a singular mass). There, this module evaluates the same formula on the
*exact* rational coefficients of P in python-flint balls at :data:`PRECISION` bits: u from
kappa as a ball (:math:`u = 2\\sin^2(\\kappa r/2)` or :math:`\\kappa^2`), the root enclosed
by interval Newton steps :math:`N(M) = m - P(m)/P_\\mu(M)` (:math:`N(M) \\subset M` proves a
unique root in N(M); Moore, Kearfott and Cloud 2009, 8.1), then the slope as a ball. The
midpoint is returned, the radius certifies it: only a ball wider than the tolerance is left
to the caller's ``failures``.

>>> import numpy as np
>>> from dispersion.symbolic.plate import plate_patch, mirror_bases
>>> from dispersion.discretization.pencil_polynomial import pencil_polynomial
>>> poly = pencil_polynomial(plate_patch(), 0.3, mirror_bases(3, exact=True)["S"])
>>> mu = np.array([[3e-6, 10.4, 14.8]])   # rough guesses of Omega^2 m_x: Newton closes them
>>> G, rel = ball_slopes(poly, np.array([1e-3]), mu)
>>> bool(rel[0, 1] < 1e-30), round(float(G[0, 1]), 8)   # S1 near its cut-off: c_g ~ kappa
(True, -0.00052169)
>>> bool(np.isinf(ball_slopes(poly, np.array([1e-3]), np.array([[3e-6, 10.4, 12.1]]))[1][0, 2]))
True

References
----------
R. E. Moore, R. B. Kearfott, M. J. Cloud, *Introduction to interval analysis*, SIAM 2009,
ch. 8 (interval Newton). F. Johansson, "Arb: efficient arbitrary-precision midpoint-radius
interval arithmetic", IEEE Trans. Comput. 66 (2017) 1281-1292.
"""
from __future__ import annotations

import numpy as np

__all__ = ["PRECISION", "ball_slopes"]

#: Bits of the balls. Rule: the coefficients of P cancel by up to 1e30 at kappa near zero
#: (the rigid-body roots, mu ~ u^2 beside O(1) roots) and the float path's own loss is
#: about 1e4; 256 bits (77 digits) leaves over 30 digits after both.
PRECISION = 256


def ball_slopes(poly, kappa: np.ndarray, mu: np.ndarray):
    """:math:`d\\Omega/d\\kappa` at the roots near ``mu`` (points, R) and its relative radius.

    ``poly`` must carry its exact coefficients (``PencilPolynomial.exact``). The relative
    radius is ``inf`` where a root could not be enclosed (a guess too far, two roots in one
    ball, two guesses drawn to the same root: the last line of the example); with ``mu``
    exactly 0 (kappa = 0) the slope is returned as NaN, radius inf.
    """
    import flint

    old = flint.ctx.prec
    flint.ctx.prec = PRECISION
    try:
        P = [flint.arb_poly(c) for c in poly.exact["P"]]           # c_j(u), j = 0..N
        dP = [c.derivative() for c in P]
        mx, dmx = flint.arb_poly(poly.exact["mx"]), flint.arb_poly(poly.exact["mx"]).derivative()
        G = np.full(mu.shape, np.nan)
        rel = np.full(mu.shape, np.inf)
        for i, k in enumerate(np.asarray(kappa, dtype=float)):
            u, dudk = _u_ball(poly, k)
            c = [p(u) for p in P]
            cu = [p(u) for p in dP]
            m, mxp = mx(u), dmx(u)
            roots = [_enclose(c, float(guess)) for guess in mu[i]]
            for j, root in enumerate(roots):
                if root is None or not root > 0:
                    continue
                # two guesses drawn to one root (a pair closer than the floats can tell,
                # such as a degenerate pair at kappa -> 0): neither slope is known
                if any(o is not None and jj != j and o.overlaps(root)
                       for jj, o in enumerate(roots)):
                    continue
                pm = _horner(c, root, deriv=True)
                pu = _horner(cu, root)
                mu_u = -pu / pm
                omega = (root / m).sqrt()
                g = (mu_u * m - root * mxp) * dudk / (2 * omega * m * m)
                mid = float(g.mid())
                G[i, j] = mid
                rad = float(g.rad())
                rel[i, j] = rad / abs(mid) if mid != 0 else (0.0 if rad == 0 else np.inf)
        return G, rel
    finally:
        flint.ctx.prec = old


def _u_ball(poly, kappa: float):
    """u and du/dkappa as balls from the float kappa (exact), with r exact (Bloch)."""
    import flint

    k = flint.arb(kappa)
    if poly.model == "x-exact":
        return k * k, 2 * k
    r = flint.arb(poly.r_exact.numerator) / poly.r_exact.denominator
    half = k * r / 2
    s, co = half.sin(), half.cos()
    return 2 * s * s, 2 * r * s * co


def _horner(c, x, deriv: bool = False):
    """P(x) or P_mu(x) of the coefficient balls ``c`` (ascending in mu)."""
    p = c[-1]
    dp = 0 * x
    for cj in reversed(c[:-1]):
        dp = dp * x + p
        p = p * x + cj
    return dp if deriv else p


def _enclose(c, guess: float, steps: int = 40):
    """A ball holding exactly one root of :math:`\\sum c_j \\mu^j` near ``guess``, by Newton
    in midpoints and interval Newton on a widening ball; None if none is proven."""
    import flint

    m = flint.arb(guess)
    for _ in range(steps):   # float-like Newton on midpoints first (the guess may be rough)
        d = _horner(c, m, deriv=True)
        if not d.is_finite() or d.contains(0):
            return None
        step = (_horner(c, m) / d).mid()
        m = (m - step).mid()
        if abs(float(step)) <= 1e-60 * max(abs(float(m)), 1e-300):
            break
    width = max(abs(float(m)), 1e-300) * 1e-40
    for _ in range(8):
        M = flint.arb(m, width)
        d = _horner(c, M, deriv=True)
        if d.is_finite() and not d.contains(0):
            N = m - _horner(c, flint.arb(m)) / d
            if M.contains(N):
                for _ in range(3):   # contract
                    d = _horner(c, N, deriv=True)
                    N2 = N.mid() - _horner(c, flint.arb(N.mid())) / d
                    if not N.contains(N2):
                        break
                    N = N2
                return N
        width *= 1e6
    return None
