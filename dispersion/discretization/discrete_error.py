"""Discretisation error of the discrete branches against the exact ones, and its order.

:func:`relative_error` compares :func:`dispersion.discretization.discrete_branches.discrete_branches`
with the exact Rayleigh-Lamb branches label by label; :func:`fitted_order` fits the rate of
that error in kappa; :func:`predicted_error` gives the leading term from the series (core
issue), so a test can compare one quantity computed two ways.

References
----------
A. Tkachuk et al., section 2, eq (16) and Figure 2.
"""
from __future__ import annotations

import numpy as np
import sympy

from dispersion.errors import InputError

__all__ = ["fitted_order", "predicted_error", "relative_error"]


def relative_error(discrete, exact) -> dict[str, np.ndarray]:
    """:math:`|\\Omega^h - \\Omega| / \\Omega` per label present in both (S0 with S0, ...).

    ``discrete`` is a :class:`dispersion.discretization.discrete_branches.DiscreteBranches`,
    ``exact`` a :class:`dispersion.continuum.exact_branches.ExactBranches` on the same grid.
    Points with :math:`\\Omega = 0` give NaN.
    """
    if not np.array_equal(discrete.kappa, exact.kappa):
        raise InputError("discrete and exact branches must share the kappa grid")
    out = {}
    for label, w in discrete.omega.items():
        if label in exact.omega:
            ref = exact.omega[label]
            with np.errstate(divide="ignore", invalid="ignore"):
                out[label] = np.where(ref > 0, np.abs(w - ref) / ref, np.nan)
    return out


def fitted_order(kappa, error) -> float:
    """Least-squares slope q of :math:`\\log e = q \\log \\kappa + c` over finite positive points.

    >>> k = np.array([0.01, 0.02, 0.04]); round(fitted_order(k, 3 * k**4), 12)
    4.0
    """
    kappa, error = np.asarray(kappa, dtype=float), np.asarray(error, dtype=float)
    ok = (kappa > 0) & (error > 0) & np.isfinite(error)
    if ok.sum() < 2:
        raise InputError("need at least two points with kappa > 0 and a positive error")
    return float(np.polyfit(np.log(kappa[ok]), np.log(error[ok]), 1)[0])


def predicted_error(branch: str, nu: float, order: int = 10, **patch_kwargs) -> tuple[int, float]:
    """Leading term of the relative error of :math:`\\Omega` from the series of the core issue.

    With :math:`\\Omega_h^2 - \\Omega^2 = \\delta \\kappa^m + \\dots` (``discrete_series`` minus
    ``exact_series``) and :math:`\\Omega^2 = c \\kappa^l + \\dots`, the relative error of
    :math:`\\Omega` is :math:`\\tfrac{\\delta}{2c} \\kappa^{m-l}`. Returns ``(m - l, delta / 2c)``.
    """
    from dispersion.symbolic.power_balance import discrete_series, first_difference
    from dispersion.continuum.exact_series import exact_series

    nu = sympy.nsimplify(nu) if isinstance(nu, float) else nu  # exact comparison below
    d = discrete_series(branch, order, nu=nu, **patch_kwargs)
    e = exact_series(branch, order, nu=nu)
    lead = min(k for k, v in e.items() if v != 0)
    m = first_difference(d, e)
    if m is None:
        raise InputError(f"no error term up to kappa^{order}; raise order")
    return m - lead, float(d.get(m, 0) - e.get(m, 0)) / (2 * float(e[lead]))
