"""The mass of a rule along one direction of a mesh: open uniform, periodic or graded knots.

A rule of the registry (:mod:`dispersion.mass_rules.mass_rule`) builds its matrix exactly on a
knot vector. Along x of a finite patch the mesh may hold thousands of elements, too many for
exact arithmetic, so the matrix is assembled in floats by one of three routes:

* **open uniform knots**: the rule is asked on meshes of :math:`m_0 = 4p + 3` and
  :math:`m_0 + 1, m_0 + 2` unit elements, exactly, and its matrix on N elements is the first
  one extended by its middle row; the extension must give the two others exactly, else the
  rule is refused (its mass is not banded and translation invariant inside). Short meshes
  (N <= 4p + 5) are built exactly as they are;
* **periodic uniform knots**: the circulant of the rule's Bloch row
  (:func:`~dispersion.mass_rules.mass_rule.x_mass_coefficients`), the lattice itself;
* **graded or perturbed knots**: the element-local rules (consistent, row-sum lumped, HRZ,
  nodal Lobatto and Greville quadratures) in floats from the float basis
  (:meth:`~dispersion.splines.bspline.SplineBasis1D.from_float_knots`); any other rule
  exactly on the rational knots, for at most :data:`MAX_EXACT_ELEMENTS` elements.

A rule whose *inverse* mass is the banded matrix (approximate-dual lumping: the Galerkin mass
:math:`S^{-1}` of Hiemstra et al. 2025) gives that inverse instead (``inverse=True``).

>>> float(x_mass("lumped", 2, 40, 0.5).sum())        # rho * length
20.0
>>> periodic_x_mass("consistent", 1, 4, 1.0).toarray()[0].tolist()   # 2/3 and 1/6 around
[0.6666666666666666, 0.16666666666666666, 0.0, 0.16666666666666666]

References
----------
J. A. Cottrell, A. Reali, Y. Bazilevs, T. J. R. Hughes, CMAME 195 (2006) 5257-5296.
R. R. Hiemstra, T.-H. Nguyen, S. Eisentraeger, W. Dornisch, D. Schillinger, Comput. Mech. 76
(2025) 205-226 (the customized mass and its banded inverse).
"""
from __future__ import annotations

from fractions import Fraction
from functools import lru_cache

import numpy as np
import scipy.sparse as sp

from dispersion.errors import InputError

__all__ = ["x_mass", "periodic_x_mass", "float_x_mass", "grams", "element_grams", "FLOAT_RULES",
           "MAX_EXACT_ELEMENTS"]

#: The rules built in floats on any knots: each is local to an element or to a point set
#: (sms: the row-sum lumped mass plus beta h^2 int N'N'^T, h the largest element).
FLOAT_RULES = ("consistent", "lumped", "hrz", "nodal-lobatto", "nodal-greville", "sms")
#: Most elements of a graded mesh on which a rule outside :data:`FLOAT_RULES` is built
#: exactly (sympy). Rule: about a second; measured, the customized mass on 60 elements
#: of p = 2 takes 0.9 s and grows like N^3 (a dense inverse).
MAX_EXACT_ELEMENTS = 60


def element_grams(basis, keys=("00", "01", "10", "11")) -> dict[str, sp.csr_matrix]:
    """:func:`grams` summed element by element first (Gauss-Legendre, p + 1 points a span):
    the same matrices to rounding, (p + 1) times fewer triplets to assemble."""
    p = basis.kv.p
    g, w = np.polynomial.legendre.leggauss(p + 1)
    a, b = basis.spans[:, :1], basis.spans[:, 1:]
    x = (a + (b - a) * (g + 1) / 2).ravel()
    wx = (b - a) / 2 * w  # (n_el, q)
    n_el = basis.spans.shape[0]
    vals = {}
    for d in sorted({int(k[0]) for k in keys} | {int(k[1]) for k in keys}):
        _, N = basis.evaluate(x, d)
        vals[d] = N.reshape(n_el, p + 1, p + 1)  # (element, point, function)
    act = basis.active
    rows = np.repeat(act, p + 1, axis=1).ravel()
    cols = np.tile(act, (1, p + 1)).ravel()
    n = basis.kv.n
    out = {}
    for key in keys:
        Me = np.einsum("eq,eqi,eqj->eij", wx, vals[int(key[0])], vals[int(key[1])])
        out[key] = sp.csr_matrix((Me.ravel(), (rows, cols)), shape=(n, n))
    return out


