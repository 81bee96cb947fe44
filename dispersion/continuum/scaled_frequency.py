"""The Rayleigh-Lamb function scaled by its Mindlin bounds: a well-scaled real form whose roots
are counted exactly.

:func:`scaled_frequency_function` R divides
:func:`~dispersion.continuum.rayleigh_lamb.frequency_function` by the factor that carries its
growth and its trivial root; its poles are the closed-form *Mindlin bounds*
(:func:`mindlin_bounds`, :func:`bound_table`), between consecutive ones R falls strictly
from :math:`+\\infty` to :math:`-\\infty`, so exactly one root lies in each interval. The
tracer of the exact branches (:mod:`dispersion.continuum.exact_branches`) counts and certifies
its roots with it (:func:`scaled_with_noise` bounds the rounding error), and the exact group
velocities (:mod:`dispersion.continuum.velocities`) are its slope :func:`scaled_slope`.

>>> b = mindlin_bounds("S", 1.0, 0.3, 4.0)       # one root between consecutive bounds
>>> r = scaled_frequency_function("S", 1.0, [b[0] * (1 + 1e-9), b[1] * (1 - 1e-9)], 0.3)
>>> bool(r[0] > 0 > r[1])
True

References
----------
R. D. Mindlin 1960 (the bounds; cited in full at :func:`scaled_frequency_function`).
"""
from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from dispersion.errors import InputError
from dispersion.continuum.numeric_frequency import (C_TAYLOR, S_TAYLOR, divided_difference,
                                                plate_arguments, taylor_sum)
from dispersion.continuum.rayleigh_lamb import speed_ratio_squared

__all__ = ["bound_table", "mindlin_bounds", "removable_bound", "scaled_frequency_function",
           "scaled_slope", "scaled_with_noise"]


def _quotient_series(num, den, n: int) -> list[float]:
    """First ``n`` Taylor coefficients of num/den (exact rational arithmetic, then float)."""
    out = []
    for k in range(n):
        c = Fraction(num[k]) - sum(out[j] * den[k - j] for j in range(k))
        out.append(c / den[0])
    return [float(c) for c in out]


#: Taylor coefficients in z of zeta(z) = C(z)/S(z) = sqrt(z) cot sqrt(z) (radius pi^2) and of
#: tau(z) = S(z)/C(z) = tan sqrt(z) / sqrt(z) (radius pi^2/4).
_ZETA_COEF = _quotient_series(C_TAYLOR, S_TAYLOR, len(C_TAYLOR))
_TAU_COEF = _quotient_series(S_TAYLOR, C_TAYLOR, len(C_TAYLOR))
#: Below this |z| zeta and tau come from their Taylor series (12 terms: error < 1e-18).
_TAYLOR_Z = 0.05
#: Below this max(|P|, |Q|) the deflated form is used: its divided differences by their
#: Taylor series (the tau series converges like (0.5 / 2.47)^k: 28 terms for 1e-18).
_DEFLATE_Z = 0.5


def _zeta_tau(z, which: str):
    """zeta(z) = sqrt(z) cot sqrt(z) or tau(z) = tan sqrt(z)/sqrt(z), real or complex z."""
    z = np.asarray(z)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if np.iscomplexobj(z):
            p = np.sqrt(z)
            val = p / np.tan(p) if which == "zeta" else np.tan(p) / p
        else:
            r = np.sqrt(np.abs(z))
            pos = z > 0
            if which == "zeta":
                val = np.where(pos, r / np.tan(r), r / np.tanh(r))
            else:
                val = np.where(pos, np.tan(r), np.tanh(r)) / r
    small = np.abs(z) < _TAYLOR_Z
    if np.any(small):
        val = np.array(val, copy=True)
        val[small] = taylor_sum(_ZETA_COEF if which == "zeta" else _TAU_COEF, z[small], 12)
    return val


