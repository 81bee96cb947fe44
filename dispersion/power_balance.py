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

All algebra is exact: F is built as a sparse polynomial over QQ in (t, w, nu[, r]) truncated
in t after every product (sympy ``PolyRing``, flint ground types), the determinant by Laplace
expansion over column subsets (n 2^(n-1) products, no division), and the order-by-order
solve in the rational function field QQ(nu[, r]).

For the discrete plate the characteristic function is :math:`\\det K_{dyn}` (paper eq 16),
split into its symmetric/antisymmetric block when the mass keeps the mirror symmetry; for the
exact plate it is the entire-function Rayleigh-Lamb equation of :mod:`dispersion.rayleigh_lamb`.

>>> nu = sympy.Symbol("nu")
>>> exact_series("S0", 4)[2]
-2/(nu - 1)

References
----------
F. A. Amirkulova, *Dispersion relations for elastic waves in plates and rods*, PhD thesis,
Rutgers University 2011 (method of power balance). A. Tkachuk et al., eqs (14)-(20).
"""
from __future__ import annotations

from dataclasses import dataclass
from math import factorial

import sympy
from sympy import QQ
from sympy.polys.fields import field as _field
from sympy.polys.rings import ring as _ring

from . import plate as _plate
from .errors import DispersionError, InputError, check_nu, check_positive_int
from .rayleigh_lamb import frequency_function

__all__ = [
    "BRANCHES", "discrete_series", "exact_series", "exact_leading_balance",
    "series_from_characteristic",
]

BRANCHES = {"S0": ("S", 1), "A0": ("A", 2)}
NU = sympy.Symbol("nu")
R_SYM = sympy.Symbol("r", positive=True)
_G = sympy.Symbol("g")


@dataclass(frozen=True)
class _Setup:
    """Series ring (t, w, *params) over QQ and the images of params in the field QQ(nu[, r])."""

    ring: object
    field: object
    images: tuple  # field elements that the params generators stand for
    symbols: tuple  # sympy symbols of the field generators


def _setup(params: tuple[str, ...], field_symbols: tuple[sympy.Symbol, ...], images) -> _Setup:
    R = _ring(",".join(("t", "w") + params), QQ)[0]
    F, *gens = _field(",".join(str(s) for s in field_symbols), QQ)
    return _Setup(R, F, tuple(images(*gens)), field_symbols)


def _trunc(f, D: int):
    """Drop every term of degree > D in t (the first generator)."""
    if all(m[0] <= D for m in f.itermonoms()):
        return f
    return f.ring({m: c for m, c in f.items() if m[0] <= D})


def _det(rows: list[list], D: int):
    """Determinant by Laplace expansion over column subsets, truncated at t^D."""
    n = len(rows)
    if n == 0:
        raise DispersionError("empty characteristic matrix")
    minors = {0: rows[0][0].ring.one}
    for i in range(n):
        nxt = {}
        for mask, val in minors.items():
            for j in range(n):
                if mask >> j & 1 or not rows[i][j]:
                    continue
                term = _trunc(val * rows[i][j], D)
                if bin(mask >> (j + 1)).count("1") % 2:
                    term = -term
                key = mask | (1 << j)
                nxt[key] = nxt[key] + term if key in nxt else term
        minors = nxt
    return minors.get((1 << n) - 1, rows[0][0].ring.zero)


def _balance(build, N: int, setup: _Setup) -> list[dict]:
    """Coefficients Q_k(w), k = 0..N, of F(t, t^sigma w) = t^m sum_k Q_k(w) t^k, in the field."""
    D = N + 2
    while True:
        F = build(D)
        if not F:
            if D > 8 * (N + 8):
                raise DispersionError("characteristic function vanishes identically near the origin")
            D *= 2
            continue
        m = min(mon[0] for mon in F.itermonoms())
        if m + N <= D:
            break
        D = m + N
    K = setup.field
    Q = [dict() for _ in range(N + 1)]
    for mon, c in F.items():
        k = mon[0] - m
        if k > N:
            continue
        val = c if getattr(c, "field", None) == K else K(c)
        for img, e in zip(setup.images, mon[2:]):
            if e:
                val *= img**e
        Q[k][mon[1]] = Q[k].get(mon[1], K.zero) + val
    return Q


def series_from_characteristic(build, sigma: int, order: int, setup: _Setup,
                               factor: bool = True) -> dict[int, sympy.Expr]:
    """Solve ``build(D) = F(t, t^sigma w) mod t^(D+1) = 0`` for the branch Omega^2 ~ kappa^(2 sigma).

    ``build(D)`` returns F as an element of ``setup.ring`` truncated at t^D. Returns
    ``{power of kappa: coefficient}`` up to kappa^order.
    """
    N = order // 2 - sigma  # corrections beyond the leading coefficient
    Q = _balance(build, N, setup)
    K = setup.field
    w0 = _leading_root(Q[0], setup)
    # Taylor shift at w0: Qs[j][k] = [delta^j t^k] Q(t, w0 + delta)
    deg = max((max(q) for q in Q if q), default=0)
    Qs = [[K.zero] * (N + 1) for _ in range(deg + 1)]
    w0_pows = [K.one]
    for _ in range(deg):
        w0_pows.append(w0_pows[-1] * w0)
    for k, q in enumerate(Q):
        for e, c in q.items():
            for j in range(e + 1):
                Qs[j][k] += c * sympy.binomial(e, j) * w0_pows[e - j]
    q1 = Qs[1][0] if deg >= 1 else K.zero
    if q1 == 0:
        raise DispersionError("the branch is not a simple root at the origin; cannot isolate it")
    delta = [K.zero] * (N + 1)

    def mul(a, b):
        return [sum((a[i] * b[k - i] for i in range(k + 1)), K.zero) for k in range(N + 1)]

    for _ in range(N):
        # evaluate sum_j Qs[j](t) delta^j, excluding the linear constant q1*delta
        total = list(Qs[0])
        power = [K.one] + [K.zero] * N
        for j in range(1, deg + 1):
            power = mul(power, delta)
            total = [a + b for a, b in zip(total, mul(Qs[j], power))]
        delta = [K.zero] + [delta[k] - total[k] / q1 for k in range(1, N + 1)]
    coeffs = [w0] + delta[1:]
    return {2 * (sigma + k): _to_expr(c, setup, factor) for k, c in enumerate(coeffs)}


def _to_expr(c, setup: _Setup, factor: bool = True) -> sympy.Expr:
    expr = c.as_expr(*setup.symbols)
    return sympy.factor(expr) if factor else expr


def _leading_root(q0: dict, setup: _Setup):
    """The unique non-zero simple root w0 of the leading balance q0(w) = 0, in the field."""
    w = sympy.Dummy("w")
    expr = sum(c.as_expr(*setup.symbols) * w**e for e, c in q0.items())
    num = sympy.numer(sympy.together(expr))
    roots = []
    for fac, mult in sympy.factor_list(num, w)[1]:
        if sympy.degree(fac, w) == 1:
            root = sympy.cancel(sympy.solve(fac, w)[0])
            if root != 0:
                roots.append((root, mult))
    if len(roots) != 1 or roots[0][1] != 1:
        raise DispersionError(
            f"leading balance {sympy.factor(num)} = 0 has no unique simple non-zero root")
    return setup.field.from_expr(roots[0][0])


def _check_order(branch: str, order) -> tuple[str, int, int]:
    if branch not in BRANCHES:
        raise InputError(f"branch must be one of {', '.join(BRANCHES)}; got {branch!r}")
    kind, sigma = BRANCHES[branch]
    order = check_positive_int("order", order)
    if order % 2 or order < 2 * sigma:
        raise InputError(
            f"order (highest power of kappa) must be an even integer >= {2 * sigma} for {branch}, "
            f"got {order}")
    return kind, sigma, order


def _substitute_nu(series: dict, nu) -> dict:
    if nu is None:
        return series
    nu = check_nu(sympy.nsimplify(nu) if isinstance(nu, float) else nu)
    return {k: sympy.factor(v.subs(NU, nu)) for k, v in series.items()}


# --------------------------------------------------------------------------- exact plate

def _entire_series(z, kind: str, D: int):
    """Truncated series of C(z) = cos(sqrt z) ("C") or S(z) = sin(sqrt z)/sqrt z ("S")."""
    out, power = z.ring.zero, z.ring.one
    for j in range(D + 1):
        den = factorial(2 * j) if kind == "C" else factorial(2 * j + 1)
        out += power * QQ((-1) ** j, den)
        power = _trunc(power * z, D)
        if not power:
            break
    return out


def exact_series(branch: str, order: int, nu=None, form: str = "standard") -> dict[int, sympy.Expr]:
    """Series of the exact Rayleigh-Lamb branch S0 or A0 (paper eqs 14-15) to kappa^order.

    The characteristic function is :func:`dispersion.rayleigh_lamb.frequency_function` itself,
    evaluated on truncated power series over QQ(nu). ``form="printed"`` uses eq (13) as
    printed; it has no such branch and raises :class:`DispersionError`.

    >>> exact_series("A0", 6, nu=0)
    {4: 2/3, 6: -34/45}
    """
    kind, sigma, order = _check_order(branch, order)
    if nu is not None:
        check_nu(nu)
    setup, build = _exact_characteristic(kind, sigma, form)
    series = series_from_characteristic(build, sigma, order, setup, factor=False)
    g_of_nu = (1 - 2 * NU) / (2 * (1 - NU))
    series = {k: sympy.factor(v.subs(_G, g_of_nu)) for k, v in series.items()}
    return _substitute_nu(series, nu)


def _exact_characteristic(kind: str, sigma: int, form: str):
    # Work over QQ[g] with g = (c_T/c_L)^2 = (1 - 2 nu)/(2 (1 - nu)): polynomial arithmetic
    # only; the map nu <-> g is an involution, so nu = (1 - 2 g)/(2 (1 - g)) at the end.
    setup = _setup(("g",), (_G,), lambda g: (g,))
    t, w, g = setup.ring.gens

    def build(D):
        C = lambda z: _entire_series(z, "C", D)
        S = lambda z: _entire_series(z, "S", D)
        return _trunc(frequency_function(kind, t, t**sigma * w, None, C, S, form, ratio=g), D)

    return setup, build


def exact_leading_balance(branch: str, form: str = "standard") -> sympy.Expr:
    """Leading balance q0(w) of the Rayleigh-Lamb equation for Omega^2 = w kappa^(2 sigma).

    Its non-zero roots are the admissible leading coefficients; used by the errata to show
    that the printed eq (13) has no A0 branch and a wrong S0 speed.

    >>> sympy.factor(exact_leading_balance("S0"))
    w*(nu*w - w + 2)/(nu - 1)
    """
    kind, sigma, _ = _check_order(branch, 2 * BRANCHES[branch][1])
    setup, build = _exact_characteristic(kind, sigma, form)
    q0 = _balance(build, 0, setup)[0]
    w = sympy.Symbol("w")
    expr = sum(c.as_expr(_G) * w**e for e, c in q0.items())
    return sympy.factor(expr.subs(_G, (1 - 2 * NU) / (2 * (1 - NU))))


# --------------------------------------------------------------------------- discrete plate

def _x_series(patch, setup: _Setup, D: int) -> dict:
    """Per-unit-length x-functions m, s^2 / kappa^2 ... as truncated series in t = kappa^2.

    Returns ``{"m", "s2", "d", "mx"}`` where ``s2 = s^2`` (the pencil is made even in kappa
    by the similarity diag(I, s I), which moves s^2 onto one off-diagonal block).
    """
    R = setup.ring
    t = R.gens[0]
    if patch.model == "x-exact":
        out = {"m": R.one, "s2": t, "d": t}
    else:
        c = _plate.bloch_coefficients(patch.p)
        r = R.gens[-1] if isinstance(patch.r, sympy.Symbol) else QQ(int(patch.r.p), int(patch.r.q))
        m, sig, d = R.zero, R.zero, R.zero
        for k in range(D + 1):
            tk = t**k * (-1) ** k
            m += tk * r ** (2 * k) * _rat(sum(v * L ** (2 * k) for L, v in c["00"].items())
                                          / factorial(2 * k))
            sig += tk * r ** (2 * k) * _rat(-2 * sum(c["10"][L] * L ** (2 * k + 1)
                                                      for L in range(1, patch.p + 1))
                                            / factorial(2 * k + 1))
            if k >= 1:
                d += tk * r ** (2 * k - 2) * _rat(sum(v * L ** (2 * k) for L, v in c["11"].items())
                                                  / factorial(2 * k))
        out = {"m": m, "s2": _trunc(t * _trunc(sig * sig, D), D), "d": d}
    out["mx"] = R.one if patch.x_lumped else out["m"]
    return out


def _rat(x) -> object:
    x = sympy.Rational(x)
    return QQ(int(x.p), int(x.q))


def _exact_matrix(M: sympy.Matrix, R) -> list[list]:
    return [[R(_rat(v)) if v != 0 else R.zero for v in M.row(i)] for i in range(M.rows)]


def _discrete_characteristic(patch, block: str | None, sigma: int, setup: _Setup):
    """Return build(D) -> det((1-2nu)(K - t^sigma w M)) over the chosen mirror block."""
    R = setup.ring
    t, w, nu = R.gens[:3]
    mats = {"L2M": 2 * (1 - nu), "M": 1 - 2 * nu, "L": 2 * nu}  # times (1 - 2 nu)
    n2 = 2 * patch.n
    if block is None:
        E, nx = sympy.eye(n2), patch.n
    else:
        E = _basis_exact(patch.n, block)
        nx = sum(1 for j in range(E.cols) if any(E[i, j] != 0 for i in range(patch.n)))
    terms = [(mats[m], f, _exact_matrix(E.T * B * E, R)) for m, f, B in _plate.stiffness_terms(patch)]
    Mb = _exact_matrix(E.T * _plate.mass_block(patch) * E, R)
    size = E.cols

    def build(D):
        xf = _x_series(patch, setup, D)
        W = t**sigma * w
        rows = [[R.zero] * size for _ in range(size)]
        for i in range(size):
            for j in range(size):
                e = R.zero
                for mat, f, B in terms:
                    if not B[i][j]:
                        continue
                    if f == "s":
                        x = xf["s2"] if (i < nx <= j) else R.one
                    else:
                        x = xf[f]
                    e += mat * B[i][j] * x
                if Mb[i][j]:
                    e -= (1 - 2 * nu) * W * Mb[i][j] * xf["mx"]
                rows[i][j] = _trunc(e, D)
        return _det(rows, D)

    return build


def _basis_exact(n: int, block: str) -> sympy.Matrix:
    """Unnormalised integer mirror basis (columns e_i +- e_(n-1-i)); same span as mirror_bases."""
    E = _plate._mirror_bases_exact(n)[block]
    return E.applyfunc(lambda v: sympy.sign(v))


def discrete_series(
    branch: str = "S0",
    order: int = 8,
    *,
    p: int = 2,
    n: int = 3,
    model: str = "x-exact",
    r=None,
    mass: str = "consistent",
    contact: str = "top",
    gamma_s=0,
    weights=None,
    nu=None,
    split: bool | None = None,
) -> dict[int, sympy.Expr]:
    """Series of the discrete S0 / A0 branch of the plate patch (paper eqs 17-20).

    Parameters are those of :func:`dispersion.plate.plate_patch`; ``order`` is the highest
    power of kappa; ``nu`` substitutes a number for the symbol nu at the end; ``split``
    (default: whenever the mass keeps the mirror symmetry) works on the symmetric (S0) or
    antisymmetric (A0) block instead of the full determinant.

    >>> discrete_series("A0", 6)[4]
    -2/(3*(nu - 1))
    """
    kind, sigma, order = _check_order(branch, order)
    if nu is not None:
        check_nu(nu)
    patch = _plate.plate_patch(p, n, model, r, mass, contact, gamma_s, weights)
    if split is None:
        split = patch.symmetric
    elif split and not patch.symmetric:
        raise InputError("split=True needs a mass that keeps the mirror symmetry")
    symbolic_r = isinstance(patch.r, sympy.Symbol)
    if symbolic_r:
        setup = _setup(("nu", "r"), (NU, R_SYM), lambda nu_f, r_f: (nu_f, r_f))
    else:
        setup = _setup(("nu",), (NU,), lambda nu_f: (nu_f,))
    build = _discrete_characteristic(patch, kind if split else None, sigma, setup)
    return _substitute_nu(series_from_characteristic(build, sigma, order, setup), nu)
