"""Exact truncated power series in :math:`t = \\kappa^2` over QQ[w, params] (python-flint).

The kernel of :mod:`dispersion.symbolic.power_balance`. A series is a list of ``D + 1`` coefficients,
each a ``flint.fmpq_mpoly`` in the generators ``(w, *params)`` (``w`` stands for
:math:`\\Omega^2 / \\kappa^{2\\sigma}`); every product is truncated after :math:`t^D`.

Three algorithms, all polynomial in their sizes:

* :class:`Series` arithmetic (truncated Cauchy products; Horner evaluation of entire
  functions, :func:`entire`);
* :func:`determinant`: fraction-free (Bareiss) elimination over truncated series. A Bareiss
  division :math:`(a_{kk} a_{ij} - a_{ik} a_{kj}) / p` is exact in the polynomial ring, and
  the quotient's low coefficients depend only on the dividend's, so truncation is harmless
  as long as every pivot :math:`p` has a non-zero constant term. The pivot order is chosen
  once, at a generic rational point, on :math:`A(t = 0)`; the remaining ``m`` rows (the
  null space of :math:`A(0)`, e.g. the rigid translations) are finished by Sylvester's
  identity :math:`\\det A = \\det A^{(k)}_{\\text{trailing}} / p_k^{m-1}`.
* :func:`branch_coefficients`: the power-balance solve. With :math:`w = w_0 + y / a`,
  :math:`w_0 = -b/a` the simple root of the leading balance and :math:`\\rho` the linear
  coefficient in :math:`y`, the substitution :math:`y = \\rho\\, Y(t / \\rho^2)` turns the
  equation into :math:`Y = -\\sum \\tilde r_{kj} Y^j u^k` with polynomial coefficients: every
  order is one polynomial update, with no division at all. With one parameter (the exact series) the
  update runs on univariate ``fmpq_poly`` by Horner in Y (:func:`_horner_recurrence`); the
  ``fmpq_mpoly`` table of powers of Y (:func:`_power_recurrence`) is the reference route.

>>> ctx = context(("g",))
>>> t = Series.gen_t(ctx, 3)
>>> entire(t, "C").coeffs  # cos(sqrt t) = 1 - t/2 + t^2/24 - t^3/720
[1, -1/2, 1/24, -1/720]

References
----------
E. H. Bareiss, "Sylvester's identity and multistep integer-preserving Gaussian elimination",
Math. Comp. 22 (1968) 565-578. F. A. Amirkulova, PhD thesis, Rutgers 2011 (power balance).
"""
from __future__ import annotations

from fractions import Fraction
from math import factorial

import flint

from dispersion.errors import DispersionError

__all__ = ["Series", "branch_coefficients", "context", "determinant", "entire"]

#: A generic point for choosing pivots: any values at which the chosen minors do not vanish.
_GENERIC = (Fraction(3, 7), Fraction(11, 5), Fraction(5, 13))


def context(params: tuple[str, ...]):
    """The flint context of the coefficient polynomials: generators ``(w, *params)``."""
    return flint.fmpq_mpoly_ctx.get(("w",) + tuple(params), "lex")