def grams(basis) -> dict[str, sp.csr_matrix]:
    """``{"00", "01", "10", "11"}``: :math:`\\int N^{(a)}_i N^{(b)}_j dx` of a
    :class:`~dispersion.splines.bspline.SplineBasis1D`, Gauss-Legendre with p + 1 points per
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
    from dispersion.mass_rules.mass_rule import RULES, gram_space, mass_matrix

    # a registered rule's stated properties are the registry's to test (test_mass_rule,
    # test_lumping_rules); checking them again here costs seconds (interpolatory-nodal at
    # p = 4: 83 s, measured); a user's rule is checked every time
    check = RULES.get(rule.name) is not rule
    with warnings.catch_warnings():  # warned about once, by the thickness build of the rule
        warnings.simplefilter("ignore")
        A = mass_matrix(rule, gram_space(open_knot_vector(p, m, 0, m)), check=check)
    if inverse:
        from sympy.polys.matrices import DomainMatrix

        A = DomainMatrix.from_Matrix(sympy.Matrix(A)).to_field().inv().to_Matrix()
    rows = sympy.Matrix(A).tolist()  # sympy numbers (never text)
    if not all(isinstance(v, sympy.Rational) for row in rows for v in row):
        raise InputError(f"mass rule {rule.name!r}: its matrix on {m} elements of degree {p} "
                         "is not in rational numbers, so the mesh cannot extend it exactly")
    return tuple(tuple(Fraction(int(v.p), int(v.q)) for v in row) for row in rows)


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
                         f"{w}; the mesh needs a banded mass (not dense) along x")
    for extra in (1, 2):
        target = _exact_x_mass(rule, p, m0 + extra, inverse)
        rows, cols, vals, _ = _extend(base, len(target))
        built = {(i, j): v for i, j, v in zip(rows, cols, vals)}
        want = {(i, j): v for i, row in enumerate(target) for j, v in enumerate(row) if v != 0}
        if built != want:
            raise InputError(f"mass rule {name!r}: its x-mass on {m0 + extra} elements is not "
                             f"the {m0}-element one with more interior rows (not banded and "
                             "translation invariant inside), so the mesh cannot build it")
    return m0


def x_mass(rule, p: int, n_elements: int, b: float, inverse: bool = False) -> sp.csr_matrix:
    """The rule (name or :class:`~dispersion.mass_rules.mass_rule.MassRule`) on ``n_elements``
    open uniform elements of length ``b`` (float CSR); with ``inverse`` its inverse, which
    must then be the banded one (a rule that states a banded inverse mass)."""
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


def _circulant(row: dict, n: int, scale: float) -> sp.csr_matrix:
    """The n x n circulant with ``row[L]`` at offset L (offsets wrap around)."""
    rows, cols, vals = [], [], []
    i = np.arange(n)
    for L, v in row.items():
        rows.append(i)
        cols.append((i + int(L)) % n)
        vals.append(np.full(n, scale * float(v)))
    A = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(n, n))
    A.sum_duplicates()
    return A


def periodic_x_mass(rule, p: int, n_elements: int, b: float, inverse: bool = False
                    ) -> sp.csr_matrix:
    """The rule on ``n_elements`` periodic uniform elements of length ``b``: the circulant of
    its Bloch row (``inverse``: of its inverse, the rules with an x-stiffness factor whose
    mass row is 1, approximate-dual lumping).

    ``n_elements`` must be at least 2p + 1 (no function overlaps its own image)."""
    from dispersion.mass_rules.mass_rule import get_rule, x_mass_coefficients, x_stiffness_factor

    rule = get_rule(rule)
    if n_elements < 2 * p + 1:
        raise InputError(f"a periodic mesh of degree {p} needs at least {2 * p + 1} elements "
                         f"(2p + 1), got {n_elements}")
    row = dict(x_mass_coefficients(rule if rule.periodic is not None else rule.x_rule, p))
    if inverse:
        if row != {0: 1}:
            raise InputError(f"mass rule {rule.name!r}: a banded inverse mass is known only "
                             "for a unit mass row")
        return _circulant(dict(x_stiffness_factor(rule, p)), n_elements, 1.0 / b)
    return _circulant(row, n_elements, b)


def float_x_mass(rule, basis, *, G: dict | None = None) -> sp.csr_matrix:
    """A rule of :data:`FLOAT_RULES` on the float ``basis`` (any open knots), in floats
    (``G``: its Gram matrices ``"00"`` and ``"11"`` if already built)."""
    from dispersion.mass_rules.mass_rule import get_rule

    rule = get_rule(rule)
    name = rule.name
    p = basis.kv.p
    n = basis.kv.n
    if name in ("consistent", "lumped", "sms"):
        G = element_grams(basis, ("00", "11")) if G is None else G
        M = G["00"]
        if name == "consistent":
            return M
        lumped = sp.diags(np.asarray(M.sum(axis=1)).ravel()).tocsr()
        if name == "lumped":
            return lumped
        from dispersion.mass_rules.mass_scaling import SMS_BETA

        h = float(np.max(basis.spans[:, 1] - basis.spans[:, 0]))
        return (lumped + float(SMS_BETA) * h**2 * G["11"]).tocsr()
    if name == "hrz":
        g, w = np.polynomial.legendre.leggauss(p + 1)
        a, b = basis.spans[:, :1], basis.spans[:, 1:]
        x = (a + (b - a) * (g + 1) / 2)
        act, N = basis.evaluate(x.ravel())
        N = N.reshape(x.shape[0], p + 1, p + 1)  # (element, point, function)
        wx = (b - a) / 2 * w
        diag = np.einsum("eq,eqa->ea", wx, N ** 2)
        total = np.einsum("eq,eqa->e", wx, N)  # element mass: partition of unity
        d = np.bincount(basis.active.ravel(), (diag * (total / diag.sum(axis=1))[:, None]).ravel(),
                        minlength=n)
        return sp.diags(d).tocsr()
    if name == "nodal-lobatto":
        from dispersion.splines.spline_mass import lobatto_rule

        nodes, weights = lobatto_rule(p + 1)
        a, b = basis.spans[:, :1], basis.spans[:, 1:]
        x = (a + (b - a) * (np.asarray(nodes, float) + 1) / 2)
        wx = ((b - a) / 2 * np.asarray(weights, float)).ravel()
        act, N = basis.evaluate(x.ravel())
        return _outer_sum(act, N, wx, n)
    if name == "nodal-greville":
        knots = np.asarray(basis.kv.knots, dtype=float)
        g = np.array([knots[i + 1:i + p + 1].mean() for i in range(n)])
        weights = (knots[p + 1:p + 1 + n] - knots[:n]) / (p + 1)  # int N_i
        act, N = basis.evaluate(g)
        return _outer_sum(act, N, weights, n)
    raise InputError(f"mass rule {name!r} is built in floats on graded knots only for "
                     f"{', '.join(FLOAT_RULES)}")


def _outer_sum(act: np.ndarray, N: np.ndarray, w: np.ndarray, n: int) -> sp.csr_matrix:
    """:math:`\\sum_q w_q N(x_q) N(x_q)^T` from the active functions at each point."""
    k = act.shape[1]
    rows = np.repeat(act, k, axis=1).ravel()
    cols = np.tile(act, (1, k)).ravel()
    vals = (w[:, None, None] * N[:, :, None] * N[:, None, :]).ravel()
    A = sp.csr_matrix((vals, (rows, cols)), shape=(n, n))
    A.sum_duplicates()
    return A
