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

import math
from dataclasses import dataclass, field

import numpy as np

from .errors import InputError, check_nu, check_positive, check_positive_int, check_wavenumbers

__all__ = [
    "ExactBranches",
    "cos_sqrt",
    "cutoff_frequencies",
    "deflated_frequency_function",
    "frequency_function",
    "numeric_frequency_function",
    "sinc_sqrt",
    "speed_ratio_squared",
    "trace_branches",
]


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
# Numeric twin and root tracing of the exact branches
# ---------------------------------------------------------------------------------------


def cos_sqrt(z):
    """:math:`C(z) = \\cos\\sqrt z` for real arrays (``cosh`` of :math:`\\sqrt{-z}` for z < 0).

    >>> float(cos_sqrt(-1.0)) == math.cosh(1.0)
    True
    """
    z = np.asarray(z, dtype=float)
    t = np.sqrt(np.abs(z))
    return np.where(z >= 0, np.cos(t), np.cosh(t))


def sinc_sqrt(z):
    """:math:`S(z) = \\sin\\sqrt z / \\sqrt z` for real arrays, equal to 1 at z = 0.

    >>> float(sinc_sqrt(0.0)), float(sinc_sqrt(math.pi**2)) < 1e-16
    (1.0, True)
    """
    z = np.asarray(z, dtype=float)
    t = np.sqrt(np.abs(z))
    safe = np.where(t == 0, 1.0, t)
    return np.where(t == 0, 1.0, np.where(z >= 0, np.sin(safe), np.sinh(safe)) / safe)


def numeric_frequency_function(kind: str, kappa, Omega, nu: float, form: str = "standard"):
    """:func:`frequency_function` evaluated in floating point (numpy arrays broadcast).

    >>> abs(float(numeric_frequency_function("S", 0.0, math.pi, 0.3))) < 1e-12
    True
    """
    kappa, Omega = np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float)
    return frequency_function(kind, kappa**2, Omega**2, nu, cos_sqrt, sinc_sqrt, form)


def _sinc(x):
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
    kappa, Omega = np.asarray(kappa, dtype=float), np.asarray(Omega, dtype=float)
    k2, W2 = kappa**2, Omega**2
    s = speed_ratio_squared(nu)
    P, Q = s * W2 - k2, W2 - k2
    a2 = (Q - k2) ** 2
    dC, dS = _divided_differences(P, Q)
    CP, SP, CQ, SQ = cos_sqrt(P), sinc_sqrt(P), cos_sqrt(Q), sinc_sqrt(Q)
    D = SP * dC - CP * dS
    if kind == "S":
        return -(1 - s) * a2 * D + (W2 - 4 * (1 - s) * k2) * SP * CQ
    if kind == "A":
        return (1 - s) * a2 * D + W2 * CP * SQ
    raise InputError(f"kind must be 'S' or 'A', got {kind!r}")


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
    check_positive("omega_max", omega_max)
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


@dataclass
class ExactBranches:
    """Exact Rayleigh-Lamb branches on a kappa grid.

    Attributes
    ----------
    kappa : ndarray, shape (m,)
    omega : dict
        ``label -> ndarray (m,)`` of :math:`\\Omega`, NaN where the branch lies above
        ``omega_max``. Labels ``S0, S1, ...`` and ``A0, A1, ...`` in the order of
        :math:`\\Omega` at each :math:`\\kappa` within each symmetry.
    failures : list of (kind, kappa, reason)
        Places where the tracer could not certify it found every root; never empty silently.
    """

    kappa: np.ndarray
    omega: dict[str, np.ndarray]
    nu: float
    omega_max: float
    failures: list[tuple[str, float, str]] = field(default_factory=list)

    def symmetry(self, label: str) -> str:
        """``"S"`` or ``"A"``."""
        return label[0]


def _check_grid(kappa) -> np.ndarray:
    kappa = check_wavenumbers(kappa)
    if kappa.max() > 300:
        raise InputError(f"kappa must be <= 300 (cosh overflow), got {kappa.max()}")
    return kappa


