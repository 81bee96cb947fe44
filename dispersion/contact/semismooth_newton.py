"""Semismooth Newton for a nonlinear contact step (primal-dual active set), tangent reused.

The step equation :math:`c_1 \\mathbf M (\\mathbf U - \\tilde{\\mathbf U}) + \\mathbf P
(\\mathbf f(\\mathbf U) - \\mathbf f^{ext}) - \\mathbf G^T \\boldsymbol\\mu = \\mathbf 0`
with :math:`\\min(\\boldsymbol\\mu, c \\mathbf g) = 0` (:func:`newton`); the factorized step
matrix is carried between iterations and steps by :class:`Tangent` (a modified Newton
method). Used by :mod:`dispersion.contact.newmark` for problems without a constant stiffness
and for the consistent initial state, for K runs at once (:mod:`.run_batch`).

References
----------
M. Hintermueller, K. Ito, K. Kunisch, "The primal-dual active set strategy as a semismooth
Newton method", SIAM J. Optim. 13 (2003).
"""
from __future__ import annotations

import numpy as np

from dispersion.contact.linear_solver import LinearSolver
from dispersion.splines.matrix_kind import dense

__all__ = ["Tangent", "newton"]


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise dot products of ``(K, n)`` arrays (ufunc calls: no Python-level wrappers on
    a path taken a few times per step)."""
    return np.add.reduce(a * b, axis=-1)


def _every(a: np.ndarray):
    """``a.all(axis=-1)`` as one ufunc call."""
    return np.logical_and.reduce(a, axis=-1)


class Tangent:
    """Factorized step matrix ``c1 M + P K_T`` at some configuration, reused across iterations
    and steps while Newton still contracts (a modified Newton method); the constraints enter
    through ``W = A^-1 G^T`` and the Schur complement ``S = G W`` on the active set."""

    def __init__(self):
        self.solve = None
        self.c_ncp = None
        self.fresh = False

    def refresh(self, prob, nm, split, U, c1, mask, keep):
        n = prob.n
        solver = LinearSolver(n, nm)
        K = prob.internal(U)[1]
        if solver.dense:
            K = dense(K)
            M = dense(split.M)
            if mask is not None:
                K = K * mask[:, None]
            A = c1 * M + K
            if keep is not None:
                A = A * keep[:, None] + np.diag(1 - keep)
        else:
            import scipy.sparse as sp

            K = sp.csr_matrix(K)
            if mask is not None:
                K = sp.diags(mask) @ K
            A = c1 * split.M + K
            if keep is not None:
                A = sp.diags(keep) @ A + sp.diags(1 - keep)
            A = sp.csc_matrix(A)
        self.solve = solver.factor(A)
        if self.c_ncp is None:
            d = np.diag(A) if solver.dense else A.diagonal()
            self.c_ncp = float(np.abs(d).max())
        G = split.G
        self.W = self.solve(dense(split.G).T) if G.shape[0] else np.zeros((n, 0))
        if self.W.ndim == 1:
            self.W = self.W[:, None]
        self.S = np.asarray(G @ self.W)
        self.fresh = True


def newton(batch, tangents, u, mu0, t, ut, rows, guess, fixed=None):
    """Semismooth Newton for ``c1 M (U - ut) + P (f(U) - f_ext) - G^T mu = 0`` with
    complementarity, for the K runs of ``batch`` (a :class:`~.run_batch.RunBatch`) at once.

    ``u``, ``ut``, ``guess``: ``(K, n)`` (the last state, the predictor, the start);
    ``mu0``: ``(K, nc)`` (warm start); ``t``: ``(K,)`` (for messages). ``rows`` (bool)
    restricts the internal force to those rows (explicit scheme); ``fixed`` (bool) holds
    DOFs at ``u`` (consistent initial state). ``tangents`` (one :class:`Tangent` per run)
    carry the factorized matrices between steps; a run's is refreshed at its current
    iterate whenever an iteration fails to reduce its residual tenfold. Each run iterates
    as it would alone (its own line search, active set, tangent and stop); a run that has
    converged is held while the others finish. Returns ``(U, mu, iterations, f(U), W,
    failed)``: W the strain energies at U where the problems give them with the force
    (else None), ``failed`` ``{run: message}`` for the runs that did not converge.
    """
    nm = batch.nm
    K = batch.K
    c1 = batch.c1[:, None]
    U = guess.copy()
    mu = mu0.copy()
    mask = None if rows is None else rows.astype(float)
    keep = None if fixed is None else (~fixed).astype(float)
    for k, tg in enumerate(tangents):
        tg.fresh = False
        if tg.solve is None or not nm.reuse_tangent:
            tg.refresh(batch.probs[k], nm, batch.splits[k], U[k], batch.c1[k], mask, keep)

    def residual(U, mu):
        f, W = batch.force(U)  # W: the strains, for the energy of the accepted iterate
        fr = f if batch.no_ext else f - batch.f_ext
        if mask is not None:
            fr = mask * fr
        r = c1 * batch.mass(U - ut) + fr - batch.contact_force(mu)
        if keep is not None:
            r = keep * r
        return f, W, r, batch.gap(U)

    def merit_of(r, mu, g):
        cg = np.minimum(mu, c * g)
        return np.hypot(np.sqrt(_dot(r, r)), np.sqrt(_dot(cg, cg)))

    f, W, r, g = residual(U, mu)
    # the scale of the step's forces, independent of the starting guess
    du = c1 * batch.mass(u - ut)
    scale = np.maximum.reduce([np.sqrt(_dot(x, x)) for x in (du, f, batch.f_ext)]
                              + [np.full(K, 1e-300)])
    c = np.array([tg.c_ncp for tg in tangents])[:, None]
    merit = merit_of(r, mu, g)
    its = np.zeros(K, dtype=int)
    done = np.zeros(K, dtype=bool)
    failed: dict[int, str] = {}
    Gs = [s.Gd if s.Gd is not None else s.G for s in batch.splits]
    for it in range(1, nm.max_iter + 1):
        act = (mu - c * g) > 0
        rhs = -(r + batch.contact_force(mu))
        dU = np.zeros_like(U)
        mu_new = mu.copy()  # a held run keeps its multipliers
        for k in range(K):
            if done[k]:
                continue
            tg = tangents[k]
            d0 = tg.solve(rhs[k])
            a = act[k]
            mu_new[k] = 0.0
            if a.any():
                try:
                    mu_new[k, a] = np.linalg.solve(tg.S[np.ix_(a, a)], -g[k, a] - Gs[k][a] @ d0)
                except np.linalg.LinAlgError:
                    # numpy >= 2.4 raises where older ones returned non-finite values
                    mu_new[k] = np.nan
                dU[k] = d0 + tg.W[:, a] @ mu_new[k, a]
            else:
                dU[k] = d0
        finite = _every(np.isfinite(dU)) & _every(np.isfinite(mu_new))
        for k in ([] if _every(finite) else np.flatnonzero(~finite)):
            failed[k] = f"singular Newton matrix at t = {t[k]:.6g}"
            done[k] = True
            dU[k] = 0.0
            mu_new[k] = mu[k]
        # backtracking on the total residual of each run: full steps near the solution,
        # damped far away. A held run's trial is its current state (dU = 0, mu_new = mu)
        mu_t, U_t = mu + (mu_new - mu), U + dU  # alpha = 1
        trial = residual(U_t, mu_t)
        m_t = merit_of(trial[2], mu_t, trial[3])
        ok = done | (m_t <= (1 - 1e-4) * merit)
        if _every(ok):  # every run takes the full step: the common case
            U, mu, m_acc = U_t, mu_t, m_t
            f, W, r, g = trial
        else:
            alpha = np.ones(K)
            pending = ~done
            acc = [U.copy(), mu.copy(), f.copy(), r.copy(), g.copy(), merit.copy(),
                   None if W is None else tuple(x.copy() for x in W)]
            while True:
                ok = pending & ((m_t <= (1 - 1e-4 * alpha) * merit) | (alpha <= 1 / 32))
                for a_acc, a_t in zip(acc[:6], (U_t, mu_t, trial[0], trial[2], trial[3], m_t)):
                    a_acc[ok] = a_t[ok]
                if acc[6] is not None:
                    for a_acc, a_t in zip(acc[6], trial[1]):
                        a_acc[ok] = a_t[ok]
                pending &= ~ok
                if not np.logical_or.reduce(pending):
                    break
                alpha[pending] /= 2
                mu_t = mu + alpha[:, None] * (mu_new - mu)
                U_t = U + alpha[:, None] * dU
                trial = residual(U_t, mu_t)
                m_t = merit_of(trial[2], mu_t, trial[3])
            U, mu, f, r, g, m_acc, W = acc
        live = ~done
        conv = live & (m_acc <= nm.tol * scale)
        its[conv] = it
        done |= conv
        if _every(done):
            return U, mu, its, f, batch.strain_energy(W, U) if W is not None else None, failed
        for k in range(K):
            if done[k]:
                continue
            tg = tangents[k]
            if not nm.reuse_tangent or (m_acc[k] > 0.1 * merit[k] and not tg.fresh):
                tg.refresh(batch.probs[k], nm, batch.splits[k], U[k], batch.c1[k], mask, keep)
        merit = np.where(done, merit, m_acc)
    for k in np.flatnonzero(~done):
        failed[k] = (f"Newton did not reach tol = {nm.tol:g} in {nm.max_iter} iterations at "
                     f"t = {t[k]:.6g}; residual {np.linalg.norm(r[k]):.3e}")
    return U, mu, its, f, batch.strain_energy(W, U) if W is not None else None, failed
