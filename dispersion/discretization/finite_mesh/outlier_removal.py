"""Outlier removal: published ways to bring the boundary frequencies of a mesh back down.

The exact modes of the bar and of the strip's symmetry planes have boundary derivatives the
open B-spline space does not know: at a free end the odd derivatives vanish
(:math:`\\cos k x`), at a fixed end the even ones (:math:`\\sin k x`). The boundary
functions that violate them carry the outlier frequencies. Three methods, each a named
option of :class:`~dispersion.discretization.finite_mesh.finite_patch.FinitePatch` (``removal``):

``constraints``
    the derivatives imposed strongly, the space restricted to the splines with
    :math:`u^{(k)} = 0` at the end for k odd, :math:`1 \\le k \\le p - 1` (free end) or k even,
    :math:`2 \\le k \\le p - 1` (fixed end); a sliding end of the strip imposes the fixed
    set on :math:`u_x` and the free set on :math:`u_y`. K and M are restricted Galerkin-wise,
    :math:`Z^T K Z`, :math:`Z^T M Z` (a diagonal mass gains a small block at each end). The
    construction of Hiemstra, Hughes, Reali and Schillinger (CMAME 387 (2021) 114115) and,
    on their knot sequences, the optimal spline subspaces of Manni, Sande and Speleers
    (CMAME 389 (2022) 114260; abstract: "no outliers").
``penalty``
    the same derivatives penalized weakly in both forms (Deng and Calo, CMAME 383 (2021)
    113907, abstract: "we penalize the higher-order derivatives from both the solution and
    test spaces at the domain boundary"; the spaces unchanged),

    .. math::

        \\tilde K = K + \\eta \\sum_k (\\omega_\\ell h)^2 h^{2k-1} c^2 \\,
        \\mathbf N^{(k)} \\mathbf N^{(k)T}, \\qquad
        \\tilde M = M + \\eta \\sum_k h^{2k+1} \\rho \\, \\mathbf N^{(k)} \\mathbf N^{(k)T},

    at each end, :math:`\\eta` = ``removal_parameter`` (default 1), :math:`\\omega_\\ell` the
    lattice's largest frequency of the same rule. The weights are ours (the body of the
    paper was not accessible here): :math:`h^{2k \\mp 1}` give each term the order of its
    form on a boundary function, and the pair's ratio places a penalized boundary mode at the
    top of the lattice (:math:`\\omega_\\ell h/c = \\pi` within 0.7 % for the consistent mass,
    p >= 2); :math:`\\eta \\to \\infty` gives ``constraints``.
``perturbation``
    the mass perturbed along each outlier mode x (M-normalized, frequency
    :math:`\\omega > \\omega_\\ell`, the lattice's largest),
    :math:`\\tilde M = M + \\alpha\\, (M x)(M x)^T`, :math:`\\alpha = \\omega^2 / \\omega_\\ell^2 - 1`:
    by perturbed eigenvalue analysis x stays a mode with :math:`\\omega^2 / (1 + \\alpha) =
    \\omega_\\ell^2` and every other mode y is untouched (:math:`x^T M y = 0`), the rigid mode
    too (translational mass kept); Mx lives on the boundary functions (entries below 1e-13
    of its largest are dropped, which lets the others move by as little), and the
    outliers are found and perturbed again until none exceeds :math:`\\omega_\\ell` by 0.1 %
    (at most 8 rounds). After Nguyen, Hiemstra, Stoter and Schillinger (CMAME 392 (2022)
    114671, arXiv:2111.06501, abstract: "a variational approach based on perturbed
    eigenvalue analysis that eliminates outlier frequencies without negatively affecting the
    accuracy in the remainder of the spectrum", perturbation parameters estimated by an
    iterative procedure); the form of the perturbation is our reading of that abstract.

The singular mass (the paper's rules, ``mass="singular-lumped"``) is measured beside them:
it is a mass rule, not a removal option.

>>> from dispersion.discretization.finite_mesh.finite_patch import finite_bar
>>> from dispersion.discretization.finite_mesh.mesh_pencil import mesh_pencil
>>> mesh_pencil(finite_bar(4, 20, removal="constraints")).size   # 24 functions, u' u''' at 2 ends
20

References
----------
R. R. Hiemstra, T. J. R. Hughes, A. Reali, D. Schillinger, "Removal of spurious outlier
frequencies and modes from isogeometric discretizations of second- and fourth-order problems
in one, two, and three dimensions", CMAME 387 (2021) 114115, doi:10.1016/j.cma.2021.114115.
C. Manni, E. Sande, H. Speleers, "Application of optimal spline subspaces for the removal of
spurious outliers in isogeometric discretizations", CMAME 389 (2022) 114260,
doi:10.1016/j.cma.2021.114260, arXiv:2106.03710.
Q. Deng, V. M. Calo, "A boundary penalization technique to remove outliers from isogeometric
analysis on tensor-product meshes", CMAME 383 (2021) 113907, doi:10.1016/j.cma.2021.113907,
arXiv:2010.08159. Q. Deng, P. Behnoudfar, V. M. Calo, "A boundary-penalized isogeometric
analysis for second-order hyperbolic equations", arXiv:2203.12373.
T.-H. Nguyen, R. R. Hiemstra, S. K. F. Stoter, D. Schillinger, "A variational approach based on
perturbed eigenvalue analysis for improving spectral properties of isogeometric multipatch
discretizations", CMAME 392 (2022) 114671, doi:10.1016/j.cma.2022.114671, arXiv:2111.06501.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from dispersion.errors import InputError

__all__ = ["REMOVALS", "SOURCES", "check_removal", "apply_removal", "end_derivatives",
           "PERTURBATION_ROUNDS", "PERTURBATION_TOL"]

#: The removal methods, by name, and the source each follows.
SOURCES = {
    "constraints": "Hiemstra, Hughes, Reali, Schillinger, CMAME 387 (2021) 114115; Manni, "
                   "Sande, Speleers, CMAME 389 (2022) 114260",
    "penalty": "Deng, Calo, CMAME 383 (2021) 113907",
    "perturbation": "Nguyen, Hiemstra, Stoter, Schillinger, CMAME 392 (2022) 114671 "
                    "(arXiv:2111.06501)",
}
REMOVALS = tuple(SOURCES)
#: Rounds of the perturbation's iteration, and its stopping tolerance (relative, on a
#: frequency over the lattice's largest).
PERTURBATION_ROUNDS = 8
PERTURBATION_TOL = 1e-3


def check_removal(patch) -> None:
    """InputError if ``patch.removal`` is not a method, or does not apply to the patch."""
    if patch.removal is None:
        if patch.removal_parameter is not None:
            raise InputError("removal_parameter is a setting of a removal method; none given")
        return
    if patch.removal not in REMOVALS:
        raise InputError(f"removal must be one of {', '.join(REMOVALS)} or None, got "
                         f"{patch.removal!r}")
    if patch.periodic:
        raise InputError("removal: a periodic patch has no boundary outliers to remove")
    if patch.mapped or patch.rule.basis != "bspline":
        raise InputError("removal applies to the straight B-spline bar and strip")
    if patch.removal_parameter is not None:
        v = patch.removal_parameter
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not (
                math.isfinite(v) and 0 < v <= 1e12):
            raise InputError(f"removal_parameter must be a number in (0, 1e12], got {v!r}")
        if patch.removal != "penalty":
            raise InputError(f"removal_parameter sets the penalty eta; {patch.removal!r} "
                             "estimates its own")


def end_derivatives(patch) -> dict:
    """``{(column, component): orders}``: the derivatives each end annuls, per component
    (u_x: 0, u_y: 1; the bar has component 0 only)."""
    p = patch.p
    odd = tuple(range(1, p, 2))
    even = tuple(range(2, p, 2))
    out = {}
    for end, kind in zip((0, 1), patch.ends):
        comps = {"free": (odd, odd), "fixed": (even, even), "sliding": (even, odd)}[kind]
        for c in range(patch.dofs_per_point):
            if comps[c]:
                out[(end, c)] = comps[c]
    return out


def _derivative_rows(basis, x: float, orders) -> np.ndarray:
    """``(len(orders), p + 1)`` values of the k-th derivatives of the active functions at x,
    and the active indices."""
    rows = []
    act = None
    for k in orders:
        act, N = basis.evaluate(np.array([x]), k)
        rows.append(N[0])
    return np.array(rows), act[0]


def _point_layout(patch):
    """``(per_column, d)``: points per x-column and DOFs per point."""
    return (1 if patch.model == "bar" else patch.n), patch.dofs_per_point


def apply_removal(pen):
    """The pencil of ``pen`` with its patch's removal method applied."""
    method = pen.patch.removal
    if pen.M is None:
        raise InputError(f"removal {method!r} changes the mass; mass rule "
                         f"{pen.patch.rule.name!r} is known by its inverse only")
    if pen.massless.size:
        raise InputError(f"removal {method!r} with a singular mass (massless DOFs) is not "
                         "defined; the singular mass is measured as a method of its own")
    return {"constraints": _constraints, "penalty": _penalty,
            "perturbation": _perturbation}[method](pen)


