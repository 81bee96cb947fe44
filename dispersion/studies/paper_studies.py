"""Studies beyond the paper (measured here, rendered by :mod:`dispersion.report.studies`).

Three studies, each computed through :func:`dispersion.sweep.parallel_map`, returned as one
frozen :class:`Studies` by :func:`measure_studies`:

(a) the redistribution weight :math:`\\gamma_s \\in [0, 1]` of the singular mass (paper
    eqs 2-4, contact on the top surface): S0/A0 series coefficients and branch errors as
    functions of :math:`\\gamma_s`, and the weight that disperses least;
(b) cubic B-splines and more control points through the thickness: the series for CMM,
    lumped and singular mass and the order of accuracy, i.e. the lowest power of
    :math:`\\kappa` at which the discrete :math:`\\Omega^2` series differs from the exact one;
(c) where the methods fail: the radius of convergence of the truncated series (the smallest
    :math:`\\kappa` at which it departs from the numeric branch by more than a tolerance) and
    the largest stable step of explicit central differences,

    .. math::

        \\Delta t_{crit} = \\frac{2}{\\max_{\\theta \\in [0, \\pi]} \\Omega(\\theta)}
        \\quad [h / c_T],

    over the Brillouin zone of the Bloch patch, after condensing the massless DOFs of
    singular masses (they carry no inertia, so they are static, not infinitely fast);
    and Newmark with and without the contact modification (paper eqs 6-10) on the bar impact
    of :mod:`dispersion.contact.bar`, whose exact solution conserves energy.

The patch is the paper's: Bloch model with square elements, :math:`r = b/h = 2` (the model
the core's derivation finds reproduces eqs 17-20), :math:`\\nu = 0.3`.

>>> series_frequency({2: 4, 4: 0}, [0.5])
array([1.])

References
----------
A. Tkachuk, M. Matzen, R. Kolman, M. Bischoff, "Singular mass matrices for isogeometric
finite element analysis of dynamic contact", eqs (1)-(4), (14)-(20) and Conclusions (the
open questions on gamma_s and bi-cubic splines). T. Belytschko, W. K. Liu, B. Moran,
*Nonlinear Finite Elements for Continua and Structures*, Wiley 2000, sec. 6.3 (critical
step of central differences, 2 / omega_max). J. L. Rose, *Ultrasonic waves in solid media*,
CUP 2004, ch. 8 (Rayleigh-Lamb branches).
"""
from __future__ import annotations

import functools
from concurrent.futures import Executor
from dataclasses import dataclass

import numpy as np
import sympy

from dispersion.discretization.discrete_branches import fundamental_branches
from dispersion.time_stepping.timestep import critical_time_step
from dispersion.symbolic.patch import as_patch
from dispersion.symbolic.plate import plate_patch
from dispersion.sweep import parallel_map
from dispersion.continuum.exact_branches import exact_fundamental

__all__ = [
    "NU",
    "R_ASPECT",
    "Studies",
    "departure_kappa",
    "measure_studies",
    "order_of_accuracy",
    "series_frequency",
]

NU = sympy.Rational(3, 10)  #: Poisson's ratio of the studies (the paper's Figure 2)
R_ASPECT = 2  #: aspect ratio b/h of the Bloch patch (square elements, b = 2h)
_MODEL = {"model": "bloch", "r": R_ASPECT}
BAR_P = 2  #: degree of the B-spline bar of study (c)
BAR_COURANT = 0.5  #: its time step over the element's transit time h / c


@dataclass(frozen=True)
class Studies:
    """The three studies' data (plain rows, stored as ``studies.json``).

    ``gamma``: per gamma_s the S0/A0 series coefficients and the *signed* relative errors
    :math:`(\\Omega^h - \\Omega)/\\Omega` at ``kappas``; ``orders``: per (p, n, mass) the
    series and the order of accuracy; ``dt_crit``: critical steps; ``radius``: relative
    deviation of each truncated series from its numeric branch on ``kappa_grid`` and the
    departure kappa at ``tol``; ``bar``: Newmark with/without the contact modification.
    """

    quick: bool
    nu: float
    r: int
    kappas: tuple
    gamma: tuple
    orders: tuple
    dt_crit: tuple
    tol: float
    kappa_grid: tuple
    radius: tuple
    bar: tuple
    #: The exact Rayleigh-Lamb coefficients of Omega^2 at ``nu`` (eqs 14-15), the reference
    #: of study (a): ``{"S0": {power: value}, "A0": {...}}``.
    exact: dict = None


