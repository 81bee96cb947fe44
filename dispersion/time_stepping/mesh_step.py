"""The largest frequency of a finite patch, bracketed: a Rayleigh quotient below, a proof above.

Central differences are stable for :math:`\\omega_{max} \\Delta t \\le 2` with
:math:`\\omega_{max}^2` the largest eigenvalue of the patch's pencil (massless DOFs
condensed). For a given :math:`\\sigma`,

.. math::

    \\sigma > \\omega_{max}^2 \\iff \\sigma M - K \\succ 0 ,

so one verified Cholesky factorization of :math:`\\sigma M - K`
(:func:`~dispersion.time_stepping.positive_definite.proves_positive_definite`, Rump 2006:
its rounding errors and those of forming the matrix are absorbed in a shift) *proves*
:math:`\\bar\\omega = \\sqrt\\sigma` an upper bound, hence :math:`2/\\bar\\omega` a stable step.
A pencil whose mass is known by its banded inverse S is proven in the congruent form
:math:`\\sigma S - S K S \\succ 0`. Massless DOFs are never inverted densely: for any matrix T,
:math:`\\hat K = \\min_{x_m} [x; x_m]^T K [x; x_m] \\preceq K_T = [I; T]^T K [I; T]`, so a
proof for :math:`(K_T, M_{rr})` bounds the condensed pencil; T is
:math:`-K_{mm}^{-1} K_{mr}` (exact for the bar's two end DOFs; on the strip truncated to the
columns within :data:`T_REACH` elements, which only loosens the bound).

The bracket:

1. **estimate**: implicitly restarted Lanczos (:func:`~dispersion.discretization.finite_mesh.mesh_spectrum.top_modes`)
   to a residual of ``tol``; its Ritz value is a Rayleigh quotient, a lower bound;
2. **proof**: :math:`\\sigma = \\theta^2 (1 + \\epsilon)`, :math:`\\epsilon = 10^{-9}, 10^{-8},
   \\dots` until the verified factorization succeeds;
3. **bisection** on the inertia between the two (a failed factorization at
   :math:`\\sigma` yields a vector with :math:`x^T (\\sigma M - K) x \\le 0`, whose Rayleigh
   quotient raises the lower bound) until the bracket is narrower than ``rtol``, while a
   factorization costs less than :data:`BISECTION_FLOPS`.

>>> from dispersion.discretization.finite_mesh.finite_patch import finite_bar
>>> w = mesh_omega_max(finite_bar(2, 60, ends="free", mass="lumped", length=60.0))
>>> round(w.omega, 3), w.omega <= w.omega_proven <= w.omega * (1 + 1e-8)
(2.32, True)

References
----------
S. M. Rump, BIT 46 (2006) 433-452 (verified positive definiteness). B. N. Parlett, *The
Symmetric Eigenvalue Problem*, SIAM 1998, ch. 3 (Sylvester's inertia, bisection) and 13
(Lanczos). T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from dispersion.time_stepping.positive_definite import UNIT_ROUNDOFF
from dispersion.errors import ConvergenceError

__all__ = ["MeshOmegaMax", "mesh_omega_max", "BISECTION_RTOL", "ESTIMATE_TOL", "T_REACH", "T_BLOCK",
           "BISECTION_FLOPS", "proof_pencil"]

#: Width of the final bracket, relative (the verified shift of 1e5 DOFs is about 6e-11).
BISECTION_RTOL = 1e-9
#: Residual of the Lanczos estimate (relative).
ESTIMATE_TOL = 1e-8
#: Elements along x over which the condensation matrix T of the strip's massless DOFs is kept,
#: and the x-columns solved for at once.
T_REACH = 6
T_BLOCK = 64
#: A band Cholesky dearer than this (n b^2 flops) is done only for the proof, not bisected.
BISECTION_FLOPS = 2e8


@dataclass(frozen=True, repr=False)
class MeshOmegaMax:
    """``omega`` (the best Rayleigh quotient found: a lower bound of the largest frequency, in
    the patch's unit) and ``omega_proven`` (a proven upper bound, None if the proof did not
    close: ``failure`` says why); ``factorizations`` verified Cholesky runs; ``seconds``."""

    patch: object
    omega: float
    omega_proven: float | None
    factorizations: int
    seconds: float
    method: str
    failure: str | None = None
    #: Stiffness applications of the Lanczos estimate.
    applications: int = 0

    @property
    def dt(self) -> float | None:
        """The proven stable step of central differences :math:`2/\\bar\\omega` (rounded
        down), in the patch's time unit; None without a proof."""
        if self.omega_proven is None:
            return None
        return float(np.nextafter(2.0 / self.omega_proven, 0.0))

    @property
    def gap(self) -> float | None:
        """Relative width of the bracket."""
        return None if self.omega_proven is None else self.omega_proven / self.omega - 1

    def __repr__(self) -> str:
        return (f"MeshOmegaMax({self.patch.label()}: {self.omega:.12g} <= omega_max <= "
                f"{self.omega_proven})")


def _abs(A: sp.spmatrix) -> sp.csr_matrix:
    return abs(sp.csr_matrix(A))


