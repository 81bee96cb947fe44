"""GetFEM's 1D Signorini benchmark: exact solution and the scene solved with :mod:`.bar`.

The problem of GetFEM's demo ``interface/tests/python/demo_dynamic_contact_1D.py``:

.. math::

    u_{tt} = u_{xx} \\text{ on } (0, 1), \\quad u(1, t) = 0, \\quad
    u(0, t) \\ge 0, \\; \\sigma = -u_x(0, t) \\ge 0, \\; u(0, t) \\sigma = 0, \\quad
    u(x, 0) = (1 - x)/2, \\; u_t(x, 0) = 0 .

Exact solution by characteristics: :math:`\\alpha = u_t - u_x` travels right
(:math:`\\alpha = A(t - x)`), :math:`\\beta = u_t + u_x` travels left
(:math:`\\beta = B(t + x)`). The clamped end reflects :math:`B(s) = -A(s - 2)`; the contact
end reflects :math:`A(t) = B(t)` when free (:math:`u_x = 0`) and :math:`A(t) = -B(t)` in
contact (:math:`u_t = 0`), the choice made by the sign of the gap and of the stress.
:func:`exact_solution` builds :math:`A, B` as piecewise constants by this event-driven
recursion (no phase table typed in) and integrates :math:`u = -\\int_x^1 u_x`. The solution
has period 3 and energy 1/8 (contact for :math:`t \\in [1, 2]` of each period).

>>> ex = exact_solution(7.0)
>>> [round(float(v), 6) + 0.0 for v in ex.u(np.array([0.0]), np.array([0.0, 0.5, 1.5, 2.5]))[:, 0]]
[0.5, 0.25, 0.0, 0.25]
>>> round(float(ex.stress(np.array([1.5]))[0]), 6), round(ex.energy(0.7), 6)
(0.5, 0.125)

References
----------
Y. Renard, F. Chouly, GetFEM demo ``demo_dynamic_contact_1D.py`` (2017-2020);
H. B. Khenous, P. Laborde, Y. Renard, "Mass redistribution method for finite element
contact problems in elastodynamics", Eur. J. Mech. A/Solids 27 (2008) 918-932.
"""
from __future__ import annotations

import bisect
import time
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from dispersion.errors import (ConvergenceError, InputError, check_memory, check_positive,
                               check_positive_int)
from dispersion.contact.bar import Bar, assemble_bar, check_steps
from dispersion.contact.energy_balance import energy_balance
from dispersion.contact.newmark import integrate_many
from dispersion.contact.newmark_scheme import newmark_for
from dispersion.rendering import Rendered

__all__ = ["ExactSignorini", "SignoriniResult", "exact_solution", "signorini_1d",
           "MAX_T_EXACT", "MAX_SECONDS", "SIGNORINI_SPREAD_RULE", "SPREAD_FIELDS", "gap_ulps",
           "signorini_runs",
           "work_seconds"]

#: How the spread of a Signorini row is measured, stated before any figure. The lumped and
#: the consistent mass chatter at the contact node under Kane's scheme, so their figures move
#: with round-off between runs (the lumped contact-stress error was seen anywhere in
#: 1.10-1.17): one number would be one draw of that spread.
SIGNORINI_SPREAD_RULE = (
    "Every 1D Signorini row is the same run repeated with the rigid wall moved k units of "
    "2^-53 (one unit in the last place of the initial gap u(0, 0) = 1/2) beyond x = 0, "
    "k = 0, 1, ..., runs - 1; each error is reported as its range over these runs "
    "(a single value where all runs agree to the digits shown).")
#: The errors of a row whose spread over the runs is reported.
SPREAD_FIELDS = ("u0_rel_l2", "v0_rel_l2", "stress_rel_l2", "energy_drift_percent",
                 "energy_error_percent", "energy_growth_percent")


def gap_ulps(runs: int) -> tuple[float, ...]:
    """The wall offsets of :data:`SIGNORINI_SPREAD_RULE`: ``k * 2**-53``, k < ``runs``.

    >>> gap_ulps(3)[1] == 2.0**-53 and 0.5 + gap_ulps(3)[1] > 0.5   # one ulp of 1/2
    True
    """
    check_positive_int("runs", runs)
    return tuple(k * 2.0**-53 for k in range(runs))

