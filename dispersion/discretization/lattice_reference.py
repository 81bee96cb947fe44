"""The periodic lattice beside a finite patch: the largest frequency of the same rule and cell.

The finite patch's outliers are measured against the lattice of its own cell: the periodic
bar of the same degree and rule (its closed form :math:`\\omega h / c = \\sqrt{d/m}` maximized
over the phase in floats, per element length h) or the Bloch plate patch of the strip's thickness mesh, rule and aspect
ratio r = b/H (:func:`dispersion.waves.timestep.patch_omega_max`). A singular rule's lattice
is its x-direction rule's along the bar (the periodic bar has no contact boundary).

>>> from dispersion.discretization.finite_patch import finite_bar
>>> round(lattice_omega_max(finite_bar(2, 10, mass="consistent", length=10.0)), 12)  # sqrt(10)
3.162277660168
"""
from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

from dispersion.errors import InputError

__all__ = ["lattice_omega_max", "lattice_rule"]


def lattice_rule(patch) -> str:
    """The rule of the lattice beside ``patch``: its own, or its x-rule for a singular bar."""
    rule = patch.rule
    return rule.x_rule if (rule.redistributes and patch.model == "bar") else rule.name


def lattice_omega_max(patch) -> float:
    """The lattice's largest frequency in the patch's unit (:math:`\\omega` with c = 1 on the
    bar's length scale; :math:`\\omega H / c_T` for the strip)."""
    if patch.mapped:
        raise InputError("a mapped patch has no periodic lattice of its own")
    if patch.knots != "uniform":
        raise InputError("the lattice is that of uniform knots; this patch's knots are "
                         f"{patch.knots}")
    if patch.model == "bar":
        return _bar(lattice_rule(patch), patch.p) / patch.element_length
    b = Fraction(patch.length / patch.n_elements).limit_denominator(10**6)
    return _strip(patch.p, patch.n, lattice_rule(patch), b, patch.contact,
                  Fraction(patch.gamma_s).limit_denominator(10**6), patch.nu)


@lru_cache(maxsize=256)
def _bar(rule: str, p: int) -> float:
    """max over theta of the periodic bar's omega h / c: a grid of 4097 phases, an interior
    maximum refined to 1e-13 in theta (bounded Brent); C0 Lagrange rules: their p branches
    (:func:`dispersion.waves.timestep.bar_omega_max`). Floats: the exact maximum
    (:func:`~dispersion.waves.timestep.bar_omega_max`, sympy) takes a second or two a rule."""
    import math

    import numpy as np

    from dispersion.symbolic.mass_rule import get_rule
    from dispersion.waves.bar_dispersion import bar_frequency

    if get_rule(rule).basis == "lagrange":
        from dispersion.waves.timestep import bar_omega_max

        return float(bar_omega_max(rule, p)[0])
    theta = np.linspace(0.0, math.pi, 4097)
    w = bar_frequency(p, rule, theta)
    i = int(np.argmax(w))
    best = float(w[i])
    if 0 < i < theta.size - 1:
        from scipy.optimize import minimize_scalar

        r = minimize_scalar(lambda t: -float(bar_frequency(p, rule, t)),
                            bounds=(theta[i - 1], theta[i + 1]), method="bounded",
                            options={"xatol": 1e-13})
        best = max(best, -float(r.fun))
    return best


@lru_cache(maxsize=256)
def _strip(p: int, n: int, rule: str, b: Fraction, contact: str, gamma_s: Fraction,
           nu: float) -> float:
    import sympy

    from dispersion.symbolic.plate import plate_patch
    from dispersion.waves.timestep import patch_omega_max

    patch = plate_patch(p, n, "bloch", sympy.Rational(b.numerator, b.denominator), rule,
                        contact, sympy.Rational(gamma_s.numerator, gamma_s.denominator))
    return float(patch_omega_max(patch, nu, n_theta=17, exact=False)[0])
