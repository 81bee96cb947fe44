"""LAPACK's banded generalized solver called through SciPy's exported ``dsbgvd``
(:mod:`dispersion.discretization.finite_mesh.banded_pencil`), against eigenvalues computed at
40 digits in mpmath (Cholesky of M, then the symmetric eigenproblem of L^-1 K L^-T).

The route's physical use, every frequency of a finite bar with a consistent mass, is searched
by the promise ``finite-bar-frequencies`` (tests/test_finite_patch_promises.py), which now
goes through it; here the solver alone over random banded pencils: orders 1..12, bandwidths
of K and M 0..4 each (M's wider than K's included, which LAPACK does not take as is),
conditions of M up to 1e6.
"""
from __future__ import annotations

import mpmath
import numpy as np
import pytest
import scipy.sparse as sp
from hypothesis import example, given
from hypothesis import strategies as st
from promise_search import FAST_FEW, SLOW

from dispersion.discretization.finite_mesh.banded_pencil import banded_pencil
from dispersion.errors import ConvergenceError


def _banded(rng, n, b, shift):
    A = rng.standard_normal((n, n))
    A = np.triu(np.tril(A + A.T, b), -b)
    if shift is not None:                       # positive definite: diagonal dominance
        A += np.diag(np.abs(A).sum(axis=1) + shift)
    return A


def _mp_eigs(K, M):
    with mpmath.workdps(40):
        L = mpmath.cholesky(mpmath.matrix(M.tolist()))
        Li = L ** -1
        A = Li * mpmath.matrix(K.tolist()) * Li.T
        A = (A + A.T) / 2
        return sorted(float(v) for v in mpmath.eigsy(A, eigvals_only=True))


def _case(seed, n, bk, bm, cond):
    rng = np.random.default_rng(seed)
    K = _banded(rng, n, bk, None)
    M = _banded(rng, n, bm, 10.0 ** -cond)
    lam, _ = banded_pencil(sp.csr_matrix(K), sp.csr_matrix(M))
    ref = np.array(_mp_eigs(K, M))
    scale = max(np.abs(ref).max(), 1e-300)
    assert np.max(np.abs(lam - ref)) / scale < 1e-11 * 10.0 ** cond
    lam, V = banded_pencil(sp.csr_matrix(K), sp.csr_matrix(M), vectors=True)
    assert np.allclose(V.T @ M @ V, np.eye(n), atol=1e-10 * 10.0 ** cond)
    assert np.max(np.abs(K @ V - M @ V * lam)) <= 1e-11 * 10.0 ** cond * scale * np.abs(M).max()


cases = given(st.integers(0, 2**32 - 1), st.integers(1, 12), st.integers(0, 4),
              st.integers(0, 4), st.integers(0, 6))


@FAST_FEW
@cases
@example(0, 1, 0, 0, 0)
@example(1, 12, 4, 4, 6)
@example(2, 12, 0, 4, 0)
@example(3, 5, 4, 0, 3)
def test_banded_pencil_against_mpmath(seed, n, bk, bm, cond):
    _case(seed, n, bk, bm, cond)


@pytest.mark.slow
@SLOW
@cases
def test_banded_pencil_against_mpmath_slow(seed, n, bk, bm, cond):
    _case(seed, n, bk, bm, cond)


def test_an_indefinite_mass_is_refused():
    K = sp.identity(4, format="csr")
    M = sp.diags([1.0, -1.0, 1.0, 1.0]).tocsr()
    with pytest.raises(ConvergenceError, match="not positive definite"):
        banded_pencil(K, M)
