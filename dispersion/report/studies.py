"""Studies beyond the paper: redistribution weight, cubic splines, where methods fail.

Three report subsections, each computed through :func:`dispersion.sweep.parallel_map`:

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

>>> K = critical_time_step(p=2, n=3, mass="consistent", r=2, nu=0.3, n_theta=65)
>>> 0 < K < 1
True

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
import json
from concurrent.futures import Executor
from pathlib import Path

import numpy as np
import sympy

from ..branches import pencil_frequencies
from ..errors import ConvergenceError, InputError, check_nu, check_positive, check_positive_int
from ..io import save_figure, write_text
from ..plate import mirror_bases, numeric_pencil, plate_patch
from ..tracer import trace_branches
from ..sweep import parallel_map

__all__ = [
    "NU",
    "R_ASPECT",
    "condensed_frequencies",
    "branch_frequencies",
    "critical_time_step",
    "exact_branch",
    "series_frequency",
    "order_of_accuracy",
    "departure_kappa",
    "report",
]

NU = sympy.Rational(3, 10)  #: Poisson's ratio of the studies (the paper's Figure 2)
R_ASPECT = 2  #: aspect ratio b/h of the Bloch patch (square elements, b = 2h)
_MODEL = {"model": "bloch", "r": R_ASPECT}


# --------------------------------------------------------------------------- numerics
def condensed_frequencies(patch, nu: float, kappa) -> np.ndarray:
    """All finite :math:`\\Omega` of the patch at each ``kappa``, ascending, shape (len, m).

    Massless DOFs (singular masses) are condensed statically,
    :math:`K_c = K_{mm} - K_{ms} K_{ss}^{-1} K_{sm}`, so the pencil keeps exactly the finite
    branches (:func:`dispersion.branches.pencil_frequencies`).

    >>> W = condensed_frequencies(plate_patch(mass="singular"), 0.3, [0.1, 0.2])
    >>> W.shape
    (2, 4)
    """
    K, M = numeric_pencil(patch, nu, kappa)
    return pencil_frequencies(K, M, patch.massless)


def branch_frequencies(patch, nu: float, kappa) -> dict[str, np.ndarray]:
    """Discrete S0 and A0 branches at ``kappa`` (small enough that both are the lowest).

    Where the mass keeps the mirror symmetry the S and A blocks are solved apart and the
    lowest root of each is taken; where it does not (singular mass on one surface) the two
    lowest finite roots are A0 (:math:`\\Omega^2 \\sim \\kappa^4`) and S0
    (:math:`\\Omega^2 \\sim \\kappa^2`), valid below the first veering with A1.
    """
    K, M = numeric_pencil(patch, nu, kappa)
    bases = mirror_bases(patch)
    if bases is None:
        W = pencil_frequencies(K, M, patch.massless)
        return {"A0": W[:, 0], "S0": W[:, 1]}
    out = {}
    for key, E in bases.items():
        idx = np.arange(E.shape[1])
        Mb = E.T @ M @ E
        zero = tuple(i for i in idx if np.allclose(Mb[:, i, :], 0.0))
        out[f"{key}0"] = pencil_frequencies(E.T @ K @ E, Mb, zero)[:, 0]
    return out


def critical_time_step(
    p: int = 2, n: int = 3, mass: str = "consistent", r: float = R_ASPECT, nu: float = 0.3,
    n_theta: int = 257, contact: str = "top", gamma_s=0,
) -> float:
    """Largest stable step of explicit central differences, :math:`2/\\max\\Omega`, in h/c_T.

    The maximum runs over the Bloch phase :math:`\\theta = \\kappa r \\in [0, \\pi]` on
    ``n_theta`` equally spaced points (both zone ends included).
    """
    check_positive_int("n_theta", n_theta, minimum=2)
    check_positive("aspect ratio r", r)
    patch = plate_patch(p, n, "bloch", r, mass=mass, contact=contact, gamma_s=gamma_s)
    theta = np.linspace(0.0, np.pi, n_theta)
    return float(2.0 / condensed_frequencies(patch, nu, theta / float(r)).max())


def exact_branch(kind: str, kappa, nu: float) -> np.ndarray:
    """Exact S0 (``kind="S"``) or A0 (``"A"``) :math:`\\Omega` of Rayleigh-Lamb at ``kappa``.

    The lowest root of the symmetry class ``kind``, from the branch tracer
    :func:`dispersion.rayleigh_lamb.trace_branches` (which reports, never hides, a root it
    could not certify: that becomes a :class:`~dispersion.errors.ConvergenceError` here).

    >>> round(float(exact_branch("S", [0.05], 0.3)[0]) ** 2 / 0.05**2, 3)  # eq 14: ~2/(1-nu)
    2.857
    """
    if kind not in ("S", "A"):
        raise InputError(f"kind must be 'S' or 'A', got {kind!r}")
    nu = float(check_nu(nu))
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    # S0 and A0 lie below the line Omega = sqrt(2/(1-nu)) kappa < 2 kappa for nu < 1/2
    traced = trace_branches(nu, kappa, omega_max=2.0 * float(kappa.max()) + 0.1, kinds=(kind,))
    if traced.failures:
        raise ConvergenceError(f"exact {kind}0 branch not certified: {traced.failures[0]}")
    omega = traced.omega[f"{kind}0"]
    if not np.all(np.isfinite(omega)):
        raise ConvergenceError(f"exact {kind}0 branch missing at some kappa in {kappa}")
    return omega


# --------------------------------------------------------------------------- series
def series_frequency(coefficients: dict, kappa, order: int | None = None) -> np.ndarray:
    """:math:`\\Omega` from the truncated series :math:`\\Omega^2 = \\sum_j a_j \\kappa^j`.

    ``coefficients`` maps powers of kappa to numbers; powers above ``order`` are dropped.
    Where the truncated :math:`\\Omega^2` turns negative the result is NaN-free: 0.

    >>> series_frequency({2: 4, 4: 0}, [0.5])
    array([1.])
    """
    kappa = np.asarray(kappa, dtype=float)
    w2 = sum(float(a) * kappa**j for j, a in coefficients.items() if order is None or j <= order)
    return np.sqrt(np.clip(w2, 0.0, None))


def order_of_accuracy(discrete: dict, exact: dict) -> int | None:
    """Lowest power of kappa at which the two :math:`\\Omega^2` series differ (None: none)."""
    for j in sorted(set(discrete) | set(exact)):
        if sympy.simplify(sympy.sympify(discrete.get(j, 0)) - sympy.sympify(exact.get(j, 0))) != 0:
            return j
    return None


def departure_kappa(kappa, reference, approx, tol: float) -> float | None:
    """Smallest ``kappa`` where ``|approx - reference| > tol * reference`` (None: never)."""
    kappa = np.asarray(kappa, dtype=float)
    rel = np.abs(np.asarray(approx) - np.asarray(reference)) / np.asarray(reference)
    bad = np.nonzero(rel > tol)[0]
    return float(kappa[bad[0]]) if bad.size else None


# --------------------------------------------------------------------------- workers
def _discrete(branch, order, nu, **kwargs) -> dict[int, object]:
    from ..power_balance import discrete_series

    return discrete_series(branch, order, nu=nu, **kwargs)


def _exact(branch, order, nu) -> dict[int, object]:
    from ..power_balance import exact_series

    return exact_series(branch, order, nu=nu)


def _gamma_case(gamma, order: int, kappas: tuple[float, ...]) -> dict:
    """Worker of study (a): series and branch errors of the singular mass at one gamma_s."""
    g = sympy.nsimplify(gamma)
    kw = dict(_MODEL, mass="singular", contact="top", gamma_s=g)
    out = {"gamma_s": float(g)}
    for branch, kind in (("S0", "S"), ("A0", "A")):
        out[branch] = {str(j): float(v) for j, v in _discrete(branch, order, NU, **kw).items()}
    patch = plate_patch(**kw)
    num = branch_frequencies(patch, float(NU), kappas)
    for branch, kind in (("S0", "S"), ("A0", "A")):
        ref = exact_branch(kind, kappas, float(NU))
        out[f"{branch}_error"] = [float(e) for e in (num[branch] - ref) / ref]
    return out


def _order_case(case: tuple[int, int, str], order: int) -> dict:
    """Worker of study (b): series and orders for one (p, n, mass)."""
    p, n, mass = case
    out = {"p": p, "n": n, "mass": mass, "order": order}
    for branch in ("S0", "A0"):
        disc = _discrete(branch, order, NU, p=p, n=n, mass=mass, contact="top", **_MODEL)
        ex = _exact(branch, order, NU)
        out[branch] = {str(j): float(v) for j, v in disc.items()}
        out[f"{branch}_order"] = order_of_accuracy(disc, ex)
    return out


def _dt_case(case: tuple[int, int, str], n_theta: int) -> dict:
    p, n, mass = case
    dt = critical_time_step(p, n, mass, R_ASPECT, float(NU), n_theta=n_theta)
    return {"p": p, "n": n, "mass": mass, "dt_crit": dt}


def _radius_case(case: tuple[str, str, int], kappa: np.ndarray, tol: float) -> dict:
    """Worker of study (c): truncated series against the numeric branch on a kappa grid."""
    mass, branch, order = case
    if mass == "exact":
        coeffs = _exact(branch, order, NU)
        ref = exact_branch(branch[0], kappa, float(NU))
    else:
        coeffs = _discrete(branch, order, NU, mass=mass, contact="top", **_MODEL)
        ref = branch_frequencies(plate_patch(mass=mass, contact="top", **_MODEL), float(NU),
                                 kappa)[branch]
    approx = series_frequency(coeffs, kappa)
    return {
        "mass": mass, "branch": branch, "order": order,
        "kappa_star": departure_kappa(kappa, ref, approx, tol),
        "deviation": (np.abs(approx - ref) / ref).tolist(),
    }


def _bar_case(case: tuple[str, str], n_elements: int) -> dict:
    """Worker of study (c): bar impact with/without the contact modification of Newmark."""
    from ..contact.bar import simulate_bar

    scheme, mass = case
    m = simulate_bar(n_elements=n_elements, mass=mass, scheme=scheme).metrics
    keys = ("energy_change_percent", "force_oscillation", "duration_error", "rebound_error")
    return {"scheme": scheme, "mass": mass, "n_elements": n_elements,
            **{k: float(m[k]) for k in keys}}


# --------------------------------------------------------------------------- report
def report(out: Path, quick: bool = False, executor: Executor | None = None) -> str:
    """Run the three studies, write figures and JSON into ``out``, return the Markdown."""
    from ..plotting import studies as plots

    out = Path(out)
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

    def run(func, items, desc):
        return parallel_map(func, items, executor=executor, progress=True, desc=desc)

    res_a = run(functools.partial(_gamma_case, order=order_a, kappas=kappas), gammas,
                "studies: gamma_s")
    res_b = run(functools.partial(_order_case, order=order_b), cases_b, "studies: p, n")
    res_dt = run(functools.partial(_dt_case, n_theta=n_theta), cases_dt, "studies: dt_crit")
    res_r = run(functools.partial(_radius_case, kappa=kappa_grid, tol=tol), cases_r,
                "studies: radius")
    cases_bar = [(s, m) for s in ("kane", "standard") for m in ("consistent", "lumped", "singular")]
    res_bar = run(functools.partial(_bar_case, n_elements=20 if quick else 40), cases_bar,
                  "studies: Newmark")

    data = {"nu": float(NU), "r": R_ASPECT, "kappas": list(kappas), "gamma": res_a,
            "orders": res_b, "dt_crit": res_dt, "tol": tol, "kappa_grid": kappa_grid.tolist(),
            "radius": res_r, "bar": res_bar}
    write_text(out / "studies.json", json.dumps(data, indent=1))
    save_figure(plots.figure_gamma(res_a, kappas), out / "studies_gamma.png", dpi=120)
    save_figure(plots.figure_radius(data), out / "studies_radius.png", dpi=120)
    return _markdown(data, quick)


def _fmt(x, digits: int = 4) -> str:
    return "-" if x is None else f"{x:.{digits}g}"


def _markdown(d: dict, quick: bool) -> str:
    nu, r = d["nu"], d["r"]
    lines = ["## Studies beyond the paper", ""]
    lines += [
        f"Bloch patch with square elements (r = b/h = {r}), nu = {nu}, contact on the top "
        "surface; all data in [studies.json](studies.json).", "",
        "### (a) The redistribution weight gamma_s", "",
        "The paper uses one weight and leaves others open. Singular mass, quadratic splines, "
        "n = 3: the coefficients of Omega^2 and the relative error of Omega against the exact "
        "Rayleigh-Lamb branch, at each gamma_s.", "",
        "![gamma_s study](studies_gamma.png)", "",
    ]
    ks = d["kappas"]
    head = "| gamma_s | S0 k^4 | S0 k^6 | A0 k^6 | " + " | ".join(
        f"S0 err k={k} | A0 err k={k}" for k in ks) + " |"
    lines += [head, "|" + "---|" * (4 + 2 * len(ks))]
    for row in d["gamma"]:
        errs = " | ".join(f"{_fmt(row['S0_error'][i], 3)} | {_fmt(row['A0_error'][i], 3)}"
                          for i in range(len(ks)))
        lines.append(f"| {row['gamma_s']:.2f} | {_fmt(row['S0'].get('4'))} | "
                     f"{_fmt(row['S0'].get('6'))} | {_fmt(row['A0'].get('6'))} | {errs} |")
    k_last = len(ks) - 1
    for branch in ("S0", "A0"):
        best = min(d["gamma"], key=lambda row: abs(row[f"{branch}_error"][k_last]))
        lines.append("")
        lines.append(f"Least {branch} dispersion at kappa = {ks[k_last]} among the weights run: "
                     f"gamma_s = {best['gamma_s']:.2f} (relative error "
                     f"{_fmt(best[f'{branch}_error'][k_last], 3)}).")
    lines += ["", "### (b) Cubic splines and more control points through the thickness", "",
              "Order = lowest power of kappa at which the discrete Omega^2 series differs from "
              "the exact Rayleigh-Lamb series (eqs 14-15); '> N' means they agree up to the "
              "highest power computed, N.", "",
              "| p | n | mass | S0 order | A0 order | S0 k^4 | A0 k^6 |",
              "|---|---|---|---|---|---|---|"]
    for row in d["orders"]:
        s0, a0 = (f"> {row['order']}" if row[f"{b}_order"] is None else row[f"{b}_order"]
                  for b in ("S0", "A0"))
        lines.append(f"| {row['p']} | {row['n']} | {row['mass']} | {s0} | {a0} | "
                     f"{_fmt(row['S0'].get('4'))} | "
                     f"{_fmt(row['A0'].get('6'))} |")
    lines += ["", "### (c) Where the methods fail", "",
              "Largest stable step of explicit central differences, dt_crit = 2 / max Omega "
              "over the Brillouin zone, in units h/c_T (massless DOFs condensed):", "",
              "| p | n | mass | dt_crit |", "|---|---|---|---|"]
    for row in d["dt_crit"]:
        lines.append(f"| {row['p']} | {row['n']} | {row['mass']} | {row['dt_crit']:.4f} |")
    lines += ["", f"Radius of validity of the truncated series: the smallest kappa at which "
              f"Omega from the series departs from the numeric branch (exact Rayleigh-Lamb "
              f"root, or the discrete patch's own eigenvalue) by more than "
              f"{d['tol']:g} relative ('-': not within kappa <= pi/r).", "",
              "![radius of the series](studies_radius.png)", "",
              "| branch | series of | truncated after | kappa* |", "|---|---|---|---|"]
    for row in d["radius"]:
        lines.append(f"| {row['branch']} | {row['mass']} | k^{row['order']} | "
                     f"{_fmt(row['kappa_star'], 3)} |")
    lines += ["", "Newmark (beta = 1/4, gamma = 1/2) with and without the contact "
              "modification of Kane et al. (paper eqs 6-10; 'standard': plain Newmark with "
              "the contact force treated like any other force): quadratic B-spline bar hitting a rigid wall "
              "(dispersion.contact.bar, Courant number 0.5), whose exact solution conserves "
              "energy and keeps a constant contact stress. Oscillation = standard deviation of "
              "the contact force over the middle of the contact, over rho c v0.", "",
              "| scheme | mass | elements | energy change % | force oscillation | "
              "contact duration error |", "|---|---|---|---|---|---|"]
    for row in d["bar"]:
        lines.append(f"| {row['scheme']} | {row['mass']} | {row['n_elements']} | "
                     f"{row['energy_change_percent']:.3g} | {row['force_oscillation']:.3g} | "
                     f"{row['duration_error']:.3g} |")
    lines.append("")
    if quick:
        lines.insert(2, "*Quick subset: fewer weights, orders and grid points.*\n")
    return "\n".join(lines)
