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

:func:`estimate_cost` is the check made *before* the strip is assembled: the DOFs are exact,
the steps follow from the largest frequency of a *short* strip of the same cross-section,
rule and element size (:data:`SHORT_ELEMENTS` elements long, assembled and solved by the same
Lanczos as the run, :mod:`dispersion.simulation.mesh_critical_step`). The largest frequency
is set by the elements and the ends, not by the length: measured against the full strips
(p = 2 lumped, singular, dual-gram, p = 3 dual-lumped and sem-lumped, p = 4 consistent) the
short strip's lies within 0.14 % of it, above it in every case; the 1D bar's frequency along x
alone (the estimate before) fell short by up to 17 times (the thickness direction), so
requests of minutes were refused only after the assembly. After the mesh's own critical step
is measured :func:`check_cost` is applied again with the true step count, still before the
loop.

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> cost = estimate_cost(plan_strip(Strip(p=1, travel=1, stations=2, elements_per_wavelength=3)))
>>> cost.dofs, cost.dof_steps < MAX_DOF_STEPS
(132, True)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

from dispersion.errors import InputError

__all__ = ["MAX_DOFS", "MAX_DOF_STEPS", "MAX_BYTES", "SPARSE_ROW", "RequestTooLarge", "RunCost",
           "estimate_cost", "check_cost", "dense_stiffness"]

MAX_DOFS = 10**6
MAX_DOF_STEPS = 10**9
#: Length in elements of the short strip whose largest frequency estimates the run's step, per
#: degree: 4 p + 4 (its value moved by less than 1e-4 relative from 2 p + 2 to 8 p + 8
#: elements, p = 3 and 4, measured).
SHORT_ELEMENTS = 4
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
        raise RequestTooLarge(f"{what}: {kind}{cost.dofs} DOFs x {_count(cost.steps)} steps = "
                              f"{_count(cost.dof_steps)} DOF-steps, more than the bound of "
                              f"{limit:.3g} ({why}); use fewer elements per wavelength, a "
                              "shorter travel or a lower degree")
    return cost


def _count(n: int) -> str:
    """A count in a message: its digits up to ten million, beyond that three significant
    ones (a Courant number of 1e-300 asks for a 306-digit number of steps, beyond the floats).

    >>> _count(52038), _count(36849319), _count(3232 * 10**306)
    ('52038', '3.68e+07', '3.23e+309')
    """
    if n < 10**7:
        return str(n)
    digits = str(int(n))
    head = round(int(digits[:4]) / 10)  # three significant digits, rounded
    exponent = len(digits) - 1 + (head >= 1000)
    head = str(head // 10 if head >= 1000 else head)
    return f"{head[0]}.{head[1:]}e+{exponent:02d}"


def estimate_cost(plan) -> RunCost:
    """DOFs (exact) and steps (from a short strip's largest frequency, module docstring) of the
    run of ``plan``."""
    s = plan.strip
    dofs = 2 * plan.n_x * plan.n
    from dispersion.mass_rules.mass_rule import get_rule

    omega = short_strip_omega(plan)
    steps = math.ceil(plan.t_end * omega / (2 * s.courant))
    return RunCost(dofs, steps, True, dense_stiffness(get_rule(s.mass)))


def short_strip_omega(plan) -> float:
    """The largest frequency (in c_T / H) of a strip of ``plan``'s cross-section, rule and
    element size, :data:`SHORT_ELEMENTS` (p + 1) elements long (no longer than the plan's)."""
    from dataclasses import replace

    from dispersion.mass_rules.mass_rule import get_rule

    s = plan.strip
    m = min(plan.n_elements_x, SHORT_ELEMENTS * (s.p + 1))
    lagrange = getattr(get_rule(s.mass), "basis", "bspline") == "lagrange"
    # only what shapes K and M is kept: one value per cross-section, rule and element size
    short = replace(plan, n_elements_x=m, n_x=m * s.p + 1 if lagrange else m + s.p,
                    length=m * plan.element_length, stations=(0.0,), phase_stations=(),
                    t_end=0.0, band=(0.0, 0.0), strip=replace(s, travel=1.0, stations=2))
    return _short_strip_omega(short)


@lru_cache(maxsize=256)
def _short_strip_omega(short) -> float:
    from dispersion.simulation.mass_operator import mass_operator
    from dispersion.simulation.mesh_critical_step import mesh_critical_step
    from dispersion.simulation.strip_mesh import strip_mesh

    mesh = strip_mesh(short)
    return mesh_critical_step(mesh, mass_operator(mesh)).omega_lanczos


def dense_stiffness(rule) -> bool:
    """True if the rule's explicit step applies a dense stiffness (every DOF to every DOF)."""
    from dispersion.simulation.strip_mesh import explicit_step

    return explicit_step(rule)[0] == "dense"
