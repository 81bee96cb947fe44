"""Phase and group velocity of the exact and the discrete branches, and zero-group-velocity points.

Dimensionless, in units of the shear speed :math:`c_T`: the phase velocity is
:math:`c_p / c_T = \\Omega / \\kappa` and the group velocity :math:`c_g / c_T = d\\Omega/d\\kappa`.

- Exact branches: implicit differentiation of the scaled Rayleigh-Lamb function,
  :math:`d\\Omega/d\\kappa = -R_\\kappa / R_\\Omega` by the complex step
  (:func:`dispersion.continuum.scaled_frequency.scaled_slope`); S0 and A0 below
  :func:`dispersion.continuum.exact_branches.series_switch` (where the series' own error estimate
  of the slope reaches 1e-14) from the derivative of their series. Each slope carries an error
  estimate: its sensitivity to the rounding of :math:`\\Omega` (large where a root sits
  within round-off-sized distances of a Mindlin bound, e.g. a branch leaving its cut-off, or
  the pair at coincident cut-offs) plus :math:`64\\epsilon |c_g|`. Where that estimate exceeds
  the tolerance (:data:`VELOCITY_RTOL` relative, :data:`VELOCITY_ATOL` absolute) the root and
  slope are recomputed in extended precision (:func:`slope_extended`, mpmath at
  :data:`EXTENDED_DPS` digits, the root bracketed between its two Mindlin bounds); whatever
  still cannot be certified is listed in :attr:`Velocities.uncertain` with the reason.
- Discrete branches: from the eigenvector :math:`\\phi` of
  :math:`(K - \\Omega^2 M)\\phi = 0` (Hellmann-Feynman),

  .. math::

      \\frac{d\\Omega}{d\\kappa} = \\frac{\\phi^T (K' - \\Omega^2 M') \\phi}{2 \\Omega\\, \\phi^T M \\phi},

  with :math:`K', M'` by complex-step differentiation of the same x-functions that build K
  and M (:func:`dispersion.discretization.discrete_branches.pencil_derivative`). On the characteristic-
  polynomial path (:mod:`dispersion.discretization.pencil_polynomial`, every small pencil) the same
  slope comes from implicit differentiation of the exact polynomial,
  :math:`d\\mu/du = -P_u / P_\\mu`, with an error bound: certified to 1e-12 relative, or the
  kappa is listed in ``DiscreteBranches.failures`` (near a zero group velocity or a double
  root, where only an absolute bound holds). Where the float eigenvalue is not accurate and
  the polynomial path is not available, the eigenvector formula runs in ball arithmetic.

>>> import numpy as np
>>> from dispersion.continuum.exact_branches import trace_branches
>>> v = exact_velocities(trace_branches(0.3, [1e-4, 1.0], 2.0))
>>> round(float(v.group["S0"][0]), 6), round(float(np.sqrt(2 / 0.7)), 6)   # plate speed
(1.690309, 1.690309)

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, 2004, ch. 8 (group velocity);
C. Prada, D. Clorennec, D. Royer, J. Acoust. Soc. Am. 124 (2008) 203 (ZGV Lamb modes).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.errors import InputError
from dispersion.rendering import Rendered
from dispersion.continuum.exact_branches import (ExactBranches, fundamental_series, series_region,
                                             trace_branches)
from dispersion.continuum.deflated_frequency import deflated_frequency_function
from dispersion.continuum.illinois import scalar_root
from dispersion.continuum.numeric_frequency import frequency_slope
from dispersion.continuum.scaled_frequency import bound_table, removable_bound, scaled_slope

__all__ = ["EXTENDED_DPS", "VELOCITY_ATOL", "VELOCITY_RTOL", "Velocities", "ZGVPoint",
           "exact_velocities", "phase_velocity", "slope_extended", "zgv_points"]

#: Tolerance of an exact group velocity: relative, or absolute (c_g / c_T) where c_g is near
#: zero (cut-offs, zero-group-velocity points), whichever is larger.
VELOCITY_RTOL = 1e-12
VELOCITY_ATOL = 1e-14
#: Digits of the extended-precision recomputation: 40, plus 4 per decade of kappa below 1 (the
#: trivial root of F costs about kappa^-4 of relative accuracy near A0).
EXTENDED_DPS = 40


@dataclass(frozen=True, repr=False)  # Rendered: a short repr, no whole arrays
class Velocities(Rendered):
    """Phase and group velocity over :math:`c_T` per branch label, on the branches' kappa grid.

    ``uncertain``: ``(label, kappa, reason)`` where the group velocity could not be certified to
    :data:`VELOCITY_RTOL` (or :data:`VELOCITY_ATOL` absolute); empty for discrete branches.
    They are the result's ``failures`` in every rendered format.
    """

    kappa: np.ndarray
    phase: dict[str, np.ndarray]
    group: dict[str, np.ndarray]
    uncertain: tuple = ()

    @property
    def failures(self) -> tuple:
        return tuple(self.uncertain)

    def title(self) -> str:
        k = np.asarray(self.kappa, dtype=float)
        span = f" in [{k.min():g}, {k.max():g}]" if k.size else ""
        return (f"phase and group velocities of {len(self.phase)} branches on {k.size} "
                f"kappa{span}")

    def header_lines(self) -> list[str]:
        return ["c_p/c_T = Omega/kappa, c_g/c_T = dOmega/dkappa (over the shear wave speed); "
                "kappa = k h"]

    def columns(self) -> tuple[str, ...]:
        return ("kappa", "branch", "c_p/c_T", "c_g/c_T")

    def rows(self) -> list[dict]:
        k = np.asarray(self.kappa, dtype=float)
        out = []
        for label, cp in self.phase.items():
            cp = np.asarray(cp, dtype=float)
            cg = np.asarray(self.group.get(label, np.full(k.shape, np.nan)), dtype=float)
            for i in np.flatnonzero(np.isfinite(cp) | np.isfinite(cg)):
                out.append({"kappa": float(k[i]), "branch": label, "c_p/c_T": float(cp[i]),
                            "c_g/c_T": float(cg[i])})
        return out


@dataclass(frozen=True)
class ZGVPoint:
    """A zero-group-velocity point of an exact branch: :math:`d\\Omega/d\\kappa = 0`, kappa > 0."""

    label: str
    kappa: float
    omega: float


def phase_velocity(kappa, omega) -> np.ndarray:
    """:math:`\\Omega / \\kappa` (NaN at :math:`\\kappa = 0`, where a cut-off has infinite c_p).

    >>> phase_velocity([0.0, 2.0], [1.0, 3.0]).tolist()
    [nan, 1.5]
    """
    kappa, omega = np.asarray(kappa, dtype=float), np.asarray(omega, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(kappa > 0, omega / np.where(kappa > 0, kappa, 1.0), np.nan)


def _mp_scaled(kind: str, kappa, W, nu, mp):
    """The scaled function of :func:`dispersion.continuum.scaled_frequency.scaled_frequency_function`
    in its quotient form, in mpmath arithmetic (cot, tan of complex square roots)."""
    s = (1 - 2 * nu) / (2 * (1 - nu))
    k2, W2 = kappa**2, W**2
    P, Q = s * W2 - k2, W2 - k2
    a = Q - k2
    p, q = mp.sqrt(mp.mpc(P)), mp.sqrt(mp.mpc(Q))
    if kind == "S":
        zP = p * mp.cot(p) if P != 0 else mp.mpf(1)
        return mp.re((a * a * zP / P + 4 * k2 * q * mp.cot(q)) / W2)
    return mp.re(-(a * a * mp.tan(p) / p + 4 * k2 * q * mp.tan(q)) / W2)


def slope_extended(kind: str, kappa: float, omega: float, nu: float, label_index: int):
    """Root and group velocity of branch ``kind + label_index`` at ``kappa`` in mpmath.

    The root is bracketed between its two Mindlin bounds (computed in the same precision:
    the j-th interval of :func:`dispersion.continuum.scaled_frequency.mindlin_bounds`, 0 below the
    first) narrowed to :math:`\\Omega (1 \\pm 10^{-10})`, closed by the Anderson-Bjorck method,
    and the slope is :math:`-R_\\kappa/R_\\Omega` by mpmath's differentiation. Returns
    ``(Omega, c_g, reason)``, ``reason`` None when certified (the bracket holds one sign change).

    >>> w, cg, why = slope_extended("A", 1e-6, 1.5707963267959473, 0.25, 1)   # A1
    >>> why is None, round(cg / 1e-6, 9)
    (True, 2.101157213)
    """
    import mpmath as mp

    dps = EXTENDED_DPS + int(4 * max(0.0, -math.log10(kappa)))
    with mp.workdps(dps):
        k, n = mp.mpf(kappa), mp.mpf(nu)
        s = (1 - 2 * n) / (2 * (1 - n))
        off = 0 if kind == "S" else mp.mpf(1) / 2
        top = mp.mpf(omega) * 2 + 10
        bounds = []
        for scale, first in ((s, 1 if removable_bound(kind, nu) else 0),
                             (mp.mpf(1), 1 if kind == "S" else 0)):
            j = first
            while True:
                w = mp.sqrt((k * k + ((j + off) * mp.pi) ** 2) / scale)
                bounds.append(w)
                if w > top:
                    break
                j += 1
        bounds.sort()
        if removable_bound(kind, nu):
            s0 = k * mp.sqrt(2)
            if abs(s0 - omega) <= 1e-15 * s0:
                return float(s0), math.sqrt(2.0), None
            # the removable bound S0 shifts the labels of the roots above it by one
            label_index -= int(omega > s0)
        lo = mp.mpf(0) if label_index == 0 else bounds[label_index - 1]
        hi = bounds[label_index]
        a = max(lo, mp.mpf(omega) * (1 - mp.mpf("1e-10")))
        b = min(hi, mp.mpf(omega) * (1 + mp.mpf("1e-10")))

        def R(kk, W):
            return _mp_scaled(kind, kk, W, n, mp)

        try:
            ra, rb = R(k, a) if a > lo else mp.inf, R(k, b) if b < hi else -mp.inf
            if not (ra > 0 > rb):
                return float("nan"), float("nan"), "no sign change of the scaled function " \
                    "within 1e-10 of the root in extended precision"
            if a == lo or b == hi:  # a pole at the end: bisect it away first
                for _ in range(200):
                    m = (a + b) / 2
                    rm = R(k, m)
                    a, b = (m, b) if rm > 0 else (a, m)
                    if b - a < mp.mpf(10) ** (-dps + 5) * b:
                        break
                W = (a + b) / 2
            else:
                W = mp.findroot(lambda x: R(k, x), (a, b), solver="anderson")
            rk = mp.diff(lambda x: R(x, W), k)
            rw = mp.diff(lambda x: R(k, x), W)
        except (ValueError, ZeroDivisionError) as exc:
            return float("nan"), float("nan"), f"extended precision failed: {exc}"
        return float(W), float(-rk / rw), None


def _slope_error(kind, kappa, omega, nu, cg):
    """Error estimate of :func:`scaled_slope` at a float root (see the module docstring).

    The sensitivity to :math:`\\Omega` is a central difference over a step of 1e-9, or 1/100
    of the distance to the nearest Mindlin bound if that is less (the slope varies on that
    scale); a root within 1e-10 of a bound gets no float estimate (infinite error).
    """
    bounds = bound_table(kind, kappa, nu, 2 * float(omega.max()) + 10)
    dist = np.min(np.abs(bounds - omega[:, None]), axis=1) / omega
    delta = np.minimum(1e-9, 0.01 * dist) * omega
    up = scaled_slope(kind, kappa, omega + delta, nu)
    dn = scaled_slope(kind, kappa, omega - delta, nu)
    with np.errstate(invalid="ignore", divide="ignore"):
        sens = np.abs(up - dn) / (2 * delta)
        # the root's own error: 8 ulp, twice the worst the exact-root search of
        # docs/promises.md found (4 ulp); 2 ulp let a 2.1e-12 error pass as certified
        err = sens * 8 * np.spacing(omega) + 64 * np.finfo(float).eps * np.abs(cg)
    err[dist < 1e-10] = np.inf
    return np.where(np.isfinite(err), err, np.inf)


def exact_velocities(exact: ExactBranches) -> Velocities:
    """Phase and group velocity of every traced exact branch (see the module docstring)."""
    k, nu = exact.kappa, exact.nu
    phase, group, uncertain = {}, {}, []
    for label, w in exact.omega.items():
        kind, j = label[0], int(label[1:])
        phase[label] = phase_velocity(k, w)
        g = np.full(k.shape, np.nan)
        ok = np.isfinite(w) & (k > 0)
        series = np.zeros(k.shape, bool)
        if j == 0 and not removable_bound(kind, nu):
            series = ok & series_region(label, nu, k)
            if np.any(series):
                g[series] = fundamental_series(label, nu, k[series])[1]
            # kappa = 0: S0 moves at the plate speed sqrt(2/(1-nu)) (eq 14), A0 starts flat
            g[k == 0] = math.sqrt(2 / (1 - nu)) if kind == "S" else 0.0
        else:
            g[(k == 0) & np.isfinite(w)] = 0.0  # cut-offs: Omega is even in kappa
            if removable_bound(kind, nu):
                g[(k == 0) & (w == 0)] = math.sqrt(2.0)
        rest = np.flatnonzero(ok & ~series)
        if rest.size:
            cg = scaled_slope(kind, k[rest], w[rest], nu)
            err = _slope_error(kind, k[rest], w[rest], nu, cg)
            g[rest] = cg
            tol = np.maximum(VELOCITY_RTOL * np.abs(cg), VELOCITY_ATOL)
            for i in np.flatnonzero(~(err <= tol)):
                W, cg_x, why = slope_extended(kind, float(k[rest[i]]), float(w[rest[i]]), nu, j)
                if why is None:
                    g[rest[i]] = cg_x
                else:
                    uncertain.append((label, float(k[rest[i]]), f"{why} (float estimate "
                                      f"{cg[i]:.12g} +- {err[i]:.1e}; near-double root)"))
        group[label] = g
    return Velocities(k, phase, group, tuple(uncertain))


def zgv_points(nu: float, kappa_max: float, omega_max: float, count: int = 400) -> list[ZGVPoint]:
    """Zero-group-velocity points of the exact branches with :math:`0 < \\kappa \\le` kappa_max.

    The branches are traced (:func:`~dispersion.continuum.exact_branches.trace_branches`) on
    ``count`` evenly spaced kappa in [0, kappa_max] (0 left out); where the slope
    :func:`~dispersion.continuum.numeric_frequency.frequency_slope` changes sign along a branch
    the Illinois method (:func:`~dispersion.continuum.illinois.scalar_root`) finds the kappa of
    zero slope, the branch solved for Omega at each kappa on the deflated function
    (:func:`~dispersion.continuum.deflated_frequency.deflated_frequency_function`). ZGV points are
    where a backward wave (e.g. S1 for most nu) turns; S0 and A0 rise monotonically, and the
    points at :math:`\\kappa = 0` (cut-offs, slope zero by symmetry) are not listed. The one
    implementation behind :func:`dispersion.continuum.frequency.zgv_points_below` too.

    >>> [(p.label, round(p.kappa, 4), round(p.omega, 4)) for p in zgv_points(0.3, 2.0, 4.0)]
    [('S1', 0.8383, 2.7303)]
    """
    if count < 3:
        raise InputError(f"count must be an integer >= 3, got {count!r}")
    kappa = np.linspace(0.0, kappa_max, int(count))[1:]
    tr = trace_branches(nu, kappa, omega_max)
    h = kappa[1] - kappa[0]
    out = []
    for label, w in tr.omega.items():
        if label[1:] == "0":
            continue  # S0 and A0 rise monotonically
        kind = label[0]
        ok = np.isfinite(w)
        g = np.full(w.shape, np.nan)
        g[ok] = frequency_slope(kind, kappa[ok], w[ok], nu)
        change = np.flatnonzero(np.isfinite(g[1:]) & np.isfinite(g[:-1])
                                & (np.sign(g[1:]) != np.sign(g[:-1])))
        for i in change:
            width = 4 * h * (abs(g[i]) + abs(g[i + 1])) + 1e-3

            def branch(kk, i=i, kind=kind, w=w, width=width):
                t = (kk - kappa[i]) / h
                guess = (1 - t) * w[i] + t * w[i + 1]
                return scalar_root(lambda W: float(deflated_frequency_function(kind, kk, W, nu)),
                                   guess - width, guess + width, 1e-15)

            try:
                kz = scalar_root(lambda kk: float(frequency_slope(kind, kk, branch(kk), nu)),
                                 kappa[i], kappa[i + 1], 1e-14)
                out.append(ZGVPoint(label, float(kz), float(branch(kz))))
            except ValueError:  # no single bracketed root near the guess: not a ZGV point
                continue
    return sorted(out, key=lambda p: (p.omega, p.label))
