"""Promises of the finite patch (docs/promises.md, "Finite patches"), searched over their
domains against independent high-precision references (mpmath at 50 digits):

* the bar's frequencies: every eigenvalue of the assembled float pencil against the exact
  pencil (the registry's rational matrices and the exact derivative Gram) at 50 digits;
* the proven bound: never below the true largest frequency of the float pencil (its entries
  exactly, massless DOFs condensed, at 50 digits);
* the verified Cholesky: never proves an indefinite matrix (mpmath eigenvalues);
* the sliding strip: its low frequencies converge to the Rayleigh-Lamb roots of the certified
  tracer at kappa = m pi H / L.

Each search has a small default run (the ends of its ranges as examples) and a slow twin.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import scipy.sparse as sp
from hypothesis import example, given
from hypothesis import strategies as st
from promise_search import FAST, FAST_FEW, SLOW, record

from dispersion.discretization.finite_mesh.finite_patch import finite_bar, finite_strip
from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
from dispersion.discretization.finite_mesh.mesh_spectrum import all_frequencies
from dispersion.time_stepping.mesh_step import mesh_omega_max
from dispersion.time_stepping.positive_definite import proves_positive_definite

DPS = 50
BAR_RULES = ("consistent", "lumped", "hrz", "nodal-greville", "nodal-lobatto", "sms")


def _mp(A) -> mpmath.matrix:
    A = A.toarray() if sp.issparse(A) else np.asarray(A)
    return mpmath.matrix([[mpmath.mpf(float(v)) for v in row] for row in A])


def _mp_eigs(K, M) -> list:
    """Eigenvalues of the pencil (K, M) (mpmath matrices, M positive definite)."""
    L = mpmath.cholesky(M)
    Li = mpmath.inverse(L)
    A = Li * K * Li.T
    A = (A + A.T) / 2
    return sorted(mpmath.eigsy(A, eigvals_only=True))


def _exact_bar(p, n, mass, ends) -> tuple:
    """The exact stiffness and mass of the bar (unit elements), mpmath, ends applied."""
    import sympy

    from dispersion.splines.bspline import open_knot_vector
    from dispersion.splines.derivative_gram import derivative_gram
    from dispersion.mass_rules.mass_rule import gram_space, mass_matrix

    kv = open_knot_vector(p, n, 0, n)
    K = sympy.Matrix(derivative_gram(kv))
    M = sympy.Matrix(mass_matrix(mass, gram_space(kv), check=False))
    keep = list(range(K.rows))
    if ends == "fixed":
        keep = keep[1:-1]
    conv = lambda A: mpmath.matrix([[mpmath.mpf(sympy.Rational(A[i, j]).p)
                                     / sympy.Rational(A[i, j]).q for j in keep] for i in keep])
    return conv(K), conv(M)


def _bar_case(p, n, mass, ends):
    with mpmath.workdps(DPS):
        K, M = _exact_bar(p, n, mass, ends)
        exact = [mpmath.sqrt(max(v, 0)) for v in _mp_eigs(K, M)]
    got = all_frequencies(mesh_pencil(finite_bar(p, n, ends=ends, mass=mass,
                                                 length=float(n)))).omega
    top = float(exact[-1])
    err = max(abs(float(a) - g) for a, g in zip(exact, got)) / top
    record("finite-bar-frequencies", err, 1e-12, p=p, n=n, mass=mass, ends=ends)


bar_cases = given(st.integers(1, 4), st.integers(1, 14), st.sampled_from(BAR_RULES),
                  st.sampled_from(("free", "fixed")))


@FAST_FEW
@bar_cases
@example(1, 1, "consistent", "free")
@example(4, 8, "lumped", "free")
@example(2, 3, "nodal-greville", "fixed")
def test_bar_frequencies_against_the_exact_pencil(p, n, mass, ends):
    if ends == "fixed" and n + p < 3:
        return  # nothing left once both ends are removed
    _bar_case(p, n, mass, ends)


@pytest.mark.slow
@SLOW
@bar_cases
@example(4, 14, "sms", "fixed")
def test_bar_frequencies_against_the_exact_pencil_slow(p, n, mass, ends):
    if ends == "fixed" and n + p < 3:
        return
    _bar_case(p, n, mass, ends)


def _true_top(pen) -> float:
    """The largest eigenvalue of the float pencil (its entries exactly), at 50 digits."""
    with mpmath.workdps(DPS):
        K = _mp(pen.K)
        m = list(map(int, pen.massless))
        if pen.M is None:
            S = _mp(pen.S)
            L = mpmath.cholesky(S)
            A = L.T * K * L
            return float(max(mpmath.eigsy((A + A.T) / 2, eigvals_only=True)))
        M = _mp(pen.M)
        r = [i for i in range(pen.size) if i not in m]
        sub = lambda A, rows, cols: mpmath.matrix([[A[i, j] for j in cols] for i in rows])
        Kh = sub(K, r, r)
        if m:
            Kh = Kh - sub(K, r, m) * mpmath.inverse(sub(K, m, m)) * sub(K, m, r)
        return float(max(_mp_eigs(Kh, sub(M, r, r))))


def _bound_case(patch):
    pen = mesh_pencil(patch)
    w = mesh_omega_max(pen)
    assert w.omega_proven is not None, w.failure
    true = math.sqrt(_true_top(pen))
    # the promise: never below (error = how far below, 0 when above); and tight (1e-8)
    record("proven-bound-above", max(0.0, true - w.omega_proven) / true, 0.0,
           patch=patch.label())
    # and close: the bisection's 1e-9 bracket, or, with massless DOFs, the proof pencil K_T
    # (above the condensed one by the truncation of T): 1e-6
    assert w.omega_proven <= true * (1 + 1e-6) and w.omega <= true * (1 + 1e-12)


proven_cases = given(st.integers(1, 4), st.integers(2, 20),
                     st.sampled_from(BAR_RULES + ("dual-lumped", "singular-lumped")),
                     st.sampled_from(("free", "fixed", ("fixed", "free"))))


@FAST_FEW
@proven_cases
@example(2, 8, "singular-lumped", "free")
@example(4, 6, "dual-lumped", "fixed")
@example(1, 2, "consistent", "free")
def test_proven_bound_never_below_the_true_omega_max(p, n, mass, ends):
    _proven_bar(p, n, mass, ends)


@pytest.mark.slow
@SLOW
@proven_cases
@example(4, 20, "singular-lumped", "free")
@example(4, 20, "dual-lumped", "fixed")
def test_proven_bound_never_below_the_true_omega_max_slow(p, n, mass, ends):
    _proven_bar(p, n, mass, ends)


def _proven_bar(p, n, mass, ends):
    try:
        patch = finite_bar(p, n, ends=ends, mass=mass, length=float(n), gamma_s=0.5)
        mesh_pencil(patch)
    except Exception as exc:  # noqa: BLE001 - a rule the mesh refuses says why
        assert "free end" in str(exc) or "elements" in str(exc)
        return
    _bound_case(patch)


@pytest.mark.slow
@SLOW
@given(st.integers(1, 3), st.integers(2, 5), st.integers(0, 2),
       st.sampled_from(("consistent", "lumped", "singular", "singular-lumped", "dual-lumped")),
       st.sampled_from(("free", "fixed", "sliding")))
@example(3, 5, 2, "singular", "free")
@example(1, 2, 0, "singular", "free")  # n = 2 is below the singular rules' 3 (found)
def test_proven_bound_never_below_the_true_omega_max_strip_slow(p, N, extra, mass, ends):
    # the singular rules need n >= 3 control points through the thickness (the plate patch's
    # own bound, refused by name): their domain starts there
    n = p + 1 + extra
    if mass.startswith("singular"):
        n = max(n, 3)
    _bound_case(finite_strip(p, N, n=n, ends=ends, mass=mass))


def _pd_case(n, margin, seed):
    rng = np.random.default_rng(seed)
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    lam = np.concatenate([[margin], rng.uniform(0.1, 10.0, n - 1)])
    A = (Q * lam) @ Q.T
    A = (A + A.T) / 2
    with mpmath.workdps(DPS):
        low = float(min(mpmath.eigsy(_mp(A), eigvals_only=True)))
    cert = proves_positive_definite(sp.csr_matrix(A))
    # never: a proof of a matrix whose smallest eigenvalue is <= 0
    record("verified-cholesky-never-wrong", 1.0 if (cert.proven and low <= 0) else 0.0, 0.0,
           n=n, margin=margin, low=low)


@FAST
@given(st.integers(2, 12), st.sampled_from((-1e-3, -1e-12, -1e-15, 0.0, 1e-15, 1e-12, 1e-3)),
       st.integers(0, 10**6))
@example(12, -1e-15, 0)
@example(2, 0.0, 1)
def test_verified_cholesky_never_proves_an_indefinite_matrix(n, margin, seed):
    _pd_case(n, margin, seed)


@pytest.mark.slow
@SLOW
@given(st.integers(2, 40), st.floats(-1e-6, 1e-6), st.integers(0, 10**6))
def test_verified_cholesky_never_proves_an_indefinite_matrix_slow(n, margin, seed):
    _pd_case(n, margin, seed)


def _sliding_case(p, nu):
    from dispersion.discretization.finite_mesh.normalized_spectrum import _sliding_exact

    errors = []
    for f in (2, 4):
        patch = finite_strip(p, 2 * f, n=p + f, ends="sliding", mass="consistent", nu=nu,
                             length=4.0)
        w = all_frequencies(mesh_pencil(patch)).omega
        w = w[w > 1e-7 * w[-1]][:4]
        exact = _sliding_exact(patch, 4)
        errors.append(float(np.max(w / exact - 1)))
    # Rayleigh-Ritz: from above; refined in both directions by 2 (2 -> 4 elements through
    # the thickness): the error falls by at least 2^(2p - 2) (the order 2p of the eigenvalue
    # errors, two powers of margin for a coarse mesh); above nu = 0.45 the displacement
    # formulation locks (nu -> 1/2): there only the fall itself is promised
    assert min(errors) >= -1e-12
    rate = 2 ** (2 * p - 2) if nu <= 0.45 else 1.0
    record("sliding-strip-converges", errors[1] * rate, errors[0], p=p, nu=nu)


@FAST_FEW
@given(st.integers(1, 3), st.floats(-0.9, 0.49))
@example(2, 0.3)
def test_sliding_strip_converges_to_the_rayleigh_lamb_roots(p, nu):
    _sliding_case(p, nu)


@pytest.mark.slow
@SLOW
@given(st.integers(1, 4), st.floats(-0.99, 0.499))
@example(4, 0.499)
@example(1, -0.99)
def test_sliding_strip_converges_to_the_rayleigh_lamb_roots_slow(p, nu):
    _sliding_case(p, nu)
