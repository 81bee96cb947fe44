"""Stiffness and mass of a finite patch, sparse: the one assembly of the bar and the strip.

The bar (c = 1): :math:`K = G^{11}`, :math:`M = M_x`, with the 1D Gram matrices
:math:`G^{ab}_{ij} = \\int N^{(a)}_i N^{(b)}_j dx` of the B-splines along x and the rule's
mass :math:`M_x` (:mod:`dispersion.discretization.finite_mesh.direction_mass`). The strip
:math:`[0, L] \\times [-H, H]` (H = 1, :math:`\\mu = \\rho = 1`, plane strain): on a rectangle
with a constant material every matrix is a sum of Kronecker products of the x-Gram matrices
and the thickness matrices :math:`Y^{ab}` of the plate patch
(:func:`dispersion.symbolic.plate.plate_patch`, x-exact model),

.. math::

    K_{xx} = (\\lambda + 2\\mu) G^{11} \\otimes Y^{00} + \\mu G^{00} \\otimes Y^{11}, \\quad
    K_{yy} = (\\lambda + 2\\mu) G^{00} \\otimes Y^{11} + \\mu G^{11} \\otimes Y^{00},

    K_{xy} = \\lambda G^{10} \\otimes Y^{01} + \\mu G^{01} \\otimes Y^{10}, \\qquad
    M = M_x \\otimes M_y ,

the mass being the rule's x-direction rule along the strip and the rule itself through the
thickness (with the redistribution of the singular rules), the tensor product the plate patch
of the dispersion analysis uses. DOFs are interleaved, ``d * point + c`` (d = 1 bar, 2 strip;
``point = i_x * n + j_y``), so the scalar mass acts on both components at once. Periodic ends
wrap the connectivity (N functions, the lattice of N cells); a mapped strip is assembled by
quadrature on its NURBS geometry (:mod:`dispersion.discretization.finite_mesh.mapped_assembly`).

>>> from dispersion.discretization.finite_mesh.finite_patch import finite_bar, finite_strip
>>> m = assemble(finite_bar(2, 10, mass="lumped"))
>>> m.K.shape, round(float(m.mass.sum()), 12)                 # rho * length
((12, 12), 1.0)
>>> s = assemble(finite_strip(2, 6, n=4))
>>> s.K.shape == (2 * s.patch.n_points,) * 2, round(float(s.mass.sum()), 9) == round(2 * s.patch.length, 9)
(True, True)

References
----------
T. J. R. Hughes, J. A. Cottrell, Y. Bazilevs, "Isogeometric analysis", CMAME 194 (2005)
4135-4195. L. Gao, V. M. Calo, "Fast isogeometric solvers for explicit dynamics", CMAME 274
(2014) 19-41 (Kronecker structure of tensor-product matrices). Paper eqs (1)-(4).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from dispersion.discretization.finite_mesh.finite_matrices import FiniteMatrices
from dispersion.errors import InputError

__all__ = ["FiniteMatrices", "assemble", "x_basis", "explicit_step", "check_rule",
           "KNOWN_STATES", "BASES"]

#: Stated properties of a mass rule the finite patch knows how to assemble (anything else a
#: rule states is refused with its name: the assembly would not know what it asks for).
KNOWN_STATES = ("symmetric", "psd", "translational", "diagonal", "zero_rows")
#: The discrete spaces assembled: smooth B-splines, and C0 Lagrange elements in the nodal GLL
#: basis (:mod:`dispersion.splines.lagrange_space`) for rules with that basis.
BASES = ("bspline", "lagrange")


def explicit_step(rule) -> tuple[str, str]:
    """``(stiffness, mass)``: how the rule's explicit step applies stiffness and inverse mass.

    Stated by the rule (``MassRule.explicit_cost`` where the registry carries one: stiffness
    ``"sparse"``, ``"banded-wide"`` or ``"dense"``; mass ``"diagonal"``, ``"banded"`` or
    ``"solve"``), else read off its stated properties: a diagonal mass divides, any other
    is solved with.

    >>> from dispersion.mass_rules.mass_rule import get_rule
    >>> explicit_step(get_rule("hrz")), explicit_step(get_rule("consistent"))
    (('sparse', 'diagonal'), ('sparse', 'solve'))
    """
    cost = getattr(rule, "explicit_cost", None)
    if cost is not None:
        return str(cost.stiffness), str(cost.mass)
    return "sparse", ("diagonal" if rule.states.diagonal else "solve")


def check_rule(rule, what: str = "the finite patch") -> None:
    """Refuse (InputError, with the reason) a rule the assembly cannot build: unknown stated
    properties, a non-symmetric mass, a basis or an explicit step it does not build."""
    states = rule.states.as_dict()
    unknown = {k: v for k, v in states.items() if k not in KNOWN_STATES}
    if unknown:
        raise InputError(f"mass rule {rule.name!r} states {unknown}, which {what} does not "
                         "handle")
    if not states.get("symmetric", True):
        raise InputError(f"mass rule {rule.name!r} is not symmetric: the explicit loop and its "
                         "energy and critical step assume a symmetric mass")
    basis = getattr(rule, "basis", "bspline")
    if basis not in BASES:
        raise InputError(f"mass rule {rule.name!r} has the basis {basis!r}; {what} builds "
                         f"{', '.join(BASES)}")
    stiffness, mass = explicit_step(rule)
    if stiffness not in ("sparse", "dense") or mass not in ("diagonal", "banded", "solve"):
        raise InputError(f"mass rule {rule.name!r}: its explicit step applies a {stiffness} "
                         f"stiffness and a {mass} inverse mass (its Petrov-Galerkin operators); "
                         f"{what} assembles the Galerkin stiffness and the sparse, banded or "
                         "diagonal inverse masses only (its Galerkin form has the same solution)")
    if getattr(rule, "x_stiffness", None) is not None and mass != "banded":
        raise InputError(f"mass rule {rule.name!r} multiplies the x-stiffness by a factor "
                         f"{what} does not assemble")


@dataclass(frozen=True)
class _Knots:
    """What :class:`~dispersion.splines.bspline.SplineBasis1D` reads of a knot vector."""

    p: int
    knots: tuple
    n: int


def x_basis(patch):
    """The basis along x: open B-splines on the patch's knots, periodic B-splines (the
    cardinal pieces, connectivity wrapped) or C0 Lagrange elements."""
    from dispersion.splines.bspline import SplineBasis1D

    p, N, L = patch.p, patch.n_elements, patch.length
    if patch.rule.basis == "lagrange":
        from dispersion.splines.lagrange_space import NodalSpace1D

        return NodalSpace1D(p, N, 0.0, L, periodic=patch.periodic)
    if patch.periodic:
        long = SplineBasis1D.uniform(p, 2 * p + 1, 0.0, (2 * p + 1) * L / N)
        e = np.arange(N)
        spans = np.column_stack([e * L / N, (e + 1) * L / N])
        active = (e[:, None] + np.arange(p + 1)) % N
        C = np.repeat(long.C[p:p + 1], N, axis=0)  # every cell: the cardinal pieces
        return SplineBasis1D(_Knots(p, (), N), spans, active, C)
    if patch.knots == "uniform":
        return SplineBasis1D.uniform(p, N, 0.0, L)
    return SplineBasis1D.from_float_knots(_Knots(p, tuple(patch.float_knots()), N + p))


def _grams(basis, exact_x: bool, keys) -> dict:
    """The x-Gram matrices: the Lagrange space's own; B-splines summed element by element
    (``exact_x``: point by point, the order of summation the simulation's strip always had)."""
    if hasattr(basis, "grams"):
        return basis.grams()
    from dispersion.discretization.finite_mesh.direction_mass import element_grams, grams

    return grams(basis) if exact_x else element_grams(basis, keys)


def _x_rule(patch):
    """The rule along x: the strip's x-direction rule (as the Bloch patch), the bar's own rule
    (its singular rules redistribute at the free ends)."""
    from dispersion.mass_rules.mass_rule import get_rule

    rule = patch.rule
    if patch.model == "strip" or rule.redistributes:
        return get_rule(rule.x_rule)
    return rule


def _exact_graded(rule, patch, inverse: bool) -> sp.csr_matrix:
    """A rule outside the float ones on graded knots: built exactly on the rational knots."""
    import sympy

    from dispersion.discretization.finite_mesh.direction_mass import MAX_EXACT_ELEMENTS
    from dispersion.splines.bspline import KnotVector

    if patch.n_elements > MAX_EXACT_ELEMENTS:
        raise InputError(f"mass rule {rule.name!r} on {patch.knots} knots is built exactly, on "
                         f"at most {MAX_EXACT_ELEMENTS} elements; got {patch.n_elements}")
    kv = KnotVector(tuple(sympy.Rational(k.numerator, k.denominator)
                          for k in patch.exact_knots()), patch.p)
    if inverse:
        from dispersion.mass_rules.approximate_dual import approximate_dual_matrix

        A = approximate_dual_matrix(kv)
    else:
        import warnings

        from dispersion.mass_rules.mass_rule import gram_space, mass_matrix

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            A = mass_matrix(rule, gram_space(kv))
    return sp.csr_matrix(np.array(A.tolist(), dtype=float))


def _mass_x(patch, basis, G, mass_kind: str, exact_x: bool = False):
    """``(M_x, S_x)``: the mass along x, or its banded inverse (the other None)."""
    from dispersion.discretization.finite_mesh import direction_mass as dm

    rule = patch.rule
    p, N, h = patch.p, patch.n_elements, patch.element_length
    if rule.basis == "lagrange":
        return (basis.lumped() if mass_kind == "diagonal" else G["00"]), None
    x_rule = _x_rule(patch)
    inverse = mass_kind == "banded"
    if patch.periodic:
        A = dm.periodic_x_mass(x_rule, p, N, h, inverse=inverse)
    elif x_rule.name in dm.FLOAT_RULES and not inverse and not (
            exact_x and patch.knots == "uniform") and _registered(x_rule):
        A = dm.float_x_mass(x_rule, basis, G=G if "11" in G and "00" in G else None)
    elif patch.knots == "uniform":
        A = dm.x_mass(x_rule, p, N, h, inverse=inverse)
    else:
        A = _exact_graded(x_rule, patch, inverse)
    if rule.redistributes and patch.model == "bar":
        A = _bar_singular(patch, A)
    return (None, A) if inverse else (A, None)


def _registered(rule) -> bool:
    from dispersion.mass_rules.mass_rule import RULES

    return RULES.get(rule.name) is rule


def _bar_singular(patch, M: sp.csr_matrix) -> sp.csr_matrix:
    """The bar's singular mass: the free ends are its contact set (paper eq 1), the end
    function's mass sent inward with the paper's weights (gamma_s to the second neighbour)."""
    from dispersion.mass_rules.mass import contact_weights

    free = [i for i, e in zip((0, patch.n_x - 1), patch.ends) if e == "free"]
    if patch.periodic or not free:
        raise InputError(f"mass rule {patch.rule.name!r} redistributes at a free end; this bar "
                         "has none")
    n = patch.n_x
    rows, cols, vals = list(range(n)), list(range(n)), [1.0] * n
    for end in free:
        side = "bottom" if end == 0 else "top"
        for c, ws in contact_weights(n, side, patch.gamma_s).items():
            vals[c] = 0.0
            for j, w in ws.items():
                rows.append(c)
                cols.append(j)
                vals.append(float(w))
    R = sp.csr_matrix((vals, (rows, cols)), shape=(n, n))
    Mm = (R.T @ M @ R).tocsr()
    if patch.rule.states.diagonal:  # the lumped form: its row sums (eq 1 right)
        Mm = sp.diags(np.asarray(Mm.sum(axis=1)).ravel()).tocsr()
    Mm.eliminate_zeros()
    return Mm


def _thickness(patch, rule, mass_kind):
    """Thickness matrices Y and the rule's thickness mass M_y (floats), and the basis."""
    import sympy

    from dispersion.splines.bspline import SplineBasis1D
    from dispersion.symbolic.plate import plate_patch

    if getattr(rule, "basis", "bspline") == "lagrange":
        from dispersion.splines.lagrange_space import NodalSpace1D

        space = NodalSpace1D(patch.p, (patch.n - 1) // patch.p, -1.0, 1.0)
        Y = {k: v.toarray() for k, v in space.grams().items()}
        My = space.lumped().toarray() if mass_kind == "diagonal" else Y["00"]
        return Y, My, space
    pp = plate_patch(patch.p, patch.n, "x-exact", None, rule.name, patch.contact,
                     sympy.Rational(repr(patch.gamma_s)))
    Y = {k: np.array(v.tolist(), dtype=float) for k, v in pp.Y.items()}
    basis = SplineBasis1D.uniform(patch.p, patch.n - patch.p, -1.0, 1.0)
    return Y, np.array(pp.My.tolist(), dtype=float), basis


def _massless(M: sp.csr_matrix) -> np.ndarray:
    rowmax = np.asarray(abs(M).max(axis=1).todense()).ravel()
    return np.flatnonzero(rowmax <= 1e-14 * rowmax.max())


def assemble(patch, *, exact_x: bool = False) -> FiniteMatrices:
    """Assemble the stiffness and mass of the :class:`FinitePatch` ``patch`` (no boundary
    condition applied: :func:`dispersion.discretization.finite_mesh.mesh_pencil.mesh_pencil` removes the
    DOFs of fixed ends).

    The local rules (:data:`~dispersion.discretization.finite_mesh.direction_mass.FLOAT_RULES`) are
    built in floats (their matrices to a few units of rounding); ``exact_x`` builds them on
    uniform knots from the exact rule instead, each entry rounded once (seconds of sympy a
    rule and degree: the simulation's strip keeps the bits it always had)."""
    rule = patch.rule
    check_rule(rule)
    if patch.model == "strip" and rule.x_rule != rule.name:
        from dispersion.mass_rules.mass_rule import get_rule

        check_rule(get_rule(rule.x_rule))
    stiffness, mass_kind = explicit_step(rule)
    if patch.mapped:
        from dispersion.discretization.finite_mesh.mapped_assembly import assemble_mapped

        return assemble_mapped(patch, (stiffness, mass_kind))
    if rule.redistributes and patch.model == "bar" and mass_kind == "banded":
        raise InputError(f"mass rule {rule.name!r}: no banded inverse with a contact set")
    basis_x = x_basis(patch)
    G = _grams(basis_x, exact_x, ("00", "11") if patch.model == "bar" else
               ("00", "01", "10", "11"))
    Mx, Sx = _mass_x(patch, basis_x, G, mass_kind, exact_x)
    if patch.model == "bar":
        K = G["11"].tocsr()
        K.sum_duplicates()
        K.sort_indices()
        M = None if Mx is None else Mx.tocsr()
        massless = np.zeros(0, dtype=int) if M is None else _massless(M)
        return FiniteMatrices(patch, rule, K, M, massless, basis_x, None,
                              (stiffness, mass_kind), Sx)
    Y, My, basis_y = _thickness(patch, rule, mass_kind)
    from dispersion.symbolic.plate import lame

    mat = lame(patch.nu)
    lam, mu, l2m = float(mat["L"]), float(mat["M"]), float(mat["L2M"])
    Ys = {k: sp.csr_matrix(v) for k, v in Y.items()}
    kron = sp.kron
    Kxx = l2m * kron(G["11"], Ys["00"]) + mu * kron(G["00"], Ys["11"])
    Kyy = l2m * kron(G["00"], Ys["11"]) + mu * kron(G["11"], Ys["00"])
    Kxy = lam * kron(G["10"], Ys["01"]) + mu * kron(G["01"], Ys["10"])
    E = [[sp.csr_matrix(([1.0], ([a], [c])), shape=(2, 2)) for c in range(2)] for a in range(2)]
    K = (kron(Kxx, E[0][0]) + kron(Kxy, E[0][1]) + kron(Kxy.T.tocsr(), E[1][0])
         + kron(Kyy, E[1][1])).tocsr()
    K.sum_duplicates()
    K.sort_indices()
    if Sx is not None:  # the rule's inverse mass is banded and known: S_x (x) M_y^-1
        inverse = sp.kron(Sx, sp.csr_matrix(np.linalg.inv(My)), format="csr")
        return FiniteMatrices(patch, rule, K, None, np.zeros(0, dtype=int), basis_x, basis_y,
                              (stiffness, mass_kind), inverse, {**Y, "My": My})
    M = sp.kron(Mx, sp.csr_matrix(My), format="csr")
    M.eliminate_zeros()
    return FiniteMatrices(patch, rule, K, M, _massless(M), basis_x, basis_y,
                          (stiffness, mass_kind), None, {**Y, "My": My})
