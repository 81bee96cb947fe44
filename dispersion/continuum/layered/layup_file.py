"""A layered plate from text a stranger wrote: a TOML layup file or a short layup string.

Both are data, never code: the file is read by :func:`dispersion.untrusted.read_text` (a
regular UTF-8 file within a size limit) and :func:`dispersion.untrusted.load_toml` (depth
bounded), every number is a TOML number or a string read by the whitelist reader
(:func:`dispersion.reader.read_number`: ``0.125``, ``1/8``), every name is looked up
in the tables (:func:`dispersion.materials.materials.material`, :func:`~dispersion.materials.materials.ply`).

A file::

    direction = 0                      # degrees from the plate's 0 deg axis (optional)
    damping = 0.0                      # loss factor of every layer (optional)

    [[layer]]                          # bottom up
    material = "steel"                 # a table material or a ply
    thickness = 0.71                   # mm
    [[layer]]
    material = "aluminium"
    thickness = 0.29
    angle = 0                          # ply angle, degrees (optional)

    [[interface]]                      # optional: springs above layer `below` (1-based)
    below = 1
    normal = 1e15                      # N/m^3
    shear = 5e14

or, for a laminate, ``layup = "[0/90]s"``, ``ply = "T800/913"``, ``ply_thickness = 0.125``
instead of the layers. A string: ``steel:0.71,aluminium:0.29`` (material:thickness_mm[:angle],
bottom up), or a layup such as ``[0/90]s`` with a ply and its thickness.

>>> plate = plate_from_string("steel:0.71,aluminium:0.29")
>>> [layer.solid.name for layer in plate.layers]
['steel', 'aluminium']
>>> plate_from_string("steel:0.71,unobtainium:1").layers
Traceback (most recent call last):
...
dispersion.errors.InputError: layer 2: material must be a ply (T800/913, TVR380/M12R) or one of aluminium, aluminium-rolled, brass, copper, epoxy, glass, magnesium, nickel, pmma, stainless-steel, steel, titanium; got 'unobtainium'
"""
from __future__ import annotations

from dispersion.errors import InputError
from dispersion.untrusted import printable

__all__ = ["read_layup", "plate_from_string", "plate_from_data", "solid_by_name",
           "MAX_LAYUP_BYTES", "MAX_LAYUP_DEPTH"]

#: Largest layup file read (bytes). Rule: 1000 layers of 100 bytes each.
MAX_LAYUP_BYTES = 100_000
#: Deepest nesting of its tables and arrays (a file has two levels: [[layer]] tables).
MAX_LAYUP_DEPTH = 3
_KEYS = {"direction", "damping", "layer", "interface", "layup", "ply", "ply_thickness"}
_LAYER_KEYS = {"material", "thickness", "angle"}
_INTERFACE_KEYS = {"below", "normal", "shear"}


def solid_by_name(name: str, where: str):
    """The ply or table material ``name`` as a :class:`~dispersion.materials.solid.Solid`."""
    from dispersion.materials.solid import as_solid
    from dispersion.materials.materials import MATERIALS, PLIES, material, ply

    if not isinstance(name, str):
        raise InputError(f"{where}: material must be a name, got {type(name).__name__}")
    try:
        return ply(name)
    except InputError:
        pass
    try:
        return as_solid(material(name))
    except InputError:
        raise InputError(f"{where}: material must be a ply ({', '.join(sorted(PLIES))}) or one "
                         f"of {', '.join(sorted(MATERIALS))}; got {printable(name, 40)!r}") from None


