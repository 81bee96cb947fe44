"""The exact plate of a claims file: the Rayleigh-Lamb equation (``model = "rayleigh-lamb"``).

It has no settings: its series are :func:`dispersion.continuum.exact_series.exact_series`, its
branches :func:`dispersion.continuum.exact_branches.trace_branches`. A claim about a
discretisation holds a :class:`dispersion.symbolic.patch.Patch` (or a
:class:`dispersion.claims.bar_model.BarModel`) instead.

>>> ExactModel().label()
'Rayleigh-Lamb (exact)'
>>> ExactModel() == ExactModel()
True
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

__all__ = ["EXACT", "ExactModel"]

#: The claims file's name of the exact model (the Rayleigh-Lamb equation of
#: :mod:`dispersion.continuum.rayleigh_lamb`).
EXACT = "rayleigh-lamb"


@dataclass(frozen=True)
class ExactModel:
    """The exact plane-strain plate: the Rayleigh-Lamb equation, eq (13) in its standard form."""

    name: ClassVar[str] = EXACT

    def label(self) -> str:
        """The model in words, as the reports show it."""
        return "Rayleigh-Lamb (exact)"
