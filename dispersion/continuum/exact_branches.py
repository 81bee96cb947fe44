"""Root tracer of the exact Rayleigh-Lamb branches: every root, counted exactly.

For real :math:`\\kappa` each symmetry class is a self-adjoint eigenproblem in
:math:`\\Omega^2`: its branches never cross (they veer), so the j-th root in increasing
:math:`\\Omega` *is* branch :math:`S_j` (or :math:`A_j`) once no root is skipped and none is
counted twice. The count is exact, not scanned: the scaled function
:func:`dispersion.continuum.scaled_frequency.scaled_frequency_function` decreases strictly between
consecutive *Mindlin bounds* (:func:`dispersion.continuum.scaled_frequency.mindlin_bounds`, the
closed-form frequencies of the plate with mixed faces) from :math:`+\\infty` to
:math:`-\\infty`, so for :math:`\\kappa > 0` exactly one root lies in each interval between
bounds (in the first, between 0 and the first bound). The tracer solves one bracketed,
monotone problem per interval (Illinois on :math:`\\arctan R`, which is bounded and smooth
across the poles) and then *certifies* each root: at :math:`\\Omega (1 \\pm 5\\cdot10^{-13})`
(or at the bounding pole itself, whose sign is known) the function must have the expected sign
above its rounding bound (:func:`dispersion.continuum.scaled_frequency.scaled_with_noise`). A root that
cannot be certified to ``CERTIFY_RTOL`` is still returned (the best float answer) and its kappa
is listed in ``failures`` with the reason; nothing is dropped silently. Near-double roots
(veering pairs, coincident cut-offs) are separated by a bound between them, so they are
resolved to round-off rather than guessed.

At :math:`\\kappa = 0` the closed-form cut-offs are used (:func:`cutoff_frequencies`); for
:math:`0 < \\kappa \\le` ``TINY_KAPPA`` the non-fundamental roots are their cut-offs (they
move by :math:`O(\\kappa) < 10^{-28}` relative); S0 and A0 come from their power series
(:func:`dispersion.continuum.exact_series.exact_series`) below the kappa where the series' own error
estimate (its first omitted term, doubled) falls below ``SERIES_RTOL`` (:func:`series_switch`),
where the root of the function would lose digits and :math:`\\Omega^2` of A0 underflows below
:math:`\\kappa \\approx 10^{-77}`.

>>> import math
>>> br = trace_branches(0.3, [0.0, 1.0], 3.5)
>>> sorted(br.omega)
['A0', 'A1', 'S0', 'S1', 'S2']
>>> bool(br.omega["S2"][0] == math.pi), round(float(br.omega["A0"][1]), 12)
(True, 0.650345159155)

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, Cambridge University Press 2004, ch. 8;
R. D. Mindlin, Waves and vibrations in isotropic, elastic plates, in *Structural Mechanics*
(J. N. Goodier, N. J. Hoff eds.), Pergamon 1960, pp. 199-232;
F. A. Amirkulova, PhD thesis, Rutgers 2011 (ref [1] of the paper).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from dispersion.branch_views import BranchViews
from dispersion.errors import (
    InputError,
    check_nu,
    check_positive,
    check_positive_int,
    check_real_in_range,
    check_wavenumbers,
)
from dispersion.continuum.illinois import illinois
from dispersion.continuum.rayleigh_lamb import OMEGA_MAX, cutoff_frequencies
from dispersion.continuum.scaled_frequency import bound_table, removable_bound, scaled_with_noise

__all__ = [
    "CERTIFY_RTOL", "KAPPA_MAX", "MAX_SAMPLES", "SERIES_RTOL", "TINY_KAPPA", "check_samples",
    "ExactBranches", "TracerAccuracy", "exact_fundamental",
    "fundamental_series", "mpmath_error", "series_region", "series_switch",
    "trace_branches", "tracer_accuracy",
]

#: Relative width to which every returned root is certified (else it is a listed failure).
CERTIFY_RTOL = 1e-12
#: Relative error the S0/A0 series must reach (its own estimate) where it replaces the solve.
SERIES_RTOL = 1e-14
#: Largest kappa where a series replaces the solve: far below the first place where S0 or A0
#: meets another branch (kappa ~ 1), so within the series' radius of convergence.
SERIES_KAPPA_MAX = 0.2
#: The series of Omega^2 is computed through kappa^14; the kappa^14 term is its error estimate.
_SERIES_ORDER = 14
#: Below this kappa (> 0) the non-fundamental roots are their cut-offs: a branch leaves its
#: cut-off like kappa^2, or like kappa where two cut-offs coincide, so by < 1e-28 relative.
TINY_KAPPA = 1e-30
#: Largest kappa of the tracer: the range its tests cover (counts against collocation up to
#: 200, property tests up to 300). The scaled function has no overflow at any kappa.
KAPPA_MAX = 300.0

#: Largest work of one call, in budget units: kappa points times omega_max / step + 1 (the
#: number of roots per kappa grows like omega_max). Rule: about a minute of work. Measured on
#: this 2-core machine while it was shared and loaded: 2.5 us and 12 B of peak memory per unit
#: for both symmetry classes at 2000 kappa x Omega <= 200, 12 us and 15 B for one kappa x
#: Omega <= 1e5 (5e4 roots per class), so 2e7 units take 1 to 4 minutes at most, and < 1 GB.
MAX_SAMPLES = 20_000_000


def check_samples(kappa_count: int, omega_max: float, step: float = 0.05,
                  what: str = "len(kappa) * (omega_max / step + 1)") -> float:
    """Refuse, up front, a trace of more than :data:`MAX_SAMPLES` budget units.

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


