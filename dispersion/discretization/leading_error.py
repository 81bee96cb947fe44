"""The leading error term of a discrete dispersion relation against the exact one, exact.

* :func:`bar_leading_term`: the periodic bar, :math:`\\omega_h^2/\\omega^2 - 1 = c\\,\\theta^k +
  O(\\theta^{k+2})` (:math:`\\theta = kh`), by exact power series of the Bloch symbols
  d / m of the rule (:func:`dispersion.discretization.bar_dispersion.bar_stiffness_coefficients`,
  :func:`dispersion.mass_rules.mass_rule.x_mass_coefficients`);
* :func:`plate_leading_terms`: S0 and A0 of the square-element Bloch patch
  (n = max(p + 1, 3), r = 2/(n - p)): the lowest power of kappa at which the power-balance
  series differs from the exact Rayleigh-Lamb series, and the difference there (exact in nu).

>>> bar_leading_term("consistent", 1, 4)      # 6(1 - cos)/(2 + cos) = theta^2 (1 + theta^2/12 ...)
(2, '1/12')
"""
from __future__ import annotations

import math
from fractions import Fraction

__all__ = ["bar_leading_term", "bar_leading_exact", "plate_leading_terms", "plate_leading_exact", "square_patch"]


def _cos_series(coeffs, K: int) -> list[Fraction]:
    """Taylor coefficients in :math:`t = \\theta^2` of :math:`\\sum_L a_L \\cos L\\theta`."""
    return [Fraction((-1) ** k, math.factorial(2 * k))
            * sum((Fraction(int(_rational(v).p), int(_rational(v).q)) * L ** (2 * k)
                   for L, v in coeffs), Fraction(0)) for k in range(K + 1)]


def _rational(v):
    from dispersion.reader import rational

    return rational("mass coefficient", v)


def bar_leading_term(rule, p: int, order: int) -> tuple[int | None, str]:
    """:func:`bar_leading_exact` with the coefficient as text ('' where there is none)."""
    k, c = bar_leading_exact(rule, p, order)
    return k, "" if c is None else str(c)


def bar_leading_exact(rule, p: int, order: int) -> tuple:
    """Leading term ``(k, c)`` of :math:`\\omega_h^2/\\theta^2 - 1 = c\\,\\theta^k + ...` by
    exact power series in :math:`\\theta^2` (the symbol d / m with d from the stiffness, m
    from the mass rows); c is an exact rational, ``(None, None)`` if no term up to ``order``."""
    from dispersion.mass_rules.mass_rule import x_mass_coefficients
    from dispersion.discretization.bar_dispersion import bar_stiffness_coefficients

    from dispersion.mass_rules.mass_rule import get_rule

    K = order // 2 + 1
    if get_rule(rule).basis == "lagrange":  # the acoustic branch of the C0 bar
        from dispersion.splines.lagrange_sem import acoustic_series

        q = acoustic_series(get_rule(rule).name, p, K + 1)
        for k in range(1, K + 1):
            if q[k] != 0:
                return 2 * k, q[k]
        return None, None
    d = _cos_series(bar_stiffness_coefficients(rule, p).items(), K + 1)
    m = _cos_series(x_mass_coefficients(rule, p), K + 1)
    # d = d_1 t + d_2 t^2 + ... (d_0 = 0); q = (d / t) / m
    num = d[1:]
    q: list[Fraction] = []
    for k in range(K + 1):
        q.append((num[k] - sum((q[j] * m[k - j] for j in range(k)), Fraction(0))) / m[0])
    if q[0] != 1:
        return 0, q[0] - 1
    for k in range(1, K + 1):
        if q[k] != 0:
            return 2 * k, q[k]
    return None, None


def plate_leading_terms(rule, p: int, order: int) -> dict[str, tuple[int | None, str]]:
    """:func:`plate_leading_exact` with the coefficients as text."""
    return {k: (power, "" if c is None else str(c))
            for k, (power, c) in plate_leading_exact(rule, p, order).items()}


def plate_leading_exact(rule, p: int, order: int) -> dict[str, tuple]:
    """``{"plate S0": (k, c), "plate A0": (k, c)}``: the lowest power of kappa at which the
    power-balance series of the square-element patch differs from the exact series, and the
    difference there (a sympy expression in nu); ``(None, None)`` if none up to ``order``."""
    import sympy

    from dispersion.reader import as_sympy
    from dispersion.symbolic.power_balance import discrete_series
    from dispersion.continuum.exact_series import exact_series

    out = {}
    for branch in ("S0", "A0"):
        disc = discrete_series(branch, order, square_patch(rule, p))
        ex = exact_series(branch, order)
        for k in sorted(set(disc) | set(ex)):
            diff = sympy.factor(sympy.cancel(as_sympy("coefficient", disc.get(k, 0))
                                             - as_sympy("coefficient", ex.get(k, 0))))
            if diff != 0:
                out[f"plate {branch}"] = (k, diff)
                break
        else:
            out[f"plate {branch}"] = (None, None)
    return out


def square_patch(rule, p: int):
    """The square-element Bloch patch of degree p: n = max(p + 1, 3), r = b/H = 2/(n - p)."""
    import sympy

    from dispersion.symbolic.patch import Patch

    n = max(p + 1, 3)
    return Patch(p=p, n=n, model="bloch", r=sympy.Rational(2, n - p), mass=rule)
