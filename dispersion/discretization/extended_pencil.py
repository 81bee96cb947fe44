"""The plate pencil in ball arithmetic: the reference and last resort of the discrete branches.

K and M are formed from the exact matrices of :func:`dispersion.symbolic.plate.stiffness_terms`
and the exact x-functions (the law's moduli as exact rationals,
:meth:`~dispersion.materials.elastic_law.ElasticLaw.rational_moduli`) in arb ball arithmetic (python-flint), projected
on a basis, massless DOFs condensed, and the eigenvalues of :math:`M^{-1}K` enclosed by
:meth:`flint.acb_mat.eig`. :mod:`dispersion.discretization.discrete_branches` calls it only where
neither the exact characteristic polynomial nor the float eigen-solver certifies a root.

References
----------
F. Johansson, "Arb: efficient arbitrary-precision midpoint-radius interval arithmetic",
IEEE Trans. Computers 66 (2017) 1281-1292.
"""
from __future__ import annotations

import functools
import math
import threading

import numpy as np
import sympy

from dispersion.errors import InputError
from dispersion.discretization.pencil_frequencies import eigenvalue_error
from dispersion.reader import as_sympy
from dispersion.symbolic.plate import (
    PlatePatch,
    mass_block,
    stiffness_terms,
    with_nu,
    x_functions,
)

__all__ = ["MAX_EXTENDED_SECONDS", "extended_frequencies", "refine_inaccurate"]

#: Longest extended-precision work one call of :func:`refine_inaccurate` accepts (seconds,
#: measured on its first kappa point): beyond it the request is refused with the count that
#: fits. Rule: about two minutes, the scale of the command line's other work bounds.
MAX_EXTENDED_SECONDS = 120.0


class _Key:
    """A patch with its law as a cache key (its sympy matrices are not hashable)."""

    def __init__(self, patch: PlatePatch):
        self.patch = patch
        # the entries themselves (hashable sympy numbers): never the printed matrix
        self.key = (patch.p, patch.n, patch.model, patch.r, tuple(patch.My), patch.x_mass,
                    patch.law)

    def __hash__(self):
        return hash(self.key)

    def __eq__(self, other):
        return isinstance(other, _Key) and self.key == other.key


def _arb_compile(expr):
    """A sympy expression in kappa (sums, products, integer powers, rationals, cos, sin) as a
    function ``k -> arb ball``: the exact formulas of :func:`x_functions`, evaluated without
    rounding the rational coefficients to floats."""
    import flint

    if expr.is_Symbol:
        return lambda k: k
    if expr.is_Rational:
        p, q = int(expr.p), int(expr.q)
        return lambda k: flint.arb(p) / q
    parts = [_arb_compile(a) for a in expr.args]
    if expr.is_Add:
        return lambda k: sum((f(k) for f in parts), flint.arb(0))
    if expr.is_Mul:
        def mul(k):
            out = flint.arb(1)
            for f in parts:
                out = out * f(k)
            return out
        return mul
    if expr.is_Pow and expr.exp.is_Integer:
        e = int(expr.exp)
        return lambda k: parts[0](k) ** e
    if isinstance(expr, sympy.cos):
        return lambda k: parts[0](k).cos()
    if isinstance(expr, sympy.sin):
        return lambda k: parts[0](k).sin()
    raise InputError(f"cannot evaluate {expr} in interval arithmetic")


@functools.lru_cache(maxsize=16)
def _exact_terms(key: _Key):
    """``[(coefficient expr, B)]`` for K, dK/dkappa, M, dM/dkappa (exact sympy data)."""
    patch = key.patch
    k = sympy.Symbol("kappa")
    mat, xf = patch.law.rational_moduli(), x_functions(patch, k)
    K = [(as_sympy("modulus", mat[m] * xf[f]), B) for m, f, B in stiffness_terms(patch)]
    M = [(as_sympy("mass", xf["mx"]), mass_block(patch))]
    return {"K": K, "dK": [(c.diff(k), B) for c, B in K], "M": M,
            "dM": [(c.diff(k), B) for c, B in M]}


def _arb_rational_matrix(B):
    import flint

    return flint.arb_mat([[flint.arb(int(v.p)) / int(v.q) for v in row] for row in B.tolist()])


