"""dispersion: grid dispersion of B-spline plate patches and singular mass matrices.

Follows Tkachuk, Matzen, Kolman, Bischoff, "Singular mass matrices for isogeometric
finite element analysis of dynamic contact".
"""
from .errors import ConvergenceError, DispersionError, IndefiniteMassWarning, InputError

__all__ = ["DispersionError", "InputError", "ConvergenceError", "IndefiniteMassWarning"]
__version__ = "0.1.0"