#: Bytes kept per time step besides the DOF arrays: the State object, its ``lam`` and ``mu``
#: arrays and the history's scalars (Python objects of about 100 bytes each).
_BYTES_PER_STEP = 1024
#: Latest time of :func:`exact_solution`. Rule: the recursion makes about one constant piece
#: per unit of time (period 3, three pieces each: 304 pieces at t_max = 300, 3004 at 3000,
#: measured), and it stops at 100000 pieces; 99000 stays below that, and the recursion is
#: linear in the pieces (about 0.3 s at the bound here).
MAX_T_EXACT = 99_000.0
_MAX_PIECES = 100_000
#: Longest run :func:`signorini_1d` accepts, by the estimate :func:`work_seconds`: half an
#: hour of this 2-core machine. Past it a coarser mesh or a shorter run serves better.
MAX_SECONDS = 1800.0


def work_seconds(p: int, n_elements: int, steps: int) -> float:
    """Estimated wall time (s) of :func:`signorini_1d`: set-up plus time steps.

    The set-up (the exact B-spline extraction operators) grows like ``n^2`` and steeply with
    ``p``; a step like ``n (p + 1)``. Fitted to runs on this 2-core machine, rounded up
    (measured set-up: p = 1: 2.7 s at n = 400, 18 s at n = 1000; p = 4, n = 400: 61 s;
    p = 6, n = 200: 47 s; a step: 0.11 ms at n = 20, 0.35 ms at p = 1, n = 1000, 0.8 ms at
    p = 4, n = 400):

    .. math:: t \\approx 3\\cdot 10^{-6} (p+1)^{3.3} n^2
              + \\text{steps}\\,(1.5\\cdot 10^{-4} + 5\\cdot 10^{-7} n (p+1)) .

    >>> round(work_seconds(1, 1000, 1000))   # measured here: 18.4 s
    31
    """
    return 3e-6 * (p + 1) ** 3.3 * n_elements**2 + steps * (1.5e-4 + 5e-7 * n_elements * (p + 1))


@dataclass(frozen=True)
class ExactSignorini:
    """Piecewise-constant Riemann invariants ``A`` on ``[-1, s_max]`` and ``B`` on
    ``[0, s_max]`` (breakpoints and values), defining the exact solution."""

    a_knots: np.ndarray
    a_vals: np.ndarray
    b_knots: np.ndarray
    b_vals: np.ndarray

    @staticmethod
    def _value(knots, vals, s):
        return vals[np.clip(np.searchsorted(knots, s, side="right") - 1, 0, len(vals) - 1)]

    @staticmethod
    def _integral(knots, vals, s):
        """:math:`\\int_{knots_0}^{s}` of the piecewise constant."""
        cum = np.concatenate([[0.0], np.cumsum(np.diff(knots) * vals)])
        k = np.clip(np.searchsorted(knots, s, side="right") - 1, 0, len(vals) - 1)
        return cum[k] + vals[k] * (s - knots[k])

    def alpha(self, x, t):
        return self._value(self.a_knots, self.a_vals, t - x)

    def beta(self, x, t):
        return self._value(self.b_knots, self.b_vals, t + x)

    def velocity(self, x, t):
        """:math:`u_t` on the grid ``x`` (columns) by ``t`` (rows)."""
        X, T = np.meshgrid(np.atleast_1d(x), np.atleast_1d(t))
        return 0.5 * (self.alpha(X, T) + self.beta(X, T))

    def strain(self, x, t):
        """:math:`u_x` on the grid ``x`` (columns) by ``t`` (rows)."""
        X, T = np.meshgrid(np.atleast_1d(x), np.atleast_1d(t))
        return 0.5 * (self.beta(X, T) - self.alpha(X, T))

    def u(self, x, t):
        """:math:`u(x, t) = -\\tfrac12 [\\int_{t+x}^{t+1} B - \\int_{t-1}^{t-x} A]` on the grid."""
        X, T = np.meshgrid(np.atleast_1d(x), np.atleast_1d(t))
        ib = self._integral(self.b_knots, self.b_vals, T + 1) - self._integral(
            self.b_knots, self.b_vals, T + X)
        ia = self._integral(self.a_knots, self.a_vals, T - X) - self._integral(
            self.a_knots, self.a_vals, T - 1)
        return -0.5 * (ib - ia)

    def stress(self, t):
        """Contact stress :math:`\\sigma(t) = -u_x(0, t) \\ge 0` (zero when free)."""
        return -self.strain(np.array([0.0]), t)[:, 0]

    def energy(self, t: float, n: int = 4001) -> float:
        """:math:`\\tfrac12 \\int_0^1 (u_t^2 + u_x^2) dx` by the midpoint rule on ``n`` cells
        (exact up to the cells cut by a jump of the invariants)."""
        x = (np.arange(n) + 0.5) / n
        v, e = self.velocity(x, t)[0], self.strain(x, t)[0]
        return float(0.5 * np.mean(v**2 + e**2))


