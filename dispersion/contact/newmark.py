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
import numpy as np

from dispersion.errors import ConvergenceError, InputError, check_positive, check_positive_int
from dispersion.contact.complementarity import solve_lcp
from dispersion.contact.contact_problem import ContactProblem
from dispersion.contact.linear_solver import LinearSolver
from dispersion.contact.mass_split import MassSplit
from dispersion.contact.newmark_scheme import Newmark
from dispersion.contact.run_batch import RunBatch
from dispersion.splines.matrix_kind import dense, is_sparse
from dispersion.contact.semismooth_newton import Tangent, newton

__all__ = ["History", "State", "critical_step", "consistent_state", "integrate",
           "integrate_many", "step"]

@dataclass
class State:
    """Displacement, velocity, internal and contact accelerations, contact forces ``lam`` at
    ``t``; ``iterations`` = Newton solves of the step, ``mu`` = raw multipliers (warm start),
    ``energy`` = the strain energy at ``u`` if the step already has it."""

    t: float
    u: np.ndarray
    v: np.ndarray
    a_int: np.ndarray
    a_c: np.ndarray
    lam: np.ndarray
    iterations: int = 0
    mu: np.ndarray | None = None
    #: Strain energy at ``u`` where the step evaluated it with the force (None: not yet).
    energy: float | None = None


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
    #: Why the run stopped early (Newton failed, a non-finite state), else None.
    error: str | None = None

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
        # a small dense system is solved as a product with its inverse: K runs stepped
        # together then take one batched product (LinearSolver.factor's dense route)
        self.inverse = getattr(self.solve, "inverse", None)
        G = split.G
        self.W = self.solve(dense(split.G).T) if G.shape[0] else np.zeros((prob.n, 0))
        if self.W.ndim == 1:
            self.W = self.W[:, None]
        self.S = np.asarray(G @ self.W)
        self.K = K


class _Linears(list):
    """The factorizations of K linear runs, with what a batched step takes from them
    stacked once (inverses, constraint responses, one-constraint Schur complements)."""

    def __init__(self, linears):
        super().__init__(linears)
        inv = [lin.inverse for lin in linears]
        self.inverse = None if any(x is None for x in inv) else np.stack(inv)
        self.W = np.stack([lin.W for lin in linears])
        self.S1 = (np.array([lin.S[0, 0] for lin in linears])
                   if linears and linears[0].S.shape == (1, 1) else None)

    def subset(self, keep) -> _Linears:
        return _Linears([self[k] for k in keep])


def _solve_linear(batch: RunBatch, linears: _Linears, nm: Newmark, ut, rows):
    """One step of K linear problems: the factorized step matrices and the contact LCPs."""
    f_ext = batch.f_ext if rows is None else np.where(rows, batch.f_ext, 0.0)
    rhs = batch.c1[:, None] * batch.mass(ut) + f_ext
    if linears.inverse is not None:
        U0 = np.matmul(linears.inverse, rhs[:, :, None])[:, :, 0]
    else:
        U0 = np.stack([lin.solve(b) for lin, b in zip(linears, rhs)])
    mu = np.zeros((batch.K, batch.nc))
    if batch.nc:
        q = batch.gap(U0)
        if linears.S1 is not None:  # one contact point: the complementarity in closed form
            mu[:, 0] = np.maximum(0.0, -q[:, 0] / linears.S1)
        else:
            mu = np.stack([solve_lcp(lin.S, qk, nm.max_iter) for lin, qk in zip(linears, q)])
    U = U0 + np.matmul(linears.W, mu[:, :, None])[:, :, 0]
    f = batch.force(U)[0] if nm.explicit else None
    return U, mu, np.ones(batch.K, dtype=int), f, None, {}


