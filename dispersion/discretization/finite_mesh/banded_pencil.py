"""Every eigenvalue of a banded symmetric-definite pencil, in the band: LAPACK's ``dsbgvd``.

A finite patch with a consistent (banded, positive definite) mass has the pencil
:math:`K x = \\lambda M x` with K and M both banded. LAPACK solves it without a dense matrix:
``dsbgst`` reduces it to a standard banded problem by the split Cholesky factor of M
(Crawford's algorithm, the band of K is kept), ``dsbtrd`` to tridiagonal form, then a
divide-and-conquer tridiagonal solver: :math:`O(n^2 b)` work and :math:`O(n b)` memory for
the eigenvalues (eigenvectors add an :math:`n \\times n` array), against the dense
:math:`O(n^3)` and :math:`O(n^2)` of ``dsygvd``.

SciPy has no Python wrapper of ``dsbgvd``; its public Cython interface to LAPACK
(:mod:`scipy.linalg.cython_lapack`) exports the routine, and it is called here through that
exported function pointer with :mod:`ctypes` (the route numba takes to SciPy's LAPACK): the
LAPACK that SciPy itself links, no second library.

>>> import numpy as np, scipy.sparse as sp
>>> n = 6                  # the consistent p = 1 bar, both ends fixed: lambda = (6/h^2)(1 - cos t)/(2 + cos t)
>>> h = 1 / (n + 1)
>>> K = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]) / h
>>> M = sp.diags([np.ones(n - 1), 4 * np.ones(n), np.ones(n - 1)], [-1, 0, 1]) * h / 6
>>> lam, _ = banded_pencil(K, M)
>>> t = np.arange(1, n + 1) * np.pi / (n + 1)
>>> bool(np.allclose(lam, 6 / h**2 * (1 - np.cos(t)) / (2 + np.cos(t)), rtol=1e-13))
True

References
----------
E. Anderson et al., *LAPACK Users' Guide*, 3rd ed., SIAM 1999 (dsbgvd, dsbgst);
C. R. Crawford, "Reduction of a band-symmetric generalized eigenvalue problem", Comm. ACM 16
(1973) 41; L. Kaufman, "Banded eigenvalue solvers on vector machines", ACM TOMS 10 (1984) 73.
"""
from __future__ import annotations

import ctypes

import numpy as np
import scipy.sparse as sp

from dispersion.errors import ConvergenceError

__all__ = ["banded_pencil", "lower_band"]

_INT = ctypes.POINTER(ctypes.c_int)
_DBL = ctypes.POINTER(ctypes.c_double)
_ROUTINE = None


def _dsbgvd():
    """The function pointer of SciPy's ``dsbgvd`` as a ctypes function (resolved once)."""
    global _ROUTINE
    if _ROUTINE is None:
        from scipy.linalg import cython_lapack

        capsule = cython_lapack.__pyx_capi__["dsbgvd"]
        name = ctypes.pythonapi.PyCapsule_GetName
        name.restype, name.argtypes = ctypes.c_char_p, [ctypes.py_object]
        pointer = ctypes.pythonapi.PyCapsule_GetPointer
        pointer.restype, pointer.argtypes = ctypes.c_void_p, [ctypes.py_object, ctypes.c_char_p]
        address = pointer(capsule, name(capsule))
        prototype = ctypes.CFUNCTYPE(None, ctypes.c_char_p, ctypes.c_char_p, _INT, _INT, _INT,
                                     _DBL, _INT, _DBL, _INT, _DBL, _DBL, _INT, _DBL, _INT, _INT,
                                     _INT, _INT)
        _ROUTINE = prototype(address)
    return _ROUTINE


def lower_band(A: sp.spmatrix, bw: int) -> np.ndarray:
    """LAPACK's lower band storage of the symmetric ``A`` (Fortran order, ``bw + 1`` rows):
    ``ab[i - j, j] = A[i, j]`` for ``j <= i <= j + bw``."""
    A = A.tocoo()
    low = A.row >= A.col
    ab = np.zeros((bw + 1, A.shape[0]), order="F")
    np.add.at(ab, (A.row[low] - A.col[low], A.col[low]), A.data[low])
    return ab


def banded_pencil(K: sp.spmatrix, M: sp.spmatrix, vectors: bool = False):
    """``(lam, V)``: every eigenvalue (ascending) of the symmetric pencil ``K x = lam M x``
    with M positive definite, both banded, and the M-orthonormal eigenvectors as columns
    (``V`` None unless ``vectors``). Raises :class:`~dispersion.errors.ConvergenceError` when
    M is not positive definite or the solver does not converge (LAPACK's ``info``)."""
    n = K.shape[0]
    if n == 1:                           # dsbgvd leaves Z unset at n = 1 (measured)
        k, m = float(K.toarray()[0, 0]), float(M.toarray()[0, 0])
        if not m > 0:
            raise ConvergenceError(f"the mass is not positive definite (its only entry {m:g})")
        return np.array([k / m]), (np.array([[1 / np.sqrt(m)]]) if vectors else None)
    bk = int(np.max(np.abs(K.tocoo().row - K.tocoo().col), initial=0))
    bm = int(np.max(np.abs(M.tocoo().row - M.tocoo().col), initial=0))
    if bm > bk:                          # dsbgvd needs ka >= kb: widen K's storage
        bk = bm
    ab, bb = lower_band(K, bk), lower_band(M, bm)
    w = np.zeros(n)
    z = np.zeros((n, n) if vectors else (1, 1), order="F")
    jobz = b"V" if vectors else b"N"
    c = ctypes.c_int
    args = [c(n), c(bk), c(bm)]
    ldab, ldbb, ldz = c(bk + 1), c(bm + 1), c(n if vectors else 1)
    info, work1 = c(0), np.zeros(1)
    lwork, liwork = c(-1), c(-1)

    def call(work, iwork):
        _dsbgvd()(jobz, b"L", *(ctypes.byref(a) for a in args),
                  ab.ctypes.data_as(_DBL), ctypes.byref(ldab), bb.ctypes.data_as(_DBL),
                  ctypes.byref(ldbb), w.ctypes.data_as(_DBL), z.ctypes.data_as(_DBL),
                  ctypes.byref(ldz), work.ctypes.data_as(_DBL), ctypes.byref(lwork),
                  iwork.ctypes.data_as(_INT), ctypes.byref(liwork), ctypes.byref(info))

    query = np.zeros(1, dtype=np.intc)
    call(work1, query)                   # workspace query
    lwork, liwork = c(max(1, int(work1[0]))), c(max(1, int(query[0])))
    call(np.zeros(lwork.value), np.zeros(liwork.value, dtype=np.intc))
    if info.value > n:
        raise ConvergenceError(f"the mass is not positive definite (dsbgvd info {info.value}: "
                               f"leading minor {info.value - n})")
    if info.value != 0:
        raise ConvergenceError(f"dsbgvd did not converge (info {info.value})")
    return w, (z if vectors else None)