def exact_solution(t_max: float, amplitude: float = 0.5) -> ExactSignorini:
    """Exact solution for ``u(x, 0) = amplitude (1 - x)``, ``u_t = 0``, up to ``t_max``."""
    check_positive("t_max", t_max)
    check_positive("amplitude", amplitude)
    if not t_max <= MAX_T_EXACT:
        raise InputError(f"t_max must be <= {MAX_T_EXACT:g} (the exact solution keeps one "
                         f"piece per unit of time, at most {_MAX_PIECES}), got {t_max:g}")
    t_max, amplitude = float(t_max), float(amplitude)
    s_max = t_max + 2.0
    # initial invariants (u_t = 0, u_x = -amplitude): A = amplitude on [-1, 0),
    # B = -amplitude on [0, 1)
    a_k, a_v = [-1.0], [amplitude]

    def b_at(s, tau):
        """B at s and the end of its constant piece (B(s) = -A(s - 2) beyond s = 1)."""
        if s < 1.0:
            return -amplitude, 1.0
        k = bisect.bisect_right(a_k, s - 2.0) - 1
        end = a_k[k + 1] + 2.0 if k + 1 < len(a_k) else tau + 2.0
        return -a_v[k], end

    tau, u0, contact = 0.0, amplitude, False
    tiny = 1e-14 * amplitude
    while tau < s_max:
        b, end = b_at(tau, tau)
        end = min(end, s_max)
        if contact and b > 0:  # the contact stress -B would turn tensile: release
            contact = False
        hits = False
        if not contact and b < 0 and u0 + b * (end - tau) <= tiny:
            end, hits = tau - u0 / b, True  # the gap closes
        if end > tau:
            a_k.append(tau)
            a_v.append(-b if contact else b)  # contact: u_t(0) = 0; free: u_x(0) = 0
        if not contact:
            u0 += b * (end - tau)  # u_t(0) = (A + B) / 2 = B when free
        if hits:
            contact, u0 = True, 0.0
        tau = end
        if len(a_k) > _MAX_PIECES:
            raise InputError("t_max: too many contact events in the exact solution")
    a_k.append(s_max)
    b_knots = np.concatenate([[0.0], np.asarray(a_k) + 2.0])
    b_vals = np.concatenate([[-amplitude], -np.asarray(a_v)])
    return ExactSignorini(np.array(a_k), np.array(a_v), b_knots, b_vals)


