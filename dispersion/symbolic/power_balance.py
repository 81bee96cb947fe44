"""Power-balance series of the dispersion branches through the origin (S0, A0).

A branch through the origin of a characteristic equation :math:`F(\\kappa^2, \\Omega^2) = 0`
is a power series :math:`\\Omega^2 = \\sum_{j \\ge \\sigma} a_j \\kappa^{2j}` with
:math:`\\sigma = 1` for S0 and :math:`\\sigma = 2` for A0. With :math:`t = \\kappa^2` and
:math:`\\Omega^2 = t^\\sigma w`, the lowest power of t in :math:`F(t, t^\\sigma w)` balances the
leading coefficient (a polynomial equation for :math:`w_0 = a_\\sigma`), and every further
power of t is linear in the next coefficient:

.. math::

    F(t, t^\\sigma w) = t^m Q(t, w), \\quad Q(0, w_0) = 0, \\quad
    w = w_0 + \\delta(t), \\quad \\delta = -\\frac{Q(t, w_0 + \\delta) - Q_w(0, w_0)\\,\\delta}
    {Q_w(0, w_0)}.

All algebra is exact and runs on python-flint (:mod:`dispersion.symbolic.series_kernel`): F is a
truncated power series in t whose coefficients are polynomials over QQ in (w, nu[, r]),
truncated after every product; the determinant is fraction-free elimination over truncated
series (cost polynomial in the matrix size, for every mass); the order-by-order solve is
division-free. sympy appears only at the edge, to hand out ``sympy.Expr`` coefficients.

For the discrete plate the characteristic function is :math:`\\det K_{dyn}` (paper eq 16),
split into its symmetric/antisymmetric block when the mass keeps the mirror symmetry; for the
exact plate it is the entire-function Rayleigh-Lamb equation, whose series
(:mod:`dispersion.continuum.exact_series`) uses :func:`solve_branch` of this module.

>>> discrete_series("S0", 4)[2]
-2/(nu - 1)

References
----------
F. A. Amirkulova, *Dispersion relations for elastic waves in plates and rods*, PhD thesis,
Rutgers University 2011 (method of power balance). A. Tkachuk et al., eqs (14)-(20).
"""
from __future__ import annotations

import math
from fractions import Fraction

import flint

from dispersion.symbolic import series_kernel as _k
from dispersion.errors import DispersionError, InputError, check_positive_int

__all__ = [
    "BRANCHES", "MAX_ORDER", "MAX_WORK", "check_request", "discrete_series",
    "discrete_series_raw", "format_coefficient", "solve_branch", "substitute_raw",
    "first_difference",
]

BRANCHES = {"S0": ("S", 1), "A0": ("A", 2)}


def __getattr__(name: str):
    # sympy symbols on demand: the flint path (exact_series_raw, the CLI's JSON) never
    # imports sympy
    if name in ("NU", "R_SYM"):  # defined once, by the reader of their names
        from dispersion.reader import symbols

        return symbols()["nu" if name == "NU" else "r"]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

#: Highest power of kappa accepted, per kind of request (see :func:`check_request`).
MAX_ORDER = {"exact": 128, "discrete": 32}
#: Largest matrix (2 n) of a discrete request times its order, see :func:`check_request`.
MAX_WORK = 12_000


def check_request(branch: str, order, exact: bool, n: int | None = None) -> tuple[str, int, int]:
    """Validate ``branch`` and ``order`` (and the size ``n``); raise :class:`InputError` early.

    The rule: a request that would take more than about a minute on a 2-core machine is
    refused. Measured (S0 + A0, whole process, nu symbolic, a shared 2-core machine):
    exact kappa^64 0.3 s / 32 MiB, kappa^96 1.0 s / 41 MiB, kappa^128 3.7 s / 64 MiB
    (before the univariate Horner route: 1.1 s, 5.9 s, 35 s), growing like order^4:
    exact orders <= 128 stay well inside the bound. Discrete, singular mass (the dearest):
    n = 12 kappa^8 7.3 s, n = 12 kappa^20 40 s / 184 MiB, n = 16 kappa^10 22 s / 176 MiB.
    Elimination costs (2n)^2 series products per row pivot and the product length grows with
    the order, so the discrete bound is
    (2n)^2 * order <= 12 000 (both measured cases inside it) and order <= 32. Memory stays far
    below the machine's 24 GiB in every case; time is the binding limit.

    >>> check_request("S0", 8, exact=True)
    ('S', 1, 8)
    """
    if branch not in BRANCHES:
        raise InputError(f"branch must be one of {', '.join(BRANCHES)}; got {branch!r}")
    kind, sigma = BRANCHES[branch]
    order = check_positive_int("order", order)
    if order % 2 or order < 2 * sigma:
        raise InputError(
            f"order (highest power of kappa) must be an even integer >= {2 * sigma} for {branch}, "
            f"got {order}")
    limit = MAX_ORDER["exact" if exact else "discrete"]
    if order > limit:
        raise InputError(f"order must be <= {limit} for the {'exact' if exact else 'discrete'} "
                         f"series (bounded time and memory), got {order}")
    if n is not None and (2 * n) ** 2 * order > MAX_WORK:
        raise InputError(f"control points n must satisfy (2n)^2 * order <= {MAX_WORK} "
                         f"(bounded time and memory), got n = {n}, order = {order}")
    return kind, sigma, order


