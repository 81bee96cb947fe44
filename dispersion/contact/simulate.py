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

from ..errors import InputError
from .assembly import discretize, internal_force, ring_mass, strain_energy
from .material import StVenantKirchhoff
from .newmark import DENSE_MAX, ContactProblem, Newmark, integrate
from .nurbs import RingPatch, quarter_ring
from .scenario import Scenario

__all__ = ["RING_MASSES", "RingResult", "Scenario", "ring_patch", "ring_problem", "simulate_ring"]

RING_MASSES = ("consistent", "lumped", "singular", "singular-lumped")
_SAMPLES_PER_ELEMENT = 8


def ring_patch(sc: Scenario) -> RingPatch:
    """Quarter ring placed so that its lowest outer point is ``sc.gap`` above ``y = 0``."""
    th0 = np.deg2rad(sc.theta0_deg)
    th = np.linspace(th0, th0 + np.pi / 2, 2001)
    lowest = sc.r_outer * min(np.sin(th).min(), np.sin(th0), np.sin(th0 + np.pi / 2))
    return quarter_ring(sc.r_inner, sc.r_outer, sc.n_xi_elements, sc.n_eta_elements, th0,
                        (0.0, sc.gap - lowest))


def ring_problem(sc: Scenario, mass: str = "singular") -> tuple[ContactProblem, RingPatch]:
    """Contact problem of the scenario with the mass ``variant`` and the patch it lives on."""
    if mass not in RING_MASSES:
        raise InputError(f"mass must be one of {', '.join(RING_MASSES)}; got {mass!r}")
    patch = ring_patch(sc)
    disc = discretize(patch)
    mat = StVenantKirchhoff(sc.E, sc.nu)
    M = ring_mass(disc, sc.rho, mass, sc.gamma_s)
    idx, R = patch.boundary_basis(patch.greville_xi())
    n_c = len(R)
    G = sp.csr_matrix((R.ravel(), (np.repeat(np.arange(n_c), R.shape[1]), 2 * idx.ravel() + 1)),
                      shape=(n_c, disc.n_dofs))
    g0 = np.einsum("ma,ma->m", R, patch.points[idx, 1])
    directions = np.zeros((2, disc.n_dofs))
    directions[0, 0::2] = directions[1, 1::2] = 1.0
    dense = disc.n_dofs <= DENSE_MAX
    prob = ContactProblem(M, lambda u: internal_force(disc, mat, u, dense=dense),
                          G, g0, lambda u: strain_energy(disc, mat, u), None, directions,
                          force=lambda u: internal_force(disc, mat, u, tangent=False))
    return prob, patch


@dataclass(frozen=True)
class RingResult:
    """Time histories (``series``: name -> array) and the ``summary`` of one ring run."""

    scenario: Scenario
    mass: str
    scheme: str
    series: dict
    summary: dict

    def to_dict(self) -> dict:
        """JSON-ready dict: scenario, summary and the time histories as lists."""
        return {"scenario": asdict(self.scenario), "summary": self.summary,
                "series": {k: np.asarray(v).tolist() for k, v in self.series.items()}}

    def csv_text(self) -> str:
        """Time histories as CSV text, one row per step."""
        names = list(self.series)
        rows = np.column_stack([np.asarray(self.series[k], dtype=float) for k in names])
        lines = [",".join(names)] + [",".join(f"{x:.10g}" for x in row) for row in rows]
        return "\n".join(lines) + "\n"


def _chord_angle(patch: RingPatch, u: np.ndarray) -> float:
    a, b = patch.boundary_points(np.array([0.0, 1.0]), u.reshape(-1, 2))
    return float(np.arctan2(b[1] - a[1], b[0] - a[0]))


def simulate_ring(sc: Scenario | None = None, mass: str = "singular", scheme: str = "kane",
                  *, progress: Callable | None = None, tol: float = 1e-8,
                  solver: str = "auto") -> RingResult:
    """Run the ring benchmark; raises :class:`~dispersion.errors.ConvergenceError` on failure.

    ``summary``: ``energy_change_percent`` (total energy at the end vs the initial kinetic
    energy), ``max_penetration`` (m, sampled on the whole outer boundary, 8 points per
    element), ``max_contact_force`` (N per m thickness), ``force_roughness``
    (:math:`\\sum |\\Delta^2 F| / \\max F`, large for an oscillating force), ``contact_events``
    (number of separate contact intervals), ``final_rotation_deg`` (rotation of the chord
    between the arc ends), ``in_contact_at_end``, ``newton_iterations_max``,
    ``free_flight_energy_spread_percent`` (max - min of the total energy after the last
    contact: the trapezoidal rule conserves energy exactly only for linear problems).
    """
    sc = sc or Scenario()
    prob, patch = ring_problem(sc, mass)
    n = prob.n
    v0 = np.zeros(n)
    v0[1::2] = -sc.v0
    hist = integrate(prob, np.zeros(n), v0, sc.dt, sc.n_steps,
                     Newmark(scheme=scheme, tol=tol, solver=solver), progress, keep_states=True)
    arr = hist.arrays()
    xi = np.linspace(0, 1, _SAMPLES_PER_ELEMENT * sc.n_xi_elements + 1)
    idx, R = patch.boundary_basis(xi)
    Ry = np.zeros((len(xi), n))
    np.put_along_axis(Ry, 2 * idx + 1, R, axis=1)
    y0 = np.einsum("ma,ma->m", R, patch.points[idx, 1])
    U = np.array([s.u for s in hist.states])
    penetration = np.maximum(0.0, -(y0 + U @ Ry.T).min(axis=1))
    ang0 = _chord_angle(patch, U[0])
    rotation = np.rad2deg(np.unwrap([_chord_angle(patch, u) for u in U]) - ang0)
    F = arr["contact_force"]
    on = F > 1e-9 * max(F.max(), 1e-300)
    series = {"t": arr["t"], "contact_force": F, "kinetic": arr["kinetic"],
              "strain": arr["strain"], "total": arr["total"],
              "momentum_x": arr["momentum"][:, 0], "momentum_y": arr["momentum"][:, 1],
              "penetration": penetration, "gap_min_greville": arr["gap_min"],
              "rotation_deg": rotation,
              "newton_iterations": arr["iterations"]}
    E0 = arr["total"][0]
    after = arr["total"][np.flatnonzero(on)[-1] + 1:] if on.any() else arr["total"]
    summary = {
        "mass": mass, "scheme": scheme, "dt": sc.dt, "t_end": sc.t_end,
        "elements": sc.n_xi_elements * sc.n_eta_elements, "dofs": n,
        "energy_change_percent": float(100 * (arr["total"][-1] - E0) / E0),
        "max_penetration": float(penetration.max()),
        "max_contact_force": float(F.max()),
        "force_roughness": float(np.abs(np.diff(F, 2)).sum() / F.max()) if F.max() > 0 else 0.0,
        "contact_events": int(np.count_nonzero(np.diff(on.astype(int)) == 1)),
        "final_rotation_deg": float(rotation[-1]),
        "in_contact_at_end": bool(on[-1]),
        "newton_iterations_max": int(arr["iterations"].max()),
        "free_flight_energy_spread_percent":
            float(100 * np.ptp(after) / E0) if len(after) else float("nan"),
    }
    return RingResult(sc, mass, scheme, series, summary)