def _illinois(f, a, b, fa, fb, rtol: float, max_iter: int = 100):
    """Vectorised Illinois (modified regula falsi) on brackets with ``fa * fb < 0``."""
    a, b, fa, fb = a.copy(), b.copy(), fa.copy(), fb.copy()
    side = np.zeros(a.shape, dtype=int)
    active = np.ones(a.shape, dtype=bool)
    for _ in range(max_iter):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        A, B, FA, FB = a[idx], b[idx], fa[idx], fb[idx]
        with np.errstate(divide="ignore", invalid="ignore"):
            c = (A * FB - B * FA) / (FB - FA)
        bad = ~((c > np.minimum(A, B)) & (c < np.maximum(A, B)))
        c = np.where(bad, 0.5 * (A + B), c)
        fc = f(idx, c)
        left = np.sign(fc) == np.sign(FA)
        # c replaces a where f(c) has the sign of f(a), else b; halve the stale end (Illinois)
        new_a, new_fa = np.where(left, c, A), np.where(left, fc, FA)
        new_b, new_fb = np.where(left, B, c), np.where(left, FB, fc)
        sd = side[idx]
        new_fb = np.where(left & (sd == 1), 0.5 * new_fb, new_fb)
        new_fa = np.where(~left & (sd == -1), 0.5 * new_fa, new_fa)
        side[idx] = np.where(left, 1, -1)
        a[idx], b[idx], fa[idx], fb[idx] = new_a, new_b, new_fa, new_fb
        done = (np.abs(new_b - new_a) <= rtol * np.abs(c)) | (fc == 0)
        a[idx[done]] = b[idx[done]] = c[done]
        active[idx[done]] = False
    return 0.5 * (a + b), active


def _scan_roots(kind, kappa, nu, omega_top, step, rtol, max_depth, max_passes=6):
    """All roots of G in (0, omega_top] for every kappa: list of arrays, and failures.

    Continuation safeguard: the roots found at each kappa's neighbours (and the midpoints
    between them) are added as samples, until no pass finds a new root.
    """
    grid = np.arange(0.0, omega_top + step, step)
    ki = np.repeat(np.arange(kappa.size), grid.size)
    w = np.tile(grid, kappa.size)
    g = deflated_frequency_function(kind, kappa[ki], w, nu)
    count = None
    for _ in range(max_passes):
        per_k, failures, ki, w, g = _refine_and_solve(kind, kappa, nu, ki, w, g, rtol, max_depth)
        new_count = np.array([r.size for r in per_k])
        if count is not None and np.array_equal(new_count, count):
            break
        count = new_count
        seeds_k, seeds_w = [], []
        for i in range(kappa.size):
            for nb in (i - 1, i + 1):
                if 0 <= nb < kappa.size and per_k[nb].size:
                    r = per_k[nb]
                    extra = np.concatenate([r, 0.5 * (r[1:] + r[:-1])])
                    seeds_w.append(extra[extra <= omega_top])
                    seeds_k.append(np.full(seeds_w[-1].size, i))
        if not seeds_k:
            break
        new_k, new_w = np.concatenate(seeds_k), np.concatenate(seeds_w)
        new_g = deflated_frequency_function(kind, kappa[new_k], new_w, nu)
        ki, w, g = _merge((ki, w, g), (new_k, new_w, new_g))
    else:
        failures.append((kind, float(kappa[0]), "continuation passes did not settle"))
    return per_k, failures


def _merge(old, new):
    """Union of two sample sets (kappa index, Omega, G), sorted, duplicates dropped."""
    ki, w, g = (np.concatenate(v) for v in zip(old, new))
    order = np.lexsort((w, ki))
    ki, w, g = ki[order], w[order], g[order]
    keep = np.concatenate([[True], (np.diff(w) != 0) | (np.diff(ki) != 0)])
    return ki[keep], w[keep], g[keep]