def _rowsum(A: sp.spmatrix) -> np.ndarray:
    return np.asarray(A.sum(axis=1)).ravel()


def _product_bound(mats) -> sp.csr_matrix:
    """Entrywise bound of the rounding of a float product of sparse ``mats``: gamma_w times
    the product of their absolute values (w: the longest inner product, plus one)."""
    w = 1
    P = None
    for A in mats:
        A = _abs(A)
        w += int(np.max(np.diff(A.tocsr().indptr), initial=1))
        P = A if P is None else (P @ A)
    g = w * UNIT_ROUNDOFF / (1 - w * UNIT_ROUNDOFF)
    return (g * P).tocsr()


def proof_pencil(pen):
    """``(Kp, Mp, Ek)``: the PD-form pencil whose definiteness at sigma proves the bound, and
    an entrywise bound ``Ek`` of the rounding made forming Kp (None: Kp is pen's own)."""
    m = np.asarray(pen.massless, dtype=int)
    K = pen.K.tocsr()
    if pen.M is None:  # sigma S - S K S
        S = pen.S.tocsr()
        return (S @ K @ S).tocsr(), S, _product_bound([S, K, S])
    if m.size == 0:
        return K, pen.M.tocsr(), None
    r = np.setdiff1d(np.arange(pen.size), m)
    Krr, Krm, Kmm = K[r][:, r].tocsr(), K[r][:, m].tocsr(), K[m][:, m].tocsr()
    T = _condensation(pen, Kmm, Krm.T.tocsr(), m, r)
    KT = (Krr + Krm @ T + T.T @ Krm.T + T.T @ Kmm @ T).tocsr()
    KT = ((KT + KT.T) / 2).tocsr()
    E = (_product_bound([Krm, T]) * 2 + _product_bound([T.T, Kmm, T])
         + 4 * UNIT_ROUNDOFF * (_abs(Krr) + 2 * _abs(Krm) @ _abs(T) + _abs(T.T) @ _abs(Kmm)
                                @ _abs(T)))
    return KT, pen.M[r][:, r].tocsr(), E.tocsr()


def _columns(pen, rows: np.ndarray) -> np.ndarray:
    """The x-column (index along x) of pencil rows."""
    patch = pen.patch
    per = (1 if patch.model == "bar" else patch.n) * patch.dofs_per_point
    return pen.dofs[rows] // per


def _condensation(pen, Kmm, Kmr, m, r) -> sp.csr_matrix:
    """T (massless x massive): column j of T is -K_mm^-1 K_mr e_j with the massless DOFs
    outside a window around j's x-column held at 0 (any T bounds the condensed pencil from
    above; this one is the exact minimizer up to the decay of K_mm^-1 over T_REACH elements).
    The massive columns go in blocks of :data:`T_BLOCK` x-columns, one dense solve a block on
    the massless DOFs within T_REACH of it."""
    import scipy.linalg as sla

    if pen.Z is not None:
        raise ValueError("a subspace pencil has no massless DOFs (removal refuses them)")
    cm, cr = _columns(pen, m), _columns(pen, r)
    Kmm, Kmr = Kmm.tocsc(), Kmr.tocsc()
    order_m = np.argsort(cm, kind="stable")
    rows, cols, vals = [], [], []
    lo_col, hi_col = int(cr.min()), int(cr.max())
    for c0 in range(lo_col, hi_col + 1, T_BLOCK):
        js = np.flatnonzero((cr >= c0) & (cr < c0 + T_BLOCK))
        if js.size == 0:
            continue
        block = Kmr[:, js]
        if block.nnz == 0:
            continue
        lo = np.searchsorted(cm[order_m], c0 - T_REACH, side="left")
        hi = np.searchsorted(cm[order_m], c0 + T_BLOCK - 1 + T_REACH, side="right")
        w = np.sort(order_m[lo:hi])
        A = Kmm[w][:, w].toarray()
        B = block[w].toarray()
        X = sla.solve(A, B, assume_a="pos")
        nz = (X != 0) & (np.abs(cm[w][:, None] - cr[js][None, :]) <= T_REACH)
        ii, jj = np.nonzero(nz)
        rows.append(w[ii])
        cols.append(js[jj])
        vals.append(-X[nz])
    if not rows:
        return sp.csr_matrix((m.size, r.size))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(m.size, r.size))


class _Proof:
    """The proof pencil in band storage, built once: ``certify(sigma)`` factors
    sigma Mp - Kp with the rounding of forming it (and of Kp itself: ``Ek``) in the shift."""

    def __init__(self, Kp, Mp, Ek):
        from dispersion.time_stepping.positive_definite import band_storage

        _, bw = band_storage((abs(Kp) + abs(Mp)).tocsr())
        self.ab_K, _ = band_storage(Kp, bw)
        self.ab_M, _ = band_storage(Mp, bw)
        self.rs_K, self.rs_M = _rowsum(_abs(Kp)), _rowsum(_abs(Mp))
        self.rs_E = None if Ek is None else _rowsum(Ek)
        self.bandwidth = bw

    def certify(self, sigma: float):
        from dispersion.time_stepping.positive_definite import proves_band

        ab = sigma * self.ab_M - self.ab_K
        E = 2 * UNIT_ROUNDOFF * (sigma * self.rs_M + self.rs_K)
        if self.rs_E is not None:
            E = E + self.rs_E
        return proves_band(ab, E * (1 + 1e-10)), ab