@functools.lru_cache(maxsize=64)
def _projected_terms(key: _Key, which: str, basis: bytes | None, shape, prec: int):
    """``[(coefficient expr, E^T B E as arb_mat)]`` at working precision ``prec`` (cached)."""
    import flint

    n2 = 2 * key.patch.n
    Ef = np.eye(n2) if basis is None else np.frombuffer(basis).reshape(shape)
    E = flint.arb_mat(Ef.tolist())
    Et = E.transpose()
    return [(_arb_compile(c), Et * _arb_rational_matrix(B) * E)
            for c, B in _exact_terms(key)[which] if c != 0]


def _arb_matrix(key, which, basis, k):
    import flint

    raw = None if basis is None else np.ascontiguousarray(basis, dtype=float)
    terms = _projected_terms(key, which, None if raw is None else raw.tobytes(),
                             None if raw is None else raw.shape, flint.ctx.prec)
    n = (2 * key.patch.n) if basis is None else np.shape(basis)[1]
    out = flint.arb_mat(n, n)
    for f, PB in terms:
        out += f(k) * PB
    return out


def extended_frequencies(patch: PlatePatch, nu, kappa, basis=None,
                         dps: int = 40, slopes: bool = False):
    """Finite :math:`\\Omega` of the pencil at one ``kappa`` in ``dps``-digit ball arithmetic.

    The reference (and the fallback) where float eigenvalues lose their relative accuracy:
    :math:`\\Omega^2` of A0 is about :math:`\\kappa^4`, so at :math:`\\kappa = 10^{-6}` it is
    1e-24 beside eigenvalues of order one. K and M are formed from the exact matrices of
    :func:`dispersion.symbolic.plate.stiffness_terms` and the exact x-functions (the law's moduli as exact rationals) in
    arb ball arithmetic (python-flint), projected on ``basis`` (columns spanning a mirror
    block, or None), massless DOFs condensed, and the eigenvalues of :math:`M^{-1}K` enclosed
    by :meth:`flint.acb_mat.eig`. With ``slopes=True`` also :math:`d\\Omega/d\\kappa` of every
    mode by the eigenvector formula in the same precision (returns ``(Omega, slopes)``).

    >>> from dispersion.symbolic.plate import plate_patch
    >>> w = extended_frequencies(plate_patch(model="x-exact"), 0.3, 1e-6)
    >>> float(w[0] / 1e-12)  # A0: Omega ~ sqrt(2 / (3 (1 - nu))) kappa^2 (eq 16)
    0.9759000729...
    """
    patch = with_nu(patch, nu)
    with _FLINT_LOCK:  # flint's working precision is process-global
        return _extended(patch, kappa, basis, dps, slopes)


_FLINT_LOCK = threading.Lock()


def _extended(patch, kappa, basis, dps, slopes):
    import flint

    patch.law.check_numeric("extended-precision frequencies")
    key = _Key(patch)
    old = flint.ctx.prec
    flint.ctx.prec = 64 * math.ceil((dps * 3.33 + 20) / 64)  # few precisions: cached terms
    try:
        k = flint.arb(float(kappa)) if not isinstance(kappa, flint.arb) else kappa
        K, M = _arb_matrix(key, "K", basis, k), _arb_matrix(key, "M", basis, k)
        n = K.nrows()
        zero = [i for i in range(n) if all(M[i, j] == 0 for j in range(n))]
        keep = [i for i in range(n) if i not in zero]
        Krr, Mrr = _arb_sub(K, keep, keep), _arb_sub(M, keep, keep)
        if zero:
            Krm = _arb_sub(K, keep, zero)
            Kmm = _arb_sub(K, zero, zero)
            Krr = Krr - Krm * Kmm.solve(Krm.transpose())
        A = flint.acb_mat(Mrr.solve(Krr))
        if slopes:
            lam, R = A.eig(right=True)
        else:
            try:
                lam = A.eig()
            except ValueError:  # a multiple eigenvalue (e.g. both rigid modes at kappa = 0)
                lam = A.eig(nonstop=True)
                tight = [float(v.rad()) <= 1e-20 * max(abs(float(v.mid())), 1.0)
                         for v in (x.real for x in lam)]
                if not all(tight):
                    raise ValueError("eigenvalue enclosures too wide") from None
        order = sorted(range(len(lam)), key=lambda j: float(lam[j].real.mid()))
        roots = [max(lam[j].real.mid(), flint.arb(0)).sqrt() for j in order]
        W = np.array([float(v) for v in roots])
        if not slopes:
            return W
        dK, dM = _arb_matrix(key, "dK", basis, k), _arb_matrix(key, "dM", basis, k)
        G = []
        for j, w in zip(order, roots):
            x = flint.acb_mat(n, 1)
            xr = flint.acb_mat([[R[a, j]] for a in range(len(keep))])
            for a, i in enumerate(keep):
                x[i, 0] = xr[a, 0]
            if zero:
                xm = flint.acb_mat(Kmm).solve(-flint.acb_mat(_arb_sub(K, zero, keep)) * xr)
                for a, i in enumerate(zero):
                    x[i, 0] = xm[a, 0]
            w_ = flint.acb(w)
            num = (x.transpose() * flint.acb_mat(dK - w * w * dM) * x)[0, 0]
            den = 2 * w_ * (x.transpose() * flint.acb_mat(M) * x)[0, 0]
            G.append(float((num / den).real.mid()) if float(w) > 0 else float("nan"))
        return W, np.array(G)
    finally:
        flint.ctx.prec = old