@dataclass(repr=False)  # BranchViews: a short repr, no whole arrays
class ExactBranches(BranchViews):
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
        from dispersion.continuum.branch_set import BranchSet

        if not isinstance(self.omega, BranchSet) or self.omega.nu != self.nu:
            self.omega = BranchSet(self.omega, nu=self.nu)

    def symmetry(self, label: str) -> str:
        """``"S"`` or ``"A"``."""
        return label[0]


@functools.lru_cache(maxsize=4)
def _raw_series(label: str):
    from dispersion.continuum.exact_series import exact_series_raw

    return exact_series_raw(label, _SERIES_ORDER)


@functools.lru_cache(maxsize=32)
def _series_coefficients(label: str, nu: float) -> tuple[tuple[int, float], ...]:
    # the coefficients (polynomials in nu over QQ, derived once) evaluated exactly at the
    # float nu (a dyadic rational), then rounded once: no symbolic substitution or factoring,
    # whose cost grows with the digits of nu
    import flint
    from fractions import Fraction

    q = Fraction(float(nu))
    x = flint.fmpq(q.numerator, q.denominator)
    out = []
    for k, num, den in _raw_series(label):
        v = num(0, x) / den(0, x)
        out.append((k, float(Fraction(int(v.p), int(v.q)))))
    return tuple(sorted(out))


def series_switch(label: str, nu: float, rtol: float = SERIES_RTOL) -> float:
    """Largest kappa where the S0/A0 series of :func:`fundamental_series` is trusted to ``rtol``.

    The series of :math:`\\Omega^2` is summed through :math:`\\kappa^{12}`; its error estimate is
    twice the first omitted term :math:`c_{14}\\kappa^{14}` relative to the leading term
    :math:`c_l \\kappa^l`, and that of the slope is 14/l times more. The switch is where the
    slope's estimate equals ``rtol`` (the value's is then smaller), at most
    ``SERIES_KAPPA_MAX``: beyond the series' radius its terms say nothing (near nu = 0 they
    stay tiny while S0 veers sharply away from the line the series follows).

    >>> round(series_switch("A0", 0.3), 4), round(series_switch("S0", 0.3), 3)
    (0.0245, 0.111)
    """
    if label not in ("S0", "A0"):
        raise InputError(f"label must be 'S0' or 'A0', got {label!r}")
    coef = _series_coefficients(label, float(check_nu(nu)))
    (lead, c_lead), (last, c_last) = coef[0], coef[-1]
    if c_last == 0:   # S0 at nu = 0: Omega^2 = 2 kappa^2 exactly, the series terminates
        return SERIES_KAPPA_MAX
    switch = (rtol * abs(c_lead) * lead / (2 * abs(c_last) * last)) ** (1 / (last - lead))
    return min(switch, SERIES_KAPPA_MAX)