def _x_functions(pen, column: int, c: int, functions: np.ndarray) -> np.ndarray:
    """Pencil rows of x-functions ``functions`` at every thickness point, component c:
    shape (len(functions), per_column); -1 where removed."""
    per, d = _point_layout(pen.patch)
    dof = d * (functions[:, None] * per + np.arange(per)[None, :]) + c
    where = np.searchsorted(pen.dofs, dof)
    where = np.minimum(where, pen.dofs.size - 1)
    return np.where(pen.dofs[where] == dof, where, -1)


def _constraints(pen):
    """Restrict to the splines whose end derivatives vanish (module docstring)."""
    patch = pen.patch
    basis = pen.matrices.basis_x
    n = pen.size
    Z = sp.identity(n, format="lil")
    drop = []
    for (end, c), orders in end_derivatives(patch).items():
        x = float(basis.spans[0, 0] if end == 0 else basis.spans[-1, 1])
        D, act = _derivative_rows(basis, x, orders)
        rows = _x_functions(pen, 0, c, act)  # (p + 1 functions, per_column)
        for t in range(rows.shape[1]):
            live = rows[:, t] >= 0
            idx, C = rows[live, t], D[:, live]
            # the constrained coefficients: those nearest the end, solved from the rest
            order = np.argsort(np.abs(act[live] - (0 if end == 0 else act.max())))
            solve, free = idx[order[:len(orders)]], idx[order[len(orders):]]
            Cs, Cf = C[:, order[:len(orders)]], C[:, order[len(orders):]]
            T = -np.linalg.solve(Cs, Cf)  # x_solve = T x_free
            for i, s in enumerate(solve):
                Z[s, s] = 0.0
                for j, f in enumerate(free):
                    Z[s, f] = T[i, j]
            drop.extend(solve.tolist())
    keep = np.setdiff1d(np.arange(n), drop)
    Z = Z.tocsr()[:, keep]
    K = (Z.T @ pen.K @ Z).tocsr()
    M = (Z.T @ pen.M @ Z).tocsr()
    return replace(pen, K=K, M=M, Z=Z, massless=np.zeros(0, dtype=int),
                   removal_note=f"{len(drop)} end derivatives imposed (Z^T K Z, Z^T M Z)")


