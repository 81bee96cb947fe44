"""Mass rules: one registry of the ways to build a mass matrix, each with its stated properties.

A *mass rule* turns the consistent Gram matrix :math:`\\mathbf M` of a B-spline space (and,
for the singular rules, a redistribution :math:`\\mathbf R`, :mod:`dispersion.symbolic.mass`)
into the mass matrix an analysis uses:

=====================  =================================================================
``consistent``         :math:`\\mathbf M`
``lumped``             row sums, :math:`M^L_{ii} = \\sum_j M_{ij}`
``hrz``                per element :math:`M^e_{ii} \\, m_e / \\operatorname{tr} \\mathbf M^e`
                       (the diagonal scaled to the element mass :math:`m_e = \\sum_{ij} M^e_{ij}`),
                       assembled (Hinton, Rock, Zienkiewicz 1976)
``nodal-greville``     :math:`\\sum_q w_q \\mathbf N(g_q) \\mathbf N(g_q)^T`, points at the Greville
                       abscissae :math:`g_q`, weights :math:`w_q = \\int N_q` (exact for linear f)
``nodal-lobatto``      per element, the :math:`p + 1` Gauss-Lobatto points (exact to degree
                       :math:`2p - 1`); for p = 1 this is the row-sum lumped mass
``singular``           :math:`\\mathbf R^T \\mathbf M \\mathbf R` (paper eq 1, left)
``singular-lumped``    row sums of :math:`\\mathbf R^T \\mathbf M \\mathbf R` (paper eq 1, right)
=====================  =================================================================

and user rules: :func:`user_rule` (a Python callable of the :class:`MassSpace`) or
:func:`rule_from_toml` (a table of redistribution weights). Each rule *states* its properties
(:class:`MassProperties`); :func:`mass_matrix` builds the matrix and checks them on the space
(:func:`check_mass`): a rule whose matrix contradicts what it states, is not symmetric, or has
massless directions that are not zero rows (the explicit scheme condenses zero rows only) is
refused with the reason; an indefinite matrix or lost translational mass is warned about.

Along x of the Bloch plate (no contact there) a rule acts through :attr:`MassRule.x_rule`;
:func:`x_mass_coefficients` gives its Bloch coefficients :math:`a_L`,
:math:`m_x(\\theta) = \\sum_L a_L \\cos L\\theta`.

>>> import sympy
>>> from dispersion.symbolic.bspline import open_knot_vector
>>> kv = open_knot_vector(2, 1, -1, 1)
>>> space = gram_space(kv)
>>> mass_matrix("hrz", space).tolist()      # diag(2/5, 4/15, 2/5) scaled to the mass 2
[[3/4, 0, 0], [0, 1/2, 0], [0, 0, 3/4]]
>>> x_mass_coefficients("lumped", 2)
((0, 1),)

References
----------
E. Hinton, T. Rock, O. C. Zienkiewicz, "A note on mass lumping and related processes in the
finite element method", Earthq. Eng. Struct. Dyn. 4 (1976) 245-249.
A. Tkachuk et al., eqs (1)-(4). J. A. Cottrell, A. Reali, Y. Bazilevs, T. J. R. Hughes,
CMAME 195 (2006) 5257-5296 (lumped IGA masses). M. Abramowitz, I. Stegun, 25.4.32
(Lobatto quadrature and its error term).
"""
from __future__ import annotations

import math
import sys
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, fields
from fractions import Fraction
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np

from dispersion.errors import IndefiniteMassWarning, InputError, check_positive_int

if TYPE_CHECKING:
    import sympy

# sympy (exact matrices, symbolic/spline_mass) and scipy (sparse matrices) are imported
# where such a matrix is made: a float bar builds and checks its mass on numpy alone.

__all__ = [
    "MassProperties",
    "MassSpace",
    "MassRule",
    "MassCheck",
    "RULES",
    "RULE_NAMES",
    "TranslationalMassWarning",
    "DENSE_CHECK_MAX",
    "get_rule",
    "gram_space",
    "mass_matrix",
    "check_mass",
    "user_rule",
    "rule_from_toml",
    "x_mass_coefficients",
    "is_exact",
    "is_sparse",
]


def is_exact(M) -> bool:
    """True for a sympy matrix; never imports sympy (such a matrix means it is loaded)."""
    sympy = sys.modules.get("sympy")
    return sympy is not None and isinstance(M, sympy.MatrixBase)


