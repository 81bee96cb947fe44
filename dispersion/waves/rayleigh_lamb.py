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
serves truncated power series (:mod:`dispersion.symbolic.power_balance`) and floating point.

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
from fractions import Fraction

from dispersion.errors import InputError, check_nu, check_real_in_range

__all__ = [
    "OMEGA_MAX",
    "cos_sqrt",
    "cutoff_frequencies",
    "deflated_frequency_function",
    "deflated_with_noise",
    "evanescent_frequency_function",
    "frequency_slope",
    "frequency_function",
    "mindlin_bounds",
    "numeric_frequency_function",
    "scaled_frequency_function",
    "scaled_slope",
    "scaled_with_noise",
    "sinc_sqrt",
    "speed_ratio_squared",
]


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


# ---------------------------------------------------------------------------------------
# Numeric twin (the root tracer is dispersion.waves.exact_branches)
# ---------------------------------------------------------------------------------------


def cos_sqrt(z):
    """:math:`C(z) = \\cos\\sqrt z` for real arrays (``cosh`` of :math:`\\sqrt{-z}` for z < 0).

    >>> float(cos_sqrt(-1.0)) == math.cosh(1.0)
    True
    """
    import numpy as np  # deferred: the exact series path needs no numpy
    z = np.asarray(z, dtype=float)
    t = np.sqrt(np.abs(z))
    return np.where(z >= 0, np.cos(t), np.cosh(t))


def sinc_sqrt(z):
    """:math:`S(z) = \\sin\\sqrt z / \\sqrt z` for real arrays, equal to 1 at z = 0.

    >>> float(sinc_sqrt(0.0)), float(sinc_sqrt(math.pi**2)) < 1e-16
    (1.0, True)
    """
    import numpy as np  # deferred: the exact series path needs no numpy
    z = np.asarray(z, dtype=float)
    t = np.sqrt(np.abs(z))
    safe = np.where(t == 0, 1.0, t)
    return np.where(t == 0, 1.0, np.where(z >= 0, np.sin(safe), np.sinh(safe)) / safe)


def numeric_frequency_function(kind: str, kappa, Omega, nu: float, form: str = "standard"):
    """:func:`frequency_function` evaluated in floating point (numpy arrays broadcast).

    >>> abs(float(numeric_frequency_function("S", 0.0, math.pi, 0.3))) < 1e-12
    True
    """
    import numpy as np  # deferred: the exact series path needs no numpy
    kappa, Omega = np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float)
    return frequency_function(kind, kappa**2, Omega**2, nu, cos_sqrt, sinc_sqrt, form)


def _sinc(x):
    import numpy as np  # deferred: the exact series path needs no numpy
    return np.sinc(x / np.pi)


_SERIES_TERMS = 24
_C_COEF = [(-1) ** k / math.factorial(2 * k) for k in range(_SERIES_TERMS)]
_S_COEF = [(-1) ** k / math.factorial(2 * k + 1) for k in range(_SERIES_TERMS)]


