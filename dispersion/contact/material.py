"""St.Venant-Kirchhoff material in plane stress or plane strain (linear in Green strain).

.. math::

    \\mathbf S = \\bar\\lambda \\, \\mathrm{tr}(\\mathbf E) \\mathbf I + 2 \\mu \\mathbf E, \\qquad
    W = \\tfrac{\\bar\\lambda}{2} \\mathrm{tr}(\\mathbf E)^2 + \\mu \\, \\mathbf E : \\mathbf E, \\qquad
    \\mathbf E = \\tfrac12 (\\mathbf F^T \\mathbf F - \\mathbf I),

with the plane-stress modulus :math:`\\bar\\lambda = 2 \\lambda \\mu / (\\lambda + 2 \\mu)
= E \\nu / (1 - \\nu^2)` (plane strain: :math:`\\bar\\lambda = \\lambda = E \\nu /
((1 + \\nu)(1 - 2 \\nu))`) and :math:`\\mu = E / (2 (1 + \\nu))`.

>>> mat = StVenantKirchhoff(E=1.0, nu=0.25)
>>> round(mat.lam_bar, 6), round(mat.mu, 6)
(0.266667, 0.4)
>>> round(StVenantKirchhoff(E=1.0, nu=0.25, plane="strain").lam_bar, 6)
0.4

References
----------
G. A. Holzapfel, *Nonlinear Solid Mechanics*, Wiley 2000, sec. 6.5 (St.Venant-Kirchhoff).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dispersion.errors import InputError, check_nu, check_positive

__all__ = ["PLANES", "StVenantKirchhoff"]

PLANES = ("stress", "strain")


@dataclass(frozen=True)
class StVenantKirchhoff:
    """St.Venant-Kirchhoff material: Young's modulus ``E`` (Pa), Poisson ``nu``, ``plane``
    ``"stress"`` (thin) or ``"strain"`` (long)."""

    E: float
    nu: float
    plane: str = "stress"

    def __post_init__(self):
        check_positive("E", self.E)
        check_nu(self.nu)
        if self.plane not in PLANES:
            raise InputError(f"plane must be one of {', '.join(PLANES)}; got {self.plane!r}")

    @property
    def mu(self) -> float:
        return self.E / (2 * (1 + self.nu))

    @property
    def lam_bar(self) -> float:
        if self.plane == "strain":
            return self.E * self.nu / ((1 + self.nu) * (1 - 2 * self.nu))
        return self.E * self.nu / (1 - self.nu**2)

    def voigt(self) -> np.ndarray:
        """Elasticity matrix for ``(E11, E22, 2 E12)``."""
        lam, mu = self.lam_bar, self.mu
        return np.array([[lam + 2 * mu, lam, 0.0], [lam, lam + 2 * mu, 0.0], [0.0, 0.0, mu]])

    def stress(self, E: np.ndarray) -> np.ndarray:
        """Second Piola-Kirchhoff stress from Green strain tensors ``E`` (shape ``(..., 2, 2)``)."""
        tr = E[..., 0, 0] + E[..., 1, 1]
        return self.lam_bar * tr[..., None, None] * np.eye(2) + 2 * self.mu * E

    def energy_density(self, E: np.ndarray) -> np.ndarray:
        """Strain energy per unit reference area and unit thickness (J/m^3)."""
        tr = E[..., 0, 0] + E[..., 1, 1]
        return 0.5 * self.lam_bar * tr**2 + self.mu * np.einsum("...ij,...ij->...", E, E)
