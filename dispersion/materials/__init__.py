"""Materials: the elastic law that travels with a patch (``elastic_law.py``), the handbook table
of solids (``materials.py``: isotropic solids and fibre-composite plies), the plausible ranges
that catch an input off by a unit (``unit_mixups.py``), the 6x6 stiffness in Voigt notation
(``stiffness.py``: isotropic, transversely isotropic, orthotropic or any, rotated about the
plate's normal, complex moduli for damping) and a solid (``solid.py``: a stiffness with its
density, name and source, the value each layer of a plate is made of).

``dispersion.materials`` named the table module before issue 33; this face hands on that
module's names (``dispersion.materials.MATERIALS``), loading it on first use.

Layers and the map of moved modules: ARCHITECTURE.md.
"""
from __future__ import annotations

import importlib


def __getattr__(name: str):
    if name.startswith("__"):
        raise AttributeError(name)
    table = importlib.import_module(f"{__name__}.materials")
    if name in table.__all__:
        return getattr(table, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