def series_region(label: str, nu: float, kappa) -> np.ndarray:
    """``kappa <= series_switch(label, nu)``, without building the series (and importing the
    symbolic engine) when no kappa is below ``SERIES_KAPPA_MAX``.

    >>> series_region("A0", 0.3, [1e-3, 0.5]).tolist()
    [True, False]
    """
    kappa = np.asarray(kappa, dtype=float)
    if not np.any(kappa <= SERIES_KAPPA_MAX):
        return np.zeros(kappa.shape, bool)
    return kappa <= series_switch(label, nu)


def _series_error(label: str, nu: float, kappa) -> np.ndarray:
    """The estimate of :func:`series_switch`: relative error of the series' Omega^2."""
    coef = _series_coefficients(label, float(nu))
    (lead, c_lead), (last, c_last) = coef[0], coef[-1]
    return 2 * abs(c_last / c_lead) * np.asarray(kappa, dtype=float) ** (last - lead)


def fundamental_series(label: str, nu: float, kappa) -> tuple[np.ndarray, np.ndarray]:
    """:math:`\\Omega` and :math:`d\\Omega/d\\kappa` of S0 or A0 from the series of
    :math:`\\Omega^2` (eqs 14 and 16, derived by :mod:`dispersion.symbolic.power_balance`).

    Summed through :math:`\\kappa^{12}`; valid below :func:`series_switch` only.
    :math:`\\Omega` is formed as :math:`\\kappa^l \\sqrt{\\sum c_k \\kappa^{k-2l}}` so it never
    underflows before :math:`\\kappa` does.

    >>> import math
    >>> w, cg = fundamental_series("S0", 0.3, [1e-200])
    >>> float(w[0] / 1e-200) == math.sqrt(2 / 0.7), float(cg[0]) == math.sqrt(2 / 0.7)
    (True, True)
    """
    if label not in ("S0", "A0"):
        raise InputError(f"label must be 'S0' or 'A0', got {label!r}")
    kappa = np.asarray(kappa, dtype=float)
    coef = _series_coefficients(label, float(nu))[:-1]  # the last term is the error estimate
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
    if kappa.max() > KAPPA_MAX:
        raise InputError(f"kappa must be <= {KAPPA_MAX:g} (the range the tracer is tested on), "
                         f"got {kappa.max()}")
    return kappa


def _scaled(kind, kappa, omega, nu):
    return scaled_with_noise(kind, kappa, omega, nu)


def _certify(kind, kk, roots, lo, hi, nu):
    """True where the root is bracketed to CERTIFY_RTOL by signs above round-off.

    Each side needs one point within CERTIFY_RTOL / 2 of the root whose sign is the expected
    one above the rounding bound: the bound (or 0) itself if that near, else the function at
    5e-13 or, should that point sit next to a pole where round-off swamps the value, at 5e-14.
    """
    ok_l, ok_h = roots - lo <= 0.5 * CERTIFY_RTOL * roots, hi - roots <= 0.5 * CERTIFY_RTOL * roots
    for frac in (0.5 * CERTIFY_RTOL, 0.05 * CERTIFY_RTOL):
        i = np.flatnonzero(~ok_l)
        if i.size:
            r, e = _scaled(kind, kk[i], roots[i] * (1 - frac), nu)
            ok_l[i] = r > e
        i = np.flatnonzero(~ok_h)
        if i.size:
            r, e = _scaled(kind, kk[i], roots[i] * (1 + frac), nu)
            ok_h[i] = r < -e
    return ok_l & ok_h


