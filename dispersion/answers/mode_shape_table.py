"""The mode shapes of one mode at one frequency: ``dispersion branches --mode-shape`` as a
function.

:func:`mode_shapes` takes a :class:`~dispersion.answers.mode_table.ModeTable` of one frequency
and a mode label (any letter case: ``a1`` is A1) and returns a :class:`ModeShapeTable`: the
displacements and stresses through the thickness of every root of that mode (a backward
branch has two), normalised as :data:`~dispersion.continuum.mode_shapes.FIELD_NORMALISATION`
says. Lamb modes (S, A) have ``u_x, u_y, sigma_xx, sigma_yy, sigma_xy``
(:func:`~dispersion.continuum.mode_shapes.exact_mode_fields`); SH modes ``u_z, sigma_yz,
sigma_xz`` (:func:`~dispersion.continuum.sh.sh_mode_shape`). The table renders itself
(:class:`dispersion.rendering.Rendered`) and draws its figure
(:func:`dispersion.plotting.lamb.figure_mode_shapes`).

>>> from dispersion.answers.mode_table import lamb_modes
>>> from dispersion.materials.materials import material
>>> shapes = mode_shapes(lamb_modes(material("steel"), 3.0, frequency_khz=200), "sh0", 5)
>>> shapes
<ModeShapeTable: SH0 mode shape, steel, d = 3 mm, nu = 0.2912, f = 200 kHz (5 rows)>
>>> [row["u_z"] for row in shapes.rows()]
[1.0, 1.0, 1.0, 1.0, 1.0]

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, 2004, sec. 8.5 (Lamb mode shapes) and ch. 9
(SH modes).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dispersion.errors import InputError
from dispersion.rendering import Rendered

__all__ = ["LAMB_FIELDS", "SH_FIELDS", "ModeShape", "ModeShapeTable", "mode_shapes"]

#: Fields of a Lamb (S, A) mode and of an SH mode, in the order of the columns.
LAMB_FIELDS = ("u_x", "u_y", "sigma_xx", "sigma_yy", "sigma_xy")
SH_FIELDS = ("u_z", "sigma_yz", "sigma_xz")


@dataclass(frozen=True)
class ModeShape:
    """One root of the mode: its frequency (kHz), wavenumber (rad/mm) and fields on ``y``."""

    f_khz: float
    k_per_mm: float
    fields: dict

    def name(self, mode: str) -> str:
        return f"{mode}, f = {self.f_khz:.6g} kHz, k = {self.k_per_mm:.6g} rad/mm"


@dataclass(frozen=True, repr=False)  # Rendered: short repr; rows, CSV, JSON from the fields
class ModeShapeTable(Rendered):
    """Fields through the thickness of every root labelled ``mode`` in ``table``."""

    table: object
    mode: str
    y_mm: np.ndarray
    shapes: tuple[ModeShape, ...]

    @property
    def field_names(self) -> tuple[str, ...]:
        return SH_FIELDS if self.mode.startswith("SH") else LAMB_FIELDS

    def title(self) -> str:
        f = self.shapes[0].f_khz
        return f"{self.mode} mode shape, {self.table.title()}, f = {f:.6g} kHz"

    def header_lines(self) -> list[str]:
        from dispersion.continuum.mode_shapes import FIELD_NORMALISATION

        head = [line for line in self.table.header_lines()
                if line.startswith(("material", "thickness"))]
        head += [f"root {i + 1}: {s.name(self.mode)}" for i, s in enumerate(self.shapes)]
        head += [f"normalisation: {FIELD_NORMALISATION} (h = {self.table.h_mm:g} mm)",
                 "u: displacement amplitude; sigma: stress amplitude (x along the plate, "
                 "y through the thickness, z across)"]
        return head

    def columns(self) -> tuple[str, ...]:
        return ("f [kHz]", "k [rad/mm]", "y [mm]", *self.field_names)

    def rows(self) -> list[dict]:
        out = []
        for s in self.shapes:
            for j, y in enumerate(self.y_mm):
                row = {"f [kHz]": s.f_khz, "k [rad/mm]": s.k_per_mm, "y [mm]": float(y)}
                row.update({key: float(s.fields[key][j]) for key in self.field_names})
                out.append(row)
        return out

    def figure_data(self) -> list[dict]:
        """Per root: ``name``, ``y [mm]`` and the field arrays (the figure's input)."""
        return [{"name": s.name(self.mode), "y [mm]": self.y_mm, **s.fields}
                for s in self.shapes]


def _label(table, mode: str) -> str:
    labels = list(dict.fromkeys(table.roots.label))
    for lab in labels:
        if lab.lower() == str(mode).strip().lower():
            return lab
    from dispersion.errors import did_you_mean

    raise InputError(f"mode must be one of the modes propagating at this frequency "
                     f"({', '.join(labels)}), got {mode!r}{did_you_mean(mode, labels)}")


def mode_shapes(table, mode: str, points: int = 41) -> ModeShapeTable:
    """Displacements and stresses of ``mode`` at the one frequency of ``table`` on ``points``
    evenly spaced y through the thickness (see the module docstring)."""
    from dispersion.continuum.mode_shapes import exact_mode_fields
    from dispersion.continuum.sh import sh_mode_shape

    if table.frequency_khz.size != 1:
        raise InputError(f"mode shapes need exactly one frequency, got "
                         f"{table.frequency_khz.size}")
    if isinstance(points, bool) or not isinstance(points, int) or not 2 <= points <= 10_001:
        raise InputError(f"points must be an integer in [2, 10001], got {points!r}")
    label = _label(table, mode)
    r = table.roots
    y = np.linspace(-1.0, 1.0, points)
    shapes = []
    for i in (i for i, lab in enumerate(r.label) if lab == label):
        kappa, W = float(r.kappa[i]), float(r.omega[r.index[i]])
        if label.startswith("SH"):
            u, du = sh_mode_shape(label, y)
            fields = {"u_z": u, "sigma_yz": du, "sigma_xz": kappa * u}
        else:
            f = exact_mode_fields(label[0], kappa, W, table.nu, y)
            fields = {key: f[key] for key in LAMB_FIELDS}
        shapes.append(ModeShape(float(table.frequency_khz[r.index[i]]), kappa / table.h_mm,
                                fields))
    return ModeShapeTable(table, label, y * table.h_mm, tuple(shapes))