def _a_int(batch: RunBatch, f: np.ndarray) -> np.ndarray:
    """Internal accelerations ``M^-1 (f_ext - f)`` on the massive DOFs (0 elsewhere)."""
    a = np.zeros_like(f)
    a[:, batch.massive] = batch.mass_solve((batch.f_ext - f)[:, batch.massive])
    return a


def _contact_acceleration(batch: RunBatch, mu: np.ndarray, m) -> np.ndarray:
    """``M_mm^-1 (G^T mu)_m`` of every run, zero (not solved for) where a run has no
    contact force."""
    y = np.zeros((batch.K, batch.n if isinstance(m, slice) else len(m)))
    touching = mu.any(axis=1)
    if touching.any():
        on = np.flatnonzero(touching)
        force = batch.contact_force(mu)[:, m]
        if batch.mass_diagonal is not None:
            y[on] = force[on] / batch.mass_diagonal[on]
        else:
            y[on] = np.stack([batch.splits[k].solve(force[k]) for k in on])
    return y


def _step(batch: RunBatch, s: dict, linears, tangents) -> tuple[dict, dict]:
    """Advance the K runs' state arrays ``s`` (``t``, ``u``, ``v``, ``a_int``, ``a_c``,
    ``mu``) by their steps; return the new arrays and ``{run: message}`` of failed runs."""
    nm = batch.nm
    beta, gamma = nm.beta, nm.gamma
    u, v = s["u"], s["v"]
    explicit = nm.explicit
    dt = batch.dt[:, None]
    c1 = batch.c1[:, None]
    a_pred = s["a_int"] if nm.scheme == "kane" else s["a_int"] + s["a_c"]
    ut = u + dt * v + 0.5 * dt**2 * (1 - 2 * beta) * a_pred
    vt = v + dt * (1 - gamma) * a_pred
    rows = batch.rows if explicit else None  # rows with an implicit internal force
    if linears is not None:
        U, mu, it, f, W, failed = _solve_linear(batch, linears, nm, ut, rows)
    else:
        # start from the second-order Taylor guess of the internal motion
        guess = u + dt * v + 0.5 * dt**2 * s["a_int"]
        U, mu, it, f, W, failed = newton(batch, tangents, u, s["mu"], s["t"], ut, rows, guess)
    m, z = batch.massive, batch.massless
    lam_scale = np.where(batch.only_massless, 1.0, 1.0 if explicit else 2 * beta)
    if explicit:
        a_int = _a_int(batch, f)
        a_c = np.zeros_like(U)
        a_c[:, m] = (c1 * (U - ut))[:, m]
        v_new = np.zeros_like(U)
        v_new[:, m] = vt[:, m] + dt * gamma * a_int[:, m] + dt * a_c[:, m]
    elif not len(z):  # every DOF has mass: whole arrays, no index copies
        a_tot = c1 * (U - ut)
        if nm.scheme == "kane":
            y = _contact_acceleration(batch, mu, slice(None))
            a_int, a_c = a_tot - y, 2 * beta * y
        else:
            a_int, a_c = a_tot, np.zeros_like(U)
            lam_scale = np.ones(batch.nc)
        v_new = vt + dt * gamma * a_int + dt * a_c
    else:
        a_tot = (c1 * (U - ut))[:, m]
        a_int, a_c = np.zeros_like(U), np.zeros_like(U)
        if nm.scheme == "kane":
            y = _contact_acceleration(batch, mu, m)
            a_int[:, m], a_c[:, m] = a_tot - y, 2 * beta * y
        else:
            a_int[:, m] = a_tot
            lam_scale = np.ones(batch.nc)
        v_new = np.zeros_like(U)
        v_new[:, m] = vt[:, m] + dt * gamma * a_int[:, m] + dt * a_c[:, m]
    if len(z):
        v_new[:, z] = (U[:, z] - u[:, z]) / dt
    new = {"t": s["t"] + batch.dt, "u": U, "v": v_new, "a_int": a_int, "a_c": a_c,
           "lam": lam_scale * mu, "mu": mu, "iterations": it, "energy": W}
    return new, failed


