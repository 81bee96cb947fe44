"""The practitioner's table of a layered or anisotropic plate: every mode at given frequencies.

:func:`layered_lamb_modes` takes a :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate`
and frequencies f (kHz) or frequency-thickness products fd (MHz mm, d the total thickness);
it solves at :math:`\\Omega = \\omega h / c_{ref}`
(:func:`dispersion.continuum.layered.layered_modes.layered_modes`: every root found by SAFE,
polished on the exact relation, counted and certified) and returns a
:class:`LayeredModeTable` with

.. math::

    k = \\kappa / h, \\quad c_p = \\frac{\\omega}{k}, \\quad c_g = \\frac{d\\omega}{dk}, \\quad
    \\lambda = \\frac{2\\pi}{k}.

A plate of one undamped isotropic layer is the Rayleigh-Lamb plate: it is answered by the
isotropic calculator (:func:`dispersion.answers.mode_table.lamb_modes`) from the same numbers,
so its table is today's, byte for byte.

>>> from dispersion.continuum.layered.layered_plate import layered_plate
>>> from dispersion.materials.materials import material
>>> plate = layered_plate([(material("steel"), 0.71), (material("aluminium"), 0.29)])
>>> t = layered_lamb_modes(plate, frequency_khz=[500.0])
>>> [(r["mode"], round(r["c_p [m/s]"], 1)) for r in t.rows()]
[('L0', 1815.6), ('SH0', 3222.2), ('L1', 5423.7)]
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.answers.plate_table import PlateTable, plate_frequencies
from dispersion.continuum.layered.layered_modes import LayeredRoots
from dispersion.errors import InputError
from dispersion.rendering import Rendered

__all__ = ["COLUMNS", "LayeredModeTable", "layered_lamb_modes"]

#: Columns of :meth:`LayeredModeTable.rows` with their units (CSV headings).
COLUMNS = ("f [kHz]", "fd [MHz mm]", "mode", "family", "k [rad/mm]", "c_p [m/s]",
           "c_g [m/s]", "skew [deg]", "wavelength [mm]", "kappa = kh", "Omega = omega h / c_ref")
#: ... of a damped plate: the attenuation, and the energy velocity instead of the group
#: velocity (which a complex wavenumber does not have): power over energy through the
#: thickness at x = 0 (Bernard, Lowe and Deschamps 2001).
DAMPED_COLUMNS = ("f [kHz]", "fd [MHz mm]", "mode", "family", "k [rad/mm]",
                  "attenuation [dB/m]", "c_p [m/s]", "c_e [m/s]", "skew [deg]",
                  "wavelength [mm]", "kappa = kh", "Im kappa", "Omega = omega h / c_ref")


@dataclass(frozen=True, repr=False)
class LayeredModeTable(PlateTable, Rendered):
    """Modes of one layered ``plate`` at the frequencies ``frequency_khz`` (``roots``: the
    dimensionless result)."""

    plate: object
    frequency_khz: np.ndarray
    roots: LayeredRoots
    #: Skew angle of each root (degrees): the energy's flow from the waves' direction
    #: (:func:`~dispersion.continuum.layered.layered_mode_shapes.skew_angles`); None if damped.
    skew: np.ndarray | None = None
    #: Zero-group-velocity points ``(label, kappa, Omega)`` up to a little above the highest
    #: frequency, when asked for (:func:`~dispersion.continuum.layered.layered_zgv.zgv_points`).
    zgv_points: tuple = ()
    #: Omega up to which the ZGV points were searched (None: not asked for).
    zgv_limit: float | None = None
    #: A damped plate's energy velocity (n, 2) along and across the waves (units of c_ref;
    #: :func:`~dispersion.continuum.layered.layered_mode_shapes.energy_velocities`).
    energy_velocity: np.ndarray | None = None

    @property
    def damped(self) -> bool:
        """True for a damped plate (complex wavenumbers)."""
        return not self.plate.lossless

    def title(self) -> str:
        return (f"{self.plate.label()}, d = {self.thickness_mm:g} mm"
                + (f", waves at {self.plate.direction:g} deg" if self.plate.direction else ""))

    def header_lines(self) -> list[str]:
        h, c = self._scale()
        lines = self.plate.header_lines() + [
            self._span(),
            f"kappa = k h, Omega = omega h / c_ref (h = {h * 1e3:g} mm, half the thickness; "
            f"c_ref = {c:.10g} m/s, the bottom layer's shear speed sqrt((C44 + C55) / 2 rho))",
            (f"mode classes: {', '.join(self.roots.classes)}; every root certified to 1e-12 "
             "relative (ball arithmetic) and counted (Wittrick-Williams), else a failure; "
             "c_g along the waves' direction, skew: the angle of the energy's flow from it "
             "(towards +90 deg)"
             if not self.damped else
             f"mode classes: {', '.join(self.roots.classes)}; damped: each complex root "
             "followed from the undamped plate's (its name) and certified to 1e-10 relative "
             "by the argument principle in ball arithmetic, else a failure; attenuation "
             "20 log10(e) Im k; c_e: the energy velocity along the waves, time-averaged "
             "power over time-averaged energy through the thickness at x = 0 (Bernard, Lowe "
             "and Deschamps 2001; c_g as the loss vanishes), skew: the angle of that power "
             "from the waves' direction (towards +90 deg)")]
        lines += [f"cut-off {lab}: {f_c:.10g} kHz" for lab, f_c in self.cutoffs_khz().items()]
        lines += [f"ZGV {p['mode']}: f = {p['f [kHz]']:.10g} kHz, fd = {p['fd [MHz mm]']:.10g}"
                  f" MHz mm, c_p = {p['c_p [m/s]']:.10g} m/s" for p in self.zgv()]
        if self.zgv_limit is not None and not self.zgv_points:
            lines.append(f"ZGV points: none up to {self._khz(self.zgv_limit):.10g} kHz")
        return lines

    def columns(self) -> tuple[str, ...]:
        return DAMPED_COLUMNS if self.damped else COLUMNS

    def text_columns(self) -> tuple[str, ...]:
        if self.damped:
            skew = () if self.plate.decoupled else ("skew [deg]",)
            return ("f [kHz]", "mode", "k [rad/mm]", "attenuation [dB/m]", "c_p [m/s]",
                    "c_e [m/s]", *skew, "wavelength [mm]")
        skew = () if self.plate.decoupled else ("skew [deg]",)
        return ("f [kHz]", "mode", "k [rad/mm]", "c_p [m/s]", "c_g [m/s]", *skew,
                "wavelength [mm]")

    def json_extra(self) -> dict:
        searched = ({} if self.zgv_limit is None
                    else {"zgv searched up to [kHz]": self._khz(self.zgv_limit)})
        return {"cutoffs [kHz]": self.cutoffs_khz(), "zgv": self.zgv(), **searched,
                "plate": self.plate.as_dict()}

    def inputs(self) -> dict:
        f = self.frequency_khz
        return {"plate": self.plate.as_dict(), "thickness [mm]": self.thickness_mm,
                "frequencies": int(f.size), "f range [kHz]": [float(f.min()), float(f.max())]}

    def rows(self) -> list[dict]:
        """One dict per root, keys :data:`COLUMNS`."""
        r = self.roots
        h, c = self._scale()
        h_mm = h * 1e3
        f = self.frequency_khz[r.index]
        out = []
        if self.damped:
            from dispersion.continuum.layered.damped_modes import DB_PER_NEPER

            for i in range(r.kappa.size):
                kap = complex(r.kappa[i])
                k = kap.real / h_mm
                out.append({
                    "f [kHz]": float(f[i]), "fd [MHz mm]": float(f[i]) * self.thickness_mm * 1e-3,
                    "mode": r.label[i], "family": r.family[i], "k [rad/mm]": k,
                    "attenuation [dB/m]": DB_PER_NEPER * kap.imag / h,
                    "c_p [m/s]": float(r.omega[r.index[i]]) / kap.real * c,
                    **self._energy(i, c),
                    "wavelength [mm]": 2 * math.pi / k, "kappa = kh": kap.real,
                    "Im kappa": kap.imag, "Omega = omega h / c_ref": float(r.omega[r.index[i]])})
            return out
        for i in range(r.kappa.size):
            k = float(r.kappa[i]) / h_mm
            out.append({
                "f [kHz]": float(f[i]), "fd [MHz mm]": float(f[i]) * self.thickness_mm * 1e-3,
                "mode": r.label[i], "family": r.family[i], "k [rad/mm]": k,
                "c_p [m/s]": float(r.omega[r.index[i]] / r.kappa[i]) * c,
                "c_g [m/s]": float(r.group[i]) * c,
                "skew [deg]": None if self.skew is None else float(self.skew[i]),
                "wavelength [mm]": 2 * math.pi / k,
                "kappa = kh": float(r.kappa[i]),
                "Omega = omega h / c_ref": float(r.omega[r.index[i]])})
        return out

    def _energy(self, i: int, c: float) -> dict:
        """A damped root's ``c_e [m/s]`` and ``skew [deg]`` (0 for a decoupled plate)."""
        if self.energy_velocity is None:
            return {"c_e [m/s]": None, "skew [deg]": None}
        along, across = self.energy_velocity[i]
        skew = 0.0 if self.plate.decoupled else math.degrees(math.atan2(across, along))
        return {"c_e [m/s]": float(along) * c, "skew [deg]": skew}

    def cutoffs_khz(self) -> dict[str, float]:
        """Cut-off frequency (kHz) of every mode that has one up to the highest frequency,
        and the next of each family."""
        return {lab: self._khz(w) for lab, w in self.roots.cutoffs.items() if w > 0}

    def zgv(self) -> list[dict]:
        """Zero-group-velocity points (when asked for): mode, f [kHz], fd [MHz mm], c_p [m/s],
        wavelength [mm], as the isotropic table lists them."""
        h, c = self._scale()
        out = []
        for lab, kap, W in self.zgv_points:
            f = self._khz(W)
            out.append({"mode": lab, "f [kHz]": f, "fd [MHz mm]": f * self.thickness_mm * 1e-3,
                        "c_p [m/s]": W / kap * c, "wavelength [mm]": 2 * math.pi * h * 1e3 / kap})
        return out

    def curves(self) -> dict[str, dict[str, np.ndarray]]:
        """Per mode, arrays ordered by k: ``f, fd, c_p, c_g, k`` (as
        :meth:`dispersion.answers.mode_table.ModeTable.curves`)."""
        out: dict[str, dict[str, list]] = {}
        for row in self.rows():
            d = out.setdefault(row["mode"], {"f": [], "fd": [], "c_p": [], "c_g": [], "k": []})
            for key, col in (("f", "f [kHz]"), ("fd", "fd [MHz mm]"), ("c_p", "c_p [m/s]"),
                             ("c_g", "c_g [m/s]"), ("k", "k [rad/mm]")):
                d[key].append(row.get(col, math.nan))   # damped: no c_g (nan, not drawn)
        curves = {}
        for lab, d in out.items():
            order = np.argsort(d["k"])
            curves[lab] = {key: np.asarray(v)[order] for key, v in d.items()}
        return curves


