"""Discrete dispersion branches of the plate patch: all finite roots of det(K - Omega^2 M) = 0.

For each :math:`\\kappa` of a grid the pencil :math:`(K, M)` of
:func:`dispersion.symbolic.plate.numeric_pencil` is solved in one batched call: massless DOFs
(singular masses, :attr:`PlatePatch.massless`) are condensed out by the Schur complement
of K, *by construction* (their eigenvalues are infinite), then
:math:`M_{rr} = L L^T` and :math:`\\Omega^2 = \\operatorname{eig}(L^{-1} \\hat K L^{-T})`,

.. math::

    \\hat K = K_{rr} - K_{rm} K_{mm}^{-1} K_{mr}, \\qquad
    \\det(\\hat K - \\Omega^2 M_{rr}) = 0.

Accuracy at every kappa: a float eigenvalue is trusted to relative :data:`RTOL` only where
the backward-error bound :math:`m\\epsilon\\lambda_{max}/\\lambda` says so; elsewhere (A0 and S0
at small kappa, where :math:`\\Omega^2 \\sim \\kappa^4` or :math:`\\kappa^2` sits beside eigenvalues
of order one) that kappa is solved again in ball arithmetic (:func:`extended_frequencies`).

Where the mass keeps the mirror symmetry y -> -y (:func:`dispersion.symbolic.plate.mirror_bases`),
the pencil splits into a symmetric and an antisymmetric block and the branches are labelled
``S0, S1, ...`` and ``A0, A1, ...`` in increasing :math:`\\Omega` (within a block they cannot
cross). Otherwise the symmetry is ``"mixed"``: a branch is labelled by the dominant mirror
parity of its mode shape, and the label says so. The Bloch model is periodic in
:math:`\\kappa` with period :math:`2\\pi/r`; beyond the zone edge :math:`\\pi/r` its branches are
the folded ones.

>>> from dispersion.symbolic.plate import plate_patch
>>> br = discrete_branches(plate_patch(), 0.3, [0.5, 1.0])
>>> sorted(br.omega), br.symmetry["S0"]
(['A0', 'A1', 'A2', 'S0', 'S1', 'S2'], 'S')

References
----------
A. Tkachuk et al., section 2, eq (16) and Figure 2. G. H. Golub, C. F. Van Loan, *Matrix
computations*, 4th ed., section 8.7 (symmetric-definite pencils).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np
import sympy

from dispersion.errors import InputError, check_nu, check_positive_int, check_wavenumbers
from dispersion.symbolic.plate import (
    PlatePatch,
    lame,
    mass_block,
    mirror_bases,
    numeric_pencil,
    stiffness_terms,
    x_functions,
)

__all__ = [
    "DiscreteBranches",
    "congruence",
    "critical_time_step",
    "discrete_branches",
    "extended_frequencies",
    "fundamental_branches",
    "pencil_derivative",
    "fitted_order",
    "pencil_frequencies",
    "predicted_error",
    "relative_error",
]


@dataclass
class DiscreteBranches:
    """Discrete branches on a kappa grid.

    ``omega[label]`` has one entry per kappa (NaN where that branch does not exist there);
    ``symmetry[label]`` is ``"S"``, ``"A"`` or ``"mixed"``; ``zone_edge`` is :math:`\\pi/r`
    for the Bloch model (None for x-exact).
    """

    kappa: np.ndarray
    omega: dict[str, np.ndarray]
    symmetry: dict[str, str]
    zone_edge: float | None = None
    #: ``label -> dOmega/dkappa`` (group velocity over c_T) when asked for, else None.
    group: dict[str, np.ndarray] | None = None


def _condense(K, M, massless):
    n = K.shape[-1]
    m = np.asarray(sorted(massless), dtype=int)
    r = np.setdiff1d(np.arange(n), m)
    if m.size == 0:
        return K, M, r, m
    Krr, Krm = K[:, r][:, :, r], K[:, r][:, :, m]
    Kmm = K[:, m][:, :, m]
    Khat = Krr - Krm @ np.linalg.solve(Kmm, np.swapaxes(Krm, 1, 2))
    return Khat, M[:, r][:, :, r], r, m


def pencil_frequencies(K, M, massless=(), vectors: bool = False):
    """Finite :math:`\\Omega \\ge 0` of batched pencils, ascending, shape ``(m, n - n_massless)``.

    ``massless`` lists DOFs whose mass rows and columns vanish identically; they are
    condensed, so no infinite eigenvalue is ever formed. With ``vectors=True`` also the
    mode shapes in all DOFs, shape ``(m, n, n_finite)``.

    >>> K = np.array([[[2.0, -1.0], [-1.0, 2.0]]]); M = np.array([[[1.0, 0.0], [0.0, 0.0]]])
    >>> pencil_frequencies(K, M, massless=(1,)).round(6).tolist()   # 2 - 1/2 = 1.5
    [[1.224745]]
    """
    K, M = np.asarray(K, dtype=float), np.asarray(M, dtype=float)
    Kh, Mr, r, m = _condense(K, M, massless)
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
    if not vectors:
        lam = np.linalg.eigvalsh(A)
        return np.sqrt(np.clip(lam, 0, None))  # rounding only: K is positive semi-definite
    lam, Y = np.linalg.eigh(A)
    X = np.empty((K.shape[0], K.shape[1], lam.shape[1]))
    Xr = np.swapaxes(Li, 1, 2) @ Y
    X[:, r] = Xr
    if m.size:
        Kmm = K[:, m][:, :, m]
        X[:, m] = -np.linalg.solve(Kmm, K[:, m][:, :, r] @ Xr)
    return np.sqrt(np.clip(lam, 0, None)), X


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
RTOL = 1e-11


def _float_error(lam: np.ndarray) -> np.ndarray:
    """Bound on the relative error of float eigenvalues of a symmetric m x m matrix.

    A backward-stable symmetric eigensolver returns the eigenvalues of :math:`A + E` with
    :math:`\\|E\\| \\le c\\, m\\, \\epsilon \\|A\\|` (forming A adds as much), so by Weyl's
    theorem :math:`|\\delta\\lambda| / \\lambda \\lesssim m \\epsilon \\lambda_{max} / \\lambda`
    (Golub and Van Loan, 4th ed., 8.1.2 and 8.7).
    """
    top = np.max(np.abs(lam), axis=-1, keepdims=True)
    m = lam.shape[-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(lam > 0, m * np.finfo(float).eps * top / lam, np.inf)


class _Key:
    """A patch as a cache key (its sympy matrices are not hashable)."""

    def __init__(self, patch: PlatePatch):
        self.patch = patch
        self.key = (patch.p, patch.n, patch.model, str(patch.r), str(patch.My), patch.x_lumped)

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
def _exact_terms(key: _Key, nu: float):
    """``[(coefficient expr, B)]`` for K, dK/dkappa, M, dM/dkappa (exact sympy data)."""
    patch = key.patch
    k = sympy.Symbol("kappa")
    nu_q = sympy.nsimplify(nu, rational=True)
    mat, xf = lame(nu_q), x_functions(patch, k)
    K = [(sympy.sympify(mat[m] * xf[f]), B) for m, f, B in stiffness_terms(patch)]
    M = [(sympy.sympify(xf["mx"]), mass_block(patch))]
    return {"K": K, "dK": [(c.diff(k), B) for c, B in K], "M": M,
            "dM": [(c.diff(k), B) for c, B in M]}


def _arb_rational_matrix(B):
    import flint

    return flint.arb_mat([[flint.arb(int(v.p)) / int(v.q) for v in row] for row in B.tolist()])


@functools.lru_cache(maxsize=64)
def _projected_terms(key: _Key, nu: float, which: str, basis: bytes | None, shape, prec: int):
    """``[(coefficient expr, E^T B E as arb_mat)]`` at working precision ``prec`` (cached)."""
    import flint

    n2 = 2 * key.patch.n
    Ef = np.eye(n2) if basis is None else np.frombuffer(basis).reshape(shape)
    E = flint.arb_mat(Ef.tolist())
    Et = E.transpose()
    return [(_arb_compile(c), Et * _arb_rational_matrix(B) * E)
            for c, B in _exact_terms(key, nu)[which] if c != 0]


def _arb_matrix(key, nu, which, basis, k):
    import flint

    raw = None if basis is None else np.ascontiguousarray(basis, dtype=float)
    terms = _projected_terms(key, nu, which, None if raw is None else raw.tobytes(),
                             None if raw is None else raw.shape, flint.ctx.prec)
    n = (2 * key.patch.n) if basis is None else np.shape(basis)[1]
    out = flint.arb_mat(n, n)
    for f, PB in terms:
        out += f(k) * PB
    return out


def extended_frequencies(patch: PlatePatch, nu: float, kappa, basis=None,
                         dps: int = 40, slopes: bool = False):
    """Finite :math:`\\Omega` of the pencil at one ``kappa`` in ``dps``-digit ball arithmetic.

    The reference (and the fallback) where float eigenvalues lose their relative accuracy:
    :math:`\\Omega^2` of A0 is about :math:`\\kappa^4`, so at :math:`\\kappa = 10^{-6}` it is
    1e-24 beside eigenvalues of order one. K and M are formed from the exact matrices of
    :func:`dispersion.symbolic.plate.stiffness_terms` and the exact x-functions (nu rationalised) in
    arb ball arithmetic (python-flint), projected on ``basis`` (columns spanning a mirror
    block, or None), massless DOFs condensed, and the eigenvalues of :math:`M^{-1}K` enclosed
    by :meth:`flint.acb_mat.eig`. With ``slopes=True`` also :math:`d\\Omega/d\\kappa` of every
    mode by the eigenvector formula in the same precision (returns ``(Omega, slopes)``).

    >>> from dispersion.symbolic.plate import plate_patch
    >>> w = extended_frequencies(plate_patch(), 0.3, 1e-6)
    >>> float(w[0] / 1e-12)  # A0: Omega ~ sqrt(2 / (3 (1 - nu))) kappa^2 (eq 16)
    0.9759000729...
    """
    import flint

    key, nu = _Key(patch), float(nu)
    old = flint.ctx.prec
    flint.ctx.prec = 64 * math.ceil((dps * 3.33 + 20) / 64)  # few precisions: cached terms
    try:
        k = flint.arb(float(kappa)) if not isinstance(kappa, flint.arb) else kappa
        K, M = _arb_matrix(key, nu, "K", basis, k), _arb_matrix(key, nu, "M", basis, k)
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
            lam = A.eig()
        order = sorted(range(len(lam)), key=lambda j: float(lam[j].real.mid()))
        roots = [max(lam[j].real.mid(), flint.arb(0)).sqrt() for j in order]
        W = np.array([float(v) for v in roots])
        if not slopes:
            return W
        dK, dM = _arb_matrix(key, nu, "dK", basis, k), _arb_matrix(key, nu, "dM", basis, k)
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


def _refine_small(patch, nu, kappa, W, basis, G=None):
    """Recompute in extended precision the kappas where some float eigenvalue of W is inaccurate.

    Digits: 30 beyond the ratio of the largest eigenvalue to the smallest (guessed as
    kappa^4 where the float value is lost in round-off). With ``G`` (slopes) given, the
    slopes there come from the eigenvector formula in the same precision.
    """
    lam = W**2
    bad = np.flatnonzero(np.any(_float_error(lam) > RTOL, axis=1) & (kappa > 0))
    for i in bad:
        top = float(np.max(lam[i]))
        small = max(float(np.min(lam[i])), 0.1 * kappa[i] ** 4, 1e-300)
        dps = 30 + int(math.ceil(math.log10(max(top / small, 1.0))))
        if G is None:
            W[i] = extended_frequencies(patch, nu, float(kappa[i]), basis, dps=dps)
        else:
            W[i], G[i] = extended_frequencies(patch, nu, float(kappa[i]), basis, dps=dps,
                                              slopes=True)
    return W


def pencil_derivative(patch: PlatePatch, nu: float, kappa) -> tuple[np.ndarray, np.ndarray]:
    """:math:`dK/d\\kappa` and :math:`dM/d\\kappa` as float stacks, by the complex step.

    The x-functions of :func:`dispersion.symbolic.plate.x_functions` (polynomials or trigonometric sums
    in kappa) are evaluated at :math:`\\kappa + i\\,10^{-30}`; the imaginary part over the
    step is the derivative to rounding, with no cancellation (Squire and Trapp 1998).

    >>> from dispersion.symbolic.plate import plate_patch
    >>> dK, dM = pencil_derivative(plate_patch(model="x-exact"), 0.3, [0.5])
    >>> bool(np.allclose(dK, dK.transpose(0, 2, 1))), float(np.abs(dM).max())  # x-exact: M const
    (True, 0.0)
    """
    nu = float(check_nu(nu))
    h = 1e-30
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float)) + 1j * h
    mat, xf = lame(nu), x_functions(patch, kappa)
    n2 = 2 * patch.n
    dK = np.zeros((kappa.size, n2, n2))
    for m, f, B in stiffness_terms(patch):
        dK += mat[m] * (np.imag(np.asarray(xf[f], dtype=complex)) / h)[:, None, None] \
            * np.array(B, dtype=float)
    dmx = np.imag(np.broadcast_to(np.asarray(xf["mx"], dtype=complex), kappa.shape)) / h
    dM = dmx[:, None, None] * np.array(mass_block(patch), dtype=float)
    return dK, dM


def _slopes(W, X, dK, dM, M):
    """Hellmann-Feynman :math:`d\\Omega/d\\kappa` of every mode (columns of X) of a stack."""
    num = np.einsum("kim,kij,kjm->km", X, dK, X) - W**2 * np.einsum("kim,kij,kjm->km", X, dM, X)
    den = 2 * W * np.einsum("kim,kij,kjm->km", X, M, X)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(W > 0, num / den, np.nan)


def discrete_branches(patch: PlatePatch, nu: float, kappa, chunk: int = 20000,
                      progress=None, group: bool = False) -> DiscreteBranches:
    """All finite discrete branches of ``patch`` on the grid ``kappa`` (see module docstring).

    Parameters
    ----------
    patch : PlatePatch
        From :func:`dispersion.symbolic.plate.plate_patch` (numeric aspect ratio for the Bloch model).
    nu : float
        Poisson's ratio in (-1, 0.5).
    kappa : array_like
        :math:`\\kappa = kh \\ge 0`.
    chunk : int
        Kappa points per batched solve (bounds the memory).
    progress : callable, optional
        Called with the number of kappa points finished after each chunk.
    group : bool
        Also the group velocity :math:`d\\Omega/d\\kappa` of every branch (eigenvector
        formula, :mod:`dispersion.waves.velocities`), in ``DiscreteBranches.group``.
    """
    if patch.model == "bloch" and isinstance(patch.r, sympy.Symbol):
        raise InputError("aspect ratio r must be a number for discrete branches, got the symbol r")
    nu = float(check_nu(nu))
    kappa = check_wavenumbers(kappa)
    chunk = check_positive_int("chunk", chunk)
    zone = math.pi / float(patch.r) if patch.model == "bloch" else None
    parts = []
    for lo in range(0, kappa.size, chunk):
        parts.append(_branches_block(patch, nu, kappa[lo:lo + chunk], group))
        if progress is not None:
            progress(min(chunk, kappa.size - lo))
    symmetry = {}
    for _, sym, _ in parts:
        symmetry.update(sym)
    sizes = [min(chunk, kappa.size - lo) for lo in range(0, kappa.size, chunk)]

    def join(i):
        return {lab: np.concatenate([part[i].get(lab, np.full(m, np.nan))
                                     for part, m in zip(parts, sizes)]) for lab in symmetry}

    return DiscreteBranches(kappa, join(0), symmetry, zone, join(2) if group else None)


def _branches_block(patch: PlatePatch, nu: float, kappa: np.ndarray, group: bool = False):
    K, M = numeric_pencil(patch, nu, kappa)
    dK, dM = pencil_derivative(patch, nu, kappa) if group else (None, None)
    massless = set(patch.massless)
    omega, symmetry, slopes = {}, {}, {}
    bases = mirror_bases(patch)
    if bases is not None:
        for kind in ("S", "A"):
            E = bases[kind]
            support = [set(np.flatnonzero(np.abs(E[:, j]) > 0)) for j in range(E.shape[1])]
            ml = tuple(j for j, s in enumerate(support) if s <= massless)
            if any(s & massless and not s <= massless for s in support):
                raise InputError("mirror basis mixes massless and massive DOFs")
            Kb, Mb = congruence(E.T, K), congruence(E.T, M)
            G = None
            if group:
                W, X = pencil_frequencies(Kb, Mb, ml, vectors=True)
                G = _slopes(W, X, congruence(E.T, dK), congruence(E.T, dM), Mb)
            else:
                W = pencil_frequencies(Kb, Mb, ml)
            W = _refine_small(patch, nu, kappa, W, E, G)
            for j in range(W.shape[1]):
                omega[f"{kind}{j}"], symmetry[f"{kind}{j}"] = W[:, j], kind
                if group:
                    slopes[f"{kind}{j}"] = G[:, j]
        return omega, symmetry, slopes
    W, X = pencil_frequencies(K, M, tuple(massless), vectors=True)
    G = _slopes(W, X, dK, dM, M) if group else None
    W = _refine_small(patch, nu, kappa, W, None, G)
    # parity of each mode shape: its share in the symmetric mirror subspace of the patch
    S = mirror_bases(replace(patch, My=patch.Y["00"]))["S"]
    frac = np.sum((S.T @ X) ** 2, axis=1) / np.sum(X**2, axis=1)
    is_s = frac >= 0.5
    rank_s = np.cumsum(is_s, axis=1) - 1
    rank_a = np.cumsum(~is_s, axis=1) - 1
    for kind, mask, rank in (("S", is_s, rank_s), ("A", ~is_s, rank_a)):
        for j in range(int(mask.sum(axis=1).max(initial=0))):
            sel = mask & (rank == j)
            has = sel.any(axis=1)
            label = f"{kind}{j}"
            vals = np.full(kappa.size, np.nan)
            vals[has] = W[has][sel[has]]
            omega[label], symmetry[label] = vals, "mixed"
            if group:
                g = np.full(kappa.size, np.nan)
                g[has] = G[has][sel[has]]
                slopes[label] = g
    return omega, symmetry, slopes


def relative_error(discrete: DiscreteBranches, exact) -> dict[str, np.ndarray]:
    """:math:`|\\Omega^h - \\Omega| / \\Omega` per label present in both (S0 with S0, ...).

    ``exact`` is a :class:`dispersion.waves.exact_branches.ExactBranches` on the same grid.
    Points with :math:`\\Omega = 0` give NaN.
    """
    if not np.array_equal(discrete.kappa, exact.kappa):
        raise InputError("discrete and exact branches must share the kappa grid")
    out = {}
    for label, w in discrete.omega.items():
        if label in exact.omega:
            ref = exact.omega[label]
            with np.errstate(divide="ignore", invalid="ignore"):
                out[label] = np.where(ref > 0, np.abs(w - ref) / ref, np.nan)
    return out


def fitted_order(kappa, error) -> float:
    """Least-squares slope q of :math:`\\log e = q \\log \\kappa + c` over finite positive points.

    >>> k = np.array([0.01, 0.02, 0.04]); round(fitted_order(k, 3 * k**4), 12)
    4.0
    """
    kappa, error = np.asarray(kappa, dtype=float), np.asarray(error, dtype=float)
    ok = (kappa > 0) & (error > 0) & np.isfinite(error)
    if ok.sum() < 2:
        raise InputError("need at least two points with kappa > 0 and a positive error")
    return float(np.polyfit(np.log(kappa[ok]), np.log(error[ok]), 1)[0])


def predicted_error(branch: str, nu: float, order: int = 10, **patch_kwargs) -> tuple[int, float]:
    """Leading term of the relative error of :math:`\\Omega` from the series of the core issue.

    With :math:`\\Omega_h^2 - \\Omega^2 = \\delta \\kappa^m + \\dots` (``discrete_series`` minus
    ``exact_series``) and :math:`\\Omega^2 = c \\kappa^l + \\dots`, the relative error of
    :math:`\\Omega` is :math:`\\tfrac{\\delta}{2c} \\kappa^{m-l}`. Returns ``(m - l, delta / 2c)``.
    """
    from dispersion.symbolic.power_balance import discrete_series, leading_difference
    from dispersion.waves.exact_series import exact_series

    nu = sympy.nsimplify(nu) if isinstance(nu, float) else nu  # exact comparison below
    d = discrete_series(branch, order, nu=nu, **patch_kwargs)
    e = exact_series(branch, order, nu=nu)
    lead = min(k for k, v in e.items() if v != 0)
    m = leading_difference(d, e)
    if m is None:
        raise InputError(f"no error term up to kappa^{order}; raise order")
    return m - lead, float(d.get(m, 0) - e.get(m, 0)) / (2 * float(e[lead]))


def fundamental_branches(patch: PlatePatch, nu: float, kappa) -> dict[str, np.ndarray]:
    """Discrete S0 and A0 at ``kappa``: the labels of :func:`discrete_branches` (one rule).

    >>> from dispersion.symbolic.plate import plate_patch
    >>> sorted(fundamental_branches(plate_patch(mass="singular"), 0.3, [0.1]))
    ['A0', 'S0']
    """
    br = discrete_branches(patch, nu, kappa)
    return {label: br.omega[label] for label in ("S0", "A0")}


def critical_time_step(patch: PlatePatch, nu: float, n_theta: int = 257) -> float:
    """Largest stable step of explicit central differences, :math:`2/\\max\\Omega`, in h/c_T.

    .. math:: \\Delta t_{crit} = 2 / \\max_{\\theta \\in [0, \\pi]} \\Omega(\\theta / r)

    over the Bloch phase :math:`\\theta = \\kappa r` on ``n_theta`` equally spaced points
    (both zone ends included), massless DOFs condensed (Belytschko, Liu, Moran 2000, 6.3).

    >>> from dispersion.symbolic.plate import plate_patch
    >>> 0 < critical_time_step(plate_patch(model="bloch", r=2), 0.3, n_theta=9) < 1
    True
    """
    check_positive_int("n_theta", n_theta, minimum=2)
    if patch.model != "bloch" or isinstance(patch.r, sympy.Symbol):
        raise InputError("critical_time_step needs a Bloch patch with a numeric aspect ratio r")
    theta = np.linspace(0.0, np.pi, n_theta)
    K, M = numeric_pencil(patch, nu, theta / float(patch.r))
    return float(2.0 / pencil_frequencies(K, M, patch.massless).max())
