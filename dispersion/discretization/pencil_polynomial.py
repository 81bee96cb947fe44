"""The characteristic polynomial of the plate pencil, exact in its coefficients, for fast roots.

Every x-function of :func:`dispersion.symbolic.plate.x_functions` is a polynomial in one
well-conditioned variable :math:`u`:

* x-exact: :math:`u = \\kappa^2` (``m = 1``, ``d = u``, ``s^2 = u``);
* Bloch: :math:`u = 1 - \\cos\\theta = 2 \\sin^2(\\theta/2)`, :math:`\\theta = \\kappa r`
  (``cos L theta = T_L(1 - u)``, ``sin L theta = sin theta U_{L-1}(1 - u)``,
  :math:`\\sin^2\\theta = u (2 - u)`).

The determinant is even in ``s`` (the y-displacements are scaled by i, so ``s`` sits in the
off-diagonal blocks only), and with the mass factor moved into the eigenvalue,
:math:`\\mu = \\Omega^2 m_x(u)`,

.. math::

    P(u, \\mu) = \\det\\bigl(K(u) - \\mu M_0\\bigr) = \\sum_{j,k} a_{jk}\\, u^k \\mu^j

has exact rational coefficients :math:`a_{jk}` (the moduli of the patch's law, exact
rationals of its float data: :meth:`~dispersion.materials.elastic_law.ElasticLaw.rational_moduli`,
nu by its shortest decimal).
They are found by exact interpolation on a grid of rational nodes (python-flint
``fmpq_mat.det``), with a degree bound from the rows of the matrix, so the rigid-body
cancellation at small kappa is done in exact arithmetic, once per patch: evaluated in
floats, :math:`P` keeps its relative accuracy where :math:`\\Omega^2 \\sim \\kappa^2` (S0)
or :math:`\\kappa^4` (A0) sits beside eigenvalues of order one.

Its roots are found and certified in :mod:`dispersion.discretization.certified_roots`, on the tables
of this module: P in u about u = 0, in :math:`v = 2 - u` about the zone edge, and centred
Taylor tables between (:func:`taylor_centres`), so that every evaluation is well conditioned.

>>> from dispersion.symbolic.plate import plate_patch, mirror_bases
>>> poly = pencil_polynomial(plate_patch(model="x-exact"), 0.3, mirror_bases(3, exact=True)["A"])
>>> poly.coef.shape   # degree 3 in mu, 3 in u = kappa^2
(4, 4)

References
----------
N. J. Higham, *Accuracy and stability of numerical algorithms*, 2nd ed., 2002, section 5.1
(running error bound of Horner's rule); P. Henrici, *Applied and computational complex
analysis* I, 1974, section 6.4 (inclusion discs of polynomial roots).
"""
from __future__ import annotations

import functools
from dataclasses import dataclass
from fractions import Fraction
from types import SimpleNamespace

import numpy as np

from dispersion.errors import InputError

__all__ = ["PencilPolynomial", "mass_factor", "parity_share", "pencil_polynomial", "slopes",
           "taylor_centres", "u_of_kappa"]

#: Largest block (rows of the projected pencil) the polynomial path takes. The rule: the
#: interpolation grid has (degree in u + 1) x (N + 1) exact determinants, and the degree in
#: u grows like N p; at N = 12 (p = 3, n = 6 unsplit) this is about 700 exact 12 x 12
#: determinants, a second, once per patch. Larger pencils use the eigen-solver path.
MAX_BLOCK = 12

_EPS = np.finfo(float).eps


@dataclass(frozen=True)
class PencilPolynomial:
    """:math:`P(u, \\mu) = \\sum a_{jk} u^k \\mu^j` of one block (``coef[j, k]``, floats).

    ``mx`` holds the coefficients of :math:`m_x(u)` (``Omega^2 = mu / m_x``); ``parity``
    the pair of coefficient tables of :math:`\\operatorname{tr}(\\operatorname{adj}(K - \\mu M) Q)`
    and of :math:`\\operatorname{tr}\\operatorname{adj}(K - \\mu M)` (Q the projector on the
    symmetric mirror subspace), whose ratio at a root is the share of the mode shape in that
    subspace; None where not asked for.
    """

    model: str
    r: float | None
    coef: np.ndarray
    mx: np.ndarray
    parity: tuple[np.ndarray, np.ndarray] | None = None
    #: Bloch: the same tables in :math:`v = 2 - u = 1 + \cos\theta` (exact Taylor shift),
    #: used where u > 1 so that the evaluation stays well conditioned up to the zone edge;
    #: ``"P centred"``: the tables of P in :math:`u - c` about the centres
    #: :math:`c = j / C`, j = 1 .. 2C - 1, C = ``centres`` (:func:`taylor_centres`), for the
    #: roots inside the zone (:func:`certified_roots`).
    shifted: dict | None = None
    centres: int = 1
    #: The exact tables (python-flint ``fmpq_poly`` in u): ``"P"`` the coefficients of
    #: :math:`\\mu^j`, ``"mx"`` of :math:`m_x(u)`, for ball arithmetic
    #: (:mod:`dispersion.discretization.certified_slopes`); the aspect ratio r exactly.
    exact: dict | None = None
    r_exact: Fraction | None = None

    @property
    def degree(self) -> int:
        """Number of finite roots (degree in mu)."""
        return self.coef.shape[0] - 1


