"""Root tracer of the exact Rayleigh-Lamb branches: every root of the frequency equation.

For real :math:`\\kappa` each symmetry class is a self-adjoint eigenproblem in
:math:`\\Omega^2`: its branches never cross (they veer), so the j-th root in increasing
:math:`\\Omega` *is* branch :math:`S_j` (or :math:`A_j`) at every :math:`\\kappa` once no root is
skipped and none is counted twice. The tracer samples the deflated, pole-free function
:func:`dispersion.waves.rayleigh_lamb.deflated_with_noise` together with a bound on its rounding
error, and counts a root only where two samples whose signs are *certain* (above the bound)
differ. Where the function stays within round-off of zero between two samples of the same
sign, two roots may hide closer than floating point can separate: that kappa is listed in
``failures``, never guessed. At :math:`\\kappa \\le` ``SERIES_KAPPA`` the fundamental branches
S0 and A0 come from their power series (:func:`dispersion.waves.exact_series.exact_series`,
truncated after :math:`\\kappa^8`, relative remainder :math:`\\le \\kappa^6`), where the root of
the function would lose digits to round-off (and :math:`\\Omega^2` of A0 underflows below
:math:`\\kappa \\approx 10^{-77}`).

>>> import math
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
from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from dispersion.errors import (
    InputError,
    check_nu,
    check_positive,
    check_positive_int,
    check_real_in_range,
    check_wavenumbers,
)
from dispersion.waves.rayleigh_lamb import (
    OMEGA_MAX,
    cutoff_frequencies,
    deflated_with_noise,
    evanescent_frequency_function,
    speed_ratio_squared,
)

__all__ = [
    "MAX_SAMPLES", "SERIES_KAPPA", "check_samples",
    "ExactBranches", "TracerAccuracy", "exact_fundamental",
    "fundamental_series", "mpmath_error",
    "trace_branches", "tracer_accuracy",
]

#: Below this kappa S0 and A0 come from their series truncated after kappa^8.
SERIES_KAPPA = 1e-3
_SERIES_ORDER = 8

#: Largest scan of one call: kappa points times Omega samples (omega_max / step + 1). Rule:
#: about a minute of work. Measured on this 2-core machine: ~3 us and ~250 B of peak memory
#: per (kappa, Omega) sample for both symmetry classes (2000 kappa x Omega <= 200, and one
#: kappa x Omega <= 1e5), so 2e7 samples take ~60 s and at most ~5 GB of the 24 GiB.
MAX_SAMPLES = 20_000_000


def check_samples(kappa_count: int, omega_max: float, step: float = 0.05,
                  what: str = "len(kappa) * (omega_max / step + 1)") -> float:
    """Refuse, up front, a scan of more than :data:`MAX_SAMPLES` (kappa, Omega) samples.

    ``what`` names the inputs in the message (the CLI passes its option names).

    >>> check_samples(2, 1e6)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: len(kappa) * (omega_max / step + 1) must be <= 2e+07 (about a minute of the tracer), got 4e+07
    """
    samples = kappa_count * (omega_max / step + 1)
    if samples > MAX_SAMPLES:
        raise InputError(f"{what} must be <= {MAX_SAMPLES:.0e} (about a minute of the tracer), "
                         f"got {samples:.3g}")
    return samples


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

    def __post_init__(self):
        # the branches carry their nu, so they cannot be put in units of another material
        from dispersion.waves.branch_set import BranchSet

        if not isinstance(self.omega, BranchSet) or self.omega.nu != self.nu:
            self.omega = BranchSet(self.omega, nu=self.nu)

    def symmetry(self, label: str) -> str:
        """``"S"`` or ``"A"``."""
        return label[0]


@functools.lru_cache(maxsize=32)
def _series_coefficients(label: str, nu: float) -> tuple[tuple[int, float], ...]:
    from dispersion.waves.exact_series import exact_series

    return tuple((k, float(c)) for k, c in sorted(exact_series(label, _SERIES_ORDER, nu=nu).items()))


def fundamental_series(label: str, nu: float, kappa) -> tuple[np.ndarray, np.ndarray]:
    """:math:`\\Omega` and :math:`d\\Omega/d\\kappa` of S0 or A0 from the series of
    :math:`\\Omega^2` (eqs 14 and 16, derived by :mod:`dispersion.symbolic.power_balance`).

    Valid for small kappa only (relative remainder about :math:`\\kappa^6` after
    :math:`\\kappa^8`); :math:`\\Omega` is formed as :math:`\\kappa^l \\sqrt{\\sum c_k \\kappa^{k-2l}}`
    so it never underflows before :math:`\\kappa` does.

    >>> import math
    >>> w, cg = fundamental_series("S0", 0.3, [1e-200])
    >>> float(w[0] / 1e-200) == math.sqrt(2 / 0.7), float(cg[0]) == math.sqrt(2 / 0.7)
    (True, True)
    """
    if label not in ("S0", "A0"):
        raise InputError(f"label must be 'S0' or 'A0', got {label!r}")
    kappa = np.asarray(kappa, dtype=float)
    coef = _series_coefficients(label, float(nu))
    lead = coef[0][0]  # 2 for S0, 4 for A0
    half = lead // 2
    u = sum(c * kappa ** (k - lead) for k, c in coef)          # Omega^2 / kappa^lead
    du = sum((k - lead) * c * kappa ** (k - lead - 1) for k, c in coef if k > lead)
    root = np.sqrt(u)
    omega = kappa**half * root
    # d/dk (k^h sqrt(u)) = h k^(h-1) sqrt(u) + k^h u' / (2 sqrt(u))
    slope = half * kappa ** (half - 1) * root + kappa**half * du / (2 * root)
    return omega, slope


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
        # no floating-point number lies strictly between the ends: the bracket is closed
        done |= np.nextafter(np.minimum(new_a, new_b), np.inf) >= np.maximum(new_a, new_b)
        a[idx[done]] = b[idx[done]] = c[done]
        active[idx[done]] = False
    return 0.5 * (a + b), active


class _Samples:
    """Samples (kappa index, Omega, G, rounding bound of G), sorted by (index, Omega)."""

    def __init__(self, kind, kappa, nu, ki, w, floor):
        self.kind, self.kappa, self.nu, self.floor = kind, kappa, nu, floor
        keep = w >= floor[ki]
        self.ki, self.w = ki[keep], w[keep]
        self.g, self.e = deflated_with_noise(kind, kappa[ki], w, nu)
        self._sort()

    def _sort(self):
        order = np.lexsort((self.w, self.ki))
        ki, w, g, e = self.ki[order], self.w[order], self.g[order], self.e[order]
        keep = np.concatenate([[True], (np.diff(w) != 0) | (np.diff(ki) != 0)])
        self.ki, self.w, self.g, self.e = ki[keep], w[keep], g[keep], e[keep]

    def add(self, ki, w):
        keep = w >= self.floor[ki]
        ki, w = ki[keep], w[keep]
        if ki.size == 0:
            return
        g, e = deflated_with_noise(self.kind, self.kappa[ki], w, self.nu)
        self.ki = np.concatenate([self.ki, ki])
        self.w = np.concatenate([self.w, w])
        self.g = np.concatenate([self.g, g])
        self.e = np.concatenate([self.e, e])
        self._sort()

    def certain(self):
        """Indices of the samples whose sign is above round-off."""
        return np.flatnonzero(np.abs(self.g) > self.e)


def _scan_roots(kind, kappa, nu, omega_top, step, rtol, max_depth, floor, max_passes=6):
    """All roots of G in (floor, omega_top] for every kappa: list of arrays, and failures.

    Continuation safeguard: the roots found at each kappa's neighbours (and the midpoints
    between them) are added as samples, until no pass finds a new root.
    """
    grid = np.arange(0.0, omega_top + step, step)
    ki = np.repeat(np.arange(kappa.size), grid.size)
    w = np.maximum(np.tile(grid, kappa.size), floor[ki])
    smp = _Samples(kind, kappa, nu, ki, w, floor)
    count = None
    for _ in range(max_passes):
        per_k, failures = _refine_and_solve(smp, rtol, max_depth)
        new_count = np.array([r.size for r in per_k])
        if count is not None and np.array_equal(new_count, count):
            break
        changed = np.ones(kappa.size, bool) if count is None else new_count != count
        count = new_count
        seeds_k, seeds_w = [], []
        for i in range(kappa.size):
            for nb in (i - 1, i + 1):
                if 0 <= nb < kappa.size and per_k[nb].size and (changed[nb] or changed[i]):
                    r = per_k[nb]
                    extra = np.concatenate([r, 0.5 * (r[1:] + r[:-1])])
                    seeds_w.append(extra[extra <= omega_top])
                    seeds_k.append(np.full(seeds_w[-1].size, i))
        if not seeds_k:
            break
        smp.add(np.concatenate(seeds_k), np.concatenate(seeds_w))
    else:
        failures += [(kind, float(kappa[i]), "continuation passes did not settle")
                     for i in np.flatnonzero(changed)]
    return per_k, failures


def _refine_and_solve(smp: _Samples, rtol, max_depth):
    kind, kappa = smp.kind, smp.kappa
    failures = []
    for depth in range(max_depth + 1):
        c = smp.certain()
        ki, w, g = smp.ki[c], smp.w[c], smp.g[c]
        same_k = (ki[1:-1] == ki[:-2]) & (ki[1:-1] == ki[2:])
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
            # cells already at the spacing of floating point cannot be refined further
            j = j[np.minimum(w[j] - w[j - 1], w[j + 1] - w[j]) > 64 * np.spacing(w[j])]
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
        smp.add(np.tile(np.repeat(ki[j], frac.size), 2), new_w)
    c = smp.certain()
    ki, w, g = smp.ki[c], smp.w[c], smp.g[c]
    same = ki[1:] == ki[:-1]
    change = same & (np.sign(g[1:]) != np.sign(g[:-1]))
    # two certain samples of one sign with round-off-level samples between them: G touches
    # zero there, and for real kappa (a self-adjoint problem, all roots real) that is a pair
    # of roots closer than floating point separates. The best float answer is a double root
    # at the centre of the stretch; the kappa is listed as a failure all the same.
    between = np.diff(c) > 1
    doubles = []
    for jj in np.flatnonzero(same & ~change & between):
        centre = 0.5 * (smp.w[c[jj] + 1] + smp.w[c[jj + 1] - 1])
        doubles.append((ki[jj], centre))
        failures.append((kind, float(kappa[ki[jj]]), "two roots closer than round-off, "
                         f"given as a double root at Omega={centre:.6g}"))
    j = np.flatnonzero(change)
    a, b, fa, fb, kk = w[j], w[j + 1], g[j], g[j + 1], ki[j]

    def f(idx, x):
        return deflated_with_noise(kind, kappa[kk[idx]], x, smp.nu)[0]

    roots, unconverged = _illinois(f, a, b, fa, fb, rtol)
    for i in np.flatnonzero(unconverged):
        failures.append((kind, float(kappa[kk[i]]), "root refinement did not converge"))
    roots = _polish_evanescent(kind, kappa[kk], roots, smp.nu, unconverged)
    if doubles:
        dk, dw = np.array(doubles).T
        kk = np.concatenate([kk, dk.astype(int), dk.astype(int)])
        roots = np.concatenate([roots, dw, dw])
        order = np.lexsort((roots, kk))
        roots, kk = roots[order], kk[order]
    per_k = np.split(roots, np.searchsorted(kk, np.arange(1, kappa.size)))
    return per_k, failures


def _polish_evanescent(kind, kappa, roots, nu, skip, width: float = 1e-9):
    """Roots with P < 0 closed again on :func:`evanescent_frequency_function`.

    At large kappa the deflated function carries cosh-sized terms whose cancellation costs
    digits (2e-14 on A0 at kappa = 10); the scaled form does not. A root whose scaled
    function has no sign change within ``width`` (relative) keeps its first value.
    """
    # only where cosh(sqrt(-P)) > 10: there the deflated function has lost a digit
    ev = (kappa**2 - speed_ratio_squared(nu) * roots**2 > 9.0) & ~skip & (roots > 0)
    if not np.any(ev):
        return roots
    k, r = kappa[ev], roots[ev]
    a, b = r * (1 - width), r * (1 + width)
    fa = evanescent_frequency_function(kind, k, a, nu)
    fb = evanescent_frequency_function(kind, k, b, nu)
    ok = np.isfinite(fa) & np.isfinite(fb) & (np.sign(fa) * np.sign(fb) < 0)
    if not np.any(ok):
        return roots
    ko = k[ok]

    def f(idx, x):
        return evanescent_frequency_function(kind, ko[idx], x, nu)

    polished, active = _illinois(f, a[ok], b[ok], fa[ok], fb[ok], 1e-17)
    out = roots.copy()
    sub = r.copy()
    sub[ok] = np.where(active, sub[ok], polished)
    out[ev] = sub
    return out


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

    Roots are bracketed on a grid of spacing ``step`` of the deflated function; wherever
    three samples of the same sign dip towards zero (the signature of two close roots, e.g.
    a veering pair or the split of a double cut-off) the cells are refined eight-fold, up to
    ``max_depth`` times, and whatever stays unresolved is listed in ``failures`` with its
    kappa. Continuation along kappa: the roots found at each grid neighbour, and the
    midpoints between them, are added as samples and the scan is repeated until the root
    counts settle; a branch that still vanishes between two neighbours that have it is
    reported. Brackets are closed by the Illinois method to relative width ``rtol``. At
    :math:`\\kappa = 0` the closed-form cut-offs (:func:`cutoff_frequencies`) are used; at
    :math:`0 < \\kappa \\le` ``SERIES_KAPPA`` S0 and A0 come from :func:`fundamental_series`.

    Parameters
    ----------
    nu : float
        Poisson's ratio, in (-1, 0.5).
    kappa : array_like
        Dimensionless wavenumbers :math:`\\kappa = kh \\ge 0`.
    omega_max : float
        Largest :math:`\\Omega = \\omega h / c_T` of interest, in (0, :data:`OMEGA_MAX`], with
        ``len(kappa) * (omega_max / step + 1) <= MAX_SAMPLES`` (:func:`check_samples`).
    step, rtol, max_depth :
        Scan spacing, root tolerance and refinement depth (the accuracy/speed settings).
    chunk : int
        Kappa points per vectorised block (bounds the memory).
    progress : callable, optional
        Called with the number of kappa points finished after each block.

    Returns
    -------
    ExactBranches
    """
    nu = float(check_nu(nu))
    kappa = _check_grid(kappa)
    try:
        omega_max = float(omega_max)
    except (TypeError, ValueError):
        raise InputError(f"omega_max must be a finite number > 0, got {omega_max!r}") from None
    check_real_in_range("omega_max", omega_max, 0, OMEGA_MAX, lo_open=True)
    check_positive("step", step)
    check_positive("rtol", rtol)
    chunk = check_positive_int("chunk", chunk)
    check_samples(kappa.size, omega_max, step)
    omega = {}
    failures = []
    top = omega_max * (1 + 1e-9) + 2 * step
    for kind in kinds:
        per_k = [None] * kappa.size
        zero = np.flatnonzero(kappa == 0)
        positive = np.flatnonzero(kappa > 0)
        cut = cutoff_frequencies(kind, nu, omega_max)
        for i in zero:
            per_k[i] = np.array([w for w, _ in cut])
        if positive.size:
            kp, roots = kappa[positive], []
            # the fundamental branch from its series where round-off would blur its root;
            # the next root of either family lies near a cut-off >= pi/2
            below = min(w for w, fam in cut if fam != "0") / 2 if len(cut) > 1 else top
            small = kp <= SERIES_KAPPA
            floor = np.where(small, below, 0.0)
            for lo in range(0, kp.size, chunk):
                hi = min(lo + chunk, kp.size)
                # one neighbour either side keeps the continuation check across chunk seams
                a, b = max(lo - 1, 0), min(hi + 1, kp.size)
                r, fails = _scan_roots(kind, kp[a:b], nu, top, step, rtol, max_depth,
                                       floor[a:b])
                roots += r[lo - a:hi - a]
                failures += [f for f in fails if kp[lo] <= f[1] <= kp[hi - 1]]
                if progress is not None:
                    progress(hi - lo)
            if np.any(small):
                w0, _ = fundamental_series(f"{kind}0", nu, kp[small])
                for i, w in zip(np.flatnonzero(small), w0):
                    roots[i] = np.concatenate([[w], roots[i]])
                    if w < np.finfo(float).tiny:
                        failures.append((kind, float(kp[i]), f"{kind}0 underflows ({w:.3g})"))
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