def is_sparse(M) -> bool:
    """True for a scipy.sparse matrix; never imports scipy (such a matrix means it is loaded)."""
    sp = sys.modules.get("scipy.sparse")
    return sp is not None and sp.issparse(M)


class TranslationalMassWarning(UserWarning):
    """A mass rule changed the total (translational) mass of the space."""


@dataclass(frozen=True)
class MassProperties:
    """Properties of a mass matrix, stated by a rule or measured on a space.

    ``zero_rows``: the matrix may have (stated) or has (measured) identically zero rows, the
    massless DOFs the explicit scheme condenses.
    """

    symmetric: bool = True
    psd: bool = True
    translational: bool = True
    diagonal: bool = False
    zero_rows: bool = False

    def as_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass(frozen=True)
class MassSpace:
    """What a rule may use: the consistent mass ``M`` of a 1D B-spline space and its data.

    ``M`` is a sympy matrix (exact) or a numpy / scipy.sparse array; ``kv`` the knot vector
    (rules that evaluate the basis need it); ``elements`` optional float element matrices
    ``(conn (n_el, nf) int, Me (n_el, nf, nf))`` of a space without a 1D knot vector (the
    ring patch); ``R`` the redistribution of the contact set (singular rules).
    """

    M: object
    kv: object = None
    elements: tuple | None = None
    R: object = None

    @property
    def n(self) -> int:
        return int(self.M.shape[0])

    @property
    def exact(self) -> bool:
        return is_exact(self.M)


@dataclass(frozen=True)
class MassRule:
    """A named way to build a mass matrix from a :class:`MassSpace`.

    ``build(space)`` returns the matrix (same kind as ``space.M``); ``states`` are the
    properties it promises; ``x_rule`` names the registered rule used along x of the Bloch
    plate; ``redistributes``: it needs ``space.R`` (a contact set).
    """

    name: str
    build: Callable = None
    states: MassProperties = MassProperties()
    x_rule: str = "consistent"
    redistributes: bool = False
    description: str = ""

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise InputError(f"mass rule name must be a non-empty string, got {self.name!r}")
        if not callable(self.build):
            raise InputError(f"mass rule {self.name!r}: build must be callable")
        if self.x_rule not in _BUILTIN:
            raise InputError(f"mass rule {self.name!r}: x_rule must be one of "
                             f"{', '.join(n for n in _BUILTIN if not _BUILTIN[n][3])}, "
                             f"got {self.x_rule!r}")
        if _BUILTIN[self.x_rule][3]:
            raise InputError(f"mass rule {self.name!r}: x_rule {self.x_rule!r} needs a "
                             "contact set, which the x-direction has not")


def _total(M):
    if is_exact(M):
        return sum(M)
    return float(np.asarray(M.sum()))


def _dense(M) -> np.ndarray:
    if is_exact(M):
        return np.array(M.tolist(), dtype=float)
    return M.toarray() if is_sparse(M) else np.asarray(M, dtype=float)


def _like(A_exact: sympy.Matrix, space: MassSpace, reference_exact: sympy.Matrix):
    """The exact matrix ``A_exact`` in the kind of ``space.M``, scaled like it.

    A float ``M`` is taken as ``scale * reference_exact`` (constant density, affine map), the
    scale being the ratio of the totals.
    """
    if space.exact:
        return A_exact
    scale = _total(space.M) / float(sum(reference_exact))
    A = scale * np.array(A_exact.tolist(), dtype=float)
    if is_sparse(space.M):
        import scipy.sparse as sp

        return sp.csr_matrix(A)
    return A


def _row_sum(M):
    from dispersion.symbolic.mass import row_sum_lump

    return row_sum_lump(M)


def _need_kv(space: MassSpace, name: str):
    if space.kv is None:
        raise InputError(f"mass rule {name!r} evaluates the basis and needs a 1D B-spline space "
                         "(knot vector); this space has none (the ring patch supports "
                         "consistent, lumped, hrz, singular, singular-lumped and user rules)")
    return space.kv


def _build_consistent(space):
    return space.M


def _build_lumped(space):
    return _row_sum(space.M)


def _build_singular(space, lump: bool = False):
    from dispersion.symbolic.mass import redistributed_mass

    if space.R is None:
        raise InputError("a singular mass rule needs a contact set (redistribution matrix R)")
    return redistributed_mass(space.M, space.R, lump)