def _to_expr(num, den, symbols: tuple, factor: bool = True):
    """num/den (fmpq_mpoly free of w) as a sympy expression; cancelled, factored by flint."""
    from sympy.core.mul import _keep_coeff
    import sympy

    g = num.gcd(den)
    if not g.is_one():
        num, den = num / g, den / g
    if not factor:
        return _poly_expr(num, symbols) / _poly_expr(den, symbols)
    cn, fn = _factored(num, symbols)
    cd, fd = _factored(den, symbols)
    return _keep_coeff(cn / cd, sympy.Mul(*fn, *(1 / f for f in fd)))


def _poly_expr(p, symbols):
    import sympy

    terms = []
    for mon, c in p.to_dict().items():
        term = sympy.Rational(int(c.p), int(c.q))
        for sym, e in zip(symbols, mon[1:]):
            if e:
                term *= sym**e
        terms.append(term)
    return sympy.Add(*terms)


def _primitive_factors(p) -> tuple[Fraction, list[tuple[object, int]]]:
    """Flint factorisation as (rational constant, [(primitive integer factor, power)])."""
    const, factors = p.factor()
    c = Fraction(int(const.p), int(const.q))
    out = []
    for f, e in factors:
        coeffs = list(f.to_dict().values())
        den = math.lcm(*(int(v.q) for v in coeffs))
        num = math.gcd(*(int(v.p) for v in coeffs))
        out.append((f * flint.fmpq(den, num), e))
        c *= Fraction(num, den) ** e
    return c, out


def _factored(p, symbols):
    import sympy

    c, factors = _primitive_factors(p)
    return sympy.Rational(c.numerator, c.denominator), \
        [_poly_expr(f, symbols) ** e for f, e in factors]


def format_coefficient(num, den) -> str:
    """``num/den`` as factored Python/sympy syntax, by flint alone (no sympy).

    >>> ctx = _k.context(("nu",))
    >>> nu = ctx.gens()[1]
    >>> format_coefficient(ctx.from_dict({}) + 2, 1 - nu)
    '-2/(nu - 1)'
    """
    g = num.gcd(den)
    if not g.is_one():
        num, den = num / g, den / g
    if num.is_zero():
        return "0"
    cn, fn = _primitive_factors(num)
    cd, fd = _primitive_factors(den)
    c = cn / cd

    def product(factors):
        parts = []
        for f, e in factors:
            text = str(f).replace("^", "**")
            if len(f.to_dict()) > 1:
                text = f"({text})"
            parts.append(text + (f"**{e}" if e > 1 else ""))
        return "*".join(parts)

    top, bottom = product(fn), product(fd)
    sign = "-" if c < 0 else ""
    c = abs(c)
    head = str(c.numerator) if (c.numerator != 1 or not top) else ""
    numerator = "*".join(x for x in (head, top) if x)
    if c.denominator != 1:
        bottom = f"{c.denominator}*{bottom}" if bottom else str(c.denominator)
    if not bottom:
        return sign + numerator
    if len(fd) + (c.denominator != 1) > 1:
        bottom = f"({bottom})"
    return f"{sign}{numerator}/{bottom}"


def substitute_raw(raw: list[tuple], name: str, value) -> list[tuple]:
    """Substitute a rational ``value`` for the parameter ``name`` in ``[(power, num, den)]``."""
    v = Fraction(value)
    v = flint.fmpq(v.numerator, v.denominator)
    out = []
    for k, a, b in raw:
        a, b = a.subs({name: v}), b.subs({name: v})
        if b.is_zero():
            raise InputError(f"{name} = {value} is a pole of the kappa^{k} coefficient")
        out.append((k, a, b))
    return out


