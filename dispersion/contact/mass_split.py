"""The massive / massless split of a contact problem's DOFs (paper eqs 11-12).

Rows of a singular mass that are zero are the massless DOFs: the time stepper treats them as
algebraic equations. :class:`MassSplit` finds them, factorizes the massive block of the mass
matrix (a diagonal one is divided, not factorized) and marks the constraints that act on
massless DOFs only (their multiplier is the contact force itself, eq 12).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from dispersion.contact.linear_solver import LinearSolver
from dispersion.splines.matrix_kind import is_sparse

if TYPE_CHECKING:
    from dispersion.contact.contact_problem import ContactProblem
    from dispersion.contact.newmark_scheme import Newmark

__all__ = ["MATVEC_DENSE_MAX", "MassSplit"]

#: Largest problem whose mass and constraint matrices are kept dense for products.
MATVEC_DENSE_MAX = 400


class MassSplit:
    """Massive / massless DOF split and a factorization of the massive block of ``M``."""

    def __init__(self, prob: ContactProblem, nm: Newmark):
        if not (is_sparse(prob.M) or is_sparse(prob.G)):
            self._init_dense(prob, nm)
            return
        import scipy.sparse as sp

        M = sp.csr_matrix(prob.M)
        rowmax = np.asarray(abs(M).max(axis=1).todense()).ravel()
        self.massless = np.flatnonzero(rowmax <= 1e-14 * rowmax.max())
        self.massive = np.setdiff1d(np.arange(M.shape[0]), self.massless)
        Mmm = M[self.massive][:, self.massive]
        self.diagonal = Mmm.nnz == Mmm.shape[0] and np.all(Mmm.indices == np.arange(Mmm.shape[0]))
        if self.diagonal:
            d = Mmm.diagonal()
            self.solve = lambda b: b / d
        else:
            solver = LinearSolver(Mmm.shape[0], nm)
            self.solve = solver.factor(solver.matrix(Mmm.tocsc()))
        G = sp.csr_matrix(prob.G)
        # a constraint that acts only on massless DOFs carries lambda = mu (eq 12)
        only_massless = np.ones(G.shape[0], bool)
        for k in range(G.shape[0]):
            cols = G.indices[G.indptr[k]:G.indptr[k + 1]]
            only_massless[k] = bool(np.all(np.isin(cols, self.massless)))
        self.only_massless = only_massless
        self.M = M
        small = M.shape[0] <= MATVEC_DENSE_MAX
        self.Md = M.toarray() if small else None
        self.G = G
        self.Gd = G.toarray() if small else None
        self.f_ext = np.zeros(prob.n) if prob.f_ext is None else np.asarray(prob.f_ext, float)
        self.rows = np.zeros(prob.n, bool)  # rows whose internal force is implicit (explicit)
        self.rows[self.massless] = True

    def _init_dense(self, prob: ContactProblem, nm: Newmark):
        """The same split for a problem given as numpy arrays (no scipy)."""
        M = np.asarray(prob.M, dtype=float)
        G = np.asarray(prob.G, dtype=float).reshape(-1, M.shape[0])
        rowmax = np.abs(M).max(axis=1)
        # boolean masks, not setdiff1d/isin: those import numpy.ma, a cost a small run notices
        without_mass = rowmax <= 1e-14 * rowmax.max()
        self.massless = np.flatnonzero(without_mass)
        self.massive = np.flatnonzero(~without_mass)
        Mmm = M[np.ix_(self.massive, self.massive)]
        self.diagonal = not np.any(Mmm - np.diag(np.diag(Mmm)))
        if self.diagonal:
            d = np.diag(Mmm).copy()
            self.solve = lambda b: b / d
        else:
            solver = LinearSolver(Mmm.shape[0], nm)
            self.solve = solver.factor(solver.matrix(Mmm))
        # a constraint that acts only on massless DOFs carries lambda = mu (eq 12)
        self.only_massless = ~np.any(G[:, ~without_mass] != 0, axis=1)
        self.M, self.Md, self.G, self.Gd = M, M, G, G
        self.f_ext = np.zeros(prob.n) if prob.f_ext is None else np.asarray(prob.f_ext, float)
        self.rows = np.zeros(prob.n, bool)
        self.rows[self.massless] = True

    def a_int(self, f: np.ndarray) -> np.ndarray:
        """Internal acceleration ``M^-1 (f_ext - f)`` on the massive DOFs (0 elsewhere)."""
        a = np.zeros(len(f))
        a[self.massive] = self.solve((self.f_ext - f)[self.massive])
        return a
