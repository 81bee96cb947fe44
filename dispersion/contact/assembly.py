"""Galerkin assembly on a NURBS patch: internal force, tangent stiffness, strain energy, mass.

Full :math:`(p+1) \\times (p+1)` Gauss quadrature per element, any degree. With nodal displacements
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

from dispersion.errors import InputError
from dispersion.mass_rules.mass_rule import mass_variant
from dispersion.contact.material import StVenantKirchhoff
from dispersion.contact.nurbs import RingPatch, SplineBasis1D
from dispersion.contact.redistribution import float_redistribution

__all__ = [
    "Discretization",
    "consistent_mass",
    "discretize",
    "float_redistribution",
    "patch_mass",
    "patch_redistribution",
    "internal_force",
    "ring_mass",
    "ring_redistribution",
    "strain_energy",
]

@dataclass(frozen=True)
class Discretization:
    """Quadrature data: connectivity ``(n_el, nf)``, ``R (n_el, ng, nf)``, ``dR (n_el, ng, nf, 2)``.

    ``nf = (p_xi + 1)(p_eta + 1)`` functions per element, ``ng`` Gauss points (``p + 1`` per
    direction). ``pattern`` is the CSR structure of the stiffness ``(indices, indptr, slot)``:
    entry ``i`` of the element matrices (flattened) adds into ``data[slot[i]]``, so assembly
    is a single ``bincount`` with no sorting per call; ``dense_slot`` holds the flat position
    of each CSR entry in a dense ``(n_dofs, n_dofs)`` array. ``BF`` maps the DOFs to the
    displacement gradient components ``(F00 - 1, F01, F10, F11 - 1)`` at all Gauss points
    (stacked); its transpose ``BFT`` maps weighted stresses back to nodal forces.
    """

    patch: RingPatch
    conn: np.ndarray
    R: np.ndarray
    dR: np.ndarray
    wdet: np.ndarray
    pattern: tuple
    dense_slot: np.ndarray
    BF: sp.csr_matrix
    BFT: sp.csr_matrix

    @property
    def n_points(self) -> int:
        return self.patch.n_points

    @property
    def n_dofs(self) -> int:
        return 2 * self.patch.n_points

    def element_dofs(self) -> np.ndarray:
        return (2 * self.conn[:, :, None] + np.arange(2)).reshape(len(self.conn), -1)


def _gauss_on_spans(basis: SplineBasis1D):
    gx, gw = np.polynomial.legendre.leggauss(basis.kv.p + 1)
    a, b = basis.spans[:, 0:1], basis.spans[:, 1:2]
    x = a + (b - a) * (gx + 1) / 2  # (n_el, p + 1)
    w = (b - a) / 2 * gw
    _, N = basis.evaluate(x.ravel(), 0)
    _, dN = basis.evaluate(x.ravel(), 1)
    shape = x.shape + (basis.kv.p + 1,)
    return N.reshape(shape), dN.reshape(shape), w


def discretize(patch: RingPatch) -> Discretization:
    """Rational basis values and reference gradients at the Gauss points of each element."""
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
    ng, nf = Nx.shape[1] * Ny.shape[1], conn.shape[1]
    N, dN1, dN2 = (a.reshape(n_el, ng, nf) for a in (N, dN1, dN2))
    w = patch.weights[conn][:, None, :]
    W = np.sum(w * N, -1, keepdims=True)
    R = w * N / W
    dR = np.stack([(w * d - R * np.sum(w * d, -1, keepdims=True)) / W for d in (dN1, dN2)], -1)
    X = patch.points[conn]  # (n_el, nf, 2)
    J = np.einsum("eak,egal->egkl", X, dR)  # dX_k / dxi_l
    detJ = np.linalg.det(J)
    if np.any(detJ == 0) or np.any(np.sign(detJ) != np.sign(detJ.flat[0])):
        raise InputError("points: the patch's Jacobian vanishes or changes sign (folded patch)")
    dRdX = np.einsum("egal,eglk->egak", dR, np.linalg.inv(J))
    wq = np.einsum("eg,eh->egh", wx[ex], wy[ey]).reshape(n_el, ng)
    dofs = (2 * conn[:, :, None] + np.arange(2)).reshape(n_el, -1)
    n = 2 * patch.n_points
    pattern = _csr_pattern(dofs, n)
    rows = np.repeat(np.arange(n), np.diff(pattern[1]))
    BF = _gradient_operator(conn, dRdX, n)
    return Discretization(patch, conn, R, dRdX, wq * np.abs(detJ), pattern,
                          rows * n + pattern[0], BF, BF.T.tocsr())


def _gradient_operator(conn: np.ndarray, dR: np.ndarray, n: int) -> sp.csr_matrix:
    """Sparse ``(4 n_gauss, n_dofs)`` map ``u -> (F00 - 1, F01, F10, F11 - 1)`` at every Gauss
    point, :math:`F_{kJ} - \\delta_{kJ} = \\sum_a u_{ak} \\partial_J R_a`."""
    n_el, ng, nf = dR.shape[:3]
    npts = n_el * ng
    point = np.arange(npts).reshape(n_el, ng)[:, :, None]
    node = conn[:, None, :]
    rows, cols, vals = [], [], []
    for block, (k, J) in enumerate(((0, 0), (0, 1), (1, 0), (1, 1))):
        r = np.broadcast_to(block * npts + point, (n_el, ng, nf))
        c = np.broadcast_to(2 * node + k, (n_el, ng, nf))
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(dR[..., J].ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(4 * npts, n))


def _csr_pattern(dofs: np.ndarray, n: int) -> tuple:
    """CSR ``(indices, indptr, slot)`` of the matrix assembled from element ``dofs``."""
    k = dofs.shape[1]
    key = (np.repeat(dofs, k, axis=1) * n + np.tile(dofs, (1, k))).ravel()
    unique, slot = np.unique(key, return_inverse=True)
    indptr = np.searchsorted(unique, np.arange(n + 1) * n)
    return unique % n, indptr, slot


def _kinematics(disc: Discretization, mat: StVenantKirchhoff, u: np.ndarray):
    ue = np.asarray(u, dtype=float).reshape(-1, 2)[disc.conn]  # (e, a, k)
    # F_kJ = delta_kJ + sum_a u_ak dR_aJ, one batched matmul over (element, gauss point)
    F = np.matmul(ue.transpose(0, 2, 1)[:, None], disc.dR)
    F[..., 0, 0] += 1.0
    F[..., 1, 1] += 1.0
    C = np.matmul(F.transpose(0, 1, 3, 2), F)
    E = 0.5 * C
    E[..., 0, 0] -= 0.5
    E[..., 1, 1] -= 0.5
    return F, E, mat.stress(E)


def _green_components(disc: Discretization, u: np.ndarray):
    """Deformation gradient and Green strain by components at every Gauss point (fast path)."""
    Fv = (disc.BF @ np.asarray(u, dtype=float)).reshape(4, -1)
    F00, F01, F10, F11 = 1.0 + Fv[0], Fv[1], Fv[2], 1.0 + Fv[3]
    E00 = 0.5 * (F00 * F00 + F10 * F10 - 1.0)
    E11 = 0.5 * (F01 * F01 + F11 * F11 - 1.0)
    E01 = 0.5 * (F00 * F01 + F10 * F11)
    return (F00, F01, F10, F11), (E00, E11, E01)


def _force(disc: Discretization, mat: StVenantKirchhoff, u: np.ndarray) -> np.ndarray:
    """Internal force alone, by components (no 2 x 2 matrix products per Gauss point)."""
    (F00, F01, F10, F11), (E00, E11, E01) = _green_components(disc, u)
    tr = mat.lam_bar * (E00 + E11)
    w = disc.wdet.ravel()
    S00, S11, S01 = (tr + 2 * mat.mu * E00) * w, (tr + 2 * mat.mu * E11) * w, 2 * mat.mu * E01 * w
    # f_ak = sum_g sum_J P_kJ dR_aJ: the transpose of the gradient map applied to P
    P = np.concatenate([F00 * S00 + F01 * S01, F00 * S01 + F01 * S11,
                        F10 * S00 + F11 * S01, F10 * S01 + F11 * S11])
    return disc.BFT @ P


def internal_force(disc: Discretization, mat: StVenantKirchhoff, u: np.ndarray,
                   tangent: bool = True, dense: bool = False):
    """Internal force vector ``(n_dofs,)`` and (if ``tangent``) the tangent stiffness.

    The stiffness is CSR, or a dense array with ``dense=True`` (small problems, where
    LAPACK on the full matrix is faster than any sparse format).
    """
    if not tangent:
        return _force(disc, mat, u)
    F, _, S = _kinematics(disc, mat, u)
    n_el, n_g, n_f = disc.R.shape
    P = np.matmul(F, S) * disc.wdet[:, :, None, None]  # first Piola-Kirchhoff stress x weight
    # f_ak = sum_g sum_J P_kJ dR_aJ
    fe = np.matmul(disc.dR, P.transpose(0, 1, 3, 2)).sum(axis=1).reshape(n_el, -1)
    dofs = disc.element_dofs()
    f = np.bincount(dofs.ravel(), fe.ravel(), minlength=disc.n_dofs)
    if not tangent:
        return f
    dR = disc.dR
    B = np.empty((n_el, n_g, 3, n_f, 2))
    B[:, :, 0] = F[:, :, None, :, 0] * dR[..., 0:1]
    B[:, :, 1] = F[:, :, None, :, 1] * dR[..., 1:2]
    B[:, :, 2] = F[:, :, None, :, 0] * dR[..., 1:2] + F[:, :, None, :, 1] * dR[..., 0:1]
    B = B.reshape(n_el, n_g, 3, 2 * n_f)  # (element, gauss, Voigt row, element DOF)
    CB = np.matmul(mat.voigt(), B) * disc.wdet[:, :, None, None]
    Km = np.matmul(B.reshape(n_el, 3 * n_g, -1).transpose(0, 2, 1), CB.reshape(n_el, 3 * n_g, -1))
    SdR = np.matmul(dR, S) * disc.wdet[:, :, None, None]  # (e, g, a, J): S symmetric
    Gm = np.matmul(dR.transpose(0, 2, 1, 3).reshape(n_el, n_f, -1),
                   SdR.transpose(0, 1, 3, 2).reshape(n_el, -1, n_f))
    Km = Km.reshape(n_el, n_f, 2, n_f, 2)
    Km[:, :, 0, :, 0] += Gm
    Km[:, :, 1, :, 1] += Gm
    n = disc.n_dofs
    indices, indptr, slot = disc.pattern
    data = np.bincount(slot, Km.ravel(), minlength=len(indices))
    if dense:
        Kd = np.zeros(n * n)
        Kd[disc.dense_slot] = data
        return f, Kd.reshape(n, n)
    return f, sp.csr_matrix((data, indices, indptr), shape=(n, n))


def strain_energy(disc: Discretization, mat: StVenantKirchhoff, u: np.ndarray) -> float:
    """Stored energy :math:`\\int_{\\Omega_0} W(\\mathbf E) \\, dA` (J per unit thickness)."""
    _, (E00, E11, E01) = _green_components(disc, u)
    tr = E00 + E11
    W = 0.5 * mat.lam_bar * tr**2 + mat.mu * (E00**2 + E11**2 + 2 * E01**2)
    return float(np.sum(disc.wdet.ravel() * W))


def consistent_mass(disc: Discretization, rho: float) -> sp.csr_matrix:
    """Scalar consistent mass ``(n_points, n_points)``: :math:`\\int \\rho R_a R_b dA`."""
    Me = rho * np.einsum("eg,ega,egb->eab", disc.wdet, disc.R, disc.R)
    nf = disc.conn.shape[1]
    rows = np.repeat(disc.conn, nf, axis=1).ravel()
    cols = np.tile(disc.conn, (1, nf)).ravel()
    n = disc.n_points
    return sp.csr_matrix((Me.ravel(), (rows, cols)), shape=(n, n))


def patch_redistribution(patch: RingPatch, side: str = "eta1",
                         gamma_s: float = 0.5) -> sp.csr_matrix:
    """Redistribution ``R`` (``N_m = N R``) moving every function of ``side`` inward.

    Each line of control points across the patch gets the paper's weights
    (:func:`dispersion.symbolic.mass.contact_weights`, eqs 2-4): ``1 - gamma_s`` to the neighbour,
    ``gamma_s`` to the next one.
    """
    if side.startswith("eta"):
        Rc = float_redistribution(patch.n_eta, "top" if side == "eta1" else "bottom", gamma_s)
        return sp.kron(sp.eye(patch.n_xi), sp.csr_matrix(Rc)).tocsr()
    Rc = float_redistribution(patch.n_xi, "top" if side == "xi1" else "bottom", gamma_s)
    return sp.kron(sp.csr_matrix(Rc), sp.eye(patch.n_eta)).tocsr()


def ring_redistribution(patch: RingPatch, gamma_s: float = 0.5) -> sp.csr_matrix:
    """:func:`patch_redistribution` of the outer surface ``eta1`` (the ring's contact side)."""
    return patch_redistribution(patch, "eta1", gamma_s)


def patch_mass(disc: Discretization, rho: float, variant: str = "consistent",
               side: str = "eta1", gamma_s: float = 0.5) -> sp.csr_matrix:
    """Mass matrix on the interleaved DOFs for ``variant`` (see
    :func:`dispersion.symbolic.mass_rule.mass_variant`); singular variants redistribute ``side``."""
    from dispersion.mass_rules.mass_rule import get_rule

    rule = get_rule(variant)
    M = consistent_mass(disc, rho)
    R = patch_redistribution(disc.patch, side, gamma_s) if rule.redistributes else None
    Me = rho * np.einsum("eg,ega,egb->eab", disc.wdet, disc.R, disc.R)
    Mv = sp.csr_matrix(mass_variant(M, rule, R, elements=(disc.conn, Me)))
    Mv.eliminate_zeros()
    return sp.kron(Mv, sp.eye(2)).tocsr()


def ring_mass(disc: Discretization, rho: float, variant: str = "consistent",
              gamma_s: float = 0.5) -> sp.csr_matrix:
    """:func:`patch_mass` with the ring's contact side ``eta1``."""
    return patch_mass(disc, rho, variant, "eta1", gamma_s)