def solve_branch(build, sigma: int, order: int, D0: int):
    """Coefficients (num, den) of the branch from ``build(D)`` = F mod t^(D+1).

    The generic engine: any characteristic function given as truncated series (the discrete
    patch here, the exact Rayleigh-Lamb equation in :mod:`dispersion.continuum.exact_series`).
    """
    N = order // 2 - sigma
    D = D0 + N
    while True:
        F = build(D)
        m = F.valuation()
        if m is None:
            if D > 8 * (N + 8):
                raise DispersionError(
                    "characteristic function vanishes identically near the origin")
            D *= 2
            continue
        if m + N <= D:
            return _k.branch_coefficients(F, N)
        D = m + N


# --------------------------------------------------------------------------- discrete plate


def _discrete_build(patch, block: str | None, sigma: int, ctx):
    """Return build(D) -> det(c (K - t^sigma w M)) over the chosen mirror block, c the scale
    that makes the law's moduli polynomials (:meth:`ElasticLaw.series_moduli`: 1 - 2 nu for
    the isotropic plate).

    The pencil is made even in kappa by the similarity diag(I, s I), which moves
    :math:`s^2 = t (s/\\kappa)^2` onto one off-diagonal block.
    """
    from dispersion.symbolic import plate as _plate

    gens = dict(zip(("w",) + _params(patch), ctx.gens()))
    w, r_gen = gens["w"], gens.get("r")
    one = ctx.from_dict({}) + 1
    mats, scale = patch.law.series_moduli(gens, one)
    if block is None:
        def project(B):
            return B
        nx, size = patch.n, 2 * patch.n
    else:
        E = _plate.mirror_bases(patch.n, exact=True)[block]
        nx = sum(1 for j in range(E.cols) if any(E[i, j] != 0 for i in range(patch.n)))
        size = E.cols

        def project(B):
            return E.T * B * E
    # interleave x and y unknowns: the matrix is banded, and elimination keeps the band
    xs, ys = list(range(nx)), list(range(nx, size))
    order = [v for pair in zip(xs, ys) for v in pair] + xs[len(ys):] + ys[len(xs):]
    is_x = [c < nx for c in order]

    def rows_of(B):
        R = _rational_rows(project(B))
        return [[R[i][j] for j in order] for i in order]

    terms = [(mats[m], f, rows_of(B)) for m, f, B in _plate.stiffness_terms(patch)]
    Mb = rows_of(_plate.mass_block(patch))
    zero = ctx.from_dict({})

    def r_power(e: int):
        if r_gen is not None:
            return r_gen ** e
        if patch.r is None:  # x-exact: no aspect ratio
            return 1
        r = flint.fmpq(int(patch.r.p), int(patch.r.q))
        return r**e

    def build(D):
        taylor = _plate.x_taylor(patch, D)
        xf = {}
        for name, pairs in taylor.items():
            coeffs = []
            for c, e in pairs:
                c = flint.fmpq(int(c.p), int(c.q))
                coeffs.append(zero if c == 0 else c * r_power(e) + zero)
            xf[name] = _k.Series(ctx, coeffs, D)
        t = _k.Series.gen_t(ctx, D)
        xf["s2"] = t * xf["s"] * xf["s"]
        mass = scale * (_k.Series(ctx, [0] * sigma + [w], D) * xf["mx"])
        rows = []
        for i in range(size):
            row = []
            for j in range(size):
                e = _k.Series(ctx, [], D)
                for mat, f, B in terms:
                    if not B[i][j]:
                        continue
                    if f == "s":
                        x = xf["s2"] if is_x[i] and not is_x[j] else None
                    else:
                        x = xf[f]
                    e = e + (x * (mat * B[i][j]) if x is not None else mat * B[i][j])
                if Mb[i][j]:
                    e = e - mass * Mb[i][j]
                row.append(e)
            rows.append(row)
        return _k.determinant(rows)

    return build


def _params(patch) -> tuple[str, ...]:
    """The symbols of the series ring after ``w``: the law's (nu), then r where symbolic."""
    import sympy

    return patch.law.series_parameters + (("r",) if isinstance(patch.r, sympy.Symbol) else ())


def _rational_rows(M) -> list[list]:
    return [[flint.fmpq(int(v.p), int(v.q)) if v else 0 for v in row] for row in M.tolist()]