def step(prob: ContactProblem, nm: Newmark, state: State, dt: float, split=None,
         linear=None, tangent=None) -> State:
    """Advance ``state`` by ``dt``; raises :class:`ConvergenceError` if Newton fails.

    ``split``, ``linear`` and ``tangent`` carry what does not change between steps (built
    on first use when omitted). One run of the batched step of :func:`integrate_many`.
    """
    split = split or MassSplit(prob, nm)
    batch = RunBatch([prob], [split], nm, [dt])
    if prob.K is not None:
        linear = linear or _Linear(prob, split, nm, float(batch.c1[0]))
    s = {"t": np.array([state.t]), "u": state.u[None], "v": state.v[None],
         "a_int": state.a_int[None], "a_c": state.a_c[None],
         "mu": (state.mu if state.mu is not None else np.zeros(batch.nc))[None]}
    new, failed = _step(batch, s, None if linear is None else _Linears([linear]),
                        None if linear is not None else [tangent or Tangent()])
    if failed:
        raise ConvergenceError(failed[0])
    return _state(new, 0)


def _state(s: dict, k: int) -> State:
    W = s.get("energy")
    return State(float(s["t"][k]), s["u"][k], s["v"][k], s["a_int"][k], s["a_c"][k],
                 s["lam"][k], int(s["iterations"][k]), s["mu"][k],
                 None if W is None else float(W[k]))


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
    batch = RunBatch([prob], [split], nm, [1.0])
    batch.c1 = np.zeros(1)  # no inertia: the massless rows' equilibrium alone
    U, mu, _, _, _, failed = newton(batch, [Tangent()], u0[None], np.zeros((1, batch.nc)),
                                    np.zeros(1), u0[None], split.rows, u0[None],
                                    fixed=~split.rows)
    if failed:
        raise ConvergenceError(failed[0])
    return U[0], mu[0]


def _record(hists: list, batch: RunBatch, s: dict, keep_states: bool) -> None:
    """Append the K runs' step to their histories (the energies, momenta and gaps of all
    runs computed together)."""
    U, V, lam = s["u"], s["v"], s["lam"]
    mv = batch.mass(V)
    kinetic = 0.5 * np.add.reduce(V * mv, axis=1)
    strain = s.get("energy")
    if strain is None:
        strain = batch.strain_energy(None if batch.forces is None else batch.force(U)[1], U)
    potential = -np.add.reduce(batch.f_ext * U, axis=1)
    if batch.directions is None:
        momentum = mv.sum(axis=1, keepdims=True)
    else:
        momentum = np.matmul(batch.directions, mv[:, :, None])[:, :, 0]
    gap_min = batch.gap(U).min(axis=1) if batch.nc else np.full(batch.K, np.inf)
    force = lam.sum(axis=1)
    for k, hist in enumerate(hists):
        hist.t.append(float(s["t"][k]))
        hist.contact_force.append(float(force[k]))
        hist.lam.append(lam[k])
        hist.kinetic.append(float(kinetic[k]))
        hist.strain.append(float(strain[k]))
        hist.potential.append(float(potential[k]))
        hist.momentum.append(momentum[k])
        hist.gap_min.append(float(gap_min[k]))
        hist.iterations.append(int(s["iterations"][k]))
        if keep_states:
            hist.states.append(_state(s, k))


