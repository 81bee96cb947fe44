"""The practitioner's table: every propagating mode of a plate at given frequencies, in units.

:func:`lamb_modes` takes a :class:`~dispersion.materials.materials.Material`, the thickness d (mm)
and frequencies f (kHz) or frequency-thickness products fd (MHz mm); it solves at
:math:`\\Omega = \\pi f d / c_T` (:func:`dispersion.continuum.frequency.modes_at_frequency`, every
root certified by a count) and returns a :class:`ModeTable` of S, A and SH modes with

.. math::

    k = \\kappa / h, \\quad c_p = \\frac{\\omega}{k} = \\frac{\\Omega}{\\kappa} c_T, \\quad
    c_g = \\frac{d\\Omega}{d\\kappa} c_T, \\quad \\lambda = \\frac{2\\pi}{k},

cut-off frequencies and zero-group-velocity points. The material fixes nu for the whole
computation. Rows, CSV and JSON headings are rendered from the table (``COLUMNS``).

>>> from dispersion.materials.materials import material
>>> t = lamb_modes(material("steel"), 3.0, frequency_khz=[200.0])
>>> [(r["mode"], round(r["c_p [m/s]"], 1), round(r["c_g [m/s]"], 1)) for r in t.rows()]
[('S0', 5414.6, 5374.3), ('A0', 2023.3, 3059.2), ('SH0', 3235.0, 3235.0)]

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, 2004, ch. 8-9; A. Huber, Dispersion Calculator
(DLR), user manual (columns of its exports).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.errors import InputError, check_positive
from dispersion.rendering import Rendered
from dispersion.continuum.frequency import FREQUENCY_OMEGA_MAX, FREQUENCY_OMEGA_MIN, FrequencyRoots
from dispersion.materials.materials import Material

__all__ = ["COLUMNS", "ModeTable", "lamb_modes"]

#: Columns of :meth:`ModeTable.rows` with their units (CSV headings).
COLUMNS = ("f [kHz]", "fd [MHz mm]", "mode", "family", "k [rad/mm]", "c_p [m/s]",
           "c_g [m/s]", "wavelength [mm]", "kappa = kh", "Omega = omega h / c_T")


@dataclass(frozen=True, repr=False)  # Rendered: a short repr; text, CSV, JSON from the rows
class ModeTable(Rendered):
    """Modes of one plate (``material``, ``thickness_mm``) at the frequencies ``frequency_khz``.

    ``roots`` holds the dimensionless result; its ``nu`` is the material's.
    """

    material: Material
    thickness_mm: float
    frequency_khz: np.ndarray
    roots: FrequencyRoots

    @property
    def nu(self) -> float:
        return self.roots.nu

    @property
    def h_mm(self) -> float:
        return self.thickness_mm / 2

    def title(self) -> str:
        """Material, thickness and nu, for captions and headers."""
        return f"{self.material.name}, d = {self.thickness_mm:g} mm, nu = {self.nu:.4f}"

    def header_lines(self) -> list[str]:
        """The inputs in words with units, the cut-offs and the ZGV points (CSV ``#`` lines)."""
        f = self.frequency_khz
        span = (f"{f.size} frequencies from {f.min():.10g} to {f.max():.10g} kHz" if f.size > 1
                else f"f = {f[0]:.10g} kHz")
        lines = [f"material: {self.material.describe()}",
                 f"material source: {self.material.source}",
                 f"thickness: d = 2h = {self.thickness_mm:g} mm", f"frequency: {span}",
                 "kappa = k h, Omega = omega h / c_T (h: half the thickness); family S, A, SH"]
        lines += [f"cut-off {lab}: {f_c:.10g} kHz" for lab, f_c in self.cutoffs_khz().items()]
        lines += [f"ZGV {p['mode']}: f = {p['f [kHz]']:.10g} kHz, fd = {p['fd [MHz mm]']:.10g}"
                  f" MHz mm, c_p = {p['c_p [m/s]']:.10g} m/s" for p in self.zgv()]
        return lines

    def columns(self) -> tuple[str, ...]:
        return COLUMNS

    def text_columns(self) -> tuple[str, ...]:
        return ("f [kHz]", "mode", "k [rad/mm]", "c_p [m/s]", "c_g [m/s]", "wavelength [mm]")

    def json_extra(self) -> dict:
        return {"cutoffs [kHz]": self.cutoffs_khz(), "zgv": self.zgv()}

    def _khz(self, Omega):
        return np.asarray(Omega, dtype=float) * self.material.c_T / (2 * math.pi * self.h_mm)

    def rows(self) -> list[dict]:
        """One dict per root, keys :data:`COLUMNS` (floats; family ``"S"``, ``"A"``, ``"SH"``)."""
        r, cT = self.roots, self.material.c_T
        f = self.frequency_khz[r.index]
        out = []
        for i in range(r.kappa.size):
            k = float(r.kappa[i]) / self.h_mm
            out.append({
                "f [kHz]": float(f[i]), "fd [MHz mm]": float(f[i]) * self.thickness_mm * 1e-3,
                "mode": r.label[i], "family": r.label[i].rstrip("0123456789?"),
                "k [rad/mm]": k, "c_p [m/s]": float(r.omega[r.index[i]] / r.kappa[i]) * cT,
                "c_g [m/s]": float(r.group[i]) * cT, "wavelength [mm]": 2 * math.pi / k,
                "kappa = kh": float(r.kappa[i]), "Omega = omega h / c_T":
                float(r.omega[r.index[i]])})
        return out

    def at_cutoff_khz(self) -> list[tuple[float, str]]:
        """``(f [kHz], mode)`` of every mode whose cut-off is a requested frequency: k = 0,
        c_p infinite there, so it is not among the propagating rows (say so when rendering)."""
        return [(float(self._khz(self.roots.omega[i])), lab) for i, lab in self.roots.at_cutoff]

    def cutoffs_khz(self) -> dict[str, float]:
        """Cut-off frequency (kHz) of every mode that has one up to the highest frequency."""
        return {lab: float(self._khz(w)) for lab, w in self.roots.cutoffs.items() if w > 0}

    def zgv(self) -> list[dict]:
        """Zero-group-velocity points: mode, f [kHz], fd [MHz mm], c_p [m/s], wavelength."""
        from dispersion.answers.units import zgv_in_units

        return zgv_in_units(self.roots.zgv, self.material, self.thickness_mm)

    def failures(self) -> list[dict]:
        """Frequencies whose roots a count did not certify, with the reason."""
        return [{"f [kHz]": float(self._khz(w)), "family": kind, "reason": why}
                for w, kind, why in self.roots.failures]

    def inputs(self) -> dict:
        """Inputs as plain data (CSV ``#`` header, JSON ``inputs``)."""
        f = self.frequency_khz
        return {"material": self.material.as_dict(), "thickness [mm]": self.thickness_mm,
                "frequencies": int(f.size), "f range [kHz]": [float(f.min()), float(f.max())]}

    def curves(self) -> dict[str, dict[str, np.ndarray]]:
        """Per mode, arrays ordered along the branch (by kappa): ``f, fd, c_p, c_g, k``.

        A backward branch (two roots of one label at one frequency) stays one curve, through
        its zero-group-velocity point when that lies within the frequencies.
        """
        rows = self.rows()
        f_lo, f_hi = float(self.frequency_khz.min()), float(self.frequency_khz.max())
        for p in self.zgv():
            if f_lo <= p["f [kHz]"] <= f_hi:
                rows.append({**p, "c_g [m/s]": 0.0, "k [rad/mm]": 2 * math.pi
                             / p["wavelength [mm]"]})
        out: dict[str, dict[str, list]] = {}
        for row in rows:
            d = out.setdefault(row["mode"], {"f": [], "fd": [], "c_p": [], "c_g": [], "k": []})
            for key, col in (("f", "f [kHz]"), ("fd", "fd [MHz mm]"), ("c_p", "c_p [m/s]"),
                             ("c_g", "c_g [m/s]"), ("k", "k [rad/mm]")):
                d[key].append(row[col])
        curves = {}
        for lab, d in out.items():
            order = np.argsort(d["k"])
            curves[lab] = {key: np.asarray(v)[order] for key, v in d.items()}
        return curves


def lamb_modes(material: Material, thickness_mm: float, *, frequency_khz=None,
               fd_mhz_mm=None, kinds=("S", "A", "SH"), zgv: bool = True) -> ModeTable:
    """Every propagating mode of the plate at each frequency (see the module docstring).

    Give exactly one of ``frequency_khz`` (f in kHz) and ``fd_mhz_mm`` (f d in MHz mm);
    a scalar, a list or an array. Frequencies must lie where
    :math:`\\Omega = \\pi f d / c_T` is in [:data:`~dispersion.continuum.frequency.FREQUENCY_OMEGA_MIN`,
    :data:`~dispersion.continuum.frequency.FREQUENCY_OMEGA_MAX`]; the message gives that range
    in kHz for the plate.
    """
    from dispersion.continuum.frequency import modes_at_frequency

    if not isinstance(material, Material):
        raise InputError(f"material must be a Material (dispersion.materials.materials), got "
                         f"{type(material).__name__}")
    thickness_mm = float(check_positive("thickness", thickness_mm))
    if (frequency_khz is None) == (fd_mhz_mm is None):
        raise InputError("give exactly one of frequency_khz (kHz) and fd_mhz_mm (MHz mm)")
    name = "frequency_khz" if fd_mhz_mm is None else "fd_mhz_mm"
    raw = frequency_khz if fd_mhz_mm is None else fd_mhz_mm
    try:
        values = np.atleast_1d(np.asarray(raw, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number or a list of numbers, got {raw!r}") from None
    if values.ndim != 1 or values.size == 0:
        raise InputError(f"{name} must be a number or a non-empty 1-d list")
    f_khz = values if fd_mhz_mm is None else values * 1e3 / thickness_mm
    h_m = thickness_mm * 1e-3 / 2
    omega = 2 * math.pi * f_khz * 1e3 * h_m / material.c_T
    lo, hi = (w * material.c_T / (2 * math.pi * h_m) * 1e-3
              for w in (FREQUENCY_OMEGA_MIN, FREQUENCY_OMEGA_MAX))
    bad = ~np.isfinite(omega) | (omega < FREQUENCY_OMEGA_MIN) | (omega > FREQUENCY_OMEGA_MAX)
    if np.any(bad):
        from dispersion.materials.unit_mixups import frequency_mixup, unit_mixups

        scale = 1.0 if fd_mhz_mm is None else thickness_mm * 1e-3
        unit = "kHz" if fd_mhz_mm is None else "MHz mm"
        mu = material.shear_modulus
        hints = unit_mixups(thickness_mm=thickness_mm, c_L=material.c_L, c_T=material.c_T,
                            rho=material.rho,
                            E_gpa=None if mu is None else 2 * mu * (1 + material.nu) / 1e9)
        if fd_mhz_mm is None and not hints:
            hints = frequency_mixup(float(f_khz[bad][0]), lo, hi)
        raise InputError(f"{name} must lie in [{lo * scale:.4g}, {hi * scale:.4g}] {unit} for "
                         f"this plate ({material.name}, d = {thickness_mm:g} mm), got "
                         f"{float(values[bad][0]):.6g} {unit}" + "".join(f"; {h}" for h in hints))
    roots = modes_at_frequency(material.nu_exact, omega, kinds=tuple(kinds), zgv=zgv)
    return ModeTable(material, thickness_mm, f_khz, roots)
