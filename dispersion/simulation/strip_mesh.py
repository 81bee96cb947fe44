"""Stiffness, mass, load and stations of the strip: a tensor-product B-spline patch.

The strip :math:`[0, L] \\times [-H, H]` (H = 1, :math:`\\mu = \\rho = 1`, plane strain) carries
open uniform B-splines of degree p along x (:math:`N_x` elements of length b) and through the
thickness (:math:`n` control points, the thickness space of the plate patch,
:func:`dispersion.symbolic.plate.plate_patch` with the x-exact model). On a rectangle with a
constant material every matrix is a sum of Kronecker products of 1D Gram matrices
:math:`G^{ab}_{ij} = \\int N^{(a)}_i N^{(b)}_j dx` (x) and :math:`Y^{ab}` (y, the plate's
thickness matrices):

.. math::

    K_{xx} = (\\lambda + 2\\mu) G^{11} \\otimes Y^{00} + \\mu G^{00} \\otimes Y^{11}, \\quad
    K_{yy} = (\\lambda + 2\\mu) G^{00} \\otimes Y^{11} + \\mu G^{11} \\otimes Y^{00},

    K_{xy} = \\lambda G^{10} \\otimes Y^{01} + \\mu G^{01} \\otimes Y^{10}, \\qquad
    M = M_x \\otimes M_y ,

the mass being the rule's: its x-direction rule :math:`M_x` along the strip and the rule
itself through the thickness :math:`M_y` (with the redistribution of the singular rules), the
tensor product the plate patch of the dispersion analysis uses. DOFs are interleaved:
``2 * (i_x * n + j_y) + c`` for component c (0: x, 1: y), so the scalar mass solves both
components at once (``(n_points, 2)`` right-hand sides).

:math:`M_x` on :math:`N_x` elements comes from the registry (:func:`mass_matrix`) exactly on
short meshes and is extended by its interior row: the rule is asked on meshes of
:math:`m_0` and :math:`m_0 + 1, m_0 + 2` elements, and the extension of the first must give
the others exactly, else the rule is refused for the strip (its mass is not banded and
translation invariant inside: an exact build on thousands of elements is beyond reach).

The load is a traction on the end x = 0 with the burst's time history: along x over the
thickness (S0, symmetric) or along y (A0, antisymmetric), its nodal values
:math:`\\int N_j dy`. Stations (the plan's stations, then its phase stations) read u_x (S0)
or u_y (A0) on the mid-plane y = 0.

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> mesh = strip_mesh(plan_strip(Strip(p=2, mass="consistent", travel=1, stations=2,
...                                    elements_per_wavelength=3)))
>>> mesh.K.shape == (2 * mesh.n_points, 2 * mesh.n_points), mesh.massless.size
(True, 0)
>>> round(float(mesh.mass.sum()), 9) == round(2 * mesh.plan.length, 9)   # rho * area
True

References
----------
T. J. R. Hughes, J. A. Cottrell, Y. Bazilevs, "Isogeometric analysis", CMAME 194 (2005)
4135-4195. L. Gao, V. M. Calo, "Fast isogeometric solvers for explicit dynamics", CMAME 274
(2014) 19-41 (Kronecker structure of tensor-product matrices). Paper eqs (1)-(4).
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache

import numpy as np
import scipy.sparse as sp

from dispersion.errors import InputError

__all__ = ["StripMesh", "strip_mesh", "spline_grams", "x_mass", "check_rule", "explicit_step",
           "KNOWN_STATES", "BASES"]

#: Stated properties of a mass rule the simulation knows how to run (anything else a rule
#: states is refused with its name: the simulation would not know what it asks for).
KNOWN_STATES = ("symmetric", "psd", "translational", "diagonal", "zero_rows")
#: The discrete spaces the strip builds: smooth B-splines, and C0 Lagrange elements in the
#: nodal GLL basis (:mod:`dispersion.simulation.lagrange_space`) for rules with that basis.
BASES = ("bspline", "lagrange")


@dataclass(frozen=True, repr=False)
class StripMesh:
    """The assembled strip: ``K`` (2N x 2N CSR), the scalar mass ``mass`` (N x N CSR, N
    points; None where only its banded inverse ``mass_inverse`` is known), the ``massless``
    points (zero rows), the load (``load_dofs``, ``load_values``: unit traction) and the
    stations (``station_dofs``, ``station_weights``, one row each)."""

    plan: object
    rule: object
    K: sp.csr_matrix
    mass: sp.csr_matrix
    massless: np.ndarray
    load_dofs: np.ndarray
    load_values: np.ndarray
    station_dofs: np.ndarray
    station_weights: np.ndarray
    #: ``(stiffness, mass)`` of the rule's explicit step (:func:`explicit_step`).
    step_kind: tuple[str, str] = ("sparse", "solve")
    #: The banded inverse of the mass (a rule whose inverse mass is banded: no ``mass``).
    mass_inverse: sp.csr_matrix | None = None

    @property
    def n_points(self) -> int:
        return self.K.shape[0] // 2

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]

    def __repr__(self) -> str:
        return (f"StripMesh({self.plan.strip.label()}: {self.n_dofs} DOFs, "
                f"{self.massless.size} massless points)")


def spline_grams(basis) -> dict[str, sp.csr_matrix]:
    """``{"00", "01", "10", "11"}``: :math:`\\int N^{(a)}_i N^{(b)}_j dx` of a
    :class:`~dispersion.symbolic.bspline.SplineBasis1D`, Gauss-Legendre with p + 1 points per
    span (exact: the products have degree at most 2p)."""
    p = basis.kv.p
    g, w = np.polynomial.legendre.leggauss(p + 1)
    a, b = basis.spans[:, :1], basis.spans[:, 1:]
    x = (a + (b - a) * (g + 1) / 2).ravel()
    wx = ((b - a) / 2 * w).ravel()
    act, N0 = basis.evaluate(x, 0)
    _, N1 = basis.evaluate(x, 1)
    n = basis.kv.n
    rows = np.repeat(act, p + 1, axis=1).ravel()
    cols = np.tile(act, (1, p + 1)).ravel()
    out = {}
    for key, (A, B) in {"00": (N0, N0), "01": (N0, N1), "10": (N1, N0), "11": (N1, N1)}.items():
        vals = (wx[:, None, None] * A[:, :, None] * B[:, None, :]).ravel()
        out[key] = sp.csr_matrix((vals, (rows, cols)), shape=(n, n))
    return out


@lru_cache(maxsize=128)
def _exact_x_mass(rule, p: int, m: int, inverse: bool = False) -> tuple:
    """The rule's matrix on ``m`` unit elements (or its inverse), exact, as rows of Fractions."""
    import warnings

    import sympy

    from dispersion.splines.bspline import open_knot_vector
    from dispersion.mass_rules.mass_rule import gram_space, mass_matrix

    with warnings.catch_warnings():  # warned about once, by the thickness build of the rule
        warnings.simplefilter("ignore")
        A = mass_matrix(rule, gram_space(open_knot_vector(p, m, 0, m)))
    if inverse:
        from sympy.polys.matrices import DomainMatrix

        A = DomainMatrix.from_Matrix(sympy.Matrix(A)).to_field().inv().to_Matrix()
    return tuple(tuple(Fraction(str(v)) for v in row) for row in A.tolist())


