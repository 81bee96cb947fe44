"""The float eigen-solver of batched plate pencils: finite frequencies, massless DOFs condensed.

For a stack of symmetric-definite pencils :math:`(K_i, M_i)` (one per kappa) whose mass
vanishes on the DOFs ``massless``, the infinite eigenvalues are never formed:

.. math::

    \\hat K = K_{rr} - K_{rm} K_{mm}^{-1} K_{mr}, \\qquad
    \\det(\\hat K - \\Omega^2 M_{rr}) = 0,

solved by a Cholesky reduction and numpy's batched ``eigvalsh``; :func:`eigenvalue_error`
bounds the relative error of what it returns. The fast path of
:mod:`dispersion.discretization.discrete_branches` uses it for anchors and fallbacks.

References
----------
G. H. Golub, C. F. Van Loan, *Matrix computations*, 4th ed., sections 8.1.2 and 8.7
(symmetric-definite pencils).
"""
from __future__ import annotations

import numpy as np

from dispersion.errors import InputError

__all__ = ["congruence", "eigenvalue_error", "pencil_frequencies"]


def _condense(K, M, massless):
    """``Khat, M_rr, r, m`` and the size of the rounding of Khat (Frobenius norms: the
    Schur complement's error is about eps ||K_rr|| + eps ||K_rm||^2 ||K_mm^-1||)."""
    n = K.shape[-1]
    m = np.asarray(sorted(massless), dtype=int)
    r = np.setdiff1d(np.arange(n), m)
    if m.size == 0:
        return K, M, r, m, np.linalg.norm(K, axis=(1, 2))
    Krr, Krm = K[:, r[:, None], r], K[:, r[:, None], m]
    Kmm = K[:, m[:, None], m]
    Khat = Krr - Krm @ np.linalg.solve(Kmm, np.swapaxes(Krm, 1, 2))
    size = np.linalg.norm(Krr, axis=(1, 2)) + np.linalg.norm(Krm, axis=(1, 2)) ** 2 \
        * np.linalg.norm(np.linalg.inv(Kmm), axis=(1, 2))
    return Khat, M[:, r[:, None], r], r, m, size


def pencil_frequencies(K, M, massless=(), vectors: bool = False, bounds: bool = False):
    """Finite :math:`\\Omega \\ge 0` of batched pencils, ascending, shape ``(m, n - n_massless)``.

    ``massless`` lists DOFs whose mass rows and columns vanish identically; they are
    condensed, so no infinite eigenvalue is ever formed. With ``vectors=True`` also the
    mode shapes in all DOFs, shape ``(m, n, n_finite)``; with ``bounds=True`` last a bound
    on the relative error of each :math:`\\Omega^2` (:func:`eigenvalue_error` with the
    scale of the reduced matrix, so the conditioning of M and of the condensation counts).

    >>> K = np.array([[[2.0, -1.0], [-1.0, 2.0]]]); M = np.array([[[1.0, 0.0], [0.0, 0.0]]])
    >>> pencil_frequencies(K, M, massless=(1,)).round(6).tolist()   # 2 - 1/2 = 1.5
    [[1.224745]]
    """
    K, M = np.asarray(K, dtype=float), np.asarray(M, dtype=float)
    Kh, Mr, r, m, k_size = _condense(K, M, massless)
    scale = _common_shape(Mr)
    try:
        if scale is not None:  # M(kappa) = scale(kappa) * M0: one factorisation for the grid
            Li = np.linalg.inv(np.linalg.cholesky(Mr[0]))
            A = congruence(Li, Kh) / scale[:, None, None]
            Li = np.broadcast_to(Li / np.sqrt(scale)[:, None, None], Mr.shape)
        else:
            Li = np.linalg.inv(np.linalg.cholesky(Mr))
            A = Li @ Kh @ np.swapaxes(Li, 1, 2)
    except np.linalg.LinAlgError:
        raise InputError("mass matrix is not positive definite on the DOFs with mass") from None
    A = 0.5 * (A + np.swapaxes(A, 1, 2))
    # ||M^-1|| <= ||L^-1||_F^2: the reduction's error is eps ||K|| ||M^-1||, not eps ||A||
    reduced = k_size * np.linalg.norm(Li, axis=(1, 2)) ** 2 if bounds else None
    if not vectors:
        lam = np.linalg.eigvalsh(A)
        W = np.sqrt(np.clip(lam, 0, None))  # rounding only: K is positive semi-definite
        return (W, eigenvalue_error(lam, reduced)) if bounds else W
    lam, Y = np.linalg.eigh(A)
    X = np.empty((K.shape[0], K.shape[1], lam.shape[1]))
    Xr = np.swapaxes(Li, 1, 2) @ Y
    X[:, r] = Xr
    if m.size:
        Kmm = K[:, m][:, :, m]
        X[:, m] = -np.linalg.solve(Kmm, K[:, m][:, :, r] @ Xr)
    W = np.sqrt(np.clip(lam, 0, None))
    return (W, X, eigenvalue_error(lam, reduced)) if bounds else (W, X)


def congruence(T, K):
    """:math:`T K_i T^T` for a constant T and a stack K, as one matrix product.

    >>> T = np.array([[1.0, 1.0]]); congruence(T, np.eye(2)[None]).tolist()
    [[[2.0]]]
    """
    T, K = np.asarray(T, dtype=float), np.asarray(K, dtype=float)
    k, n = T.shape
    return (K.reshape(K.shape[0], n * n) @ np.kron(T, T).T).reshape(K.shape[0], k, k)


def _common_shape(M):
    """``s`` with ``M[i] == s[i] * M[0]`` to rounding, or None."""
    if M.shape[0] == 0 or M.shape[1] == 0:
        return None
    d = np.diagonal(M[0])
    i0 = int(np.argmax(d))
    if d[i0] <= 0:
        return None
    s = M[:, i0, i0] / d[i0]
    if np.any(s <= 0):
        return None
    if np.max(np.abs(M - s[:, None, None] * M[0])) <= 1e-14 * np.max(np.abs(M)):
        return s
    return None


#: Relative accuracy the float eigenvalues must reach; below it the extended-precision path runs.
def eigenvalue_error(lam: np.ndarray, reduced=None) -> np.ndarray:
    """Bound on the relative error of float eigenvalues of a symmetric m x m matrix.

    A backward-stable symmetric eigensolver returns the eigenvalues of :math:`A + E` with
    :math:`\\|E\\| \\le c\\, m\\, \\epsilon \\|A\\|`, so by Weyl's theorem
    :math:`|\\delta\\lambda| / \\lambda \\lesssim m \\epsilon \\lambda_{max} / \\lambda`
    (Golub and Van Loan, 4th ed., 8.1.2). Forming :math:`A = L^{-1} K L^{-T}` from a pencil
    adds :math:`\\epsilon \\|K\\| \\|M^{-1}\\|` (8.7.2), far more than
    :math:`\\epsilon \\lambda_{max}` where M is ill-conditioned (the B-spline mass at high
    p: cond 6e13 at p = 24): ``reduced`` (one value per row) is that scale, and the bound
    takes the larger of the two.
    """
    top = np.max(np.abs(lam), axis=-1, keepdims=True)
    if reduced is not None:
        top = np.maximum(top, np.asarray(reduced, dtype=float).reshape(-1, 1))
    m = lam.shape[-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(lam > 0, m * np.finfo(float).eps * top / lam, np.inf)
