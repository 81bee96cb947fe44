"""Certified roots of the characteristic polynomial of a pencil block, vectorized over kappa.

For each kappa the roots :math:`\\mu` of :math:`P(x, \\mu) = \\sum_j c_j(x) \\mu^j`
(:mod:`dispersion.discretization.pencil_polynomial`; x = u or a Taylor-shifted variable) are
Newton-polished from guesses and *certified*: Newton-Kantorovich on the computed x with
a-posteriori rounding bounds (:func:`_radius`) gives a disc holding exactly one root; N
pairwise disjoint discs hold all N roots, one each. The rounding of x itself, a perturbation
of kappa by a few ulp, is added to each radius through :math:`P_x / P_\\mu`.

>>> from dispersion.symbolic.plate import plate_patch, mirror_bases
>>> from dispersion.discretization.pencil_polynomial import pencil_polynomial, u_of_kappa
>>> poly = pencil_polynomial(plate_patch(model="x-exact"), 0.3, mirror_bases(3, exact=True)["S"])
>>> u, v, _ = u_of_kappa("x-exact", None, np.array([0.5]))
>>> mu, rad = certified_roots(poly, u, v, np.array([[0.6, 10.0, 17.0]]))   # guesses
>>> bool(np.all(rad <= 1e-12 * mu))
True

References
----------
N. J. Higham, *Accuracy and stability of numerical algorithms*, 2nd ed., 2002, sections 3.1
and 5.1 (rounding bounds of Horner's rule); J. M. Ortega, W. C. Rheinboldt, *Iterative
solution of nonlinear equations in several variables*, 1970, 12.6.2 (Newton-Kantorovich).
"""
from __future__ import annotations

import numpy as np

from dispersion.discretization.pencil_polynomial import (
    PencilPolynomial,
    _derivative_u,
    _horner_mu,
    _horner_u,
)

__all__ = ["U_ULPS", "certified_roots"]

_EPS = np.finfo(float).eps


#: Relative error of the computed ``u`` and ``v`` of :func:`u_of_kappa` in units of eps,
#: for an exact half angle :math:`\\phi = \\kappa r / 2`: numpy's sin or cos (under one
#: ulp), the square and the product (half an ulp each), the factor 2 exact: 4 (x-exact
#: :math:`u = \\kappa^2`: half an ulp). The rounding of :math:`\\phi` itself (half an ulp)
#: moves u and v by at most :math:`|dv/d\\phi|\\,\\epsilon|\\phi|/2 = 2 \\epsilon |\\phi|
#: \\sqrt{uv}`, absolute (relative to v it is unbounded at the zone edge, where v -> 0).
#: About a centre c, :math:`x = u - c` (c <= 1) or :math:`(2 - c) - v` (c > 1) is an exact
#: subtraction (Sterbenz), so its error is that of u or v.
U_ULPS = 4