def _moduli(patch) -> tuple[float, float]:
    """``(stiffness, density)`` scales of component c: c^2 = 1 for the bar; the strip's
    lambda + 2 mu (u_x) and mu (u_y)."""
    if patch.model == "bar":
        return (1.0, 1.0)
    from dispersion.symbolic.plate import lame

    mat = lame(patch.nu)
    return (float(mat["L2M"]), float(mat["M"]))


def _point_terms(pen, eta_k, eta_m):
    """Sum of the penalty terms (stiffness, mass) at the ends, on the pencil rows."""
    from dispersion.discretization.finite_mesh.lattice_reference import lattice_omega_max

    patch = pen.patch
    top2 = (lattice_omega_max(patch) * patch.element_length) ** 2  # (omega_l h)^2
    basis = pen.matrices.basis_x
    h = patch.element_length
    n = pen.size
    Kp = sp.lil_matrix((n, n))
    Mp = sp.lil_matrix((n, n))
    Yd = _thickness_weights(pen)
    moduli = _moduli(patch)
    for (end, c), orders in end_derivatives(patch).items():
        x = float(basis.spans[0, 0] if end == 0 else basis.spans[-1, 1])
        D, act = _derivative_rows(basis, x, orders)
        rows = _x_functions(pen, 0, c, act)
        stiff = moduli[c] if patch.model == "strip" else 1.0
        for i, k in enumerate(orders):
            outer = np.outer(D[i], D[i])
            for s in range(rows.shape[1]):
                for t in range(rows.shape[1]):
                    w = Yd[s, t]
                    if w == 0:
                        continue
                    for a in range(rows.shape[0]):
                        for b in range(rows.shape[0]):
                            ra, rb = rows[a, s], rows[b, t]
                            if ra < 0 or rb < 0:
                                continue
                            Kp[ra, rb] += eta_k * top2 * h ** (2 * k - 1) * stiff * \
                                w * outer[a, b]
                            Mp[ra, rb] += eta_m * h ** (2 * k + 1) * w * outer[a, b]
    return Kp.tocsr(), Mp.tocsr()


