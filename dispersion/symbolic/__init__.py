"""The exact algebra of the patch: the ``Patch`` value (``patch.py``), the plate's matrices
(``plate.py``) and the power-balance series engine (``series_kernel.py``,
``power_balance.py``).

The basis, the material and the mass rules that lived here moved to ``splines/``,
``materials/`` and ``mass_rules/`` (issue 33, ARCHITECTURE.md); their old paths
``dispersion.symbolic.<module>`` still import, with a DeprecationWarning naming the new path
(:mod:`dispersion._moved`).
"""
from __future__ import annotations

from dispersion._moved import install, package_getattr

install()


def __getattr__(name: str):
    return package_getattr(__name__, name)
