"""Critical time step of central differences for any mass rule: :math:`\\Delta t_{crit} = 2/\\omega_{max}`.

Central differences are stable for :math:`\\omega_{max} \\Delta t \\le 2` (Hughes 2000, 9.3),
with :math:`\\omega_{max}` the largest discrete frequency. For a uniform mesh it is the
largest frequency over the Brillouin zone :math:`\\theta \\in [0, \\pi]` of the Bloch patch:

* the periodic 1D bar (element length h, wave speed c), one branch,

  .. math::

      \\left(\\frac{\\omega h}{c}\\right)^2 = \\frac{d(\\theta)}{m(\\theta)}, \\quad
      d = \\sum_L c^{11}_L \\cos L\\theta, \\quad m = \\sum_L a_L \\cos L\\theta,

  a rational function of :math:`z = \\cos\\theta` (:math:`\\cos L\\theta = T_L(z)`), maximised
  *exactly*: at :math:`z = \\pm 1` and the real roots of :math:`d' m - d m'` in (-1, 1)
  (sympy's exact root isolation); p = 1 gives :math:`h/c` lumped and
  :math:`h/(\\sqrt 3 c)` consistent.
* the Bloch plate patch (:func:`dispersion.symbolic.plate.plate_patch`, plane strain), all
  :math:`2n` branches: exact at the zone ends :math:`\\theta = 0, \\pi` (there the pencil is
  rational; the largest root of its characteristic polynomial is isolated exactly), and a
  grid of ``n_theta`` phases refined by bounded maximisation inside. The result says which
  one gave the maximum (``method``); :func:`certified_omega_max` (``certify=True``) adds a
  *proven* upper bound within 0.1 % by interval arithmetic, hence a proven stable step.
  Massless DOFs (singular rules) are condensed,
  :math:`\\hat K = K_{rr} - K_{rm} K_{mm}^{-1} K_{mr}`, as the explicit scheme solves them.

A finite (non-periodic) mesh has boundary modes: for p >= 2 its :math:`\\omega_{max}` exceeds
the Bloch value (the "outliers" of Cottrell et al. 2006), so its stable step is smaller;
:func:`matrix_critical_step` gives it from assembled matrices.

>>> cs = critical_step("lumped", 1, model="bar", wave_speed=1.0, h=1.0)
>>> cs.omega_max_exact, round(cs.dt, 12), round(cs.ratio, 12)     # h/c, and sqrt(3) vs consistent
(2, 1.0, 1.732050807569)

References
----------
T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3. J. A. Cottrell, A. Reali,
Y. Bazilevs, T. J. R. Hughes, "Isogeometric analysis of structural vibrations", CMAME 195
(2006) 5257-5296. T. Belytschko, W. K. Liu, B. Moran, *Nonlinear Finite Elements for Continua
and Structures*, Wiley 2000, sec. 6.3.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import sympy

from dispersion.budget import check_bar_degree, check_phases
from dispersion.errors import (InputError, check_positive, check_positive_int,
                               check_real_in_range)
from dispersion.rendering import Rendered
from dispersion.mass_rules.mass_rule import get_rule, x_mass_coefficients
from dispersion.discretization.bar_dispersion import bar_rule
from dispersion.materials.materials import MATERIALS, Material
from dispersion.time_stepping.omega_max_bound import certified_omega_max
from dispersion.time_stepping.time_integration import CRITICAL_STEP_MODELS, H_RANGE

__all__ = ["MATERIALS", "CRITICAL_STEP_MODELS", "EXACT_MAX_DOFS", "MAX_N", "H_RANGE",
           "certified_omega_max",
           "CriticalStep", "bar_omega_squared", "critical_time_step", "float_pencil",
           "bar_omega_max", "patch_omega_max", "critical_step", "matrix_critical_step"]


_z = sympy.Symbol("z")


def _coefficients(rule, p: int):
    from dispersion.discretization.bar_dispersion import bar_stiffness_coefficients

    return bar_stiffness_coefficients(rule, p), dict(x_mass_coefficients(rule, p))


def bar_omega_squared(mass, p: int) -> sympy.Expr:
    """Exact :math:`(\\omega h / c)^2` of the periodic bar as a rational function of :math:`z = \\cos\\theta`.

    >>> sympy.factor(bar_omega_squared("consistent", 1))
    -6*(z - 1)/(z + 2)
    """
    rule = bar_rule(mass)
    p = check_bar_degree(check_positive_int("degree p", p))  # cost bound: dispersion.budget
    if rule.basis == "lagrange":
        raise InputError(f"mass {rule.name!r}: the C0 Lagrange bar has p branches, no single "
                         "rational omega^2(cos theta) (its acoustic series: "
                         "dispersion.splines.lagrange_sem.acoustic_series)")
    c11, a = _coefficients(rule, p)
    d = sum(v * sympy.chebyshevt(abs(L), _z) for L, v in c11.items())
    m = sum(v * sympy.chebyshevt(abs(L), _z) for L, v in a.items())
    return sympy.cancel(sympy.expand(d) / sympy.expand(m))


def bar_omega_max(mass, p: int) -> tuple[sympy.Expr, float]:
    """Exact :math:`\\max_\\theta \\omega h / c` of the periodic bar and the phase where it is reached.

    >>> bar_omega_max("consistent", 2)      # Cottrell et al. 2006: sqrt(10) at theta = pi
    (sqrt(10), 3.141592653589793)
    """
    if bar_rule(mass).basis == "lagrange":  # p branches: the Bloch pencil's largest root
        from dispersion.discretization.sem_bar import sem_bar_omega_max

        w, exact, theta, _ = sem_bar_omega_max(bar_rule(mass).name, p)
        return (exact if exact is not None else sympy.Float(w, 15)), theta
    f = bar_omega_squared(mass, p)
    num, den = sympy.fraction(sympy.together(f))
    crit = sympy.Poly(sympy.expand(sympy.diff(num, _z) * den - num * sympy.diff(den, _z)), _z)
    candidates = [sympy.Integer(-1), sympy.Integer(1)]
    if crit.degree() > 0:
        candidates += [z for z in crit.real_roots() if -1 < z < 1]
    best, best_val = None, None
    for z in candidates:
        val = f.subs(_z, z)
        num_val = sympy.N(val, 40)
        if best_val is None or num_val > best_val:
            best, best_val = z, num_val
    exact = sympy.sqrt(f.subs(_z, best))   # rational at a rational z: stays exact
    return sympy.simplify(exact), float(sympy.acos(best))


@dataclass(frozen=True, repr=False)  # Rendered: a short repr
class CriticalStep(Rendered):
    """Critical step of central differences for one rule, with what it was computed from.

    ``omega_max`` is dimensionless: :math:`\\omega_{max} h / c` (bar: h the element length,
    c the wave speed) or :math:`\\omega_{max} H / c_T` (plate: H the half-thickness);
    ``dt`` is :math:`2 / \\omega_{max}` in seconds for ``h`` (m) and the material; ``ratio``
    is ``dt`` over the consistent mass's; ``method`` says how the maximum was found.
    """

    mass: str
    p: int
    model: str
    h: float
    wave_speed: float
    omega_max: float
    omega_max_exact: object
    theta: float
    method: str
    dt: float
    dt_consistent: float
    n: int | None = None
    r: object = None
    nu: float | None = None
    material: str | None = None
    #: Proven upper bound on omega_max (dimensionless, :func:`certified_omega_max`), or None.
    omega_certified: float | None = None
    #: What was asked for and could not be done (a proof that did not close), in words.
    failures: tuple[str, ...] = ()

    @property
    def ratio(self) -> float:
        return self.dt / self.dt_consistent

    @property
    def dt_certified(self) -> float | None:
        """A proven stable step :math:`2/\\bar\\Omega` in seconds (None if not certified)."""
        if self.omega_certified is None:
            return None
        return self.dt * self.omega_max / self.omega_certified

    # the rendering protocol: one row; the words of describe() as title and header
    def title(self) -> str:
        return self.describe().splitlines()[0]

    def header_lines(self) -> list[str]:
        return self.describe().splitlines()[1:]

    def columns(self) -> tuple[str, ...]:
        return ("mass", "p", "model", "omega_max", "theta", "found", "dt_crit [s]",
                "ratio to consistent", "omega_max proven bound", "proven stable dt [s]")

    def rows(self) -> list[dict]:
        return [dict(zip(self.columns(), (self.mass, self.p, self.model, self.omega_max,
                                          self.theta, self.method, self.dt, self.ratio,
                                          self.omega_certified, self.dt_certified)))]

    def describe(self) -> str:
        """Lines for a terminal, rendered from the fields."""
        where = "pi" if abs(self.theta - math.pi) < 1e-12 else f"{self.theta:.6g}"
        if self.model == "bar":
            setting = (f"periodic 1D bar, element length h = {self.h:g} m, wave speed "
                       f"c = {self.wave_speed:g} m/s")
            unit = "omega_max h / c"
        else:
            setting = (f"Bloch plate patch (plane strain, nu = {self.nu:.4g}): n = {self.n} control "
                       f"points through the thickness, element length h = {self.h:g} m, "
                       f"aspect ratio r = b/H = {self.r}, c_T = {self.wave_speed:g} m/s")
            unit = "omega_max H / c_T"
        shown = str(self.omega_max_exact)
        # a closed form only where it reads better than the number (a float nu rationalises
        # to long integers)
        exact = "" if self.omega_max_exact is None or shown == f"{self.omega_max:.12g}" \
            or len(shown) > 40 else f" = {shown}"
        mat = f", material {self.material}" if self.material else ""
        lines = [
            f"mass {self.mass}, p = {self.p}{mat}; {setting}",
            f"{unit} = {self.omega_max:.12g}{exact} at theta = {where} ({self.method})",
            f"Delta t_crit = 2 / omega_max = {self.dt:.6g} s; ratio to consistent mass "
            f"= {self.ratio:.6g}",
        ]
        if self.omega_certified is not None:
            lines.append(f"proven: {unit} <= {self.omega_certified:.12g} (interval arithmetic), "
                         f"so {self.dt_certified:.6g} s is a proven stable step")
        lines += [f"not proven: {why}" for why in self.failures]
        return "\n".join(lines)


def _edge_omega_max(patch, theta) -> tuple[sympy.Expr, float] | None:
    """Exact largest Omega of the condensed pencil at theta = 0 or pi (rational there).

    Every entry is rational (the law's moduli, :meth:`~dispersion.materials.elastic_law.ElasticLaw.exact`:
    nu by its shortest decimal;
    the x-functions at theta = 0 or pi are integers), and the arithmetic stays in QQ: no
    float, no surd (sympy's root isolation needs a polynomial over QQ).
    """
    from sympy.polys.matrices import DomainMatrix

    from dataclasses import replace

    from dispersion.symbolic.plate import dynamic_stiffness

    kappa = sympy.Integer(0) if theta == 0 else sympy.pi / patch.r
    exact = replace(patch, law=patch.law.exact())
    Kd = sympy.Matrix(dynamic_stiffness(exact, kappa, sympy.Integer(0)))
    M = -(sympy.Matrix(dynamic_stiffness(exact, kappa, sympy.Integer(1))) - Kd)
    K, M = (DomainMatrix.from_Matrix(A).convert_to(sympy.QQ) for A in (Kd, M))
    ml = list(patch.massless)
    keep = [i for i in range(K.shape[0]) if i not in ml]
    if ml:
        Krm, Kmm = K.extract(keep, ml), K.extract(ml, ml)
        K = K.extract(keep, keep) - Krm * Kmm.inv() * Krm.transpose()
        M = M.extract(keep, keep)
    # det(K - lam M) = det(M) det(M^-1 K - lam): the characteristic polynomial over QQ
    coeffs = (M.inv() * K).charpoly()
    poly = sympy.Poly(coeffs, sympy.Symbol("lam"), domain=sympy.QQ)
    roots = poly.real_roots()
    if not roots:
        return None
    top = max(roots, key=lambda v: sympy.N(v, 40))
    return sympy.sqrt(top), float(sympy.N(sympy.sqrt(top), 20))


def float_pencil(patch, nu):
    """``kappa -> (K, M)`` float stacks of :func:`dispersion.symbolic.plate.numeric_pencil`,
    its constant matrices converted once (the pencil is evaluated many times here)."""
    from dispersion.symbolic.plate import with_nu

    patch = with_nu(patch, nu)
    from dispersion.symbolic.plate import mass_block, stiffness_terms, x_functions

    mat = patch.law.float_moduli()
    terms = [(mat[m], f, np.array(B, dtype=float)) for m, f, B in stiffness_terms(patch)]
    M0 = np.array(mass_block(patch), dtype=float)

    def pencil(kappa):
        kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
        xf = x_functions(patch, kappa)
        K = sum(c * xf[f][:, None, None] * B for c, f, B in terms)
        return K, xf["mx"][:, None, None] * M0

    return pencil


#: Largest pencil (2n DOFs) whose zone-end maximum is certified symbolically. Rule: the
#: exact characteristic polynomial takes at most about a second (measured, p = 2, HRZ:
#: 2n = 8 0.29 s, 10 0.61 s, 12 0.88 s, 14 2.0 s on the shared 2-core machine).
EXACT_MAX_DOFS = 12
#: Most control points through the thickness for a critical step (as ``dispersion branches``):
#: the exact patch of p = 2, n = 24 builds and is maximised in about 8 s (measured).
MAX_N = 24


def patch_omega_max(patch, nu, n_theta: int = 65, exact: bool = True
                    ) -> tuple[float, object, float, str]:
    """Largest :math:`\\Omega` of a numeric Bloch patch over the zone: ``(value, exact, theta, method)``.

    ``exact`` (returned) is a sympy number where the maximum sits at a zone end (else None);
    ``exact=False`` skips that symbolic check and reports the float maximum of the grid.
    """
    from dispersion.symbolic.plate import with_nu

    patch = with_nu(patch, nu)
    from dispersion.discretization.pencil_frequencies import pencil_frequencies

    n_theta = check_phases(check_positive_int("n_theta", n_theta, minimum=3), 2 * patch.n)
    if patch.model != "bloch" or isinstance(patch.r, sympy.Symbol):
        raise InputError("the critical step needs a Bloch patch with a numeric aspect ratio r")
    r = float(patch.r)
    pencil = float_pencil(patch, None)

    def top(theta):
        K, M = pencil(np.atleast_1d(theta) / r)
        return pencil_frequencies(K, M, patch.massless)[:, -1]

    theta = np.linspace(0.0, math.pi, n_theta)
    values = top(theta)
    i = int(np.argmax(values))
    best, where = float(values[i]), float(theta[i])
    if 0 < i < n_theta - 1:  # interior maximum: the root of its slope between the neighbours
        where = _interior_maximum(patch, pencil, theta[i - 1], theta[i + 1], top)
        best = max(best, float(top(where)[0]))
        return best, None, where, (f"numeric: grid of {n_theta} phases, the root of the "
                                   "slope between its neighbours")
    if not exact or 2 * patch.n > EXACT_MAX_DOFS:
        return best, None, where, f"numeric: grid of {n_theta} phases, maximum at a zone end"
    edge = _edge_omega_max(patch, 0 if i == 0 else 1)
    if edge is None or abs(edge[1] - best) > 1e-9 * best:
        raise InputError("exact and float largest frequency disagree at the zone end; "
                         "the pencil is ill-conditioned")
    return edge[1], edge[0], where, f"exact at the zone end (grid of {n_theta} phases found no larger)"


def _interior_maximum(patch, pencil, lo: float, hi: float, top) -> float:
    """Phase of the largest frequency in (lo, hi): the root of its slope (Hellmann-Feynman,
    :math:`d\\Omega/d\\theta = x^T (K' - \\Omega^2 M') x / (2 \\Omega\\, x^T M x)`, the
    derivatives by the complex step), so located to rounding (a search on the values
    themselves finds a flat maximum only to about the square root of eps, 3e-8); a
    bounded search on the values where the slope keeps its sign (a maximum at a crossing
    of two branches, where the top branch has a kink)."""
    from scipy.optimize import brentq, minimize_scalar

    from dispersion.discretization.discrete_branches import pencil_derivative
    from dispersion.discretization.pencil_frequencies import pencil_frequencies

    r = float(patch.r)

    def slope(theta):
        K, M = pencil(np.atleast_1d(theta) / r)
        W, X = pencil_frequencies(K, M, patch.massless, vectors=True)
        dK, dM = pencil_derivative(patch, None, np.atleast_1d(theta) / r)
        x, w = X[0, :, -1], W[0, -1]
        return float((x @ dK[0] @ x - w * w * (x @ dM[0] @ x)) / (2 * w * (x @ M[0] @ x)))

    a, b = slope(lo), slope(hi)
    if a > 0 > b:
        return float(brentq(slope, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps))
    res = minimize_scalar(lambda t: -float(top(t)[0]), bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-12})
    return float(res.x)


def critical_time_step(patch, nu, n_theta: int = 65, certify: bool = False) -> float:
    """Largest stable step of explicit central differences for a Bloch patch, in :math:`H/c_T`.

    .. math:: \\Delta t_{crit} = 2 / \\max_{\\theta \\in [0, \\pi]} \\Omega(\\theta / r)

    with the maximum of :func:`patch_omega_max` (grid of ``n_theta`` phases, refined inside,
    exact at a zone end); ``certify=True`` returns :math:`2/\\bar\\Omega` with the proven
    bound of :func:`certified_omega_max` instead, a proven stable step.

    >>> from dispersion.symbolic.plate import plate_patch
    >>> 0 < critical_time_step(plate_patch(model="bloch", r=2), 0.3, n_theta=9) < 1
    True
    """
    from dispersion.symbolic.plate import with_nu

    patch = with_nu(patch, nu)
    omega = patch_omega_max(patch, None, n_theta)[0]
    return 2.0 / (certified_omega_max(patch, None, omega) if certify else omega)


def critical_step(mass, p: int = 2, *, model: str = "plate", material: Material | str = "steel",
                  h: float = 1.0, n: int | None = None, wave_speed: float | None = None,
                  contact: str = "top", gamma_s=sympy.Rational(1, 2), n_theta: int = 65,
                  certify: bool = False) -> CriticalStep:
    """Critical step of central differences for rule ``mass`` and its ratio to the consistent mass.

    Parameters
    ----------
    mass : str or MassRule
    p : int
        Degree, 1 <= p <= 24.
    model : ``"plate"`` or ``"bar"``
        ``"plate"``: the Bloch plate patch with ``n`` (default max(p + 1, 3), the singular
        rules need three) control points through
        the thickness and square elements of edge ``h`` (m): thickness :math:`2H = (n - p) h`,
        aspect ratio :math:`r = 2/(n - p)`; Poisson's ratio and :math:`c_T` of ``material``.
        ``"bar"``: the periodic bar, element length ``h``, wave speed ``wave_speed`` (default
        the material's bar speed :math:`\\sqrt{E/\\rho} = c_T \\sqrt{2(1+\\nu)}`).
    material : Material or name in :data:`MATERIALS`
    contact, gamma_s :
        Contact set and weight of the singular rules (plate only).
    certify : bool
        Plate only: also prove an upper bound on omega_max within 0.1 %
        (:func:`certified_omega_max`); the bar's maximum is exact already. A proof that
        does not close is listed in ``CriticalStep.failures`` (never reported as a false
        bound).

    >>> cs = critical_step("hrz", 2, model="bar", wave_speed=1.0)
    >>> cs.omega_max_exact, round(cs.theta, 6), round(cs.ratio, 6)  # at 2 pi/3; sqrt(10)/sqrt(3/2)
    (sqrt(6)/2, 2.094395, 2.581989)
    """
    if model not in CRITICAL_STEP_MODELS:
        raise InputError(f"model must be one of {', '.join(CRITICAL_STEP_MODELS)}; got {model!r}")
    if isinstance(material, str):
        if material not in MATERIALS:
            raise InputError(f"material must be one of {', '.join(MATERIALS)}; got {material!r}")
        material = MATERIALS[material]
    h = float(check_real_in_range("h", h, *H_RANGE))
    rule = get_rule(mass)
    if model == "bar":
        c = float(check_positive("wave_speed", wave_speed)) if wave_speed is not None \
            else material.c_T * math.sqrt(2 * (1 + material.nu))
        exact, theta = bar_omega_max(rule, p)
        ref, _ = bar_omega_max("consistent", p)
        w, w_ref = float(exact), float(ref)
        method = ("exact (rational function of cos theta)" if rule.basis == "bspline" else
                  "C0 Lagrange bar: all p branches, " + ("exact at a zone end"
                                                         if exact.is_algebraic else "numeric"))
        return CriticalStep(rule.name, p, "bar", h, c, w, exact, theta, method,
                            2 * h / (c * w),
                            2 * h / (c * w_ref),
                            material=None if wave_speed is not None else material.name)
    from dispersion.symbolic.patch import check_size
    from dispersion.symbolic.plate import plate_patch

    n = max(p + 1, 3) if n is None else n
    if isinstance(n, int) and not isinstance(n, bool) and n > MAX_N:  # plate allows N_MAX
        raise InputError(f"control points n must be an integer in [p + 1, {MAX_N}] for a "
                         f"critical step, got {n}")
    p, n = check_size(p, n)
    r = sympy.Rational(2, n - p)
    nu = material.nu
    if rule.basis == "lagrange":  # the plate's Bloch patch has no such rule; the bar has
        raise InputError(f"mass {rule.name!r} uses C0 Lagrange elements, which carry p DOFs a "
                         "cell along x; the Bloch plate patch has one B-spline symbol there",
                         ways=[("model", "bar")])
    patch = plate_patch(p, n, "bloch", r, rule, contact, gamma_s, nu=nu)
    w, exact, theta, method = patch_omega_max(patch, None, n_theta)
    w_ref = patch_omega_max(plate_patch(p, n, "bloch", r, "consistent", nu=nu), None, n_theta)[0]
    H = (n - p) * h / 2
    c = material.c_T
    proven, failures = None, ()
    if certify:
        from dispersion.errors import ConvergenceError

        try:
            proven = certified_omega_max(patch, None, w)
        except ConvergenceError as exc:
            failures = (f"no proven stable step: {exc}",)
    return CriticalStep(rule.name, p, "plate", h, c, w, exact, theta, method, 2 * H / (c * w),
                        2 * H / (c * w_ref), n, r, nu, material.name, proven, failures)


def matrix_critical_step(K, M, tol: float = 1e-12) -> float:
    """:math:`2/\\omega_{max}` of assembled matrices, zero rows of M condensed (free surface).

    >>> round(matrix_critical_step(np.array([[2.0, -1.0], [-1.0, 2.0]]), np.diag([1.0, 0.0])), 9)
    1.632993162
    """
    import scipy.linalg as sla
    import scipy.sparse as sp

    K = K.toarray() if sp.issparse(K) else np.asarray(K, dtype=float)
    M = M.toarray() if sp.issparse(M) else np.asarray(M, dtype=float)
    zero = np.all(np.abs(M) <= tol * np.abs(M).max(), axis=1)
    r, m = np.flatnonzero(~zero), np.flatnonzero(zero)
    Kh = K[np.ix_(r, r)]
    if m.size:
        Kh = Kh - K[np.ix_(r, m)] @ np.linalg.solve(K[np.ix_(m, m)], K[np.ix_(m, r)])
    w2 = float(sla.eigh(Kh, M[np.ix_(r, r)], eigvals_only=True)[-1])
    return 2.0 / math.sqrt(w2) if w2 > 0 else math.inf
