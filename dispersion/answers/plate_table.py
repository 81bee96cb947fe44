"""What the tables of a layered plate at given frequencies share: the frequencies read and
checked against the solvers' range (:func:`plate_frequencies`), and the plate's thickness,
the failures in kHz, the scaling of Omega to kHz and the frequency line of the header.

:class:`PlateTable` is a mixin of :class:`~dispersion.answers.layered_mode_table.LayeredModeTable`
and :class:`~dispersion.answers.evanescent_mode_table.EvanescentModeTable`; a subclass holds
``plate`` (a :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate`),
``frequency_khz`` and ``roots`` (with ``failures`` as ``(Omega, class, why)``).
"""
from __future__ import annotations

import math

import numpy as np

from dispersion.errors import InputError

__all__ = ["PlateTable", "plate_frequencies"]


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


def plate_frequencies(plate, frequency_khz=None, fd_mhz_mm=None):
    """``(f_khz, Omega)``: exactly one of ``frequency_khz`` (kHz) and ``fd_mhz_mm`` (MHz mm)
    read as a non-empty list of finite numbers, and each frequency's
    :math:`\\Omega = \\omega h / c_{ref}` (:meth:`LayeredPlate.scaled`), refused in the
    argument's own unit when outside the solvers' range
    (:data:`~dispersion.continuum.layered.layered_modes.OMEGA_RANGE`)."""
    from dispersion.continuum.layered.layered_modes import OMEGA_RANGE

    if (frequency_khz is None) == (fd_mhz_mm is None):
        raise InputError("give exactly one of frequency_khz (kHz) and fd_mhz_mm (MHz mm)")
    fd = fd_mhz_mm is not None
    name, raw = ("fd_mhz_mm", fd_mhz_mm) if fd else ("frequency_khz", frequency_khz)
    try:
        values = np.atleast_1d(np.asarray(raw, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number or a list of numbers, got {raw!r}") from None
    if values.ndim != 1 or values.size == 0 or not np.all(np.isfinite(values)):
        raise InputError(f"{name} must be a finite number or a non-empty 1-d list")
    f_khz = values * 1e3 / plate.total_thickness_mm if fd else values
    st = plate.scaled()
    omega = 2 * math.pi * f_khz * 1e3 * st.h_m / st.c_ref
    lo, hi = OMEGA_RANGE
    bad = (omega < lo) | (omega > hi)
    if np.any(bad):
        scale = plate.total_thickness_mm * 1e-3 if fd else 1.0
        unit = "MHz mm" if fd else "kHz"
        lo_f, hi_f = (w * st.c_ref / (2 * math.pi * st.h_m) * 1e-3 * scale for w in (lo, hi))
        raise InputError(f"{name} must lie in [{lo_f:.4g}, {hi_f:.4g}] {unit} for this plate "
                         f"(d = {plate.total_thickness_mm:g} mm), got "
                         f"{float(f_khz[bad][0]) * scale:.6g} {unit}")
    return f_khz, omega
