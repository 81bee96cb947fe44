"""What a calculator asks of a plate: the continuum as a family of plate models.

The frequency calculator (:mod:`dispersion.continuum.frequency`: every propagating mode at a
frequency, found by a certain scan in kappa, counted, certified) needs of a plate only what
the :class:`PlateModel` protocol below lists; it never reaches for the Rayleigh-Lamb function
itself. A plate is a value that answers these questions:

- the isotropic plate (:class:`~dispersion.continuum.isotropic_plate.IsotropicPlate`: the
  deflated Rayleigh-Lamb function with its rounding bound, closed-form cut-offs, roots
  certified in floats or ball arithmetic at the exact Poisson ratio, SH in closed form);
- the layered or anisotropic plate
  (:class:`~dispersion.continuum.layered.layered_model.LayeredModel`: the determinant of the
  stack's dynamic stiffness, signed by its exact Wittrick-Williams count, certified in ball
  arithmetic; it also has a **count** -- the number of its branches below Omega at any kappa
  -- with which the counted calculator (:mod:`dispersion.continuum.layered.layered_modes`)
  finds every root from SAFE candidates).

A new plate (fluid-loaded, graded, a cylinder's wall) is a new value with these methods, not
a change to a calculator. A mode class is named by a string (``"S"``, ``"A"``, ``"SH"``,
``"L"``, ``"M"``, ...); its branches are numbered from 0 in increasing Omega at kappa = 0+ and
named by :meth:`PlateModel.label`.

>>> from dispersion.continuum.isotropic_plate import IsotropicPlate
>>> from fractions import Fraction
>>> isinstance(IsotropicPlate(Fraction(3, 10)), PlateModel)
True
"""
from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

__all__ = ["PlateModel"]


@runtime_checkable
class PlateModel(Protocol):
    """The questions a calculator asks a plate (units: :math:`\\kappa = kh`,
    :math:`\\Omega = \\omega h / c_{ref}` of the model; arrays are 1-d and broadcast)."""

    #: Largest kappa a scan may reach.
    kappa_limit: float

    def classes(self) -> tuple[str, ...]:
        """The mode classes, each solved alone (their roots never interact)."""

    def closed_form(self, cls: str) -> bool:
        """True for a class whose roots come in closed form (:meth:`closed_form_roots`)."""

    def closed_form_roots(self, cls: str, omega: float) -> list:
        """``[(label, kappa, group)]`` of a closed-form class at one Omega."""

    def label(self, cls: str, j: int) -> str:
        """The name of branch ``j`` of the class (``S0``, ``A3``, ``L2``)."""

    def dispersion(self, cls: str, kappa, omega) -> tuple[np.ndarray, np.ndarray]:
        """``(value, bound)``: the dispersion function of the class (zero on a branch, of one
        sign between branches) and a bound of its rounding error; where ``|value| > bound``
        the sign is certain."""

    def decide(self, cls: str, kappa: float, omega: float) -> int:
        """The certain sign (1 or -1) of the dispersion function where floats could not tell
        (``|value| <= bound``), 0 if it cannot be decided."""

    def kappa_start(self, omega: np.ndarray) -> np.ndarray:
        """A first kappa beyond every root at each Omega (checked, never trusted)."""

    def cutoffs(self, cls: str, omega_top: float) -> np.ndarray:
        """The class's branches at kappa = 0 (cut-offs) up to ``omega_top``, sorted."""

    def cutoff_table(self, cls: str, omega_top: float) -> list[tuple[str, float]]:
        """``[(label, Omega)]`` of every cut-off up to ``omega_top`` and the first above."""

    def polish(self, cls: str, kappa: np.ndarray, omega: np.ndarray) -> np.ndarray:
        """Roots closed again where the dispersion function loses digits (or unchanged)."""

    def certify(self, cls: str, kappa: np.ndarray, omega: np.ndarray, cells: np.ndarray):
        """``(roots, redone, bad)``: each root certified to the calculator's accuracy by a
        certain sign change of the exact function (``redone``: certified after refinement
        in exact arithmetic; ``bad``: the indices not certified). ``cells``: the scan's
        brackets of each root."""

    def slope(self, cls: str, kappa: np.ndarray, omega: np.ndarray,
              redone: np.ndarray) -> np.ndarray:
        """The group velocity :math:`d\\Omega/d\\kappa` at each root."""

    def split_pair(self, cls: str, kappa: float, omega: float, sign: int):
        """Next to a zero-group-velocity point at ``kappa``: the kappa of the extremum of the
        dispersion function if its certain sign is not ``sign`` (a hidden pair of roots), or
        None."""

    def count(self, cls: str, kappa, omega):
        """The number of the class's branches below Omega at each kappa, or None for a model
        without a count."""

    def candidates(self, cls: str, omega: float):
        """``(near, real)``: a discretisation's wavenumbers near the positive real axis and
        those on it (the counted calculator's first test points), or None for a model
        without a discretisation."""

    def close(self, cls: str, omega: float, a, b):
        """``(roots, still open)``: the roots in kappa on the brackets ``[a, b]`` (a sign
        change each), closed on the dispersion function."""
