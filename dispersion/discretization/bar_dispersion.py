"""Dispersion of the 1D bar discretised by uniform periodic B-splines of any degree p.

For maximally smooth B-splines on a uniform mesh of element length h, a Bloch wave
:math:`u_j = e^{i j \\theta}`, :math:`\\theta = kh`, turns the discrete equation of motion into

.. math::

    (\\omega h / c)^2 = \\frac{d(\\theta)}{m(\\theta)}, \\qquad
    d(\\theta) = \\sum_L c^{11}_L \\cos L\\theta, \\quad
    m(\\theta) = \\sum_L c^{00}_L \\cos L\\theta \\;\\; \\text{(consistent)}, \\quad
    m = \\sum_L c^{00}_L = 1 \\;\\; \\text{(row-sum lumped)},

and in general :math:`m = \\sum_L a_L \\cos L\\theta` with the Bloch coefficients of any mass
rule without a contact set (:func:`dispersion.mass_rules.mass_rule.x_mass_coefficients`: HRZ,
nodal quadrature, user rules),

with the Gram coefficients :math:`c^{ab}_L` of the cardinal B-spline
(:func:`dispersion.symbolic.plate.bloch_coefficients`, the same numbers the plate's Bloch model uses
along x). For p = 1 this is the textbook :math:`6(1-\\cos\\theta)/(2+\\cos\\theta)` (consistent)
and :math:`2(1-\\cos\\theta)` (lumped). A singular mass acts only at a contact boundary, which a
periodic bar does not have, so only the rules without one apply here. The relative
frequency error equals the relative phase-velocity error at the same wavenumber and is
presented against elements per wavelength :math:`2\\pi/\\theta` (Cottrell, Reali, Bazilevs,
Hughes 2006).

>>> import numpy as np
>>> round(float(bar_frequency(1, "consistent", np.pi / 2) ** 2), 12)   # 6 (1 - 0) / (2 + 0)
3.0

References
----------
J. A. Cottrell, A. Reali, Y. Bazilevs, T. J. R. Hughes, "Isogeometric analysis of structural
vibrations", CMAME 195 (2006) 5257-5296, doi:10.1016/j.cma.2005.09.027.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.errors import InputError, check_positive_int
from dispersion.symbolic.plate import bloch_coefficients

__all__ = ["BAR_MASSES", "BarDispersion", "bar_dispersion", "bar_frequency", "bar_rule",
           "bar_stiffness_coefficients"]

#: Mass variants of the periodic bar shown by default (the registry's rules without a contact
#: set also apply: hrz, nodal-greville, nodal-lobatto, user rules).
BAR_MASSES = ("consistent", "lumped")


def bar_rule(mass):
    """The mass rule ``mass`` (name or rule) if it applies to the periodic bar, else InputError.

    A singular mass redistributes at a contact boundary, which the periodic bar has not.

    >>> bar_rule("lumped").name
    'lumped'
    """
    from dispersion.mass_rules.mass_rule import get_rule

    rule = get_rule(mass)
    if rule.redistributes or rule.states.zero_rows:
        raise InputError(f"mass {rule.name!r} does not apply to the periodic bar: it "
                         "redistributes at a contact boundary, which the periodic bar has "
                         "not (use model='plate')")
    return rule


def bar_frequency(p: int, mass: str, theta) -> np.ndarray:
    """Discrete :math:`\\omega h / c` at :math:`\\theta = kh` (module docstring), float array."""
    p = check_positive_int("degree p", p)
    rule = bar_rule(mass)
    if rule.basis == "lagrange":  # C0 elements: p branches, the acoustic one
        from dispersion.discretization.sem_bar import sem_bar_frequency

        return sem_bar_frequency(rule.name, p, theta)
    from dispersion.mass_rules.mass_rule import x_mass_coefficients

    theta = np.asarray(theta, dtype=float)
    # sum_L c11_L = 0 (derivatives of a partition of unity), so d = -2 sum c11_L sin^2(L theta/2)
    # without the cancellation that 1 - cos costs at small theta
    d = -2 * sum(float(v) * np.sin(L * theta / 2) ** 2
                 for L, v in bar_stiffness_coefficients(rule, p).items())
    m = sum(float(v) * np.cos(L * theta) for L, v in x_mass_coefficients(rule, p))
    return np.sqrt(np.clip(d, 0, None) / m)


def bar_stiffness_coefficients(mass, p: int) -> dict:
    """Bloch coefficients of the bar's stiffness symbol :math:`d(\\theta)` for rule ``mass``:
    :math:`c^{11}_L`, times the rule's x-factor for a Petrov-Galerkin rule
    (:func:`dispersion.mass_rules.mass_rule.x_stiffness_factor`; ``dual-lumped``).

    >>> bar_stiffness_coefficients("consistent", 1)
    {-1: -1, 0: 2, 1: -1}
    """
    from dispersion.mass_rules.approximate_dual import bloch_product
    from dispersion.mass_rules.mass_rule import x_stiffness_factor

    c11 = bloch_coefficients(check_positive_int("degree p", p))["11"]
    rule = bar_rule(mass)
    if rule.basis != "bspline":
        raise InputError(f"mass {rule.name!r} uses C0 Lagrange elements: the bar has p "
                         "branches, not one B-spline symbol (dispersion.discretization.sem_bar)")
    factor = dict(x_stiffness_factor(rule, p))
    if factor == {0: 1}:
        return c11
    return {L: v for L, v in bloch_product(c11, factor).items() if v != 0}


@dataclass(frozen=True)
class BarDispersion:
    """Signed relative frequency (= phase-velocity) error per degree and mass vs elements per wavelength."""

    elements_per_wavelength: np.ndarray
    error: dict[str, np.ndarray]  # key "p=2 consistent"


def bar_dispersion(degrees=(1, 2, 3, 4), masses=BAR_MASSES, elements_per_wavelength=None
                   ) -> BarDispersion:
    """:math:`\\omega^h / \\omega - 1` for each degree and mass on a grid of elements per wavelength.

    >>> bd = bar_dispersion((1,), ("lumped",), [4.0])
    >>> round(float(bd.error["p=1 lumped"][0]), 6)     # 2 sin(pi/4) / (pi/2) - 1
    -0.099684
    """
    epw = np.geomspace(2.0, 200.0, 60) if elements_per_wavelength is None else \
        np.asarray(elements_per_wavelength, dtype=float)
    if np.any(epw < 2) or not np.all(np.isfinite(epw)):
        raise InputError("elements per wavelength must be finite and >= 2 (Nyquist)")
    theta = 2 * math.pi / epw
    err = {f"p={p} {getattr(m, 'name', m)}": bar_frequency(p, m, theta) / theta - 1
           for p in degrees for m in masses}
    return BarDispersion(epw, err)
