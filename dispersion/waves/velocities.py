"""Phase and group velocity of the exact and the discrete branches, and zero-group-velocity points.

Dimensionless, in units of the shear speed :math:`c_T`: the phase velocity is
:math:`c_p / c_T = \\Omega / \\kappa` and the group velocity :math:`c_g / c_T = d\\Omega/d\\kappa`.

- Exact branches: implicit differentiation of the Rayleigh-Lamb function,
  :math:`d\\Omega/d\\kappa = -F_\\kappa / F_\\Omega`
  (:func:`dispersion.waves.rayleigh_lamb.frequency_slope`); S0 and A0 below
  :data:`dispersion.waves.exact_branches.SERIES_KAPPA` from the derivative of their series.
- Discrete branches: from the eigenvector :math:`\\phi` of
  :math:`(K - \\Omega^2 M)\\phi = 0` (Hellmann-Feynman),

  .. math::

      \\frac{d\\Omega}{d\\kappa} = \\frac{\\phi^T (K' - \\Omega^2 M') \\phi}{2 \\Omega\\, \\phi^T M \\phi},

  with :math:`K', M'` by complex-step differentiation of the same x-functions that build K
  and M (:func:`dispersion.waves.discrete_branches.pencil_derivative`). On the characteristic-
  polynomial path (:mod:`dispersion.waves.pencil_polynomial`, every small pencil) the same
  slope comes from implicit differentiation of the exact polynomial,
  :math:`d\\mu/du = -P_u / P_\\mu`, with an error bound: certified to 1e-12 relative, or the
  kappa is listed in ``DiscreteBranches.failures`` (near a zero group velocity or a double
  root, where only an absolute bound holds). Where the float eigenvalue is not accurate and
  the polynomial path is not available, the eigenvector formula runs in ball arithmetic.

>>> import numpy as np
>>> from dispersion.waves.exact_branches import trace_branches
>>> v = exact_velocities(trace_branches(0.3, [1e-4, 1.0], 2.0))
>>> round(float(v.group["S0"][0]), 6), round(float(np.sqrt(2 / 0.7)), 6)   # plate speed
(1.690309, 1.690309)

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, 2004, ch. 8 (group velocity);
C. Prada, D. Clorennec, D. Royer, J. Acoust. Soc. Am. 124 (2008) 203 (ZGV Lamb modes).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dispersion.errors import InputError
from dispersion.waves.rayleigh_lamb import deflated_frequency_function, frequency_slope
from dispersion.waves.exact_branches import SERIES_KAPPA, ExactBranches, fundamental_series, trace_branches

__all__ = ["Velocities", "ZGVPoint", "exact_velocities", "phase_velocity", "zgv_points"]


@dataclass(frozen=True)
class Velocities:
    """Phase and group velocity over :math:`c_T` per branch label, on the branches' kappa grid."""

    kappa: np.ndarray
    phase: dict[str, np.ndarray]
    group: dict[str, np.ndarray]


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


def exact_velocities(exact: ExactBranches) -> Velocities:
    """Phase and group velocity of every traced exact branch (see the module docstring)."""
    k = exact.kappa
    phase, group = {}, {}
    for label, w in exact.omega.items():
        phase[label] = phase_velocity(k, w)
        g = np.full(k.shape, np.nan)
        ok = np.isfinite(w) & (k > 0)
        g[ok] = frequency_slope(label[0], k[ok], w[ok], exact.nu)
        if label in ("S0", "A0"):
            small = ok & (k <= SERIES_KAPPA)
            if np.any(small):
                g[small] = fundamental_series(label, exact.nu, k[small])[1]
            if label == "S0":
                g[k == 0] = fundamental_series(label, exact.nu, [0.0])[1][0]
            else:
                g[k == 0] = 0.0
        else:
            g[(k == 0) & np.isfinite(w)] = 0.0  # cut-offs: Omega is even in kappa
        group[label] = g
    return Velocities(k, phase, group)


def _branch_omega(kind: str, kappa: float, guess: float, nu: float, width: float) -> float:
    from scipy.optimize import brentq

    def g(w):
        return float(deflated_frequency_function(kind, kappa, w, nu))

    lo, hi = guess - width, guess + width
    if g(lo) * g(hi) > 0:
        raise InputError(f"no single root of the {kind} branch near Omega={guess:.6g} at "
                         f"kappa={kappa:.6g}")
    return brentq(g, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)


def zgv_points(nu: float, kappa_max: float, omega_max: float, count: int = 400) -> list[ZGVPoint]:
    """Zero-group-velocity points of the exact branches with :math:`0 < \\kappa \\le` kappa_max.

    Sign changes of :math:`d\\Omega/d\\kappa` along each traced branch are closed by Brent's
    method in kappa, the branch followed by a bracketed root solve at each kappa. ZGV
    points are where a backward wave (e.g. S1 for most nu) turns; the points at
    :math:`\\kappa = 0` (cut-offs, slope zero by symmetry) are not listed.

    >>> [(p.label, round(p.kappa, 4), round(p.omega, 4)) for p in zgv_points(0.3, 2.0, 4.0)]
    [('S1', 0.8383, 2.7303)]
    """
    from scipy.optimize import brentq

    kappa = np.linspace(0.0, kappa_max, count)[1:]
    exact = trace_branches(nu, kappa, omega_max)
    v = exact_velocities(exact)
    h = kappa[1] - kappa[0]
    out = []
    for label, g in v.group.items():
        w = exact.omega[label]
        change = np.flatnonzero(np.isfinite(g[1:]) & np.isfinite(g[:-1]) & (np.sign(g[1:]) != np.sign(g[:-1])))
        for i in change:
            width = 4 * h * (abs(g[i]) + abs(g[i + 1])) + 1e-3

            def slope(kk, i=i, label=label, width=width):
                t = (kk - kappa[i]) / h
                guess = (1 - t) * w[i] + t * w[i + 1]
                om = _branch_omega(label[0], kk, guess, nu, width)
                return float(frequency_slope(label[0], kk, om, nu))

            try:
                kz = brentq(slope, kappa[i], kappa[i + 1], xtol=1e-14)
                t = (kz - kappa[i]) / h
                om = _branch_omega(label[0], kz, (1 - t) * w[i] + t * w[i + 1], nu, width)
            except (InputError, ValueError):
                continue
            out.append(ZGVPoint(label, float(kz), float(om)))
    return sorted(out, key=lambda p: (p.omega, p.label))
