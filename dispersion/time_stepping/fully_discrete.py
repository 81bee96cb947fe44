"""Fully discrete dispersion: the patch's semi-discrete frequency through a Newmark time stepper.

A mode of the semi-discrete patch with frequency :math:`\\Omega_h` (:mod:`.discrete_branches`)
integrated by Newmark's method with step :math:`\\tau` (all in the units of the patch, here
:math:`h / c_T`) obeys the three-term recurrence with amplification :math:`z`,

.. math::

    (1 + \\beta X) z^2 - (2 - (\\tfrac12 - 2\\beta + \\gamma) X) z + (1 + (\\tfrac12 + \\beta - \\gamma) X)
    = 0, \\qquad X = (\\Omega_h \\tau)^2,

and travels with the fully discrete frequency :math:`\\tilde\\Omega = |\\arg z| / \\tau`.
For :math:`\\gamma = \\tfrac12` (no numerical damping) while stable,

.. math::

    \\cos \\tilde\\Omega\\tau = 1 - \\frac{X}{2 (1 + \\beta X)}, \\qquad
    \\text{central differences } (\\beta = 0): \\;
    \\sin \\frac{\\tilde\\Omega \\tau}{2} = \\frac{\\Omega_h \\tau}{2},

so :math:`\\tilde\\Omega^2 = \\tau^{-2} g(X)` with
:math:`g = 2 \\sum_{m \\ge 1} (2y)^m / (m^2 \\binom{2m}{m})`, :math:`y = X / (2 (1 + \\beta X))`
(from :math:`\\arcsin^2 x = \\tfrac12 \\sum (2x)^{2m} / (m^2 \\binom{2m}{m})`); substituting the
semi-discrete series :math:`\\Omega_h^2(\\kappa)` gives the series in :math:`\\kappa` and
:math:`\\tau` (:func:`fully_discrete_series`). Central differences lag (:math:`\\tilde\\Omega >
\\Omega_h`), the trapezoidal rule (:math:`\\beta = 1/4`) leads the other way, so a lumped mass
(too soft) and central differences partly cancel: for p = 1 at the critical step the bar is
exact (:math:`\\tilde\\omega = c k`, the "magic" time step).

The Courant number here is :math:`C = \\tau / \\tau_{crit}`, the step as a fraction of the
central-difference limit of the same patch and mass (:mod:`.timestep`).

>>> import numpy as np
>>> float(np.round(time_frequency(np.array([1.0]), 1.0)[0], 12))    # 2 arcsin(1/2) = pi/3
1.047197551197

References
----------
T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3 (Newmark's method,
amplification matrix, period error). N. M. Newmark, "A method of computation for structural
dynamics", J. Eng. Mech. Div. ASCE 85 (1959) 67-94.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import sympy

from dispersion.budget import check_series_work, check_time_terms
from dispersion.errors import InputError, check_positive, check_positive_int, check_real_in_range
from dispersion.time_stepping.time_integration import NEWMARK_MEMBERS

__all__ = ["NEWMARK_MEMBERS", "TimeScheme", "time_scheme", "time_frequency", "time_frequency_slope",
           "fully_discrete_branches",
           "fully_discrete_error", "time_series", "fully_discrete_series"]



@dataclass(frozen=True)
class TimeScheme:
    """A Newmark member: ``name``, ``beta``, ``gamma`` (exact where given exactly)."""

    name: str
    beta: object
    gamma: object

    @property
    def explicit(self) -> bool:
        return self.beta == 0

    def stability_limit(self) -> float:
        """Largest stable :math:`\\Omega_h \\tau`: :math:`1/\\sqrt{\\gamma/2 - \\beta}` (inf if unconditional).

        >>> time_scheme("central").stability_limit()
        2.0
        """
        s = float(self.gamma) / 2 - float(self.beta)
        return math.inf if s <= 0 else 1 / math.sqrt(s)


def time_scheme(name: str = "central", beta=None, gamma=None) -> TimeScheme:
    """A :class:`TimeScheme` by name (:data:`~dispersion.time_stepping.time_integration.NEWMARK_MEMBERS`) or ``"newmark"`` with ``beta``, ``gamma``.

    ``gamma >= 1/2`` and ``beta`` in [0, 1/2] (Hughes 2000, 9.3: stability needs gamma >= 1/2).
    """
    if name in NEWMARK_MEMBERS:
        if beta is not None or gamma is not None:
            raise InputError(f"scheme {name!r} fixes beta and gamma; use scheme 'newmark' to set them")
        return TimeScheme(name, *(sympy.Rational(x.numerator, x.denominator)
                                  for x in NEWMARK_MEMBERS[name]))
    if name != "newmark":
        raise InputError(f"scheme must be one of {', '.join(list(NEWMARK_MEMBERS) + ['newmark'])}; "
                         f"got {name!r}")
    if beta is None or gamma is None:
        raise InputError("scheme 'newmark' needs beta and gamma")
    beta = check_real_in_range("beta", beta, 0, 0.5)
    gamma = check_real_in_range("gamma", gamma, 0.5, 1)
    return TimeScheme("newmark", beta, gamma)


def _newmark_terms(sch: TimeScheme, w, tau: float):
    """``X``, the constants ``p``, ``q``, ``r`` and the stable-oscillation mask of the recurrence.

    With :math:`p = \\tfrac12 - 2\\beta + \\gamma`, :math:`q = \\tfrac12 + \\beta - \\gamma`
    (:math:`p + \\beta + q = 1`), the discriminant of the recurrence is, expanded by hand so
    that nothing cancels at small X,

    .. math:: b^2 - 4ac = -X\\,(4 - rX), \\qquad r = p^2 - 4\\beta q,

    the roots are complex (oscillation) for :math:`rX < 4` (a double root on the limit
    :math:`rX = 4`, counted as stable as in Hughes 2000), and :math:`|z|^2 = c/a =
    (1 + qX)/(1 + \\beta X) \\le 1` for :math:`q \\le \\beta`, that is :math:`\\gamma \\ge 1/2`.
    """
    beta, gamma = float(sch.beta), float(sch.gamma)
    w = np.abs(np.asarray(w, dtype=float))
    X = (w * tau) ** 2
    p, q = 0.5 - 2 * beta + gamma, 0.5 + beta - gamma
    r = p * p - 4 * beta * q
    with np.errstate(invalid="ignore"):
        ok = r * X <= 4   # |z| <= 1 holds already: time_scheme keeps gamma >= 1/2
    return w, X, beta, p, q, r, ok


def time_frequency(omega_h, tau, scheme: TimeScheme | str = "central"):
    """Fully discrete :math:`\\tilde\\Omega` for semi-discrete ``omega_h`` and step ``tau`` (arrays).

    .. math::

        \\tilde\\Omega\\tau = \\arg z = \\operatorname{atan2}\\bigl(\\Omega_h\\tau\\sqrt{4 - rX},
        \\; 2 - pX\\bigr)

    (:func:`_newmark_terms`): both arguments are computed without cancellation, so the
    result keeps the relative accuracy of :math:`\\Omega_h` at every :math:`X > 0` (the
    textbook form :math:`\\arccos(1 - X/(2(1 + \\beta X)))` loses :math:`\\epsilon / X`
    relative and returns 0 below :math:`X \\approx 10^{-16}`); central differences:
    :math:`2 \\arcsin(\\Omega_h\\tau / 2)`. NaN where the step is unstable or the roots
    are real (no oscillation).

    >>> float(time_frequency(np.array([1e-12]), 1.0)[0])    # no cancellation: Omega_h itself
    1e-12
    """
    sch = time_scheme(scheme) if isinstance(scheme, str) else scheme
    tau = float(check_positive("tau", tau))
    w, X, beta, p, q, r, ok = _newmark_terms(sch, omega_h, tau)
    with np.errstate(invalid="ignore"):
        theta = np.arctan2(w * tau * np.sqrt(4 - r * X), 2 - p * X) / tau
    return np.where(ok, theta, np.nan)


def time_frequency_slope(omega_h, tau, scheme: TimeScheme | str = "central"):
    """:math:`d\\tilde\\Omega / d\\Omega_h` of :func:`time_frequency` (NaN where that is NaN).

    Differentiating :math:`\\arg z` and simplifying by hand (the numerator collapses to
    :math:`4(2 + (p - r)X)` through :math:`p + \\beta + q = 1`):

    .. math::

        \\frac{d\\tilde\\Omega}{d\\Omega_h} = \\frac{2 + (p - r) X}{\\sqrt{4 - rX}\\,(1 + \\beta X)
        (1 + qX)};

    central differences: :math:`1/\\cos(\\tilde\\Omega\\tau/2)`. The fully discrete group
    velocity is this times the semi-discrete one (chain rule).

    >>> float(time_frequency_slope(np.array([1.0]), 1.0)[0])   # 1 / cos(pi/6)
    1.1547005383792517
    """
    sch = time_scheme(scheme) if isinstance(scheme, str) else scheme
    tau = float(check_positive("tau", tau))
    w, X, beta, p, q, r, ok = _newmark_terms(sch, omega_h, tau)
    with np.errstate(invalid="ignore", divide="ignore"):
        slope = (2 + (p - r) * X) / (np.sqrt(4 - r * X) * (1 + beta * X) * (1 + q * X))
    return np.where(ok, slope, np.nan)


def fully_discrete_branches(branches, tau: float, scheme: TimeScheme | str = "central"):
    """The :class:`~.discrete_branches.DiscreteBranches` with every :math:`\\Omega_h` mapped by
    :func:`time_frequency`, group velocities (where computed) by the chain rule
    (:func:`time_frequency_slope`); the failures of the semi-discrete branches are kept."""
    omega = {lab: time_frequency(w, tau, scheme) for lab, w in branches.omega.items()}
    group = None
    if branches.group is not None:
        group = {lab: g * time_frequency_slope(branches.omega[lab], tau, scheme)
                 for lab, g in branches.group.items()}
    return replace(branches, omega=omega, group=group)


def fully_discrete_error(patch, nu, kappa, courant: float,
                         scheme: TimeScheme | str = "central") -> dict[str, np.ndarray]:
    """Signed phase-velocity error :math:`\\tilde\\Omega / \\Omega - 1` of S0 and A0 at ``kappa``.

    The step is ``courant`` times the patch's central-difference critical step
    (:func:`dispersion.time_stepping.timestep.patch_omega_max`); :math:`\\Omega` is the exact
    Rayleigh-Lamb root at the same kappa (so the ratio of frequencies is the ratio of phase
    velocities; an isotropic plate: :meth:`~dispersion.materials.elastic_law.ElasticLaw.poisson_ratio`).
    NaN where the step is unstable for that mode.

    >>> from dispersion.symbolic.plate import plate_patch
    >>> err = fully_discrete_error(plate_patch(mass="lumped"), 0.3, [0.2], 0.5)
    >>> sorted(err), bool(abs(err["S0"][0]) < 0.05)
    (['A0', 'S0'], True)
    """
    from dispersion.symbolic.plate import with_nu

    patch = with_nu(patch, nu)
    from dispersion.discretization.discrete_branches import fundamental_branches
    from dispersion.continuum.exact_branches import trace_branches
    from dispersion.time_stepping.timestep import patch_omega_max

    nu = patch.law.poisson_ratio("exact Rayleigh-Lamb branches")
    courant = float(check_positive("courant", courant))
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    if np.any(kappa <= 0) or not np.all(np.isfinite(kappa)):
        raise InputError("kappa must be finite and > 0 (the phase velocity needs kappa > 0)")
    tau = courant * 2 / patch_omega_max(patch, None, exact=False)[0]
    semi = fundamental_branches(patch, None, kappa)
    top = max(float(np.nanmax(w)) for w in semi.values())
    exact = trace_branches(nu, kappa, 2 * top + 1).omega
    return {lab: time_frequency(semi[lab], tau, scheme) / exact[lab] - 1 for lab in ("S0", "A0")}


_X = sympy.Symbol("X")


def time_series(order: int, beta=0) -> list:
    """Coefficients :math:`g_m` of :math:`(\\tilde\\Omega\\tau)^2 = \\sum_{m=1}^{order} g_m X^m`, gamma = 1/2.

    >>> time_series(3)                   # central differences: 1, 1/12, 1/90
    [1, 1/12, 1/90]
    >>> time_series(2, sympy.Rational(1, 4))    # trapezoidal rule: 1, -1/6 (leads)
    [1, -1/6]
    """
    order = check_time_terms(check_positive_int("order", order))  # dispersion.budget
    from dispersion.symbolic.patch import rational

    beta = rational("beta", beta)   # exact: floats by their shortest decimal, never surds
    y = _X / (2 * (1 + beta * _X))
    g = 2 * sum((2 * y) ** m / (m**2 * sympy.binomial(2 * m, m)) for m in range(1, order + 1))
    poly = sympy.series(g, _X, 0, order + 1).removeO()
    return [sympy.cancel(poly.coeff(_X, m)) for m in range(1, order + 1)]


def fully_discrete_series(omega2: dict, order: int, beta=0) -> sympy.Expr:
    """:math:`\\tilde\\Omega^2` as a polynomial in kappa and tau to total kappa-order ``order``.

    ``omega2`` is a semi-discrete series ``{k: a_k}`` of :math:`\\Omega_h^2 = \\sum a_k \\kappa^k`
    (:func:`dispersion.symbolic.power_balance.discrete_series`); terms of kappa-order above
    ``order`` are dropped. Central differences by default (gamma = 1/2 always).

    >>> k, t = sympy.symbols("kappa tau")
    >>> sympy.expand(fully_discrete_series({2: 1}, 4))      # Omega_h = kappa, central
    kappa**4*tau**2/12 + kappa**2
    """
    order = check_positive_int("order", order)
    kappa, tau = sympy.symbols("kappa tau")
    lowest = min((k for k, v in omega2.items() if v != 0), default=None)
    if lowest is None or lowest < 1:
        raise InputError("omega2 must be a series with a first nonzero term at kappa^k, k >= 1")
    terms = check_time_terms(order // lowest, "order // lowest power")  # dispersion.budget
    from dispersion.reader import as_sympy

    # numbers and sympy expressions; text (also inside a tuple or a dict) is refused
    omega2 = {k: as_sympy(f"omega2[{k}]", v) for k, v in omega2.items()}
    kept = [v for k, v in omega2.items() if k <= order and v != 0]
    check_series_work(len(kept), terms, any(v.free_symbols for v in kept))
    g = time_series(max(terms, 1), beta)
    S = sum(v * kappa**k for k, v in omega2.items() if k <= order)
    out = sympy.Integer(0)
    for m, gm in enumerate(g, start=1):
        power = sympy.expand(S**m)
        trunc = sum(power.coeff(kappa, k) * kappa**k for k in range(order + 1))
        out += gm * tau ** (2 * m - 2) * trunc
    return sympy.expand(out)
