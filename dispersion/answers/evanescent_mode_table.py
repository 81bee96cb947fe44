"""The evanescent modes of a plate at given frequencies, in physical units.

:func:`evanescent_lamb_modes` takes a
:class:`~dispersion.continuum.layered.layered_plate.LayeredPlate` (one isotropic layer is
the Rayleigh-Lamb plate, in the same units: :math:`\\kappa = k h`, h half the thickness) and
frequencies f (kHz) or fd (MHz mm), solves at :math:`\\Omega = \\omega h / c_{ref}`
(:func:`~dispersion.continuum.layered.evanescent_modes.evanescent_modes`) and returns an
:class:`EvanescentModeTable`: per mode :math:`k = (\\kappa' + i\\kappa'')/h`, the decay
:math:`20\\log_{10}(e)\\,\\mathrm{Im}\\,k` in dB/m and over one plate thickness d.

>>> from dispersion.continuum.layered.layered_plate import layered_plate
>>> from dispersion.materials.materials import material
>>> t = evanescent_lamb_modes(layered_plate([(material("steel"), 1.0)]),
...                           frequency_khz=[1000.0], decay_db=20.0, families=("A",))
>>> [(r["mode"], r["kind"], round(r["decay [dB/thickness]"], 3)) for r in t.rows()]
[('A-e1', 'imaginary', 10.326)]
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dispersion.answers.plate_table import PlateTable, plate_frequencies
from dispersion.continuum.layered.evanescent_modes import (DB_PER_NEPER, DECAY_RANGE,
                                                          DEFAULT_DECAY, EvanescentRoots,
                                                          im_max_of)
from dispersion.errors import InputError
from dispersion.rendering import Rendered

__all__ = ["COLUMNS", "EvanescentModeTable", "evanescent_lamb_modes"]

#: Columns of :meth:`EvanescentModeTable.rows` with their units (CSV headings).
COLUMNS = ("f [kHz]", "fd [MHz mm]", "mode", "family", "kind", "Re k [rad/mm]",
           "Im k [1/mm]", "decay [dB/m]", "decay [dB/thickness]", "Re kappa", "Im kappa",
           "Omega = omega h / c_ref")


@dataclass(frozen=True, repr=False)
class EvanescentModeTable(PlateTable, Rendered):
    """Evanescent modes of one ``plate`` at the frequencies ``frequency_khz`` (``roots``:
    the dimensionless result), searched up to ``decay_db`` dB per thickness."""

    plate: object
    frequency_khz: np.ndarray
    roots: EvanescentRoots
    decay_db: float

    def title(self) -> str:
        return (f"evanescent modes, {self.plate.label()}, d = {self.thickness_mm:g} mm"
                + (f", waves at {self.plate.direction:g} deg" if self.plate.direction else ""))

    def header_lines(self) -> list[str]:
        h, c = self._scale()
        r = self.roots
        R = max(r.region.values(), default=0.0)
        return self.plate.header_lines() + [
            self._span(),
            f"kappa = k h, Omega = omega h / c_ref (h = {h * 1e3:g} mm, half the thickness; "
            f"c_ref = {c:.10g} m/s)",
            f"searched: 0 < Im kappa <= {r.im_max:.10g} (decay <= {self.decay_db:g} dB per "
            f"thickness), |Re kappa| <= R (R <= {R:.4g}, per frequency and class in JSON); "
            "one of each mirror set: Im k > 0 (decaying towards +x), Re k >= 0 (-Re k + i Im "
            "k is the same mode towards -x)",
            f"mode classes: {', '.join(r.classes)}; each root certified to 1e-10 relative "
            "by the argument principle (ball arithmetic), the number of roots in the "
            "rectangle counted the same way and compared with the list, else a failure; "
            "names: family-e and rank by Im k"]

    def columns(self) -> tuple[str, ...]:
        return COLUMNS

    def text_columns(self) -> tuple[str, ...]:
        return ("f [kHz]", "mode", "kind", "Re k [rad/mm]", "Im k [1/mm]", "decay [dB/m]",
                "decay [dB/thickness]")

    def json_extra(self) -> dict:
        r = self.roots
        return {"plate": self.plate.as_dict(), "Im kappa max": r.im_max,
                "searched": [{"f [kHz]": float(self.frequency_khz[i]), "class": cls,
                              "Re kappa max": R, "counted": r.counts[(i, cls)][0],
                              "listed": r.counts[(i, cls)][1]}
                             for (i, cls), R in r.region.items()]}

    def inputs(self) -> dict:
        f = self.frequency_khz
        return {"plate": self.plate.as_dict(), "thickness [mm]": self.thickness_mm,
                "frequencies": int(f.size), "f range [kHz]": [float(f.min()), float(f.max())],
                "decay [dB/thickness]": self.decay_db}

    def rows(self) -> list[dict]:
        """One dict per root, keys :data:`COLUMNS`."""
        r = self.roots
        h, _ = self._scale()
        h_mm = h * 1e3
        out = []
        for i in range(r.kappa.size):
            kap = complex(r.kappa[i])
            f = float(self.frequency_khz[r.index[i]])
            out.append({
                "f [kHz]": f, "fd [MHz mm]": f * self.thickness_mm * 1e-3,
                "mode": r.label[i], "family": r.family[i], "kind": r.kind[i],
                "Re k [rad/mm]": kap.real / h_mm, "Im k [1/mm]": kap.imag / h_mm,
                "decay [dB/m]": DB_PER_NEPER * kap.imag / h,
                "decay [dB/thickness]": DB_PER_NEPER * 2 * kap.imag,
                "Re kappa": kap.real, "Im kappa": kap.imag,
                "Omega = omega h / c_ref": float(r.omega[r.index[i]])})
        return out


def evanescent_lamb_modes(plate, *, frequency_khz=None, fd_mhz_mm=None, families=None,
                          decay_db: float = DEFAULT_DECAY) -> EvanescentModeTable:
    """Every evanescent mode of an undamped ``plate`` at each frequency with a decay of at
    most ``decay_db`` dB per plate thickness (in (0, 200], default 60): an
    :class:`EvanescentModeTable`. Give exactly one of ``frequency_khz`` and ``fd_mhz_mm``;
    ``families`` a subset of the plate's families (S, A, SH; L, SH; M)."""
    from dispersion.continuum.layered.evanescent_modes import evanescent_modes
    from dispersion.continuum.layered.layered_plate import LayeredPlate

    if not isinstance(plate, LayeredPlate):
        raise InputError(f"plate must be a LayeredPlate, got {type(plate).__name__}")
    if (frequency_khz is None) == (fd_mhz_mm is None):
        raise InputError("give exactly one of frequency_khz (kHz) and fd_mhz_mm (MHz mm)")
    lo_d, hi_d = DECAY_RANGE
    if isinstance(decay_db, bool) or not isinstance(decay_db, (int, float)) or not (
            lo_d < decay_db <= hi_d):
        raise InputError(f"--decay-max (dB per plate thickness) must lie in ({lo_d:g}, "
                         f"{hi_d:g}], got {decay_db!r}")
    f_khz, omega = plate_frequencies(plate, frequency_khz, fd_mhz_mm)
    roots = evanescent_modes(plate, omega, im_max=im_max_of(decay_db), families=families)
    return EvanescentModeTable(plate, f_khz, roots, float(decay_db))