def _tables(poly: PencilPolynomial, u: np.ndarray, v, kappa=None, running: bool = False):
    """Coefficients of P in mu at every point, shape (J, points) each: :math:`c_j(x)`,
    :math:`\\sum_k |a_{jk}| |x|^k`, :math:`\\partial c_j / \\partial x` and
    :math:`\\sum_k k |a_{jk}| |x|^{k-1}`, and a bound on the absolute error of x (points).

    x = u - c about the nearest centre c = j / C (Bloch; x-exact: u = kappa^2 only);
    each table is the exact Taylor shift of the same P. ``kappa`` (Bloch) bounds the half
    angle of :data:`U_ULPS`; None: the first zone, :math:`\\phi \\le \\pi/2`. With
    ``running``, the first table is followed by a running error bound of its evaluation
    (:func:`_horner_running`) and the tuple has six entries.
    """
    def run(coef, x):
        J = coef.shape[0]
        dc = np.zeros_like(coef)   # d/dx, padded to the width of coef
        dc[:, :-1] = _derivative_u(coef)[:, :coef.shape[1] - 1]
        bar = _horner_u(np.abs(np.concatenate([coef, dc])), np.abs(x))
        if running:
            val, err = _horner_running(coef, x)
            return val, err, bar[:J], _horner_u(dc, x), bar[J:]
        val = _horner_u(np.concatenate([coef, dc]), x)
        return val[:J], bar[:J], val[J:], bar[J:]

    if v is None or poly.shifted is None:
        return (*run(poly.coef, u), 0.5 * _EPS * u)
    phi = np.pi / 2 if kappa is None else np.abs(kappa) * (0.5 * poly.r)
    arg = 2 * _EPS * phi * np.sqrt(u * v) * (1 + 4 * _EPS)
    eu, ev = U_ULPS * _EPS * u + arg, U_ULPS * _EPS * v + arg
    C = poly.centres
    top = 2 * C
    j = np.clip(np.rint(u * C), 0, top).astype(int)
    out = [np.empty((poly.coef.shape[0], u.size)) for _ in range(5 if running else 4)]
    dx = np.empty(u.shape)
    order = np.argsort(j, kind="stable")
    bounds = np.searchsorted(j[order], np.arange(top + 2))
    for jj in range(top + 1):
        idx = order[bounds[jj]:bounds[jj + 1]]
        if not idx.size:
            continue
        if jj == 0:
            coef, x, err = poly.coef, u[idx], eu[idx]
        elif jj == top:
            coef, x, err = poly.shifted["P"], v[idx], ev[idx]
        else:
            coef = poly.shifted["P centred"][jj - 1]
            # u - c, from v past the middle (both exact subtractions)
            x = u[idx] - jj / C if 2 * jj <= top else (2 - jj / C) - v[idx]
            err = eu[idx] if 2 * jj <= top else ev[idx]
        if idx.size == u.size:
            return (*run(coef, x), err)
        for o, val in zip(out, run(coef, x)):
            o[:, idx] = val
        dx[idx] = err
    return (*out, dx)


def _horner_running(coef: np.ndarray, x: np.ndarray):
    """``sum_k coef[:, k] x^k`` and a bound on its rounding error (Higham 2002, Algorithm
    5.1: the running error bound, :math:`\\epsilon \\mu` with
    :math:`\\mu \\leftarrow |x| \\mu + |y_k|`), both of shape (rows, len(x))."""
    out = np.empty((coef.shape[0], x.size))
    out[:] = coef[:, -1:]
    m = 0.5 * np.abs(out)
    a = np.abs(x)
    for k in range(coef.shape[1] - 2, -1, -1):
        out *= x
        out += coef[:, k:k + 1]
        m *= a
        m += np.abs(out)
    m *= _EPS
    return out, m


