"""What one explicit step costs with a mass rule: the structure of the matrices it applies.

A mass rule fixes more than frequencies: the explicit update
:math:`\\ddot u = M^{-1}(f - K u)` applies the stiffness in the rule's test basis and the
inverse of its mass. :class:`ExplicitCost` states both, per rule, as the toolkit models them:

* ``stiffness``: ``"sparse"`` (the B-spline or Lagrange stiffness, :math:`(2p+1)^d`
  entries a row in d dimensions), ``"banded-wide"`` (the Petrov-Galerkin stiffness
  :math:`S K`, :math:`(4p+1)^d` entries a row), or ``"dense"`` (every DOF couples to every
  DOF: the dual basis of the inverted Gram matrix, the globally supported interpolatory
  spline basis);
* ``mass``: how :math:`M^{-1}` is applied: ``"diagonal"`` (one entry a row), ``"banded"``
  (a banded matrix known explicitly, :math:`(2q+1)^d` entries a row: the approximate dual
  S), or ``"solve"`` (a linear solve every step: the consistent mass and every other
  non-diagonal mass, modelled as a sparse Cholesky back-substitution costing twice the
  factor's row, :math:`2 (2p+1)^d`).

:meth:`ExplicitCost.work_per_dof` is the modelled number of multiply-adds per DOF and step
(stiffness row plus mass application), with ``dofs`` the size of the problem for the dense
cases. It is a *model*: the measured cost of a simulation is a different study.

>>> ExplicitCost().work_per_dof(2, 2)            # 2D, p = 2: stiffness 2 * 5^2, mass 1
51
>>> ExplicitCost(stiffness="dense").work_per_dof(2, 2, dofs=1000)
1001
"""
from __future__ import annotations

from dataclasses import dataclass

from dispersion.errors import InputError, check_positive_int

__all__ = ["ExplicitCost", "STIFFNESS_KINDS", "MASS_KINDS"]

STIFFNESS_KINDS = ("sparse", "banded-wide", "dense")
MASS_KINDS = ("diagonal", "banded", "solve")


@dataclass(frozen=True)
class ExplicitCost:
    """How a rule's explicit step applies stiffness and inverse mass (module docstring)."""

    stiffness: str = "sparse"
    mass: str = "diagonal"
    note: str = ""

    def __post_init__(self):
        if self.stiffness not in STIFFNESS_KINDS:
            raise InputError(f"stiffness must be one of {', '.join(STIFFNESS_KINDS)}, "
                             f"got {self.stiffness!r}")
        if self.mass not in MASS_KINDS:
            raise InputError(f"mass must be one of {', '.join(MASS_KINDS)}, got {self.mass!r}")

    def work_per_dof(self, p: int, dim: int = 2, dofs: int | None = None) -> int:
        """Modelled multiply-adds per DOF and step in ``dim`` dimensions (two displacement
        components: the stiffness row couples both)."""
        p = check_positive_int("degree p", p)
        dim = check_positive_int("dimension dim", dim, maximum=3)
        comps = dim
        if self.stiffness == "dense" or self.mass == "dense":
            if dofs is None:
                raise InputError("a dense stiffness costs per DOF the number of DOFs: give dofs")
            dofs = check_positive_int("dofs", dofs)
        stiff = {"sparse": comps * (2 * p + 1) ** dim,
                 "banded-wide": comps * (4 * p + 1) ** dim,
                 "dense": dofs}[self.stiffness]
        mass = {"diagonal": 1, "banded": (2 * p + 1) ** dim,
                "solve": 2 * (2 * p + 1) ** dim}[self.mass]
        return stiff + mass

    def describe(self) -> str:
        """One line in words."""
        text = f"stiffness {self.stiffness}, inverse mass {self.mass}"
        return text + (f" ({self.note})" if self.note else "")
