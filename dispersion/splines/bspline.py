"""B-spline bases by Bezier extraction: knot vectors, Greville points, knot insertion.

Every B-spline of degree :math:`p` restricted to one knot span is a polynomial, written
in the Bernstein basis of that span,

.. math::

    N^e_a(\\xi) = \\sum_{b=0}^{p} C^e_{ab} \\, B_{b,p}(u), \\qquad
    B_{b,p}(u) = \\binom{p}{b} u^b (1-u)^{p-b}, \\quad u = \\frac{\\xi - \\xi_e}{\\xi_{e+1} - \\xi_e}.

The extraction operators :math:`C^e` are exact rationals obtained by knot insertion
(Borden et al. 2011), so one code path serves both the symbolic dispersion analysis
(sympy polynomials) and the numeric ring solver (float Bernstein values). An open uniform
knot vector also has a float path, :meth:`SplineBasis1D.uniform` (the 1D bar: no sympy).

>>> kv = open_knot_vector(2, 1)
>>> kv.n
3
>>> [str(g) for g in kv.greville()]
['0', '1/2', '1']
>>> import sympy
>>> u = sympy.Symbol("u")
>>> [sympy.factor(f) for f in basis_polynomials(kv, u)[0][1]]
[(u - 1)**2, -2*u*(u - 1), u**2]

References
----------
M. J. Borden, M. A. Scott, J. A. Evans, T. J. R. Hughes, "Isogeometric finite element data
structures based on Bezier extraction of NURBS", IJNME 87 (2011) 15-47, doi:10.1002/nme.3167.
L. Piegl, W. Tiller, *The NURBS Book*, 2nd ed., Springer 1997 (knot insertion, A5.1).
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import comb
from typing import TYPE_CHECKING

import numpy as np

from dispersion.errors import InputError, check_positive_int

if TYPE_CHECKING:  # annotations only: sympy is imported where it is used
    import sympy

__all__ = [
    "KnotVector",
    "MAX_ELEMENTS",
    "open_knot_vector",
    "cardinal_knot_vector",
    "insert_knot",
    "refine",
    "extraction_operators",
    "bernstein",
    "bernstein_numeric",
    "basis_polynomials",
    "cardinal_pieces",
    "SplineBasis1D",
]


@dataclass(frozen=True)
class KnotVector:
    """A non-decreasing knot vector ``knots`` (exact rationals) for degree ``p``."""

    knots: tuple
    p: int

    def __post_init__(self):
        from dispersion.reader import rational

        check_positive_int("degree p", self.p)
        ks = tuple(rational("knots", k) for k in self.knots)
        if any(b < a for a, b in zip(ks, ks[1:])):
            raise InputError("knots must be non-decreasing")
        if len(ks) < 2 * self.p + 2:
            raise InputError(f"a degree-{self.p} knot vector needs >= {2 * self.p + 2} knots")
        object.__setattr__(self, "knots", ks)

    @property
    def n(self) -> int:
        """Number of basis functions."""
        return len(self.knots) - self.p - 1

    def spans(self) -> list[int]:
        """Indices ``k`` of the non-empty spans ``[t_k, t_k+1)`` carrying p+1 functions."""
        t, p = self.knots, self.p
        return [k for k in range(p, self.n) if t[k + 1] > t[k]]

    def elements(self) -> list[tuple]:
        """The non-empty knot spans as ``(left, right)`` pairs."""
        return [(self.knots[k], self.knots[k + 1]) for k in self.spans()]

    def greville(self) -> list:
        """Greville abscissae :math:`(t_{i+1} + \\dots + t_{i+p}) / p`."""
        t, p = self.knots, self.p
        return [sum(t[i + 1:i + p + 1]) / p for i in range(self.n)]


#: Most spans of :func:`open_knot_vector`. The rule: about ten times the largest mesh a
#: command accepts (``dispersion impact --elements`` <= 100 000), and cheap to build: the
#: knots are exact rationals, 10**6 spans take 9 s and 0.3 GiB (measured, linear growth).
MAX_ELEMENTS = 10**6


def open_knot_vector(p: int, n_elements: int, a=0, b=1) -> KnotVector:
    """Open (clamped) uniform knot vector on ``[a, b]`` with ``n_elements`` spans.

    It carries ``p + n_elements`` basis functions; end knots have multiplicity p+1.
    ``n_elements`` lies in [1, ``MAX_ELEMENTS``].

    >>> open_knot_vector(1, 2).knots
    (0, 0, 1/2, 1, 1)
    """
    import sympy

    p = check_positive_int("degree p", p)
    n_elements = check_positive_int("number of elements", n_elements, maximum=MAX_ELEMENTS)
    from dispersion.reader import rational

    a, b = rational("interval end a", a), rational("interval end b", b)
    if not b > a:
        raise InputError(f"interval must have b > a, got [{a}, {b}]")
    inner = [a + (b - a) * sympy.Rational(i, n_elements) for i in range(1, n_elements)]
    return KnotVector(tuple([a] * (p + 1) + inner + [b] * (p + 1)), p)


def cardinal_knot_vector(p: int) -> KnotVector:
    """Uniform knots ``-p, ..., 2p+1``: basis function ``p`` is the cardinal B-spline on ``[0, p+1]``.

    The padding of p knots on either side makes every span of ``[0, p+1]`` extractable.
    Shifts of that function by integers span the uniform periodic spline space.
    """
    p = check_positive_int("degree p", p)
    return KnotVector(tuple(range(-p, 2 * p + 2)), p)


def insert_knot(kv: KnotVector, x) -> tuple[KnotVector, sympy.Matrix]:
    """Insert the knot ``x`` once (Boehm).

    Returns the new knot vector and the ``(n+1) x n`` matrix ``A`` mapping old control
    points to new ones, ``Q = A P``; the bases obey ``N_old = A^T N_new``.
    """
    import sympy

    from dispersion.reader import rational

    x = rational("knot x", x)
    t, p = kv.knots, kv.p
    if not t[p] <= x <= t[kv.n]:
        raise InputError(f"knot {x} lies outside the parameter range [{t[p]}, {t[kv.n]}]")
    k = max(i for i in range(p, kv.n) if t[i] <= x) if x < t[kv.n] else kv.n - 1
    A = sympy.zeros(kv.n + 1, kv.n)
    for i in range(kv.n + 1):
        if i <= k - p:
            A[i, i] = 1
        elif i >= k + 1:
            A[i, i - 1] = 1
        else:
            alpha = (x - t[i]) / (t[i + p] - t[i])
            A[i, i] = alpha
            A[i, i - 1] = 1 - alpha
    return KnotVector(t[:k + 1] + (x,) + t[k + 1:], p), A


def refine(kv: KnotVector, n_new: int) -> tuple[KnotVector, sympy.Matrix]:
    """Split every span into ``n_new`` equal parts by knot insertion; returns ``(kv, A)``."""
    import sympy

    n_new = check_positive_int("number of subdivisions", n_new)
    A = sympy.eye(kv.n)
    for a, b in kv.elements():
        for j in range(1, n_new):
            kv, Aj = insert_knot(kv, a + (b - a) * sympy.Rational(j, n_new))
            A = Aj * A
    return kv, A


def extraction_operators(kv: KnotVector) -> list[tuple[tuple, list[int], sympy.Matrix]]:
    """Bezier extraction: for each span, ``((left, right), active indices, C)``.

    ``C`` is ``(p+1) x (p+1)``; row ``a`` holds the Bernstein coefficients of the basis
    function with global index ``active[a]`` on that span.
    """
    import sympy

    p = kv.p
    new, T = kv, sympy.eye(kv.n)  # N_old = T N_new throughout
    for x in sorted(set(kv.knots[p:kv.n + 1])):
        while new.knots.count(x) < p:
            new, A = insert_knot(new, x)
            T = T * A.T
    out = []
    for k in new.spans():
        left, right = new.knots[k], new.knots[k + 1]
        k_old = max(i for i in kv.spans() if kv.knots[i] <= left)
        active = list(range(k_old - p, k_old + 1))
        out.append(((left, right), active, T[active, list(range(k - p, k + 1))]))
    return out


def bernstein(p: int, u: sympy.Symbol) -> list[sympy.Expr]:
    """Bernstein polynomials :math:`B_{b,p}(u)`, b = 0..p, on ``[0, 1]``."""
    return [comb(p, b) * u**b * (1 - u) ** (p - b) for b in range(p + 1)]


def bernstein_numeric(p: int, u, deriv: int = 0) -> np.ndarray:
    """Values (or ``deriv``-th derivatives w.r.t. u) of the Bernstein basis at points ``u``.

    Returns an array of shape ``u.shape + (p+1,)``.

    >>> bernstein_numeric(2, np.array([0.5])).tolist()
    [[0.25, 0.5, 0.25]]
    """
    u = np.asarray(u, dtype=float)
    if deriv > p:
        return np.zeros(u.shape + (p + 1,))
    q = p - deriv
    low = np.stack([comb(q, b) * u**b * (1 - u) ** (q - b) for b in range(q + 1)], axis=-1)
    # d^r/du^r B_{b,p} = p!/(p-r)! * sum_j (-1)^(r-j) C(r,j) B_{b-j,p-r}
    out = np.zeros(u.shape + (p + 1,))
    scale = 1
    for j in range(deriv):
        scale *= p - j
    for b in range(p + 1):
        for j in range(deriv + 1):
            if 0 <= b - j <= q:
                out[..., b] += (-1) ** (deriv - j) * comb(deriv, j) * low[..., b - j]
    return scale * out


def basis_polynomials(kv: KnotVector, x: sympy.Symbol, local: bool = True):
    """Element polynomials of the basis: list of ``((left, right), [N_a(x) for active a], active)``.

    With ``local=True`` the variable is the span coordinate u in [0, 1]; otherwise the
    global parameter x.
    """
    import sympy

    out = []
    for (left, right), active, C in extraction_operators(kv):
        u = x if local else (x - left) / (right - left)
        B = sympy.Matrix(bernstein(kv.p, u))
        out.append(((left, right), [sympy.expand(e) for e in C * B], active))
    return out


def cardinal_pieces(p: int, x: sympy.Symbol) -> list[sympy.Expr]:
    """Polynomial pieces of the cardinal B-spline of degree p on ``[j, j+1]``, j = 0..p, in local u.

    >>> import sympy
    >>> [str(e) for e in cardinal_pieces(1, sympy.Symbol("u"))]
    ['u', '1 - u']
    """
    kv = cardinal_knot_vector(p)
    pieces = {}
    for (left, _), polys, active in basis_polynomials(kv, x):
        if p in active and 0 <= left <= p:
            pieces[int(left)] = polys[active.index(p)]
    return [pieces[j] for j in range(p + 1)]


def as_fraction_matrix(C: sympy.Matrix) -> np.ndarray:
    """Extraction operator as an object array of ``fractions.Fraction`` (exact, numpy-friendly)."""
    return np.array([[Fraction(int(c.p), int(c.q)) for c in row] for row in C.tolist()], dtype=object)


@dataclass(frozen=True)
class UniformKnots:
    """Float open uniform knot vector: degree ``p``, ``n_elements`` equal spans of [a, b].

    What :class:`SplineBasis1D` reads of a knot vector (``p``, ``n``, ``knots``), without
    exact rationals (see :meth:`SplineBasis1D.uniform`).
    """

    p: int
    n_elements: int
    a: float = 0.0
    b: float = 1.0

    @property
    def n(self) -> int:
        """Number of basis functions."""
        return self.n_elements + self.p

    @property
    def knots(self) -> tuple[float, ...]:
        inner = [self.a + (self.b - self.a) * i / self.n_elements
                 for i in range(1, self.n_elements)]
        return tuple([float(self.a)] * (self.p + 1) + inner + [float(self.b)] * (self.p + 1))

    def greville(self) -> list[float]:
        """Greville abscissae :math:`(t_{i+1} + \\dots + t_{i+p}) / p` (floats)."""
        t, p = self.knots, self.p
        return [sum(t[i + 1:i + p + 1]) / p for i in range(self.n)]


def _cox_de_boor(knots: np.ndarray, p: int, span: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The p + 1 B-splines non-zero on knot span ``span`` at ``x`` (The NURBS Book, A2.2),
    vectorised over the last axes of ``span`` and ``x``; shape ``x.shape + (p + 1,)``."""
    N = [np.ones_like(x)] + [np.zeros_like(x) for _ in range(p)]
    left = [None] + [x - knots[span + 1 - j] for j in range(1, p + 1)]
    right = [None] + [knots[span + j] - x for j in range(1, p + 1)]
    for j in range(1, p + 1):
        saved = np.zeros_like(x)
        for r in range(j):
            temp = N[r] / (right[r + 1] + left[j - r])
            N[r] = saved + right[r + 1] * temp
            saved = left[j - r] * temp
        N[j] = saved
    return np.stack(N, axis=-1)