def _refine_and_solve(kind, kappa, nu, ki, w, g, rtol, max_depth):
    failures = []
    for depth in range(max_depth + 1):
        same_k = ki[1:-1] == ki[:-2]
        same_k &= ki[1:-1] == ki[2:]
        g0, g1, g2 = g[:-2], g[1:-1], g[2:]
        dip = same_k & (np.sign(g0) == np.sign(g1)) & (np.sign(g2) == np.sign(g1))
        dip &= (np.abs(g1) <= np.abs(g0)) & (np.abs(g1) <= np.abs(g2))
        j = np.flatnonzero(dip) + 1
        if j.size:
            # vertex of the parabola through the three samples: a hidden pair of roots
            # (a near crossing, a veering) shows as a vertex across or close to zero
            w0, w1, w2 = w[j - 1], w[j], w[j + 1]
            d01 = (g[j] - g[j - 1]) / (w1 - w0)
            d12 = (g[j + 1] - g[j]) / (w2 - w1)
            c2 = (d12 - d01) / (w2 - w0)
            with np.errstate(divide="ignore", invalid="ignore"):
                wv = 0.5 * (w0 + w1) - d01 / (2 * c2)
                vertex = g[j - 1] + (wv - w0) * d01 + c2 * (wv - w0) * (wv - w1)
            suspect = ~np.isfinite(vertex) | (np.sign(vertex) != np.sign(g[j]))
            suspect |= np.abs(vertex) < 0.5 * np.abs(g[j])
            j = j[suspect]
        if j.size == 0:
            break
        if depth == max_depth:
            for jj in j:
                failures.append((kind, float(kappa[ki[jj]]),
                                 f"unresolved near-double root near Omega={w[jj]:.6g}"))
            break
        frac = np.linspace(0, 1, 9)[1:-1]
        new_w = np.concatenate([
            (w[j - 1][:, None] + frac * (w[j] - w[j - 1])[:, None]).ravel(),
            (w[j][:, None] + frac * (w[j + 1] - w[j])[:, None]).ravel(),
        ])
        new_k = np.concatenate([np.repeat(ki[j], frac.size), np.repeat(ki[j], frac.size)])
        new_g = deflated_frequency_function(kind, kappa[new_k], new_w, nu)
        ki, w, g = _merge((ki, w, g), (new_k, new_w, new_g))
    # brackets: sign changes between neighbours at the same kappa, plus exact zeros
    same = ki[1:] == ki[:-1]
    change = same & (np.sign(g[1:]) != np.sign(g[:-1])) & (g[:-1] != 0)
    j = np.flatnonzero(change)
    a, b, fa, fb, kk = w[j], w[j + 1], g[j], g[j + 1], ki[j]
    exact = np.flatnonzero(same & (g[1:] == 0))

    def f(idx, x):
        return deflated_frequency_function(kind, kappa[kk[idx]], x, nu)

    roots, unconverged = _illinois(f, a, b, fa, fb, rtol)
    for i in np.flatnonzero(unconverged):
        failures.append((kind, float(kappa[kk[i]]), "root refinement did not converge"))
    roots = np.concatenate([roots, w[exact + 1]])
    kk = np.concatenate([kk, ki[exact + 1]])
    order = np.lexsort((roots, kk))
    roots, kk = roots[order], kk[order]
    per_k = np.split(roots, np.searchsorted(kk, np.arange(1, kappa.size)))
    return per_k, failures, ki, w, g