def _scaled_parts(kind: str, kappa, Omega, nu: float, noise: bool):
    if kind not in ("S", "A"):
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    kappa, Omega = np.broadcast_arrays(np.asarray(kappa), np.asarray(Omega))
    k2, W2, s, P, Q, a = plate_arguments(kappa, Omega, nu)
    eps = np.finfo(float).eps
    small = np.maximum(np.abs(P), np.abs(Q)) <= _DEFLATE_Z
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if kind == "S":
            zP, zQ = _zeta_tau(P, "zeta"), _zeta_tau(Q, "zeta")
            t1, t2 = a * a * zP / P, 4 * k2 * zQ
            R = (t1 + t2) / W2
        elif kind == "A":
            tP, tQ = _zeta_tau(P, "tau"), _zeta_tau(Q, "tau")
            t1, t2 = a * a * tP, 4 * k2 * Q * tQ
            R = -(t1 + t2) / W2
        else:
            raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
        if noise:
            # P, Q and a carry the rounding of Omega^2, kappa^2, their sum and the square root
            dP, dQ, da = 4 * eps * (s * W2 + k2), 4 * eps * (W2 + k2), 4 * eps * (W2 + 2 * k2)
            if kind == "S":
                dzP = np.where(np.abs(P) < _TAYLOR_Z, 1 / 3, (zP - zP * zP - P) / (2 * P))
                dzQ = np.where(np.abs(Q) < _TAYLOR_Z, 1 / 3, (zQ - zQ * zQ - Q) / (2 * Q))
                sens = a * a * np.abs(dzP / P - zP / (P * P)) * dP + 4 * k2 * np.abs(dzQ) * dQ
            else:
                dtP = np.where(np.abs(P) < _TAYLOR_Z, 1 / 3, (1 + P * tP * tP - tP) / (2 * P))
                dtQ = np.where(np.abs(Q) < _TAYLOR_Z, 1 / 3, (1 + Q * tQ * tQ - tQ) / (2 * Q))
                sens = a * a * np.abs(dtP) * dP + 4 * k2 * np.abs(tQ + Q * dtQ) * dQ
            err = (64 * eps * (np.abs(t1) + np.abs(t2)) + sens + 2 * np.abs(t1 * da / a)) / W2
    # A, evanescent (P, Q < 0, not small): the deflated form with the divided difference of
    # tau by the hyperbolic identity tau[P, Q] = ((tanh t_P + tanh t_Q)/(t_P + t_Q)
    #   - sinhc(t_P - t_Q) sech t_P sech t_Q) / (2 t_P t_Q), t = sqrt(-z): no cancellation with
    # P - Q (A0 at kappa ~ 1 has Omega^2 ~ kappa^2 / 5) and no overflow
    ev = (P < 0) & (Q < 0) & ~small if kind == "A" else np.zeros(P.shape, bool)
    if np.any(ev):
        tP, tQ = np.sqrt(-P[ev]), np.sqrt(-Q[ev])
        d = tP - tQ
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            shc = np.where(np.abs(d) < 1e-4, 1 + d * d / 6, np.sinh(d) / np.where(d == 0, 1, d))
            sech = 4 * np.exp(-(tP + tQ)) / ((1 + np.exp(-2 * tP)) * (1 + np.exp(-2 * tQ)))
            v1 = (np.tanh(tP) + np.tanh(tQ)) / (tP + tQ)
            v2 = shc * sech
            dd = (v1 - v2) / (2 * tP * tQ)
            ai = Q[ev] - k2[ev]
            u1 = (1 - s) * ai * ai * dd
            u2 = -W2[ev] * np.tanh(tQ) / tQ
        R = np.array(R, copy=True)
        R[ev] = u1 + u2
        if noise:
            err = np.array(err, copy=True)
            err[ev] = 128 * eps * (np.abs(u1) * (v1 + v2) / np.abs(v1 - v2) + np.abs(u2))
    if np.any(small):
        i = small
        Pi, Qi, W2i, k2i = P[i], Q[i], W2[i], k2[i]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            if kind == "S":
                zP, zQ = taylor_sum(_ZETA_COEF, Pi, 16), taylor_sum(_ZETA_COEF, Qi, 16)
                u1 = W2i * zP
                u2 = 4 * (1 - s) * k2i * (Qi * divided_difference(_ZETA_COEF, Pi, Qi) - zQ)
                Ri = (u1 + u2) / Pi
                scale = (np.abs(u1) + np.abs(u2)) / np.abs(Pi)
                rel = eps * (s * W2i + k2i) / np.abs(Pi)
            else:
                ai = Qi - k2i
                u1 = (1 - s) * ai * ai * divided_difference(_TAU_COEF, Pi, Qi)
                u2 = -W2i * taylor_sum(_TAU_COEF, Qi, 28)
                Ri = u1 + u2
                scale = np.abs(u1) + np.abs(u2)
                rel = 0.0
        R = np.array(R, copy=True)
        R[i] = Ri
        if noise:
            err = np.array(err, copy=True)
            err[i] = 64 * eps * scale + 4 * rel * np.abs(Ri)
    return (R, err) if noise else R