def _failure_vector(cert, ab: np.ndarray) -> np.ndarray:
    """A vector with x^T A x <= 0 (exact arithmetic) from a factorization that broke at row
    k: x = [-A_(k-1)^-1 a_k; 1; 0] (A in lower band storage ``ab``)."""
    from scipy.linalg import lapack

    k = cert.failed_at
    n = ab.shape[1]
    x = np.zeros(n)
    x[k] = 1.0
    if k > 0:
        s = cert.scale
        bw = ab.shape[0] - 1
        col = np.zeros(k)  # A[i, k] for i < k: ab[k - i, i]
        i = np.arange(max(0, k - bw), k)
        col[i] = ab[k - i, i]
        b = (s[:k] * col) * s[k]  # the scaled column above row k
        y, info = lapack.dpbtrs(np.ascontiguousarray(cert.factor[:, :k]), b, lower=1)
        if info != 0 or not np.all(np.isfinite(y)):
            return x
        x[:k] = -y * s[:k] / s[k]
    return x


def _rayleigh(condensed, x_rows: np.ndarray) -> float:
    """The Rayleigh quotient of the condensed pencil ``(Khat, M_rr, ...)`` at a vector of its
    massive rows."""
    Kh, M = condensed[0], condensed[1]
    return float(x_rows @ (Kh @ x_rows)) / float(x_rows @ (M @ x_rows))


def mesh_omega_max(patch_or_pencil, *, rtol: float = BISECTION_RTOL,
                   tol: float = ESTIMATE_TOL) -> MeshOmegaMax:
    """The bracket of the largest frequency of a finite patch (or of its pencil)."""
    from dispersion.discretization.finite_mesh.mesh_pencil import MeshPencil, mesh_pencil
    from dispersion.discretization.finite_mesh.mesh_spectrum import top_modes

    t0 = time.perf_counter()
    pen = patch_or_pencil if isinstance(patch_or_pencil, MeshPencil) else \
        mesh_pencil(patch_or_pencil)
    count: list = []
    w, _ = top_modes(pen, 1, tol=tol, counter=count)
    applications = sum(count)
    lower = float(w[-1]) ** 2
    Kp, Mp, Ek = proof_pencil(pen)
    proof = _Proof(Kp, Mp, Ek)
    factorizations = 0
    upper = None
    eps = 1e-9
    while eps < 1.0:
        sigma = lower * (1 + eps)
        cert, A = proof.certify(sigma)
        factorizations += 1
        if cert.proven:
            upper = sigma
            break
        eps *= 10
    if upper is None:
        return MeshOmegaMax(pen.patch, math.sqrt(lower), None, factorizations,
                            time.perf_counter() - t0, "Lanczos; no proof",
                            "sigma M - K was not proven positive definite up to twice the "
                            "Lanczos estimate (the bound is not known to be false)",
                            applications)
    n = Mp.shape[0]
    bw = int(proof.bandwidth)
    lo_bis = lower
    condensed = None
    if n * (bw + 1) ** 2 <= BISECTION_FLOPS:
        while (upper - lo_bis) > rtol * upper:
            sigma = 0.5 * (lo_bis + upper)
            cert, A = proof.certify(sigma)
            factorizations += 1
            if cert.proven:
                upper = sigma
                continue
            lo_bis = sigma
            x = _failure_vector(cert, A)
            if pen.massless.size and condensed is None:
                from dispersion.discretization.finite_mesh.mesh_spectrum import (
                    condensed_operator)

                condensed = condensed_operator(pen)  # factored once for every quotient
            q = _rayleigh_of(pen, Kp, Mp, x, condensed)
            if q is not None and lower < q <= upper:
                lower = q
                lo_bis = max(lo_bis, q)
    omega_up = float(np.nextafter(math.sqrt(upper), math.inf))
    if not omega_up >= math.sqrt(lower):
        raise ConvergenceError("the proven bound lies below a Rayleigh quotient")
    method = (f"Lanczos estimate, bisection on the inertia ({factorizations} verified band "
              f"Cholesky factorizations, bandwidth {bw})")
    return MeshOmegaMax(pen.patch, math.sqrt(lower), omega_up, factorizations,
                        time.perf_counter() - t0, method, None, applications)


def _rayleigh_of(pen, Kp, Mp, x, condensed=None) -> float | None:
    """The Rayleigh quotient, on the true (condensed) pencil, of the proof pencil's vector x:
    a valid lower bound of the largest eigenvalue."""
    if not np.any(x):
        return None
    if pen.M is None:  # congruent form: the pencil vector is S x
        return float(x @ (Kp @ x)) / float(x @ (Mp @ x))
    if pen.massless.size:
        return _rayleigh(condensed, x)
    return float(x @ (pen.K @ x)) / float(x @ (pen.M @ x))