def integrate(prob: ContactProblem, u0: np.ndarray, v0: np.ndarray, dt: float, n_steps: int,
              newmark: Newmark | None = None, progress: Callable | None = None,
              keep_states: bool = False, consistent: bool = True,
              penetration_tol: float = 1e-12) -> History:
    """Run ``n_steps`` steps of size ``dt`` from ``(u0, v0)``.

    ``consistent`` (default) first puts the massless DOFs in equilibrium with contact
    (:func:`consistent_state`); ``History.initial_energy_change`` reports what that changed.
    An initial gap below ``-penetration_tol * max(1, |g0|)`` is refused, as is an explicit
    step above :func:`critical_step`. ``progress(k)`` is called after each step. Raises
    :class:`~dispersion.errors.ConvergenceError` where Newton fails or the state becomes
    non-finite. The run is :func:`integrate_many` with one run.
    """
    hist = integrate_many([prob], [u0], [v0], [dt], [n_steps], newmark, progress,
                          keep_states, consistent, penetration_tol)[0]
    if hist.error is not None:
        raise ConvergenceError(hist.error)
    return hist


def integrate_many(probs: list[ContactProblem], u0s, v0s, dts, n_steps, newmark=None,
                   progress: Callable | None = None, keep_states: bool = False,
                   consistent: bool = True, penetration_tol: float = 1e-12) -> list[History]:
    """Run K problems together, run k ``n_steps[k]`` steps of ``dts[k]`` from
    ``(u0s[k], v0s[k])``: one :class:`History` per run, as :func:`integrate` gives it.

    The problems need the same DOF layout (:class:`~.run_batch.RunBatch`); each run is
    stepped as it would be alone, its states stacked with the others' so that every array
    operation serves all runs (a small problem's step is dominated by the fixed cost of
    each operation). A run that fails (Newton, a non-finite state) stops with its
    ``History.error`` set; the others go on; a run that has taken its steps leaves the
    batch. ``progress(1)`` is called after each step of the batch. Bad input (shapes,
    steps, a penetrating start, an explicit step above the limit) raises
    :class:`~dispersion.errors.InputError` naming the run.
    """
    # overflow and invalid values surface as failures (a non-finite state, a singular
    # matrix), not as numpy warnings printed before the one-line error
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        return _integrate_many(list(probs), u0s, v0s, dts, n_steps, newmark, progress,
                               keep_states, consistent, penetration_tol)


def _check_run(prob, u0, v0, dt, n_steps, nm, split, penetration_tol, name):
    check_positive(f"dt{name}", dt)
    if not (float(dt) ** 2 > 0 and 1.0 / float(dt) ** 2 < np.inf):  # matrices ~ 1 / dt^2
        raise InputError(f"dt{name} must be >= 1e-150 (1/dt^2 overflows), got {dt!r}")
    check_positive_int(f"n_steps{name}", n_steps)
    u0 = np.asarray(u0, float)
    v0 = np.asarray(v0, float)
    if u0.shape != (prob.n,) or v0.shape != (prob.n,):
        raise InputError(f"u0 and v0{name} must have shape ({prob.n},), got {u0.shape}, "
                         f"{v0.shape}")
    if not (np.all(np.isfinite(u0)) and np.all(np.isfinite(v0))):
        raise InputError(f"u0 and v0{name} must be finite")
    g = prob.g0 + split.G @ u0
    tol = penetration_tol * max(1.0, float(np.abs(prob.g0).max()) if len(g) else 1.0)
    if len(g) and g.min() < -tol:
        raise InputError(f"u0{name} penetrates the obstacle (min gap {g.min():.3g}); the "
                         "initial gap must be >= 0")
    if nm.explicit:
        dt_crit = critical_step(prob, u0)
        if dt > dt_crit:
            raise InputError(f"dt{name} must be <= the explicit stability limit "
                             f"{dt_crit:.6g} (2 / omega_max), got {dt:g}")
    return u0, v0


