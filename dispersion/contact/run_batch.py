"""K runs of contact problems that step together: their operators side by side.

The time stepper (:mod:`.newmark`) advances the states of K runs as ``(K, n)`` arrays: K
problems with the same DOF layout (the same number of DOFs and constraints, the same
massless DOFs), each with its own matrices, gap, step size and number of steps (a ring
scene at several sizes, landing angles, step sizes and round-off perturbations). Products
with the mass and constraint matrices are batched matrix products, the internal force one
block-diagonal evaluation (:class:`~.elastic_forces.ElasticForces`); what differs per run
(a factorized tangent, an active contact set) is solved run by run. A single run is the
batch K = 1: one code path.
"""
from __future__ import annotations

import numpy as np

from typing import TYPE_CHECKING

from dispersion.errors import InputError
from dispersion.contact.contact_problem import ContactProblem
from dispersion.contact.mass_split import MassSplit
from dispersion.splines.matrix_kind import is_sparse

if TYPE_CHECKING:  # pragma: no cover
    from dispersion.contact.newmark_scheme import Newmark

__all__ = ["RunBatch"]


def _stack_or_none(arrays):
    return None if any(a is None for a in arrays) else np.stack(arrays)


def _block(matrices):
    """The block-diagonal matrix of ``matrices`` (sparse if any of them is, as scipy's; the
    dense ones of a problem given as numpy arrays stay numpy)."""
    if any(is_sparse(m) for m in matrices):
        import scipy.sparse as sp

        return sp.block_diag([sp.csr_matrix(m) for m in matrices], format="csr")
    rows = sum(np.shape(m)[0] for m in matrices)
    cols = sum(np.shape(m)[1] for m in matrices)
    out = np.zeros((rows, cols))
    r = c = 0
    for m in matrices:
        m = np.asarray(m, dtype=float)
        out[r:r + m.shape[0], c:c + m.shape[1]] = m
        r, c = r + m.shape[0], c + m.shape[1]
    return out


def _diagonal(M) -> np.ndarray | None:
    """The diagonal of ``M`` if ``M`` is diagonal (a lumped mass), else None (never imports
    scipy: a problem given as numpy arrays runs on numpy alone)."""
    if is_sparse(M):
        import scipy.sparse as sp

        M = sp.csr_matrix(M)
        if M.nnz == 0 or not np.all(M.indices == np.repeat(np.arange(M.shape[0]),
                                                            np.diff(M.indptr))):
            return None
        return M.diagonal()
    M = np.asarray(M)
    d = np.diag(M)
    return d.copy() if not np.any(M - np.diag(d)) else None


