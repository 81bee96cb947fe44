"""Linear solves of the time stepper: dense LAPACK or sparse SuperLU, chosen by size.

A problem given as numpy arrays (the 1D bar up to a few hundred DOFs) runs on numpy alone:
scipy is imported only when a sparse matrix is met or a large matrix is factorized.

>>> import numpy as np
>>> from dispersion.contact.newmark import Newmark
>>> solve = LinearSolver(2, Newmark()).factor(np.array([[2.0, 0.0], [0.0, 4.0]]))
>>> solve(np.array([2.0, 2.0])).tolist()
[1.0, 0.5]
"""
from __future__ import annotations

import sys
from typing import TYPE_CHECKING

import numpy as np

from dispersion.errors import ConvergenceError

if TYPE_CHECKING:
    from dispersion.contact.newmark import Newmark

__all__ = ["DENSE_MAX", "LinearSolver", "dense", "issparse"]

#: Largest step matrix factorized with dense LAPACK; sparse SuperLU above. Chosen by
#: measurement (``python benchmarks/bench_ring.py``, table 1, 2-core machine): at the ring's
#: 144 DOFs the two factorize within 2x of each other when the machine is quiet, and
#: threaded LAPACK is up to 20x slower when it is loaded; from 408 DOFs on SuperLU wins
#: outright (0.74 vs 1.6 ms, 12 vs 74 ms at 1320). Dense stays for the bar's few dozen DOFs.
DENSE_MAX = 64


def issparse(A) -> bool:
    """True for a scipy.sparse matrix; never imports scipy (such a matrix means it is loaded).

    A problem given as numpy arrays (the 1D bar up to a few hundred DOFs) runs on numpy alone:
    scipy's import costs more than a whole small run.
    """
    sp = sys.modules.get("scipy.sparse")
    return sp is not None and sp.issparse(A)


def dense(A) -> np.ndarray:
    """``A`` as a dense float array (a scipy.sparse matrix is densified)."""
    return A.toarray() if issparse(A) else np.asarray(A, dtype=float)


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