def u_of_kappa(model: str, r: float | None, kappa: np.ndarray):
    """``u``, ``v = 2 - u`` (Bloch; None for x-exact) and ``du/dkappa``, each to a few ulp.

    >>> u_of_kappa("bloch", 2.0, np.array([1e-9]))[0] / 2e-18    # u ~ (kappa r)^2 / 2
    array([1.])
    """
    if model == "x-exact":
        return kappa * kappa, None, 2 * kappa
    half = kappa * (0.5 * r)
    s, co = np.sin(half), np.cos(half)
    return 2 * s * s, 2 * co * co, (2 * r) * s * co   # du/dkappa = r sin(kappa r)


def _cheb(L: int, kind: str):
    """T_L(1 - u) or U_L(1 - u) as a list of Fraction coefficients in u (ascending)."""
    import flint

    x = flint.fmpq_poly([1, -1])
    a, b = flint.fmpq_poly([1]), (x if kind == "T" else 2 * x)
    if L == 0:
        return a
    for _ in range(L - 1):
        a, b = b, 2 * x * b - a
    return b


def _x_polys(model: str, p: int, r: Fraction | None, x_mass, x_factor=((0, 1),)):
    """``m, d, s2, mx`` as flint fmpq_poly in u (see the module docstring); ``x_mass`` is the
    patch's ``((L, c_L), ...)`` with :math:`m_x = \\sum_L c_L \\cos L\\theta` (Bloch)."""
    import flint

    from dispersion.symbolic.plate import bloch_coefficients

    one = flint.fmpq_poly([1])
    u = flint.fmpq_poly([0, 1])
    if model == "x-exact":
        return {"m": one, "d": u, "s2": u, "mx": one}
    c = bloch_coefficients(p)
    if dict(x_factor) != {0: 1}:  # a Petrov-Galerkin rule: its x-factor times the symbols
        from dispersion.mass_rules.approximate_dual import bloch_product

        c = {k: bloch_product(v, dict(x_factor)) for k, v in c.items()}
    q = flint.fmpq(r.numerator, r.denominator)

    m = sum((_q(v) * _cheb(abs(L), "T") for L, v in c["00"].items()), flint.fmpq_poly([0]))
    d = sum((_q(v) * _cheb(abs(L), "T") for L, v in c["11"].items()), flint.fmpq_poly([0])) \
        / (q * q)
    sh = sum((_q(v) * _cheb(L - 1, "U") for L, v in c["10"].items() if L > 0),
             flint.fmpq_poly([0])) * (-2) / q
    s2 = u * (2 - u) * sh * sh
    mx = sum((_q(v) * _cheb(abs(L), "T") for L, v in x_mass), flint.fmpq_poly([0]))
    return {"m": m, "d": d, "s2": s2, "mx": mx}


def _q(v):
    """A sympy Rational (or int) as flint.fmpq."""
    import flint

    return flint.fmpq(int(v.p), int(v.q)) if hasattr(v, "q") else flint.fmpq(int(v))


def _fmpq_mat(rows):
    import flint

    return flint.fmpq_mat([[_q(v) for v in row] for row in rows])