def certified_roots(poly: PencilPolynomial, u: np.ndarray, v, guess: np.ndarray,
                    rtol: float = 2e-10, iterations: int = 8, kappa=None):
    """Newton-polished roots ``mu`` (ascending, shape of ``guess`` = (points, R)) and radii.

    Newton's method runs until its step is below 1e-9 relative (the error is then about
    the square of that), at most ``1 + iterations`` steps; then one certificate per root
    (:func:`_radius`). The radius is ``inf`` where the certificate fails (a disc
    overlapping a neighbour, a derivative lost in its error bound, NaN). The certificate
    does not depend on ``rtol`` (kept for the callers, who compare the radius with it).
    ``kappa`` (Bloch, same length as u) bounds the rounding of u and v (:data:`U_ULPS`);
    None: kappa in the first zone. The certificate takes a priori rounding bounds first
    and, where a radius exceeds ``rtol`` relative, running error bounds (tighter, dearer).
    """
    c, cbar, cd, cdbar, dx = _tables(poly, u, v, kappa)
    du = poly.coef.shape[1] - 1
    # a priori bound of the coefficients' errors (Higham 2002, 3.1 and 5.1): their rounding
    # to floats (eps/2) and the Horner rule in x (gamma_{2 du}), doubled for second-order
    # terms and the rounding of the bars themselves
    gx = 2 * (du + 1) * _EPS
    # Newton in the form mu' = (mu P_mu - P) / P_mu, numerator by its own Horner rule:
    # near mu = 0 it is -c_0 / c_1 without the cancellation of mu - P / P_mu
    cn = c * (np.arange(c.shape[0]) - 1)[:, None]
    n = c.shape[1]
    with np.errstate(all="ignore"):
        mu0 = _small_guesses(c, np.array(guess, dtype=float).T.copy())
        mu = _newton(c, cn, mu0)
        again = np.flatnonzero(np.any(~(np.abs(mu - mu0) <= 1e-9 * mu), axis=0))
        for _ in range(iterations):
            if not again.size:
                break
            if again.size > n // 2:   # most columns: whole rows beat gathering them
                m0 = mu
                mu = _newton(c, cn, m0)
                again = np.flatnonzero(np.any(~(np.abs(mu - m0) <= 1e-9 * mu), axis=0))
                continue
            m0 = mu[:, again]
            m = _newton(c[:, again], cn[:, again], m0)
            mu[:, again] = m
            again = again[np.any(~(np.abs(m - m0) <= 1e-9 * m), axis=0)]
        if mu.shape[0] > 1 and not np.all(mu[1:] >= mu[:-1]):
            mu = np.sort(mu, axis=0)
        rad = _radius(c, cbar, cd, cdbar, mu, dx, gx)
        loose = np.flatnonzero(np.any(~(rad <= rtol * mu), axis=0))
        if loose.size:
            k = None if kappa is None else np.asarray(kappa)[loose]
            cl, E, cbl, cdl, cdbl, dxl = _tables(poly, u[loose], None if v is None else v[loose],
                                                 k, running=True)
            # x-Horner's running bound, the coefficients' own rounding (eps/2), and 1 %
            # for the rounding of the bounds themselves
            E = 1.01 * (E + 0.5 * _EPS * cbl)
            rad[:, loose] = np.minimum(rad[:, loose],
                                       _radius(cl, cbl, cdl, cdbl, mu[:, loose], dxl, gx, E))
        if mu.shape[0] > 1:
            clash = np.diff(mu, axis=0) <= rad[1:] + rad[:-1]
            bad = np.zeros_like(rad, dtype=bool)
            bad[1:] |= clash
            bad[:-1] |= clash
            rad[bad] = np.inf
    return mu.T, rad.T


