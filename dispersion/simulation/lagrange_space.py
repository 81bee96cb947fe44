"""Moved: the C0 Lagrange space is a basis of the splines wing
(:mod:`dispersion.splines.lagrange_space`); this path keeps working."""
from dispersion.splines.lagrange_space import NodalSpace1D

__all__ = ["NodalSpace1D"]
