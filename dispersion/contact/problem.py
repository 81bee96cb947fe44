"""Impact problems as data: a user NURBS patch, a rigid plane, Dirichlet sides, a mass variant.

A 2D problem is a NURBS patch (knots, control points, weights: :class:`~.nurbs.RingPatch`
holds any such patch), a St.Venant-Kirchhoff material (plane stress or plane strain), a
density, a mass rule of :mod:`dispersion.symbolic.mass_rule`, the patch side that may
touch a rigid plane and the plane itself, and the sides held fixed. :func:`patch_problem`
turns it into a :class:`~.contact_problem.ContactProblem` on the free DOFs. The gap of the plane
:math:`\\mathbf n \\cdot (\\mathbf x - \\mathbf p) \\ge 0` is imposed at the Greville abscissae
of the contact side, where :math:`\\mathbf x(\\xi) = \\sum_a R_a(\\xi) (\\mathbf X_a +
\\mathbf u_a)` is linear in the control-point displacements.

>>> from dispersion.contact.nurbs import quarter_ring
>>> from dispersion.contact.material import StVenantKirchhoff
>>> ring = quarter_ring(0.9, 1.0, 4, 2, np.pi, (0.0, 1.05))
>>> model = patch_problem(ring, StVenantKirchhoff(1.0, 0.3), 1.0, "singular", "eta1",
...                       Plane((0.0, 0.0), (0.0, 1.0)))
>>> model.problem.n, len(model.problem.g0), round(float(model.problem.g0.min()), 6)
(48, 6, 0.05)
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from dispersion.splines.bspline import open_knot_vector
from dispersion.errors import InputError, check_positive, check_positive_int
from dispersion.mass_rules.mass_rule import get_rule
from dispersion.contact.assembly import discretize, internal_force, patch_mass, strain_energy
from dispersion.contact.material import StVenantKirchhoff
from dispersion.contact.contact_problem import ContactProblem
from dispersion.contact.newmark_scheme import DENSE_MAX
from dispersion.contact.nurbs import RingPatch, SplineBasis1D

__all__ = ["SIDES", "Plane", "PatchProblem", "patch_problem", "rectangle_patch", "restrict",
           "side_basis", "side_points"]

#: Sides of a patch: ``eta1`` is the last row of control points across ``eta`` (the ring's
#: outer surface), ``eta0`` the first, likewise ``xi0`` and ``xi1``.
SIDES = ("eta1", "eta0", "xi1", "xi0")


@dataclass(frozen=True)
class Plane:
    """Rigid frictionless plane through ``point`` with unit normal ``normal`` pointing into
    the admissible half space (the gap is :math:`\\mathbf n \\cdot (\\mathbf x - \\mathbf p)`)."""

    point: tuple
    normal: tuple

    def __post_init__(self):
        p, n = np.asarray(self.point, float), np.asarray(self.normal, float)
        if p.shape != (2,) or not np.all(np.isfinite(p)):
            raise InputError(f"obstacle point must be two finite numbers, got {self.point!r}")
        if n.shape != (2,) or not np.all(np.isfinite(n)) or np.hypot(*n) == 0:
            raise InputError(f"obstacle normal must be a finite non-zero 2-vector, got "
                             f"{self.normal!r}")

    @property
    def unit_normal(self) -> np.ndarray:
        n = np.asarray(self.normal, float)
        return n / np.hypot(*n)


@dataclass(frozen=True)
class PatchProblem:
    """A 2D problem ready to integrate: ``problem`` on the free DOFs ``free`` (indices into
    the interleaved DOFs ``2 * point + component`` of ``patch``), the contact side's
    Greville abscissae ``contact_xi`` and the discretization ``disc``."""

    problem: ContactProblem
    patch: RingPatch
    free: np.ndarray
    contact_side: str
    contact_params: np.ndarray
    disc: object

    def full(self, u_free: np.ndarray) -> np.ndarray:
        """Displacements of all control points ``(n_points, 2)`` from the free DOFs."""
        u = np.zeros(self.disc.n_dofs)
        u[self.free] = u_free
        return u.reshape(-1, 2)


def rectangle_patch(width: float, height: float, n_xi: int = 2, n_eta: int = 2, p: int = 2,
                    origin: tuple = (0.0, 0.0)) -> RingPatch:
    """Rectangle ``[x0, x0 + width] x [y0, y0 + height]`` as a B-spline patch of degree ``p``
    (unit weights, control points at the Greville abscissae: the linear map is exact).

    >>> patch = rectangle_patch(2.0, 1.0, 3, 2)
    >>> patch.n_xi, patch.n_eta, patch.points[-1].tolist()
    (5, 4, [2.0, 1.0])
    """
    check_positive("width", width)
    check_positive("height", height)
    kx = open_knot_vector(p, check_positive_int("n_xi", n_xi))
    ky = open_knot_vector(p, check_positive_int("n_eta", n_eta))
    gx = np.array([float(g) for g in kx.greville()])
    gy = np.array([float(g) for g in ky.greville()])
    X, Y = np.meshgrid(origin[0] + width * gx, origin[1] + height * gy, indexing="ij")
    return RingPatch(kx, ky, np.column_stack([X.ravel(), Y.ravel()]), np.ones(X.size))


def side_points(patch: RingPatch, side: str) -> np.ndarray:
    """Global indices of the control points on ``side``, in order along the side."""
    if side not in SIDES:
        raise InputError(f"side must be one of {', '.join(SIDES)}; got {side!r}")
    i, j = np.meshgrid(np.arange(patch.n_xi), np.arange(patch.n_eta), indexing="ij")
    idx = i * patch.n_eta + j
    return {"eta1": idx[:, -1], "eta0": idx[:, 0], "xi1": idx[-1, :], "xi0": idx[0, :]}[side]


def side_basis(patch: RingPatch, side: str, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rational basis of the boundary curve ``side`` at parameters ``s``: ``(indices, R)``."""
    pts = side_points(patch, side)
    kv = patch.kv_xi if side.startswith("eta") else patch.kv_eta
    act, N = SplineBasis1D.from_knots(kv).evaluate(s)
    w = patch.weights[pts][act]
    return pts[act], w * N / np.sum(w * N, axis=1, keepdims=True)