def _newton(c: np.ndarray, cn: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """One Newton step ``(sum (j - 1) c_j mu^j) / P_mu`` for every root."""
    num = _horner_mu(cn, mu, deriv=False)[0]
    num /= _horner_mu(c, mu)[1]
    return num


def _radius(c, cbar, cd, cdbar, mu, dx, gx, E=None):
    """A disc about each root estimate that holds exactly one root of :math:`P(x, \\cdot)`.

    Newton-Kantorovich (Ortega and Rheinboldt 1970, 12.6.2) at the computed x: with
    :math:`F \\ge |P(\\mu)|` and :math:`D \\le |P_\\mu(\\mu)|` (values and their rounding
    bounds), :math:`\\eta = F / D` and :math:`K \\ge |P_{\\mu\\mu}|` on the disc of radius
    :math:`2\\eta` (second derivative of the bar polynomial at :math:`|\\mu| + 2\\eta`),
    :math:`h = K \\eta / D \\le 1/2` puts one root within :math:`2\\eta` and no other
    there. The rounding of x itself (``dx`` absolute) moves the root by
    :math:`|P_x / P_\\mu|\\, dx` to first order, taken twice. Disjoint discs (checked by
    the caller) then hold all roots, one each. Inf where D <= 0 or h > 0.45.

    Rounding bounds (Higham 2002, 3.1 and 5.1): the coefficients :math:`c_j` are off by
    ``E`` (None: the a priori ``gx`` times their bars :math:`\\sum_k |a_{jk}| |x|^k`, for
    the x-Horner and the coefficients' rounding); the mu-Horner adds
    :math:`\\gamma_{2 d}` times the bar of P (a priori), or with ``E`` its running bound,
    each doubled.
    """
    a = np.abs(mu)
    dm = c.shape[0] - 1
    # one Horner loop: P, P_mu at mu; the bars and their first two derivatives at |mu|;
    # P_x and its bar; with E, the errors' polynomial, its derivative and the running bound
    p = np.empty_like(mu)
    p[:] = c[-1]
    pb = np.empty_like(mu)
    pb[:] = cbar[-1]
    px = np.empty_like(mu)
    px[:] = cd[-1]
    pxb = np.empty_like(mu)
    pxb[:] = cdbar[-1]
    dp = np.zeros_like(mu)
    dpb = np.zeros_like(mu)
    d2pb = np.zeros_like(mu)
    if E is not None:
        pe = np.empty_like(mu)
        pe[:] = E[-1]
        dpe = np.zeros_like(mu)
        run = 0.5 * np.abs(p)
    for j in range(dm - 1, -1, -1):
        dp *= mu
        dp += p
        p *= mu
        p += c[j]
        d2pb *= a
        d2pb += dpb
        dpb *= a
        dpb += pb
        pb *= a
        pb += cbar[j]
        px *= mu
        px += cd[j]
        pxb *= a
        pxb += cdbar[j]
        if E is not None:
            dpe *= a
            dpe += pe
            pe *= a
            pe += E[j]
            run *= a
            run += np.abs(p)
    gm = 2 * (2 * dm + 1) * _EPS   # gamma_{2 dm}, doubled (a priori mu-Horner)
    g = gx + gm
    if E is None:
        F = np.abs(p) + g * pb
        D = np.abs(dp) - g * dpb
    else:
        F = np.abs(p) + pe + 2.02 * _EPS * run
        D = np.abs(dp) - dpe - gm * dpb
    eta = F / D
    # |P''| on the disc: the bars' second derivative at |mu| + 2 eta <= its value at |mu|
    # times (1 + t)^m <= 1 / (1 - m t), t = 2 eta / |mu|, m = dm - 2 (nonnegative
    # coefficients; m t < 1 else the certificate fails); |c_j| <= (1 + g) bar_j
    grow = 1 - max(dm - 2, 0) * 2 * eta / a
    K = 2 * d2pb * (1 + 4 * g) / grow
    h = K * eta / D
    rad = 2 * eta + 2 * dx * (np.abs(px) + g * pxb) / D
    rad[~(D > 0) | ~(grow > 0) | ~(h <= 0.45) | ~np.isfinite(mu) | ~np.isfinite(rad)] = np.inf
    return rad


def _small_guesses(c: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """Replace guesses lost in round-off (below 1e-8 of the largest) by the roots of the
    truncated polynomial: the rigid-body branches (at most two: u_x and u_y translations)
    are the roots of :math:`c_0 + c_1\\mu` or :math:`c_0 + c_1\\mu + c_2\\mu^2` to a
    relative O(u) (the remaining roots are O(1)). Arrays are (rows, points)."""
    small = mu < 1e-8 * np.max(mu, axis=0)
    z = small.sum(axis=0)
    one = np.flatnonzero(z == 1)
    if one.size:
        mu[0, one] = -c[0, one] / c[1, one]
    two = np.flatnonzero(z == 2)
    if two.size and c.shape[0] > 2:
        a0, a1, a2 = c[0, two], c[1, two], c[2, two]
        q = -0.5 * (a1 + np.copysign(np.sqrt(np.maximum(a1 * a1 - 4 * a0 * a2, 0)), a1))
        r1, r2 = a0 / q, q / a2   # stable quadratic roots (Numerical Recipes 5.6)
        mu[0, two], mu[1, two] = np.minimum(r1, r2), np.maximum(r1, r2)
    return mu