class Series:
    """Truncated power series :math:`\\sum_{k \\le D} c_k t^k` with ``fmpq_mpoly`` coefficients."""

    __slots__ = ("ctx", "coeffs", "D")

    def __init__(self, ctx, coeffs, D: int):
        zero = ctx.from_dict({})
        coeffs = list(coeffs or [])[: D + 1]
        self.ctx, self.D = ctx, D
        self.coeffs = [c if isinstance(c, flint.fmpq_mpoly) else zero + c for c in coeffs] + \
            [zero] * (D + 1 - len(coeffs))

    @classmethod
    def constant(cls, ctx, c, D: int) -> Series:
        return cls(ctx, [c], D)

    @classmethod
    def gen_t(cls, ctx, D: int) -> Series:
        return cls(ctx, [0, 1], D)

    def _lift(self, other) -> Series:
        if isinstance(other, Series):
            return other
        return Series(self.ctx, [other], self.D)

    def __add__(self, other):
        other = self._lift(other)
        return Series(self.ctx, [a + b for a, b in zip(self.coeffs, other.coeffs)], self.D)

    __radd__ = __add__

    def __neg__(self):
        return Series(self.ctx, [-a for a in self.coeffs], self.D)

    def __sub__(self, other):
        return self + (-self._lift(other))

    def __rsub__(self, other):
        return self._lift(other) - self

    def __mul__(self, other):
        if not isinstance(other, Series):
            return Series(self.ctx, [a * other for a in self.coeffs], self.D)
        return Series(self.ctx, _mul(self.coeffs, other.coeffs, self.D), self.D)

    __rmul__ = __mul__

    def __truediv__(self, other):
        """Exact division by a polynomial (raises if a coefficient is not divisible)."""
        return Series(self.ctx, [a / other for a in self.coeffs], self.D)

    def __pow__(self, e: int):
        out = Series(self.ctx, [1], self.D)
        for _ in range(e):
            out = out * self
        return out

    def __eq__(self, other):
        return isinstance(other, Series) and self.coeffs == other.coeffs

    def __bool__(self):
        return any(not c.is_zero() for c in self.coeffs)

    def valuation(self) -> int | None:
        return next((k for k, c in enumerate(self.coeffs) if not c.is_zero()), None)


def _mul(a: list, b: list, D: int) -> list:
    ia = [(i, c) for i, c in enumerate(a) if not c.is_zero()]
    ib = [(j, c) for j, c in enumerate(b) if not c.is_zero()]
    out = [a[0] * 0 for _ in range(D + 1)]
    for i, x in ia:
        for j, y in ib:
            if i + j > D:
                break
            out[i + j] += x * y
    return out


def _div(a: list, p: list, D: int) -> list:
    """Exact series quotient a / p, p[0] != 0 (coefficients divided exactly by p[0])."""
    p0 = p[0]
    nz = [(i, c) for i, c in enumerate(p) if i and not c.is_zero()]
    q = []
    for k in range(D + 1):
        acc = a[k]
        for i, c in nz:
            if i > k:
                break
            acc = acc - q[k - i] * c
        q.append(acc / p0 if not acc.is_zero() else acc)
    return q


def entire(z: Series, kind: str) -> Series:
    """Horner evaluation of :math:`C(z) = \\cos\\sqrt z` (``"C"``) or :math:`S(z) =
    \\sin\\sqrt z/\\sqrt z` (``"S"``) at a series ``z`` with zero constant term."""
    if not z.coeffs[0].is_zero():
        raise DispersionError("entire functions are evaluated at series with zero constant term")
    out = Series(z.ctx, [], z.D)
    for j in range(z.D, -1, -1):
        den = factorial(2 * j) if kind == "C" else factorial(2 * j + 1)
        out = out * z + flint.fmpq((-1) ** j, den)
    return out


# --------------------------------------------------------------------------- determinant


def _at_generic(c) -> Fraction:
    """Value of the polynomial c at the generic point (w, *params) = _GENERIC."""
    point = [flint.fmpq(x.numerator, x.denominator) for x in _GENERIC[: c.context().nvars()]]
    value = c(*point)
    return Fraction(int(value.p), int(value.q))


def _pivot_order(A0: list[list[Fraction]]) -> tuple[list[int], int]:
    """Indices ordered so that the first ``k`` leading minors of A0 are non-zero; return k."""
    n = len(A0)
    S = [row[:] for row in A0]
    chosen: list[int] = []
    rest = list(range(n))
    while True:
        piv = next((i for i in rest if S[i][i] != 0), None)
        if piv is None:
            break
        chosen.append(piv)
        rest.remove(piv)
        for i in rest:
            f = S[i][piv] / S[piv][piv]
            if f:
                for j in rest:
                    S[i][j] -= f * S[piv][j]
    return chosen + rest, len(chosen)


