"""Moved: the C0 Lagrange space is the finite patch's
(:mod:`dispersion.discretization.lagrange_space`); this path keeps working."""
from dispersion.discretization.lagrange_space import NodalSpace1D

__all__ = ["NodalSpace1D"]