@dataclass(frozen=True, repr=False)  # Rendered: a short repr, no whole arrays
class SignoriniResult(Rendered):
    """One run of the 1D Signorini scene: inputs, histories at ``x = 0`` and errors.

    ``errors``: relative L2-in-time errors of ``u(0, t)``, ``u_t(0, t)`` and the contact
    stress against :func:`exact_solution` (None where the exact history is 0 throughout, as
    the stress before the first contact at t = 1); ``energy_drift_percent`` (max over the run of
    the total energy minus its value at t = 0, in % of 1/8), ``first_step_change_percent``,
    ``initial_energy_change_percent`` (what the consistent initial state changed, % of 1/8),
    ``energy_error_percent`` (final energy vs the exact 1/8), ``min_gap``; the energy balance
    (:func:`~.energy_balance.energy_balance`: ``energy_growth_percent``,
    ``energy_growth_bound_percent``, ``energy_flag``); ``seconds`` wall time.
    """

    p: int
    n_elements: int
    mass: str
    scheme: str
    dt: float
    t_end: float
    consistent: bool
    t: np.ndarray
    u0: np.ndarray
    v0: np.ndarray
    stress: np.ndarray
    kinetic: np.ndarray
    strain: np.ndarray
    total: np.ndarray
    errors: dict
    seconds: float

    @property
    def failures(self) -> tuple[str, ...]:
        flag = self.errors.get("energy_flag")
        return ((f"signorini-1d ({self.mass} mass, {self.scheme}): {flag}; the figures of this "
                 "run are not a result",) if flag else ())

    def summary(self) -> dict:
        """Inputs, errors and wall time of the run (strict-JSON ready)."""
        return {"scene": "signorini-1d", "p": self.p, "n_elements": self.n_elements,
                "mass": self.mass, "scheme": self.scheme, "dt": self.dt, "t_end": self.t_end,
                "consistent": self.consistent, "steps": len(self.t) - 1,
                "seconds": self.seconds, **self.errors}

    def title(self) -> str:
        return (f"signorini-1d: P{self.p}, {self.n_elements} elements, {self.mass} mass, "
                f"{self.scheme}, dt = {self.dt:g}, t_end = {self.t_end:g}")

    def header_lines(self) -> list[str]:
        return [f"consistent initial state: {self.consistent}",
                "dimensionless: unit bar length, wave speed, density and stiffness; the "
                "history at the contact point x = 0"]

    def columns(self) -> tuple[str, ...]:
        return tuple(f"{c} [-]" for c in HISTORY_COLUMNS)

    def rows(self) -> list[dict]:
        cols = np.column_stack([self.t, self.u0, self.v0, self.stress, self.kinetic,
                                self.strain, self.total])
        return [dict(zip(self.columns(), map(float, row))) for row in cols]

    def json_extra(self) -> dict:
        return {"summary": self.summary()}

    def to_text(self, digits: int = 7) -> str:
        """The run in one line: energy drift and the errors against the exact solution."""
        s = self.summary()

        def rel(value) -> str:  # None: the exact value is 0 throughout
            return "n/a (exact value 0)" if value is None else f"{value:.3g}"
        return (f"signorini-1d (P{self.p}, {self.n_elements} elements, {self.mass} mass, "
                f"{self.scheme}, dt {self.dt:g}): energy drift {s['energy_drift_percent']:.2g} "
                f"% of 1/8 (initial state {s['initial_energy_change_percent']:+.3g} %), rel. L2 "
                f"errors u(0) {rel(s['u0_rel_l2'])}, v(0) {rel(s['v0_rel_l2'])}, contact stress "
                f"{rel(s['stress_rel_l2'])}; {s['seconds']:.2f} s"
                + (" [UNSTABLE: energy grows; not a result]" if s.get("energy_flag") else ""))

    def __repr__(self) -> str:
        return f"<SignoriniResult: {self.title()} ({len(self.t)} samples)>"


#: Columns of :meth:`SignoriniResult.rows` (every unit is ``[-]``).
HISTORY_COLUMNS = ("t", "u0", "v0", "contact_stress", "kinetic", "strain", "total")


def _rel_l2(num, ref, dt):
    """Relative L2-in-time error; None where the exact history is 0 throughout (no contact
    before ``t_end``: a relative error is undefined, and a NaN would pass silently)."""
    den = np.sqrt(np.sum(ref**2) * dt)
    return float(np.sqrt(np.sum((num - ref) ** 2) * dt) / den) if den > 0 else None


def signorini_1d(p: int = 1, n_elements: int = 20, mass: str = "singular",
                 scheme: str = "kane", dt: float = 0.002, t_end: float = 12.0,
                 consistent: bool = True, gap: float = 0.0) -> SignoriniResult:
    """Solve GetFEM's 1D Signorini problem with the bar API and compare with the exact solution.

    ``scheme``: ``"kane"`` (contact-modified Newmark, beta = 1/4), ``"standard"`` or
    ``"central"`` (central differences, explicit; refused above the stability limit). ``gap`` moves
    the rigid wall that far beyond x = 0 (default 0, the problem's); a round-off-sized gap
    (a few units of 2**-53, the last place of the initial gap u(0, 0) = 1/2) measures how
    much a run's figures move with round-off (:data:`SIGNORINI_SPREAD_RULE`); the exact
    solution it is compared with keeps the wall at 0.
    """
    return signorini_runs(p, n_elements, mass, scheme, dt, t_end, consistent, (gap,))[0]


