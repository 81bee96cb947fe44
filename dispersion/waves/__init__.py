"""The old home of the branches, split by issue 33 into ``continuum/``, ``discretization/``,
``time_stepping/``, ``answers/`` and ``materials/`` (ARCHITECTURE.md maps every module).

``dispersion.waves.<module>`` still imports, with a DeprecationWarning naming the new path
(:mod:`dispersion._moved`).
"""
from __future__ import annotations

from dispersion._moved import install, package_getattr

install()


def __getattr__(name: str):
    return package_getattr(__name__, name)