def _trace_class(kind, kappa, nu, omega_max, rtol, max_iter):
    """Roots of one symmetry class at kappa > TINY_KAPPA: (m, n) array (NaN padded), failures."""
    m = kappa.size
    # nu = 0: S0 is the removable bound P = 0, with one root (S1) between 0 and the next bound
    removable = removable_bound(kind, nu)
    poles = bound_table(kind, kappa, nu, omega_max, first_p=1 if removable else 0)
    s0 = kappa * math.sqrt(2.0)
    count = np.sum(poles < omega_max, axis=1)         # intervals 0..count hold roots <= top
    n_int = int(count.max()) + 1
    lo = np.concatenate([np.zeros((m, 1)), poles[:, :n_int - 1]], axis=1)
    hi = poles[:, :n_int]
    use = np.arange(n_int)[None, :] <= count[:, None]
    label = f"{kind}0"
    series = (np.arange(n_int)[None, :] == 0) & series_region(label, nu, kappa)[:, None]
    series &= not removable
    roots = np.full((m, n_int), np.nan)
    failures = []
    if np.any(series[:, 0]):
        si = np.flatnonzero(series[:, 0])
        w0 = fundamental_series(label, nu, kappa[si])[0]
        # the series root is certified like any other; where it is not, it is solved for
        good = (w0 > 0) & (w0 < hi[si, 0])
        good[good] = _certify(kind, kappa[si[good]], w0[good], lo[si[good], 0], hi[si[good], 0], nu)
        roots[si[good], 0] = w0[good]
        series[si[~good], 0] = False
    ki, ji = np.nonzero(use & ~series)
    kk, a, b = kappa[ki], lo[ki, ji], hi[ki, ji]
    fa, fb = np.full(a.shape, np.pi / 2), np.full(a.shape, -np.pi / 2)
    # the fundamental branch: a tight first bracket from its series where that is close
    first = np.flatnonzero((ji == 0) & (kk <= SERIES_KAPPA_MAX)) if not removable else []
    if len(first):
        w0 = fundamental_series(label, nu, kk[first])[0]
        width = np.minimum(10 * _series_error(label, nu, kk[first]), 1e-3)
        ga, gb = w0 * (1 - width), w0 * (1 + width)
        ra = _scaled(kind, kk[first], ga, nu)[0]
        rb = _scaled(kind, kk[first], gb, nu)[0]
        good = (ra > 0) & (rb < 0) & (ga > a[first]) & (gb < b[first])
        sel = first[good]
        a[sel], b[sel] = ga[good], gb[good]
        fa[sel], fb[sel] = np.arctan(ra[good]), np.arctan(rb[good])

    def g(idx, x):
        return np.arctan(_scaled(kind, kk[idx], x, nu)[0])

    w, _, _, open_ = illinois(g, a, b, fa, fb, rtol, max_iter)
    ok = _certify(kind, kk, w, lo[ki, ji], hi[ki, ji], nu)
    roots[ki, ji] = w
    for r in np.flatnonzero(open_ | ~ok):
        why = (f"root solver still open after max_depth={max_iter} iterations" if open_[r] else
               f"not certified to {CERTIFY_RTOL:g}: the function is within its rounding bound "
               f"at Omega*(1 +- {CERTIFY_RTOL / 2:g}) (near-double root)")
        failures.append((kind, float(kk[r]), f"{kind}{ji[r]} near Omega={w[r]:.10g} {why}"))
    if removable:
        roots = np.sort(np.concatenate([s0[:, None], roots], axis=1), axis=1)
    roots[roots > omega_max] = np.nan
    return roots, failures


