"""One-dimensional impact problems: an elastic B-spline bar (P1 = degree 1) against a rigid wall.

A bar on :math:`[0, L]` (unit area, modulus :math:`E`, density :math:`\\rho`, wave speed
:math:`c = \\sqrt{E/\\rho}`) discretized by open uniform B-splines of degree :math:`p`
(:mod:`dispersion.splines.bspline`; :math:`p = 1` is the P1 finite element), with either end free or
clamped, a rigid wall at distance ``gap`` beyond the left or the right end, initial
displacement and velocity fields and a body force :math:`b(x)`:

.. math::

    \\rho u_{tt} = E u_{xx} + b, \\qquad g = \\mathrm{gap} \\pm u(x_c) \\ge 0, \\quad
    \\lambda \\ge 0, \\quad \\lambda g = 0 .

The mass is any rule of :mod:`dispersion.mass_rules.mass_rule` (a name or a
:class:`~dispersion.mass_rules.mass_rule.MassRule`); the singular ones redistribute
the contact end's function onto its two neighbours (paper eqs 2-4).

A bar of up to :data:`DENSE_DOFS` functions is assembled as numpy arrays on the float
B-spline basis (:meth:`~dispersion.splines.bspline.SplineBasis1D.uniform`), and the rules
that read only the consistent mass and the redistribution (:data:`NUMERIC_RULES`) are
applied to it in floats: such a run imports neither sympy nor scipy (issue 23: their import
costs more than a whole small run). Larger bars are assembled sparse (scipy), and the rules
that evaluate the basis (HRZ, nodal quadratures, user rules) are given the exact knot vector.

Validation case (:func:`simulate_bar`): a free bar moving with velocity :math:`-v_0` touches
the wall at :math:`x = 0` at :math:`t = 0`. The exact solution (d'Alembert) keeps contact for
exactly :math:`2L/c` with constant contact stress :math:`\\rho c v_0`, then the bar leaves
the wall at :math:`+v_0`, undeformed, with its energy :math:`\\tfrac12 \\rho A L v_0^2`.

>>> res = simulate_bar(n_elements=20, mass="singular", courant=0.5)
>>> bool(abs(res.metrics["duration_error"]) < 0.06), bool(abs(res.metrics["energy_change_percent"]) < 1)
(True, True)

References
----------
K. F. Graff, *Wave Motion in Elastic Solids*, Dover 1991, sec. 1.2 (impact of a bar).
Paper eqs (1)-(12); C. Hager, S. Huebner, B. Wohlmuth, IJNME 73 (2008) 205-225 (bar test).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from dispersion.defaults import GAMMA_S_FLOAT
from dispersion.errors import InputError, check_positive, check_positive_int, check_real_in_range
from dispersion.splines.bspline import SplineBasis1D
from dispersion.mass_rules.mass_rule import RULES, get_rule, mass_variant
from dispersion.contact.contact_problem import ContactProblem
from dispersion.contact.newmark import History, integrate
from dispersion.contact.newmark_scheme import Newmark
from dispersion.contact.redistribution import float_redistribution
from dispersion.rendering import Rendered

__all__ = ["ENDS", "MAX_STEPS", "DENSE_DOFS", "NUMERIC_RULES", "Bar", "BarAssembly", "BarResult",
           "assemble_bar", "bar_problem", "check_steps", "simulate_bar"]

ENDS = ("left", "right")

#: Most time steps of one bar run. Rule: a run finishes in about a minute on this machine;
#: a step of a small bar costs about 60 microseconds (signorini-1d, 20 elements: 24000 steps
#: in 1.4 s), so 10^6 steps take about a minute.
MAX_STEPS = 1_000_000
#: Most functions of a bar assembled as dense numpy arrays; sparse (scipy) above. The rule:
#: the time stepper keeps its matrix products dense up to the same size (there
#: scipy.sparse's per-call overhead dominates), and a dense 400 x 400 matrix is 1.3 MB.
DENSE_DOFS = 400
#: Registered rules built from the consistent mass and the redistribution alone (row sums,
#: :math:`R^T M R`): applied in floats without the knot vector.
NUMERIC_RULES = ("consistent", "lumped", "singular", "singular-lumped")


def check_steps(t_end: float, dt: float, t_end_name: str = "t_end") -> int:
    """The step count ``ceil(t_end / dt)`` if it is at most :data:`MAX_STEPS`; raise otherwise.

    >>> check_steps(12.0, 1e-12)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: t_end / dt must be <= 1000000 steps, got 1.2e+13 (dt = 1e-12, t_end = 12)
    """
    steps = t_end / dt
    if not steps <= MAX_STEPS:
        raise InputError(f"{t_end_name} / dt must be <= {MAX_STEPS} steps, got {steps:.3g} "
                         f"(dt = {dt:g}, {t_end_name} = {t_end:g})")
    return max(1, int(np.ceil(steps)))


@dataclass(frozen=True)
class Bar:
    """A 1D impact problem as data (lengths in m, E in Pa, rho in kg/m^3, unit area).

    ``clamped`` lists the ends held at u = 0; ``contact`` is the end facing the wall, which
    stands ``gap`` beyond it; ``body_force`` is a number or a function ``b(x)`` (N/m^3).
    """

    n_elements: int = 20
    p: int = 1
    L: float = 1.0
    E: float = 1.0
    rho: float = 1.0
    mass: str = "lumped"
    clamped: tuple = ()
    contact: str = "left"
    gap: float = 0.0
    gamma_s: float = GAMMA_S_FLOAT
    body_force: float | Callable | None = field(default=None, compare=False)

    def __post_init__(self):
        check_positive_int("n_elements", self.n_elements)
        check_positive_int("p", self.p)
        for name in ("L", "E", "rho"):
            check_positive(name, getattr(self, name))
        rule = get_rule(self.mass)
        if self.contact not in ENDS:
            raise InputError(f"contact must be one of {', '.join(ENDS)}; got {self.contact!r}")
        bad = [e for e in self.clamped if e not in ENDS]
        if bad:
            raise InputError(f"clamped ends must be among {', '.join(ENDS)}; got {bad}")
        if self.contact in self.clamped:
            raise InputError(f"clamped: the contact end {self.contact!r} cannot be clamped")
        if not (np.isfinite(self.gap) and self.gap >= 0):
            raise InputError(f"gap must be a finite number >= 0, got {self.gap!r}")
        if rule.redistributes and self.n_elements + self.p < 3:
            raise InputError("n_elements: a singular mass needs >= 3 functions "
                             f"(n_elements + p >= 3), got {self.n_elements} + {self.p}")

    @property
    def wave_speed(self) -> float:
        return float(np.sqrt(self.E / self.rho))


@dataclass(frozen=True)
class BarAssembly:
    """The bar's :class:`~.contact_problem.ContactProblem` on the free DOFs ``free`` of ``basis``."""

    bar: Bar
    problem: ContactProblem
    basis: SplineBasis1D
    free: np.ndarray
    contact_dof: int

    def coefficients(self, fn: Callable | float) -> np.ndarray:
        """Spline coefficients (free DOFs) interpolating ``fn(x)`` at the Greville points."""
        g = np.array([float(x) for x in self.basis.kv.greville()]) * self.bar.L
        vals = np.broadcast_to(np.asarray(fn(g) if callable(fn) else fn, float), g.shape)
        act, N = self.basis.evaluate(g / self.bar.L)
        n = self.basis.kv.n
        A = np.zeros((len(g), n))
        np.put_along_axis(A, act, N, axis=1)
        c = np.linalg.solve(A, vals)
        held = np.ones(n, bool)
        held[self.free] = False
        if not np.allclose(c[held], 0, atol=1e-12):
            raise InputError("initial field must vanish at a clamped end")
        return c[self.free]

    def evaluate(self, coeffs: np.ndarray, x: np.ndarray) -> np.ndarray:
        """The field of free-DOF coefficients ``coeffs`` at points ``x`` (m)."""
        c = np.zeros(self.basis.kv.n)
        c[self.free] = coeffs
        act, N = self.basis.evaluate(np.asarray(x, float) / self.bar.L)
        return np.einsum("ma,ma->m", N, c[act])