def series_frequency(coefficients: dict, kappa, order: int | None = None) -> np.ndarray:
    """:math:`\\Omega` from the truncated series :math:`\\Omega^2 = \\sum_j a_j \\kappa^j`.

    ``coefficients`` maps powers of kappa to numbers; powers above ``order`` are dropped.
    Where the truncated :math:`\\Omega^2` turns negative the result is 0.
    """
    kappa = np.asarray(kappa, dtype=float)
    w2 = sum(float(a) * kappa**j for j, a in coefficients.items() if order is None or j <= order)
    return np.sqrt(np.clip(w2, 0.0, None))


def order_of_accuracy(discrete: dict, exact: dict) -> int | None:
    """Lowest power of kappa at which the two :math:`\\Omega^2` series differ (None: none):
    :func:`dispersion.symbolic.power_balance.first_difference`."""
    from dispersion.symbolic.power_balance import first_difference

    return first_difference(discrete, exact)


def departure_kappa(kappa, reference, approx, tol: float) -> float | None:
    """Smallest ``kappa`` where ``|approx - reference| > tol * reference`` (None: never)."""
    kappa = np.asarray(kappa, dtype=float)
    rel = np.abs(np.asarray(approx) - np.asarray(reference)) / np.asarray(reference)
    bad = np.nonzero(rel > tol)[0]
    return float(kappa[bad[0]]) if bad.size else None


def _discrete(branch, order, nu, **kwargs) -> dict[int, object]:
    from dispersion.symbolic.power_balance import discrete_series

    return discrete_series(branch, order, nu=nu, **kwargs)


def _exact(branch, order, nu) -> dict[int, object]:
    from dispersion.continuum.exact_series import exact_series

    return exact_series(branch, order, nu=nu)


def _gamma_case(gamma, order: int, kappas: tuple[float, ...]) -> dict:
    """Study (a) at one gamma_s: series and signed branch errors of the singular mass."""
    g = sympy.nsimplify(gamma)
    kw = dict(_MODEL, mass="singular", contact="top", gamma_s=g)
    patch = plate_patch(**kw)
    out = {"gamma_s": float(g), "patch": patch.spec.as_dict()}
    for branch in ("S0", "A0"):
        out[branch] = {str(j): float(v) for j, v in _discrete(branch, order, NU, **kw).items()}
    num = fundamental_branches(patch, float(NU), kappas)
    for branch in ("S0", "A0"):
        ref = exact_fundamental(branch[0], kappas, float(NU))
        out[f"{branch}_error"] = [float(e) for e in (num[branch] - ref) / ref]
    return out


def _order_case(case: tuple[int, int, str], order: int) -> dict:
    """Study (b) for one (p, n, mass): series and orders."""
    p, n, mass = case
    spec = as_patch(p=p, n=n, mass=mass, contact="top", **_MODEL)
    out = {"p": p, "n": n, "mass": mass, "order": order, "patch": spec.as_dict()}
    for branch in ("S0", "A0"):
        disc = _discrete(branch, order, NU, patch=spec)
        ex = _exact(branch, order, NU)
        out[branch] = {str(j): float(v) for j, v in disc.items()}
        out[f"{branch}_order"] = order_of_accuracy(disc, ex)
    return out


def _dt_case(case: tuple[int, int, str], n_theta: int) -> dict:
    p, n, mass = case
    patch = plate_patch(p, n, "bloch", R_ASPECT, mass=mass, contact="top")
    return {"p": p, "n": n, "mass": mass, "patch": patch.spec.as_dict(),
            "dt_crit": critical_time_step(patch, float(NU), n_theta=n_theta)}


