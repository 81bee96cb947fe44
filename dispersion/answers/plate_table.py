"""What the tables of a layered plate at given frequencies share: the plate's thickness, the
failures in kHz, the scaling of Omega to kHz and the frequency line of the header.

:class:`PlateTable` is a mixin of :class:`~dispersion.answers.layered_mode_table.LayeredModeTable`
and :class:`~dispersion.answers.evanescent_mode_table.EvanescentModeTable`; a subclass holds
``plate`` (a :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate`),
``frequency_khz`` and ``roots`` (with ``failures`` as ``(Omega, class, why)``).
"""
from __future__ import annotations

import math

__all__ = ["PlateTable"]


class PlateTable:
    """The shared part of a layered plate's tables (module docstring); a mixin beside
    :class:`~dispersion.rendering.Rendered`, not a result of its own."""

    @property
    def thickness_mm(self) -> float:
        return self.plate.total_thickness_mm

    @property
    def failures(self) -> tuple:
        """Frequencies whose roots or count were not certified, with the reason."""
        return tuple(f"f = {self._khz(w):.10g} kHz, class {cls}: {why}"
                     for w, cls, why in self.roots.failures)

    def _scale(self):
        st = self.plate.scaled()
        return st.h_m, st.c_ref

    def _khz(self, Omega):
        h, c = self._scale()
        return float(Omega) * c / (2 * math.pi * h) / 1e3

    def _span(self) -> str:
        """The header's frequency line."""
        f = self.frequency_khz
        return "frequency: " + (f"{f.size} frequencies from {f.min():.10g} to {f.max():.10g} "
                                "kHz" if f.size > 1 else f"f = {f[0]:.10g} kHz")
