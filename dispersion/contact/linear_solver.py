"""Linear solves of the time stepper: dense LAPACK or sparse SuperLU, chosen by size.

A problem given as numpy arrays (the 1D bar up to a few hundred DOFs) runs on numpy alone:
scipy is imported only when a sparse matrix is met or a large matrix is factorized.

>>> import numpy as np
>>> from dispersion.contact.newmark_scheme import Newmark
>>> solve = LinearSolver(2, Newmark()).factor(np.array([[2.0, 0.0], [0.0, 4.0]]))
>>> solve(np.array([2.0, 2.0])).tolist()
[1.0, 0.5]
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dispersion.errors import ConvergenceError
from dispersion.splines.matrix_kind import dense

if TYPE_CHECKING:
    from dispersion.contact.newmark_scheme import Newmark

__all__ = ["LinearSolver"]

class LinearSolver:
    """Linear solves of one problem: dense LAPACK or sparse SuperLU, chosen by size."""

    def __init__(self, n_unknowns: int, nm: Newmark):
        self.dense = nm.solver == "dense" or (nm.solver == "auto" and n_unknowns <= nm.dense_max)

    def matrix(self, A):
        if self.dense:
            return dense(A)
        import scipy.sparse as sp

        return sp.csc_matrix(A)

    def solve(self, A, b):
        try:
            if self.dense:
                return np.linalg.solve(A, b)
            import scipy.sparse.linalg as spla

            return spla.spsolve(A, b)
        except (RuntimeError, np.linalg.LinAlgError, ValueError) as exc:  # SuperLU, LAPACK
            raise ConvergenceError(f"singular or non-finite step matrix ({exc}); the scene's "
                                   "scale is beyond double precision") from None

    def factor(self, A):
        try:
            if self.dense:
                # a few dozen unknowns: one product with the inverse beats any solve call
                inv = np.linalg.inv(dense(A))
                return lambda b: inv @ b
            import scipy.sparse.linalg as spla

            return spla.splu(A).solve
        except (RuntimeError, np.linalg.LinAlgError, ValueError) as exc:  # SuperLU, LAPACK
            raise ConvergenceError(f"singular or non-finite step matrix ({exc}); the scene's "
                                   "scale is beyond double precision") from None