class RunBatch:
    """The runs ``probs`` (with their :class:`~.mass_split.MassSplit` ``splits``) and step
    sizes ``dts``: stacked operators and the per-run pieces of one batched step."""

    def __init__(self, probs: list[ContactProblem], splits: list[MassSplit], nm: Newmark,
                 dts):
        first, s0 = probs[0], splits[0]
        for p, s in zip(probs, splits):
            if (p.n != first.n or p.G.shape[0] != first.G.shape[0]
                    or not np.array_equal(s.massless, s0.massless)
                    or not np.array_equal(s.only_massless, s0.only_massless)
                    or (p.K is None) != (first.K is None)):
                raise InputError("runs stepped together need the same DOF layout: the same "
                                 "number of DOFs and constraints, the same massless DOFs and "
                                 "all linear or all nonlinear")
        self.probs, self.splits, self.nm = list(probs), list(splits), nm
        self.K, self.n, self.nc = len(probs), first.n, first.G.shape[0]
        self.massive, self.massless = s0.massive, s0.massless
        self.rows, self.only_massless = s0.rows, s0.only_massless
        self.dt = np.asarray(dts, dtype=float)
        self.c1 = 2.0 / self.dt**2 if nm.explicit else 1.0 / (nm.beta * self.dt**2)
        self.f_ext = np.stack([s.f_ext for s in splits])
        self.no_ext = not self.f_ext.any()
        self.g0 = np.stack([np.asarray(p.g0, dtype=float) for p in probs])
        # products: a diagonal mass elementwise; one run by its own (dense when small)
        # matrices; several runs by one block-diagonal sparse product
        full_diag = [_diagonal(s.M) for s in splits]
        self.mass_full_diagonal = _stack_or_none(full_diag)
        if self.K == 1:
            self._M = splits[0].Md if splits[0].Md is not None else splits[0].M
            self._G = splits[0].Gd if splits[0].Gd is not None else splits[0].G
            self._GT = self._G.T
        else:
            self._M = _block([s.M for s in splits])
            self._G = _block([s.G for s in splits])
            self._GT = self._G.T.tocsr() if is_sparse(self._G) else self._G.T
        diag = [getattr(s, "mass_diagonal", None) for s in splits]
        self.mass_diagonal = _stack_or_none(diag)
        dirs = [p.directions for p in probs]
        self.directions = None if dirs[0] is None else np.stack(dirs)
        # a linear problem's strain energy u.K u / 2 for all runs at once
        self._K = None
        if first.K is not None:
            self._K = first.K if self.K == 1 else _block([p.K for p in probs])
        forces = [p.forces for p in probs]
        self.forces = None
        if all(f is not None for f in forces):
            from dispersion.contact.elastic_forces import ElasticForces

            self.forces = ElasticForces.stack(forces)

    def subset(self, keep: np.ndarray) -> RunBatch:
        """The batch of the runs ``keep`` (indices), e.g. without those that finished."""
        return RunBatch([self.probs[k] for k in keep], [self.splits[k] for k in keep],
                        self.nm, self.dt[keep])

    # ------------------------------------------------------------------ products
    def mass(self, X: np.ndarray) -> np.ndarray:
        """``M_k x_k`` for every run (``X``: ``(K, n)``)."""
        if self.mass_full_diagonal is not None:
            return X * self.mass_full_diagonal
        return (self._M @ X.reshape(-1)).reshape(self.K, self.n)

    def gap(self, U: np.ndarray) -> np.ndarray:
        """``g0_k + G_k u_k`` for every run (``(K, nc)``)."""
        return self.g0 + (self._G @ U.reshape(-1)).reshape(self.K, self.nc)

    def contact_force(self, Mu: np.ndarray) -> np.ndarray:
        """``G_k^T mu_k`` for every run (``(K, n)``)."""
        return (self._GT @ Mu.reshape(-1)).reshape(self.K, self.n)

    def mass_solve(self, B: np.ndarray) -> np.ndarray:
        """``M_mm^-1 b_k`` on the massive DOFs of every run (``B``: ``(K, n_massive)``)."""
        if self.mass_diagonal is not None:
            return B / self.mass_diagonal
        return np.stack([s.solve(b) for s, b in zip(self.splits, B)])

    def force(self, U: np.ndarray):
        """Internal forces ``(K, n)`` and what :meth:`strain_energy` needs to give the
        strain energies at ``U`` later (None where the problems cannot)."""
        if self.forces is not None:
            return self.forces.force(U)
        f = [p.force(u) if p.force is not None else p.internal(u)[0]
             for p, u in zip(self.probs, U)]
        return np.stack([np.asarray(x, dtype=float) for x in f]), None

    def strain_energy(self, strains, U: np.ndarray) -> np.ndarray:
        """Strain energies ``(K,)`` at ``U``, from the strains :meth:`force` returned there
        when it did (no second evaluation), as ``u.K u / 2`` for linear problems, else from
        the problems' energies."""
        if strains is not None:
            return self.forces.energy(strains)
        if self._K is not None:
            return 0.5 * np.add.reduce(U * (self._K @ U.reshape(-1)).reshape(U.shape), axis=1)
        return np.array([float(p.energy(u)) for p, u in zip(self.probs, U)])
