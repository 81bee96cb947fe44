"""What one explicit step pays for the mass: a division, or a solve with a factorization made once.

The scalar mass of the strip (:class:`~dispersion.simulation.strip_mesh.StripMesh`) acts on
both displacement components alike. Its massless points (zero rows, the singular rules) are
set apart: the explicit scheme treats their DOFs as algebraic equations (paper eq 12),
:math:`\\mathbf 0 = \\mathbf f^{ext}_m - \\mathbf f^{int}_m`, solved each step with the
stiffness block :math:`K_{mm}` (factorized once). On the massive points:

* **diagonal** (the rule states it, or the matrix measured on this mesh is diagonal): the
  step divides by the diagonal;
* **banded** (the rule states that its *inverse* mass is a known banded matrix, the
  approximate dual S of Nguyen et al. 2023): the step multiplies by it;
* **factorized** otherwise: the massive block is factorized once by SuperLU
  (``scipy.sparse.linalg.splu``, natural ordering: the x-major numbering keeps the band,
  symmetric mode) and every step solves with it, both components as two right-hand sides.
  CHOLMOD (scikit-sparse) has no wheel for this platform and does not build from PyPI without
  SuiteSparse's headers, so it is not used;
* **dense** (the rule states a dense stiffness: the dual basis of the inverted Gram matrix,
  Held et al. 2023): the step multiplies by the dense :math:`M^{-1} K`, formed once; it is
  what that rule costs (the bounds of :mod:`dispersion.simulation.run_cost` count it).

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> from dispersion.simulation.strip_mesh import strip_mesh
>>> op = mass_operator(strip_mesh(plan_strip(Strip(p=1, mass="singular-lumped", travel=1,
...                                                stations=2, elements_per_wavelength=3))))
>>> op.kind, op.massless.size > 0
('diagonal', True)

References
----------
X. S. Li, "An overview of SuperLU", ACM TOMS 31 (2005) 302-325. Paper eqs (11)-(12).
"""
from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from dispersion.errors import ConvergenceError

__all__ = ["MassOperator", "mass_operator"]


@dataclass(frozen=True, repr=False)
class MassOperator:
    """Solve with the massive block of the mass: ``solve(B)`` for ``B`` of shape
    ``(n_massive, 2)``; ``kind`` is ``"diagonal"`` or ``"factorized"``, ``why`` says which
    statement or measurement chose it; ``diagonal`` holds the massive diagonal (diagonal
    kind); ``factor_nnz`` the stored entries of the factors; ``seconds`` the factorization."""

    kind: str
    why: str
    massive: np.ndarray
    massless: np.ndarray
    diagonal: np.ndarray | None
    solve: Callable
    factor_nnz: int
    seconds: float
    #: The dense step operator :math:`M^{-1} K` and the load's :math:`M^{-1} g` (dense kind).
    dense: np.ndarray | None = None
    dense_load: np.ndarray | None = None

    @property
    def nbytes(self) -> int:
        """Bytes the operator holds (a diagonal, the factors' or the banded inverse's values
        and indices, or the dense operator)."""
        if self.kind == "diagonal":
            return int(self.diagonal.nbytes)
        if self.kind == "dense":
            return int(self.dense.nbytes)
        return int(self.factor_nnz * 12 + 8 * (self.massive.size + 1) * 2)

    def __repr__(self) -> str:
        return (f"MassOperator({self.kind}: {self.massive.size} massive, "
                f"{self.massless.size} massless points)")


def _is_diagonal(M) -> bool:
    M = M.tocsr()
    rows = np.repeat(np.arange(M.shape[0]), np.diff(M.indptr))
    return bool(np.all(M.indices[M.data != 0] == rows[M.data != 0]))


def mass_operator(mesh) -> MassOperator:
    """The mass operator of a :class:`~dispersion.simulation.strip_mesh.StripMesh`."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    stiffness, stated_mass = mesh.step_kind
    t0 = time.perf_counter()
    if stated_mass == "banded":
        S = mesh.mass_inverse.tocsr()
        return MassOperator("banded", "stated: the inverse mass is a known banded matrix",
                            np.arange(S.shape[0]), np.zeros(0, dtype=int), None,
                            lambda B: S @ B, int(S.nnz), time.perf_counter() - t0)
    M = mesh.mass.tocsr()
    massless = np.asarray(mesh.massless, dtype=int)
    massive = np.setdiff1d(np.arange(M.shape[0]), massless)
    Mrr = M[massive][:, massive].tocsr()
    if stiffness == "dense":
        return _dense(mesh, M, massless, t0)
    stated = stated_mass == "diagonal"
    if stated and not _is_diagonal(Mrr):
        from dispersion.errors import InputError

        raise InputError(f"mass rule {mesh.rule.name!r} states a diagonal mass, but its mass "
                         "on the strip is not diagonal")
    if stated or _is_diagonal(Mrr):
        d = Mrr.diagonal().copy()
        if np.any(d <= 0):
            raise ConvergenceError(f"mass rule {mesh.rule.name!r}: a massive point has a "
                                   "non-positive diagonal mass; the explicit step cannot divide")
        why = "stated diagonal" if stated else "diagonal on this mesh (not stated by the rule)"
        return MassOperator("diagonal", why, massive, massless, d,
                            lambda B: B / d[:, None], 0, time.perf_counter() - t0)
    try:
        lu = spla.splu(sp.csc_matrix(Mrr), permc_spec="NATURAL", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
    except RuntimeError as exc:
        raise ConvergenceError(f"mass rule {mesh.rule.name!r}: the massive block is singular "
                               f"({exc})") from None
    seconds = time.perf_counter() - t0
    return MassOperator("factorized", "not diagonal: SuperLU factorization made once",
                        massive, massless, None, lu.solve, int(lu.L.nnz + lu.U.nnz), seconds)


def _dense(mesh, M, massless, t0) -> MassOperator:
    """The dense step operator :math:`M^{-1}K` of a rule whose stiffness is dense."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    from dispersion.errors import InputError

    if massless.size:
        raise InputError(f"mass rule {mesh.rule.name!r}: a dense stiffness with massless DOFs "
                         "is not run")
    lu = spla.splu(sp.csc_matrix(M), permc_spec="NATURAL", diag_pivot_thresh=0.0,
                   options={"SymmetricMode": True})
    n = M.shape[0]
    K = mesh.K.toarray()  # interleaved rows 2i + c: solve each component's rows with M
    D = lu.solve(K.reshape(n, -1)).reshape(2 * n, 2 * n)
    g = np.zeros(2 * n)
    g[mesh.load_dofs] = mesh.load_values
    Dg = lu.solve(g.reshape(n, 2)).ravel()
    return MassOperator("dense", "stated: a dense stiffness, M^-1 K formed once and applied "
                        "every step", np.arange(n), massless, None, lambda B: lu.solve(B),
                        int(lu.L.nnz + lu.U.nnz), time.perf_counter() - t0, D, Dg)
