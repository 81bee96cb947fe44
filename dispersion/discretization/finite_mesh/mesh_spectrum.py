"""The spectrum of a finite patch: every frequency (moderate N) or the top ones (large N).

On the pencil of a patch (:func:`~dispersion.discretization.finite_mesh.mesh_pencil.mesh_pencil`), the
massless DOFs condensed, :math:`\\hat K = K_{rr} - K_{rm} K_{mm}^{-1} K_{mr}`:

* **every frequency**: with a diagonal mass D the standard matrix
  :math:`D^{-1/2} \\hat K D^{-1/2}` keeps the band of K, and LAPACK's banded symmetric
  solver (``dsbevd`` through :func:`scipy.linalg.eig_banded`) gives all eigenvalues in
  :math:`O(n^2)` without forming a dense matrix; a banded mass (consistent), frequencies
  only, goes to LAPACK's banded generalized solver (:mod:`.banded_pencil`, ``dsbgvd``,
  bounded by :data:`MAX_BANDED`); any other request to the dense symmetric
  definite solver (:func:`scipy.linalg.eigh`, ``gvd``), bounded by :data:`MAX_DENSE`;
  a rule known by its banded inverse S solves :math:`L^T K L`, :math:`S = L L^T`;
* **the top**: implicitly restarted Lanczos (ARPACK, :func:`scipy.sparse.linalg.eigsh`) on
  the scaled matrix (diagonal mass), on the pencil in ARPACK's generalized mode (a factored
  mass), or on :math:`L^T K L` applied as products (inverse-banded masses).

Frequencies are :math:`\\omega = \\sqrt{\\lambda}` in the patch's unit
(:meth:`~dispersion.discretization.finite_mesh.finite_patch.FinitePatch.frequency_unit`); eigenvalues
within rounding of zero (rigid modes) are returned as 0.

>>> from dispersion.discretization.finite_mesh.finite_patch import finite_bar
>>> from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
>>> s = all_frequencies(mesh_pencil(finite_bar(1, 20, ends="fixed", mass="lumped")))
>>> import math                  # the lumped p = 1 bar: omega_1 = 2 N sin(pi / 2N), L = 1
>>> s.method, round(float(s.omega[0]), 12) == round(40 * math.sin(math.pi / 40), 12)
('banded', True)

References
----------
E. Anderson et al., *LAPACK Users' Guide*, SIAM 1999 (dsbevd, dsygvd). R. B. Lehoucq,
D. C. Sorensen, C. Yang, *ARPACK Users' Guide*, SIAM 1998.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from dispersion.errors import ConvergenceError, InputError

__all__ = ["MAX_DENSE", "MAX_BANDED", "LANCZOS_TOL", "MeshSpectrum", "condensed", "condensed_operator",
           "all_frequencies",
           "top_modes", "bandwidth"]

#: Largest pencil solved by the dense route: 6000 DOFs take about 40 s and 0.6 GB there
#: (measured, scipy.linalg.eigh gvd, both triangles of two float matrices).
MAX_DENSE = 6000
#: Largest banded pencil (a banded non-diagonal mass, frequencies only) solved by LAPACK's
#: ``dsbgvd`` (:mod:`.banded_pencil`): O(n^2 b) work; measured (consistent bar, free ends):
#: 2002 DOFs of p = 2 in 0.13 s against 2.1 s dense, 20004 DOFs of p = 4 in 24 s, so about a
#: minute at this bound.
MAX_BANDED = 30000
#: Relative residual of a Lanczos Ritz pair (the Ritz value is a Rayleigh quotient: below the
#: largest eigenvalue; the proven bound of :mod:`.mesh_step` brackets it from above).
LANCZOS_TOL = 1e-10


@dataclass(frozen=True, repr=False)
class MeshSpectrum:
    """Frequencies ``omega`` (ascending) of a pencil, and its mode shapes ``vectors`` (pencil
    coordinates, columns; None if not asked), ``method`` (``"banded"``, ``"dense"``),
    ``seconds``."""

    pencil: object
    omega: np.ndarray
    vectors: np.ndarray | None
    method: str
    seconds: float

    def __repr__(self) -> str:
        return (f"MeshSpectrum({self.pencil.patch.label()}: {self.omega.size} frequencies, "
                f"{self.method})")


def condensed(pen):
    """``(Khat, M_rr or None, S or None, r)``: the massless DOFs condensed (sparse); ``r`` the
    pencil rows kept."""
    import scipy.sparse.linalg as spla

    n = pen.size
    m = np.asarray(pen.massless, dtype=int)
    r = np.setdiff1d(np.arange(n), m)
    if m.size == 0:
        return pen.K, pen.M, pen.S, r
    if m.size * r.size > 5 * 10**7:
        raise InputError(f"condensing {m.size} massless DOFs of {n} densely is refused (the "
                         "top frequencies condense them as an operator)")
    K = pen.K.tocsr()
    Krm = K[r][:, m].tocsc()
    lu = spla.splu(K[m][:, m].tocsc())
    X = lu.solve(Krm.T.toarray())  # (m, r): dense only in the columns the contact reaches
    Kh = (K[r][:, r] - sp.csr_matrix(Krm @ X)).tocsr()
    Kh = ((Kh + Kh.T) / 2).tocsr()
    Kh.eliminate_zeros()
    M = None if pen.M is None else pen.M[r][:, r].tocsr()
    return Kh, M, None, r


def condensed_operator(pen):
    """``(Khat, M_rr, S, r)`` with ``Khat`` a linear operator (the massless block factored
    once, never inverted densely): :func:`condensed` for meshes of any size."""
    import scipy.sparse.linalg as spla

    m = np.asarray(pen.massless, dtype=int)
    if m.size == 0:
        return pen.K, pen.M, pen.S, np.arange(pen.size)
    r = np.setdiff1d(np.arange(pen.size), m)
    K = pen.K.tocsr()
    Krr, Krm = K[r][:, r].tocsr(), K[r][:, m].tocsr()
    Kmr = Krm.T.tocsr()
    lu = spla.splu(K[m][:, m].tocsc())
    op = spla.LinearOperator((r.size, r.size), dtype=float,
                             matvec=lambda x: Krr @ np.ravel(x) - Krm @ lu.solve(Kmr @ np.ravel(x)))
    return op, None if pen.M is None else pen.M[r][:, r].tocsr(), None, r


def bandwidth(A: sp.spmatrix) -> int:
    """Largest |i - j| of a stored non-zero."""
    A = A.tocoo()
    return int(np.max(np.abs(A.row - A.col), initial=0))


def _clip(lam: np.ndarray, scale: float) -> np.ndarray:
    """sqrt of eigenvalues, those within rounding of zero (rigid modes) as 0."""
    lam = np.where(np.abs(lam) <= 1e-10 * scale, 0.0, lam)
    if np.any(lam < 0):
        raise ConvergenceError(f"a negative eigenvalue {lam.min():.3g} (scale {scale:.3g}): the "
                               "pencil is not semi-definite")
    return np.sqrt(lam)


def _scaled(Kh, d) -> sp.csr_matrix:
    s = 1.0 / np.sqrt(d)
    return (sp.diags(s) @ Kh @ sp.diags(s)).tocsr()


def all_frequencies(pen, vectors: bool = False) -> MeshSpectrum:
    """Every finite frequency of the pencil ``pen`` (module docstring)."""
    import scipy.linalg as sla

    t0 = time.perf_counter()
    Kh, M, S, r = condensed(pen)
    n = Kh.shape[0]
    if M is not None and _is_diagonal(M):
        d = M.diagonal()
        if np.any(d <= 0):
            raise ConvergenceError("a massive DOF has a non-positive diagonal mass")
        A = _scaled(Kh, d)
        bw = bandwidth(A)
        if bw <= max(16, n // 20):
            ab = np.zeros((bw + 1, n))
            Ac = A.tocoo()
            low = Ac.row >= Ac.col
            ab[Ac.row[low] - Ac.col[low], Ac.col[low]] = Ac.data[low]
            if vectors:
                lam, V = sla.eig_banded(ab, lower=True)
                V = V / np.sqrt(d)[:, None]
            else:
                lam, V = sla.eig_banded(ab, lower=True, eigvals_only=True), None
            return MeshSpectrum(pen, _clip(lam, float(np.abs(lam).max())),
                                _embed(V, r, pen.size), "banded", time.perf_counter() - t0)
    if M is not None and not vectors:
        bw = max(bandwidth(Kh), bandwidth(M))
        if bw <= max(16, n // 20):
            if n > MAX_BANDED:
                raise InputError(f"every frequency of {n} DOFs is refused (the banded pencil "
                                 f"solver is bounded at {MAX_BANDED} DOFs: ask for the top "
                                 "ones)")
            from dispersion.discretization.finite_mesh.banded_pencil import banded_pencil

            lam, _ = banded_pencil(Kh, M)
            return MeshSpectrum(pen, _clip(lam, float(np.abs(lam).max())), None, "banded",
                                time.perf_counter() - t0)
    if n > MAX_DENSE:
        raise InputError(f"every frequency of {n} DOFs needs the dense solver, which is bounded "
                         f"at {MAX_DENSE} DOFs (ask for the top ones, or a diagonal mass)")
    Kd = Kh.toarray()
    if M is not None:
        out = sla.eigh(Kd, M.toarray(), eigvals_only=not vectors, driver="gvd")
    else:
        L = np.linalg.cholesky(S.toarray())
        out = sla.eigh(L.T @ Kd @ L, eigvals_only=not vectors, driver="evd")
        if vectors:
            out = (out[0], L @ out[1])
    lam, V = (out, None) if not vectors else out
    return MeshSpectrum(pen, _clip(lam, float(np.abs(lam).max())), _embed(V, r, pen.size),
                        "dense", time.perf_counter() - t0)


def _embed(V, r, n):
    """Mode shapes on the condensed rows as pencil vectors (massless rows left 0: their
    values follow from the equilibrium K_mm x_m = -K_mr x_r, not needed for the shapes'
    plots, which read the massive DOFs)."""
    if V is None or r.size == n:
        return V
    out = np.zeros((n, V.shape[1]))
    out[r] = V
    return out


def _is_diagonal(M) -> bool:
    M = M.tocoo()
    nz = M.data != 0
    return bool(np.all(M.row[nz] == M.col[nz]))


def top_modes(pen, k: int = 1, tol: float = LANCZOS_TOL, *, ncv: int | None = None,
              counter: list | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The ``k`` largest frequencies (ascending) and their modes (pencil coordinates) by
    Lanczos; :class:`ConvergenceError` if ARPACK does not converge. ``counter`` (a list)
    receives the number of stiffness applications."""
    import scipy.sparse.linalg as spla

    if pen.size <= max(2 * k + 2, 40):  # too small for ARPACK: every frequency
        s = all_frequencies(pen, vectors=True)
        return s.omega[-k:], s.vectors[:, -k:]
    Kh0, M, S, r = condensed_operator(pen)
    n = Kh0.shape[0]
    count = [0]

    def kmul(x):
        count[0] += 1
        return Kh0 @ np.ravel(x)

    Kh = spla.LinearOperator((n, n), matvec=kmul, dtype=float)
    v0 = np.random.default_rng(0).standard_normal(n)
    ncv = min(n - 1, max(2 * k + 20, 40) if ncv is None else ncv)
    try:
        if M is not None and _is_diagonal(M):
            d = M.diagonal()
            s = 1.0 / np.sqrt(d)
            A = spla.LinearOperator((n, n), matvec=lambda x: s * (Kh @ (s * np.ravel(x))),
                                    dtype=float)
            lam, V = spla.eigsh(A, k=k, which="LA", tol=tol, v0=v0, ncv=ncv, maxiter=20000)
            V = V * s[:, None]
        elif M is not None:
            lu = spla.splu(M.tocsc())
            Minv = spla.LinearOperator((n, n), matvec=lu.solve, dtype=float)
            lam, V = spla.eigsh(Kh, k=k, M=M, Minv=Minv, which="LA", tol=tol, v0=v0, ncv=ncv,
                                maxiter=20000)
        else:
            L = _cholesky_factor(S)
            A = spla.LinearOperator((n, n), matvec=lambda x: L.T @ (Kh @ (L @ x)), dtype=float)
            lam, V = spla.eigsh(A, k=k, which="LA", tol=tol, v0=v0, ncv=ncv, maxiter=20000)
            V = L @ V
    except spla.ArpackNoConvergence as exc:
        raise ConvergenceError(f"Lanczos did not converge on the largest frequencies ({exc})") \
            from None
    finally:
        if counter is not None:
            counter.append(count[0])
    order = np.argsort(lam)
    lam, V = lam[order], V[:, order]
    if not np.all(lam > 0):
        raise ConvergenceError(f"the largest eigenvalue is {lam.max()}, not positive")
    return np.sqrt(lam), _embed(V, r, pen.size)


def _cholesky_factor(S: sp.csr_matrix):
    """A sparse lower factor L with S = L L^T (banded S: the band Cholesky of LAPACK)."""
    import scipy.linalg as sla

    n = S.shape[0]
    bw = bandwidth(S)
    ab = np.zeros((bw + 1, n))
    Sc = S.tocoo()
    low = Sc.row >= Sc.col
    ab[Sc.row[low] - Sc.col[low], Sc.col[low]] = Sc.data[low]
    cb = sla.cholesky_banded(ab, lower=True)
    rows, cols, vals = [], [], []
    for k in range(bw + 1):
        j = np.arange(n - k)
        rows.append(j + k)
        cols.append(j)
        vals.append(cb[k, :n - k])
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n, n))