def _isotropic_material(solid):
    """The isotropic :class:`~dispersion.materials.materials.Material` of an undamped isotropic
    solid: the one it was made from, else one from its speeds."""
    from dispersion.materials.materials import Material

    if solid.origin is not None:
        return solid.origin
    lam, mu = solid.stiffness.lame()
    return Material(math.sqrt((lam + 2 * mu) / solid.rho), math.sqrt(mu / solid.rho),
                    solid.rho, solid.name, solid.source)


def layered_lamb_modes(plate, *, frequency_khz=None, fd_mhz_mm=None, families=None,
                       zgv: bool = False):
    """Every propagating mode of ``plate`` at each frequency: a :class:`LayeredModeTable`
    (or, for one undamped isotropic layer, the isotropic calculator's
    :class:`~dispersion.answers.mode_table.ModeTable`). Give exactly one of ``frequency_khz``
    and ``fd_mhz_mm``; ``families`` a subset of the plate's families (S, A, SH; L, SH; M);
    ``zgv``: also the zero-group-velocity points of an undamped layered plate up to 5 % above
    the highest frequency (a SAFE scan in kappa closed on the exact branches: seconds)."""
    from dispersion.continuum.layered.layered_plate import LayeredPlate

    if not isinstance(plate, LayeredPlate):
        raise InputError(f"plate must be a LayeredPlate, got {type(plate).__name__}")
    if (frequency_khz is None) == (fd_mhz_mm is None):
        raise InputError("give exactly one of frequency_khz (kHz) and fd_mhz_mm (MHz mm)")
    if plate.isotropic_single():   # undamped: isotropic_single() is False for a damped layer
        from dispersion.answers.mode_table import lamb_modes

        kinds = ("S", "A", "SH") if families is None else tuple(families)
        material = _isotropic_material(plate.layers[0].solid)
        return lamb_modes(material, plate.total_thickness_mm, frequency_khz=frequency_khz,
                          fd_mhz_mm=fd_mhz_mm, kinds=kinds)
    f_khz, omega = plate_frequencies(plate, frequency_khz, fd_mhz_mm)
    if not plate.lossless:
        from dispersion.continuum.layered.damped_modes import damped_modes
        from dispersion.continuum.layered.layered_mode_shapes import energy_velocities

        roots = damped_modes(plate, omega, families=families)
        return LayeredModeTable(plate, f_khz, roots,
                                energy_velocity=energy_velocities(plate, roots))
    from dispersion.continuum.layered.layered_mode_shapes import skew_angles
    from dispersion.continuum.layered.layered_modes import layered_modes

    roots = layered_modes(plate, omega, families=families)
    points, limit = (), None
    if zgv:
        from dispersion.continuum.layered.layered_zgv import zgv_points

        fams = set(roots.family)
        limit = 1.05 * float(omega.max())
        points = tuple(p for p in zgv_points(plate, limit)
                       if p[0].rstrip("0123456789") in fams)
    return LayeredModeTable(plate, f_khz, roots, skew_angles(plate, roots), points, limit)