def _extend(A: tuple, n: int):
    """Triplets of the extension of the square ``A`` to size ``n`` by its middle row."""
    n0 = len(A)
    c = n0 // 2
    nz = [j - c for j in range(n0) if A[c][j] != 0]
    w = max((abs(L) for L in nz), default=0)
    shift = n - n0
    rows, cols, vals = [], [], []
    for i in range(c):
        for j in range(n0):
            if A[i][j] != 0 and j < c + w + 1:
                rows.append(i)
                cols.append(j)
                vals.append(A[i][j])
    for i in range(c, c + shift + 1):
        for L in nz:
            rows.append(i)
            cols.append(i + L)
            vals.append(A[c][c + L])
    for i in range(c + 1, n0):
        for j in range(n0):
            if A[i][j] != 0 and j > c - w - 1:
                rows.append(i + shift)
                cols.append(j + shift)
                vals.append(A[i][j])
    return rows, cols, vals, w


def _banded_rule(rule, p: int, inverse: bool = False) -> int:
    """The short mesh whose matrix extends exactly to the next two; InputError if it does not."""
    name = rule.name + (" (inverse mass)" if inverse else "")
    m0 = 4 * p + 3
    base = _exact_x_mass(rule, p, m0, inverse)
    _, _, _, w = _extend(base, len(base))
    if 2 * w + 2 > len(base) // 2:
        raise InputError(f"mass rule {name!r}: its x-mass on {m0} elements has a bandwidth of "
                         f"{w}; the strip needs a banded mass (not dense) along x")
    for extra in (1, 2):
        target = _exact_x_mass(rule, p, m0 + extra, inverse)
        rows, cols, vals, _ = _extend(base, len(target))
        built = {(i, j): v for i, j, v in zip(rows, cols, vals)}
        want = {(i, j): v for i, row in enumerate(target) for j, v in enumerate(row) if v != 0}
        if built != want:
            raise InputError(f"mass rule {name!r}: its x-mass on {m0 + extra} elements is not "
                             f"the {m0}-element one with more interior rows (not banded and "
                             "translation invariant inside), so the strip cannot build it")
    return m0