def _arb_sub(A, rows, cols):
    import flint

    return flint.arb_mat([[A[i, j] for j in cols] for i in rows])


def _extended_safe(patch, k, basis, dps, slopes):
    """:func:`extended_frequencies`, retried at twice the digits; ``(None, reason)`` if both fail."""
    why = ""
    for digits in (dps, 2 * dps):
        try:
            return extended_frequencies(patch, None, k, basis, dps=digits, slopes=slopes), ""
        except (ValueError, ZeroDivisionError, ArithmeticError) as exc:  # flint: eig failed
            why = f"extended-precision eigen-solver failed at {digits} digits ({exc})"
    return None, why


def refine_inaccurate(patch, nu, kappa, W, basis, G=None, failures=None, error=None,
                      rtol: float = 1e-11):
    """Recompute in extended precision the kappas where some float eigenvalue of W is inaccurate.

    Digits: 30 beyond the ratio of the largest eigenvalue to the smallest (guessed as
    kappa^4 where the float value is lost in round-off). With ``G`` (slopes) given, the
    slopes there come from the eigenvector formula in the same precision. Never raises
    from the eigen-solver: a kappa where the ball solve fails twice gets NaN and an entry
    ``("omega", kappa, reason)`` in ``failures`` (a list, if given). ``error``: the float
    eigen-solver's bound per root (:func:`~dispersion.discretization.pencil_frequencies.pencil_frequencies`
    with ``bounds=True``); ``rtol`` the accuracy asked of it. Work beyond
    :data:`MAX_EXTENDED_SECONDS` (estimated on the first kappa) is refused.
    """
    patch = with_nu(patch, nu)
    import time

    lam = W**2
    error = eigenvalue_error(lam) if error is None else error
    bad = np.flatnonzero(np.any(error > rtol, axis=1) & (kappa > 0))
    started = time.perf_counter()
    for done, i in enumerate(bad):
        if done == 1 and (time.perf_counter() - started) * bad.size > MAX_EXTENDED_SECONDS:
            each = time.perf_counter() - started
            worst = float(np.max(error[bad]))
            # the count of kappa points whose share of such points fits in the time: advice a
            # grid accepts (2 points at least), or none about the count at all
            fits = int(kappa.size * MAX_EXTENDED_SECONDS / (each * bad.size))
            advice = (f"ask for fewer kappa points (count <= {fits}) or a lower p" if fits >= 2
                      else "ask for a lower p or n (even a grid of 2 kappa points needs more)")
            raise InputError(
                f"{bad.size} kappa points need the extended-precision eigen-solver (the float "
                f"one certifies their eigenvalues to {worst:.1g} relative only, not {rtol:g}: "
                f"p = {patch.p}, n = {patch.n}), at about {each:.2g} s each: over "
                f"{MAX_EXTENDED_SECONDS:.0f} s; {advice}")
        top = float(np.max(lam[i]))
        small = max(min(float(np.min(lam[i])), 0.1 * kappa[i] ** 4), 1e-300)
        ratio = top / small
        if not 1.0 <= ratio < 1e300:   # float eigenvalues lost (inf, NaN): the widest guess
            ratio = 1e300 if not ratio < 1.0 else 1.0
        dps = 30 + int(math.ceil(math.log10(ratio)))
        out, why = _extended_safe(patch, float(kappa[i]), basis, dps, G is not None)
        if out is None:
            W[i] = np.nan
            if failures is not None:
                failures.append(("omega", float(kappa[i]), why))
            continue
        if G is None:
            W[i] = out
        else:
            W[i], G[i] = out
    return W
