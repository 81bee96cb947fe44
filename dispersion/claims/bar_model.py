"""The periodic 1D bar of the explicit-dynamics claims (``model = "bar"``): a degree and a mass.

The bar has no thickness, no aspect ratio and no contact boundary, so it is not a
:class:`dispersion.symbolic.patch.Patch`: it holds the degree ``p`` of its B-splines and the
mass rule, checked here once. Its frequencies are those of
:func:`dispersion.time_stepping.timestep.bar_omega_squared` (element length h, wave speed c).

>>> BarModel(1, "lumped").label()
'periodic bar p=1, lumped mass'
>>> BarModel(2, "singular")
Traceback (most recent call last):
...
dispersion.errors.InputError: mass 'singular' needs a contact boundary, which the periodic bar has not
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from dispersion import defaults
from dispersion.errors import check_int_in_range

__all__ = ["BarModel"]


@dataclass(frozen=True)
class BarModel:
    """The periodic bar: ``p`` in [1, :data:`dispersion.symbolic.plate.P_MAX`], a mass rule
    of :mod:`dispersion.mass_rules.mass_rule` that does not redistribute (name or rule)."""

    p: int = defaults.P
    mass: str = defaults.MASS
    name: ClassVar[str] = "bar"

    def __post_init__(self):
        from dispersion.errors import InputError
        from dispersion.mass_rules.mass_rule import get_rule
        from dispersion.symbolic.plate import P_MAX

        object.__setattr__(self, "p", check_int_in_range("p", self.p, 1, P_MAX))
        rule = get_rule(self.mass)  # a registered name or a MassRule, else InputError
        if rule.redistributes:
            raise InputError(f"mass {rule.name!r} needs a contact boundary, which the periodic "
                             "bar has not")

    @property
    def mass_name(self) -> str:
        """The mass rule's name (``mass`` may be a rule object)."""
        return getattr(self.mass, "name", self.mass)

    def label(self) -> str:
        """The model in words, as the reports show it."""
        return f"periodic bar p={self.p}, {self.mass_name} mass"
