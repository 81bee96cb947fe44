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
    "numeric_frequency_function",
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

