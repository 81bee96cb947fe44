"""The mode shapes of one mode at one frequency: ``dispersion branches --mode-shape`` as a
function.

:func:`mode_shapes` takes a :class:`~dispersion.answers.mode_table.ModeTable` of one frequency
and a mode label (any letter case: ``a1`` is A1) and returns a :class:`ModeShapeTable`: the
displacements and stresses through the thickness of every root of that mode (a backward
branch has two), normalised as :data:`~dispersion.continuum.mode_shapes.FIELD_NORMALISATION`
says. Lamb modes (S, A) have ``u_x, u_y, sigma_xx, sigma_yy, sigma_xy``
(:func:`~dispersion.continuum.mode_shapes.exact_mode_fields`); SH modes ``u_z, sigma_yz,
sigma_xz`` (:func:`~dispersion.continuum.sh.sh_mode_shape`). A layered plate's table
(:func:`layered_mode_shapes`) has every displacement and stress of a mode, real and imaginary
parts, its energy densities and power flow, in physical units, on the samples of each
sublayer, with the layers. The table renders itself
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

__all__ = ["LAMB_FIELDS", "SH_FIELDS", "LAYERED_FIELDS", "AMPLITUDE_UM", "ModeShape",
           "ModeShapeTable", "mode_shapes", "layered_mode_shapes"]

#: Fields of a Lamb (S, A) mode and of an SH mode, in the order of the columns.
LAMB_FIELDS = ("u_x", "u_y", "sigma_xx", "sigma_yy", "sigma_xy")
SH_FIELDS = ("u_z", "sigma_yz", "sigma_xz")


@dataclass(frozen=True)
class ModeShape:
    """One root of the mode: its frequency (kHz), wavenumber (rad/mm) and fields on ``y``;
    ``y_mm``: its own points through the thickness where they are not the table's (a
    layered plate's root samples its own sublayers)."""

    f_khz: float
    k_per_mm: float
    fields: dict
    y_mm: np.ndarray | None = None

    def points(self, table_y: np.ndarray) -> np.ndarray:
        """Its points through the thickness (mm)."""
        return table_y if self.y_mm is None else self.y_mm

    def name(self, mode: str) -> str:
        return f"{mode}, f = {self.f_khz:.6g} kHz, k = {self.k_per_mm:.6g} rad/mm"


