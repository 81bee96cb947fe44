"""Verified positive definiteness of a sparse symmetric matrix by one floating-point Cholesky.

Rump's theorem (BIT 46 (2006) 433-452, Theorem 2.3 and Corollary 2.4, as in INTLAB's
``isspd``): let A be a symmetric floating-point matrix with positive diagonal, :math:`t_i`
the number of stored entries left of the diagonal in row i (here the band: at most the
bandwidth), u = 2^-53 the unit roundoff and :math:`\\eta` = 2^-1074 the smallest subnormal.
With

.. math::

    c \\ge \\sum_i (t_i + 3)\\, u\\, a_{ii} + \\|\\Delta\\|_2 + 6 n (n + \\max_i a_{ii})\\,\\eta,

if the floating-point Cholesky factorization of :math:`A - cI` (diagonal rounded down) runs to
completion, then every symmetric matrix :math:`A + \\Delta'` with
:math:`\\|\\Delta'\\|_2 \\le \\|\\Delta\\|_2` is positive definite. (The factor :math:`t_i + 3`
holds for :math:`n < 67\\,108\\,861`, i.e. :math:`(t_i + 2) u / (1 - (t_i + 2) u)^2
\\le (t_i + 3) u`.) The rows are first scaled by powers of two (exact) so the diagonal lies in
[1/4, 1) (van der Sluis). :math:`\\|\\Delta\\|_2` is bounded by the largest row sum of an
entrywise bound (Gershgorin on a symmetric non-negative matrix), computed with a relative
margin of 1e-10 for its own rounding. The factorization is LAPACK's band Cholesky
(``dpbtrf``); the theorem holds for any order of the inner products it computes.

>>> import scipy.sparse as sp
>>> A = sp.csr_matrix([[2.0, -1.0], [-1.0, 2.0]])
>>> proves_positive_definite(A).proven, proves_positive_definite(A - 0.9 * sp.identity(2)).proven
(True, True)
>>> proves_positive_definite(A - 3.0 * sp.identity(2)).proven
False

References
----------
S. M. Rump, "Verification of positive definiteness", BIT Numer. Math. 46 (2006) 433-452,
doi:10.1007/s10543-006-0056-1. N. J. Higham, *Accuracy and Stability of Numerical
Algorithms*, 2nd ed., SIAM 2002, Theorem 10.5 (the Cholesky backward error).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

__all__ = ["UNIT_ROUNDOFF", "PDCertificate", "proves_positive_definite", "proves_band",
           "band_storage"]

UNIT_ROUNDOFF = 2.0 ** -53
_ETA = 2.0 ** -1074
_RUMP_N_MAX = 67_108_861


@dataclass(frozen=True)
class PDCertificate:
    """``proven``: the Cholesky of A - cI ran to completion; ``shift`` c (scaled units),
    ``failed_at`` the first non-positive pivot's row (None: none), ``factor`` the band
    factor (lower storage) as far as it went, ``scale`` the power-of-two row scaling."""

    proven: bool
    shift: float
    failed_at: int | None
    factor: np.ndarray
    scale: np.ndarray
    bandwidth: int


def band_storage(A: sp.spmatrix, bw: int | None = None) -> tuple[np.ndarray, int]:
    """Lower band storage ``ab[i - j, j] = A[i, j]`` (LAPACK's ``lower=1``) and the bandwidth."""
    A = sp.csr_matrix(A)
    A.sum_duplicates()  # one entry a position: the band is filled by assignment
    A = A.tocoo()
    low = A.row >= A.col
    r, c, v = A.row[low], A.col[low], A.data[low]
    if bw is None:
        bw = int(np.max(r - c, initial=0))
    ab = np.zeros((bw + 1, A.shape[0]))
    ab[r - c, c] = v
    return ab, bw


def proves_positive_definite(A: sp.spmatrix, error_rowsum: np.ndarray | None = None
                             ) -> PDCertificate:
    """Prove ``A + Delta`` positive definite for every symmetric Delta whose entries are
    bounded by a matrix with row sums ``error_rowsum`` (module docstring); ``A`` symmetric
    (its lower triangle is read)."""
    ab, bw = band_storage(A)
    return proves_band(ab, error_rowsum)


def proves_band(ab: np.ndarray, error_rowsum: np.ndarray | None = None) -> PDCertificate:
    """:func:`proves_positive_definite` of a matrix in lower band storage ``ab``."""
    from scipy.linalg import lapack

    bw = ab.shape[0] - 1
    n = ab.shape[1]
    d = ab[0]
    empty = np.zeros((1, n))
    if n == 0 or n >= _RUMP_N_MAX or not np.all(d > 0) or not np.all(np.isfinite(d)):
        return PDCertificate(False, math.nan, int(np.argmin(d > 0)) if n else None, empty,
                             np.ones(n), bw)
    # van der Sluis: powers of two, so D A D is exact (no underflow at these sizes)
    scale = np.exp2(-np.ceil(0.5 * np.log2(d)))
    shifted = ab * scale[None, :]
    for k in range(bw + 1):  # row i = j + k of column j: times scale_i
        shifted[k, : n - k] *= scale[k:]
    ds = shifted[0].copy()
    t = np.minimum(np.arange(n), bw)
    rump = float(np.sum((t + 3) * UNIT_ROUNDOFF * ds)) * (1 + 1e-10)
    delta = 0.0
    if error_rowsum is not None:
        # the scaled bound: D E D has row sums <= max(scale) * scale_i * rowsum_i
        delta = float(np.max(scale * np.asarray(error_rowsum, float)) * np.max(scale)) \
            * (1 + 1e-10)
    c = rump + delta + 6 * n * (n + float(ds.max())) * _ETA
    shifted[0] = np.nextafter(ds - c, -np.inf)  # rounded down: below the exact a_ii - c
    factor, info = lapack.dpbtrf(shifted, lower=1)
    if info < 0:
        raise ValueError(f"dpbtrf: argument {-info} illegal")
    return PDCertificate(info == 0, c, None if info == 0 else int(info) - 1, factor, scale, bw)
