"""Quarter ring as one exact quadratic NURBS patch, refined by uniform knot insertion.

A quarter circle of radius :math:`r` is exactly the rational quadratic curve with control
points at angles :math:`\\theta_0, \\theta_0 + 45^\\circ, \\theta_0 + 90^\\circ`, the middle one
at distance :math:`r / \\cos 45^\\circ` and with weight :math:`\\cos 45^\\circ`,

.. math::

    \\mathbf x(\\xi, \\eta) = \\frac{\\sum_{ij} w_{ij} N_i(\\xi) N_j(\\eta) \\mathbf P_{ij}}
                                 {\\sum_{ij} w_{ij} N_i(\\xi) N_j(\\eta)} .

Through the thickness (:math:`\\eta`) the radius is linear, written as a quadratic with three
equally spaced control points, so that both directions have degree 2. Knot insertion is
applied to the homogeneous points :math:`(w\\mathbf P, w)` and leaves the geometry unchanged.
Control point ``(i, j)`` (``i`` along the arc, ``j`` through the thickness, ``j = n_eta - 1``
on the outer surface) has the global index ``i * n_eta + j``.

>>> ring = quarter_ring(0.9, 1.0, 4, 2)
>>> ring.n_xi, ring.n_eta
(6, 4)
>>> xy = ring.boundary_points(np.linspace(0, 1, 5))
>>> np.allclose(np.hypot(*xy.T), 1.0)
True

References
----------
L. Piegl, W. Tiller, *The NURBS Book*, 2nd ed., Springer 1997, sec. 7.5 (circle), A5.1.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from dispersion.splines.bspline import KnotVector, SplineBasis1D, open_knot_vector, refine
from dispersion.errors import InputError, check_positive, check_positive_int

__all__ = ["RingPatch", "SplineBasis1D", "quarter_ring"]


@dataclass(frozen=True)
class RingPatch:
    """Quadratic NURBS patch: knot vectors, control points ``(n_xi*n_eta, 2)`` and weights."""

    kv_xi: KnotVector
    kv_eta: KnotVector
    points: np.ndarray
    weights: np.ndarray

    @property
    def n_xi(self) -> int:
        return self.kv_xi.n

    @property
    def n_eta(self) -> int:
        return self.kv_eta.n

    @property
    def n_points(self) -> int:
        return self.n_xi * self.n_eta

    def outer_indices(self) -> np.ndarray:
        """Global indices of the control points on the outer surface (``eta = 1``)."""
        return np.arange(self.n_xi) * self.n_eta + self.n_eta - 1

    def boundary_basis(self, xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Rational basis of the outer boundary curve at ``xi``: ``(global indices, R)``."""
        act, N = _basis(self.kv_xi).evaluate(xi)
        outer = self.outer_indices()
        w = self.weights[outer][act]
        R = w * N / np.sum(w * N, axis=1, keepdims=True)
        return outer[act], R

    def boundary_points(self, xi: np.ndarray, u: np.ndarray | None = None) -> np.ndarray:
        """Points of the (displaced by ``u``, shape ``(n_points, 2)``) outer boundary at ``xi``."""
        idx, R = self.boundary_basis(xi)
        x = self.points if u is None else self.points + u
        return np.einsum("ma,mak->mk", R, x[idx])

    def greville_xi(self) -> np.ndarray:
        """Greville abscissae of the arc direction: the contact points of the outer surface."""
        return np.array([float(g) for g in self.kv_xi.greville()])


@lru_cache(maxsize=32)
def _basis(kv: KnotVector) -> SplineBasis1D:
    return SplineBasis1D.from_knots(kv)


def _refine_homogeneous(Pw: np.ndarray, kv: KnotVector, m: int, axis: int):
    if m == 1:
        return Pw, kv
    kv_new, A = refine(kv, m)
    A = np.array(A.tolist(), dtype=float)
    return np.moveaxis(np.tensordot(A, np.moveaxis(Pw, axis, 0), axes=1), 0, axis), kv_new


def quarter_ring(r_inner: float, r_outer: float, n_xi_elements: int = 1,
                 n_eta_elements: int = 1, theta0: float = 0.0,
                 center: tuple[float, float] = (0.0, 0.0)) -> RingPatch:
    """Quarter ring between radii ``r_inner < r_outer`` spanning ``[theta0, theta0 + pi/2]``.

    Parameters
    ----------
    r_inner, r_outer : float
        Radii (m).
    n_xi_elements, n_eta_elements : int
        Uniform subdivisions of the single coarse element along the arc and through the
        thickness (knot insertion, geometry unchanged).
    theta0 : float
        Start angle of the arc (rad).
    center : (float, float)
        Centre of the ring (m).

    >>> ring = quarter_ring(1.0, 2.0)
    >>> ring.points.shape, ring.weights.round(4).tolist()[:3]
    ((9, 2), [1.0, 1.0, 1.0])
    """
    check_positive("r_inner", r_inner)
    check_positive("r_outer", r_outer)
    if not r_outer > r_inner:
        raise InputError(f"r_outer must be > r_inner = {r_inner}, got {r_outer}")
    m_xi = check_positive_int("n_xi_elements", n_xi_elements)
    m_eta = check_positive_int("n_eta_elements", n_eta_elements)
    c = np.cos(np.pi / 4)
    angles = theta0 + np.array([0.0, np.pi / 4, np.pi / 2])
    radii = np.array([r_inner, 0.5 * (r_inner + r_outer), r_outer])
    scale = np.array([1.0, 1.0 / c, 1.0])
    w_xi = np.array([1.0, c, 1.0])
    P = (scale[:, None, None] * radii[None, :, None]
         * np.stack([np.cos(angles), np.sin(angles)], -1)[:, None, :]) + np.asarray(center)
    w = np.repeat(w_xi[:, None], 3, axis=1)
    Pw = np.concatenate([P * w[..., None], w[..., None]], axis=-1)  # (3, 3, 3)
    Pw, kv_xi = _refine_homogeneous(Pw, open_knot_vector(2, 1), m_xi, 0)
    Pw, kv_eta = _refine_homogeneous(Pw, open_knot_vector(2, 1), m_eta, 1)
    weights = Pw[..., 2].reshape(-1)
    points = (Pw[..., :2] / Pw[..., 2:]).reshape(-1, 2)
    return RingPatch(kv_xi, kv_eta, points, weights)