@functools.lru_cache(maxsize=64)
def _build(key):
    (p, n, model, r, my, x_mass, law, basis, parity, x_factor, space) = key
    import flint
    import sympy

    from dispersion.symbolic.plate import stiffness_terms, thickness_matrices

    Y = thickness_matrices(p, n, space)
    n2 = 2 * n
    My = sympy.Matrix(n, n, list(my))
    M0 = sympy.diag(My, My)
    mat = law.rational_moduli()
    xp = _x_polys(model, p, r, x_mass, x_factor)
    E = sympy.eye(n2) if basis is None else sympy.Matrix(len(basis), len(basis[0]),
                                                         [v for row in basis for v in row])
    nb = E.shape[1]
    # the determinant is unchanged by scaling the y-columns by s and the y-rows by 1/s
    # (module docstring): the upper-right part of each s-term takes s^2, the lower-left 1
    parts = []
    for m_, f, B in stiffness_terms(SimpleNamespace(Y=Y, n=n)):
        if f == "s":
            UR = sympy.zeros(n2)
            LL = sympy.zeros(n2)
            UR[:n, n:] = B[:n, n:]
            LL[n:, :n] = B[n:, :n]
            parts.append((xp["s2"], mat[m_], E.T * UR * E))
            parts.append((flint.fmpq_poly([1]), mat[m_], E.T * LL * E))
        else:
            parts.append((xp[f], mat[m_], E.T * B * E))
    parts = [(poly, _q(c), _fmpq_mat(P.tolist())) for poly, c, P in parts
             if any(v != 0 for v in P)]
    Mp = _fmpq_mat((E.T * M0 * E).tolist())
    # degree bound in u: sum over rows of the largest degree of the terms touching the row
    row_deg = [0] * nb
    for poly, _, P in parts:
        for i in range(nb):
            if any(P[i, j] != 0 for j in range(nb)):
                row_deg[i] = max(row_deg[i], poly.degree())
    du = sum(row_deg)
    N = nb
    Q = None
    if parity:
        from dispersion.symbolic.plate import mirror_bases

        S = mirror_bases(n, exact=True)["S"]
        Qs = sympy.zeros(n2)
        for j in range(S.shape[1]):
            col = S[:, j]
            Qs += col * col.T / (col.T * col)[0, 0]
        Q = _fmpq_mat(Qs.tolist())
    unodes = [flint.fmpq(k) for k in range(du + 1)]
    mnodes = [flint.fmpq(-(j + 1)) for j in range(N + 1)]
    vals = [[None] * (N + 1) for _ in range(du + 1)]
    tq = [[None] * (N + 1) for _ in range(du + 1)]
    ti = [[None] * (N + 1) for _ in range(du + 1)]
    for a, uu in enumerate(unodes):
        K = flint.fmpq_mat(nb, nb)
        for poly, c, P in parts:
            K = K + (c * poly(uu)) * P
        for b, mu in enumerate(mnodes):
            A = K - mu * Mp
            det = A.det()
            vals[a][b] = det
            if parity:
                if det == 0:
                    raise InputError("singular interpolation node")  # caller falls back
                Ai = A.inv()
                AiQ = Ai * Q   # once: the sum below multiplied it again for every i
                tq[a][b] = det * sum(AiQ[i, i] for i in range(nb))
                ti[a][b] = det * sum(Ai[i, i] for i in range(nb))
    Vu = flint.fmpq_mat([[uu**k for k in range(du + 1)] for uu in unodes]).inv()
    Vm = flint.fmpq_mat([[mu**j for j in range(N + 1)] for mu in mnodes]).inv().transpose()

    shift = flint.fmpq_poly([2, -1])   # u = 2 - v
    shifted = {} if model == "bloch" else None

    def floats(polys):
        out = np.zeros((len(polys), max(p.degree() for p in polys) + 1 if polys else 1))
        for j, pj in enumerate(polys):
            cs = pj.coeffs()
            out[j, :len(cs)] = [float(c) for c in cs]   # exact zeros stay 0.0
        return _trim_like(out)

    exact = {"mx": xp["mx"]}

    def solve(name, table):
        C = Vu * flint.fmpq_mat(table) * Vm   # C[k, j]
        polys = [flint.fmpq_poly([C[k, j] for k in range(du + 1)]) for j in range(N + 1)]
        if name == "P":
            while len(polys) > 1 and polys[-1] == 0:   # as _trim_like does for the floats
                polys.pop()
            exact["P"] = tuple(polys)
        if shifted is not None:
            shifted[name] = floats([pj(shift) for pj in polys])
            if name == "P":
                centres = shifted["centres"] = taylor_centres(max(pj.degree() for pj in polys))
                shifted["P centred"] = tuple(
                    floats([pj(flint.fmpq_poly([flint.fmpq(j, centres), 1])) for pj in polys])
                    for j in range(1, 2 * centres))
        return floats(polys)

    coef = solve("P", vals)
    par = None
    if parity:
        par = (solve("Q", tq), solve("I", ti))
    mx = floats([xp["mx"]])[0]
    if shifted is not None:
        shifted["mx"] = floats([xp["mx"](shift)])
    return PencilPolynomial(model, None if r is None else float(r), coef, mx, par, shifted,
                            1 if shifted is None else shifted.pop("centres"), exact, r)