def _build_hrz(space):
    if space.kv is not None and (space.exact or space.elements is None):
        from dispersion.symbolic.spline_mass import gram_matrix, hrz_matrix

        return _like(hrz_matrix(space.kv), space, gram_matrix(space.kv))
    if space.elements is None:
        _need_kv(space, "hrz")
    conn, Me = space.elements
    diag = np.einsum("eii->ei", Me)
    diag = diag * (Me.sum(axis=(1, 2)) / diag.sum(axis=1))[:, None]
    d = np.bincount(np.asarray(conn).ravel(), diag.ravel(), minlength=space.n)
    if is_sparse(space.M):
        import scipy.sparse as sp

        return sp.diags(d).tocsr()
    return np.diag(d)


def _build_greville(space):
    from dispersion.symbolic.spline_mass import gram_matrix, greville_matrix

    kv = _need_kv(space, "nodal-greville")
    return _like(greville_matrix(kv), space, gram_matrix(kv))


def _build_lobatto(space):
    from dispersion.symbolic.spline_mass import gram_matrix, lobatto_matrix

    kv = _need_kv(space, "nodal-lobatto")
    return _like(lobatto_matrix(kv), space, gram_matrix(kv))


# name -> (build, stated properties, x rule, redistributes, description)
_BUILTIN = {
    "consistent": (_build_consistent, MassProperties(), "consistent", False,
                   "consistent Gram matrix"),
    "lumped": (_build_lumped, MassProperties(diagonal=True), "lumped", False,
               "row-sum lumped"),
    "hrz": (_build_hrz, MassProperties(diagonal=True), "hrz", False,
            "HRZ: element diagonal scaled to the element mass"),
    "nodal-greville": (_build_greville, MassProperties(), "nodal-greville", False,
                       "nodal quadrature at the Greville points"),
    "nodal-lobatto": (_build_lobatto, MassProperties(), "nodal-lobatto", False,
                      "nodal quadrature at p+1 Gauss-Lobatto points per element"),
    "singular": (_build_singular, MassProperties(zero_rows=True), "consistent", True,
                 "singular: R^T M R (paper eq 1 left)"),
    "singular-lumped": (lambda s: _build_singular(s, lump=True),
                        MassProperties(diagonal=True, zero_rows=True), "lumped", True,
                        "singular lumped: row sums of R^T M R (paper eq 1 right)"),
}

#: The registered rules, by name (one registry for patch, bar, contact scenes and CLI).
RULES: dict[str, MassRule] = {
    name: MassRule(name, build, states, x_rule, redis, desc)
    for name, (build, states, x_rule, redis, desc) in _BUILTIN.items()
}
RULE_NAMES = tuple(RULES)


def get_rule(mass) -> MassRule:
    """The :class:`MassRule` for a registered name or a rule object.

    >>> get_rule("hrz").states.diagonal
    True
    """
    if isinstance(mass, MassRule):
        return mass
    if isinstance(mass, str) and mass in RULES:
        return RULES[mass]
    raise InputError(f"mass must be one of {', '.join(RULE_NAMES)} or a MassRule; got {mass!r}")


def gram_space(kv, R=None) -> MassSpace:
    """The exact :class:`MassSpace` of knot vector ``kv``: its Gram matrix :math:`\\int N N^T`."""
    import sympy

    from dispersion.symbolic.spline_mass import gram_matrix

    return MassSpace(sympy.Matrix(gram_matrix(kv)), kv, None, R)


@dataclass(frozen=True)
class MassCheck:
    """Properties measured on a space, and the reasons a rule is refused or warned about."""

    measured: MassProperties
    refused: tuple[str, ...]
    warned: tuple[str, ...]


