"""The branches study: discrete against exact branches, measured once and stored as data.

:func:`measure_branches` returns a frozen :class:`BranchesStudy` that
:mod:`dispersion.report.branches` renders from JSON (Figure 2 with labelled modes and signed,
shape-paired errors; velocities with ZGV points; discretization error per wavelength, plate
and bar; mode shapes; the speed/accuracy of the tracer and the discrete solver).

- Figure 2: Bloch patch r = 1/2 (the caption's h/b = 2), p = 2, n = 3, consistent and singular
  mass (contact on top), nu = 0.3; errors of each exact branch against the discrete mode of
  the same shape (:func:`dispersion.discretization.discrete_mode_shapes.pair_by_shape`), signed.
- Fitted orders: every mass at r = 2 and r = 1/2, least squares over 5 kappas inside the
  window where the series of the error says its leading term dominates
  (:mod:`dispersion.studies.asymptotic_fit`), with the window, the points, the residual and
  the series' prediction; no order where the window is empty or the residual large.
- Error per wavelength: Bloch patch with square elements (r = 2, as in the studies), signed
  relative phase-velocity error :math:`c^h_p / c_p - 1 = \\Omega^h/\\Omega - 1` of S0 and A0
  against elements per wavelength :math:`2\\pi / (\\kappa r)`; and the bar of
  :mod:`dispersion.discretization.bar_dispersion`.

>>> BRANCH_NU
0.3
"""
from __future__ import annotations

import math
import time
from concurrent.futures import Executor
from dataclasses import dataclass

import numpy as np

from dispersion import defaults
from dispersion.discretization.bar_dispersion import bar_dispersion
from dispersion.discretization.discrete_branches import discrete_branches, fundamental_branches
from dispersion.continuum.mode_shapes import exact_mode_shape
from dispersion.discretization.discrete_mode_shapes import discrete_mode_shape, discrete_modes, mac
from dispersion.discretization.discrete_mode_shapes import pair_by_shape
from dispersion.symbolic.patch import Patch
from dispersion.symbolic.plate import plate_patch
from dispersion.continuum.exact_branches import (
    ExactBranches,
    exact_fundamental,
    mpmath_error,
    trace_branches,
    tracer_accuracy,
)
from dispersion.answers.units import ALUMINIUM
from dispersion.continuum.velocities import exact_velocities, zgv_points

__all__ = [
    "BRANCH_NU", "BranchesStudy", "discrete_speed", "figure2_data", "measure_branches",
]

BRANCH_NU = defaults.NU_FLOAT
_R_FIG2 = float(defaults.FIGURE2_R)
_R_SQUARE = float(defaults.R)


@dataclass(frozen=True)
class BranchesStudy:
    """Everything the branches section shows, as plain arrays and rows (see module docstring)."""

    quick: bool
    nu: float
    r_figure2: float
    kappa: tuple
    omega_max: float
    exact: dict            # label -> {"omega", "phase", "group"}
    exact_failures: tuple
    discrete: dict         # mass -> {"omega", "symmetry", "group", "paired", "mac", "zone_edge"}
    mpmath_error: float
    mpmath_points: int
    zgv: tuple
    orders: tuple
    per_wavelength: dict
    bar: dict
    shapes: dict
    tracer: dict
    discrete_speed: tuple
    fd_per_omega_aluminium: float


def _arr(x) -> list:
    return np.asarray(x, dtype=float).tolist()


#: The patches whose error orders are fitted: every mass, at the studies' square elements
#: (r = 2) and at Figure 2's aspect ratio (r = 1/2); p = 2, n = 3, contact on top,
#: gamma_s = 0. The result carries each as :meth:`Patch.as_dict`; every heading is rendered
#: from that.
FIT_PATCHES = tuple(Patch(model="bloch", r=r, mass=m, contact="top", gamma_s=0)
                    for r in ("2", "1/2") for m in ("consistent", "lumped", "singular"))


