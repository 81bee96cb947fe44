"""The pencil of a finite patch: :math:`K x = \\omega^2 M x` on the DOFs its ends leave.

From the assembled patch (:func:`~dispersion.discretization.finite_mesh.finite_assembly.assemble`):

* the DOFs of a ``"fixed"`` end (the whole end column) and the :math:`u_x` of a
  ``"sliding"`` end are removed, rows and columns, from K and from the Galerkin mass; a rule
  known by its banded inverse S keeps it banded: :math:`(S^{-1})_{rr}^{-1} = S_{rr} - S_{rc}
  S_{cc}^{-1} S_{cr}` (Hiemstra et al. 2025, :func:`dispersion.mass_rules.approximate_dual.dirichlet_dual`);
* an outlier-removal method (:mod:`dispersion.discretization.finite_mesh.outlier_removal`) changes K and
  M or restricts them to a subspace :math:`x = Z y`;
* the massless DOFs (zero rows of M: the singular rules) are named; the solvers condense
  them, :math:`\\hat K = K_{rr} - K_{rm} K_{mm}^{-1} K_{mr}`, as the explicit scheme solves
  them.

>>> from dispersion.discretization.finite_mesh.finite_patch import finite_bar
>>> pen = mesh_pencil(finite_bar(2, 8, ends="fixed", mass="lumped"))
>>> pen.size, pen.massless.size            # 10 functions, the two end ones removed
(8, 0)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

__all__ = ["MeshPencil", "mesh_pencil", "removed_dofs"]


@dataclass(frozen=True, repr=False)
class MeshPencil:
    """``K x = omega^2 M x`` of a patch on its remaining DOFs (``dofs``: their indices among
    the assembled ones, or, after a subspace restriction, the assembled DOFs ``Z`` maps to).

    ``M`` is the DOF-level mass (None where only its banded inverse ``S`` is known);
    ``massless`` the pencil rows with zero mass; ``Z`` the subspace basis (assembled remaining
    DOFs x pencil rows) or None; ``matrices`` the assembly it came from."""

    patch: object
    K: sp.csr_matrix
    M: sp.csr_matrix | None
    S: sp.csr_matrix | None
    massless: np.ndarray
    dofs: np.ndarray
    Z: sp.csr_matrix | None
    matrices: object
    #: What the removal method did, in words (None: no removal).
    removal_note: str | None = None

    @property
    def size(self) -> int:
        return self.K.shape[0]

    @property
    def diagonal_mass(self) -> bool:
        """True if M is diagonal (the banded eigensolver and the scaled Lanczos apply)."""
        if self.M is None:
            return False
        M = self.M.tocoo()
        return bool(np.all(M.row[M.data != 0] == M.col[M.data != 0]))

    def mode_on_mesh(self, x: np.ndarray) -> np.ndarray:
        """A pencil vector as the assembled DOF vector (removed DOFs zero)."""
        full = np.zeros(self.matrices.n_dofs)
        full[self.dofs] = x if self.Z is None else self.Z @ x
        return full

    def __repr__(self) -> str:
        return f"MeshPencil({self.patch.label()}: {self.size} DOFs, {self.massless.size} massless)"


def removed_dofs(patch) -> np.ndarray:
    """The assembled DOFs a fixed or sliding end removes (sorted)."""
    d = patch.dofs_per_point
    per_column = 1 if patch.model == "bar" else patch.n
    out = []
    for column, end in ((0, patch.ends[0]), (patch.n_x - 1, patch.ends[1])):
        points = column * per_column + np.arange(per_column)
        if end == "fixed":
            out.append((d * points[:, None] + np.arange(d)).ravel())
        elif end == "sliding":
            out.append(d * points)  # u_x only
    return np.unique(np.concatenate(out)) if out else np.zeros(0, dtype=int)


def _dof_level(A: sp.csr_matrix, d: int) -> sp.csr_matrix:
    return A.tocsr() if d == 1 else sp.kron(A, sp.identity(d), format="csr")


def mesh_pencil(patch, matrices=None) -> MeshPencil:
    """The pencil of ``patch`` (its assembly ``matrices`` if already built)."""
    from dispersion.discretization.finite_mesh.finite_assembly import assemble

    m = assemble(patch) if matrices is None else matrices
    d = patch.dofs_per_point
    removed = removed_dofs(patch)
    keep = np.setdiff1d(np.arange(m.n_dofs), removed)
    K = m.K[keep][:, keep].tocsr()
    M = S = None
    if m.mass is not None:
        M = _dof_level(m.mass, d)[keep][:, keep].tocsr()
    else:
        Sd = _dof_level(m.mass_inverse, d)
        S = Sd[keep][:, keep].tocsr()
        if removed.size:
            import scipy.sparse.linalg as spla

            Src = Sd[keep][:, removed].tocsc()
            Scc = Sd[removed][:, removed].tocsc()
            S = (S - Src @ sp.csr_matrix(spla.spsolve(Scc, Src.T.tocsc()))).tocsr()
            S.eliminate_zeros()
    massless_points = np.asarray(m.massless, dtype=int)
    massless_dofs = (d * massless_points[:, None] + np.arange(d)).ravel()
    where = np.searchsorted(keep, massless_dofs)
    ok = (where < keep.size) & (keep[np.minimum(where, keep.size - 1)] == massless_dofs)
    pencil = MeshPencil(patch, K, M, S, np.sort(where[ok]), keep, None, m)
    if patch.removal is not None:
        from dispersion.discretization.finite_mesh.outlier_removal import apply_removal

        pencil = apply_removal(pencil)
    return pencil