def determinant(rows: list[list[Series]]) -> Series:
    """:math:`\\det A` of a square matrix of truncated series, by fraction-free elimination.

    Cost :math:`O(n^3)` series products (no Laplace expansion). The null space of
    :math:`A(t=0)` is left to the end and finished by Sylvester's identity.
    """
    n = len(rows)
    if n == 0:
        raise DispersionError("empty characteristic matrix")
    ctx, D = rows[0][0].ctx, rows[0][0].D
    A0 = [[_at_generic(rows[i][j].coeffs[0]) for j in range(n)] for i in range(n)]
    order, k = _pivot_order(A0)
    a = [[list(rows[i][j].coeffs) for j in order] for i in order]
    nonzero = [[any(not c.is_zero() for c in x) for x in row] for row in a]
    zero = ctx.from_dict({})
    pivots = [[zero + 1] + [zero] * D]  # pivots[s] = leading minor of order s
    level = [0] * n  # row i holds its Bareiss level-`level[i]` entries (lazy row scaling)

    def lift(i: int, s: int) -> None:
        # a row untouched since level l is the level-s row times p_s / p_l (exact division)
        if level[i] != s:
            for j in range(s, n):
                if nonzero[i][j]:
                    a[i][j] = _div(_mul(a[i][j], pivots[s], D), pivots[level[i]], D)
            level[i] = s

    for s in range(k):
        lift(s, s)
        piv, prev = a[s][s], pivots[s]
        for i in range(s + 1, n):
            if not nonzero[i][s]:
                continue  # not coupled to the pivot row: scaled lazily (banded matrices)
            lift(i, s)
            ais = a[i][s]
            for j in range(s + 1, n):
                if nonzero[s][j]:
                    x = _mul(ais, a[s][j], D)
                    if nonzero[i][j]:
                        x = [u - v for u, v in zip(_mul(piv, a[i][j], D), x)]
                    else:
                        x = [-v for v in x]
                elif nonzero[i][j]:
                    x = _mul(piv, a[i][j], D)
                else:
                    continue
                a[i][j] = _div(x, prev, D)
                nonzero[i][j] = any(not c.is_zero() for c in a[i][j])
            level[i] = s + 1
        pivots.append(piv)
    for i in range(k, n):
        lift(i, k)
    m = n - k
    if m == 0:  # A(0) is regular: the last pivot is the determinant
        return Series(ctx, pivots[n], D)
    trailing = [[a[i][j] for j in range(k, n)] for i in range(k, n)]
    det = _cofactor(trailing, D)
    for _ in range(m - 1):
        det = _div(det, pivots[k], D)
    return Series(ctx, det, D)


def _cofactor(rows: list[list[list]], D: int) -> list:
    """Laplace expansion along the first row (used for the small trailing block only)."""
    n = len(rows)
    if n == 1:
        return rows[0][0]
    total = None
    for j in range(n):
        minor = [r[:j] + r[j + 1:] for r in rows[1:]]
        term = _mul(rows[0][j], _cofactor(minor, D), D)
        if j % 2:
            term = [-c for c in term]
        total = term if total is None else [u + v for u, v in zip(total, term)]
    return total


# --------------------------------------------------------------------------- branch solve


