"""Newmark time stepping with Lagrange-multiplier contact: standard, and contact-modified (Kane).

Semi-discrete problem (paper eq 5) with a linear gap :math:`\\mathbf g = \\mathbf g_0 + \\mathbf G
\\mathbf U \\ge 0` (rigid frictionless plane) and contact force
:math:`\\mathbf f^c = -\\mathbf G^T \\boldsymbol\\lambda`, :math:`\\boldsymbol\\lambda \\ge 0`:

.. math::

    \\mathbf M \\ddot{\\mathbf U} = \\mathbf f^{ext} - \\mathbf f^{int}(\\mathbf U) - \\mathbf f^c .

``scheme="kane"`` (paper eqs 6-10): the acceleration splits into an internal part and a
contact part; the predictor (8) uses only the internal part, the corrector (7) treats the
contact part fully implicitly, giving the step equation (9)

.. math::

    \\frac{1}{\\beta \\Delta t^2} \\mathbf M (\\mathbf U_{n+1} - \\tilde{\\mathbf U}_{n+1})
    = \\mathbf f^{ext}_{n+1} - \\mathbf f^{int}_{n+1} - \\frac{1}{2\\beta} \\mathbf f^c_{n+1}.

For a singular mass the contact DOFs carry no inertia; their rows are the algebraic equations
(12) :math:`0 = \\mathbf f^{ext,c} - \\mathbf f^{int,c} - \\mathbf f^c` and the inner rows are
(11). Both cases are one saddle-point system in :math:`(\\mathbf U, \\boldsymbol\\mu)` with
:math:`\\boldsymbol\\lambda = 2 \\beta \\boldsymbol\\mu` (regular mass, eq 9) or
:math:`\\boldsymbol\\lambda = \\boldsymbol\\mu` (massless contact DOFs, eq 12, or
``scheme="standard"``). It is solved by a semismooth Newton method on
:math:`\\min(\\boldsymbol\\mu, c \\mathbf g) = 0` (a primal-dual active set method); the
contact stiffness :math:`\\mathbf K_c` of eq 10 vanishes because the gap is linear.

>>> import scipy.sparse as sp
>>> M = sp.identity(1, format="csr")   # unit mass on a unit spring, no contact
>>> prob = ContactProblem(M, lambda u: (u.copy(), sp.identity(1, format="csr")),
...                       sp.csr_matrix((0, 1)), np.zeros(0), lambda u: 0.5 * float(u @ u))
>>> hist = integrate(prob, np.array([1.0]), np.zeros(1), dt=0.1, n_steps=100)
>>> bool(abs(hist.total[-1] - 0.5) < 1e-12)   # trapezoidal rule conserves energy
True

References
----------
C. Kane, E. Repetto, M. Ortiz, J. E. Marsden, "Finite element analysis of nonsmooth contact",
CMAME 180 (1999) 1-26. Paper eqs (6)-(12). M. Hintermueller, K. Ito, K. Kunisch, "The
primal-dual active set strategy as a semismooth Newton method", SIAM J. Optim. 13 (2003).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import ConvergenceError, InputError, check_positive, check_positive_int

__all__ = ["SCHEMES", "ContactProblem", "History", "Newmark", "State", "integrate", "step"]

SCHEMES = ("kane", "standard")


@dataclass(frozen=True)
class ContactProblem:
    """Mass ``M``, ``internal(u) -> (f_int, K_T)``, gap ``g0 + G u``, ``energy(u)`` (strain).

    ``directions`` (``(k, n)``) maps ``M v`` to the momentum components; ``f_ext`` is constant.
    """

    M: sp.csr_matrix
    internal: Callable
    G: sp.csr_matrix
    g0: np.ndarray
    energy: Callable
    f_ext: np.ndarray | None = None
    directions: np.ndarray | None = None

    @property
    def n(self) -> int:
        return self.M.shape[0]


@dataclass(frozen=True)
class Newmark:
    """Newmark parameters (``beta``, ``gamma``), ``scheme`` and Newton controls.

    ``tol`` bounds the total residual (force residual and complementarity) relative to
    ``max(1, |inertia|, |f_int|)``; ``solver="dense"`` is the benchmark baseline.
    """

    beta: float = 0.25
    gamma: float = 0.5
    scheme: str = "kane"
    tol: float = 1e-8
    max_iter: int = 25
    solver: str = "sparse"

    def __post_init__(self):
        check_positive("beta", self.beta)
        check_positive("gamma", self.gamma)
        if self.scheme not in SCHEMES:
            raise InputError(f"scheme must be one of {', '.join(SCHEMES)}; got {self.scheme!r}")
        if self.solver not in ("sparse", "dense"):
            raise InputError(f"solver must be 'sparse' or 'dense', got {self.solver!r}")
        check_positive("tol", self.tol)
        check_positive_int("max_iter", self.max_iter)


@dataclass
class State:
    """Displacement, velocity, internal and contact accelerations, contact forces ``lam`` at
    ``t``; ``iterations`` = Newton solves of the step, ``mu`` = raw multipliers (warm start)."""

    t: float
    u: np.ndarray
    v: np.ndarray
    a_int: np.ndarray
    a_c: np.ndarray
    lam: np.ndarray
    iterations: int = 0
    mu: np.ndarray | None = None


@dataclass
class History:
    """Time histories; ``contact_force`` is the total normal force :math:`\\sum \\lambda_k`."""

    t: list = field(default_factory=list)
    contact_force: list = field(default_factory=list)
    kinetic: list = field(default_factory=list)
    strain: list = field(default_factory=list)
    momentum: list = field(default_factory=list)
    gap_min: list = field(default_factory=list)
    iterations: list = field(default_factory=list)
    states: list = field(default_factory=list)

    @property
    def total(self) -> np.ndarray:
        return np.asarray(self.kinetic) + np.asarray(self.strain)

    def arrays(self) -> dict[str, np.ndarray]:
        out = {k: np.asarray(getattr(self, k)) for k in
               ("t", "contact_force", "kinetic", "strain", "momentum", "gap_min", "iterations")}
        out["total"] = self.total
        return out


class _Split:
    """Massive / massless DOF split and a factorization of the massive block of ``M``."""

    def __init__(self, prob: ContactProblem):
        M = sp.csr_matrix(prob.M)
        rowmax = np.asarray(abs(M).max(axis=1).todense()).ravel()
        self.massless = np.flatnonzero(rowmax <= 1e-14 * rowmax.max())
        self.massive = np.setdiff1d(np.arange(M.shape[0]), self.massless)
        Mmm = M[self.massive][:, self.massive].tocsc()
        self.solve = spla.factorized(Mmm)
        touched = np.unique(sp.csr_matrix(prob.G).indices)
        self.contact_massless = bool(len(touched)) and bool(np.all(np.isin(touched, self.massless)))


def _kinetic(M, v) -> float:
    return 0.5 * float(v @ (M @ v))


def step(prob: ContactProblem, nm: Newmark, state: State, dt: float, split=None) -> State:
    """Advance ``state`` by ``dt``; raises :class:`ConvergenceError` if Newton fails."""
    split = split or _Split(prob)
    beta, gamma = nm.beta, nm.gamma
    u, v = state.u, state.v
    a_pred = state.a_int if nm.scheme == "kane" else state.a_int + state.a_c
    ut = u + dt * v + 0.5 * dt**2 * (1 - 2 * beta) * a_pred
    vt = v + dt * (1 - gamma) * a_pred
    f_ext = np.zeros(prob.n) if prob.f_ext is None else prob.f_ext
    M, G = prob.M, sp.csr_matrix(prob.G)
    c1 = 1.0 / (beta * dt**2)
    c1M = c1 * M
    # Newton starts from the last converged configuration: the predictor itself carries the
    # high-frequency part of a_n and lies far from equilibrium in the stiff directions
    U = u.copy()
    mu = state.mu.copy() if state.mu is not None else np.zeros(G.shape[0])  # warm start
    c_ncp = None

    def residual(U, mu):
        f, K = prob.internal(U)
        inertia = c1 * (M @ (U - ut))
        g = prob.g0 + G @ U
        phi = np.minimum(mu, c_ncp * g) if c_ncp is not None else None
        return f, K, inertia, inertia + f - f_ext - G.T @ mu, g, phi

    f, K, inertia, r, g, _ = residual(U, mu)
    for it in range(1, nm.max_iter + 1):
        Keff = c1M + K
        if c_ncp is None:
            c_ncp = float(Keff.diagonal().max())
        phi = np.minimum(mu, c_ncp * g)
        merit = np.hypot(np.linalg.norm(r), np.linalg.norm(phi))
        scale = max(1.0, np.linalg.norm(inertia), np.linalg.norm(f))
        if it > 1 and merit <= nm.tol * scale:
            break
        act = np.flatnonzero(mu - c_ncp * g > 0)
        rhs = np.concatenate([-(inertia + f - f_ext), -g[act]])
        # the saddle-point matrix is only needed while a constraint is active
        A = sp.bmat([[Keff, -G[act].T], [G[act], None]], format="csc") if len(act) else Keff
        sol = np.linalg.solve(A.toarray(), rhs) if nm.solver == "dense" else spla.spsolve(A, rhs)
        if not np.all(np.isfinite(sol)):
            raise ConvergenceError(f"singular Newton matrix at t = {state.t + dt:.6g}")
        dU = sol[:prob.n]
        mu_new = np.zeros_like(mu)
        mu_new[act] = sol[prob.n:]
        # backtracking on the total residual: full steps near the solution, damped far away
        alpha = 1.0
        while True:
            trial = residual(U + alpha * dU, mu + alpha * (mu_new - mu))
            m_trial = np.hypot(np.linalg.norm(trial[3]), np.linalg.norm(trial[5]))
            if m_trial <= (1 - 1e-4 * alpha) * merit or alpha <= 1 / 32:
                break
            alpha /= 2
        U, mu = U + alpha * dU, mu + alpha * (mu_new - mu)
        f, K, inertia, r, g, _ = trial
    else:
        raise ConvergenceError(
            f"Newton did not reach tol = {nm.tol:g} in {nm.max_iter} iterations at "
            f"t = {state.t + dt:.6g} (dt = {dt:g}); residual {np.linalg.norm(r):.3e}")
    m, z = split.massive, split.massless
    a_int = np.zeros(prob.n)
    a_c = np.zeros(prob.n)
    v_new = np.zeros(prob.n)
    a_tot = c1 * (U - ut)[m]
    if nm.scheme == "kane":
        y = split.solve((G.T @ mu)[m]) if np.any(mu) else np.zeros(len(m))
        a_int[m], a_c[m] = a_tot - y, 2 * beta * y
        lam_scale = 1.0 if split.contact_massless else 2 * beta
    else:
        a_int[m] = a_tot
        lam_scale = 1.0
    v_new[m] = vt[m] + dt * gamma * a_int[m] + dt * a_c[m]
    v_new[z] = (U[z] - u[z]) / dt
    return State(state.t + dt, U, v_new, a_int, a_c, lam_scale * mu, it - 1, mu)


def _record(hist: History, prob: ContactProblem, s: State, keep_states: bool):
    hist.t.append(s.t)
    hist.contact_force.append(float(np.sum(s.lam)))
    hist.kinetic.append(_kinetic(prob.M, s.v))
    hist.strain.append(float(prob.energy(s.u)))
    mv = prob.M @ s.v
    hist.momentum.append(mv.sum(keepdims=True) if prob.directions is None else prob.directions @ mv)
    g = prob.g0 + prob.G @ s.u
    hist.gap_min.append(float(g.min()) if len(g) else np.inf)
    hist.iterations.append(s.iterations)
    if keep_states:
        hist.states.append(s)


def integrate(prob: ContactProblem, u0: np.ndarray, v0: np.ndarray, dt: float, n_steps: int,
              newmark: Newmark | None = None, progress: Callable | None = None,
              keep_states: bool = False) -> History:
    """Run ``n_steps`` steps of size ``dt`` from ``(u0, v0)`` (no initial contact force).

    ``progress(k)`` is called after each step (e.g. ``tqdm.update``).
    """
    nm = newmark or Newmark()
    check_positive("dt", dt)
    check_positive_int("n_steps", n_steps)
    split = _Split(prob)
    f0 = prob.internal(np.asarray(u0, float))[0]
    f_ext = np.zeros(prob.n) if prob.f_ext is None else prob.f_ext
    a0 = np.zeros(prob.n)
    a0[split.massive] = split.solve((f_ext - f0)[split.massive])
    s = State(0.0, np.asarray(u0, float), np.asarray(v0, float), a0, np.zeros(prob.n),
              np.zeros(prob.G.shape[0]))
    hist = History()
    _record(hist, prob, s, keep_states)
    for _ in range(n_steps):
        s = step(prob, nm, s, dt, split)
        _record(hist, prob, s, keep_states)
        if progress is not None:
            progress(1)
    return hist