def _numeric(rule) -> bool:
    return any(RULES[name] is rule for name in NUMERIC_RULES)


def _assemble(values: np.ndarray, rows: np.ndarray, cols: np.ndarray, n: int, dense: bool):
    """The ``n x n`` matrix summing ``values`` at ``(rows, cols)``: numpy or scipy.sparse."""
    if dense:
        return np.bincount(rows * n + cols, values, minlength=n * n).reshape(n, n)
    import scipy.sparse as sp

    return sp.csr_matrix((values, (rows, cols)), shape=(n, n))


def assemble_bar(bar: Bar) -> BarAssembly:
    """Assemble the bar: stiffness, mass variant, wall constraint, body force, clamped ends."""
    p, L = bar.p, bar.L
    basis = SplineBasis1D.uniform(p, bar.n_elements)
    n = basis.kv.n
    dense = n <= DENSE_DOFS
    xg, wg = np.polynomial.legendre.leggauss(p + 1)
    a, b = basis.spans[:, :1] * L, basis.spans[:, 1:] * L
    x = (a + (b - a) * (xg + 1) / 2).ravel()
    w = ((b - a) / 2 * wg).ravel()
    act, N = basis.evaluate(x / L)
    _, dN = basis.evaluate(x / L, 1)
    dN = dN / L
    rows = np.repeat(act, p + 1, axis=1).ravel()
    cols = np.tile(act, (1, p + 1)).ravel()
    K = _assemble((bar.E * w[:, None, None] * dN[:, :, None] * dN[:, None, :]).ravel(),
                  rows, cols, n, dense)
    M = _assemble((bar.rho * w[:, None, None] * N[:, :, None] * N[:, None, :]).ravel(),
                  rows, cols, n, dense)
    side = "bottom" if bar.contact == "left" else "top"
    rule = get_rule(bar.mass)
    R = float_redistribution(n, side, bar.gamma_s) if rule.redistributes else None
    kv = None
    if not _numeric(rule):  # HRZ, nodal quadratures, user rules: the exact knot vector
        from dispersion.splines.bspline import open_knot_vector

        kv = open_knot_vector(p, bar.n_elements, 0, 1)
    Mv = mass_variant(M, rule, R, kv=kv)
    if dense:
        Mv = np.asarray(Mv, dtype=float)
    else:
        import scipy.sparse as sp

        Mv = sp.csr_matrix(Mv)
        Mv.eliminate_zeros()
    f_ext = None
    if bar.body_force is not None:
        bx = bar.body_force(x) if callable(bar.body_force) else np.full(len(x), bar.body_force)
        f_ext = np.bincount(act.ravel(), (N * (w * np.asarray(bx, float))[:, None]).ravel(),
                            minlength=n)
    dof = 0 if bar.contact == "left" else n - 1
    sign = 1.0 if bar.contact == "left" else -1.0
    fixed = {"left": 0, "right": n - 1}
    held = np.zeros(n, bool)  # a mask, not setdiff1d: that imports numpy.ma
    held[[fixed[e] for e in bar.clamped]] = True
    free = np.flatnonzero(~held)
    k = int(np.flatnonzero(free == dof)[0])
    if dense:
        Kf = K[np.ix_(free, free)]
        Mf = Mv[np.ix_(free, free)]
        G = np.zeros((1, len(free)))
        G[0, k] = sign
    else:
        import scipy.sparse as sp

        Kf = K[free][:, free].tocsr()
        Mf = Mv[free][:, free].tocsr()
        G = sp.csr_matrix(([sign], ([0], [k])), shape=(1, len(free)))
    prob = ContactProblem(Mf, lambda u: (Kf @ u, Kf), G, np.array([bar.gap]),
                          lambda u: 0.5 * float(u @ (Kf @ u)),
                          None if f_ext is None else f_ext[free], None, Kf,
                          lambda u: Kf @ u)
    return BarAssembly(bar, prob, basis, free, dof)