@dataclass(frozen=True)
class SplineBasis1D:
    """Float Bezier extraction of a knot vector: spans, active indices and operators ``C``.

    The numeric twin of :func:`extraction_operators` (the ring solver, the bar and the
    through-thickness mode shapes evaluate B-splines with it).

    >>> basis = SplineBasis1D.from_knots(open_knot_vector(2, 2))
    >>> active, N = basis.evaluate([0.0, 0.25, 1.0])
    >>> np.allclose(N.sum(axis=1), 1.0), active[1].tolist()      # partition of unity
    (True, [0, 1, 2])
    >>> np.allclose(SplineBasis1D.uniform(2, 2).C, basis.C)     # the float path agrees
    True
    """

    kv: KnotVector | UniformKnots
    spans: np.ndarray  # (n_el, 2) float [left, right]
    active: np.ndarray  # (n_el, p+1) int
    C: np.ndarray  # (n_el, p+1, p+1) float

    @classmethod
    def from_knots(cls, kv: KnotVector) -> SplineBasis1D:
        ops = extraction_operators(kv)
        spans = np.array([[float(a), float(b)] for (a, b), _, _ in ops])
        active = np.array([act for _, act, _ in ops], dtype=int)
        C = np.array([np.array(c.tolist(), dtype=float) for _, _, c in ops])
        return cls(kv, spans, active, C)

    @classmethod
    def uniform(cls, p: int, n_elements: int, a: float = 0.0, b: float = 1.0) -> SplineBasis1D:
        """The open uniform basis in floats: no sympy, cost linear in ``n_elements``.

        On each span the p + 1 non-zero B-splines (Cox-de Boor) are sampled at p + 1
        Chebyshev points and ``C`` solves :math:`N(u_k) = C B(u_k)` (the Bernstein matrix
        at those points is well conditioned for the degrees accepted here). Agrees with
        :meth:`from_knots` of :func:`open_knot_vector` to round-off (tested).
        """
        p = check_positive_int("degree p", p)
        n_elements = check_positive_int("number of elements", n_elements, maximum=MAX_ELEMENTS)
        if not b > a:
            raise InputError(f"interval must have b > a, got [{a}, {b}]")
        kv = UniformKnots(p, n_elements, float(a), float(b))
        knots = np.asarray(kv.knots)
        e = np.arange(n_elements)
        spans = np.column_stack([knots[p + e], knots[p + e + 1]])
        u = 0.5 - 0.5 * np.cos((2 * np.arange(p + 1) + 1) * np.pi / (2 * p + 2))
        x = spans[:, :1] + (spans[:, 1:] - spans[:, :1]) * u  # (n_el, p+1)
        N = _cox_de_boor(knots, p, (p + e)[:, None], x)  # (n_el, point k, function a)
        B = bernstein_numeric(p, u)  # (point k, bernstein b)
        C = np.linalg.solve(B[None], N).transpose(0, 2, 1)  # N_ka = B_kb C_ab
        active = e[:, None] + np.arange(p + 1)
        return cls(kv, spans, active, C)

    def element_of(self, x: np.ndarray) -> np.ndarray:
        """Index of the span holding each parameter value (the last span includes its end)."""
        x = np.asarray(x, dtype=float)
        e = np.searchsorted(self.spans[:, 1], x, side="right")
        return np.minimum(e, len(self.spans) - 1)

    def evaluate(self, x: np.ndarray, deriv: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """B-spline values (or first derivatives) at ``x``: ``(active (m, p+1), N (m, p+1))``."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        e = self.element_of(x)
        a, b = self.spans[e, 0], self.spans[e, 1]
        u = (x - a) / (b - a)
        B = bernstein_numeric(self.kv.p, u, deriv) / ((b - a) ** deriv)[:, None]
        return self.active[e], np.einsum("mab,mb->ma", self.C[e], B)
