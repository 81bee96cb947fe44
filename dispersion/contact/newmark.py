"""Time stepping with Lagrange-multiplier contact: Kane's Newmark, standard Newmark, central differences.

Semi-discrete problem (paper eq 5) with a linear gap :math:`\\mathbf g = \\mathbf g_0 + \\mathbf G
\\mathbf U \\ge 0` (rigid frictionless obstacle) and contact force
:math:`\\mathbf f^c = -\\mathbf G^T \\boldsymbol\\lambda`, :math:`\\boldsymbol\\lambda \\ge 0`:

.. math::

    \\mathbf M \\ddot{\\mathbf U} = \\mathbf f^{ext} - \\mathbf f^{int}(\\mathbf U) - \\mathbf f^c .

``scheme="kane"`` (paper eqs 6-10): the predictor (8) uses only the internal acceleration, the
corrector (7) treats the contact part fully implicitly, giving the step equation (9)

.. math::

    \\frac{1}{\\beta \\Delta t^2} \\mathbf M (\\mathbf U_{n+1} - \\tilde{\\mathbf U}_{n+1})
    = \\mathbf f^{ext}_{n+1} - \\mathbf f^{int}_{n+1} - \\frac{1}{2\\beta} \\mathbf f^c_{n+1}.

``beta = 0`` is the explicit central-difference scheme with the same implicit contact impulse:
:math:`\\tfrac{2}{\\Delta t^2} \\mathbf M (\\mathbf U_{n+1} - \\tilde{\\mathbf U}_{n+1}) =
\\mathbf G^T \\boldsymbol\\lambda` on the rows with mass. Rows without mass (singular mass,
eqs 11-12) are the algebraic equations :math:`\\mathbf 0 = \\mathbf f^{ext} - \\mathbf f^{int}
- \\mathbf f^c` in every scheme. One step is a saddle-point system in
:math:`(\\mathbf U, \\boldsymbol\\mu)`, solved by a semismooth Newton method on
:math:`\\min(\\boldsymbol\\mu, c \\mathbf g) = 0` (primal-dual active set). For a linear problem
(``ContactProblem.K`` given) the step matrix never changes: it is factorized once and the
contact is a small linear complementarity problem on the constrained DOFs.

>>> import scipy.sparse as sp
>>> K = sp.identity(1, format="csr")   # unit mass on a unit spring, no contact
>>> prob = ContactProblem(K, lambda u: (K @ u, K), sp.csr_matrix((0, 1)), np.zeros(0),
...                       lambda u: 0.5 * float(u @ u), K=K)
>>> hist = integrate(prob, np.array([1.0]), np.zeros(1), dt=0.1, n_steps=100)
>>> bool(abs(hist.total[-1] - 0.5) < 1e-12)   # trapezoidal rule conserves energy
True

References
----------
C. Kane, E. Repetto, M. Ortiz, J. E. Marsden, "Finite element analysis of nonsmooth contact",
CMAME 180 (1999) 1-26. Paper eqs (6)-(12). M. Hintermueller, K. Ito, K. Kunisch, "The
primal-dual active set strategy as a semismooth Newton method", SIAM J. Optim. 13 (2003).
T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3 (central differences:
stable for :math:`\\omega_{max} \\Delta t \\le 2`).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from dispersion.errors import ConvergenceError, InputError, check_positive, check_positive_int
from dispersion.contact.complementarity import solve_lcp
from dispersion.contact.contact_problem import ContactProblem
from dispersion.contact.linear_solver import LinearSolver
from dispersion.contact.mass_split import MassSplit
from dispersion.contact.newmark_scheme import Newmark
from dispersion.splines.matrix_kind import dense, is_sparse
from dispersion.contact.semismooth_newton import Tangent, newton

if TYPE_CHECKING:
    pass

__all__ = ["History", "State", "critical_step", "consistent_state", "integrate", "step"]

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
    """Time histories; ``contact_force`` is the total normal force :math:`\\sum \\lambda_k`.

    ``initial_energy_change`` is the total energy the consistent initial state added to the
    given one (negative: removed), ``lam`` the multipliers per step (rows: constraints).
    """

    t: list = field(default_factory=list)
    contact_force: list = field(default_factory=list)
    kinetic: list = field(default_factory=list)
    strain: list = field(default_factory=list)
    potential: list = field(default_factory=list)
    momentum: list = field(default_factory=list)
    gap_min: list = field(default_factory=list)
    iterations: list = field(default_factory=list)
    states: list = field(default_factory=list)
    lam: list = field(default_factory=list)
    initial_energy_change: float = 0.0

    @property
    def total(self) -> np.ndarray:
        return np.asarray(self.kinetic) + np.asarray(self.strain) + np.asarray(self.potential)

    def arrays(self) -> dict[str, np.ndarray]:
        out = {k: np.asarray(getattr(self, k)) for k in
               ("t", "contact_force", "kinetic", "strain", "potential", "momentum", "gap_min",
                "iterations")}
        out["total"] = self.total
        return out


class _Linear:
    """Factorized step matrix ``c1 M + P K`` and its response to the constraints (linear)."""

    def __init__(self, prob: ContactProblem, split: MassSplit, nm: Newmark, c1: float):
        if is_sparse(split.M):
            import scipy.sparse as sp

            K = sp.csr_matrix(prob.K)
            if nm.explicit:
                K = sp.diags(split.rows.astype(float)) @ K
            A = (c1 * split.M + K).tocsc()
        else:
            K = dense(prob.K)
            if nm.explicit:
                K = split.rows.astype(float)[:, None] * K
            A = c1 * split.M + K
        solver = LinearSolver(prob.n, nm)
        self.solve = solver.factor(solver.matrix(A))
        G = split.G
        self.W = self.solve(dense(split.G).T) if G.shape[0] else np.zeros((prob.n, 0))
        self.S = G @ self.W
        self.K = K


def step(prob: ContactProblem, nm: Newmark, state: State, dt: float, split=None,
         linear=None, tangent=None) -> State:
    """Advance ``state`` by ``dt``; raises :class:`ConvergenceError` if Newton fails.

    ``split``, ``linear`` and ``tangent`` carry what does not change between steps (built
    on first use when omitted).
    """
    split = split or MassSplit(prob, nm)
    beta, gamma = nm.beta, nm.gamma
    u, v = state.u, state.v
    explicit = nm.explicit
    c1 = 2.0 / dt**2 if explicit else 1.0 / (beta * dt**2)
    a_pred = state.a_int if nm.scheme == "kane" else state.a_int + state.a_c
    ut = u + dt * v + 0.5 * dt**2 * (1 - 2 * beta) * a_pred
    vt = v + dt * (1 - gamma) * a_pred
    f_ext = split.f_ext
    rows = split.rows if explicit else None  # rows with an implicit internal force
    G = split.G
    if prob.K is not None:
        linear = linear or _Linear(prob, split, nm, c1)
        M = split.Md if split.Md is not None else split.M
        rhs = c1 * (M @ ut) + (f_ext if rows is None else np.where(rows, f_ext, 0.0))
        U0 = linear.solve(rhs)
        mu = np.zeros(G.shape[0])
        if G.shape[0]:
            Gm = split.Gd if split.Gd is not None else G
            mu = solve_lcp(linear.S, prob.g0 + Gm @ U0, nm.max_iter)
        U = U0 + linear.W @ mu
        it = 1
        f = prob.internal(U)[0] if explicit else None
    else:
        # start from the second-order Taylor guess of the internal motion
        guess = u + dt * v + 0.5 * dt**2 * state.a_int
        U, mu, it, f = newton(prob, nm, split, state, ut, c1, rows, tangent=tangent,
                               guess=guess)
    m, z = split.massive, split.massless
    n = prob.n
    a_int = np.zeros(n)
    a_c = np.zeros(n)
    v_new = np.zeros(n)
    lam_scale = np.where(split.only_massless, 1.0, 1.0 if explicit else 2 * beta)
    if explicit:
        a_int = split.a_int(f)
        a_c[m] = c1 * (U - ut)[m]
        v_new[m] = vt[m] + dt * gamma * a_int[m] + dt * a_c[m]
    else:
        a_tot = c1 * (U - ut)[m]
        if nm.scheme == "kane":
            GT = split.Gd.T if split.Gd is not None else G.T
            y = split.solve((GT @ mu)[m]) if mu.any() else np.zeros(len(m))
            a_int[m], a_c[m] = a_tot - y, 2 * beta * y
        else:
            a_int[m] = a_tot
            lam_scale = np.ones(G.shape[0])
        v_new[m] = vt[m] + dt * gamma * a_int[m] + dt * a_c[m]
    v_new[z] = (U[z] - u[z]) / dt
    return State(state.t + dt, U, v_new, a_int, a_c, lam_scale * mu, it, mu)


def critical_step(prob: ContactProblem, u: np.ndarray | None = None) -> float:
    """Largest stable explicit step :math:`2 / \\omega_{max}` (s) of the massive DOFs.

    :math:`\\omega_{max}^2` is the largest eigenvalue of :math:`\\mathbf K_{mm} \\mathbf x =
    \\omega^2 \\mathbf M_{mm} \\mathbf x` with the tangent at ``u`` (default 0) restricted to the
    DOFs with mass: massless DOFs held fixed (in contact) make the system stiffest; condensing
    them out (free) only lowers :math:`\\omega_{max}`.

    >>> import scipy.sparse as sp
    >>> K = sp.csr_matrix([[4.0]])
    >>> critical_step(ContactProblem(sp.identity(1, format="csr"), lambda u: (K @ u, K),
    ...               sp.csr_matrix((0, 1)), np.zeros(0), lambda u: 0.0))
    1.0
    """
    split = MassSplit(prob, Newmark())
    u = np.zeros(prob.n) if u is None else np.asarray(u, float)
    K = dense(prob.internal(u)[1])
    m = split.massive
    Kmm = K[np.ix_(m, m)]
    Mmm = dense(split.M)[np.ix_(m, m)]
    # K x = w^2 M x with M = L L^T: the standard problem L^-1 K L^-T (numpy alone)
    L = np.linalg.cholesky(Mmm)
    X = np.linalg.solve(L, Kmm)
    w2 = float(np.linalg.eigvalsh(np.linalg.solve(L, X.T).T)[-1])
    return float(2.0 / np.sqrt(w2)) if w2 > 0 else float("inf")


def consistent_state(prob: ContactProblem, u0: np.ndarray, nm: Newmark | None = None,
                     split=None) -> tuple[np.ndarray, np.ndarray]:
    """Displacement and multipliers at t = 0 with the massless DOFs in equilibrium.

    The DOFs with mass keep ``u0``; the massless ones solve :math:`\\mathbf f^{int}_z(\\mathbf u)
    = \\mathbf f^{ext}_z + (\\mathbf G^T \\boldsymbol\\lambda)_z`, :math:`\\mathbf g \\ge 0`,
    :math:`\\boldsymbol\\lambda \\ge 0`, :math:`\\boldsymbol\\lambda \\cdot \\mathbf g = 0`
    (eq 12 at t = 0). Without massless DOFs ``u0`` is returned unchanged.
    """
    nm = nm or Newmark()
    split = split or MassSplit(prob, nm)
    u0 = np.asarray(u0, float)
    if len(split.massless) == 0:
        return u0.copy(), np.zeros(prob.G.shape[0])
    s = State(0.0, u0, np.zeros(prob.n), np.zeros(prob.n), np.zeros(prob.n),
              np.zeros(prob.G.shape[0]))
    fixed = ~split.rows
    U, mu, _, _ = newton(prob, nm, split, s, u0, 0.0, split.rows, fixed)
    return U, mu


def _record(hist: History, prob: ContactProblem, split: MassSplit, s: State, keep_states: bool):
    hist.t.append(s.t)
    hist.contact_force.append(float(s.lam.sum()))
    hist.lam.append(s.lam)
    M = split.Md if split.Md is not None else split.M
    mv = M @ s.v
    hist.kinetic.append(0.5 * float(s.v @ mv))
    hist.strain.append(float(prob.energy(s.u)))
    hist.potential.append(-float(split.f_ext @ s.u))
    hist.momentum.append(mv.sum(keepdims=True) if prob.directions is None else prob.directions @ mv)
    g = prob.g0 + (split.Gd if split.Gd is not None else split.G) @ s.u
    hist.gap_min.append(float(g.min()) if len(g) else np.inf)
    hist.iterations.append(s.iterations)
    if keep_states:
        hist.states.append(s)


def integrate(prob: ContactProblem, u0: np.ndarray, v0: np.ndarray, dt: float, n_steps: int,
              newmark: Newmark | None = None, progress: Callable | None = None,
              keep_states: bool = False, consistent: bool = True,
              penetration_tol: float = 1e-12) -> History:
    """Run ``n_steps`` steps of size ``dt`` from ``(u0, v0)``.

    ``consistent`` (default) first puts the massless DOFs in equilibrium with contact
    (:func:`consistent_state`); ``History.initial_energy_change`` reports what that changed.
    An initial gap below ``-penetration_tol * max(1, |g0|)`` is refused, as is an explicit
    step above :func:`critical_step`. ``progress(k)`` is called after each step.
    """
    # overflow and invalid values surface as ConvergenceError (a non-finite state, a singular
    # matrix), not as numpy warnings printed before the one-line error
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        return _integrate(prob, u0, v0, dt, n_steps, newmark, progress, keep_states,
                          consistent, penetration_tol)


def _integrate(prob, u0, v0, dt, n_steps, newmark, progress, keep_states, consistent,
               penetration_tol) -> History:
    nm = newmark or Newmark()
    check_positive("dt", dt)
    if not (float(dt) ** 2 > 0 and 1.0 / float(dt) ** 2 < np.inf):  # matrices ~ 1 / dt^2
        raise InputError(f"dt must be >= 1e-150 (1/dt^2 overflows), got {dt!r}")
    check_positive_int("n_steps", n_steps)
    u0 = np.asarray(u0, float)
    v0 = np.asarray(v0, float)
    if u0.shape != (prob.n,) or v0.shape != (prob.n,):
        raise InputError(f"u0 and v0 must have shape ({prob.n},), got {u0.shape}, {v0.shape}")
    if not (np.all(np.isfinite(u0)) and np.all(np.isfinite(v0))):
        raise InputError("u0 and v0 must be finite")
    split = MassSplit(prob, nm)
    g = prob.g0 + split.G @ u0
    tol = penetration_tol * max(1.0, float(np.abs(prob.g0).max()) if len(g) else 1.0)
    if len(g) and g.min() < -tol:
        raise InputError(f"u0 penetrates the obstacle (min gap {g.min():.3g}); the initial "
                         "gap must be >= 0")
    if nm.explicit:
        dt_crit = critical_step(prob, u0)
        if dt > dt_crit:
            raise InputError(f"dt must be <= the explicit stability limit {dt_crit:.6g} "
                             f"(2 / omega_max), got {dt:g}")
    hist = History()
    mu0 = np.zeros(prob.G.shape[0])
    if consistent and len(split.massless):
        E_given = (0.5 * float(v0 @ (split.M @ v0)) + float(prob.energy(u0))
                   - float(split.f_ext @ u0))
        u0, mu0 = consistent_state(prob, u0, nm, split)
        E_new = (0.5 * float(v0 @ (split.M @ v0)) + float(prob.energy(u0))
                 - float(split.f_ext @ u0))
        hist.initial_energy_change = E_new - E_given
    f0 = prob.internal(u0)[0]
    a0 = split.a_int(f0)
    s = State(0.0, u0, v0, a0, np.zeros(prob.n), mu0.copy(), 0, mu0)
    _record(hist, prob, split, s, keep_states)
    linear, tangent = None, Tangent()
    if prob.K is not None:
        linear = _Linear(prob, split, nm, 2.0 / dt**2 if nm.explicit else 1 / (nm.beta * dt**2))
    for _ in range(n_steps):
        s = step(prob, nm, s, dt, split, linear, tangent)
        if not (np.isfinite(s.u).all() and np.isfinite(s.v).all()):
            raise ConvergenceError(f"the state became non-finite at t = {s.t:.6g}; the "
                                   "scene's scale (speeds, sizes, dt) is beyond double precision")
        _record(hist, prob, split, s, keep_states)
        if progress is not None:
            progress(1)
    return hist