def scaled_frequency_function(kind: str, kappa, Omega, nu: float):
    """The Rayleigh-Lamb function scaled by its Mindlin-bound factor: a well-scaled real form.

    .. math::

        R_S = \\frac{F_S}{\\Omega^2 P S(P) S(Q)}
            = \\frac{a^2 \\zeta(P)/P + 4\\kappa^2 \\zeta(Q)}{\\Omega^2}, \\qquad
        R_A = -\\frac{F_A}{\\Omega^2 C(P) C(Q)}
            = -\\frac{a^2 \\tau(P) + 4\\kappa^2 Q\\,\\tau(Q)}{\\Omega^2},

    with :math:`\\zeta(z) = \\sqrt z \\cot\\sqrt z` and :math:`\\tau(z) = \\tan\\sqrt z/\\sqrt z`
    (``coth``, ``tanh`` for z < 0), :math:`a = Q - \\kappa^2`. R has the roots of F with
    :math:`\\Omega > 0` and stays of order one where F grows like :math:`e^{2\\kappa}`. Its
    poles are the frequencies of the plate with *mixed* faces (normal displacement and shear
    traction zero, Mindlin 1960), :func:`mindlin_bounds`, and R is the ratio
    :math:`\\sigma_{yy}/u_y` on the face of the solution that satisfies the other boundary
    condition: by the variational principle it *decreases* strictly in :math:`\\Omega^2`
    between consecutive poles, from :math:`+\\infty` to :math:`-\\infty` (from a positive
    value at :math:`\\Omega = 0^+`). Hence, for :math:`\\kappa > 0`, exactly one root lies
    between consecutive bounds, and the number of roots below :math:`\\Omega` is the number
    of bounds below it plus one if :math:`R(\\Omega) < 0`: an exact count (the Morse index of
    the energy form split along the face condition). Where :math:`\\max(|P|, |Q|)` is small
    the deflated forms

    .. math::

        R_S = \\frac{\\Omega^2 \\zeta(P) + 4(1-s)\\kappa^2 (Q\\,\\zeta[P,Q] - \\zeta(Q))}{P},
        \\qquad
        R_A = (1-s)\\,a^2 \\tau[P,Q] - \\Omega^2 \\tau(Q)

    (divided differences by Taylor series) remove the trivial root at :math:`\\Omega = 0`,
    which costs the quotient form its accuracy on A0 at small kappa. Real or complex
    arguments (the complex step of :func:`scaled_slope`).

    >>> r = [float(scaled_frequency_function("A", 10.0, w, 0.3)) for w in (9.27, 9.28)]
    >>> r[0] > 0 > r[1]          # A0 at kappa = 10 lies at Omega = 9.2711348522995...
    True

    References
    ----------
    R. D. Mindlin, Waves and vibrations in isotropic, elastic plates, in *Structural
    Mechanics* (J. N. Goodier, N. J. Hoff eds.), Pergamon 1960, pp. 199-232 (the bounds).
    """
    return _scaled_parts(kind, kappa, Omega, nu, noise=False)


def scaled_with_noise(kind: str, kappa, Omega, nu: float):
    """:func:`scaled_frequency_function` (real arguments) and a bound on its rounding error.

    The bound is :math:`64\\epsilon` times the magnitudes of the terms plus the first-order
    effect of rounding P, Q and a (their derivatives in closed form, from the Riccati
    equations :math:`\\zeta' = (\\zeta - \\zeta^2 - z)/(2z)`,
    :math:`\\tau' = (1 + z\\tau^2 - \\tau)/(2z)`): where :math:`|R|` lies below it the sign
    of R carries no information.

    >>> r, e = scaled_with_noise("S", 1.0, 1.5, 0.3)
    >>> bool(0 < e < 1e-13 * abs(r))
    True
    """
    return _scaled_parts(kind, np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float),
                         nu, noise=True)


def removable_bound(kind: str, nu: float) -> bool:
    """True for the symmetric class where :math:`(c_T/c_L)^2` rounds to 1/2 (nu = 0 in
    floating point): there the first bound, :math:`P = 0` (:math:`\\Omega^2 = 2\\kappa^2`), is
    itself the root S0 (:math:`u_x` uniform, :math:`\\sigma_{yy} = \\lambda\\,\\mathrm{div}\\,u = 0`):
    a removable pole, across which the scaled function is continuous.

    >>> removable_bound("S", 0.0), removable_bound("A", 0.0), removable_bound("S", 0.3)
    (True, False, False)
    """
    return kind == "S" and speed_ratio_squared(nu) == 0.5