def trace_branches(
    nu: float,
    kappa,
    omega_max: float,
    *,
    kinds: tuple[str, ...] = ("S", "A"),
    step: float = 0.05,
    rtol: float = 1e-15,
    max_depth: int = 12,
    chunk: int = 2000,
    progress=None,
) -> ExactBranches:
    """Every exact Rayleigh-Lamb branch with :math:`\\Omega \\le \\Omega_{max}` on a kappa grid.

    For real :math:`\\kappa` each symmetry class is a self-adjoint eigenproblem in
    :math:`\\Omega^2`: its branches never cross (they veer), so the j-th root in increasing
    :math:`\\Omega` *is* branch :math:`S_j` (or :math:`A_j`) at every :math:`\\kappa`, and the
    labels cannot swap at a near-crossing once no root is skipped. Roots are bracketed on a
    grid of spacing ``step`` of the deflated, pole-free function
    (:func:`deflated_frequency_function`); wherever three samples of the same sign dip
    towards zero (the signature of two close roots, e.g. a veering pair or the split of a
    double cut-off) the cells are refined eight-fold, up to ``max_depth`` times, and
    whatever stays unresolved is listed in ``failures`` with its kappa. Continuation along
    kappa: the roots found at each grid neighbour, and the midpoints between them, are added
    as samples and the scan is repeated until the root counts settle, so a pair seen at one
    kappa is found at the next; a branch that still vanishes between two neighbours that have
    it is reported. Brackets are closed
    by the Illinois method to relative width ``rtol``. At :math:`\\kappa = 0` the closed-form
    cut-offs (:func:`cutoff_frequencies`) are used.

    Parameters
    ----------
    nu : float
        Poisson's ratio, in (-1, 0.5).
    kappa : array_like
        Dimensionless wavenumbers :math:`\\kappa = kh \\ge 0`.
    omega_max : float
        Largest :math:`\\Omega = \\omega h / c_T` of interest.
    step, rtol, max_depth :
        Scan spacing, root tolerance and refinement depth (the accuracy/speed settings).
    chunk : int
        Kappa points per vectorised block (bounds the memory).
    progress : callable, optional
        Called with the number of kappa points finished after each block.

    Returns
    -------
    ExactBranches

    Examples
    --------
    >>> br = trace_branches(0.3, [0.0, 1.0], 3.5)
    >>> sorted(br.omega)
    ['A0', 'A1', 'S0', 'S1', 'S2']
    >>> bool(br.omega["S2"][0] == math.pi), round(float(br.omega["A0"][1]), 12)
    (True, 0.650345159155)

    References
    ----------
    J. L. Rose, *Ultrasonic waves in solid media*, Cambridge University Press 2004, ch. 8;
    F. A. Amirkulova, PhD thesis, Rutgers 2011 (ref [1] of the paper).
    """
    nu = float(check_nu(nu))
    kappa = _check_grid(kappa)
    try:
        omega_max = float(omega_max)
    except (TypeError, ValueError):
        raise InputError(f"omega_max must be a finite number > 0, got {omega_max!r}") from None
    check_positive("omega_max", omega_max)
    check_positive("step", step)
    check_positive("rtol", rtol)
    chunk = check_positive_int("chunk", chunk)
    omega = {}
    failures = []
    top = omega_max * (1 + 1e-9) + 2 * step
    for kind in kinds:
        per_k = [None] * kappa.size
        zero = np.flatnonzero(kappa == 0)
        positive = np.flatnonzero(kappa > 0)
        cut = np.array([w for w, _ in cutoff_frequencies(kind, nu, omega_max)])
        for i in zero:
            per_k[i] = cut
        if positive.size:
            kp, roots = kappa[positive], []
            for lo in range(0, kp.size, chunk):
                hi = min(lo + chunk, kp.size)
                # one neighbour either side keeps the continuation check across chunk seams
                a, b = max(lo - 1, 0), min(hi + 1, kp.size)
                r, fails = _scan_roots(kind, kp[a:b], nu, top, step, rtol, max_depth)
                roots += r[lo - a:hi - a]
                failures += [f for f in fails if kp[lo] <= f[1] <= kp[hi - 1]]
                if progress is not None:
                    progress(hi - lo)
            for i, r in zip(positive, roots):
                per_k[i] = r[r <= omega_max]
        n_br = max(len(r) for r in per_k)
        for j in range(n_br):
            omega[f"{kind}{j}"] = np.array(
                [r[j] if j < len(r) else np.nan for r in per_k], dtype=float)
        # a branch that vanishes and reappears in the window away from omega_max is a skip
        for j in range(n_br):
            y = omega[f"{kind}{j}"]
            gone = np.isnan(y)
            inner = np.flatnonzero(gone[1:-1] & ~gone[:-2] & ~gone[2:]) + 1
            for i in inner:
                if max(y[i - 1], y[i + 1]) < omega_max - 4 * step:
                    failures.append((kind, float(kappa[i]), f"{kind}{j} lost between neighbours"))
    return ExactBranches(kappa, omega, nu, omega_max, list(dict.fromkeys(failures)))
