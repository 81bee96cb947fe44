"""The cost rule of a simulation: DOFs x steps, checked before the work, refused in one line.

Two bounds, stated with their rules:

* :data:`MAX_DOFS`: the memory. The stiffness of p = 4 holds about 120 entries per row
  (12 bytes each), the records and vectors are small beside it: 10**6 DOFs take about
  1.5 GB, a sixteenth of the machine's 24 GiB, so that a sweep on two workers fits twice over.
* :data:`MAX_DOF_STEPS`: the time. The slowest loop measured on the shared 2-core machine
  (p = 4, factorized consistent mass, about 32,000 DOFs) ran at about 7e-7 s per DOF-step:
  1e9 DOF-steps are about 10 minutes. A rule whose explicit step applies a *dense* stiffness
  (the dual basis of the inverted Gram matrix) costs what it is: DOFs multiply-adds a row,
  DOFs / :data:`SPARSE_ROW` sparse DOF-steps, and 8 DOFs^2 bytes (:data:`MAX_BYTES`).

:func:`estimate_cost` is the check made *before* anything is assembled: the DOFs are exact,
the steps estimated from the 1D bar's largest frequency of the rule along x
(:func:`dispersion.waves.timestep.bar_omega_max`, exact) at the longitudinal speed over the
element length: an estimate from below (the plate's and the open mesh's maxima are higher),
so a request refused here could not finish. After the mesh's own critical step is measured
(:mod:`dispersion.simulation.mesh_critical_step`) :func:`check_cost` is applied again with
the true step count, still before the loop.

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> cost = estimate_cost(plan_strip(Strip(p=1, travel=1, stations=2, elements_per_wavelength=3)))
>>> cost.dofs, cost.dof_steps < MAX_DOF_STEPS
(114, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from dispersion.errors import InputError

__all__ = ["MAX_DOFS", "MAX_DOF_STEPS", "MAX_BYTES", "SPARSE_ROW", "RequestTooLarge", "RunCost",
           "estimate_cost", "check_cost", "dense_stiffness"]

MAX_DOFS = 10**6
MAX_DOF_STEPS = 10**9
#: Entries of a sparse stiffness row of the strip (p = 2: 50; p = 4: 120): the unit of the
#: DOF-step, in which a dense row costs DOFs / SPARSE_ROW times more.
SPARSE_ROW = 100
#: Most bytes of a stiffness: a sixteenth of the machine's memory (1.5 GB of 24 GiB).
MAX_BYTES = 3 * 2**29


class RequestTooLarge(InputError):
    """A simulation over a bound of :mod:`dispersion.simulation.run_cost` (refused before work)."""


@dataclass(frozen=True)
class RunCost:
    """``dofs``, ``steps`` and their product; ``estimated``: the steps are an estimate;
    ``dense``: every step multiplies by a dense DOFs x DOFs matrix."""

    dofs: int
    steps: int
    estimated: bool
    dense: bool = False

    @property
    def dof_steps(self) -> int:
        """DOFs x steps; a dense step counts DOFs / :data:`SPARSE_ROW` times (a sparse row
        of the strip holds about that many entries, a dense one all DOFs)."""
        per = max(1, self.dofs // SPARSE_ROW) if self.dense else 1
        return self.dofs * self.steps * per

    @property
    def nbytes(self) -> int:
        """Memory of the stiffness: a dense one's 8 DOFs^2 bytes; else about 12 SPARSE_ROW."""
        return 8 * self.dofs**2 if self.dense else 12 * SPARSE_ROW * self.dofs


def check_cost(cost: RunCost, what: str, limit: int = MAX_DOF_STEPS) -> RunCost:
    """Raise :class:`RequestTooLarge` (an InputError: one line, naming what sets the size)
    over a bound."""
    if cost.dofs > MAX_DOFS or cost.nbytes > MAX_BYTES:
        kind = "a dense stiffness of " if cost.dense else ""
        raise RequestTooLarge(f"{what}: {kind}{cost.dofs} DOFs, {cost.nbytes / 2**30:.2g} GiB, "
                              f"more than the bound of {MAX_DOFS} DOFs and "
                              f"{MAX_BYTES / 2**30:.2g} GiB (memory); use fewer elements per "
                              "wavelength or a lower degree")
    if cost.dof_steps > limit:
        kind = "about " if cost.estimated else ""
        why = "about 10 minutes" if limit == MAX_DOF_STEPS else "the budget asked for"
        raise RequestTooLarge(f"{what}: {kind}{cost.dofs} DOFs x {cost.steps} steps = "
                              f"{cost.dof_steps:.3g} DOF-steps, more than the bound of "
                              f"{limit:.3g} ({why}); use fewer elements per wavelength, a "
                              "shorter travel or a lower degree")
    return cost


def estimate_cost(plan) -> RunCost:
    """DOFs (exact) and steps (estimated from below) of the run of ``plan``."""
    from dispersion.mass_rules.mass_rule import get_rule
    from dispersion.symbolic.plate import lame
    from dispersion.time_stepping.timestep import bar_omega_max

    s = plan.strip
    dofs = 2 * plan.n_x * plan.n
    rule = get_rule(s.mass)
    try:
        w_bar = float(bar_omega_max(rule.x_rule, s.p)[0])
    except InputError:
        w_bar = float(bar_omega_max("lumped", s.p)[0])
    c_L = math.sqrt(float(lame(plan.nu)["L2M"]))
    omega = c_L * w_bar / plan.element_length
    steps = math.ceil(plan.t_end * omega / (2 * s.courant))
    return RunCost(dofs, steps, True, dense_stiffness(rule))


def dense_stiffness(rule) -> bool:
    """True if the rule's explicit step applies a dense stiffness (every DOF to every DOF)."""
    from dispersion.simulation.strip_mesh import explicit_step

    return explicit_step(rule)[0] == "dense"