def x_mass(rule, p: int, n_elements: int, b: float, inverse: bool = False) -> sp.csr_matrix:
    """The rule (name or :class:`~dispersion.symbolic.mass_rule.MassRule`) along x on
    ``n_elements`` elements of length ``b`` (float CSR); with ``inverse`` its inverse, which
    must then be the banded one (a rule that states a banded inverse mass).

    >>> float(x_mass("lumped", 2, 40, 0.5).sum())        # rho * length
    20.0
    """
    from dispersion.mass_rules.mass_rule import get_rule

    rule = get_rule(rule)
    scale = 1.0 / b if inverse else b
    if n_elements <= 4 * p + 5:  # small enough to build exactly: no extension needed
        A = _exact_x_mass(rule, p, n_elements, inverse)
        dense = np.array([[float(v) for v in row] for row in A])
        return sp.csr_matrix(scale * dense)
    m0 = _banded_rule(rule, p, inverse)
    rows, cols, vals, _ = _extend(_exact_x_mass(rule, p, m0, inverse), n_elements + p)
    n = n_elements + p
    return sp.csr_matrix((scale * np.array([float(v) for v in vals]), (rows, cols)),
                         shape=(n, n))


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


def check_rule(rule) -> None:
    """Refuse (InputError, with the reason) a rule the strip cannot run: unknown stated
    properties, a non-symmetric mass, a basis or an explicit step it does not build."""
    states = rule.states.as_dict()
    unknown = {k: v for k, v in states.items() if k not in KNOWN_STATES}
    if unknown:
        raise InputError(f"mass rule {rule.name!r} states {unknown}, which the wave simulation "
                         "does not handle")
    if not states.get("symmetric", True):
        raise InputError(f"mass rule {rule.name!r} is not symmetric: the explicit loop and its "
                         "energy and critical step assume a symmetric mass")
    basis = getattr(rule, "basis", "bspline")
    if basis not in BASES:
        raise InputError(f"mass rule {rule.name!r} has the basis {basis!r}; the strip builds "
                         f"{', '.join(BASES)}")
    stiffness, mass = explicit_step(rule)
    if stiffness not in ("sparse", "dense") or mass not in ("diagonal", "banded", "solve"):
        raise InputError(f"mass rule {rule.name!r}: its explicit step applies a {stiffness} "
                         f"stiffness and a {mass} inverse mass (its Petrov-Galerkin operators); "
                         "the strip assembles the Galerkin stiffness and the sparse, banded or "
                         "diagonal inverse masses only (its Galerkin form has the same solution)")
    if getattr(rule, "x_stiffness", None) is not None and mass != "banded":
        raise InputError(f"mass rule {rule.name!r} multiplies the x-stiffness by a factor the "
                         "strip does not assemble")