@dataclass(frozen=True, repr=False)  # Rendered: short repr; rows, CSV, JSON from the fields
class ModeShapeTable(Rendered):
    """Fields through the thickness of every root labelled ``mode`` in ``table``.

    An isotropic plate's table leaves the last fields at their defaults. A layered plate's
    (:func:`mode_shapes` of a
    :class:`~dispersion.answers.layered_mode_table.LayeredModeTable`) names its ``fields``
    (columns with units), its ``notes`` (header lines: amplitude, energy velocity), the
    ``layers`` ``(name, z_bottom_mm, z_top_mm)`` bottom up, the through-thickness ``axis``,
    the columns of the text table ``text_fields`` and the figure's ``panels`` ``(x label,
    fields)``."""

    table: object
    mode: str
    y_mm: np.ndarray
    shapes: tuple[ModeShape, ...]
    fields: tuple = ()
    notes: tuple = ()
    layers: tuple = ()
    axis: str = "y [mm]"
    text_fields: tuple = ()
    panels: tuple = ()

    @property
    def field_names(self) -> tuple[str, ...]:
        if self.fields:
            return self.fields
        return SH_FIELDS if self.mode.startswith("SH") else LAMB_FIELDS

    def title(self) -> str:
        f = self.shapes[0].f_khz
        return f"{self.mode} mode shape, {self.table.title()}, f = {f:.6g} kHz"

    def header_lines(self) -> list[str]:
        if self.layers:
            head = [line for line in self.table.header_lines()
                    if line.startswith(("layer", "interface", "thickness"))]
        else:
            head = [line for line in self.table.header_lines()
                    if line.startswith(("material", "thickness"))]
        head += [f"root {i + 1}: {s.name(self.mode)}" for i, s in enumerate(self.shapes)]
        if self.notes:
            return head + list(self.notes)
        from dispersion.continuum.mode_shapes import FIELD_NORMALISATION

        head += [f"normalisation: {FIELD_NORMALISATION} (h = {self.table.h_mm:g} mm)",
                 "u: displacement amplitude; sigma: stress amplitude (x along the plate, "
                 "y through the thickness, z across)"]
        return head

    def columns(self) -> tuple[str, ...]:
        return ("f [kHz]", "k [rad/mm]", self.axis, *self.field_names)

    def text_columns(self) -> tuple[str, ...]:
        if not self.text_fields:
            return self.columns()
        if len(self.shapes) > 1:    # the roots of a backward pair: k tells them apart
            return ("k [rad/mm]", self.axis, *self.text_fields)
        return (self.axis, *self.text_fields)

    def rows(self) -> list[dict]:
        out = []
        for s in self.shapes:
            for j, y in enumerate(s.points(self.y_mm)):
                row = {"f [kHz]": s.f_khz, "k [rad/mm]": s.k_per_mm, self.axis: float(y)}
                row.update({key: np.asarray(s.fields[key])[j].item()
                            for key in self.field_names})
                out.append(row)
        return out

    def json_extra(self) -> dict:
        if not self.layers:
            return {}
        return {"layers": [{"name": n, "z from [mm]": lo, "z to [mm]": hi}
                           for n, lo, hi in self.layers]}

    def figure_data(self) -> list[dict]:
        """Per root: ``name``, the axis (``y [mm]``, a layered plate's ``z [mm]``) and the
        field arrays (the figure's input)."""
        return [{"name": s.name(self.mode), self.axis: s.points(self.y_mm), **s.fields}
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
    evenly spaced y through the thickness (see the module docstring); a layered plate's
    table (:class:`~dispersion.answers.layered_mode_table.LayeredModeTable`): see
    :func:`layered_mode_shapes` (``points`` does not apply: each sublayer's own samples)."""
    from dispersion.continuum.mode_shapes import exact_mode_fields
    from dispersion.continuum.sh import sh_mode_shape

    if table.frequency_khz.size != 1:
        raise InputError(f"mode shapes need exactly one frequency, got "
                         f"{table.frequency_khz.size}")
    if hasattr(table, "plate"):
        return layered_mode_shapes(table, mode)
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


#: The amplitude of a layered plate's mode in its table: the largest displacement component
#: (real where it is largest). Stresses scale with it, energy and power with its square.
AMPLITUDE_UM = 1.0
#: Columns of a layered plate's mode (u in um, stresses in MPa, energies in J/m^3, power in
#: W/m^2): the real part (the field at x = 0, t = 0) and the imaginary part (a quarter period
#: later, up to its sign) of each amplitude.
_U = ("u1", "u2", "u3")
_S = ("s11", "s22", "s33", "s23", "s13", "s12")
LAYERED_FIELDS = ("layer", *(f"{p} {c} [um]" for c in _U for p in ("Re", "Im")),
                  *(f"{p} {c} [MPa]" for c in _S for p in ("Re", "Im")),
                  "e_kin [J/m^3]", "e_str [J/m^3]", "P1 [W/m^2]", "P2 [W/m^2]")


def layered_mode_shapes(table, mode: str) -> ModeShapeTable:
    """The mode ``mode`` of a :class:`~dispersion.answers.layered_mode_table.LayeredModeTable`
    at its one frequency through the thickness
    (:func:`~dispersion.continuum.layered.layered_mode_shapes.root_shape`), in physical
    units for an amplitude of :data:`AMPLITUDE_UM`: displacements (x1 along the waves, x2
    across, x3 through the thickness), the six stresses, the time-averaged kinetic and
    strain energy densities and the power flow density along (P1) and across (P2) the
    waves; the energy velocity and skew angle in the header. ``z`` from the mid-plane; a
    point on an interface appears once in each layer (the in-plane stresses jump there)."""
    from dispersion.continuum.layered.layered_mode_shapes import root_shape

    label = _label(table, mode)
    plate, r = table.plate, table.roots
    st = plate.scaled()
    h_mm = st.h_m * 1e3
    a = AMPLITUDE_UM * 1e-6 / st.h_m                 # the amplitude in units of h
    bounds = np.concatenate([[0.0], np.cumsum([layer.thickness_mm for layer in plate.layers])])
    bounds -= bounds[-1] / 2
    shapes, notes = [], []
    # every root of the name (two: a backward wave and its forward twin), each on the points
    # of its own sublayers
    for i in (i for i, lab in enumerate(r.label) if lab == label):
        s = root_shape(plate, r, i)
        z = s.z * h_mm
        # the faces and interfaces where the sublayers' sums of thicknesses round next to them
        near = np.abs(z[:, None] - bounds[None, :]) <= 1e-12 * h_mm
        z = np.where(near.any(axis=1), bounds[np.argmax(near, axis=1)], z)
        u = s.u * AMPLITUDE_UM
        sig = s.stress * st.mu_ref * a / 1e6
        fields = {"layer": s.layer + 1}
        for j, c in enumerate(_U):
            fields[f"Re {c} [um]"], fields[f"Im {c} [um]"] = u[j].real, u[j].imag
        for j, c in enumerate(_S):
            fields[f"Re {c} [MPa]"], fields[f"Im {c} [MPa]"] = sig[j].real, sig[j].imag
        e = st.mu_ref * a**2
        fields.update({"e_kin [J/m^3]": s.kinetic * e, "e_str [J/m^3]": s.strain * e,
                       "P1 [W/m^2]": s.flow[0] * e * st.c_ref,
                       "P2 [W/m^2]": s.flow[1] * e * st.c_ref})
        # + 0.0: no "-0.0" in the tables (a vanishing field's rounded sign means nothing)
        fields = {key: val + 0.0 if key != "layer" else val for key, val in fields.items()}
        kap = complex(s.kappa)
        shapes.append(ModeShape(float(table.frequency_khz[r.index[i]]), kap.real / h_mm,
                                fields, z))
        c_e = s.energy_velocity * st.c_ref
        along = (f"c_g = {s.group * st.c_ref:.10g} m/s" if s.group is not None else
                 f"Im k = {kap.imag / h_mm:.10g} rad/mm")
        notes.append(f"root {len(shapes)}: energy velocity c_e = {c_e[0]:.10g} m/s along the "
                     f"waves, {c_e[1]:.10g} m/s across (skew {s.skew_degrees:.6g} deg); "
                     f"{along}")
    layers = tuple((f"{n + 1}: {layer.describe()}", float(bounds[n]), float(bounds[n + 1]))
                   for n, layer in enumerate(plate.layers))
    notes += [f"amplitude: the largest displacement component {AMPLITUDE_UM:g} um, real where "
              "it is largest; Re: the field at x = 0, t = 0, Im: a quarter period later "
              "(u e^(i(k x - omega t)))",
              "x1 along the waves, x2 across, x3 (z) through the thickness from the mid-plane; "
              "s: stress; e_kin, e_str: time-averaged kinetic and strain energy densities; "
              "P1, P2: time-averaged power flow density along and across the waves"
              + ("; damped: the time averages at x = 0 (the wave decays along x1), c_e the "
                 "power over the energy through the thickness (Bernard, Lowe and Deschamps "
                 "2001)" if table.damped else ""),
              "interfaces at z = " + ", ".join(f"{b:.6g}" for b in bounds[1:-1]) + " mm"
              if len(bounds) > 2 else "one layer"]
    panels = (("displacement [um] (Re solid, Im dashed)",
               tuple(k for k in LAYERED_FIELDS if k.endswith("[um]"))),
              ("stress [MPa] (Re solid, Im dashed)",
               tuple(k for k in LAYERED_FIELDS if k.endswith("[MPa]"))),
              ("energy density [J/m^3]", ("e_kin [J/m^3]", "e_str [J/m^3]")),
              ("power flow density [W/m^2]", ("P1 [W/m^2]", "P2 [W/m^2]")))
    text = ("layer", *(k for k in LAYERED_FIELDS if k.endswith("[um]")), "e_kin [J/m^3]",
            "e_str [J/m^3]", "P1 [W/m^2]")
    return ModeShapeTable(table, label, shapes[0].y_mm, tuple(shapes), LAYERED_FIELDS,
                          tuple(notes), layers,
                          "z [mm]", text, panels)
