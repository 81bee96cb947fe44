"""A layered plate as a value: layers of solids, the interfaces between them, a direction.

Layers are listed from the bottom face (:math:`x_3 = 0`) up. Each :class:`Layer` is a
:class:`~dispersion.materials.solid.Solid` of thickness ``thickness_mm`` turned by ``angle``
degrees about the normal (a ply angle: the fibres, the solid's axis 1, at that angle from
the plate's 0 degree axis). Between two layers the interface is perfect (displacement and
traction continuous) or a :class:`SpringInterface` (traction continuous and proportional to
the jump of displacement: normal and shear stiffness per unit area, N/m^3). ``direction`` is
the angle of the wave's direction from the plate's 0 degree axis, so a layer enters the wave's
frame turned by ``angle - direction``.

:func:`layered_plate` builds one from ``(material, thickness_mm[, angle])`` rows;
:func:`laminate` from a layup string such as ``[0/90]s`` and one ply.

>>> from dispersion.materials.materials import material, ply
>>> plate = laminate("[0/90]s", ply("T800/913"), 0.125)
>>> [(l.angle, l.thickness_mm) for l in plate.layers]
[(0.0, 0.125), (90.0, 0.25), (0.0, 0.125)]
>>> plate.symmetric, plate.total_thickness_mm
(True, 0.5)
>>> layered_plate([(material("steel"), 0.71), (material("aluminium"), 0.29)]).symmetric
False

References
----------
A. H. Nayfeh, *Wave propagation in layered anisotropic media*, Elsevier 1995, ch. 3-4;
S. I. Rokhlin, Y. J. Wang, "Stable recursive algorithm for elastic wave propagation in
layered anisotropic media: stiffness matrix method", JASA 112 (2002) 822 (spring interfaces).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from dispersion.errors import InputError, as_real, check_positive
from dispersion.materials.solid import Solid, as_solid

__all__ = ["Layer", "SpringInterface", "LayeredPlate", "ScaledStack", "layered_plate",
           "laminate", "parse_layup", "MAX_LAYERS"]

#: Most layers of a plate. Rule: the count a practitioner's laminate reaches (GEWtool's
#: largest example has 400 plies), with room; the exact relation's cost grows linearly.
MAX_LAYERS = 1000


@dataclass(frozen=True)
class Layer:
    """One layer: a ``solid``, its ``thickness_mm`` and its ply ``angle`` (degrees)."""

    solid: Solid
    thickness_mm: float
    angle: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "solid", as_solid(self.solid))
        object.__setattr__(self, "thickness_mm", float(check_positive("layer thickness",
                                                                      self.thickness_mm)))
        angle = float(as_real("ply angle", self.angle))
        if not -360 <= angle <= 360:
            raise InputError(f"ply angle must lie in [-360, 360] degrees, got {angle}")
        object.__setattr__(self, "angle", angle)

    def describe(self) -> str:
        turn = f" at {self.angle:g} deg" if self.angle else ""
        return f"{self.thickness_mm:g} mm {self.solid.name}{turn}"


@dataclass(frozen=True)
class SpringInterface:
    """An imperfect interface: ``normal`` and ``shear`` stiffness per unit area (N/m^3),
    tractions :math:`\\sigma_{33} = K_N [u_3]`, :math:`\\sigma_{13} = K_T [u_1]`,
    :math:`\\sigma_{23} = K_T [u_2]`."""

    normal: float
    shear: float

    def __post_init__(self):
        for name in ("normal", "shear"):
            object.__setattr__(self, name, float(check_positive(f"interface {name} stiffness",
                                                                getattr(self, name))))

    def describe(self) -> str:
        return f"springs K_N {self.normal:.4g} N/m^3, K_T {self.shear:.4g} N/m^3"


@dataclass(frozen=True)
class ScaledStack:
    """The plate in the units of the numerics: lengths over ``h_m`` (half the total
    thickness), stiffness over ``mu_ref`` (Pa), density over ``rho_ref`` (kg/m^3), so that
    :math:`\\Omega = \\omega h / c_{ref}`, :math:`c_{ref} = \\sqrt{\\mu_{ref}/\\rho_{ref}}`
    and :math:`\\kappa = k h` (for one isotropic layer: the units of the Rayleigh-Lamb code).

    ``C`` (L, 6, 6) in the wave's frame, ``rho`` (L,), ``thickness`` (L,) summing to 2,
    ``springs`` (L - 1, 3) of ``(K_T, K_T, K_N)`` per interface (``inf``: perfect).
    """

    C: np.ndarray = field(repr=False)
    rho: np.ndarray
    thickness: np.ndarray
    springs: np.ndarray
    h_m: float
    mu_ref: float
    rho_ref: float

    @property
    def c_ref(self) -> float:
        return math.sqrt(self.mu_ref / self.rho_ref)

    @property
    def lossless(self) -> bool:
        return not np.iscomplexobj(self.C) or not np.any(self.C.imag != 0)

    @cached_property
    def parts(self) -> np.ndarray:
        """Each layer's constant parts of the system matrix, ``(L, 4, 6, 6)``
        (:func:`~dispersion.continuum.layered.stroh.system_parts`), computed once."""
        from dispersion.continuum.layered.stroh import system_parts

        return np.array([system_parts(C, r) for C, r in zip(self.C, self.rho)])


@dataclass(frozen=True)
class LayeredPlate:
    """``layers`` from the bottom face up, ``interfaces`` (one per pair of neighbours:
    None for perfect, or a :class:`SpringInterface`; empty: all perfect) and the wave's
    ``direction`` in degrees."""

    layers: tuple
    interfaces: tuple = ()
    direction: float = 0.0

    def __post_init__(self):
        layers = tuple(self.layers)
        if not layers:
            raise InputError("a layered plate needs at least one layer")
        if len(layers) > MAX_LAYERS:
            raise InputError(f"a layered plate has at most {MAX_LAYERS} layers, got {len(layers)}")
        if not all(isinstance(layer, Layer) for layer in layers):
            raise InputError("layers must be Layer values")
        interfaces = tuple(self.interfaces) or (None,) * (len(layers) - 1)
        if len(interfaces) != len(layers) - 1:
            raise InputError(f"a plate of {len(layers)} layers has {len(layers) - 1} "
                             f"interfaces, got {len(interfaces)}")
        if not all(i is None or isinstance(i, SpringInterface) for i in interfaces):
            raise InputError("interfaces must be None (perfect) or SpringInterface values")
        direction = float(as_real("direction", self.direction))
        if not -360 <= direction <= 360:
            raise InputError(f"direction must lie in [-360, 360] degrees, got {direction}")
        object.__setattr__(self, "layers", layers)
        object.__setattr__(self, "interfaces", interfaces)
        object.__setattr__(self, "direction", direction)

    # ------------------------------------------------------------------ properties

    @property
    def total_thickness_mm(self) -> float:
        return float(sum(layer.thickness_mm for layer in self.layers))

    def wave_frame_stiffness(self) -> list:
        """Each layer's :class:`~dispersion.materials.stiffness.Stiffness` in the wave's
        frame (turned by ``angle - direction``)."""
        return [layer.solid.stiffness.rotated(layer.angle - self.direction)
                for layer in self.layers]

    @property
    def lossless(self) -> bool:
        return all(layer.solid.stiffness.lossless for layer in self.layers)

    @property
    def symmetric(self) -> bool:
        """True if the stack is its own mirror image about the mid-plane (same solids,
        thicknesses, angles and interfaces read from the top) and every layer is monoclinic
        about its plane: its modes are symmetric or antisymmetric."""
        L = self.layers
        same = all(a.solid == b.solid and a.thickness_mm == b.thickness_mm
                   and a.angle % 360 == b.angle % 360 for a, b in zip(L, reversed(L)))
        return bool(same and self.interfaces == tuple(reversed(self.interfaces))
                    and all(s.mirror_normal() for s in self.wave_frame_stiffness()))

    @property
    def decoupled(self) -> bool:
        """True if Lamb (:math:`u_1, u_3`) and SH (:math:`u_2`) waves are apart along the
        direction (every layer symmetric about the :math:`x_1 x_3` plane in the wave's
        frame)."""
        return all(s.mirror_transverse() for s in self.wave_frame_stiffness())

    def isotropic_single(self) -> bool:
        """True for one undamped isotropic layer: the Rayleigh-Lamb plate itself."""
        return (len(self.layers) == 1 and self.lossless
                and self.layers[0].solid.stiffness.is_isotropic())

    def turned(self, direction: float) -> LayeredPlate:
        """The same plate with the wave along ``direction`` (degrees)."""
        return LayeredPlate(self.layers, self.interfaces, direction)

    def scaled(self) -> ScaledStack:
        """The plate in the units of the numerics (:class:`ScaledStack`). Reference: the
        bottom layer's density and mean out-of-plane shear modulus (C44 + C55) / 2 (for one
        isotropic layer: mu and rho, the Rayleigh-Lamb units)."""
        h_m = self.total_thickness_mm * 1e-3 / 2
        C0 = self.layers[0].solid.stiffness.array().real
        mu_ref = float((C0[3, 3] + C0[4, 4]) / 2)
        rho_ref = self.layers[0].solid.rho
        C = np.array([s.array() for s in self.wave_frame_stiffness()]) / mu_ref
        springs = np.full((len(self.layers) - 1, 3), np.inf)
        for i, face in enumerate(self.interfaces):
            if face is not None:
                springs[i] = np.array([face.shear, face.shear, face.normal]) * h_m / mu_ref
        return ScaledStack(C, np.array([layer.solid.rho for layer in self.layers]) / rho_ref,
                           np.array([layer.thickness_mm * 1e-3 for layer in self.layers]) / h_m,
                           springs, h_m, mu_ref, rho_ref)

    # ------------------------------------------------------------------ words

    def describe(self) -> str:
        """The stack in words, bottom up."""
        parts = []
        for i, layer in enumerate(self.layers):
            parts.append(layer.describe())
            if i < len(self.interfaces) and self.interfaces[i] is not None:
                parts.append(f"[{self.interfaces[i].describe()}]")
        turn = f", waves at {self.direction:g} deg" if self.direction else ""
        return f"{' / '.join(parts)} (d = {self.total_thickness_mm:g} mm{turn})"

    def label(self) -> str:
        """A short name: ``T800/913 [0/90/0] (0.125/0.25/0.125 mm)`` for plies of one solid,
        ``0.71 mm steel / 0.29 mm aluminium`` otherwise.

        >>> from dispersion.materials.materials import ply
        >>> laminate("[0/90]s", ply("T800/913"), 0.125).label()
        'T800/913 [0/90/0] (0.125/0.25/0.125 mm)'
        """
        names = {layer.solid.name for layer in self.layers}
        if len(names) == 1 and len(self.layers) > 1:
            angles = "/".join(f"{layer.angle:g}" for layer in self.layers)
            thick = "/".join(f"{layer.thickness_mm:g}" for layer in self.layers)
            return f"{names.pop()} [{angles}] ({thick} mm)"
        return " / ".join(layer.describe() for layer in self.layers)

    def header_lines(self) -> list[str]:
        lines = [f"layer {i + 1} (from the bottom): {layer.describe()}; {layer.solid.describe()}"
                 f"; source: {layer.solid.source}" for i, layer in enumerate(self.layers)]
        lines += [f"interface {i + 1}-{i + 2}: {face.describe()}"
                  for i, face in enumerate(self.interfaces) if face is not None]
        lines.append(f"thickness: d = {self.total_thickness_mm:g} mm; direction of the waves: "
                     f"{self.direction:g} deg from the plate's 0 deg axis")
        return lines

    def as_dict(self) -> dict:
        return {"layers": [{"thickness [mm]": layer.thickness_mm, "angle [deg]": layer.angle,
                            **layer.solid.as_dict()} for layer in self.layers],
                "interfaces": [None if f is None else {"K_N [N/m^3]": f.normal,
                                                       "K_T [N/m^3]": f.shear}
                               for f in self.interfaces],
                "direction [deg]": self.direction}


def layered_plate(rows, *, interfaces=(), direction: float = 0.0,
                  damping: float = 0.0) -> LayeredPlate:
    """A plate from rows ``(material, thickness_mm)`` or ``(material, thickness_mm,
    angle)``, bottom up; ``material`` a :class:`~dispersion.materials.solid.Solid` or an
    isotropic :class:`~dispersion.materials.materials.Material` with a density; ``damping`` a
    loss factor given to every layer (:meth:`~dispersion.materials.solid.Solid.with_loss`)."""
    layers = []
    for row in rows:
        if not isinstance(row, (tuple, list)) or len(row) not in (2, 3):
            raise InputError("each layer is (material, thickness_mm) or (material, "
                             "thickness_mm, angle)")
        solid = as_solid(row[0]).with_loss(damping)
        layers.append(Layer(solid, row[1], row[2] if len(row) == 3 else 0.0))
    return LayeredPlate(tuple(layers), tuple(interfaces), direction)


_ANGLE = re.compile(r"^(\u00b1|\+-|-\+|\u2213)?([+-]?\d{1,3}(?:\.\d{1,6})?)$")
_LAYUP = re.compile(r"^\[([^\[\]]{1,400})\](\d{0,3})(s?)$")
#: Most plies a layup string may expand to (before it is checked against MAX_LAYERS).
MAX_PLIES = MAX_LAYERS


def parse_layup(text: str) -> list[float]:
    """Ply angles (degrees, bottom up) of a layup string: ``[0/90]s``, ``[0/45/-45/90]2s``,
    ``[0/+-45/90]``, ``[0/90]3`` (the bracket repeated 3 times). ``s``: the stack and its
    mirror image. A whitelist of digits, signs and ``/``; nothing is evaluated.

    >>> parse_layup("[0/90]s")
    [0.0, 90.0, 90.0, 0.0]
    >>> parse_layup("[+-45]2")
    [45.0, -45.0, 45.0, -45.0]
    >>> parse_layup("[0/90")
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: layup must look like [0/90]s or [0/45/-45/90]2s (angles in degrees between / in brackets, then a repeat count and s for symmetric), got '[0/90'
    """
    if not isinstance(text, str):
        raise InputError(f"layup must be a string such as [0/90]s, got {type(text).__name__}")
    shown = text[:60]
    match = _LAYUP.match(text.strip().replace(" ", "").lower())
    if not match:
        raise InputError("layup must look like [0/90]s or [0/45/-45/90]2s (angles in degrees "
                         "between / in brackets, then a repeat count and s for symmetric), "
                         f"got {shown!r}")
    angles = []
    for word in match.group(1).split("/"):
        m = _ANGLE.match(word)
        if not m:
            raise InputError(f"layup angle must be a number of degrees such as 45, -45 or "
                             f"+-45, got {word[:20]!r} in {shown!r}")
        value = float(m.group(2))
        if abs(value) > 360:
            raise InputError(f"layup angle must lie in [-360, 360], got {value:g}")
        angles += [value, -value] if m.group(1) in ("\u00b1", "+-") else \
            [-value, value] if m.group(1) else [value]
    repeat = int(match.group(2) or 1)
    if repeat < 1:
        raise InputError(f"layup repeat count must be at least 1, got {repeat}")
    total = len(angles) * repeat * (2 if match.group(3) else 1)
    if total > MAX_PLIES:
        raise InputError(f"layup {shown!r} has {total} plies, more than {MAX_PLIES}")
    angles = angles * repeat
    if match.group(3):
        angles = angles + angles[::-1]
    return [a + 0.0 for a in angles]


def laminate(layup: str, ply, ply_thickness_mm: float, *, direction: float = 0.0,
             damping: float = 0.0) -> LayeredPlate:
    """A laminate of one ply ``ply`` (a Solid, fibres along its axis 1) of thickness
    ``ply_thickness_mm`` per ply, angles from :func:`parse_layup` (bottom up). Neighbouring
    plies of the same angle are one layer (the same plate, fewer interfaces)."""
    solid = as_solid(ply).with_loss(damping)
    t = float(check_positive("ply thickness", ply_thickness_mm))
    merged: list[list] = []
    for angle in parse_layup(layup):
        if merged and merged[-1][1] % 360 == angle % 360:
            merged[-1][0] += t
        else:
            merged.append([t, angle])
    return LayeredPlate(tuple(Layer(solid, thick, angle) for thick, angle in merged), (),
                        direction)