def _trim_like(c):
    while c.shape[0] > 1 and not np.any(c[-1]):
        c = c[:-1]
    while c.shape[1] > 1 and not np.any(c[:, -1]):
        c = c[:, :-1]
    return c


def pencil_polynomial(patch, nu, basis=None, parity: bool = False) -> PencilPolynomial:
    """The exact characteristic polynomial of ``patch`` projected on ``basis`` (module docstring).

    ``basis`` is an integer mirror basis (``mirror_bases(n, exact=True)[kind]``) or None
    (the whole pencil). Cached per patch data, law and basis; raises :class:`InputError`
    for blocks larger than :data:`MAX_BLOCK`.
    """
    from dispersion.symbolic.plate import with_nu

    patch = with_nu(patch, nu)
    nb = 2 * patch.n if basis is None else basis.shape[1]
    if nb > MAX_BLOCK:
        raise InputError(f"pencil block of {nb} rows is larger than MAX_BLOCK = {MAX_BLOCK}")
    r = None if patch.model != "bloch" else Fraction(str(patch.r))
    x_mass = ((0, 1),) if patch.model != "bloch" or patch.x_lumped else tuple(patch.x_mass)
    key = (patch.p, patch.n, patch.model, r, tuple(patch.My), x_mass,
           patch.law.check_numeric("characteristic polynomial"),
           None if basis is None else tuple(tuple(int(v) for v in basis.row(i))
                                            for i in range(basis.shape[0])), bool(parity),
           tuple(patch.x_stiffness) if patch.model == "bloch" else ((0, 1),),
           getattr(patch.rule, "basis", "bspline"))
    return _build(key)


# Numerics below keep arrays as (rows, points): each Horner step is then a contiguous
# row-broadcast, several times faster than the (points, rows) layout.

def _horner_u(coef: np.ndarray, u: np.ndarray) -> np.ndarray:
    """``sum_k coef[:, k] u^k`` for every u: shape (rows of coef, len(u))."""
    out = np.empty((coef.shape[0], u.size))
    out[:] = coef[:, -1:]
    for k in range(coef.shape[1] - 2, -1, -1):
        out *= u
        out += coef[:, k:k + 1]
    return out


def _derivative_u(coef: np.ndarray) -> np.ndarray:
    k = np.arange(coef.shape[1])
    return (coef * k)[:, 1:] if coef.shape[1] > 1 else np.zeros_like(coef)


def _values(poly: PencilPolynomial, name: str, u, v, deriv: bool = False, bars: bool = True):
    """Values (and absolute sums) of the u-polynomials of table ``name`` ("P", "Q", "I", "mx").

    Where u > 1 (Bloch) the shifted table in v is used; ``deriv`` gives d/du instead.
    Returns arrays of shape (rows of the table, len(u)).
    """
    table = {"P": poly.coef, "mx": poly.mx[None, :]}
    if poly.parity is not None:
        table.update(Q=poly.parity[0], I=poly.parity[1])
    hi = None if v is None or poly.shifted is None else np.flatnonzero(u > 1)

    def run(c, x, sign):
        if deriv:
            c = sign * _derivative_u(c)
        J = c.shape[0]
        out = _horner_u(np.concatenate([c, np.abs(c)]) if bars else c, x)
        return out[:J], (out[J:] if bars else None)

    if hi is None or hi.size == 0:
        return run(table[name], u, 1)
    lo = np.flatnonzero(u <= 1)
    val_lo, bar_lo = run(table[name], u[lo], 1)
    val_hi, bar_hi = run(poly.shifted[name], v[hi], -1)
    val = np.empty((val_lo.shape[0], u.size))
    val[:, lo], val[:, hi] = val_lo, val_hi
    bar = None
    if bars:
        bar = np.empty_like(val)
        bar[:, lo], bar[:, hi] = bar_lo, bar_hi
    return val, bar


def _horner_mu(c: np.ndarray, mu: np.ndarray, deriv: bool = True):
    """``P`` and ``P_mu`` (None unless ``deriv``) at ``mu`` (shape (R, points)) from
    coefficient values (J, points)."""
    p = np.empty_like(mu)
    p[:] = c[-1]
    dp = np.zeros_like(mu) if deriv else None
    for j in range(c.shape[0] - 2, -1, -1):
        if deriv:
            dp *= mu
            dp += p
        p *= mu
        p += c[j]
    return p, dp