def bound_table(kind: str, kappa, nu: float, top: float, first_p: int = 0) -> np.ndarray:
    """The Mindlin bounds (poles of :func:`scaled_frequency_function`) per kappa, sorted,
    shape ``(len(kappa), n)``: every bound up to ``top`` and at least one above it per row.

    Symmetric: :math:`P = (m\\pi)^2, m \\ge` ``first_p`` and :math:`Q = (n\\pi)^2, n \\ge 1`;
    antisymmetric: :math:`P = ((m+\\tfrac12)\\pi)^2, m \\ge` ``first_p`` and
    :math:`Q = ((n+\\tfrac12)\\pi)^2, n \\ge 0` (:math:`P = s\\Omega^2 - \\kappa^2`,
    :math:`Q = \\Omega^2 - \\kappa^2`). ``first_p = 1`` leaves out the removable bound
    (:func:`removable_bound`).

    >>> t = bound_table("A", [0.0, 1.0], 0.3, 3.0)   # at kappa = 0: pi/2, pi/(2 sqrt s), 3 pi/2
    >>> t[:, :3].round(6).tolist()
    [[1.570796, 2.938691, 4.712389], [1.862096, 3.483662, 4.817324]]
    """
    s = speed_ratio_squared(nu)
    off = 0.0 if kind == "S" else 0.5
    k2 = np.asarray(kappa, dtype=float)[:, None] ** 2
    nP = int(math.sqrt(s) * top / math.pi + off) + 2
    nQ = int(top / math.pi + off) + 2
    jP = np.arange(first_p, nP + first_p) + off           # P = (j pi)^2, j >= 0 (+ 1/2 for A)
    jQ = np.arange(1 if kind == "S" else 0, nQ + 1) + off  # Q = (j pi)^2, j >= 1 for S
    wP = np.sqrt((k2 + (jP * math.pi) ** 2) / s)
    wQ = np.sqrt(k2 + (jQ * math.pi) ** 2)
    return np.sort(np.concatenate([wP, wQ], axis=1), axis=1)


def mindlin_bounds(kind: str, kappa: float, nu: float, omega_max: float) -> list[float]:
    """The poles of :func:`scaled_frequency_function` at one kappa, up to the first above
    ``omega_max``: the frequencies of the plate with mixed faces (Mindlin 1960), sorted.

    One row of :func:`bound_table`. For :math:`\\kappa > 0` exactly one root of the class
    lies between 0 and the first bound and between consecutive bounds (a root sits *on* a
    bound that occurs twice).

    >>> [round(w, 6) for w in mindlin_bounds("A", 0.0, 0.3, 3.0)]
    [1.570796, 2.938691, 4.712389]
    """
    if kind not in ("S", "A"):
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    row = bound_table(kind, [kappa], nu, omega_max)[0]
    return row[:int(np.searchsorted(row, omega_max, side="right")) + 1].tolist()


def scaled_slope(kind: str, kappa, Omega, nu: float):
    """Slope :math:`d\\Omega/d\\kappa = -R_\\kappa / R_\\Omega` of a root of the scaled function.

    The partial derivatives of :func:`scaled_frequency_function` by the complex step,
    :math:`R_x = \\operatorname{Im} R(x + i h)/h` with :math:`h = 10^{-30} x`: no difference
    is formed, so no digits are lost to cancellation in h, and the deflated form keeps A0 at
    small kappa free of the trivial root's cancellation. At a point on a branch this is the
    group velocity :math:`c_g/c_T`.

    >>> cp = math.sqrt(2 / (1 - 0.3))   # plate speed / c_T: the S0 slope at kappa -> 0
    >>> abs(float(scaled_slope("S", 0.01, cp * 0.01, 0.3)) - cp) < 1e-4
    True
    """
    kappa, Omega = np.broadcast_arrays(np.asarray(kappa, dtype=float),
                                       np.asarray(Omega, dtype=float))
    hk, hw = 1e-30 * kappa, 1e-30 * Omega
    with np.errstate(divide="ignore", invalid="ignore"):  # h underflows at kappa ~ 1e-300
        Rk = scaled_frequency_function(kind, kappa + 1j * hk, Omega + 0j, nu).imag / hk
        Rw = scaled_frequency_function(kind, kappa + 0j, Omega + 1j * hw, nu).imag / hw
        return -Rk / Rw
