"""Materials: the elastic law that travels with a patch (``elastic_law.py``), the handbook table
of isotropic solids (``materials.py``) and the plausible ranges that catch an input off by a
unit (``unit_mixups.py``).

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