def _orders(nu: float, patches=FIT_PATCHES) -> list[dict]:
    """Fitted orders of |Omega_h / Omega - 1| inside the window the error series allows
    (:mod:`dispersion.studies.asymptotic_fit`), per patch and branch, errors shape-paired."""
    from fractions import Fraction

    from dispersion.studies.asymptotic_fit import fit_in_window, relative_error_series

    from dispersion.reader import rational

    q = rational("nu", nu)  # a float by its shortest decimal; text by the whitelist
    nu_q = Fraction(int(q.p), int(q.q))
    rows = []
    for spec in patches:
        fields = spec.as_dict()
        patch = plate_patch(spec)

        def measure(kappa, patch=patch):
            exact = trace_branches(nu, kappa, 4.0)
            return pair_by_shape(patch, nu, exact).relative_error(exact)

        cache = {}
        for branch in ("S0", "A0"):
            series = relative_error_series(branch, nu_q, spec)

            def one(kappa, branch=branch):
                key = tuple(np.round(kappa, 15))
                if key not in cache:
                    cache[key] = measure(np.asarray(kappa))
                return cache[key][branch]

            row = fit_in_window(series, one, kappa_max=math.pi / float(spec.r))
            rows.append({"patch": fields, "mass": spec.mass, "branch": branch,
                         "points": len(row["kappa"]),
                         "series_terms": {str(k): float(v) for k, v in series.items()}, **row})
    return rows


def _per_wavelength(nu: float, quick: bool) -> dict:
    epw = np.geomspace(2.0, 1000.0, 30 if quick else 90)
    kappa = 2 * math.pi / (epw * _R_SQUARE)
    exact = {b: exact_fundamental(b[0], kappa, nu) for b in ("S0", "A0")}
    curves = []
    for p, n in ((2, 3), (3, 4)):
        for mass in ("consistent", "lumped", "singular", "dual-lumped"):
            patch = plate_patch(p=p, n=n, model="bloch", r=_R_SQUARE, mass=mass)
            disc = fundamental_branches(patch, nu, kappa)
            for b in ("S0", "A0"):
                curves.append({"p": p, "n": n, "mass": mass, "branch": b,
                               "patch": patch.spec.as_dict(),
                               "error": _arr(disc[b] / exact[b] - 1)})
    return {"r": _R_SQUARE, "elements_per_wavelength": _arr(epw), "curves": curves}


def _shapes(nu: float, kappa: float = 1.0) -> dict:
    y = np.linspace(-1, 1, 41)
    exact = trace_branches(nu, [kappa], 4.0)
    patch = plate_patch(model="bloch", r=_R_FIG2, mass="consistent")
    W, X = discrete_modes(patch, nu, [kappa])
    out = {"kappa": kappa, "patch": patch.spec.as_dict(), "y": _arr(y), "modes": []}
    for label in ("S0", "A0", "A1", "S1"):
        w = float(exact.omega[label][0])
        ex = exact_mode_shape(label[0], kappa, w, nu, y)
        cand = [discrete_mode_shape(patch, X[0, :, j], y) for j in range(W.shape[1])]
        scores = [mac(np.concatenate(ex), np.concatenate(c)) for c in cand]
        j = int(np.argmax(scores))
        d = cand[j]
        sign = np.sign(np.dot(np.concatenate(ex), np.concatenate(d))) or 1.0
        out["modes"].append({"label": label, "omega": w, "omega_h": float(W[0, j]),
                             "mac": scores[j], "exact": [_arr(ex[0]), _arr(ex[1])],
                             "discrete": [_arr(sign * d[0]), _arr(sign * d[1])]})
    return out


def discrete_speed(nu: float, kappa, configs, repeat: int = 3) -> list[dict]:
    """Cost (batched solve time) and accuracy (max |relative error| of S0/A0, kappa <= 1)."""
    small = np.linspace(0.05, 1.0, 20)
    exact = {b: exact_fundamental(b[0], small, nu) for b in ("S0", "A0")}
    rows = []
    for p, n, mass in configs:
        patch = plate_patch(p=p, n=n, mass=mass)
        best = np.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            discrete_branches(patch, nu, kappa)
            best = min(best, time.perf_counter() - t0)
        disc = fundamental_branches(patch, nu, small)
        err = max(float(np.max(np.abs(disc[b] / exact[b] - 1))) for b in ("S0", "A0"))
        rows.append({"p": p, "n": n, "mass": mass, "time_s": best,
                     "points_per_s": np.size(kappa) / best, "error": err})
    return rows


