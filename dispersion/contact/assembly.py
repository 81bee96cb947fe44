"""Galerkin assembly on a NURBS patch: internal force, tangent stiffness, strain energy, mass.

Full :math:`3 \\times 3` Gauss quadrature per element. With nodal displacements
:math:`\\mathbf u_a` and the rational basis :math:`R_a`,

.. math::

    \\mathbf F = \\mathbf I + \\sum_a \\mathbf u_a \\otimes \\nabla_X R_a, \\qquad
    \\mathbf f^{\\mathrm{int}}_a = \\int_{\\Omega_0} \\mathbf F \\mathbf S \\nabla_X R_a \\, dA,

    \\mathbf K_{ab} = \\int_{\\Omega_0} \\big( (\\nabla_X R_a \\cdot \\mathbf S \\nabla_X R_b)
    \\mathbf I + \\mathbf B_a^T \\mathbb C \\mathbf B_b \\big) dA, \\qquad
    \\mathbf M_{ab} = \\int_{\\Omega_0} \\rho R_a R_b \\, dA \\; \\mathbf I .

Degrees of freedom are interleaved: ``2 * point + k`` for component ``k`` (0 = x, 1 = y).
Matrices are ``scipy.sparse`` CSR. Unit out-of-plane thickness.

>>> from dispersion.contact.nurbs import quarter_ring
>>> from dispersion.contact.material import StVenantKirchhoff
>>> disc = discretize(quarter_ring(1.0, 2.0, 2, 1))
>>> bool(abs(disc.wdet.sum() - np.pi * 3 / 4) < 1e-6)  # area (R^2 - r^2) pi / 4
True
>>> f, K = internal_force(disc, StVenantKirchhoff(1.0, 0.3), np.zeros((disc.n_points, 2)))
>>> float(abs(f).max()), K.shape
(0.0, (24, 24))

References
----------
T. Belytschko, W. K. Liu, B. Moran, *Nonlinear Finite Elements for Continua and Structures*,
Wiley 2000, sec. 4.9 (total Lagrangian internal force and tangent).
T. J. R. Hughes, J. A. Cottrell, Y. Bazilevs, "Isogeometric analysis", CMAME 194 (2005).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..mass import contact_weights, mass_variant, redistribution_matrix
from .material import StVenantKirchhoff
from .nurbs import RingPatch, SplineBasis1D

__all__ = [
    "Discretization",
    "consistent_mass",
    "discretize",
    "internal_force",
    "ring_mass",
    "ring_redistribution",
    "strain_energy",
]

_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(3)


@dataclass(frozen=True)
class Discretization:
    """Quadrature data: connectivity ``(n_el, 9)``, ``R (n_el, 9g, 9)``, ``dR (n_el, 9g, 9, 2)``.

    ``pattern`` is the CSR structure of the stiffness ``(indices, indptr, slot)``: entry ``i``
    of the element matrices (flattened) adds into ``data[slot[i]]``, so assembly is a single
    ``bincount`` with no sorting per call.
    """

    patch: RingPatch
    conn: np.ndarray
    R: np.ndarray
    dR: np.ndarray
    wdet: np.ndarray
    pattern: tuple

    @property
    def n_points(self) -> int:
        return self.patch.n_points

    @property
    def n_dofs(self) -> int:
        return 2 * self.patch.n_points

    def element_dofs(self) -> np.ndarray:
        return (2 * self.conn[:, :, None] + np.arange(2)).reshape(len(self.conn), -1)


def _gauss_on_spans(basis: SplineBasis1D):
    a, b = basis.spans[:, 0:1], basis.spans[:, 1:2]
    x = a + (b - a) * (_GAUSS_X + 1) / 2  # (n_el, 3)
    w = (b - a) / 2 * _GAUSS_W
    _, N = basis.evaluate(x.ravel(), 0)
    _, dN = basis.evaluate(x.ravel(), 1)
    shape = x.shape + (basis.kv.p + 1,)
    return N.reshape(shape), dN.reshape(shape), w


def discretize(patch: RingPatch) -> Discretization:
    """Rational basis values and reference gradients at the 3 x 3 Gauss points of each element."""
    bx, by = SplineBasis1D.from_knots(patch.kv_xi), SplineBasis1D.from_knots(patch.kv_eta)
    Nx, dNx, wx = _gauss_on_spans(bx)
    Ny, dNy, wy = _gauss_on_spans(by)
    ex, ey = np.meshgrid(np.arange(len(bx.spans)), np.arange(len(by.spans)), indexing="ij")
    ex, ey = ex.ravel(), ey.ravel()
    conn = (bx.active[ex][:, :, None] * patch.n_eta + by.active[ey][:, None, :]).reshape(len(ex), -1)
    # tensor products over (gauss x, gauss y) and (function x, function y)
    N = np.einsum("egi,ehj->eghij", Nx[ex], Ny[ey])
    dN1 = np.einsum("egi,ehj->eghij", dNx[ex], Ny[ey])
    dN2 = np.einsum("egi,ehj->eghij", Nx[ex], dNy[ey])
    n_el = len(ex)
    N, dN1, dN2 = (a.reshape(n_el, 9, 9) for a in (N, dN1, dN2))
    w = patch.weights[conn][:, None, :]
    W = np.sum(w * N, -1, keepdims=True)
    R = w * N / W
    dR = np.stack([(w * d - R * np.sum(w * d, -1, keepdims=True)) / W for d in (dN1, dN2)], -1)
    X = patch.points[conn]  # (n_el, 9, 2)
    J = np.einsum("eak,egal->egkl", X, dR)  # dX_k / dxi_l
    detJ = np.linalg.det(J)
    dRdX = np.einsum("egal,eglk->egak", dR, np.linalg.inv(J))
    wq = np.einsum("eg,eh->egh", wx[ex], wy[ey]).reshape(n_el, 9)
    dofs = (2 * conn[:, :, None] + np.arange(2)).reshape(n_el, -1)
    return Discretization(patch, conn, R, dRdX, wq * np.abs(detJ),
                          _csr_pattern(dofs, 2 * patch.n_points))


def _csr_pattern(dofs: np.ndarray, n: int) -> tuple:
    """CSR ``(indices, indptr, slot)`` of the matrix assembled from element ``dofs``."""
    k = dofs.shape[1]
    key = (np.repeat(dofs, k, axis=1) * n + np.tile(dofs, (1, k))).ravel()
    unique, slot = np.unique(key, return_inverse=True)
    indptr = np.searchsorted(unique, np.arange(n + 1) * n)
    return unique % n, indptr, slot


def _kinematics(disc: Discretization, mat: StVenantKirchhoff, u: np.ndarray):
    ue = np.asarray(u, dtype=float).reshape(-1, 2)[disc.conn]
    F = np.eye(2) + np.einsum("eak,egaJ->egkJ", ue, disc.dR, optimize=True)
    E = 0.5 * (F.transpose(0, 1, 3, 2) @ F - np.eye(2))
    return F, E, mat.stress(E)


def internal_force(disc: Discretization, mat: StVenantKirchhoff, u: np.ndarray,
                   tangent: bool = True):
    """Internal force vector ``(n_dofs,)`` and (if ``tangent``) the tangent stiffness (CSR)."""
    F, _, S = _kinematics(disc, mat, u)
    n_el = len(disc.conn)
    P = (F @ S) * disc.wdet[:, :, None, None]  # first Piola-Kirchhoff stress times weight
    fe = np.einsum("egkJ,egaJ->eak", P, disc.dR, optimize=True).reshape(n_el, -1)
    dofs = disc.element_dofs()
    f = np.bincount(dofs.ravel(), fe.ravel(), minlength=disc.n_dofs)
    if not tangent:
        return f
    dR = disc.dR
    B = np.empty(F.shape[:2] + (3, 9, 2))
    B[:, :, 0] = F[:, :, None, :, 0] * dR[..., 0:1]
    B[:, :, 1] = F[:, :, None, :, 1] * dR[..., 1:2]
    B[:, :, 2] = F[:, :, None, :, 0] * dR[..., 1:2] + F[:, :, None, :, 1] * dR[..., 0:1]
    B = B.reshape(n_el, 27, 18)  # (element, gauss x Voigt row, element DOF)
    CB = (mat.voigt() @ B.reshape(n_el, 9, 3, 18)) * disc.wdet[:, :, None, None]
    Km = B.transpose(0, 2, 1) @ CB.reshape(n_el, 27, 18)
    SdR = (dR @ S) * disc.wdet[:, :, None, None]  # (e, g, a, J): S symmetric
    G = dR.transpose(0, 2, 1, 3).reshape(n_el, 9, 18) @ SdR.transpose(0, 1, 3, 2).reshape(
        n_el, 18, 9)
    Ke = Km + np.einsum("eab,kl->eakbl", G, np.eye(2)).reshape(n_el, 18, 18)
    indices, indptr, slot = disc.pattern
    data = np.bincount(slot, Ke.ravel(), minlength=len(indices))
    K = sp.csr_matrix((data, indices, indptr), shape=(disc.n_dofs, disc.n_dofs))
    return f, K


def strain_energy(disc: Discretization, mat: StVenantKirchhoff, u: np.ndarray) -> float:
    """Stored energy :math:`\\int_{\\Omega_0} W(\\mathbf E) \\, dA` (J per unit thickness)."""
    _, E, _ = _kinematics(disc, mat, u)
    return float(np.sum(disc.wdet * mat.energy_density(E)))


def consistent_mass(disc: Discretization, rho: float) -> sp.csr_matrix:
    """Scalar consistent mass ``(n_points, n_points)``: :math:`\\int \\rho R_a R_b dA`."""
    Me = rho * np.einsum("eg,ega,egb->eab", disc.wdet, disc.R, disc.R)
    rows = np.repeat(disc.conn, 9, axis=1).ravel()
    cols = np.tile(disc.conn, (1, 9)).ravel()
    n = disc.n_points
    return sp.csr_matrix((Me.ravel(), (rows, cols)), shape=(n, n))


def ring_redistribution(patch: RingPatch, gamma_s: float = 0.5) -> sp.csr_matrix:
    """Redistribution ``R`` (``N_m = N R``) moving every outer-surface function inward.

    Each column of control points through the thickness gets the paper's weights
    (:func:`dispersion.mass.contact_weights`, eqs 2-4): ``1 - gamma_s`` to the neighbour,
    ``gamma_s`` to the next one.
    """
    Rc = redistribution_matrix(patch.n_eta, contact_weights(patch.n_eta, "top", gamma_s))
    Rc = np.array(Rc.tolist(), dtype=float)
    return sp.kron(sp.eye(patch.n_xi), sp.csr_matrix(Rc)).tocsr()


def ring_mass(disc: Discretization, rho: float, variant: str = "consistent",
              gamma_s: float = 0.5) -> sp.csr_matrix:
    """Mass matrix on the interleaved DOFs for ``variant`` (see :func:`dispersion.mass.mass_variant`)."""
    M = consistent_mass(disc, rho)
    R = ring_redistribution(disc.patch, gamma_s) if variant.startswith("singular") else None
    Mv = sp.csr_matrix(mass_variant(M, variant, R))
    Mv.eliminate_zeros()
    return sp.kron(Mv, sp.eye(2)).tocsr()