def bar_problem(n_elements: int, p: int = 2, mass: str = "lumped", L: float = 1.0,
                E: float = 1.0, rho: float = 1.0, gamma_s: float = GAMMA_S_FLOAT
                ) -> ContactProblem:
    """Free bar on ``[0, L]`` (unit area) with the wall constraint ``g = u_0 >= 0``."""
    return assemble_bar(Bar(n_elements, p, L, E, rho, mass, gamma_s=gamma_s)).problem


@dataclass(frozen=True, repr=False)  # Rendered: a short repr; rows are the history
class BarResult(Rendered):
    """History of a bar run and its errors against the exact solution, with the ``bar`` and
    the ``scheme`` it was computed from."""

    history: History
    exact: dict
    metrics: dict
    bar: Bar | None = None
    scheme: str = ""

    def title(self) -> str:
        b = self.bar
        return (f"bar impact: p = {b.p}, {b.n_elements} elements, "
                f"{getattr(b.mass, 'name', b.mass)} mass, "
                f"{self.scheme}, dt = {self.metrics['dt']:g} s")

    def header_lines(self) -> list[str]:
        b = self.bar
        m = self.metrics
        return [f"bar: length L = {b.L:g} m, Young's modulus E = {b.E:g} Pa, density "
                f"rho = {b.rho:g} kg/m^3 (unit area), wave speed c = {b.wave_speed:g} m/s",
                f"exact: contact duration 2L/c = {self.exact['duration']:g} s, contact stress "
                f"rho c v0 = {self.exact['stress']:g} Pa",
                "errors (relative): contact duration "
                f"{m['duration_error']:.3g}, contact stress {m['stress_error']:.3g}, rebound "
                f"velocity {m['rebound_error']:.3g}; energy change "
                f"{m['energy_change_percent']:.3g} %"]

    def columns(self) -> tuple[str, ...]:
        return ("t [s]", "contact force [N]", "kinetic [J]", "strain [J]", "total [J]")

    def rows(self) -> list[dict]:
        a = self.history.arrays()
        keys = ("t", "contact_force", "kinetic", "strain", "total")
        return [dict(zip(self.columns(), map(float, vals))) for vals in zip(*(a[k] for k in keys))]

    def json_extra(self) -> dict:
        return {"metrics": self.metrics, "exact": self.exact}