def figure2_data(nu: float, kappa, omega_max: float, patches: dict, *, exact=None,
                 velocities=None, discrete: dict | None = None):
    """Exact branches with velocities and, per named patch, its branches, group velocities and
    signed errors of each exact branch against its shape partner; plain data for
    :func:`dispersion.plotting.branches.figure2`. Returns ``(data, ExactBranches)``.

    Branches computed already are passed in and not computed again: ``exact`` (an
    :class:`ExactBranches` on ``kappa``), ``velocities`` (its :class:`Velocities`) and
    ``discrete`` (``{name: DiscreteBranches}`` with group velocities, on ``kappa``).
    """
    kappa = np.asarray(kappa, dtype=float)
    if exact is None:
        exact = trace_branches(nu, kappa, omega_max)
    vel = exact_velocities(exact) if velocities is None else velocities
    ex_data = {lab: {"omega": _arr(w), "phase": _arr(vel.phase[lab]), "group": _arr(vel.group[lab])}
               for lab, w in exact.omega.items()}
    discrete_data = {}
    for name, patch in patches.items():
        d = (discrete or {}).get(name)
        if d is None or d.group is None:
            d = discrete_branches(patch, nu, kappa, group=True)
        # exact partners of a Bloch branch exist in the first zone only
        inside = kappa <= (d.zone_edge if d.zone_edge is not None else np.inf)
        sub = ExactBranches(kappa[inside], {lab: w[inside] for lab, w in exact.omega.items()},
                            exact.nu, exact.omega_max)
        pb = pair_by_shape(patch, nu, sub)
        pad = int(np.count_nonzero(~inside))
        discrete_data[name] = {
            "patch": patch.spec.as_dict() if getattr(patch, "spec", None) else None,
            "omega": {lab: _arr(w) for lab, w in d.omega.items()},
            "group": {lab: _arr(g) for lab, g in d.group.items()},
            "symmetry": dict(d.symmetry),
            "zone_edge": d.zone_edge,
            "paired_error": {lab: _arr(np.concatenate([e, np.full(pad, np.nan)]))
                             for lab, e in pb.relative_error(sub).items()},
            "mac": {lab: _arr(np.concatenate([m, np.full(pad, np.nan)]))
                    for lab, m in pb.mac.items()},
            # which discrete mode is the partner (-1: none): the figure breaks its line where
            # the partner changes instead of drawing the jump as a vertical line
            "paired_partner": {lab: [int(v) for v in np.concatenate([c, np.full(pad, -1)])]
                               for lab, c in pb.partner.items()},
        }
    data = {"nu": nu, "kappa": _arr(kappa), "omega_max": omega_max, "exact": ex_data,
            "discrete": discrete_data}
    return data, exact


def measure_branches(quick: bool = False, executor: Executor | None = None) -> BranchesStudy:
    """Run the branches study (``quick``: coarser grids, fewer settings; ``executor`` unused:
    every part is one vectorised solve)."""
    nu = BRANCH_NU
    omega_max = 8.0
    kappa = np.linspace(0, 8, 200 if quick else 800)
    fig2, exact = figure2_data(nu, kappa, omega_max, {
        mass: plate_patch(model="bloch", r=_R_FIG2, mass=mass)
        for mass in ("consistent", "singular")})
    n_check = 8 if quick else 40
    tr_k = np.linspace(0, 10, 200 if quick else 1000)
    settings = [(0.05, 1e-6), (0.05, 1e-15)] if quick else None
    acc = tracer_accuracy(nu, tr_k, settings=settings, repeat=1 if quick else 3,
                          mpmath_points=n_check)
    d_k = np.linspace(0, 5, 1000 if quick else 2000)
    configs = ([(2, 3, "consistent"), (2, 3, "singular"), (3, 4, "consistent")] if quick else
               [(p, n, m) for p in (2, 3) for n in (p + 1, p + 3)
                for m in ("consistent", "lumped", "singular")])
    bd = bar_dispersion((1, 2, 3, 4), ("consistent", "lumped", "dual-lumped"))
    return BranchesStudy(
        quick=quick, nu=nu, r_figure2=_R_FIG2, kappa=tuple(_arr(kappa)), omega_max=omega_max,
        exact=fig2["exact"], exact_failures=tuple(tuple(f) for f in exact.failures),
        discrete=fig2["discrete"],
        mpmath_error=mpmath_error(exact, count=n_check), mpmath_points=n_check,
        zgv=tuple({"label": z.label, "kappa": z.kappa, "omega": z.omega}
                  for z in zgv_points(nu, 8.0, omega_max, count=200 if quick else 400)),
        orders=tuple(_orders(nu)),
        per_wavelength=_per_wavelength(nu, quick),
        bar={"elements_per_wavelength": _arr(bd.elements_per_wavelength),
             "error": {k: _arr(v) for k, v in bd.error.items()}},
        shapes=_shapes(nu),
        tracer={"kappa_count": acc.kappa_count, "omega_max": acc.omega_max,
                "reference": list(acc.reference),
                "reference_mpmath_error": acc.reference_mpmath_error,
                "mpmath_points": acc.mpmath_points, "rows": list(acc.rows)},
        discrete_speed=tuple(discrete_speed(nu, d_k, configs, repeat=1 if quick else 2)),
        fd_per_omega_aluminium=ALUMINIUM.c_T / math.pi * 1e-3,
    )