def restrict(prob: ContactProblem, free: np.ndarray) -> ContactProblem:
    """The problem on the DOFs ``free`` with the others held at zero (Dirichlet)."""
    n = prob.n
    free = np.asarray(free, int)
    if len(free) == n:
        return prob

    def full(u):
        U = np.zeros(n)
        U[free] = u
        return U

    def internal(u):
        f, K = prob.internal(full(u))
        K = K[free][:, free] if sp.issparse(K) else K[np.ix_(free, free)]
        return f[free], K

    force = None if prob.force is None else (lambda u: prob.force(full(u))[free])
    M = sp.csr_matrix(prob.M)[free][:, free]
    G = sp.csr_matrix(prob.G)[:, free]
    f_ext = None if prob.f_ext is None else np.asarray(prob.f_ext)[free]
    directions = None if prob.directions is None else np.asarray(prob.directions)[:, free]
    K = None if prob.K is None else sp.csr_matrix(prob.K)[free][:, free]
    return ContactProblem(M, internal, G, prob.g0, lambda u: prob.energy(full(u)), f_ext,
                          directions, K, force)


def patch_problem(patch: RingPatch, material: StVenantKirchhoff, rho: float,
                  mass: str = "consistent", contact_side: str = "eta1",
                  obstacle: Plane | None = None, dirichlet: Sequence[tuple[str, int]] = (),
                  gamma_s: float = 0.5) -> PatchProblem:
    """Contact problem of a NURBS ``patch`` against a rigid ``obstacle`` plane.

    Parameters
    ----------
    patch : RingPatch
        Any NURBS patch (knots, control points ``(n_xi * n_eta, 2)`` in m, weights).
    material : StVenantKirchhoff
        Plane stress or plane strain.
    rho : float
        Density (kg/m^3); unit thickness.
    mass : str
        A rule of :mod:`dispersion.symbolic.mass_rule` (name or object); the singular ones redistribute the
        functions of ``contact_side`` inward with weight ``gamma_s`` (paper eqs 1-4).
    contact_side : str
        One of :data:`SIDES`: the side that may touch the obstacle.
    obstacle : Plane
        Default: the plane ``y = 0`` with normal ``+y``.
    dirichlet : sequence of ``(side, component)``
        Components (0 = x, 1 = y) held at zero on whole sides.
    """
    get_rule(mass)
    if contact_side not in SIDES:
        raise InputError(f"contact_side must be one of {', '.join(SIDES)}; got {contact_side!r}")
    if not (np.isfinite(rho) and rho > 0):
        raise InputError(f"rho must be a finite number > 0, got {rho!r}")
    obstacle = obstacle or Plane((0.0, 0.0), (0.0, 1.0))
    disc = discretize(patch)
    n = disc.n_dofs
    fixed = np.zeros(n, bool)
    for side, comp in dirichlet:
        if comp not in (0, 1):
            raise InputError(f"dirichlet component must be 0 (x) or 1 (y), got {comp!r}")
        fixed[2 * side_points(patch, side) + comp] = True
    contact_pts = side_points(patch, contact_side)
    if np.any(fixed[2 * contact_pts] | fixed[2 * contact_pts + 1]) and any(
            side == contact_side for side, _ in dirichlet):
        raise InputError(f"dirichlet: the contact side {contact_side} cannot be held fixed")
    M2 = patch_mass(disc, rho, mass, contact_side, gamma_s)
    kv = patch.kv_xi if contact_side.startswith("eta") else patch.kv_eta
    s = np.array([float(g) for g in kv.greville()])
    idx, Rb = side_basis(patch, contact_side, s)
    nrm = obstacle.unit_normal
    n_c = len(s)
    rows = np.repeat(np.arange(n_c), Rb.shape[1])
    G = sp.csr_matrix((np.concatenate([(Rb * nrm[0]).ravel(), (Rb * nrm[1]).ravel()]),
                       (np.concatenate([rows, rows]),
                        np.concatenate([2 * idx.ravel(), 2 * idx.ravel() + 1]))), shape=(n_c, n))
    x = np.einsum("ma,mak->mk", Rb, patch.points[idx])
    g0 = (x - np.asarray(obstacle.point, float)) @ nrm
    directions = np.zeros((2, n))
    directions[0, 0::2] = directions[1, 1::2] = 1.0
    dense = n <= DENSE_MAX
    prob = ContactProblem(M2, lambda u: internal_force(disc, material, u, dense=dense), G, g0,
                          lambda u: strain_energy(disc, material, u), None, directions,
                          force=lambda u: internal_force(disc, material, u, tangent=False))
    free = np.flatnonzero(~fixed)
    return PatchProblem(restrict(prob, free), patch, free, contact_side, s, disc)