def check_mass(rule: MassRule, Mv, M, tol: float = 1e-10) -> MassCheck:
    """Measure the properties of ``Mv`` (built by ``rule`` from the consistent ``M``).

    Refused: not symmetric; stated diagonal but is not; zero rows it did not state; a
    massless direction that is no zero row. Warned: indefinite; translational mass changed
    (the warning says if the rule stated otherwise). ``tol`` is relative to the largest entry (float matrices; exact ones compare
    exactly, except the eigenvalues).
    """
    exact = is_exact(Mv)
    if exact:
        import sympy
    if not exact and Mv.shape[0] > DENSE_CHECK_MAX:
        return _check_large(rule, Mv, M, tol)
    A = _dense(Mv)
    n = A.shape[0]
    if A.shape != (n, n) or A.shape[0] != M.shape[0]:
        raise InputError(f"mass rule {rule.name!r} returned shape {A.shape}, expected "
                         f"{tuple(M.shape)}")
    if not np.all(np.isfinite(A)):
        raise InputError(f"mass rule {rule.name!r} returned non-finite entries")
    scale = max(float(np.abs(A).max(initial=0.0)), np.finfo(float).tiny)
    if exact:
        symmetric = Mv.is_symmetric()
        diagonal = Mv.is_diagonal()
        zero = [i for i in range(n) if all(v == 0 for v in Mv.row(i))]
        translational = sympy.expand(sum(Mv) - sum(sympy.Matrix(M))) == 0 \
            if is_exact(M) else abs(float(sum(Mv)) - _total(M)) <= tol * scale * n
    else:
        symmetric = bool(np.allclose(A, A.T, rtol=0, atol=tol * scale))
        diagonal = bool(np.all(np.abs(A - np.diag(np.diag(A))) <= tol * scale))
        zero = [i for i in range(n) if np.all(np.abs(A[i]) <= tol * scale)]
        translational = abs(A.sum() - _total(M)) <= tol * scale * n
    keep = np.setdiff1d(np.arange(n), zero)
    Ar = A[np.ix_(keep, keep)]
    ev = np.linalg.eigvalsh((Ar + Ar.T) / 2) if keep.size else np.zeros(0)
    psd = bool(ev.size == 0 or ev.min() >= -tol * scale * n)
    if exact and keep.size:
        # rank decided exactly (fraction-free over QQ): high-degree nodal masses are
        # nonsingular but far too ill-conditioned for a float test
        from sympy.polys.matrices import DomainMatrix

        rest = Mv.extract(list(keep), list(keep))
        try:
            nonsingular_rest = DomainMatrix.from_Matrix(rest).to_field().rank() == keep.size
        except (ValueError, TypeError, NotImplementedError, sympy.polys.polyerrors.PolynomialError):
            nonsingular_rest = bool(np.abs(ev).min() > tol * scale * n)
    else:
        nonsingular_rest = bool(ev.size == 0 or np.abs(ev).min() > tol * scale * n)
    measured = MassProperties(bool(symmetric), psd, bool(translational), bool(diagonal),
                              bool(zero))
    smallest = f"smallest eigenvalue {ev.min():.3g}" if ev.size else ""
    return _verdict(rule, measured, zero, nonsingular_rest, smallest)


#: Largest float matrix checked with dense eigenvalues; above, a sparse symmetric
#: factorisation gives the inertia (Sylvester). Rule: the dense check stays near a second
#: (numpy eigvalsh of 2000 x 2000, O(n^3)) and its memory near 32 MB.
DENSE_CHECK_MAX = 2000


