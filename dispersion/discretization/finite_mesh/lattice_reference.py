"""The periodic lattice beside a finite patch: the largest frequency of the same rule and cell.

The finite patch's outliers are measured against the lattice of its own cell: the periodic
bar of the same degree and rule (its closed form :math:`\\omega h / c = \\sqrt{d/m}` maximized
over the phase in floats, per element length h) or the Bloch plate patch of the strip's
thickness mesh, rule and aspect ratio r = b/H (its float pencil maximized over the phase; the
time stepper's :func:`dispersion.time_stepping.timestep.patch_omega_max` adds the exact zone
ends). A singular rule's lattice
is its x-direction rule's along the bar (the periodic bar has no contact boundary).

>>> from dispersion.discretization.finite_mesh.finite_patch import finite_bar
>>> round(lattice_omega_max(finite_bar(2, 10, mass="consistent", length=10.0)), 12)  # sqrt(10)
3.162277660168
"""
from __future__ import annotations

import math
from fractions import Fraction
from functools import lru_cache

import numpy as np

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
    (:func:`dispersion.discretization.sem_bar.sem_bar_omega_max`). Floats: the exact maximum
    (:func:`dispersion.time_stepping.timestep.bar_omega_max`, sympy) takes a second or two a
    rule."""
    from dispersion.discretization.bar_dispersion import bar_frequency
    from dispersion.mass_rules.mass_rule import get_rule

    if get_rule(rule).basis == "lagrange":
        from dispersion.discretization.sem_bar import sem_bar_omega_max

        return float(sem_bar_omega_max(rule, p)[0])
    return _grid_maximum(lambda t: bar_frequency(p, rule, t))


def _grid_maximum(top, n_theta: int = 4097) -> float:
    """The largest of ``top(theta)`` over [0, pi]: a grid, an interior maximum refined by
    bounded Brent to 1e-13 in theta."""
    theta = np.linspace(0.0, math.pi, n_theta)
    w = np.asarray(top(theta), dtype=float)
    i = int(np.argmax(w))
    best = float(w[i])
    if 0 < i < theta.size - 1:
        from scipy.optimize import minimize_scalar

        r = minimize_scalar(lambda t: -float(np.asarray(top(np.array([t])), float).max()),
                            bounds=(theta[i - 1], theta[i + 1]), method="bounded",
                            options={"xatol": 1e-13})
        best = max(best, -float(r.fun))
    return best


@lru_cache(maxsize=256)
def _strip(p: int, n: int, rule: str, b: Fraction, contact: str, gamma_s: Fraction,
           nu: float) -> float:
    """The Bloch plate patch's largest frequency over the zone, every branch (the float
    pencil, massless DOFs condensed: :func:`dispersion.discretization.pencil_frequencies.pencil_frequencies`),
    on a grid of 129 phases refined by bounded Brent."""
    import sympy

    from dispersion.discretization.pencil_frequencies import pencil_frequencies
    from dispersion.symbolic.plate import numeric_pencil, plate_patch

    r = sympy.Rational(b.numerator, b.denominator)
    patch = plate_patch(p, n, "bloch", r, rule, contact,
                        sympy.Rational(gamma_s.numerator, gamma_s.denominator))

    def top(theta):
        K, M = numeric_pencil(patch, nu, np.atleast_1d(theta) / float(r))
        return pencil_frequencies(K, M, patch.massless)[:, -1]

    return _grid_maximum(top, 129)
