"""Stiffness and mass of a strip mapped by a NURBS geometry (the ring's quarter annulus).

On a patch :math:`\\mathbf x(\\xi, \\eta) = \\sum_a R_a(\\xi, \\eta) \\mathbf P_a` with the
rational basis :math:`R_a = w_a N_a / \\sum_b w_b N_b` (tensor-product B-splines
:math:`N_a`), linear elasticity with the shear modulus :math:`\\mu = 1` and density
:math:`\\rho = 1` (frequencies in :math:`c_T` over the geometry's length unit):

.. math::

    K = \\int_\\Omega B^T D B \\, dA, \\qquad M_{ab} = \\int_\\Omega \\rho R_a R_b \\, dA,

:math:`D` the plane-strain moduli (:math:`\\lambda + 2\\mu, \\lambda, \\mu`) or plane-stress
ones (:math:`\\lambda^* = 2 \\lambda \\mu / (\\lambda + 2 \\mu)` for :math:`\\lambda`),
Gauss-Legendre with p + 1 points per direction on each element. The scalar mass is then the
rule's: consistent, row-sum lumped, HRZ (per element), or the singular rules' redistribution
of the contact side (``top``: :math:`\\eta = 1`, the ring's outer surface) with the paper's
weights, :math:`R^T M R` and its row sums (eq 1). DOFs ``2 * (i * n_eta + j) + c``.

>>> from dispersion.splines.nurbs import quarter_ring
>>> from dispersion.discretization.finite_mesh.finite_patch import mapped_strip
>>> from dispersion.discretization.finite_mesh.finite_assembly import assemble
>>> m = assemble(mapped_strip(quarter_ring(0.9, 1.0, 4, 2), mass="lumped"))
>>> abs(float(m.mass.sum()) - 3.141592653589793 / 4 * (1 - 0.81)) < 1e-6   # rho * area
True

References
----------
T. J. R. Hughes, J. A. Cottrell, Y. Bazilevs, CMAME 194 (2005) 4135-4195. L. Piegl, W. Tiller,
*The NURBS Book*, 2nd ed., Springer 1997 (rational basis derivatives). Paper eqs (1)-(4).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from dispersion.errors import InputError

__all__ = ["MAPPED_RULES", "assemble_mapped"]

#: The rules a mapped patch builds (from the consistent mass and its elements only).
MAPPED_RULES = ("consistent", "lumped", "hrz", "singular", "singular-lumped")


def _gauss(basis):
    p = basis.kv.p
    g, w = np.polynomial.legendre.leggauss(p + 1)
    a, b = basis.spans[:, :1], basis.spans[:, 1:]
    x = a + (b - a) * (g + 1) / 2
    _, N = basis.evaluate(x.ravel(), 0)
    _, dN = basis.evaluate(x.ravel(), 1)
    shape = x.shape + (p + 1,)
    return N.reshape(shape), dN.reshape(shape), (b - a) / 2 * w


def _moduli(nu: float, plane: str) -> tuple[float, float]:
    """``(lambda, mu)`` with mu = 1."""
    lam = 2 * nu / (1 - 2 * nu)
    if plane == "stress":
        lam = 2 * lam / (lam + 2)
    return lam, 1.0


def assemble_mapped(patch, step_kind):
    """The :class:`~dispersion.discretization.finite_mesh.finite_assembly.FiniteMatrices` of a mapped
    strip (``patch.geometry``)."""
    from dispersion.discretization.finite_mesh.finite_matrices import FiniteMatrices
    from dispersion.splines.bspline import SplineBasis1D

    rule = patch.rule
    if rule.name not in MAPPED_RULES:
        raise InputError(f"mass rule {rule.name!r} on a mapped patch: the rules built there "
                         f"are {', '.join(MAPPED_RULES)}")
    g = patch.geometry
    bx, by = SplineBasis1D.from_knots(g.kv_xi), SplineBasis1D.from_knots(g.kv_eta)
    n_eta = g.kv_eta.n
    Nx, dNx, wx = _gauss(bx)
    Ny, dNy, wy = _gauss(by)
    ex, ey = np.meshgrid(np.arange(len(bx.spans)), np.arange(len(by.spans)), indexing="ij")
    ex, ey = ex.ravel(), ey.ravel()
    conn = (bx.active[ex][:, :, None] * n_eta + by.active[ey][:, None, :]).reshape(len(ex), -1)
    n_el, nf = conn.shape
    N = np.einsum("egi,ehj->eghij", Nx[ex], Ny[ey]).reshape(n_el, -1, nf)
    d1 = np.einsum("egi,ehj->eghij", dNx[ex], Ny[ey]).reshape(n_el, -1, nf)
    d2 = np.einsum("egi,ehj->eghij", Nx[ex], dNy[ey]).reshape(n_el, -1, nf)
    w = np.asarray(g.weights, float)[conn][:, None, :]
    W = np.sum(w * N, -1, keepdims=True)
    R = w * N / W
    dR = np.stack([(w * d - R * np.sum(w * d, -1, keepdims=True)) / W for d in (d1, d2)], -1)
    X = np.asarray(g.points, float)[conn]
    J = np.einsum("eak,egal->egkl", X, dR)
    detJ = np.linalg.det(J)
    if np.any(detJ == 0) or np.any(np.sign(detJ) != np.sign(detJ.flat[0])):
        raise InputError("geometry: the patch's Jacobian vanishes or changes sign")
    G = np.einsum("egal,eglk->egak", dR, np.linalg.inv(J))  # dR_a / dx_k
    wq = np.einsum("eg,eh->egh", wx[ex], wy[ey]).reshape(n_el, -1) * np.abs(detJ)
    lam, mu = _moduli(patch.nu, patch.plane)
    gx, gy = G[..., 0], G[..., 1]
    # element stiffness blocks (component c of a, component d of b)
    Kxx = np.einsum("eg,ega,egb->eab", wq, gx, gx) * (lam + 2 * mu) + \
        np.einsum("eg,ega,egb->eab", wq, gy, gy) * mu
    Kyy = np.einsum("eg,ega,egb->eab", wq, gy, gy) * (lam + 2 * mu) + \
        np.einsum("eg,ega,egb->eab", wq, gx, gx) * mu
    Kxy = np.einsum("eg,ega,egb->eab", wq, gx, gy) * lam + \
        np.einsum("eg,ega,egb->eab", wq, gy, gx) * mu
    Ke = np.zeros((n_el, 2 * nf, 2 * nf))
    Ke[:, 0::2, 0::2], Ke[:, 1::2, 1::2] = Kxx, Kyy
    Ke[:, 0::2, 1::2], Ke[:, 1::2, 0::2] = Kxy, Kxy.transpose(0, 2, 1)
    dofs = (2 * conn[:, :, None] + np.arange(2)).reshape(n_el, -1)
    n_points = g.kv_xi.n * n_eta
    K = sp.csr_matrix((Ke.ravel(), (np.repeat(dofs, 2 * nf, axis=1).ravel(),
                                    np.tile(dofs, (1, 2 * nf)).ravel())),
                      shape=(2 * n_points, 2 * n_points))
    K.sum_duplicates()
    Me = np.einsum("eg,ega,egb->eab", wq, R, R)
    M = sp.csr_matrix((Me.ravel(), (np.repeat(conn, nf, axis=1).ravel(),
                                    np.tile(conn, (1, nf)).ravel())), shape=(n_points,) * 2)
    M.sum_duplicates()
    M = _rule_mass(patch, M, conn, Me, g.kv_xi.n, n_eta)
    rowmax = np.asarray(abs(M).max(axis=1).todense()).ravel()
    massless = np.flatnonzero(rowmax <= 1e-14 * rowmax.max())
    return FiniteMatrices(patch, rule, K.tocsr(), M, massless, bx, by, step_kind)


def _rule_mass(patch, M, conn, Me, n_xi, n_eta) -> sp.csr_matrix:
    """The rule's scalar mass from the consistent one and its elements."""
    from dispersion.mass_rules.mass import contact_weights

    name = patch.rule.name
    if name == "consistent":
        return M.tocsr()
    if name == "lumped":
        return sp.diags(np.asarray(M.sum(axis=1)).ravel()).tocsr()
    if name == "hrz":
        diag = np.einsum("eii->ei", Me)
        diag = diag * (Me.sum(axis=(1, 2)) / diag.sum(axis=1))[:, None]
        return sp.diags(np.bincount(conn.ravel(), diag.ravel(), minlength=M.shape[0])).tocsr()
    Re = np.eye(n_eta)
    for c, ws in contact_weights(n_eta, patch.contact, patch.gamma_s).items():
        Re[c, c] = 0.0
        for j, wt in ws.items():
            Re[c, j] = float(wt)
    Rm = sp.kron(sp.identity(n_xi), sp.csr_matrix(Re), format="csr")
    Mm = (Rm.T @ M @ Rm).tocsr()
    if name == "singular-lumped":
        Mm = sp.diags(np.asarray(Mm.sum(axis=1)).ravel()).tocsr()
    Mm.eliminate_zeros()
    return Mm
