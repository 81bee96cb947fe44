"""Slowness curves of a layered or anisotropic plate: every mode at one frequency over the
direction of the waves in the plate's plane.

:func:`slowness_curves` turns the plate (:meth:`~dispersion.continuum.layered.layered_plate.
LayeredPlate.turned`) to each angle :math:`\\theta` and solves it at the one frequency
(:func:`dispersion.continuum.layered.layered_modes.layered_modes`: every root found by SAFE,
polished on the exact relation, counted and certified, as in the mode table), with the
energy velocity of each root
(:func:`dispersion.continuum.layered.layered_mode_shapes.energy_velocities`). A row is one
mode at one angle:

.. math::

    s = \\frac{1}{c_p} = \\frac{k}{\\omega}, \\quad c_g = \\frac{d\\omega}{dk}\\Big|_\\theta,
    \\quad \\psi = \\arctan\\frac{c_{e2}}{c_{e1}}, \\quad |c_e| = \\sqrt{c_{e1}^2 + c_{e2}^2},

the slowness :math:`s(\\theta)` drawn in polar form is the slowness curve; the energy flows
along its normal, at the skew angle :math:`\\psi` from the waves' direction. Names are the
family's at each angle (S, A and SH along the plies of a symmetric cross-ply, S and A between
them, where SH couples in): a curve is followed by its points, not by its name.

>>> from dispersion.continuum.layered.layered_plate import layered_plate
>>> from dispersion.materials.materials import material
>>> t = slowness_curves(layered_plate([(material("steel"), 0.71), (material("aluminium"), 0.29)]),
...                     500.0, [0.0, 45.0])
>>> sorted({round(r["slowness [s/km]"], 6) for r in t.rows() if r["mode"] == "L0"})
[0.550767]

References
----------
B. A. Auld, *Acoustic fields and waves in solids*, vol. 1, 2nd ed., Krieger 1990, ch. 7
(slowness surfaces; the energy velocity along their normal).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.defaults import MAX_ANGLES
from dispersion.errors import InputError
from dispersion.rendering import Rendered

__all__ = ["COLUMNS", "MAX_ANGLES", "SlownessTable", "slowness_curves"]

#: Columns of :meth:`SlownessTable.rows` with their units.
COLUMNS = ("angle [deg]", "mode", "family", "k [rad/mm]", "c_p [m/s]", "slowness [s/km]",
           "c_g [m/s]", "skew [deg]", "c_e [m/s]", "wavelength [mm]", "kappa = kh",
           "Omega = omega h / c_ref")


@dataclass(frozen=True, repr=False)
class SlownessTable(Rendered):
    """Every mode of ``plate`` at ``frequency_khz`` at each of ``angles`` (degrees);
    ``roots[i]`` and ``energy[i]`` (n, 2: energy velocity along and across the waves, units
    of c_ref) at ``angles[i]``."""

    plate: object
    frequency_khz: float
    angles: np.ndarray
    roots: tuple
    energy: tuple

    @property
    def failures(self) -> tuple:
        return tuple(f"angle {a:g} deg, class {cls}: {why}"
                     for a, r in zip(self.angles, self.roots) for _, cls, why in r.failures)

    def title(self) -> str:
        return (f"Slowness of {self.plate.label()}, d = {self.plate.total_thickness_mm:g} mm, "
                f"at f = {self.frequency_khz:.10g} kHz")

    def header_lines(self) -> list[str]:
        a = self.angles
        st = self.plate.scaled()
        plate = self.plate.header_lines()[:-1]    # its own direction is not this table's
        return plate + [
            f"thickness: d = {self.plate.total_thickness_mm:g} mm; directions of the waves: "
            f"{a.size} from {a.min():g} to {a.max():g} deg from the plate's 0 deg axis",
            f"f = {self.frequency_khz:.10g} kHz (Omega = {self._omega():.10g}; h = "
            f"{st.h_m * 1e3:g} mm, c_ref = {st.c_ref:.10g} m/s)",
            "every root certified to 1e-12 relative (ball arithmetic) and counted "
            "(Wittrick-Williams), else a failure; slowness = 1 / c_p; c_g along the waves; "
            "skew: the energy's flow from the waves' direction (towards +90 deg); c_e: the "
            "energy velocity's magnitude; names are the families' at each angle"]

    def _omega(self) -> float:
        st = self.plate.scaled()
        return 2 * math.pi * self.frequency_khz * 1e3 * st.h_m / st.c_ref

    def columns(self) -> tuple[str, ...]:
        return COLUMNS

    def text_columns(self) -> tuple[str, ...]:
        return ("angle [deg]", "mode", "c_p [m/s]", "slowness [s/km]", "c_g [m/s]",
                "skew [deg]", "c_e [m/s]")

    def inputs(self) -> dict:
        return {"plate": self.plate.turned(0.0).as_dict(), "f [kHz]": self.frequency_khz,
                "angles [deg]": [float(a) for a in self.angles]}

    def json_extra(self) -> dict:
        return {"plate": self.plate.turned(0.0).as_dict()}

    def rows(self) -> list[dict]:
        st = self.plate.scaled()
        h_mm, c = st.h_m * 1e3, st.c_ref
        W = self._omega()
        out = []
        for a, r, e in zip(self.angles, self.roots, self.energy):
            for i in range(len(r.label)):
                kap = float(r.kappa[i])
                c_p = W / kap * c
                out.append({
                    "angle [deg]": float(a), "mode": r.label[i], "family": r.family[i],
                    "k [rad/mm]": kap / h_mm, "c_p [m/s]": c_p, "slowness [s/km]": 1e3 / c_p,
                    "c_g [m/s]": float(r.group[i]) * c,
                    "skew [deg]": math.degrees(math.atan2(e[i, 1], e[i, 0])),
                    "c_e [m/s]": math.hypot(e[i, 0], e[i, 1]) * c,
                    "wavelength [mm]": 2 * math.pi * h_mm / kap, "kappa = kh": kap,
                    "Omega = omega h / c_ref": W})
        return out

    def points(self) -> dict[str, dict[str, np.ndarray]]:
        """Per family: ``angle`` (degrees), ``slowness`` (s/km) and ``mode`` of every root, for
        a polar figure."""
        out: dict[str, dict[str, list]] = {}
        for row in self.rows():
            d = out.setdefault(row["family"], {"angle": [], "slowness": [], "mode": []})
            d["angle"].append(row["angle [deg]"])
            d["slowness"].append(row["slowness [s/km]"])
            d["mode"].append(row["mode"])
        return {fam: {k: np.asarray(v) for k, v in d.items()} for fam, d in out.items()}


def slowness_curves(plate, frequency_khz: float, angles, *, families=None) -> SlownessTable:
    """Every propagating mode of an undamped ``plate`` at ``frequency_khz`` for waves along
    each of ``angles`` (degrees from the plate's 0 deg axis, at most :data:`MAX_ANGLES`):
    a :class:`SlownessTable`. ``families``: as in
    :func:`~dispersion.answers.layered_mode_table.layered_lamb_modes`."""
    from dispersion.continuum.layered.layered_mode_shapes import energy_velocities
    from dispersion.continuum.layered.layered_modes import OMEGA_RANGE, layered_modes
    from dispersion.continuum.layered.layered_plate import LayeredPlate

    if not isinstance(plate, LayeredPlate):
        raise InputError(f"plate must be a LayeredPlate, got {type(plate).__name__}")
    if not plate.lossless:
        raise InputError("slowness curves of a damped plate are not computed (its energy "
                         "velocity is not); give an undamped plate")
    try:
        f = float(frequency_khz)
        a = np.atleast_1d(np.asarray(angles, dtype=float))
    except (TypeError, ValueError):
        raise InputError("frequency_khz must be one number and angles numbers (degrees)") \
            from None
    if not math.isfinite(f) or f <= 0:
        raise InputError(f"frequency_khz must be one finite number > 0, got {frequency_khz!r}")
    if a.ndim != 1 or not 1 <= a.size <= MAX_ANGLES or not np.all(np.abs(a) <= 360):
        raise InputError(f"angles must be 1 to {MAX_ANGLES} directions in [-360, 360] "
                         "degrees")
    st = plate.scaled()
    W = 2 * math.pi * f * 1e3 * st.h_m / st.c_ref
    lo, hi = OMEGA_RANGE
    if not lo <= W <= hi:
        k = st.c_ref / (2 * math.pi * st.h_m) * 1e-3
        raise InputError(f"frequency_khz must lie in [{lo * k:.4g}, {hi * k:.4g}] kHz for this "
                         f"plate (d = {plate.total_thickness_mm:g} mm), got {f:.6g}")
    roots, energy = [], []
    for angle in a:
        turned = plate.turned(float(angle))
        r = layered_modes(turned, [W], families=families)
        e = energy_velocities(turned, r)
        if turned.decoupled:     # no power crosses the waves, by symmetry (round-off aside)
            e[:, 1] = 0.0
        roots.append(r)
        energy.append(e)
    return SlownessTable(plate, f, a, tuple(roots), tuple(energy))