def mpmath_error(exact: ExactBranches, count: int = 20, dps: int = 40, seed: int = 0) -> float:
    """Largest relative error of ``count`` random traced roots (kappa > 0) against roots of the
    defining equation (:func:`dispersion.waves.rayleigh_lamb.frequency_function`) found by mpmath
    in ``dps`` digits (:func:`mpmath.workdps`, the global precision is left alone).

    >>> mpmath_error(trace_branches(0.3, [0.5, 2.0], 4.0), count=3) < 1e-14
    True
    """
    import mpmath

    from dispersion.waves.rayleigh_lamb import frequency_function

    rng = np.random.default_rng(seed)
    pts = [(lab, i) for lab, w in exact.omega.items() for i in np.flatnonzero(np.isfinite(w))
           if exact.kappa[i] > 0]
    worst = 0.0
    with mpmath.workdps(dps):
        nu = mpmath.mpf(exact.nu)
        for j in rng.choice(len(pts), size=min(count, len(pts)), replace=False):
            lab, i = pts[j]
            k2, w0 = mpmath.mpf(exact.kappa[i]) ** 2, mpmath.mpf(exact.omega[lab][i])

            def f(W, lab=lab, k2=k2):
                F = frequency_function(lab[0], k2, W**2, nu, lambda z: mpmath.cos(mpmath.sqrt(z)),
                                       lambda z: mpmath.sinc(mpmath.sqrt(z)))
                return mpmath.re(F) / W**2

            eps = mpmath.mpf("1e-9")
            root = mpmath.findroot(f, (w0 * (1 - eps), w0 * (1 + eps)), solver="anderson",
                                   verify=False)
            worst = max(worst, float(abs(root - w0) / root))
    return worst