def _check_large(rule: MassRule, Mv, M, tol: float) -> MassCheck:
    """:func:`check_mass` of a large float matrix without forming it densely."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import splu

    A = sp.csr_matrix(Mv, dtype=float)
    n = A.shape[0]
    if A.shape != (n, n) or n != M.shape[0]:
        raise InputError(f"mass rule {rule.name!r} returned shape {A.shape}, expected "
                         f"{tuple(M.shape)}")
    if not np.all(np.isfinite(A.data)):
        raise InputError(f"mass rule {rule.name!r} returned non-finite entries")
    scale = max(float(np.abs(A.data).max(initial=0.0)), np.finfo(float).tiny)
    symmetric = float(np.abs((A - A.T).data).max(initial=0.0)) <= tol * scale
    off = A - sp.diags(A.diagonal())
    diagonal = float(np.abs(off.data).max(initial=0.0)) <= tol * scale
    rowabs = np.asarray(abs(A).sum(axis=1)).ravel()
    zero = [int(i) for i in np.flatnonzero(rowabs <= tol * scale)]
    translational = abs(float(A.sum()) - _total(M)) <= tol * scale * n
    keep = np.setdiff1d(np.arange(n), zero)
    S = ((A + A.T) / 2).tocsc()[keep][:, keep]
    if diagonal:
        pivots = S.diagonal()
    else:  # LDL^T by symmetric-mode LU without pivoting: the pivots carry the inertia
        try:
            pivots = splu(S, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                          options={"SymmetricMode": True}).U.diagonal()
        except RuntimeError:  # exactly singular
            pivots = np.zeros(1)
    psd = bool(pivots.size == 0 or pivots.min() >= -tol * scale)
    nonsingular_rest = bool(pivots.size == 0 or np.abs(pivots).min() > tol * scale)
    measured = MassProperties(bool(symmetric), psd, bool(translational), bool(diagonal),
                              bool(zero))
    smallest = f"smallest pivot {pivots.min():.3g}" if pivots.size else ""
    return _verdict(rule, measured, zero, nonsingular_rest, smallest)


def _verdict(rule: MassRule, measured: MassProperties, zero, nonsingular_rest: bool,
             smallest: str) -> MassCheck:
    refused, warned = [], []
    if not measured.symmetric:
        refused.append("it is not symmetric")
    if not nonsingular_rest:
        refused.append("it has massless directions that are not zero rows (the explicit "
                       "scheme condenses zero rows only)")
    if zero and not rule.states.zero_rows:
        refused.append(f"it has zero rows {zero} but does not state zero_rows")
    if rule.states.diagonal and not measured.diagonal:
        refused.append("it states diagonal but is not")
    # indefinite or mass-changing matrices are legitimate objects of study (negative weights
    # on request, mass scaling): warned, with the stated promise named if it is broken
    if not measured.psd:
        broken = " although it states psd" if rule.states.psd else ""
        warned.append(f"it is indefinite ({smallest}){broken}")
    if not measured.translational:
        broken = " although it states translational" if rule.states.translational else ""
        warned.append(f"it changes the translational mass{broken}")
    return MassCheck(measured, tuple(refused), tuple(warned))


def mass_matrix(mass, space: MassSpace, *, check: bool = True):
    """The mass matrix of rule ``mass`` (name or :class:`MassRule`) on ``space``, checked.

    Raises :class:`InputError` naming the rule and the reason where :func:`check_mass`
    refuses it; warns (:class:`IndefiniteMassWarning`, :class:`TranslationalMassWarning`)
    where it only warns.
    """
    rule = get_rule(mass)
    Mv = rule.build(space)
    if isinstance(Mv, (list, tuple)):
        Mv = np.asarray(Mv, dtype=float)
    if space.exact and not is_exact(Mv):
        import sympy

        Mv = sympy.Matrix(Mv)
    if check:
        result = check_mass(rule, Mv, space.M)
        if result.refused:
            raise InputError(f"mass rule {rule.name!r} refused: " + "; ".join(result.refused))
        for reason in result.warned:
            cls = IndefiniteMassWarning if "indefinite" in reason else TranslationalMassWarning
            warnings.warn(f"mass rule {rule.name!r}: {reason}", cls, stacklevel=2)
    return Mv


def user_rule(name: str, build: Callable, *, states: MassProperties | None = None,
              x_rule: str = "consistent", description: str = "user rule") -> MassRule:
    """A :class:`MassRule` from a callable ``build(space: MassSpace) -> matrix``.

    ``states`` defaults to symmetric, positive semi-definite, translational mass kept, not
    diagonal, no zero rows; the toolkit checks them whenever the rule builds a matrix.

    >>> half = user_rule("half-lumped", lambda s: (s.M + _row_sum(s.M)) / 2)
    >>> from dispersion.symbolic.bspline import open_knot_vector
    >>> mass_matrix(half, gram_space(open_knot_vector(1, 1))).tolist()
    [[5/12, 1/12], [1/12, 5/12]]
    """
    if name in RULES:
        raise InputError(f"user rule name {name!r} is taken by a registered rule")
    return MassRule(name, build, states or MassProperties(), x_rule, False, description)


def _resolve(index: int, n: int) -> int:
    return index + n if index < 0 else index


def rule_from_toml(source) -> MassRule:
    """A redistribution rule from a TOML table (text or path), read as plain data.

    ::

        name = "far-half"
        lumped = false            # row-sum lump R^T M R (eq 1 right) if true
        [weights]                 # contact index -> {target index: weight}; negative
        "-1" = { "-2" = 0.5, "-3" = 0.5 }   # indices count from the far end (any n)

    The weights go through :func:`dispersion.symbolic.mass.redistribution_matrix` (sum one,
    in [0, 1]) on every space the rule is applied to.

    >>> rule = rule_from_toml('name = "far-half"\\n[weights]\\n"-1" = {"-2" = 0.5, "-3" = 0.5}')
    >>> from dispersion.symbolic.bspline import open_knot_vector
    >>> mass_matrix(rule, gram_space(open_knot_vector(1, 2))).tolist()  # M00 + M02 + M22/4 = 5/24
    [[5/24, 1/6, 0], [1/6, 11/24, 0], [0, 0, 0]]
    """
    import os

    try:  # Python >= 3.11
        import tomllib
    except ModuleNotFoundError:  # pragma: no cover - Python 3.10
        import tomli as tomllib

    from dispersion.symbolic.mass import redistribution_matrix

    text = source
    if isinstance(source, os.PathLike) or (isinstance(source, str) and "\n" not in source
                                           and source.endswith(".toml")):
        try:
            with open(source, "rb") as fh:
                text = fh.read().decode("utf-8")
        except OSError as exc:
            raise InputError(f"mass rule file {source}: {exc.strerror}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"mass rule TOML: {exc}") from None
    unknown = set(data) - {"name", "lumped", "weights", "description"}
    if unknown:
        raise InputError(f"mass rule TOML: unknown keys {sorted(unknown)} (allowed: name, lumped, "
                         "weights, description)")
    name = data.get("name")
    if not isinstance(name, str) or not name or name in RULES:
        raise InputError(f"mass rule TOML: name must be a new non-empty string, got {name!r}")
    lumped = data.get("lumped", False)
    if not isinstance(lumped, bool):
        raise InputError(f"mass rule TOML: lumped must be true or false, got {lumped!r}")
    raw = data.get("weights")
    if not isinstance(raw, Mapping) or not raw:
        raise InputError("mass rule TOML: [weights] must be a non-empty table")
    table = {}
    for c, ws in raw.items():
        if not isinstance(ws, Mapping):
            raise InputError(f"mass rule TOML: weights of {c!r} must be a table {{index = weight}}")
        try:
            table[int(c)] = {int(j): w for j, w in ws.items()}
        except ValueError:
            raise InputError(f"mass rule TOML: weight indices must be integers, got {c!r}: "
                             f"{dict(ws)!r}") from None
        for j, w in ws.items():
            if isinstance(w, bool) or not isinstance(w, (int, float)) or not math.isfinite(w):
                raise InputError(f"mass rule TOML: weight [{c}][{j}] must be a finite number, "
                                 f"got {w!r}")

    def build(space: MassSpace):
        n = space.n
        weights = {}
        for c, ws in table.items():
            cr = _resolve(c, n)
            if cr in weights:
                raise InputError(f"mass rule {name!r}: contact index {c} repeats another on n = {n}")
            weights[cr] = {_resolve(j, n): w for j, w in ws.items()}
        R = redistribution_matrix(n, weights)
        if not space.exact:
            R = np.array(R.tolist(), dtype=float)
        return _build_singular(MassSpace(space.M, space.kv, space.elements, R), lump=lumped)

    return MassRule(name, build, MassProperties(diagonal=lumped, zero_rows=True),
                    "lumped" if lumped else "consistent", False,
                    str(data.get("description", "redistribution weights from TOML")))


def _bloch_mesh(p: int) -> int:
    # function 2p of an open mesh of 3p + 1 unit spans: every span under its support carries
    # only cardinal (uniform interior) functions, so its row is the periodic stencil
    return 3 * p + 1


@lru_cache(maxsize=None)
def x_mass_coefficients(rule, p: int) -> tuple[tuple[int, sympy.Rational], ...]:
    """Bloch coefficients :math:`((L, a_L), ...)` of a rule (name or object) on the uniform x-mesh.

    Read off the middle row of the rule's matrix on an open uniform mesh of unit elements
    long enough that the row sees interior (cardinal) elements only; zeros are dropped.

    >>> x_mass_coefficients("consistent", 1)
    ((-1, 1/6), (0, 2/3), (1, 1/6))
    >>> x_mass_coefficients("nodal-greville", 2)   # N = 3/4 at its Greville point, 1/8 beside
    ((-2, 1/64), (-1, 3/16), (0, 19/32), (1, 3/16), (2, 1/64))
    """
    import sympy

    from dispersion.symbolic.bspline import open_knot_vector
    from dispersion.symbolic.spline_mass import PERIODIC_ROWS

    rule = get_rule(rule)
    if rule.redistributes:
        raise InputError(f"mass rule {rule.name!r} needs a contact set; the x-direction has none")
    p = check_positive_int("degree p", p)
    if RULES.get(rule.name) is rule and rule.name in PERIODIC_ROWS:
        row = PERIODIC_ROWS[rule.name](p)
    else:  # any other rule: the middle row of its matrix on the open mesh
        ne = _bloch_mesh(p)
        kv = open_knot_vector(p, ne, 0, ne)
        M = mass_matrix(rule, gram_space(kv), check=False)
        mid = 2 * p  # the first function whose spans carry cardinal functions only
        row = {L: M[mid, mid + L] for L in range(-p, p + 1)}
    return tuple((L, sympy.Rational(v.numerator, v.denominator) if isinstance(v, Fraction)
                  else v) for L, v in sorted(row.items()) if v != 0)