def taylor_centres(degree: int) -> int:
    """Taylor centres per unit of u for a table of ``degree`` in u: ``ceil(degree / 9)``.

    P is tabulated about u = 0, 1/C, ..., 2 (Bloch), so every table is evaluated at
    :math:`|x| \\le 1/(2C)`. The rule: the terms of a table in u lose to cancellation
    roughly like the binomial growth of a Taylor shift, about :math:`2^{d}` at
    :math:`|x| = 1` for degree d; with :math:`|x| \\le 1/(2C)` and C = d/9 that loss stays
    below a few hundred (measured: the degree-36 table of p = 3, n = 6, singular mass loses
    up to 1e4 at :math:`|x| = 1/2` and certifies every point inside the zone at 1/8).

    >>> taylor_centres(6), taylor_centres(18), taylor_centres(36)
    (1, 2, 4)
    """
    return max(1, -(-int(degree) // 9))


def mass_factor(poly: PencilPolynomial, u, v) -> np.ndarray:
    """:math:`m_x(u)`, shape (len(u), 1)."""
    return _values(poly, "mx", u, v, bars=False)[0].T


def slopes(poly: PencilPolynomial, u: np.ndarray, v, dudk: np.ndarray, mu: np.ndarray,
           rad: np.ndarray | None = None):
    """:math:`d\\Omega/d\\kappa` at roots ``mu`` (points, R) and a bound on its absolute error.

    Implicitly :math:`d\\mu/du = -P_u / P_\\mu`; with :math:`\\Omega^2 = \\mu / m_x`,
    :math:`d\\Omega/d\\kappa = (\\mu_u m_x - \\mu m_x') u_\\kappa / (2 \\Omega m_x^2)`.
    ``rad`` (same shape as mu): the radius the roots are known to; its effect on the slope,
    :math:`|\\partial\\mu_u/\\partial\\mu|\\, rad` with
    :math:`\\partial\\mu_u/\\partial\\mu = -(P_{u\\mu} P_\\mu - P_u P_{\\mu\\mu})/P_\\mu^2`
    (bars of the derivatives, first order) and through :math:`\\Omega`, is added to the bound.
    """
    du, dm = poly.coef.shape[1] - 1, poly.coef.shape[0] - 1
    mu = mu.T
    cu, cub = _values(poly, "P", u, v, deriv=True)
    c, cb = _values(poly, "P", u, v)
    with np.errstate(all="ignore"):
        pu, _ = _horner_mu(cu, mu)
        pub, pumb = _horner_mu(cub, np.abs(mu))
        _, pm = _horner_mu(c, mu)
        _, pmb = _horner_mu(cb, np.abs(mu))
        # the rounding constants of certified_roots without its safety factor 2 (each is a
        # worst-case bound already, Higham 2002, 3.1 and 5.1)
        g = (6 * du + 2 * dm + 4) * _EPS
        mu_u = -pu / pm
        err_mu_u = (g * pub + np.abs(mu_u) * g * pmb) / np.abs(pm)
        if rad is not None:
            r = np.abs(rad.T)
            jj = np.arange(cb.shape[0])[:, None]
            _, pmmb = _horner_mu((cb * jj)[1:] if cb.shape[0] > 1 else 0 * cb, np.abs(mu) + r)
            err_mu_u = err_mu_u + 2 * r * (pumb + np.abs(mu_u) * pmmb) / np.abs(pm)
        mx = _values(poly, "mx", u, v, bars=False)[0]
        mxd = _values(poly, "mx", u, v, deriv=True, bars=False)[0]
        omega = np.sqrt(mu / mx)
        fac = dudk / (2 * omega * mx * mx)
        g_val = (mu_u * mx - mu * mxd) * fac
        g_err = np.abs(fac) * (err_mu_u * np.abs(mx) + 8 * _EPS * (np.abs(mu_u * mx)
                                                                   + np.abs(mu * mxd))) \
            + 8 * _EPS * np.abs(g_val)
        if rad is not None:   # mu in the numerator and in Omega (relative r / mu, halved)
            g_err = g_err + np.abs(fac) * np.abs(mxd) * r + np.abs(g_val) * r / (2 * mu)
    return g_val.T, g_err.T


def parity_share(poly: PencilPolynomial, u: np.ndarray, v, mu: np.ndarray) -> np.ndarray:
    """Share of each root's mode shape in the symmetric mirror subspace (0..1), (points, R)."""
    mu = mu.T
    with np.errstate(all="ignore"):
        a, _ = _horner_mu(_values(poly, "Q", u, v, bars=False)[0], mu)
        b, _ = _horner_mu(_values(poly, "I", u, v, bars=False)[0], mu)
        return (a / b).T