def _radius_case(case: tuple[str, str, int], kappa: np.ndarray, tol: float) -> dict:
    """Study (c): truncated series against the numeric branch on a kappa grid."""
    mass, branch, order = case
    spec = None
    if mass == "exact":
        coeffs = _exact(branch, order, NU)
        ref = exact_fundamental(branch[0], kappa, float(NU))
    else:
        spec = as_patch(mass=mass, contact="top", **_MODEL)
        coeffs = _discrete(branch, order, NU, patch=spec)
        ref = fundamental_branches(plate_patch(spec), float(NU), kappa)[branch]
    approx = series_frequency(coeffs, kappa)
    return {
        "mass": mass, "branch": branch, "order": order,
        "patch": None if spec is None else spec.as_dict(),
        "kappa_star": departure_kappa(kappa, ref, approx, tol),
        "deviation": (np.abs(approx - ref) / ref).tolist(),
    }


def _bar_case(case: tuple[str, str], n_elements: int) -> dict:
    """Study (c): bar impact with/without the contact modification of Newmark."""
    from dispersion.contact.bar import simulate_bar

    scheme, mass = case
    m = simulate_bar(n_elements=n_elements, p=BAR_P, mass=mass, scheme=scheme,
                     courant=BAR_COURANT).metrics
    keys = ("energy_change_percent", "force_oscillation", "duration_error", "rebound_error")
    return {"scheme": scheme, "mass": mass, "n_elements": n_elements, "p": BAR_P,
            "courant": BAR_COURANT, **{k: float(m[k]) for k in keys}}


def measure_studies(quick: bool = False, executor: Executor | None = None) -> Studies:
    """Run the three studies (``quick``: fewer weights, orders and grid points)."""
    gammas = [0, sympy.Rational(1, 2), 1] if quick else [sympy.Rational(i, 10) for i in range(11)]
    kappas = (0.25, 0.5)
    order_a = 6
    order_b = 6 if quick else 8
    cases_b = [(2, 3, m) for m in ("consistent", "lumped", "singular")]
    cases_b += [(3, n, m) for n in ((4,) if quick else (4, 5))
                for m in ("consistent", "lumped", "singular")]
    n_theta = 65 if quick else 513
    masses_c = ("consistent", "lumped", "singular", "singular-lumped")
    cases_dt = [(p, n, m) for p, n in ((2, 3), (3, 4)) for m in masses_c]
    tol = 1e-3
    kappa_grid = np.geomspace(0.01, np.pi / R_ASPECT, 60 if quick else 240)
    cases_r = [(m, b, k) for m in ("exact", "consistent", "singular") for b in ("S0", "A0")
               for k in ((4, 6) if quick else (4, 6, 8))]
    cases_bar = [(s, m) for s in ("kane", "standard") for m in ("consistent", "lumped", "singular")]

    def run(func, items, desc):
        return tuple(parallel_map(func, items, executor=executor, progress=None, desc=desc))

    return Studies(
        quick=quick, nu=float(NU), r=R_ASPECT, kappas=kappas,
        gamma=run(functools.partial(_gamma_case, order=order_a, kappas=kappas), gammas,
                  "studies: gamma_s"),
        orders=run(functools.partial(_order_case, order=order_b), cases_b, "studies: p, n"),
        dt_crit=run(functools.partial(_dt_case, n_theta=n_theta), cases_dt, "studies: dt_crit"),
        tol=tol, kappa_grid=tuple(kappa_grid.tolist()),
        radius=run(functools.partial(_radius_case, kappa=kappa_grid, tol=tol), cases_r,
                   "studies: radius"),
        bar=run(functools.partial(_bar_case, n_elements=20 if quick else 40), cases_bar,
                "studies: Newmark"),
        exact={b: {str(k): float(v) for k, v in _exact(b, order_a, NU).items()}
               for b in ("S0", "A0")},
    )
