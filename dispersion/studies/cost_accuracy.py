"""Cost against accuracy of explicit dynamics for every mass rule and degree (issue 21).

For each degree p and mass rule, on the Bloch plate patch with square elements (``n`` control
points through the thickness, :math:`r = b/H = 2/(n - p)`, plane strain, Poisson's ratio nu):

* **step**: the critical step of central differences :math:`\\tau_{crit} = 2/\\Omega_{max}`
  (:func:`dispersion.time_stepping.timestep.patch_omega_max`, in units :math:`H/c_T`), massless DOFs
  condensed;
* **accuracy**: the phase-velocity error of S0 and A0 at ``elements_per_wavelength``
  (:math:`\\kappa = 2\\pi / (N r)`), *fully discrete* at the largest stable step
  (:math:`\\tau = \\tau_{crit}`, :func:`dispersion.time_stepping.fully_discrete.time_frequency`),
  against the exact Rayleigh-Lamb roots; the signed errors and the worse of the two;
* **cost** (modelled): time steps per unit time times degrees of freedom per unit area times
  the work of one explicit step per DOF,
  :math:`(1/\\tau_{crit}) \\cdot 2n / (2 r) \\cdot w`, in multiply-adds
  :math:`\\cdot c_T / H^3` (all 2n DOFs of the cell counted, massless ones too: the explicit
  update of the singular masses still solves for them). The work per DOF
  :math:`w` is the rule's :class:`~dispersion.mass_rules.explicit_cost.ExplicitCost` in two
  dimensions: stiffness row plus inverse mass (a diagonal, the banded approximate dual, or a
  solve with a non-diagonal mass); a dense stiffness costs every DOF of a model problem of
  :data:`MODEL_ELEMENTS` x :data:`MODEL_ELEMENTS` elements. It is a model, not a measurement:
  the measured price of each explicit step (the SuperLU solve of a non-diagonal mass against
  a division) is in :mod:`dispersion.studies.wave_simulation`.

A point is on the Pareto front if no other point is both cheaper and more accurate (worse of
S0/A0). The result carries its inputs; the report renders from it alone.

>>> res = cost_accuracy((1,), ("lumped", "consistent"))
>>> [round(pt.tau_crit * pt.cost / pt.work, 12) for pt in res.points]   # 2n/(2r), n = 3, r = 1
[3.0, 3.0]
>>> [pt.work for pt in res.points]        # 2 * 3^2 stiffness + 1 (diagonal) or 2 * 3^2 (solve)
[19, 36]
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import sympy

__all__ = ["CostAccuracyPoint", "CostAccuracy", "cost_accuracy", "pareto_front", "measure"]

#: Rules of the chart: None stands for the registry's rules that apply to the Bloch patch
#: (:data:`dispersion.mass_rules.mass_rule.BLOCH_RULE_NAMES`, read at call time; the C0
#: Lagrange rules carry p DOFs a cell along x and are on the bar's charts only).
RULES = None
#: Elements per direction of the model problem whose DOFs a dense stiffness row couples.
MODEL_ELEMENTS = 100


@dataclass(frozen=True)
class CostAccuracyPoint:
    """One (p, rule): step, cost and the fully discrete errors (signed, relative)."""

    p: int
    mass: str
    n: int
    r: float
    tau_crit: float
    cost: float
    error_S0: float
    error_A0: float
    semi_error_S0: float
    semi_error_A0: float
    pareto: bool
    #: Modelled multiply-adds per DOF and step (stiffness row plus inverse mass).
    work: int = 1
    #: The rule's explicit step in words (stiffness and inverse mass).
    step_kind: str = ""

    @property
    def error(self) -> float:
        return max(abs(self.error_S0), abs(self.error_A0))


@dataclass(frozen=True)
class CostAccuracy:
    """The chart's data and the inputs it was computed from."""

    nu: float
    elements_per_wavelength: int
    courant: float
    degrees: tuple[int, ...]
    rules: tuple[str, ...]
    contact: str
    gamma_s: float
    points: tuple[CostAccuracyPoint, ...]


def pareto_front(cost, error) -> np.ndarray:
    """Mask of the points no other point beats in both cost and error (ties kept).

    >>> pareto_front([1, 2, 3], [3, 1, 2]).tolist()
    [True, True, False]
    """
    cost, error = np.asarray(cost, float), np.asarray(error, float)
    keep = np.ones(cost.size, bool)
    for i in range(cost.size):
        better = (cost <= cost[i]) & (error <= error[i]) & ((cost < cost[i]) | (error < error[i]))
        keep[i] = not better.any()
    return keep


def cost_accuracy(degrees=(1, 2, 3, 4), rules=None, *, nu: float = 0.3,
                  elements_per_wavelength: int = 8, courant: float = 1.0,
                  contact: str = "top", gamma_s=sympy.Rational(1, 2),
                  n_theta: int = 33) -> CostAccuracy:
    """Compute the chart (module docstring); ``courant`` is the step over the critical step."""
    from dispersion.errors import InputError, check_positive_int, check_real_in_range
    from dispersion.symbolic.plate import plate_patch
    from dispersion.discretization.discrete_branches import fundamental_branches
    from dispersion.continuum.exact_branches import trace_branches
    from dispersion.time_stepping.fully_discrete import time_frequency
    from dispersion.time_stepping.timestep import patch_omega_max

    N = check_positive_int("elements_per_wavelength", elements_per_wavelength, minimum=2)
    courant = check_real_in_range("courant", courant, 0, 1, lo_open=True)
    from dispersion.mass_rules.mass_rule import BLOCH_RULE_NAMES, get_rule

    rules = BLOCH_RULE_NAMES if rules is None else rules
    if not degrees or not rules:
        raise InputError("degrees and rules must be non-empty")
    raw = []
    for p in degrees:
        n = max(p + 1, 3)
        r = sympy.Rational(2, n - p)
        kappa = 2 * math.pi / (N * float(r))
        exact = trace_branches(nu, np.array([kappa]), 3.0).omega
        for mass in rules:
            patch = plate_patch(p, n, "bloch", r, mass, contact, gamma_s)
            w_max = patch_omega_max(patch, nu, n_theta, exact=False)[0]
            tau = 2 / w_max
            semi = fundamental_branches(patch, nu, [kappa])
            errs = {}
            for label in ("S0", "A0"):
                ref = float(exact[label][0])
                full = float(time_frequency(semi[label], courant * tau)[0])
                errs[label] = (full / ref - 1, float(semi[label][0]) / ref - 1)
            step = get_rule(mass).explicit_cost
            work = step.work_per_dof(p, 2, dofs=2 * (MODEL_ELEMENTS + p) ** 2)
            cost = (1 / (courant * tau)) * (2 * n) / (2 * float(r)) * work
            raw.append((p, getattr(mass, "name", mass), n, float(r), tau, cost, errs["S0"][0],
                        errs["A0"][0], errs["S0"][1], errs["A0"][1], work, step.describe()))
    front = pareto_front([row[5] for row in raw],
                         [max(abs(row[6]), abs(row[7])) for row in raw])
    points = tuple(CostAccuracyPoint(*row[:10], bool(f), *row[10:]) for row, f in zip(raw, front))
    return CostAccuracy(float(nu), N, float(courant), tuple(degrees),
                        tuple(getattr(m, "name", m) for m in rules), contact,
                        float(gamma_s), points)


def measure(quick: bool = False, executor=None) -> CostAccuracy:
    """The report's measurement: p = 1..4 (quick: 1..2), every built-in rule."""
    del executor  # a few seconds in-process; nothing to farm out
    return cost_accuracy((1, 2) if quick else (1, 2, 3, 4))
