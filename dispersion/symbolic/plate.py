"""Plane-strain plate patch of B-splines: stiffness, mass and dynamic stiffness K - Omega^2 M.

The plate occupies :math:`-h \\le y \\le h`; units are dimensionless with :math:`h = 1`,
shear modulus :math:`D_{66} = \\mu = 1`, :math:`\\rho = 1` (so :math:`c_T = 1`,
:math:`\\Omega = \\omega h / c_T`, :math:`\\kappa = k h`). The material is the patch's
elastic law (:mod:`dispersion.materials.elastic_law`: the plane-strain D over the shear
modulus; isotropic, :math:`D_{11} = D_{22} = \\lambda + 2\\mu`, :math:`D_{12} = \\lambda`,
or orthotropic). Through the thickness, ``n`` open B-splines of degree ``p`` carry the
displacement; along x either

* ``model="x-exact"``: :math:`u = U(y) e^{i k x}` (semi-discrete in the thickness only), or
* ``model="bloch"``: uniform :math:`C^{p-1}` B-splines of element length :math:`b = r h` and
  one Bloch-periodic column of control points, phase :math:`\\theta = \\kappa r`.

The x-direction enters only through three per-unit-length functions of :math:`\\kappa`,

.. math::

    m = \\sum_L c^{00}_L \\cos L\\theta, \\quad
    s = -\\frac{2}{r} \\sum_{L>0} c^{10}_L \\sin L\\theta, \\quad
    d = \\frac{1}{r^2} \\sum_L c^{11}_L \\cos L\\theta

(Bloch sums of the cardinal B-spline Gram integrals :math:`c^{ab}_L`); the x-exact model
has :math:`m = 1, s = \\kappa, d = \\kappa^2`. With the thickness integrals
:math:`Y_{ab} = \\int N^{(a)} N^{(b)T} dy`, and the y-displacements scaled by i so that the
pencil is real symmetric,

.. math::

    K = \\begin{bmatrix} D_{11} d Y_{00} + D_{66} m Y_{11} & s(D_{12} Y_{01} - D_{66} Y_{10}) \\\\
        \\cdot & D_{22} m Y_{11} + D_{66} d Y_{00} \\end{bmatrix}, \\qquad
    M = m_x \\begin{bmatrix} M_y & 0 \\\\ 0 & M_y \\end{bmatrix},

with :math:`M_y` the thickness mass of the chosen rule (:mod:`dispersion.mass_rules.mass_rule`) and
:math:`m_x = \\sum_L a_L \\cos L\\theta` the Bloch sum of the rule's x-mass
(:func:`dispersion.mass_rules.mass_rule.x_mass_coefficients`: :math:`m_x = m` consistent, 1
row-sum lumped or HRZ; 1 in the x-exact model).

>>> patch = plate_patch()
>>> patch.Y["00"].tolist()
[[2/5, 1/5, 1/15], [1/5, 4/15, 1/5], [1/15, 1/5, 2/5]]

References
----------
A. Tkachuk et al., section 2 and Figure 2 (left). J. A. Cottrell, A. Reali, Y. Bazilevs,
T. J. R. Hughes, "Isogeometric analysis of structural vibrations", CMAME 195 (2006) 5257-5296.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
import sympy

from dispersion.splines import bspline
from dispersion.errors import InputError, check_positive_int
from dispersion.materials.elastic_law import ElasticLaw, Isotropic, lame
from dispersion.mass_rules.mass import contact_weights, redistribution_matrix
from dispersion.mass_rules.mass_rule import (get_rule, mass_variant, x_mass_coefficients,
                                           x_stiffness_factor)

__all__ = [
    "PATCH_MODELS",
    "P_MAX",
    "N_MAX",
    "PlatePatch",
    "plate_patch",
    "thickness_matrices",
    "thickness_knot_vector",
    "bloch_coefficients",
    "x_functions",
    "x_coefficients",
    "lame",
    "with_nu",
    "stiffness_terms",
    "dynamic_stiffness",
    "numeric_pencil",
    "numeric_terms",
    "mirror_bases",
    "x_taylor",
]

# stated with the defaults (a light module the command line reads without sympy)
from dispersion.defaults import N_MAX, P_MAX, PATCH_MODELS  # noqa: E402
from dispersion.symbolic.patch import (  # noqa: E402  (the patch's own rules, stated there)
    PATCH_FIELDS, Patch, as_patch)
_y = sympy.Symbol("y")


def thickness_matrices(p: int, n: int, basis: str = "bspline") -> dict[str, sympy.ImmutableMatrix]:
    """Exact :math:`Y_{ab} = \\int_{-1}^{1} N^{(a)}_i N^{(b)}_j dy` for ``n`` open B-splines of degree p.

    ``basis="lagrange"``: the C0 space of degree p with ``n = p * elements + 1`` DOFs
    (:func:`thickness_knot_vector`).

    >>> thickness_matrices(1, 2)["11"].tolist()
    [[1/2, -1/2], [-1/2, 1/2]]
    """
    return dict(zip(("00", "01", "10", "11"), _thickness_matrices(p, n, basis)))


def thickness_knot_vector(p: int, n: int, basis: str = "bspline"):
    """The knot vector through the thickness [-1, 1]: open uniform B-splines, or the C0
    (Lagrange) space, interior knots repeated p times.

    >>> [str(k) for k in thickness_knot_vector(2, 5, "lagrange").knots]
    ['-1', '-1', '-1', '0', '0', '1', '1', '1']
    """
    if basis == "lagrange":
        from dispersion.splines.lagrange_sem import c0_elements, c0_knot_vector

        return c0_knot_vector(p, c0_elements(p, n), -1, 1)
    if basis != "bspline":
        raise InputError(f"basis must be 'bspline' or 'lagrange', got {basis!r}")
    return bspline.open_knot_vector(p, n - p, -1, 1)


@lru_cache(maxsize=None)
def _thickness_matrices(p: int, n: int, basis: str = "bspline") -> tuple[sympy.ImmutableMatrix, ...]:
    # cached and shared, hence immutable
    kv = thickness_knot_vector(p, n, basis)
    Y = {k: sympy.zeros(n, n) for k in ("00", "01", "10", "11")}
    for (a, b), polys, active in bspline.basis_polynomials(kv, _y, local=False):
        ders = [[sympy.Poly(f, _y) for f in polys], [sympy.Poly(f, _y).diff(_y) for f in polys]]
        for key, Ymat in Y.items():
            da, db = int(key[0]), int(key[1])
            for i, gi in zip(active, ders[da]):
                for j, gj in zip(active, ders[db]):
                    prim = (gi * gj).integrate()
                    Ymat[i, j] += prim.eval(b) - prim.eval(a)
    return tuple(sympy.ImmutableMatrix(Y[k]) for k in ("00", "01", "10", "11"))


def bloch_coefficients(p: int) -> dict[str, dict[int, sympy.Rational]]:
    """Gram integrals :math:`c^{ab}_L = \\int N_0^{(a)} N_L^{(b)} d\\xi` of the unit cardinal B-spline.

    >>> bloch_coefficients(1)["00"]
    {-1: 1/6, 0: 2/3, 1: 1/6}
    """
    return {key: dict(val) for key, val in _bloch_coefficients(p)}


@lru_cache(maxsize=None)
def _bloch_coefficients(p: int) -> tuple:
    u = sympy.Symbol("u")
    pieces = [sympy.Poly(f, u) for f in bspline.cardinal_pieces(p, u)]
    ders = [pieces, [f.diff(u) for f in pieces]]
    out = []
    for key in ("00", "10", "11"):
        da, db = int(key[0]), int(key[1])
        coeffs = []
        for L in range(-p, p + 1):
            total = sympy.Integer(0)
            for j in range(p + 1):
                if 0 <= j - L <= p:
                    prim = (ders[da][j] * ders[db][j - L]).integrate()
                    total += prim.eval(1) - prim.eval(0)
            coeffs.append((L, total))
        out.append((key, tuple(coeffs)))
    return tuple(out)


@dataclass(frozen=True)
class PlatePatch:
    """The representative patch of the plate: basis data, mass rule, derived matrices (exact)
    and the material they are computed with.

    ``mass`` is the rule's name, ``rule`` the :class:`~dispersion.mass_rules.mass_rule.MassRule`
    itself, ``x_mass`` the Bloch coefficients ``((L, a_L), ...)`` of its mass along x,
    ``law`` the :class:`~dispersion.materials.elastic_law.ElasticLaw` of its stiffness.
    """

    p: int
    n: int
    model: str
    r: object
    mass: str
    R: sympy.Matrix | None
    Y: dict = field(repr=False)
    My: sympy.Matrix = field(repr=False)
    x_lumped: bool = False
    #: The :class:`dispersion.symbolic.patch.Patch` value this patch was built from.
    spec: object = field(default=None, compare=False)
    x_mass: tuple = ()
    rule: object = field(default=None, repr=False, compare=False)
    #: Bloch factor ``((L, s_L), ...)`` of the x-stiffness (1 but for Petrov-Galerkin rules,
    #: :func:`dispersion.mass_rules.mass_rule.x_stiffness_factor`).
    x_stiffness: tuple = ((0, 1),)
    #: The plate's material (:mod:`dispersion.materials.elastic_law`): the spec's law. Every
    #: function that computes on the patch reads its moduli here.
    law: ElasticLaw = field(default_factory=Isotropic)

    @property
    def massless(self) -> tuple[int, ...]:
        """DOF indices (order u_x 0..n-1, u_y 0..n-1) whose mass rows vanish identically."""
        zero = [i for i in range(self.n) if all(v == 0 for v in self.My.row(i))]
        return tuple(zero + [self.n + i for i in zero])

    @property
    def symmetric(self) -> bool:
        """True if the mass keeps the mirror symmetry y -> -y of the patch."""
        n = self.n
        J = sympy.Matrix(n, n, lambda i, j: 1 if i + j == n - 1 else 0)
        return J * self.My * J == self.My


def plate_patch(*args, allow_negative: bool = False, **fields) -> PlatePatch:
    """Build the plate patch of a :class:`dispersion.symbolic.patch.Patch` (or of its fields).

    ``plate_patch(patch)`` takes a ``Patch`` value; ``plate_patch(p, n, model, ...)`` or
    keywords build one first, with the toolkit's defaults (:mod:`dispersion.defaults`: Bloch
    model, r = 2, p = 2, n = 3, gamma_s = 1/2). The fields and their limits are documented on
    :class:`~dispersion.symbolic.patch.Patch`; ``allow_negative`` admits negative redistribution
    weights (a study of indefinite masses).

    >>> plate_patch(mass="lumped").spec.label()
    'bloch p=2 n=3 r=2, lumped mass'
    """
    if args and isinstance(args[0], Patch):
        spec = as_patch(args[0], **dict(zip(PATCH_FIELDS, args[1:])), **fields)
    else:
        spec = Patch(*args, **fields)
    return _build(spec, allow_negative)


@lru_cache(maxsize=64)
def _build(spec, allow_negative: bool) -> PlatePatch:
    rule = get_rule(spec.mass)
    Y = thickness_matrices(spec.p, spec.n, rule.basis)
    R = None
    if rule.redistributes:
        weights = spec.weights_dict
        if weights is None:
            weights = contact_weights(spec.n, spec.contact, spec.gamma_s)
        R = redistribution_matrix(spec.n, weights, allow_negative=allow_negative)
    kv = thickness_knot_vector(spec.p, spec.n, rule.basis)
    My = mass_variant(Y["00"], rule, R, kv=kv)
    # a rule with its own periodic row (a family member: sms_rule(beta)) uses it along x
    x_mass = x_mass_coefficients(rule if rule.periodic is not None else rule.x_rule, spec.p)
    return PlatePatch(spec.p, spec.n, spec.model, spec.r, rule.name, R, Y, My,
                      x_lumped=x_mass == ((0, sympy.Integer(1)),), spec=spec, x_mass=x_mass,
                      rule=rule, x_stiffness=x_stiffness_factor(
                          rule if rule.x_stiffness is not None else rule.x_rule, spec.p),
                      law=spec.law)


def x_coefficients(patch) -> dict[str, dict[int, sympy.Rational]]:
    """The Bloch coefficients of the x-stiffness of ``patch``: :func:`bloch_coefficients`
    times its factor :attr:`PlatePatch.x_stiffness` (a Laurent product; unchanged for every
    Galerkin rule).

    >>> x_coefficients(plate_patch(p=1, mass="dual-lumped"))["00"]
    {-2: -1/36, -1: 1/9, 0: 5/6, 1: 1/9, 2: -1/36}
    """
    from dispersion.mass_rules.approximate_dual import bloch_product

    c = bloch_coefficients(patch.p)
    factor = dict(getattr(patch, "x_stiffness", ((0, 1),)))
    if factor == {0: 1}:
        return c
    return {key: {L: v for L, v in bloch_product(val, factor).items() if v != 0}
            for key, val in c.items()}


def x_functions(patch: PlatePatch, kappa) -> dict[str, object]:
    """The per-unit-length x-functions ``m, s, d`` (and ``mx``, the mass factor) at ``kappa``.

    ``kappa`` may be a sympy expression or a numpy array; trig functions follow its kind.
    """
    numeric = not isinstance(kappa, sympy.Basic)
    cos, sin = (np.cos, np.sin) if numeric else (sympy.cos, sympy.sin)
    if patch.model == "x-exact":
        one = np.ones_like(kappa, dtype=float) if numeric else sympy.Integer(1)
        out = {"m": one, "s": kappa, "d": kappa**2}
    else:
        c = x_coefficients(patch)
        r = float(patch.r) if numeric else patch.r
        th = kappa * r
        conv = float if numeric else (lambda v: v)
        out = {
            "m": sum(conv(v) * cos(L * th) for L, v in c["00"].items()),
            "s": -2 / r * sum(conv(v) * sin(L * th) for L, v in c["10"].items() if L > 0),
            "d": sum(conv(v) * cos(L * th) for L, v in c["11"].items()) / r**2,
        }
    if patch.model == "x-exact" or patch.x_lumped:
        out["mx"] = np.ones_like(out["m"]) if numeric else sympy.Integer(1)
    else:
        th = kappa * (float(patch.r) if numeric else patch.r)
        conv = float if numeric else (lambda v: v)
        out["mx"] = sum(conv(v) * cos(L * th) for L, v in patch.x_mass)
    return out


def x_taylor(patch: PlatePatch, D: int) -> dict[str, list[tuple[sympy.Rational, int]]]:
    """Taylor coefficients in :math:`t = \\kappa^2` of the x-functions of :func:`x_functions`.

    Returns ``{"m", "s", "d", "mx"}``, each a list of ``D + 1`` pairs ``(c_k, e_k)`` meaning
    :math:`[t^k] f = c_k r^{e_k}`; ``"s"`` is :math:`s / \\kappa` (s is odd in kappa). From
    :math:`\\cos L\\theta = \\sum_k (-1)^k (L r)^{2k} t^k / (2k)!` and the same Gram
    integrals :func:`bloch_coefficients`; ``tests/test_plate.py`` checks them against the
    ``sympy.series`` of :func:`x_functions`.

    >>> x_taylor(plate_patch(model="bloch", r=2), 1)["d"]
    [(0, -2), (1, 0)]
    """
    if patch.model == "x-exact":
        out = {"m": [(sympy.Integer(1), 0)] + [(sympy.Integer(0), 0)] * D,
               "s": [(sympy.Integer(1), 0)] + [(sympy.Integer(0), 0)] * D,
               "d": [(sympy.Integer(0), 0), (sympy.Integer(1), 0)][: D + 1]
               + [(sympy.Integer(0), 0)] * (D - 1)}
    else:
        c = x_coefficients(patch)
        out = {"m": [], "s": [], "d": []}
        for k in range(D + 1):
            sign = (-1) ** k
            out["m"].append((sign * sum(v * L ** (2 * k) for L, v in c["00"].items())
                             / sympy.factorial(2 * k), 2 * k))
            out["s"].append((-2 * sign * sum(v * L ** (2 * k + 1)
                                             for L, v in c["10"].items() if L > 0)
                             / sympy.factorial(2 * k + 1), 2 * k))
            out["d"].append((sign * sum(v * L ** (2 * k) for L, v in c["11"].items())
                             / sympy.factorial(2 * k), 2 * k - 2))
    if patch.model == "x-exact" or patch.x_lumped:
        out["mx"] = [(sympy.Integer(1), 0)] + [(sympy.Integer(0), 0)] * D
    else:
        out["mx"] = [((-1) ** k * sum(v * L ** (2 * k) for L, v in patch.x_mass)
                      / sympy.factorial(2 * k), 2 * k) for k in range(D + 1)]
    return out


def stiffness_terms(patch: PlatePatch) -> list[tuple[str, str, sympy.Matrix]]:
    """K as ``[(modulus, xfunc, B)]``: :math:`K = \\sum` modulus * xfunc(kappa) * B.

    ``modulus`` in {"D11", "D22", "D12", "D66"}, the entries of the plane-strain D over the
    shear modulus (:data:`dispersion.materials.elastic_law.MODULI`, given by the patch's law),
    ``xfunc`` in {"m", "s", "d"}. This single list defines K for the symbolic, series and
    numeric code paths.

    .. math::

        K = \\begin{bmatrix} D_{11} d Y_{00} + D_{66} m Y_{11} & s(D_{12} Y_{01} - D_{66} Y_{10}) \\\\
            \\cdot & D_{22} m Y_{11} + D_{66} d Y_{00} \\end{bmatrix}
    """
    Y, n = patch.Y, patch.n
    Z = sympy.zeros(n, n)

    def blocks(a, b, c, d):
        # by slices: sympy.Matrix(BlockMatrix(...)) looked each entry up symbolically (5 to 50
        # times slower; every uncached caller pays it, the tests' mpmath reference per kappa)
        out = sympy.zeros(2 * n, 2 * n)
        out[:n, :n], out[:n, n:], out[n:, :n], out[n:, n:] = a, b, c, d
        return out

    return [
        ("D11", "d", blocks(Y["00"], Z, Z, Z)),
        ("D66", "m", blocks(Y["11"], Z, Z, Z)),
        ("D22", "m", blocks(Z, Z, Z, Y["11"])),
        ("D66", "d", blocks(Z, Z, Z, Y["00"])),
        ("D12", "s", blocks(Z, Y["01"], Y["01"].T, Z)),
        ("D66", "s", -blocks(Z, Y["10"], Y["10"].T, Z)),
    ]


def mass_block(patch: PlatePatch) -> sympy.Matrix:
    """Constant part of M: ``diag(M_y, M_y)``; the full mass is ``mx(kappa)`` times this."""
    return sympy.diag(patch.My, patch.My)


def with_nu(patch: PlatePatch, nu=None) -> PlatePatch:
    """``patch`` with Poisson's ratio ``nu`` (an isotropic plate), or as it is (its own law)
    if ``nu`` is None: the ``nu`` argument every numeric function keeps resolves here, once.

    >>> with_nu(plate_patch(), 0.3).law
    Isotropic(nu=0.3)
    >>> from dispersion.materials.elastic_law import Orthotropic
    >>> with_nu(plate_patch(law=Orthotropic(3, 2, 1, 1)), 0.3)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: nu applies to an isotropic plate; this one is orthotropic (C11 = 3, C22 = 2, C12 = 1, C66 = 1) (give nu=None: the patch's law)
    """
    if nu is None:
        return patch
    if not isinstance(patch.law, Isotropic):
        raise InputError(f"nu applies to an isotropic plate; this one is "
                         f"{patch.law.describe()} (give nu=None: the patch's law)")
    return replace(patch, law=Isotropic(nu))


def dynamic_stiffness(patch: PlatePatch, kappa=None, Omega=None, nu=None) -> sympy.Matrix:
    """Exact :math:`K_{dyn}(\\kappa, \\Omega) = K - \\Omega^2 M` (sympy; symbols by default,
    the moduli of the patch's law: nu stays a symbol where the law keeps it; ``nu`` replaces
    an isotropic plate's Poisson's ratio, :func:`with_nu`).

    >>> Kd = dynamic_stiffness(plate_patch())
    >>> Kd.is_symmetric()
    True
    """
    patch = with_nu(patch, nu)
    kappa = sympy.Symbol("kappa") if kappa is None else kappa
    Omega = sympy.Symbol("Omega") if Omega is None else Omega
    from dispersion.reader import as_sympy

    # numbers and sympy objects; text (also inside a tuple or a dict) is refused, never parsed
    kappa, Omega = as_sympy("kappa", kappa), as_sympy("Omega", Omega)
    mat, xf = patch.law.moduli(), x_functions(patch, kappa)
    K = sum((mat[m] * xf[f] * B for m, f, B in stiffness_terms(patch)), sympy.zeros(2 * patch.n))
    return K - Omega**2 * xf["mx"] * mass_block(patch)


def numeric_pencil(patch: PlatePatch, nu, kappa) -> tuple[np.ndarray, np.ndarray]:
    """Float stacks ``K, M`` of shape ``(len(kappa), 2n, 2n)``, built from :func:`stiffness_terms`
    with the float moduli of the patch's law (``nu``: Poisson's ratio of an isotropic plate,
    None: the patch's own law, :func:`with_nu`).

    >>> K, M = numeric_pencil(plate_patch(), 0.3, [0.0, 0.5])
    >>> K.shape, bool(np.allclose(K, K.transpose(0, 2, 1)))
    ((2, 6, 6), True)
    >>> K2, _ = numeric_pencil(plate_patch(nu=0.3), None, [0.0, 0.5])
    >>> bool((K2 == K).all())
    True
    """
    mat = with_nu(patch, nu).law.float_moduli()
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    if not np.all(np.isfinite(kappa)):
        raise InputError("kappa must be finite")
    if patch.model == "bloch" and isinstance(patch.r, sympy.Symbol):
        raise InputError("aspect ratio r must be a number for numeric evaluation")
    xf = x_functions(patch, kappa)
    terms, M0 = numeric_terms(patch)
    n2 = 2 * patch.n
    # one matrix product: coefficients (points x terms) times the flattened term matrices
    C = np.column_stack([np.broadcast_to(mat[m] * xf[f], kappa.shape) for m, f, _ in terms])
    K = (C @ np.stack([B.ravel() for _, _, B in terms])).reshape(kappa.size, n2, n2)
    M = xf["mx"][:, None, None] * M0
    return K, M


def numeric_terms(patch: PlatePatch) -> tuple[tuple[tuple[str, str, np.ndarray], ...], np.ndarray]:
    """:func:`stiffness_terms` and :func:`mass_block` as float arrays, built once per patch data.

    >>> terms, M0 = numeric_terms(plate_patch())
    >>> len(terms), M0.shape
    (6, (6, 6))
    """
    rule = getattr(patch, "rule", None)
    return _numeric_terms(patch.p, patch.n, tuple(patch.My),
                          getattr(rule, "basis", "bspline"))


@lru_cache(maxsize=64)
def _numeric_terms(p: int, n: int, my: tuple, basis: str = "bspline"):
    from types import SimpleNamespace

    terms = stiffness_terms(SimpleNamespace(Y=thickness_matrices(p, n, basis), n=n))
    out = []
    for m, f, B in terms:
        arr = np.array(B, dtype=float)
        arr.setflags(write=False)  # cached and shared
        out.append((m, f, arr))
    My = sympy.Matrix(n, n, list(my))
    M0 = np.array(sympy.diag(My, My), dtype=float)
    M0.setflags(write=False)
    return tuple(out), M0


def mirror_bases(patch_or_n, exact: bool = False):
    """Bases of the symmetric ("S") and antisymmetric ("A") DOF subspaces of the mirror y -> -y.

    S: u_x even and u_y odd in y; A: the reverse (DOF order u_x 0..n-1, u_y 0..n-1; the
    mirror maps control point i to n-1-i). This is the one definition of the mirror split.

    Parameters
    ----------
    patch_or_n : PlatePatch or int
        A patch (``None`` is returned if its mass breaks the symmetry) or the number n of
        control points through the thickness (the geometric mirror, whatever the mass).
    exact : bool
        False: orthonormal float arrays of shape (2n, n_S) and (2n, n_A). True: integer
        ``sympy.ImmutableMatrix`` columns :math:`e_i \\pm e_{n-1-i}` (same span, unnormalised).

    >>> B = mirror_bases(3)
    >>> B["S"].shape, B["A"].shape
    ((6, 3), (6, 3))
    >>> mirror_bases(2, exact=True)["S"].tolist()
    [[1, 0], [1, 0], [0, 1], [0, -1]]
    """
    if isinstance(patch_or_n, PlatePatch):
        if not patch_or_n.symmetric:
            return None
        n = patch_or_n.n
    else:
        n = check_positive_int("control points n", patch_or_n)
    bases = dict(zip(("S", "A"), _mirror_integer_bases(n)))
    if exact:
        return bases
    out = {}
    for k, E in bases.items():
        F = np.array(E, dtype=float)
        out[k] = F / np.linalg.norm(F, axis=0) if F.shape[1] else F
    return out


@lru_cache(maxsize=None)
def _mirror_integer_bases(n: int) -> tuple[sympy.ImmutableMatrix, sympy.ImmutableMatrix]:
    """Integer mirror bases (S, A), shape (2n, n_S) and (2n, n_A); immutable (cached)."""
    half = n // 2
    even = [[1 if i in (c, n - 1 - c) else 0 for i in range(n)] for c in range(half)]
    if n % 2:
        even.append([1 if i == half else 0 for i in range(n)])
    odd = [[1 if i == c else (-1 if i == n - 1 - c else 0) for i in range(n)]
           for c in range(half)]

    def stack(top, bottom):
        cols = [v + [0] * n for v in top] + [[0] * n + v for v in bottom]
        return sympy.ImmutableMatrix(2 * n, len(cols), lambda i, j: cols[j][i])

    return stack(even, odd), stack(odd, even)
