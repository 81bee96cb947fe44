"""The assembled matrices of a finite patch, as one value (what the assembly returns).

Built by :func:`dispersion.discretization.finite_mesh.finite_assembly.assemble` (straight bar
and strip) and :func:`dispersion.discretization.finite_mesh.mapped_assembly.assemble_mapped`
(a strip mapped by a NURBS geometry).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

__all__ = ["FiniteMatrices"]


@dataclass(frozen=True, repr=False)
class FiniteMatrices:
    """The assembled patch: ``K`` (all DOFs, CSR), the scalar ``mass`` (points x points; None
    where only its banded inverse ``mass_inverse`` is known), the ``massless`` points (zero
    rows), the bases along x and through the thickness, and how the rule's explicit step
    applies stiffness and mass (``step_kind``)."""

    patch: object
    rule: object
    K: sp.csr_matrix
    mass: sp.csr_matrix | None
    massless: np.ndarray
    basis_x: object
    basis_y: object = None
    step_kind: tuple[str, str] = ("sparse", "solve")
    mass_inverse: sp.csr_matrix | None = None
    #: Thickness matrices Y^{ab} and the thickness mass "My" (floats) of the strip.
    thickness: dict | None = None

    @property
    def n_points(self) -> int:
        return self.K.shape[0] // self.patch.dofs_per_point

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]

    def __repr__(self) -> str:
        return (f"FiniteMatrices({self.patch.label()}: {self.n_dofs} DOFs, "
                f"{self.massless.size} massless points)")
