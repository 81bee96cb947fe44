"""Mass rules: one registry of the ways to build a mass matrix, each with its stated properties.

A *mass rule* turns the consistent Gram matrix :math:`\\mathbf M` of a B-spline space (and,
for the singular rules, a redistribution :math:`\\mathbf R`, :mod:`dispersion.mass_rules.mass`)
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
:func:`dispersion.mass_rules.mass_rule_file.rule_from_toml` (a table of redistribution weights,
read as untrusted data). Each rule *states* its properties
(:class:`MassProperties`); :func:`mass_matrix` builds the matrix and checks them on the space
(:func:`check_mass`): a rule whose matrix contradicts what it states, is not symmetric, or has
massless directions that are not zero rows (the explicit scheme condenses zero rows only) is
refused with the reason; an indefinite matrix or lost translational mass is warned about.

Along x of the Bloch plate (no contact there) a rule acts through :attr:`MassRule.x_rule`;
:func:`x_mass_coefficients` gives its Bloch coefficients :math:`a_L`,
:math:`m_x(\\theta) = \\sum_L a_L \\cos L\\theta`.

>>> import sympy
>>> from dispersion.splines.bspline import open_knot_vector
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

import re
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache
from typing import TYPE_CHECKING

from dispersion.errors import IndefiniteMassWarning, InputError, check_positive_int
from dispersion.mass_rules.mass import redistributed_mass, row_sum_lump
from dispersion.mass_rules.explicit_cost import ExplicitCost
from dispersion.mass_rules.mass_check import MassProperties, check_mass
from dispersion.splines.matrix_kind import is_exact, is_sparse, total

if TYPE_CHECKING:
    import sympy

# numpy, sympy (exact matrices, symbolic/spline_mass) and scipy (sparse matrices) are imported
# where a matrix is made: the registry itself (RULES, RULE_NAMES, get_rule) loads without them,
# so that the command line names the rules, and answers a mistyped one, before any of them.

__all__ = [
    "FAMILY_NAMES",
    "family_rule",
    "MassSpace",
    "MassRule",
    "RULES",
    "RULE_NAMES",
    "BLOCH_RULE_NAMES",
    "TranslationalMassWarning",
    "get_rule",
    "gram_space",
    "mass_matrix",
    "user_rule",
    "x_mass_coefficients",
    "x_stiffness_factor",
    "mass_variant",
]


class TranslationalMassWarning(UserWarning):
    """A mass rule changed the total (translational) mass of the space."""


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
    #: Periodic row ``p -> {L: a_L}`` of the rule along x (None: read off its matrix).
    periodic: Callable | None = field(default=None, compare=False, repr=False)
    #: Bloch factor ``p -> {L: s_L}`` multiplying the x-stiffness symbol (Petrov-Galerkin
    #: test functions along x, :mod:`dispersion.mass_rules.lumping_rules`); None: 1.
    x_stiffness: Callable | None = field(default=None, compare=False, repr=False)
    #: How the explicit step applies stiffness and inverse mass (None: from ``states``).
    cost: ExplicitCost | None = field(default=None, compare=False, repr=False)
    #: The discrete space: ``"bspline"`` (smooth B-splines) or ``"lagrange"`` (C0 elements,
    #: :mod:`dispersion.splines.lagrange_sem`): such a rule changes the stiffness too.
    basis: str = "bspline"

    @property
    def explicit_cost(self) -> ExplicitCost:
        """The rule's :class:`~dispersion.mass_rules.explicit_cost.ExplicitCost`: stated, or a
        diagonal mass if it states diagonal and a solve otherwise."""
        if self.cost is not None:
            return self.cost
        return ExplicitCost("sparse", "diagonal" if self.states.diagonal else "solve")

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


def _like(A_exact: sympy.Matrix, space: MassSpace, reference_exact: sympy.Matrix):
    """The exact matrix ``A_exact`` in the kind of ``space.M``, scaled like it.

    A float ``M`` is taken as ``scale * reference_exact`` (constant density, affine map), the
    scale being the ratio of the totals.
    """
    import numpy as np
    if space.exact:
        return A_exact
    scale = total(space.M) / float(sum(reference_exact))
    A = scale * np.array(A_exact.tolist(), dtype=float)
    if is_sparse(space.M):
        import scipy.sparse as sp

        return sp.csr_matrix(A)
    return A


def _row_sum(M):
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

    if space.R is None:
        raise InputError("a singular mass rule needs a contact set (redistribution matrix R)")
    return redistributed_mass(space.M, space.R, lump)


def _build_hrz(space):
    import numpy as np
    if space.kv is not None and (space.exact or space.elements is None):
        from dispersion.splines.spline_mass import gram_matrix, hrz_matrix

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
    from dispersion.splines.spline_mass import gram_matrix, greville_matrix

    kv = _need_kv(space, "nodal-greville")
    return _like(greville_matrix(kv), space, gram_matrix(kv))


def _build_lobatto(space):
    from dispersion.splines.spline_mass import gram_matrix, lobatto_matrix

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


def _literature():
    # the rules of the recent lumping literature (their own module); the x-rule check of
    # MassRule needs their names in _BUILTIN first
    from dispersion.mass_rules.lumping_rules import ENTRIES

    for name, e in ENTRIES.items():
        _BUILTIN[name] = (literature_build(e["build"]), e["states"], e["x_rule"], False,
                          e["description"])
    return {name: literature_rule(name, e) for name, e in ENTRIES.items()}


def literature_build(build: Callable) -> Callable:
    """``build`` (exact matrices from the space's knot vector) in the kind of the space."""
    def kind_of_space(space: MassSpace):
        A = build(space)
        if space.exact or not is_exact(A):
            return A
        from dispersion.splines.spline_mass import gram_matrix

        return _like(A, space, gram_matrix(space.kv))

    return kind_of_space


def literature_rule(name: str, e: dict) -> MassRule:
    """A :class:`MassRule` from an entry of :data:`dispersion.mass_rules.lumping_rules.ENTRIES`."""
    return MassRule(name, literature_build(e["build"]), e["states"], e["x_rule"], False,
                    e["description"], e.get("periodic"), e.get("x_stiffness"), e.get("cost"),
                    e.get("basis", "bspline"))


_LITERATURE = _literature()

#: The registered rules, by name (one registry for patch, bar, contact scenes and CLI).
RULES: dict[str, MassRule] = {
    name: _LITERATURE.get(name) or MassRule(name, build, states, x_rule, redis, desc)
    for name, (build, states, x_rule, redis, desc) in _BUILTIN.items()
}
RULE_NAMES = tuple(RULES)
#: The rules that apply to the Bloch plate patch (its x-direction is one B-spline symbol; the
#: C0 Lagrange rules carry p DOFs a cell there and apply to the x-exact model and the bar).
BLOCH_RULE_NAMES = tuple(name for name, rule in RULES.items() if rule.basis == "bspline")


#: The family names :func:`family_rule` reads, as error messages show them.
FAMILY_NAMES = "dual-lumped-q<q> (q = 0..8)"
#: ``dual-lumped-q<q>``: one digit, the whole string (no signs, spaces or leading zeros).
_DUAL = re.compile(r"dual-lumped-q([0-8])")


def family_rule(name) -> MassRule | None:
    """The member of a rule family a name denotes (``dual-lumped-q<q>``, q = 0..8: the
    approximate dual of reproduction degree q, row-sum lumped), else None; one object per
    name. The name is matched whole by a regular expression (at most one digit): text never
    reaches anything but that pattern.

    >>> family_rule("dual-lumped-q1").name, family_rule("dual-lumped-q01")
    ('dual-lumped-q1', None)
    """
    m = _DUAL.fullmatch(name) if isinstance(name, str) and len(name) <= 16 else None
    return _dual_member(int(m.group(1))) if m else None


@lru_cache(maxsize=None)
def _dual_member(q: int) -> MassRule:
    from dispersion.mass_rules.lumping_rules import approximate_dual_entry

    return literature_rule(f"dual-lumped-q{q}", dict(approximate_dual_entry(q),
                                                     x_rule="dual-lumped"))


def get_rule(mass) -> MassRule:
    """The :class:`MassRule` for a registered name, a family member's name
    (:func:`dispersion.mass_rules.rule_families.family_rule`: ``dual-lumped-q1``) or a rule
    object.

    >>> get_rule("hrz").states.diagonal
    True
    """
    if isinstance(mass, MassRule):
        return mass
    if isinstance(mass, str) and mass in RULES:
        return RULES[mass]
    member = family_rule(mass)  # a member of a rule family by name: dual-lumped-q1
    if member is not None:
        return member
    from dispersion.errors import did_you_mean

    hint = did_you_mean(mass, RULE_NAMES) if isinstance(mass, str) else ""
    raise InputError(f"mass must be one of {', '.join(RULE_NAMES)}, {FAMILY_NAMES} or a "
                     f"MassRule; got {mass!r}{hint}")


def gram_space(kv, R=None) -> MassSpace:
    """The exact :class:`MassSpace` of knot vector ``kv``: its Gram matrix :math:`\\int N N^T`."""
    import sympy

    from dispersion.splines.spline_mass import gram_matrix

    return MassSpace(sympy.Matrix(gram_matrix(kv)), kv, None, R)


def mass_matrix(mass, space: MassSpace, *, check: bool = True):
    """The mass matrix of rule ``mass`` (name or :class:`MassRule`) on ``space``, checked.

    Raises :class:`InputError` naming the rule and the reason where :func:`check_mass`
    refuses it; warns (:class:`IndefiniteMassWarning`, :class:`TranslationalMassWarning`)
    where it only warns.
    """
    import numpy as np
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
    >>> from dispersion.splines.bspline import open_knot_vector
    >>> mass_matrix(half, gram_space(open_knot_vector(1, 1))).tolist()
    [[5/12, 1/12], [1/12, 5/12]]
    """
    if name in RULES:
        raise InputError(f"user rule name {name!r} is taken by a registered rule")
    return MassRule(name, build, states or MassProperties(), x_rule, False, description)


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

    from dispersion.splines.bspline import open_knot_vector
    from dispersion.splines.spline_mass import PERIODIC_ROWS

    rule = get_rule(rule)
    if rule.redistributes:
        raise InputError(f"mass rule {rule.name!r} needs a contact set; the x-direction has none")
    p = check_positive_int("degree p", p)
    if rule.periodic is not None:
        row = rule.periodic(p)
    elif RULES.get(rule.name) is rule and rule.name in PERIODIC_ROWS:
        row = PERIODIC_ROWS[rule.name](p)
    else:  # any other rule: the middle row of its matrix on the open mesh
        ne = _bloch_mesh(p)
        kv = open_knot_vector(p, ne, 0, ne)
        M = mass_matrix(rule, gram_space(kv), check=False)
        mid = 2 * p  # the first function whose spans carry cardinal functions only
        row = {L: M[mid, mid + L] for L in range(-p, p + 1)}
    return tuple((L, sympy.Rational(v.numerator, v.denominator) if isinstance(v, Fraction)
                  else v) for L, v in sorted(row.items()) if v != 0)


@lru_cache(maxsize=None)
def x_stiffness_factor(rule, p: int) -> tuple[tuple[int, sympy.Rational], ...]:
    """Bloch coefficients :math:`((L, s_L), ...)` of the factor multiplying a rule's x-stiffness.

    1 for every Galerkin rule; the approximate-dual symbol for ``dual-lumped`` (its
    Petrov-Galerkin test functions along x, :mod:`dispersion.mass_rules.lumping_rules`).

    >>> x_stiffness_factor("lumped", 2)
    ((0, 1),)
    """
    import sympy

    rule = get_rule(rule)
    p = check_positive_int("degree p", p)
    if rule.x_stiffness is None:
        return ((0, sympy.Integer(1)),)
    from dispersion.reader import rational

    return tuple((L, rational(f"x_stiffness of rule {rule.name!r}", v))
                 for L, v in sorted(rule.x_stiffness(p).items()) if v != 0)


def mass_variant(M, variant, R=None, *, kv=None, elements=None, check: bool = True):
    """Mass matrix of rule ``variant`` from the consistent mass ``M`` and redistribution ``R``.

    ``variant`` is a name of :data:`RULE_NAMES` or a :class:`MassRule`. ``"consistent"``: M; ``"lumped"``: row
    sums of M; ``"singular"``: R^T M R (eq 1 left); ``"singular-lumped"``: row sums of
    R^T M R (eq 1 right); ``"hrz"`` and the nodal quadratures need the knot vector ``kv``
    (or, HRZ, the float element matrices ``elements``). The result is checked against the
    rule's stated properties (:func:`dispersion.mass_rules.mass_rule.mass_matrix`).
    """
    import numpy as np
    rule = get_rule(variant)
    shape = getattr(M, "shape", None)
    if shape is None or len(shape) != 2 or shape[0] != shape[1]:
        raise InputError(f"M must be a square matrix, got shape {shape}")
    if R is not None and tuple(getattr(R, "shape", np.shape(R))) != tuple(shape):
        raise InputError(f"R must have the shape of M {tuple(shape)}, got "
                         f"{tuple(getattr(R, 'shape', np.shape(R)))}")
    if rule.redistributes and R is None:
        raise InputError(f"mass variant {rule.name!r} needs a redistribution matrix R")
    return mass_matrix(rule, MassSpace(M, kv, elements, R), check=check)