def branch_coefficients(F: Series, N: int, univariate: bool | None = None) -> tuple[object, list]:
    """Solve :math:`F(t, w) = t^m Q(t, w) = 0` for :math:`w = w_0 + \\sum_{k \\ge 1} w_k t^k`.

    ``F.coeffs`` are polynomials in ``(w, *params)``; ``F.D`` must reach ``m + N``.
    Returns ``(den, [num_0, ..., num_N])`` as ``fmpq_mpoly`` in the same context (``w``
    absent) with :math:`w_k = \\text{num}_k / \\text{den}_k`, ``den`` a list of denominators.
    ``univariate``: with one parameter, work on ``fmpq_poly`` by Horner in Y (the fast route,
    default); ``False`` keeps ``fmpq_mpoly`` and the table of powers of Y throughout (the
    reference route, same coefficients).
    """
    m = F.valuation()
    if m is None:
        raise DispersionError("characteristic function vanishes identically near the origin")
    if m + N > F.D:
        raise DispersionError(f"series precision t^{F.D} too low for t^{m + N}")
    Q = F.coeffs[m: m + N + 1]
    ctx = F.ctx
    w0num, w0den = _leading_root(Q[0])
    a, b = w0den, -w0num  # w0 = -b / a
    # R_k(y) = a^E Q_k((y - b) / a), E = max w-degree: polynomial in (y, params) with y = a delta.
    # With one parameter every coefficient below is univariate (w is absent): the work runs
    # on fmpq_poly, whose products are several times cheaper than fmpq_mpoly's, and the
    # results are mapped back exactly (the same coefficients, another representation).
    uni = ctx.nvars() == 2 and univariate is not False
    R = _shifted_uni(Q, a, b) if uni else _shifted(Q, a, b)
    r0 = R[0]
    if r0.get(0) is not None and not r0[0].is_zero():
        raise DispersionError("internal: leading balance not solved by its root")
    rho = r0.get(1)
    if rho is None or rho.is_zero():
        raise DispersionError("the branch is not a simple root at the origin; cannot isolate it")
    if uni:
        return _solve_uni(R, rho, N, ctx, a, w0num)
    # Y = -sum_{(k,j) != (0,1)} r_kj rho^(j + 2k - 2) Y^j u^k, Y = sum_{k>=1} z_k u^k
    zero = rho * 0
    rp = _powers(rho)
    coef = {}
    for k, rk in enumerate(R):
        for j, c in rk.items():
            if (k, j) == (0, 1) or c.is_zero():
                continue
            if k == 0 and j < 2:
                continue
            coef[(k, j)] = c * rp(j + 2 * k - 2)
    z = _power_recurrence(coef, N, zero)
    nums = [w0num] + [z[k] for k in range(1, N + 1)]
    return nums, [a] + [a * rp(2 * k - 1) for k in range(1, N + 1)]


def _powers(base):
    """``e -> base**e`` (e >= 0), each power formed once from the one below it."""
    table = {0: base * 0 + 1}

    def power(e: int):
        for k in range(len(table), e + 1):
            table[k] = table[k - 1] * base
        return table[e]

    return power


#: Scalings y = rho'^p Y, t = rho'^q u tried by the fast route, cheapest first; the last one
#: always gives polynomial coefficients.
_SCALINGS = ((0, 0), (1, 0), (0, 1), (1, 1), (1, 2))


def _solve_uni(R: list[dict], rho, N: int, ctx, a, w0num) -> tuple[list, list]:
    """The fast route of :func:`branch_coefficients` (one parameter x, ``fmpq_poly``).

    Over QQ[x] a constant is a unit: with rho = L rho' (rho' monic) the substitution
    y = rho'^p Y, t = rho'^q u and the equation divided by L rho'^(p + 1) give
    Y = -sum r_kj rho'^(p (j - 1) + q k - 1) / L Y^j u^k. (p, q) = (1, 2) always has
    polynomial coefficients; a smaller scaling is taken when every coefficient with a
    negative power of rho' is exactly divisible by it (checked, exact division), which keeps
    the factors rho'^(2k) out of the z_k (for the Rayleigh-Lamb series, rho' = g - 1 divides
    them all). Then w_k = rho'^p z_k / (a rho'^(q k)).
    """
    lead = rho.coeffs()[-1]
    rho = rho / lead
    zero = rho * 0
    rp = _powers(rho)

    terms = [(k, j, c) for k, rk in enumerate(R) for j, c in rk.items()
             if not c.is_zero() and (k, j) != (0, 1) and not (k == 0 and j < 2)]
    for p, q in _SCALINGS:
        coef = {}
        for k, j, c in terms:
            e = p * (j - 1) + q * k - 1
            if e >= 0:
                coef[(k, j)] = c * rp(e) / lead
                continue
            quo, rem = divmod(c, rp(-e))
            if not rem.is_zero():
                break
            coef[(k, j)] = quo / lead
        else:
            break
    z = _horner_recurrence(coef, N, zero)
    a_ = _to_uni(a)
    nums = [w0num] + [_from_uni(ctx, rp(p) * z[k]) for k in range(1, N + 1)]
    dens = [a] + [_from_uni(ctx, a_ * rp(q * k)) for k in range(1, N + 1)]
    return nums, dens