def _thickness_weights(pen) -> np.ndarray:
    """The thickness Gram Y^00 (edge integral of products) of the strip; 1 for the bar."""
    if pen.patch.model == "bar":
        return np.ones((1, 1))
    return np.asarray(pen.matrices.thickness["00"], dtype=float)


def _penalty(pen):
    eta = 1.0 if pen.patch.removal_parameter is None else float(pen.patch.removal_parameter)
    Kp, Mp = _point_terms(pen, eta, eta)
    return replace(pen, K=(pen.K + Kp).tocsr(), M=(pen.M + Mp).tocsr(),
                   removal_note=f"boundary penalty, eta = {eta:g}")


def _perturbation(pen):
    from dispersion.discretization.finite_mesh.lattice_reference import lattice_omega_max
    from dispersion.discretization.finite_mesh.mesh_spectrum import top_modes

    target2 = lattice_omega_max(pen.patch) ** 2
    M = pen.M.tocsr()
    k = min(pen.size - 2, 2 * pen.patch.p + 2)  # at most p - 1 outliers an end (and a margin)
    total, rounds = 0, 0
    for rounds in range(1, PERTURBATION_ROUNDS + 1):
        w, X = top_modes(replace(pen, M=M), k)
        above = np.flatnonzero(w**2 > target2 * (1 + PERTURBATION_TOL))
        if above.size == 0:
            break
        for j in above:  # x^T M x = 1: lambda -> lambda / (1 + alpha) with Mx Mx^T alpha
            x = X[:, j] / math.sqrt(float(X[:, j] @ (M @ X[:, j])))
            alpha = w[j] ** 2 / target2 - 1.0
            u = M @ x
            u[np.abs(u) < 1e-13 * np.abs(u).max()] = 0.0  # the mode's boundary support
            nz = np.flatnonzero(u)
            M = (M + sp.csr_matrix((alpha * np.outer(u[nz], u[nz]).ravel(),
                                    (np.repeat(nz, nz.size), np.tile(nz, nz.size))),
                                   shape=M.shape)).tocsr()
            total += 1
    return replace(pen, M=M, removal_note=f"{total} boundary modes' mass raised to the "
                                          f"lattice's top ({rounds} rounds)")