def trace_branches(
    nu: float,
    kappa,
    omega_max: float,
    *,
    kinds: tuple[str, ...] = ("S", "A"),
    step: float = 0.05,
    rtol: float = 1e-15,
    max_depth: int = 100,
    chunk: int = 2000,
    progress=None,
) -> ExactBranches:
    """Every exact Rayleigh-Lamb branch with :math:`\\Omega \\le \\Omega_{max}` on a kappa grid.

    One root per interval between consecutive Mindlin bounds (see the module docstring): the
    count is exact, each root is closed by the Illinois method on :math:`\\arctan R` to
    relative width ``rtol`` and then certified to ``CERTIFY_RTOL`` by two signs above
    round-off; a root that is not certified is returned all the same and its kappa listed in
    ``failures`` with the reason. At :math:`\\kappa = 0` the closed-form cut-offs
    (:func:`cutoff_frequencies`) are used, at :math:`0 < \\kappa \\le` ``TINY_KAPPA`` the
    cut-offs for all but S0 and A0, and S0, A0 come from :func:`fundamental_series` below
    :func:`series_switch`.

    Parameters
    ----------
    nu : float
        Poisson's ratio, in (-1, 0.5).
    kappa : array_like
        Dimensionless wavenumbers :math:`0 \\le \\kappa = kh \\le` ``KAPPA_MAX``.
    omega_max : float
        Largest :math:`\\Omega = \\omega h / c_T` of interest, in (0, :data:`OMEGA_MAX`], with
        ``len(kappa) * (omega_max / step + 1) <= MAX_SAMPLES`` (:func:`check_samples`).
    step : float
        Unit of the work budget of :func:`check_samples` only (the count needs no scan).
    rtol : float
        Relative width at which a root's bracket is closed.
    max_depth : int
        Most solver iterations per root (>= 1); a root still open after them is a failure.
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
    max_iter = check_positive_int("max_depth", max_depth)
    chunk = check_positive_int("chunk", chunk)
    for kind in kinds:
        if kind not in ("S", "A"):
            raise InputError(f"kinds must hold 'S' and/or 'A', got {kind!r}")
    check_samples(kappa.size, omega_max, step)
    omega = {}
    failures = []
    for kind in kinds:
        per_k = [None] * kappa.size
        cut = np.array([w for w, _ in cutoff_frequencies(kind, nu, omega_max)])
        tiny = np.flatnonzero(kappa <= TINY_KAPPA)
        if tiny.size:
            w0, _ = fundamental_series(f"{kind}0", nu, kappa[tiny])
            for i, w in zip(tiny, w0):
                per_k[i] = np.concatenate([[w], cut[1:]])
                if 0 < kappa[i] and w < np.finfo(float).tiny:
                    failures.append((kind, float(kappa[i]), f"{kind}0 underflows ({w:.3g})"))
            if progress is not None and np.any(kappa[tiny] > 0):
                progress(int(np.count_nonzero(kappa[tiny] > 0)))
        rest = np.flatnonzero(kappa > TINY_KAPPA)
        for lo in range(0, rest.size, chunk):
            idx = rest[lo:lo + chunk]
            roots, fails = _trace_class(kind, kappa[idx], nu, omega_max, rtol, max_iter)
            failures += fails
            for i, r in zip(idx, roots):
                per_k[i] = r[np.isfinite(r)]
            if progress is not None:
                progress(idx.size)
        n_br = max(len(r) for r in per_k)
        for j in range(n_br):
            omega[f"{kind}{j}"] = np.array(
                [r[j] if j < len(r) else np.nan for r in per_k], dtype=float)
    return ExactBranches(kappa, omega, nu, omega_max, list(dict.fromkeys(failures)))

def mpmath_error(exact: ExactBranches, count: int = 20, dps: int = 40, seed: int = 0) -> float:
    """Largest relative error of ``count`` random traced roots (kappa > 0) against roots of the
    defining equation (:func:`dispersion.continuum.rayleigh_lamb.mpmath_frequency_function`) found by mpmath
    in ``dps`` digits (:func:`mpmath.workdps`, the global precision is left alone).

    >>> mpmath_error(trace_branches(0.3, [0.5, 2.0], 4.0), count=3) < 1e-14
    True
    """
    import mpmath

    from dispersion.continuum.rayleigh_lamb import mpmath_frequency_function

    rng = np.random.default_rng(seed)
    pts = [(lab, i) for lab, w in exact.omega.items() for i in np.flatnonzero(np.isfinite(w))
           if exact.kappa[i] > 0]
    worst = 0.0
    with mpmath.workdps(dps):
        nu = mpmath.mpf(exact.nu)
        for j in rng.choice(len(pts), size=min(count, len(pts)), replace=False):
            lab, i = pts[j]
            k, w0 = mpmath.mpf(exact.kappa[i]), mpmath.mpf(exact.omega[lab][i])

            def f(W, lab=lab, k=k):
                return mpmath_frequency_function(lab[0], k, W, nu) / W**2

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

    # the step only sets the work budget of check_samples since the count needs no scan
    settings = settings or [(0.05, t) for t in (1e-4, 1e-6, 1e-9, 1e-12, 1e-15)]
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