def _number(value, where: str) -> float:
    if isinstance(value, bool):
        raise InputError(f"{where} must be a number, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        from dispersion.reader import read_number

        try:
            return float(read_number(value))
        except (InputError, OverflowError) as exc:
            raise InputError(f"{where} must be a number such as 0.125 or 1/8, got "
                             f"{printable(value, 40)!r} ({exc})") from None
    raise InputError(f"{where} must be a number, got {type(value).__name__}")


def plate_from_data(data: dict, where: str = "layup"):
    """A :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate` from parsed TOML data."""
    from dispersion.continuum.layered.layered_plate import (Layer, LayeredPlate, SpringInterface,
                                                    laminate)

    if not isinstance(data, dict):
        raise InputError(f"{where}: must be a table")
    unknown = sorted(set(data) - _KEYS)
    if unknown:
        raise InputError(f"{where}: unknown key {printable(unknown[0], 40)!r} (keys: "
                         f"{', '.join(sorted(_KEYS))})")
    direction = _number(data.get("direction", 0.0), f"{where}: direction")
    damping = _number(data.get("damping", 0.0), f"{where}: damping")
    if "layup" in data:
        if "layer" in data:
            raise InputError(f"{where}: give either layup (with ply, ply_thickness) or "
                             "[[layer]] tables, not both")
        for key in ("ply", "ply_thickness"):
            if key not in data:
                raise InputError(f"{where}: layup needs {key}")
        if not isinstance(data["layup"], str):
            raise InputError(f"{where}: layup must be a string such as [0/90]s")
        plate = laminate(data["layup"], solid_by_name(data["ply"], f"{where}: ply"),
                         _number(data["ply_thickness"], f"{where}: ply_thickness"),
                         direction=direction, damping=damping)
        faces = data.get("interface", [])
    else:
        rows = data.get("layer")
        if not isinstance(rows, list) or not rows:
            raise InputError(f"{where}: needs [[layer]] tables (or layup, ply, ply_thickness)")
        layers = []
        for n, row in enumerate(rows, 1):
            at = f"{where}: layer {n}"
            if not isinstance(row, dict):
                raise InputError(f"{at}: must be a table")
            bad = sorted(set(row) - _LAYER_KEYS)
            if bad:
                raise InputError(f"{at}: unknown key {printable(bad[0], 40)!r} (keys: "
                                 f"{', '.join(sorted(_LAYER_KEYS))})")
            for key in ("material", "thickness"):
                if key not in row:
                    raise InputError(f"{at}: needs {key}")
            solid = solid_by_name(row["material"], at).with_loss(damping)
            layers.append(Layer(solid, _number(row["thickness"], f"{at}: thickness"),
                                _number(row.get("angle", 0.0), f"{at}: angle")))
        plate = LayeredPlate(tuple(layers), (), direction)
        faces = data.get("interface", [])
    springs = [None] * (len(plate.layers) - 1)
    if not isinstance(faces, list):
        raise InputError(f"{where}: interface must be a list of [[interface]] tables")
    for n, face in enumerate(faces, 1):
        at = f"{where}: interface {n}"
        if not isinstance(face, dict) or set(face) != _INTERFACE_KEYS:
            raise InputError(f"{at}: needs exactly the keys {', '.join(sorted(_INTERFACE_KEYS))}")
        below = face["below"]
        if isinstance(below, bool) or not isinstance(below, int) or not 1 <= below < len(
                plate.layers):
            raise InputError(f"{at}: below must be a layer number in [1, "
                             f"{len(plate.layers) - 1}], got {printable(below, 20)!r}")
        springs[below - 1] = SpringInterface(_number(face["normal"], f"{at}: normal"),
                                             _number(face["shear"], f"{at}: shear"))
    return LayeredPlate(plate.layers, tuple(springs), plate.direction)


def read_layup(path):
    """The plate of a TOML layup file (see the module docstring), read as untrusted data."""
    from dispersion.untrusted import load_toml, read_text

    text = read_text(path, "layup file", MAX_LAYUP_BYTES, suffix=".toml")
    shown = printable(str(path))
    return plate_from_data(load_toml(text, str(path), "layup file", MAX_LAYUP_DEPTH,
                                     MAX_LAYUP_BYTES),
                           f"layup file {shown}")


def plate_from_string(text: str, *, ply=None, ply_thickness_mm=None, direction: float = 0.0,
                      damping: float = 0.0):
    """A plate from a short string: ``material:thickness_mm[:angle],...`` bottom up, or a
    layup such as ``[0/90]s`` with ``ply`` (a name or a Solid) and ``ply_thickness_mm``."""
    from dispersion.continuum.layered.layered_plate import laminate, layered_plate

    if not isinstance(text, str) or not text.strip():
        raise InputError("layup must be a non-empty string")
    if len(text) > 2000:
        raise InputError(f"layup string must be at most 2000 characters, got {len(text)}")
    text = text.strip()
    if text.startswith("["):
        if ply is None or ply_thickness_mm is None:
            raise InputError("a layup such as [0/90]s needs a ply (--ply) and its thickness "
                             "(--ply-thickness, mm)")
        solid = solid_by_name(ply, "ply") if isinstance(ply, str) else ply
        return laminate(text, solid, ply_thickness_mm, direction=direction, damping=damping)
    if ply is not None or ply_thickness_mm is not None:
        raise InputError("--ply and --ply-thickness go with a layup such as [0/90]s, not "
                         "with material:thickness layers")
    rows = []
    for n, part in enumerate(text.split(","), 1):
        fields = part.strip().split(":")
        if len(fields) not in (2, 3):
            raise InputError(f"layer {n}: write material:thickness_mm or "
                             f"material:thickness_mm:angle, got {printable(part, 40)!r}")
        solid = solid_by_name(fields[0].strip(), f"layer {n}")
        values = [_number(f.strip(), f"layer {n}: {what}")
                  for f, what in zip(fields[1:], ("thickness", "angle"))]
        rows.append((solid, *values))
    return layered_plate(rows, direction=direction, damping=damping)
