"""The ring benchmark: a quarter ring bouncing on a rigid frictionless plane ``y = 0``.

Builds the patch (:mod:`.nurbs`), the St.Venant-Kirchhoff internal force (:mod:`.assembly`),
the mass variant, the linear gap at the Greville abscissae of the outer surface,
and runs the Newmark scheme of :mod:`.newmark`. No gravity: after the contact events the ring
flies off, so its total (kinetic + strain) energy must equal the initial kinetic energy.

>>> res = simulate_ring(Scenario(n_xi_elements=8, n_eta_elements=1, t_end=0.5), "singular")
>>> res.summary["in_contact_at_end"], bool(abs(res.series["momentum_x"]).max() < 1e-6)
(True, True)

References
----------
Paper sec. 3 and Figure 4.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import asdict, dataclass

import numpy as np
import scipy.sparse as sp

from dispersion.errors import ConvergenceError, InputError
from dispersion.contact.energy_balance import energy_balance
from dispersion.contact.material import StVenantKirchhoff
from dispersion.contact.contact_problem import ContactProblem
from dispersion.contact.newmark import integrate, integrate_many
from dispersion.contact.newmark_scheme import CONTACT_SCHEMES, newmark_for
from dispersion.rendering import Rendered
from dispersion.splines.nurbs import RingPatch, quarter_ring
from dispersion.contact.problem import Plane, patch_problem
from dispersion.contact.scenario import Scenario

__all__ = ["CONTACT_SCHEMES", "RingResult", "Scenario", "newmark_for", "ring_patch", "ring_problem",
           "simulate_ring", "simulate_rings"]

_SAMPLES_PER_ELEMENT = 8


def ring_patch(sc: Scenario) -> RingPatch:
    """Quarter ring placed so that its lowest outer point is ``sc.gap`` above ``y = 0``."""
    th0 = np.deg2rad(sc.theta0_deg)
    th = np.linspace(th0, th0 + np.pi / 2, 2001)
    lowest = sc.r_outer * min(np.sin(th).min(), np.sin(th0), np.sin(th0 + np.pi / 2))
    return quarter_ring(sc.r_inner, sc.r_outer, sc.n_xi_elements, sc.n_eta_elements, th0,
                        (0.0, sc.gap - lowest))


def ring_problem(sc: Scenario, mass: str = "singular") -> tuple[ContactProblem, RingPatch]:
    """Contact problem of the scenario with the mass ``variant`` and the patch it lives on:
    the ring as one scene of :func:`~.problem.patch_problem` (outer side ``eta1`` against the
    plane ``y = 0``, no Dirichlet side)."""
    patch = ring_patch(sc)
    model = patch_problem(patch, StVenantKirchhoff(sc.E, sc.nu), sc.rho, mass, "eta1",
                          Plane((0.0, 0.0), (0.0, 1.0)), (), sc.gamma_s)
    return model.problem, patch


@dataclass(frozen=True, repr=False)  # Rendered: a short repr, no whole arrays
class RingResult(Rendered):
    """Time histories (``series``: name -> array) and the ``summary`` of one ring run.

    Renders itself (:class:`dispersion.rendering.Rendered`): the text form is the run's
    summary in one line, CSV and the DataFrame the histories with units
    (:data:`SERIES_UNITS`), JSON the summary with the histories.
    """

    scenario: Scenario
    mass: str
    scheme: str
    series: dict
    summary: dict

    @property
    def failures(self) -> tuple[str, ...]:
        flag = self.summary.get("energy_flag")
        return ((f"ring ({self.mass} mass, {self.scheme}): {flag}; the figures of this run are "
                 "not a result",) if flag else ())

    def record(self) -> dict:
        """The run as plain data: scenario, summary and the time histories as lists (what
        ``ring --out`` saves as ``result.json`` and the figures read; :meth:`to_dict` is the
        rendered form every result has)."""
        return {"scenario": dict(asdict(self.scenario), E=self.scenario.E),
                "summary": self.summary,
                "series": {k: np.asarray(v).tolist() for k, v in self.series.items()}}

    def title(self) -> str:
        from dispersion.contact.newmark_scheme import SCHEME_TEXT

        return (f"ring on a rigid plane: {self.mass} mass, "
                f"{SCHEME_TEXT.get(self.scheme, self.scheme)}")

    def header_lines(self) -> list[str]:
        scene = dict(asdict(self.scenario), E=self.scenario.E)
        return ["scene: " + ", ".join(f"{k} = {v:g}{SCENE_UNITS.get(k, '')}"
                                      if isinstance(v, float) else f"{k} = {v}"
                                      for k, v in scene.items()),
                "plane strain: forces and energies per metre of thickness"]

    def columns(self) -> tuple[str, ...]:
        return tuple(f"{k} [{SERIES_UNITS.get(k, '-')}]" for k in self.series)

    def rows(self) -> list[dict]:
        cols = self.columns()
        arrays = [np.asarray(v, dtype=float) for v in self.series.values()]
        return [dict(zip(cols, map(float, values))) for values in zip(*arrays)]

    def json_extra(self) -> dict:
        return {"summary": self.summary}

    def to_text(self, digits: int = 7) -> str:
        """The run in one line: energy change, penetration, contact events, rotation."""
        s = self.summary
        text = (f"ring ({s['mass']} mass, {s['scheme']}): energy change "
                f"{s['energy_change_percent']:+.3f} %, max penetration "
                f"{s['max_penetration_greville']:.2e} m at the Greville points, "
                f"{s['max_penetration']:.2e} m between them, {s['contact_events']} contact "
                f"events, rotation {s['final_rotation_deg']:.1f} deg")
        return text + (" [UNSTABLE: energy grows; not a result]" if s.get("energy_flag") else "")

    def __repr__(self) -> str:
        s = self.summary
        return (f"<RingResult: {self.mass} mass, {self.scheme}, {len(self.series['t'])} steps, "
                f"energy change {s['energy_change_percent']:+.4g} %, "
                f"{s['contact_events']} contact events>")


#: Units of the ring's time histories (plane strain: per metre of thickness).
SERIES_UNITS = {"t": "s", "contact_force": "N/m", "kinetic": "J/m", "strain": "J/m",
                "total": "J/m", "momentum_x": "kg/s", "momentum_y": "kg/s", "penetration": "m",
                "gap_min_greville": "m", "rotation_deg": "deg", "newton_iterations": "count"}


#: Units of the scene's fields in the ``#`` lines of the CSV.
SCENE_UNITS = {"r_inner": " m", "r_outer": " m", "rho": " kg/m^3", "v0": " m/s",
               "theta0_deg": " deg", "gap": " m", "dt": " s", "t_end": " s", "E": " Pa"}


def simulate_ring(sc: Scenario | None = None, mass: str = "singular", scheme: str = "kane",
                  *, progress: Callable | None = None, tol: float = 1e-8,
                  solver: str = "auto", contact_threshold: float = 1e-9,
                  perturbation: float = 0.0, seed: int = 0,
                  consistent: bool = True, reuse_tangent: bool = True) -> RingResult:
    """Run the ring benchmark; raises :class:`~dispersion.errors.ConvergenceError` on failure.

    Parameters
    ----------
    contact_threshold : float
        A step counts as "in contact" when its total contact force exceeds this fraction of
        the run's largest force; it defines ``contact_events`` and the free flight.
    perturbation, seed : float, int
        Relative size of a random perturbation of the initial velocity (every DOF, normal
        distribution from ``seed``): ``1e-12`` probes how runs differ by round-off.
    consistent : bool
        Put the massless DOFs in equilibrium at t = 0 (:func:`~.newmark.consistent_state`).
    tol, solver, reuse_tangent
        Newton controls of :class:`~.newmark_scheme.Newmark`.

    ``summary``: ``energy_change_percent`` (total energy at the end vs the initial kinetic
    energy), ``max_penetration_greville`` (m, at the Greville points, where the constraint
    is imposed), ``max_penetration`` (m, sampled on the whole outer boundary, 8 points per
    element: between the Greville points), ``max_contact_force`` (N per m thickness),
    ``force_roughness`` (:math:`\\sum |\\Delta^2 F| / \\max F`, large for an oscillating
    force), ``contact_events`` (separate contact intervals), ``final_rotation_deg`` (rotation
    of the chord between the arc ends), ``in_contact_at_end``, ``newton_iterations_max``,
    ``free_flight_energy_spread_percent`` (max - min of the total energy after the last
    contact; ``None`` when the run ends in contact), and the energy balance of
    :func:`~.energy_balance.energy_balance` (``energy_growth_percent``,
    ``energy_growth_bound_percent``, ``energy_flag``: None or why the run is flagged).
    """
    sc = sc or Scenario()
    sc.check_work()
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # errors, not warnings
        return _simulate(sc, mass, scheme, progress, tol, solver, contact_threshold,
                         perturbation, seed, consistent, reuse_tangent)


def _check_representable(sc: Scenario, prob: ContactProblem) -> None:
    """Refuse a scene whose matrices leave double precision (sizes like r_outer = 1e300 m:
    the mass grows like rho r^2, the stiffness like E), before any step is taken."""
    f0, K0 = prob.internal(np.zeros(prob.n))
    data = [np.asarray(prob.M.data), np.asarray(f0)] + (
        [np.asarray(K0.data if hasattr(K0, "data") else K0)] if K0 is not None else [])
    if not all(np.all(np.isfinite(d)) for d in data) or not np.abs(prob.M.data).max() > 0:
        raise InputError(
            f"the ring's matrices leave double precision (r_inner = {sc.r_inner:g} m, "
            f"r_outer = {sc.r_outer:g} m, rho = {sc.rho:g} kg/m^3, E = {sc.E:g} Pa); choose "
            "sizes and material nearer 1")


def _check_controls(contact_threshold, perturbation) -> None:
    if not (np.isfinite(contact_threshold) and 0 < contact_threshold < 1):
        raise InputError(f"contact_threshold must lie in (0, 1), got {contact_threshold!r}")
    if not (np.isfinite(perturbation) and perturbation >= 0):
        raise InputError(f"perturbation must be a finite number >= 0, got {perturbation!r}")


def _start(sc: Scenario, mass: str, perturbation: float, seed: int):
    """The run's problem, patch and initial velocity (the ring falling at ``v0``, every DOF
    perturbed by ``perturbation`` relative, normal from ``seed``)."""
    prob, patch = ring_problem(sc, mass)
    _check_representable(sc, prob)
    v0 = np.zeros(prob.n)
    v0[1::2] = -sc.v0
    if perturbation:
        v0 = v0 + perturbation * sc.v0 * np.random.default_rng(seed).standard_normal(prob.n)
    return prob, patch, v0


def _simulate(sc, mass, scheme, progress, tol, solver, contact_threshold, perturbation, seed,
              consistent, reuse_tangent) -> RingResult:
    _check_controls(contact_threshold, perturbation)
    prob, patch, v0 = _start(sc, mass, perturbation, seed)
    hist = integrate(prob, np.zeros(prob.n), v0, sc.dt, sc.n_steps,
                     newmark_for(scheme, tol=tol, solver=solver, reuse_tangent=reuse_tangent),
                     progress, keep_states=True, consistent=consistent)
    return _result(sc, mass, scheme, prob, patch, hist, contact_threshold, perturbation, seed)


def simulate_rings(runs, scheme: str = "kane", *, tol: float = 1e-8,
                   contact_threshold: float = 1e-9, consistent: bool = True) -> list:
    """Several ring runs at once: ``runs`` are ``(scenario, mass, perturbation, seed)``;
    returns, in order, each run's :class:`RingResult` or the
    :class:`~dispersion.errors.ConvergenceError` it ended with.

    Runs with the same mesh and mass rule step together
    (:func:`~dispersion.contact.newmark.integrate_many`), each as it would alone: one
    evaluation of their forces and one set of array operations per Newton iteration for
    all of them, which is what a small mesh's step costs (the ring study's 150 runs).
    """
    runs = list(runs)
    _check_controls(contact_threshold, 0.0)
    for sc, _, perturbation, _ in runs:
        sc.check_work()
        _check_controls(contact_threshold, perturbation)
    groups: dict = {}
    for i, (sc, mass, _, _) in enumerate(runs):
        groups.setdefault((sc.n_xi_elements, sc.n_eta_elements, mass), []).append(i)
    out: list = [None] * len(runs)
    nm = newmark_for(scheme, tol=tol)
    for members in groups.values():
        starts = [_start(runs[i][0], runs[i][1], runs[i][2], runs[i][3]) for i in members]
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            hists = integrate_many([p for p, _, _ in starts], [np.zeros(p.n) for p, _, _ in starts],
                                   [v0 for _, _, v0 in starts], [runs[i][0].dt for i in members],
                                   [runs[i][0].n_steps for i in members], nm, keep_states=True,
                                   consistent=consistent)
            for i, (prob, patch, _), hist in zip(members, starts, hists):
                sc, mass, perturbation, seed = runs[i]
                out[i] = (ConvergenceError(hist.error) if hist.error is not None else
                          _result(sc, mass, scheme, prob, patch, hist, contact_threshold,
                                  perturbation, seed))
    return out


def _result(sc, mass, scheme, prob, patch, hist, contact_threshold, perturbation,
            seed) -> RingResult:
    """The run's time histories and summary from its integrated history."""
    n = prob.n
    arr = hist.arrays()
    xi = np.linspace(0, 1, _SAMPLES_PER_ELEMENT * sc.n_xi_elements + 1)
    idx, R = patch.boundary_basis(xi)
    # sparse: a dense (samples, DOFs) map would outgrow the states on a long thin mesh
    Ry = sp.csr_matrix((R.ravel(), (np.repeat(np.arange(len(xi)), idx.shape[1]),
                                    (2 * idx + 1).ravel())), shape=(len(xi), n))
    y0 = np.einsum("ma,ma->m", R, patch.points[idx, 1])
    U = np.array([s.u for s in hist.states])
    penetration = np.maximum(0.0, -(y0 + (Ry @ U.T).T).min(axis=1))
    ends, Re = patch.boundary_basis(np.array([0.0, 1.0]))
    X = patch.points[ends]  # (2, a, 2)
    Ue = U.reshape(len(U), -1, 2)[:, ends]  # (steps, 2, a, 2)
    pts = np.einsum("ma,tmak->tmk", Re, X[None] + Ue)
    chord = pts[:, 1] - pts[:, 0]
    angle = np.unwrap(np.arctan2(chord[:, 1], chord[:, 0]))
    rotation = np.rad2deg(angle - angle[0])
    F = arr["contact_force"]
    on = F > contact_threshold * max(F.max(), 1e-300)
    series = {"t": arr["t"], "contact_force": F, "kinetic": arr["kinetic"],
              "strain": arr["strain"], "total": arr["total"],
              "momentum_x": arr["momentum"][:, 0], "momentum_y": arr["momentum"][:, 1],
              "penetration": penetration, "gap_min_greville": arr["gap_min"],
              "rotation_deg": rotation,
              "newton_iterations": arr["iterations"]}
    E0 = arr["total"][0]
    after = arr["total"][np.flatnonzero(on)[-1] + 1:] if on.any() else arr["total"]
    summary = {
        "mass": mass, "scheme": scheme, "dt": sc.dt, "t_end": sc.t_end, "E": sc.E,
        "elements": sc.n_xi_elements * sc.n_eta_elements, "dofs": n,
        "energy_change_percent": float(100 * (arr["total"][-1] - E0) / E0),
        "initial_energy_change_percent": float(100 * hist.initial_energy_change / E0),
        "max_penetration_greville": float(max(0.0, -np.min(arr["gap_min"]))),
        "max_penetration": float(penetration.max()),
        "max_contact_force": float(F.max()),
        "force_roughness": float(np.abs(np.diff(F, 2)).sum() / F.max()) if F.max() > 0 else 0.0,
        "contact_events": int(np.count_nonzero(np.diff(on.astype(int)) == 1)),
        "contact_threshold": contact_threshold,
        "final_rotation_deg": float(rotation[-1]),
        "in_contact_at_end": bool(on[-1]),
        "newton_iterations_max": int(arr["iterations"].max()),
        "free_flight_energy_spread_percent":
            float(100 * np.ptp(after) / E0) if len(after) else None,
        "perturbation": perturbation, "seed": seed,
        **energy_balance(arr["total"], scheme, mass).fields(),
    }
    return RingResult(sc, mass, scheme, series, summary)