def signorini_runs(p: int = 1, n_elements: int = 20, mass: str = "singular",
                   scheme: str = "kane", dt: float = 0.002, t_end: float = 12.0,
                   consistent: bool = True, gaps=(0.0,)) -> list[SignoriniResult]:
    """:func:`signorini_1d` at each wall offset of ``gaps``, the runs stepped together
    (:func:`~dispersion.contact.newmark.integrate_many`: the same bar, K gaps, one array
    operation per step for all of them); each result's ``seconds`` is the wall time of the
    whole batch divided by its runs."""
    check_positive_int("n_elements", n_elements)
    check_positive_int("p", p)
    check_positive("dt", dt)
    check_positive("t_end", t_end)
    check_steps(t_end, dt)
    steps = t_end / dt
    if abs(steps - round(steps)) > 1e-9 * steps:
        raise InputError(f"t_end must be a whole multiple of dt = {dt:g}, got {t_end:g}")
    if not t_end <= MAX_T_EXACT:
        raise InputError(f"t_end must be <= {MAX_T_EXACT:g} (the exact solution it is "
                         f"compared with), got {t_end:g}")
    gaps = tuple(gaps)
    if not gaps:
        raise InputError("gaps must name at least one wall offset")
    # every state is kept (u, v, a_int, a_c) and the array of all u: 5 floats per DOF
    check_memory(f"n_elements = {n_elements} over t_end / dt = {round(steps)} steps"
                 + (f", {len(gaps)} runs" if len(gaps) > 1 else ""),
                 len(gaps) * (round(steps) + 1) * (40 * (n_elements + p) + _BYTES_PER_STEP))
    seconds = len(gaps) * work_seconds(p, n_elements, round(steps))
    if seconds > MAX_SECONDS:
        raise InputError(f"p = {p}, n_elements = {n_elements} over t_end / dt = {round(steps)} "
                         f"steps would take about {seconds / 60:.0f} min, more than the bound "
                         f"of {MAX_SECONDS / 60:.0f} min (fewer elements, a lower p or fewer "
                         "steps)")
    models = [assemble_bar(Bar(n_elements, p, 1.0, 1.0, 1.0, mass, clamped=("right",),
                               contact="left", gap=gap)) for gap in gaps]
    u_init = models[0].coefficients(lambda x: 0.5 * (1 - x))
    t0 = time.perf_counter()
    hists = integrate_many([m.problem for m in models], [u_init] * len(gaps),
                           [np.zeros(models[0].problem.n)] * len(gaps), [dt] * len(gaps),
                           [round(steps)] * len(gaps), newmark_for(scheme), keep_states=True,
                           consistent=consistent)
    for hist in hists:
        if hist.error is not None:
            raise ConvergenceError(hist.error)
    seconds = (time.perf_counter() - t0) / len(gaps)
    return [_signorini_result(p, n_elements, mass, scheme, dt, t_end, consistent, model, hist,
                              seconds) for model, hist in zip(models, hists)]


def _signorini_result(p, n_elements, mass, scheme, dt, t_end, consistent, model, hist,
                      seconds) -> SignoriniResult:
    """The errors of one run against the exact solution."""
    arr = hist.arrays()
    # t_k = k dt, each the float nearest the exact product with dt taken by its decimal
    # (the integrator's running sum drifts: t[1500] was 2.999999999999891 at dt = 0.002, so
    # samples at the exact solution's jumps, t = 1, 3, ..., fell on the wrong side)
    dt_q = Fraction(repr(float(dt)))
    t = np.array([float(k * dt_q) for k in range(len(arr["t"]))])
    k = int(np.flatnonzero(model.free == model.contact_dof)[0])
    U = np.array([s.u for s in hist.states])
    u0 = U[:, k]
    v0 = np.concatenate([[0.0], np.diff(u0) / dt])
    stress = arr["contact_force"]
    ex = exact_solution(t_end)
    u_ex = ex.u(np.array([0.0]), t)[:, 0]
    v_ex = ex.velocity(np.array([0.0]), t)[:, 0]
    s_ex = ex.stress(t)
    total = arr["total"]
    E_exact = 0.125
    errors = {
        "u0_rel_l2": _rel_l2(u0, u_ex, dt),
        "v0_rel_l2": _rel_l2(v0, v_ex, dt),
        "stress_rel_l2": _rel_l2(stress, s_ex, dt),
        "energy_drift_percent": float(100 * np.max(np.abs(total - total[0])) / E_exact),
        "first_step_change_percent": float(100 * (total[1] - total[0]) / E_exact),
        "initial_energy_change_percent": float(100 * hist.initial_energy_change / E_exact),
        "energy_error_percent": float(100 * (total[-1] - E_exact) / E_exact),
        "min_gap": float(np.min(arr["gap_min"])),
        **energy_balance(total, scheme, mass).fields(),
    }
    return SignoriniResult(p, n_elements, mass, scheme, dt, t_end, consistent, t, u0, v0,
                           stress, arr["kinetic"], arr["strain"], total, errors, seconds)
