"""A set of branches that remembers the Poisson ratio it was computed at.

:class:`BranchSet` is a ``dict`` (``label -> array``) with a ``nu`` attribute, so code that
receives only ``branches.omega`` can still refuse to mix Poisson ratios
(:func:`dispersion.answers.units.physical_branches`).

>>> b = BranchSet({"S0": [0.0, 1.0]}, nu=0.3)
>>> b.nu, list(b)
(0.3, ['S0'])
"""
from __future__ import annotations

__all__ = ["BranchSet"]


class BranchSet(dict):
    """``label -> values`` computed at Poisson's ratio ``nu``."""

    def __init__(self, data=(), *, nu: float):
        super().__init__(data)
        self.nu = nu

    def __reduce__(self):  # keeps nu through pickling (parallel sweeps)
        return (_rebuild, (dict(self), self.nu))


def _rebuild(data, nu):
    return BranchSet(data, nu=nu)