def _divided_differences(P, Q):
    """:math:`C[P,Q]` and :math:`S[P,Q]`, the divided differences, without cancellation.

    Near the origin by their power series; elsewhere by the half-angle forms
    :math:`C[P,Q] = -\\tfrac12 \\operatorname{sinc}\\frac{p+q}2 \\operatorname{sinc}\\frac{p-q}2`
    and :math:`S[P,Q] = (T[P,Q] - S(P)) / Q` with :math:`T(z) = z S(z) = p \\sin p`,
    where :math:`p = \\sqrt P, q = \\sqrt Q` (complex for negative arguments).
    """
    import numpy as np  # deferred: the exact series path needs no numpy
    P, Q = np.broadcast_arrays(np.asarray(P, dtype=float), np.asarray(Q, dtype=float))
    small = (np.abs(P) <= 2) & (np.abs(Q) <= 2)
    dC, dS = np.empty(P.shape), np.empty(P.shape)
    # series: X[P,Q] = sum_k c_k h_{k-1}(P, Q), h the complete homogeneous polynomials
    Ps, Qs = P[small], Q[small]
    h, qk = np.ones_like(Ps), np.ones_like(Ps)
    sc, ss = np.zeros_like(Ps), np.zeros_like(Ps)
    for k in range(1, _SERIES_TERMS):
        sc += _C_COEF[k] * h
        ss += _S_COEF[k] * h
        qk = qk * Qs
        h = Ps * h + qk
    dC[small], dS[small] = sc, ss
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

    :func:`frequency_function` vanishes at :math:`\\Omega = 0` for every :math:`\\kappa`
    (there P = Q and the two terms cancel). With :math:`a = Q - \\kappa^2`,
    :math:`s = (c_T/c_L)^2` and the divided difference
    :math:`D = (C(P)S(Q) - S(P)C(Q))/(P - Q) = S(P)C[P,Q] - C(P)S[P,Q]`, exact algebra gives

    .. math::

        G_S &= -(1-s)\\,a^2 D + (\\Omega^2 - 4(1-s)\\kappa^2)\\, S(P) C(Q), \\\\
        G_A &= (1-s)\\,a^2 D + \\Omega^2\\, C(P) S(Q),

    free of the cancellation that costs :math:`F` its relative accuracy on A0 at small
    :math:`\\kappa` (there :math:`\\Omega^2 \\sim \\kappa^4`). ``tests/test_rayleigh_lamb.py``
    checks :math:`\\Omega^2 G = F` against :func:`frequency_function` in mpmath.

    >>> abs(float(deflated_frequency_function("A", 0.1, 0.0, 0.3))) > 0
    True
    """
    return deflated_with_noise(kind, kappa, Omega, nu)[0]


def _float_arguments(kappa, Omega, nu: float):
    """Float arrays of the frequency function's arguments: kappa^2, Omega^2, (c_T/c_L)^2, P, Q
    and :math:`a^2 = (Q - \\kappa^2)^2`."""
    import numpy as np  # deferred: the exact series path needs no numpy
    kappa, Omega = np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float)
    k2, W2 = kappa**2, Omega**2
    s = speed_ratio_squared(nu)
    P, Q = s * W2 - k2, W2 - k2
    return k2, W2, s, P, Q, (Q - k2) ** 2


def deflated_with_noise(kind: str, kappa, Omega, nu: float):
    """:func:`deflated_frequency_function` and a bound on its rounding error.

    The bound is :math:`64\\,\\epsilon` times the sum of the magnitudes of the two terms:
    where :math:`|G|` lies below it the sign of G carries no information, so a root tracer
    must not count sign changes there (they are round-off, not roots).

    >>> g, noise = deflated_with_noise("S", 1e-8, math.pi, 0.3)
    >>> bool(abs(g) <= noise)
    True
    """
    import numpy as np  # deferred: the exact series path needs no numpy
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
    import numpy as np  # deferred: the exact series path needs no numpy
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


def _sinc_sqrt_prime(z):
    """:math:`S'(z) = (C(z) - S(z)) / (2z)`, by its power series near 0."""
    import numpy as np  # deferred: the exact series path needs no numpy
    z = np.asarray(z, dtype=float)
    small = np.abs(z) < 0.5
    with np.errstate(divide="ignore", invalid="ignore"):
        out = (cos_sqrt(z) - sinc_sqrt(z)) / (2 * np.where(small, 1.0, z))
    ser = np.zeros_like(z)
    zk = np.ones_like(z)
    for k in range(1, 14):
        ser += k * _S_COEF[k] * zk
        zk = zk * z
    return np.where(small, ser, out)


def frequency_slope(kind: str, kappa, Omega, nu: float):
    """Slope :math:`d\\Omega/d\\kappa = -F_\\kappa / F_\\Omega` of a root of F (implicit function).

    With :math:`C'(z) = -S(z)/2` and :math:`S'(z) = (C(z) - S(z))/(2z)` the partial derivatives
    of :func:`frequency_function` in :math:`(\\kappa^2, P, Q)` are closed forms, and

    .. math::

        \\frac{d\\Omega}{d\\kappa} = -\\frac{\\kappa\\,(F_{\\kappa^2} - F_P - F_Q)}
                                         {\\Omega\\,(s F_P + F_Q)},

    the dimensionless group velocity :math:`c_g / c_T` when :math:`(\\kappa, \\Omega)` lies
    on a branch. Meaningful only at roots (elsewhere it is the slope of a level set).

    >>> cp = math.sqrt(2 / (1 - 0.3))   # plate speed / c_T: the S0 slope at kappa -> 0
    >>> W = float(cp * 0.01)
    >>> abs(float(frequency_slope("S", 0.01, W, 0.3)) - cp) < 1e-4
    True
    """
    import numpy as np  # deferred: the exact series path needs no numpy
    kappa, Omega = np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float)
    k2, W2 = kappa**2, Omega**2
    s = speed_ratio_squared(nu)
    P, Q = s * W2 - k2, W2 - k2
    a = Q - k2
    CP, SP, CQ, SQ = cos_sqrt(P), sinc_sqrt(P), cos_sqrt(Q), sinc_sqrt(Q)
    dCP, dCQ = -SP / 2, -SQ / 2
    dSP, dSQ = _sinc_sqrt_prime(P), _sinc_sqrt_prime(Q)
    if kind == "S":
        Fk = -2 * a * CP * SQ + 4 * P * SP * CQ
        FP = a * a * dCP * SQ + 4 * k2 * (SP + P * dSP) * CQ
        FQ = 2 * a * CP * SQ + a * a * CP * dSQ + 4 * k2 * P * SP * dCQ
    elif kind == "A":
        Fk = -2 * a * SP * CQ + 4 * Q * CP * SQ
        FP = a * a * dSP * CQ + 4 * k2 * Q * dCP * SQ
        FQ = 2 * a * SP * CQ + a * a * SP * dCQ + 4 * k2 * (CP * SQ + Q * CP * dSQ)
    else:
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    with np.errstate(divide="ignore", invalid="ignore"):
        return -kappa * (Fk - FP - FQ) / (Omega * (s * FP + FQ))


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



# ---------------------------------------------------------------------------------------
# The scaled (Mindlin-bound) form: a well-scaled real function with a certified root count
# ---------------------------------------------------------------------------------------


def _quotient_series(num, den, n: int) -> list[float]:
    """First ``n`` Taylor coefficients of num/den (exact rational arithmetic, then float)."""
    out = []
    for k in range(n):
        c = Fraction(num[k]) - sum(out[j] * den[k - j] for j in range(k))
        out.append(c / den[0])
    return [float(c) for c in out]


_N_TAYLOR = 32
_C_FRAC = [Fraction((-1) ** k, math.factorial(2 * k)) for k in range(_N_TAYLOR)]
_S_FRAC = [Fraction((-1) ** k, math.factorial(2 * k + 1)) for k in range(_N_TAYLOR)]
#: Taylor coefficients in z of zeta(z) = C(z)/S(z) = sqrt(z) cot sqrt(z) (radius pi^2) and of
#: tau(z) = S(z)/C(z) = tan sqrt(z) / sqrt(z) (radius pi^2/4).
_ZETA_COEF = _quotient_series(_C_FRAC, _S_FRAC, _N_TAYLOR)
_TAU_COEF = _quotient_series(_S_FRAC, _C_FRAC, _N_TAYLOR)
#: Below this |z| zeta and tau come from their Taylor series (12 terms: error < 1e-18).
_TAYLOR_Z = 0.05
#: Below this max(|P|, |Q|) the deflated form is used: its divided differences by their
#: Taylor series (the tau series converges like (0.5 / 2.47)^k: 28 terms for 1e-18).
_DEFLATE_Z = 0.5


def _taylor(coef, z, terms: int):
    out = coef[terms - 1] + 0 * z
    for c in coef[terms - 2::-1]:
        out = out * z + c
    return out


def _zeta_tau(z, which: str):
    """zeta(z) = sqrt(z) cot sqrt(z) or tau(z) = tan sqrt(z)/sqrt(z), real or complex z."""
    import numpy as np  # deferred: the exact series path needs no numpy

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
        val[small] = _taylor(_ZETA_COEF if which == "zeta" else _TAU_COEF, z[small], 12)
    return val


def _divided_difference(coef, P, Q, terms: int = 28):
    """f[P, Q] = sum_k c_k h_{k-1}(P, Q) for f = sum_k c_k z^k (h: complete homogeneous)."""
    h, qk = 1 + 0 * P, 1 + 0 * Q
    out = 0 * P
    for k in range(1, terms):
        out = out + coef[k] * h
        qk = qk * Q
        h = P * h + qk
    return out


def _scaled_parts(kind: str, kappa, Omega, nu: float, noise: bool):
    import numpy as np  # deferred: the exact series path needs no numpy

    if kind not in ("S", "A"):
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    kappa, Omega = np.broadcast_arrays(np.asarray(kappa), np.asarray(Omega))
    k2, W2 = kappa * kappa, Omega * Omega
    s = speed_ratio_squared(nu)
    P, Q = s * W2 - k2, W2 - k2
    a = Q - k2
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
                zP, zQ = _taylor(_ZETA_COEF, Pi, 16), _taylor(_ZETA_COEF, Qi, 16)
                u1 = W2i * zP
                u2 = 4 * (1 - s) * k2i * (Qi * _divided_difference(_ZETA_COEF, Pi, Qi) - zQ)
                Ri = (u1 + u2) / Pi
                scale = (np.abs(u1) + np.abs(u2)) / np.abs(Pi)
                rel = eps * (s * W2i + k2i) / np.abs(Pi)
            else:
                ai = Qi - k2i
                u1 = (1 - s) * ai * ai * _divided_difference(_TAU_COEF, Pi, Qi)
                u2 = -W2i * _taylor(_TAU_COEF, Qi, 28)
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
    import numpy as np  # deferred: the exact series path needs no numpy
    return _scaled_parts(kind, np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float),
                         nu, noise=True)


def mindlin_bounds(kind: str, kappa: float, nu: float, omega_max: float) -> list[float]:
    """The poles of :func:`scaled_frequency_function` at one kappa, up to the first above
    ``omega_max``: the frequencies of the plate with mixed faces (Mindlin 1960), sorted.

    Symmetric: :math:`P = (m\\pi)^2, m \\ge 0` and :math:`Q = (n\\pi)^2, n \\ge 1`;
    antisymmetric: :math:`P = ((m+\\tfrac12)\\pi)^2` and :math:`Q = ((n+\\tfrac12)\\pi)^2`,
    :math:`m, n \\ge 0` (:math:`P = s\\Omega^2 - \\kappa^2`, :math:`Q = \\Omega^2 - \\kappa^2`).
    For :math:`\\kappa > 0` exactly one root of the class lies between 0 and the first bound
    and between consecutive bounds (a root sits *on* a bound that occurs twice).

    >>> [round(w, 6) for w in mindlin_bounds("A", 0.0, 0.3, 3.0)]
    [1.570796, 2.938691, 4.712389]
    """
    if kind not in ("S", "A"):
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    s = speed_ratio_squared(nu)
    off = 0.0 if kind == "S" else 0.5
    k2 = kappa * kappa
    out = []
    for scale, first in ((s, 0), (1.0, 1 if kind == "S" else 0)):
        j = first
        while True:
            w = math.sqrt((k2 + ((j + off) * math.pi) ** 2) / scale)
            out.append(w)
            if w > omega_max:
                break
            j += 1
    out.sort()
    top = next(i for i, w in enumerate(out) if w > omega_max)
    return out[:top + 1]


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
    import numpy as np  # deferred: the exact series path needs no numpy

    kappa, Omega = np.broadcast_arrays(np.asarray(kappa, dtype=float),
                                       np.asarray(Omega, dtype=float))
    hk, hw = 1e-30 * kappa, 1e-30 * Omega
    with np.errstate(divide="ignore", invalid="ignore"):  # h underflows at kappa ~ 1e-300
        Rk = scaled_frequency_function(kind, kappa + 1j * hk, Omega + 0j, nu).imag / hk
        Rw = scaled_frequency_function(kind, kappa + 0j, Omega + 1j * hw, nu).imag / hw
        return -Rk / Rw