def discrete_series_raw(branches=("S0",), order: int = 8, patch=None, *,
                        split: bool | None = None, **fields) -> tuple[dict[str, list[tuple]], tuple]:
    """``({branch: [(power of kappa, num, den)]}, params)``: the flint core of
    :func:`discrete_series`, for one or both branches.

    Without the mirror split, one determinant :math:`F_1(t, w) = \\det(K - t w M)` serves
    both branches: A0 (:math:`\\Omega^2 = t^2 w`) reads :math:`F_1(t, t w)`, i.e. the term
    :math:`t^k w^e` moves to :math:`t^{k+e}`, which truncation at :math:`t^D` keeps exact.
    """
    from dispersion.symbolic import plate as _plate
    from dispersion.symbolic.patch import as_patch

    if isinstance(branches, str):
        branches = (branches,)
    spec = as_patch(patch, **fields)  # checks the size first: p = 100, n = 101 names p
    checked = {b: check_request(b, order, exact=False, n=spec.n) for b in branches}
    patch = _plate.plate_patch(spec)
    if split is None:
        split = patch.symmetric
    elif split and not patch.symmetric:
        raise InputError("split=True needs a mass that keeps the mirror symmetry")
    params = _params(patch)
    ctx = _k.context(params)
    shared = None if split else _Shared(_discrete_build(patch, None, 1, ctx),
                                        order // 2 + 4)
    out = {}
    for branch, (kind, sigma, order) in checked.items():
        if split:
            build = _discrete_build(patch, kind, sigma, ctx)
        else:
            build = shared if sigma == 1 else (lambda D: _w_times_t(shared(D)))
        nums, dens = solve_branch(build, sigma, order, 2 + 2 * sigma)
        out[branch] = [(2 * (sigma + k), a, b) for k, (a, b) in enumerate(zip(nums, dens))]
    return out, params


class _Shared:
    """``build(D)`` computed once at the highest precision asked for, truncated on demand."""

    def __init__(self, build, D0: int):
        self.build, self.F = build, None
        self.D0 = D0

    def __call__(self, D: int):
        if self.F is None or self.F.D < D:
            self.F = self.build(max(D, self.D0))
        return _k.Series(self.F.ctx, self.F.coeffs[: D + 1], D)


def _w_times_t(F):
    """F(t, t w) from F(t, w), truncated at the same t^D."""
    out = [F.ctx.from_dict({}) for _ in range(F.D + 1)]
    for k, c in enumerate(F.coeffs):
        for mon, v in c.to_dict().items():
            if k + mon[0] <= F.D:
                out[k + mon[0]] += F.ctx.from_dict({mon: v})
    return _k.Series(F.ctx, out, F.D)


def discrete_series(
    branch: str = "S0",
    order: int = 8,
    patch=None,
    *,
    split: bool | None = None,
    factor: bool = True,
    **fields,
) -> dict:
    """Series of the discrete S0 / A0 branch of the plate patch (paper eqs 17-20).

    ``patch`` is a :class:`dispersion.symbolic.patch.Patch` (default: the toolkit's default patch), its
    fields may be given or replaced as keywords; ``order`` is the highest
    power of kappa. The patch's law decides the symbols: an isotropic plate's series is
    derived in nu and a numeric nu (the patch's, or ``nu=`` here: a field of the patch)
    substituted at the end; ``split``
    (default: whenever the mass keeps the mirror symmetry) works on the symmetric (S0) or
    antisymmetric (A0) block instead of the full determinant (a speed-up only: both give
    the same series); ``factor`` factors the output (flint, cheap).

    >>> discrete_series("A0", 6)[4]
    -2/(3*(nu - 1))
    """
    import sympy

    from dispersion.symbolic.patch import as_patch

    spec = as_patch(patch, **fields)
    raws, params = discrete_series_raw((branch,), order, spec, split=split)
    raw = raws[branch]
    symbols = tuple(sympy.Symbol(name, positive=True) if name == "r" else sympy.Symbol(name)
                    for name in params)
    return spec.law.substitute({k: _to_expr(a, b, symbols, factor) for k, a, b in raw})


def first_difference(a: dict, b: dict, upto: int | None = None) -> int | None:
    """Lowest power of kappa at which two series ``{power: coefficient}`` differ (None: none).

    Exact: the difference of the coefficients is cancelled over QQ(nu[, r]). ``upto`` ignores
    higher powers (a series derived further than asked).

    >>> from dispersion.continuum.exact_series import exact_series
    >>> first_difference(discrete_series("S0", 8, model="bloch", r=2), exact_series("S0", 8))
    6
    """
    import sympy

    from dispersion.reader import as_sympy

    for k in sorted(set(a) | set(b)):
        if upto is not None and k > upto:
            break
        if sympy.cancel(sympy.together(as_sympy(f"coefficient {k}", a.get(k, 0))
                                       - as_sympy(f"coefficient {k}", b.get(k, 0)))) != 0:
            return k
    return None