def _shifted(Q: list, a, b) -> list[dict]:
    """``[{j: [y^j] a^E Q_k((y - b) / a)}]`` over (y, *params) (``fmpq_mpoly``, y in w's place)."""
    ctx = a.context()
    E = max(q.degrees()[0] for q in Q)
    y = ctx.gens()[0]
    a_pows = [ctx.from_dict({}) + 1]
    for _ in range(E):
        a_pows.append(a_pows[-1] * a)
    shift = y - b
    R = []
    for q in Q:
        by_e: dict[int, object] = {}
        for mon, c in q.to_dict().items():
            rest = ctx.from_dict({(0,) + tuple(mon[1:]): c})
            by_e[mon[0]] = by_e.get(mon[0], 0) + rest
        acc = ctx.from_dict({})
        for e in range(E, -1, -1):  # Horner in w: sum_e c_e (y - b)^e a^(E - e)
            acc = acc * shift
            if e in by_e:
                acc += by_e[e] * a_pows[E - e]
        R.append(_by_power(acc))
    return R


def _shifted_uni(Q: list, a, b) -> list[dict]:
    """:func:`_shifted` for one parameter x: ``{j: fmpq_poly in x}`` (same coefficients)."""
    E = max(q.degrees()[0] for q in Q)
    A, B = _to_uni(a), _to_uni(b)
    zero = flint.fmpq_poly(0)
    a_pows = [zero + 1]
    for _ in range(E):
        a_pows.append(a_pows[-1] * A)
    R = []
    for q in Q:
        by_e: dict[int, dict] = {}
        for (e, i), c in q.to_dict().items():
            by_e.setdefault(e, {})[i] = c
        acc: list = []  # coefficients of y^0, y^1, ...
        for e in range(E, -1, -1):  # Horner in w: sum_e c_e (y - b)^e a^(E - e)
            new = [zero] * (len(acc) + 1)
            for j, c in enumerate(acc):  # acc * (y - b)
                if not c.is_zero():
                    new[j + 1] += c
                    new[j] -= c * B
            acc = new
            if e in by_e:
                acc[0] += _poly(by_e[e]) * a_pows[E - e]
        R.append({j: c for j, c in enumerate(acc) if not c.is_zero()})
    return R


def _poly(terms: dict):
    """``fmpq_poly`` with the coefficients ``{power: value}``."""
    out = [flint.fmpq(0)] * (max(terms) + 1)
    for i, v in terms.items():
        out[i] = v
    return flint.fmpq_poly(out)


def _to_uni(c):
    """A polynomial in (w, x) free of w as an ``fmpq_poly`` in x."""
    terms = {mon[1]: v for mon, v in c.to_dict().items()}
    return _poly(terms) if terms else flint.fmpq_poly(0)


def _from_uni(ctx, p):
    """Inverse of :func:`_to_uni`: an ``fmpq_poly`` in x as a polynomial in (w, x)."""
    return ctx.from_dict({(0, i): v for i, v in enumerate(p.coeffs()) if v != 0})


