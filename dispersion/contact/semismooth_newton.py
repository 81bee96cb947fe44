"""Semismooth Newton for a nonlinear contact step (primal-dual active set), tangent reused.

The step equation :math:`c_1 \\mathbf M (\\mathbf U - \\tilde{\\mathbf U}) + \\mathbf P
(\\mathbf f(\\mathbf U) - \\mathbf f^{ext}) - \\mathbf G^T \\boldsymbol\\mu = \\mathbf 0`
with :math:`\\min(\\boldsymbol\\mu, c \\mathbf g) = 0` (:func:`newton`); the factorized step
matrix is carried between iterations and steps by :class:`Tangent` (a modified Newton
method). Used by :mod:`dispersion.contact.newmark` for problems without a constant stiffness
and for the consistent initial state.

References
----------
M. Hintermueller, K. Ito, K. Kunisch, "The primal-dual active set strategy as a semismooth
Newton method", SIAM J. Optim. 13 (2003).
"""
from __future__ import annotations

import numpy as np

from dispersion.errors import ConvergenceError
from dispersion.contact.linear_solver import LinearSolver
from dispersion.splines.matrix_kind import dense

__all__ = ["Tangent", "newton"]


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


def newton(prob, nm, split, state, ut, c1, rows, fixed=None, tangent=None, guess=None):
    """Semismooth Newton for ``c1 M (U - ut) + P (f(U) - f_ext) - G^T mu = 0``, complementarity.

    ``rows`` (bool) restricts the internal force to those rows (explicit scheme); ``fixed``
    (bool) holds DOFs at ``state.u`` (consistent initial state). ``tangent`` (a
    :class:`Tangent`) carries the factorized matrix between steps; it is refreshed at the
    current iterate whenever an iteration fails to reduce the residual tenfold. Returns
    ``(U, mu, iterations, f(U))``.
    """
    tangent = tangent if tangent is not None else Tangent()
    tangent.fresh = False
    M = split.Md if split.Md is not None else split.M
    G = split.Gd if split.Gd is not None else split.G
    GT = G.T
    f_ext = split.f_ext
    U = state.u.copy() if guess is None else guess.copy()
    mu = state.mu.copy() if state.mu is not None else np.zeros(G.shape[0])  # warm start
    mask = None if rows is None else rows.astype(float)
    keep = None if fixed is None else (~fixed).astype(float)
    if tangent.solve is None or not nm.reuse_tangent:
        tangent.refresh(prob, nm, split, U, c1, mask, keep)

    def residual(U, mu):
        f = prob.force(U) if prob.force is not None else prob.internal(U)[0]
        inertia = c1 * (M @ (U - ut))
        fr = f - f_ext if mask is None else mask * (f - f_ext)
        r = inertia + fr - GT @ mu
        if keep is not None:
            r = keep * r
        return f, inertia, r, prob.g0 + G @ U

    f, inertia, r, g = residual(U, mu)
    # the scale of the step's forces, independent of the starting guess
    scale = max(np.linalg.norm(c1 * (M @ (state.u - ut))), np.linalg.norm(f),
                np.linalg.norm(f_ext), 1e-300)
    c = tangent.c_ncp
    merit = np.hypot(np.linalg.norm(r), np.linalg.norm(np.minimum(mu, c * g)))
    for it in range(1, nm.max_iter + 1):
        act = (mu - c * g) > 0
        d0 = tangent.solve(-(r + GT @ mu))
        mu_new = np.zeros_like(mu)
        if act.any():
            try:
                mu_new[act] = np.linalg.solve(tangent.S[np.ix_(act, act)],
                                              -g[act] - G[act] @ d0)
            except np.linalg.LinAlgError:
                # numpy >= 2.4 raises where older ones returned non-finite values
                raise ConvergenceError(
                    f"singular Newton matrix at t = {state.t:.6g}") from None
        dU = d0 + tangent.W[:, act] @ mu_new[act]
        if not (np.all(np.isfinite(dU)) and np.all(np.isfinite(mu_new))):
            raise ConvergenceError(f"singular Newton matrix at t = {state.t:.6g}")
        # backtracking on the total residual: full steps near the solution, damped far away
        alpha = 1.0
        while True:
            mu_t = mu + alpha * (mu_new - mu)
            trial = residual(U + alpha * dU, mu_t)
            m_trial = np.hypot(np.linalg.norm(trial[2]),
                               np.linalg.norm(np.minimum(mu_t, c * trial[3])))
            if m_trial <= (1 - 1e-4 * alpha) * merit or alpha <= 1 / 32:
                break
            alpha /= 2
        U, mu = U + alpha * dU, mu_t
        f, inertia, r, g = trial
        if m_trial <= nm.tol * scale:
            return U, mu, it, f
        if not nm.reuse_tangent or (m_trial > 0.1 * merit and not tangent.fresh):
            tangent.refresh(prob, nm, split, U, c1, mask, keep)
        merit = m_trial
    raise ConvergenceError(
        f"Newton did not reach tol = {nm.tol:g} in {nm.max_iter} iterations at "
        f"t = {state.t:.6g}; residual {np.linalg.norm(r):.3e}")
