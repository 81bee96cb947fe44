"""A solid: an elastic law with its density, name and source (what a layer is made of).

The isotropic table (:data:`dispersion.materials.materials.MATERIALS`, bulk speeds and density)
gives solids by :func:`as_solid`; the plies of fibre composites are solids of their own
(:data:`dispersion.materials.materials.PLIES`).

>>> from dispersion.materials.materials import material
>>> s = as_solid(material("steel"))
>>> s.name, round(s.stiffness.matrix[3][3] / 1e9, 2)
('steel', 82.15)
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from dispersion.errors import InputError, check_positive
from dispersion.materials.stiffness import Stiffness, from_speeds

__all__ = ["Solid", "as_solid", "isotropic_solid"]


@dataclass(frozen=True)
class Solid:
    """``stiffness`` (:class:`~dispersion.materials.stiffness.Stiffness`, Pa), density
    ``rho`` (kg/m^3), a ``name`` and the ``source`` of its numbers."""

    stiffness: Stiffness
    rho: float
    name: str = "custom"
    source: str = "user input"
    #: The isotropic :class:`~dispersion.materials.materials.Material` this solid was made from
    #: (None otherwise): a plate of one such layer is solved by the Rayleigh-Lamb
    #: calculator from the very same numbers.
    origin: object = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        if not isinstance(self.stiffness, Stiffness):
            raise InputError(f"a solid's stiffness must be a Stiffness, got "
                             f"{type(self.stiffness).__name__}")
        object.__setattr__(self, "rho", float(check_positive("rho", self.rho)))

    def slowest_speed(self) -> float:
        """A lower bound of every bulk speed (m/s): :math:`\\sqrt{\\lambda_{min} / \\rho}`
        with :math:`\\lambda_{min}` the smallest Kelvin eigenvalue of the real stiffness."""
        return math.sqrt(self.stiffness.kelvin_min() / self.rho)

    def fastest_speed(self) -> float:
        """An upper bound of every bulk speed (m/s): the largest Kelvin eigenvalue."""
        from dispersion.materials.stiffness import _kelvin

        lam = np.linalg.eigvalsh(_kelvin(self.stiffness.array().real))[-1]
        return math.sqrt(lam / self.rho)

    def rotated(self, degrees: float) -> Solid:
        """The solid turned about the normal (:meth:`Stiffness.rotated`)."""
        return Solid(self.stiffness.rotated(degrees), self.rho, self.name, self.source,
                     self.origin if self.stiffness.is_isotropic() else None)

    def with_loss(self, eta: float) -> Solid:
        """The solid with hysteretic damping (:meth:`Stiffness.with_loss`)."""
        if eta == 0:
            return self
        return Solid(self.stiffness.with_loss(eta), self.rho, self.name,
                     f"{self.source}; loss factor {eta:g}")

    def describe(self) -> str:
        """Name, density and law in words."""
        return f"{self.name} (rho {self.rho:g} kg/m^3, {self.stiffness.describe()})"

    def as_dict(self) -> dict:
        return {"name": self.name, "rho [kg/m^3]": self.rho, "source": self.source,
                **self.stiffness.as_dict()}


def as_solid(value) -> Solid:
    """A :class:`Solid` as it is, or an isotropic
    :class:`~dispersion.materials.materials.Material` with a density turned into one (its
    :meth:`~dispersion.materials.materials.Material.solid`)."""
    if isinstance(value, Solid):
        return value
    if callable(getattr(value, "solid", None)):
        return value.solid()
    raise InputError(f"a layer's material must be a Solid or a Material, got "
                     f"{type(value).__name__}")


def isotropic_solid(c_L: float, c_T: float, rho: float, name: str, source: str,
                    origin=None) -> Solid:
    """The solid of an isotropic material given by its bulk speeds and density."""
    return Solid(from_speeds(c_L, c_T, rho), rho, name, source, origin)