def simulate_bar(n_elements: int = 40, p: int = 2, mass: str = "lumped", *,
                 courant: float = 0.5, dt: float | None = None, scheme: str = "kane",
                 L: float = 1.0, E: float = 1.0, rho: float = 1.0, v0: float = 1.0,
                 t_end_factor: float = 3.0, gamma_s: float = GAMMA_S_FLOAT,
                 contact_threshold: float = 1e-12) -> BarResult:
    """Bar impact up to ``t_end_factor * L / c``; ``dt = courant * h / c`` unless given.

    ``metrics``: relative errors of the contact duration (``dt`` times the number of steps
    whose force exceeds ``contact_threshold * rho c v0``, vs ``2L/c``), of the mean contact
    stress (vs ``rho c v0``) and of the rebound velocity (momentum / mass at the end, vs
    ``v0``); the energy change in percent; the contact-force oscillation (standard deviation
    over the middle half of the contact divided by ``rho c v0``).
    """
    bar = Bar(n_elements, p, L, E, rho, mass, gamma_s=gamma_s)
    check_positive("v0", v0)
    check_positive("t_end_factor", t_end_factor)
    c = bar.wave_speed
    h = L / n_elements
    if dt is None:
        check_real_in_range("courant", courant, 0, None, lo_open=True)
        dt = courant * h / c
    check_positive("dt", dt)
    n_steps = check_steps(t_end_factor * L / c, dt, "t_end_factor * L / c")
    prob = assemble_bar(bar).problem
    n = prob.n
    nm = Newmark(beta=0.0, gamma=0.5) if scheme == "central" else Newmark(scheme=scheme)
    hist = integrate(prob, np.zeros(n), -v0 * np.ones(n), dt, n_steps, nm)
    arr = hist.arrays()
    exact = {"duration": 2 * L / c, "stress": rho * c * v0, "rebound_velocity": v0,
             "energy": 0.5 * rho * L * v0**2}
    lam = arr["contact_force"]
    on = lam > contact_threshold * exact["stress"]
    duration = dt * np.count_nonzero(on)
    idx = np.flatnonzero(on)
    mid = idx[len(idx) // 4: max(len(idx) // 4 + 1, 3 * len(idx) // 4)] if len(idx) else idx
    mass_total = rho * L
    metrics = {
        "dt": dt,
        "n_elements": n_elements,
        "duration_error": (duration - exact["duration"]) / exact["duration"],
        "stress_error": (float(lam[mid].mean()) - exact["stress"]) / exact["stress"]
        if len(mid) else float("nan"),
        "force_oscillation": float(lam[mid].std()) / exact["stress"] if len(mid) else float("nan"),
        "rebound_error": (float(arr["momentum"][-1, 0]) / mass_total - v0) / v0,
        "energy_change_percent": 100 * (arr["total"][-1] - arr["total"][0]) / arr["total"][0],
        "in_contact_at_end": bool(on[-1]),
    }
    return BarResult(hist, exact, metrics, bar, scheme)
