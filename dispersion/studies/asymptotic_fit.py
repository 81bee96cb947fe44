"""Fitted orders inside their asymptotic range, the kappa window chosen by the series.

A fitted order of the relative error :math:`e(\\kappa) = \\Omega_h / \\Omega - 1` is the
leading power of kappa only where the leading term of the error dominates. The toolkit knows
the error's series: with :math:`\\Omega_h^2 = \\sum_j d_j \\kappa^j`
(:func:`dispersion.symbolic.power_balance.discrete_series`) and
:math:`\\Omega^2 = \\sum_j e_j \\kappa^j` (:func:`dispersion.continuum.exact_series.exact_series`),

.. math::

    e(\\kappa) = \\sqrt{\\frac{\\sum_j d_j \\kappa^j}{\\sum_j e_j \\kappa^j}} - 1
               = c_m \\kappa^m + c_{m+2} \\kappa^{m+2} + \\dots

(:func:`relative_error_series`, exact rational arithmetic at a rational nu). The rule, stated
before any fit is looked at (:func:`asymptotic_window`):

- upper end: the largest kappa where :math:`|c_m| \\kappa^m` is at least
  :data:`LEAD_OVER_REST` = 10 times :math:`\\sum_{j > m} |c_j| \\kappa^j` over the known terms
  (so at least 10 times the next term), and at most the Bloch zone edge :math:`\\pi / r`;
- lower end: where the leading term equals :data:`ERROR_FLOOR` = 1e-7, a thousand times the
  relative accuracy that the discrete branches guarantee (1e-10), so that round-off moves a
  fitted slope by less than about 1e-3;
- a window narrower than a factor :data:`MIN_SPAN` = 2 is empty: no order is fitted;
- :data:`POINTS` = 5 geometrically spaced kappas; least squares on log-log; a fit whose
  largest log residual exceeds :data:`RESIDUAL_MAX` = 0.05 reports no order.

>>> from fractions import Fraction
>>> s = {2: Fraction(43, 10000), 4: Fraction(-117, 1000), 6: Fraction(42, 100)}
>>> lo, hi = asymptotic_window(s)
>>> round(lo, 4), round(hi, 4)
(0.0048, 0.0602)
"""
from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

__all__ = ["ERROR_FLOOR", "LEAD_OVER_REST", "MIN_SPAN", "POINTS", "RESIDUAL_MAX",
           "SERIES_ORDER", "asymptotic_window", "fit_in_window", "relative_error_series"]

LEAD_OVER_REST = 10.0
ERROR_FLOOR = 1e-7
MIN_SPAN = 2.0
POINTS = 5
RESIDUAL_MAX = 0.05
#: Upper end of the search for the window when no ``kappa_max`` bounds it.
_KAPPA_BIG = 1e6
#: Highest power of kappa of the Omega^2 series behind the error series.
SERIES_ORDER = 12


def _fraction(x) -> Fraction:
    from dispersion.reader import rational

    q = rational("series coefficient", x)
    return Fraction(int(q.p), int(q.q))


def relative_error_series(branch: str, nu, patch=None, order: int = SERIES_ORDER,
                          **patch_fields) -> dict[int, Fraction]:
    """Series of :math:`\\Omega_h / \\Omega - 1` of ``branch`` ("S0" or "A0") at a rational ``nu``.

    ``patch`` (a :class:`dispersion.symbolic.patch.Patch`) and ``patch_fields`` as in
    :func:`dispersion.symbolic.power_balance.discrete_series`. Exact:
    :math:`R = \\Omega_h^2 / \\Omega^2` by series division, then :math:`\\sqrt R` by the
    recursion :math:`s_0 = 1`, :math:`2 s_k = R_k - \\sum_{0<i<k} s_i s_{k-i}`. Powers up to
    ``order`` minus the leading power of :math:`\\Omega^2`; zero terms are left out.

    >>> s = relative_error_series("A0", Fraction(3, 10), order=8, model="bloch", r=2,
    ...                           mass="consistent")
    >>> min(s)
    2
    """
    import sympy

    from dispersion.symbolic.power_balance import discrete_series
    from dispersion.continuum.exact_series import exact_series

    from dispersion.reader import read_number

    nu = read_number(nu) if isinstance(nu, str) else Fraction(nu)  # text by the whitelist
    nu_q = sympy.Rational(nu.numerator, nu.denominator)
    d = {k: _fraction(v) for k, v in discrete_series(branch, order, patch, nu=nu_q,
                                                     **patch_fields).items()}
    e = {k: _fraction(v) for k, v in exact_series(branch, order, nu=nu_q).items()}
    lead = min(k for k, v in e.items() if v != 0)
    if d.get(lead, 0) != e[lead]:
        raise ValueError(f"{branch}: the discrete and exact leading coefficients differ")
    n = order - lead  # R known to kappa^n
    D = [d.get(lead + j, Fraction(0)) for j in range(n + 1)]
    E = [e.get(lead + j, Fraction(0)) for j in range(n + 1)]
    R = []
    for k in range(n + 1):
        R.append((D[k] - sum((R[i] * E[k - i] for i in range(k)), Fraction(0))) / E[0])
    s = [Fraction(1)] + [Fraction(0)] * n
    for k in range(1, n + 1):
        s[k] = (R[k] - sum((s[i] * s[k - i] for i in range(1, k)), Fraction(0))) / 2
    return {k: s[k] for k in range(1, n + 1) if s[k] != 0}