def _thickness(plan, rule, mass_kind):
    """Thickness matrices Y and the rule's thickness mass M_y (floats), and the basis."""
    import sympy

    from dispersion.splines.bspline import SplineBasis1D
    from dispersion.symbolic.plate import plate_patch

    s = plan.strip
    if getattr(rule, "basis", "bspline") == "lagrange":
        from dispersion.simulation.lagrange_space import NodalSpace1D

        space = NodalSpace1D(s.p, plan.n_elements_y, -1.0, 1.0)
        Y = {k: v.toarray() for k, v in space.grams().items()}
        My = space.lumped().toarray() if mass_kind == "diagonal" else Y["00"]
        return Y, My, space
    patch = plate_patch(s.p, plan.n, "x-exact", None, s.mass, s.contact,
                        sympy.Rational(repr(s.gamma_s)))
    Y = {k: np.array(v.tolist(), dtype=float) for k, v in patch.Y.items()}
    basis = SplineBasis1D.uniform(s.p, plan.n - s.p, -1.0, 1.0)
    return Y, np.array(patch.My.tolist(), dtype=float), basis


def strip_mesh(plan) -> StripMesh:
    """Assemble the strip of ``plan`` (:func:`dispersion.simulation.strip.plan_strip`)."""
    from dispersion.splines.bspline import SplineBasis1D
    from dispersion.mass_rules.mass_rule import get_rule
    from dispersion.symbolic.plate import lame

    s = plan.strip
    rule = get_rule(s.mass)
    check_rule(rule)
    if rule.x_rule != rule.name:
        check_rule(get_rule(rule.x_rule))
    stiffness, mass_kind = explicit_step(rule)
    Y, My, basis_y = _thickness(plan, rule, mass_kind)
    if getattr(rule, "basis", "bspline") == "lagrange":
        from dispersion.simulation.lagrange_space import NodalSpace1D

        basis_x = NodalSpace1D(s.p, plan.n_elements_x, 0.0, plan.length)
        G = basis_x.grams()
        Mx = basis_x.lumped() if mass_kind == "diagonal" else G["00"]
    else:
        basis_x = SplineBasis1D.uniform(s.p, plan.n_elements_x, 0.0, plan.length)
        G = spline_grams(basis_x)
        x_rule = get_rule(rule.x_rule)
        Mx = None if mass_kind == "banded" else x_mass(x_rule, s.p, plan.n_elements_x,
                                                          plan.element_length)
    mat = lame(plan.nu)
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
    n = plan.n
    inverse = None
    if mass_kind == "banded":  # the rule's inverse mass is banded and known: S_x (x) M_y^-1
        Sx = x_mass(get_rule(rule.x_rule), s.p, plan.n_elements_x, plan.element_length,
                    inverse=True)
        inverse = sp.kron(Sx, sp.csr_matrix(np.linalg.inv(My)), format="csr")
        M = None
        massless = np.zeros(0, dtype=int)
    else:
        M = sp.kron(Mx, sp.csr_matrix(My), format="csr")
        M.eliminate_zeros()
        rowmax = np.asarray(abs(M).max(axis=1).todense()).ravel()
        massless = np.flatnonzero(rowmax <= 1e-14 * rowmax.max())
    comp = 0 if s.kind == "S" else 1
    load_dofs = 2 * np.arange(n) + comp  # the column x = 0: i_x = 0
    load_values = Y["00"].sum(axis=1)  # int N_j dy (partition of unity)
    where = np.asarray(plan.stations + plan.phase_stations)  # the stations, then the phase ones
    ax, Nx = basis_x.evaluate(where)
    ay, Ny = basis_y.evaluate(np.zeros(1))
    station_dofs = 2 * (ax[:, :, None] * n + ay[0][None, None, :]).reshape(where.size, -1) + comp
    station_weights = (Nx[:, :, None] * Ny[0][None, None, :]).reshape(where.size, -1)
    return StripMesh(plan, rule, K, M, massless, load_dofs, load_values, station_dofs,
                     station_weights, (stiffness, mass_kind), inverse)