def _horner_recurrence(coef: dict, N: int, zero) -> list:
    """:func:`_power_recurrence` by Horner in Y, order by order (the fast route).

    With A_j(u) = sum_k c_kj u^k, H_jmax = A_jmax and H_j = A_j + Y H_(j+1), the equation is
    Y = -H_0. [u^i] H_j needs z_1 .. z_i and [u^(< i)] H_(j+1) only (Y has no constant
    term, and [u^0] H_1 = 0), so every entry is one sum of products z_l [u^(i-l)] H_(j+1) and
    no coefficient c_kj is multiplied at all. [u^i] H_j reaches u^N in H_0 only for
    i <= N - j.
    """
    jmax = max((j for _, j in coef), default=0)
    A = [[zero] * (N + 1) for _ in range(jmax + 2)]
    for (k, j), c in coef.items():
        if k <= N:
            A[j][k] = c
    # H[j][i], i <= N - j; H[jmax + 1] = 0
    H = [[None] * (N + 1) for _ in range(jmax + 2)]
    H[jmax + 1] = [zero] * (N + 1)
    for j in range(1, jmax + 1):
        H[j][0] = A[j][0]
    z = [zero] * (N + 1)
    for kk in range(1, N + 1):
        i = kk - 1  # H_j[kk - 1] for j >= 1 uses z_1 .. z_(kk-1)
        if i >= 1:
            for j in range(jmax, 0, -1):
                if i > N - j:
                    continue
                nxt = H[j + 1]
                acc = A[j][i]
                for l in range(1, i + 1):
                    h = nxt[i - l]
                    if h is not None and not z[l].is_zero() and not h.is_zero():
                        acc = acc + z[l] * h
                H[j][i] = acc
        acc = A[0][kk]
        for l in range(1, kk):
            h = H[1][kk - l]
            if h is not None and not h.is_zero():
                acc = acc + z[l] * h
        z[kk] = -acc
    return z


def _power_recurrence(coef: dict, N: int, zero) -> list:
    """``[z_0 = 0, z_1, ..., z_N]`` of Y = sum z_k u^k solving Y = -sum c_kj Y^j u^k."""
    jmax = max((j for _, j in coef), default=0)
    # P[j][i] = [u^i] Y^j, needed for i <= need[j] only: by c_kj P[j][kk - k] (kk <= N) and
    # by P[j + 1][i + 1] (the terms w^j of an exact branch come with high powers of t, so
    # the high powers of Y are needed to low order only: most products are skipped)
    need = [0] * (jmax + 2)
    for j in range(jmax, 0, -1):
        kmin = min((k for k, jj in coef if jj == j), default=None)
        need[j] = max(N - kmin if kmin is not None else -1, need[j + 1] - 1)
    P = [[zero + 1] + [zero] * N] + [[zero] * (N + 1) for _ in range(jmax)]
    z = [zero] * (N + 1)
    for kk in range(1, N + 1):
        for j in range(2, jmax + 1):  # [u^kk] Y^j uses z_1 .. z_(kk-1) only
            if kk > need[j]:
                continue
            P[j][kk] = sum((z[l] * P[j - 1][kk - l] for l in range(1, kk - j + 2)), zero)
        acc = zero
        for (k, j), c in coef.items():
            if k <= kk and not P[j][kk - k].is_zero():
                acc += c * P[j][kk - k]
        z[kk] = -acc
        P[1][kk] = z[kk]
    return z


def _by_power(p) -> dict[int, object]:
    """Split a polynomial in (w, *params) by its power of w."""
    ctx = p.context()
    out: dict[int, object] = {}
    for mon, c in p.to_dict().items():
        out.setdefault(mon[0], []).append(((0,) + tuple(mon[1:]), c))
    return {e: ctx.from_dict(dict(terms)) for e, terms in out.items()}


def _leading_root(q0) -> tuple[object, object]:
    """The unique non-zero simple root w0 = num / den of q0(w) = 0 (num, den free of w)."""
    _, factors = q0.factor()
    roots = []
    for f, mult in factors:
        if f.degrees()[0] != 1:
            continue
        parts = _by_power(f)
        a1, a0 = parts[1], parts.get(0)
        if a0 is None or a0.is_zero():
            continue  # the trivial root w = 0
        roots.append((-a0, a1, mult))
    if len(roots) != 1 or roots[0][2] != 1:
        raise DispersionError(f"leading balance {q0} = 0 has no unique simple non-zero root")
    return roots[0][0], roots[0][1]