def asymptotic_window(series: dict, kappa_max: float = math.inf) -> tuple[float, float] | None:
    """``(lo, hi)`` of the module's rule for the error series ``{power: coefficient}``;
    None if it is empty (narrower than a factor :data:`MIN_SPAN`) or the series is zero."""
    terms = sorted((k, abs(float(c))) for k, c in series.items() if c != 0)
    if not terms:
        return None
    m, cm = terms[0]
    rest = terms[1:]

    def too_big(k: float) -> bool:
        return LEAD_OVER_REST * sum(c * k ** (j - m) for j, c in rest) > cm

    hi = kappa_max
    if rest and math.isinf(hi) and not too_big(_KAPPA_BIG):
        return None  # no bound from the known terms and none given: no window is claimed
    if rest and (math.isinf(hi) or too_big(hi)):
        a, b = 1e-12, (_KAPPA_BIG if math.isinf(hi) else hi)  # bisection on log kappa
        for _ in range(200):
            mid = math.sqrt(a * b)
            a, b = (a, mid) if too_big(mid) else (mid, b)
        hi = a
    lo = (ERROR_FLOOR / cm) ** (1.0 / m)
    if math.isinf(hi) or hi < MIN_SPAN * lo:
        return None
    return lo, hi


def fit_in_window(series: dict, measure, kappa_max: float = math.inf) -> dict:
    """Fit the order of ``measure(kappa) -> relative errors`` inside the series' window.

    Returns the window, the points, the measured errors, the fitted slope and its largest
    log residual, the series' leading power and the slope the truncated series itself gives
    on the same points, and ``verdict``: "fitted", or why no order is given.
    """
    lead = min((k for k, c in series.items() if c != 0), default=None)
    row = {"series_order": lead, "series_leading_coefficient":
           float(series[lead]) if lead is not None else None,
           "window": None, "kappa": [], "error": [], "fitted": None, "max_log_residual": None,
           "series_slope": None, "verdict": ""}
    window = asymptotic_window(series, kappa_max)
    if window is None:
        row["verdict"] = ("no window: the leading error term never dominates the rest by "
                          f"{LEAD_OVER_REST:g}x above an error of {ERROR_FLOOR:g}")
        return row
    kappa = np.geomspace(window[0], window[1], POINTS)
    err = np.abs(np.asarray(measure(kappa), dtype=float))
    truncated = np.abs(sum(float(c) * kappa**k for k, c in series.items()))
    row.update(window=[float(window[0]), float(window[1])], kappa=kappa.tolist(),
               error=err.tolist(),
               series_slope=float(np.polyfit(np.log(kappa), np.log(truncated), 1)[0]))
    if not np.all(np.isfinite(err) & (err > 0)):
        row["verdict"] = "no fit: a measured error is zero or not finite"
        return row
    c = np.polyfit(np.log(kappa), np.log(err), 1)
    resid = float(np.max(np.abs(np.polyval(c, np.log(kappa)) - np.log(err))))
    row.update(fitted=float(c[0]), max_log_residual=resid)
    row["verdict"] = ("fitted" if resid <= RESIDUAL_MAX else
                      f"no order: largest log residual {resid:.2g} > {RESIDUAL_MAX:g}")
    return row