@dataclass(frozen=True)
class TracerAccuracy:
    """Speed and accuracy of :func:`trace_branches` over its (step, rtol) settings.

    ``rows``: dicts ``step, rtol, time_s, error, failures``; ``error`` is the largest relative
    deviation from the reference setting ``reference`` (step, rtol), whose own error against
    40-digit mpmath roots is ``reference_mpmath_error`` (measured, on ``mpmath_points`` roots).
    """

    kappa_count: int
    omega_max: float
    reference: tuple[float, float]
    reference_mpmath_error: float
    mpmath_points: int
    rows: tuple


def _max_rel(a: dict, b: dict) -> float:
    worst = 0.0
    for lab, w in b.items():
        v = a.get(lab)
        if v is None:
            return float("inf")  # a branch went missing
        ok = np.isfinite(w) & (w > 0)
        if not np.all(np.isfinite(v[ok])):
            return float("inf")
        worst = max(worst, float(np.max(np.abs(v[ok] - w[ok]) / w[ok], initial=0)))
    return worst


def tracer_accuracy(nu: float, kappa, omega_max: float = 6.0, settings=None, repeat: int = 3,
                    mpmath_points: int = 40) -> TracerAccuracy:
    """Time and error of :func:`trace_branches` per (step, rtol); see :class:`TracerAccuracy`."""
    import time

    settings = settings or [(s, t) for s in (0.05, 0.2) for t in (1e-4, 1e-6, 1e-9, 1e-12, 1e-15)]
    reference = (0.02, 1e-16)
    ref = trace_branches(nu, kappa, omega_max, step=reference[0], rtol=reference[1])
    ref_err = mpmath_error(ref, count=mpmath_points)
    rows = []
    for step, rtol in settings:
        best = np.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            br = trace_branches(nu, kappa, omega_max, step=step, rtol=rtol)
            best = min(best, time.perf_counter() - t0)
        rows.append({"step": step, "rtol": rtol, "time_s": best,
                     "error": _max_rel(br.omega, ref.omega), "failures": len(br.failures)})
    return TracerAccuracy(int(np.size(kappa)), float(omega_max), reference, ref_err,
                          mpmath_points, tuple(rows))


def exact_fundamental(kind: str, kappa, nu: float) -> np.ndarray:
    """Exact S0 (``kind="S"``) or A0 (``"A"``) :math:`\\Omega` at ``kappa``, certified.

    The lowest root of the class, from :func:`trace_branches`; a root the tracer could not
    certify raises :class:`~dispersion.errors.ConvergenceError`.

    >>> round(float(exact_fundamental("S", [0.05], 0.3)[0]) ** 2 / 0.05**2, 3)  # eq 14
    2.857
    """
    from dispersion.errors import ConvergenceError

    if kind not in ("S", "A"):
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    nu = float(check_nu(nu))
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    # S0 and A0 lie below Omega = sqrt(2/(1-nu)) kappa < 2 kappa for nu < 1/2
    traced = trace_branches(nu, kappa, omega_max=2.0 * float(kappa.max()) + 0.1, kinds=(kind,))
    if traced.failures:
        raise ConvergenceError(f"exact {kind}0 branch not certified: {traced.failures[0]}")
    omega = traced.omega[f"{kind}0"]
    if not np.all(np.isfinite(omega)):
        raise ConvergenceError(f"exact {kind}0 branch missing at some kappa in {kappa}")
    return omega
