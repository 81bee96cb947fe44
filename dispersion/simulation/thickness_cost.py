"""What one explicit step costs as the strip thickens: each mass's step against the thickness mesh.

The strip of a scene is meshed through its thickness by the plan's rule (the fewest elements
within a wavelength over N, :func:`~.strip.plan_strip`): one to three elements for the study's
plate. A factorized (consistent) mass is then a band of a few points' width, and its solve
may cost less per DOF than it does on a mesh with more elements through the thickness (a
thicker structure, or a plate meshed finer across than along). :func:`thickness_cost`
measures it: the same strip with ``thickness_elements`` n_y of the list, each mass of the
list, the explicit loop of :func:`~.central_difference.run_explicit` (mat-vec, division or
solve, updates, station gather) timed in ``repeat`` equal segments of ``steps`` steps each;
the seconds per step are the median segment's. The load is zero: the work of a step does not
depend on the values, and a zero field cannot grow whatever the step (no Lanczos estimate is
needed to time it).

>>> from dispersion.simulation.strip import Strip
>>> cost = thickness_cost(Strip(p=1, elements_per_wavelength=3, travel=1, stations=2),
...                       (2, 4), ("lumped", "consistent"), steps=20, repeat=2)
>>> cost.dofs[1] > cost.dofs[0], len(cost.seconds_per_step["consistent"])
(True, 2)

References
----------
A. George, "Nested dissection of a regular finite element mesh", SIAM J. Numer. Anal. 10
(1973) 345-363 (fill of a banded factor grows with the band's width).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from dispersion.errors import check_positive_int

__all__ = ["ThicknessCost", "thickness_cost"]


@dataclass(frozen=True)
class ThicknessCost:
    """Seconds per explicit step of ``strip`` with each of ``thickness_elements`` through the
    thickness (``dofs`` each), for each mass: ``seconds_per_step[mass][i]``; the factor's
    stored entries per point of a factorized mass (``factor_per_point[mass][i]``, None for
    a division); ``plan_elements``: what the plan's own rule gives."""

    strip: object
    thickness_elements: tuple[int, ...]
    dofs: tuple[int, ...]
    masses: tuple[str, ...]
    seconds_per_step: dict
    factor_per_point: dict
    plan_elements: int
    steps: int
    repeat: int

    def ratio(self, mass: str, over: str) -> tuple[float, ...]:
        """Seconds per step of ``mass`` over those of ``over``, at each thickness."""
        return tuple(a / b for a, b in zip(self.seconds_per_step[mass],
                                           self.seconds_per_step[over]))


def thickness_cost(strip, thickness_elements=(2, 4, 8, 16), masses=("lumped", "consistent"),
                   *, steps: int = 50, repeat: int = 5) -> ThicknessCost:
    """Time the explicit step of ``strip`` at each thickness mesh and mass (module docstring)."""
    from dispersion.simulation.central_difference import run_explicit
    from dispersion.simulation.mass_operator import mass_operator
    from dispersion.simulation.strip import plan_strip
    from dispersion.simulation.strip_mesh import strip_mesh

    steps = check_positive_int("steps", steps)
    repeat = check_positive_int("repeat", repeat)
    base = replace(strip, thickness_elements=None)
    plan_elements = plan_strip(base).n_elements_y
    seconds = {m: [] for m in masses}
    factor = {m: [] for m in masses}
    dofs = []
    for n_y in thickness_elements:
        for k, mass in enumerate(masses):
            plan = plan_strip(replace(base, mass=mass, thickness_elements=int(n_y)))
            mesh = strip_mesh(plan)
            op = mass_operator(mesh)
            if k == 0:
                dofs.append(mesh.n_dofs)
            run = run_explicit(mesh, op, plan.element_length * 1e-3, np.zeros(steps * repeat),
                               segments=repeat)
            seconds[mass].append(float(np.median(run.seconds_per_step)))
            factor[mass].append(None if op.kind != "factorized"
                                else op.factor_nnz / op.massive.size)
    return ThicknessCost(base, tuple(int(n) for n in thickness_elements), tuple(dofs),
                         tuple(masses), {m: tuple(v) for m, v in seconds.items()},
                         {m: tuple(v) for m, v in factor.items()}, int(plan_elements),
                         steps, repeat)