def _integrate_many(probs, u0s, v0s, dts, n_steps, newmark, progress, keep_states,
                    consistent, penetration_tol) -> list[History]:
    nm = newmark or Newmark()
    K = len(probs)
    if not K or not len(u0s) == len(v0s) == len(dts) == len(n_steps) == K:
        raise InputError(f"probs, u0s, v0s, dts and n_steps must be K >= 1 runs each, got "
                         f"{K}, {len(u0s)}, {len(v0s)}, {len(dts)}, {len(n_steps)}")
    splits = [MassSplit(p, nm) for p in probs]
    hists = [History() for _ in probs]
    starts = []
    for k, (prob, split) in enumerate(zip(probs, splits)):
        name = "" if K == 1 else f" (run {k})"
        u0, v0 = _check_run(prob, u0s[k], v0s[k], dts[k], n_steps[k], nm, split,
                            penetration_tol, name)
        mu0 = np.zeros(prob.G.shape[0])
        if consistent and len(split.massless):
            E_given = (0.5 * float(v0 @ (split.M @ v0)) + float(prob.energy(u0))
                       - float(split.f_ext @ u0))
            try:
                u0, mu0 = consistent_state(prob, u0, nm, split)
            except ConvergenceError as exc:
                hists[k].error = str(exc)
            E_new = (0.5 * float(v0 @ (split.M @ v0)) + float(prob.energy(u0))
                     - float(split.f_ext @ u0))
            hists[k].initial_energy_change = E_new - E_given
        starts.append((u0, v0, mu0))
    batch = RunBatch(probs, splits, nm, [float(d) for d in dts])
    U0 = np.stack([x[0] for x in starts])
    f0, strains0 = batch.force(U0)
    W0 = batch.strain_energy(strains0, U0)
    s = {"t": np.zeros(K), "u": U0, "v": np.stack([x[1] for x in starts]),
         "a_int": _a_int(batch, f0), "a_c": np.zeros_like(U0),
         "mu": np.stack([x[2] for x in starts]), "lam": np.stack([x[2] for x in starts]),
         "iterations": np.zeros(K, dtype=int), "energy": W0}
    _record(hists, batch, s, keep_states)
    runs = np.flatnonzero([h.error is None for h in hists])  # the runs of the batch
    left = np.asarray(n_steps)
    linear = probs[0].K is not None
    linears = (_Linears([_Linear(p, sp_, nm, float(c))
                         for p, sp_, c in zip(probs, splits, batch.c1)]) if linear else None)
    tangents = None if linear else [Tangent() for _ in probs]
    if not len(runs):
        return hists
    if len(runs) < K:
        batch, s, linears, tangents = _keep(batch, s, linears, tangents, runs)
    taken = 0
    while len(runs):
        s, failed = _step(batch, s, linears, tangents)
        taken += 1
        bad = dict(failed)
        finite = np.isfinite(s["u"]).all(axis=1) & np.isfinite(s["v"]).all(axis=1)
        for i in np.flatnonzero(~finite):
            bad.setdefault(int(i), f"the state became non-finite at t = {s['t'][i]:.6g}; the "
                                   "scene's scale (speeds, sizes, dt) is beyond double "
                                   "precision")
        ok = np.array([i not in bad for i in range(len(runs))])
        for i, message in bad.items():
            hists[runs[i]].error = message
        if bad:
            if ok.any():
                good = np.flatnonzero(ok)
                _record([hists[r] for r in runs[good]], batch.subset(good), _rows(s, good),
                        keep_states)
        else:
            _record([hists[r] for r in runs], batch, s, keep_states)
        if progress is not None:
            progress(1)
        still = ok & (left[runs] > taken)
        if not still.any():
            break
        if not still.all():
            keep = np.flatnonzero(still)
            batch, s, linears, tangents = _keep(batch, s, linears, tangents, keep)
            runs = runs[keep]
    return hists


def _rows(s: dict, keep: np.ndarray) -> dict:
    return {k: (None if v is None else v[keep]) for k, v in s.items()}


def _keep(batch, s, linears, tangents, keep):
    """The batch, state, factorizations and tangents of the runs ``keep`` only."""
    keep = np.asarray(keep, dtype=int)
    return (batch.subset(keep), _rows(s, keep),
            None if linears is None else linears.subset(keep),
            None if tangents is None else [tangents[k] for k in keep])
