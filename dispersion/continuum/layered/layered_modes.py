"""Every propagating mode of a layered plate at given frequencies: found by SAFE, polished on
the exact relation, counted and certified.

At each :math:`\\Omega` and for each :class:`~dispersion.continuum.layered.dynamic_stiffness.ModeClass`:

1. **Candidates.** The B-spline SAFE pencil (:mod:`dispersion.continuum.layered.safe`) gives every
   wavenumber at once; those near the positive real axis are candidates.
2. **Counted walk.** The exact count :math:`N(\\kappa, \\Omega)` (the class's modes below
   :math:`\\Omega` at :math:`\\kappa`, :func:`~dispersion.continuum.layered.dynamic_stiffness.count_and_det`)
   is taken at :math:`\\kappa \\to 0`, on both sides of each candidate, between candidates and
   at a :math:`\\kappa_{hi}` where it is 0. Between two test points whose counts differ by one
   lies a root (the determinant changes sign); where they differ by more the interval is
   halved, counted again and so on, so a root SAFE missed is found by the count. Each root
   is closed by the Illinois method on :math:`\\det K` and named by the counts on its sides:
   the branch that leaves (count falls, forward wave) or joins (count rises, backward wave)
   the branches below :math:`\\Omega` -- S_j, A_j, SH_n as for one isotropic layer.
3. **Certified.** Each root's :math:`\\det K` is evaluated in ball arithmetic
   (:func:`~dispersion.continuum.layered.dynamic_stiffness.det_ball`) at :math:`\\kappa(1 \\pm \\delta)`,
   :math:`\\delta` = :data:`ROOT_RTOL` / 4: opposite certain signs prove a root within
   :data:`ROOT_RTOL` relative (else the bracket is bisected with certain signs, or the root
   is listed in ``failures``). The group velocity
   :math:`c_g = d\\Omega/d\\kappa = -\\bar v^T K_\\kappa v / \\bar v^T K_\\Omega v` (v the null
   vector of K) must have the sign the counts say, else the root is a failure.

Test points with equal counts are taken to enclose no root: a pair of roots between two of
them (a branch touching :math:`\\Omega` at a zero-group-velocity point) is seen only if a test
point lies between the pair -- the real part of every SAFE eigenvalue with
:math:`|\\mathrm{Im}\\,\\kappa| < 0.05 |\\kappa|` is one, so a pair SAFE resolves, even as a
complex pair, is found.

>>> from dispersion.continuum.layered.layered_plate import layered_plate
>>> from dispersion.materials.materials import material
>>> r = layered_modes(layered_plate([(material("steel"), 1.0)]), [1.0])
>>> [(lab, round(float(k), 10)) for lab, k in zip(r.label, r.kappa)]
[('S0', 0.6023346704), ('A0', 1.3582234981), ('SH0', 1.0)]
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dispersion.continuum.layered.layered_model import (  # noqa: F401 (names of this module)
    KAPPA_LIMIT, MAX_HALVINGS, OMEGA_RANGE, ROOT_RTOL, LayeredModel, _group, branches_at_kappa)
from dispersion.errors import InputError

__all__ = ["LayeredRoots", "layered_modes", "checked_omega", "chosen_classes", "ROOT_RTOL", "OMEGA_RANGE", "KAPPA_LIMIT"]


@dataclass(frozen=True)
class LayeredRoots:
    """Propagating modes at each requested :math:`\\Omega` (units of
    :class:`~dispersion.continuum.layered.layered_plate.ScaledStack`).

    One entry per root: ``index`` (into ``omega``), ``label``, ``family`` (S, A, SH, L, M),
    ``kappa`` and ``group`` (:math:`c_g / c_{ref}`). ``cutoffs`` maps each label with a
    cut-off at or below ``max(omega)`` to its Omega at kappa = 0; ``failures`` holds
    ``(Omega, class, reason)`` wherever a root or a count was not certified; ``classes`` the
    names of the classes solved.
    """

    plate: object
    omega: np.ndarray
    index: np.ndarray
    label: tuple
    family: tuple
    kappa: np.ndarray
    group: np.ndarray
    cutoffs: dict
    failures: tuple
    classes: tuple
    at_cutoff: tuple = ()

    @property
    def phase(self) -> np.ndarray:
        return self.omega[self.index] / self.kappa


def _class_roots(model, name: str, omega: float):
    """Roots, labels, group velocities and failures of one class of a counted ``model`` (a
    :class:`~dispersion.continuum.plate_model.PlateModel` with a count and candidates) at one
    Omega."""
    failures = []
    cand, exact_real = model.candidates(name, omega)
    k_hi = 1.2 * max(float(cand.max(initial=0.0)), omega) + 0.5
    for _ in range(20):
        if model.count(name, [k_hi], omega, kappa_max=k_hi)[0] == 0:
            break
        k_hi *= 1.5
        if k_hi > model.kappa_limit:
            failures.append((omega, name, f"no kappa_hi <= {model.kappa_limit:g} with every "
                             "branch above Omega"))
            return [], [], [], failures
    # test points: near zero, around and between candidates, the near-real parts, kappa_hi
    k_lo = 1e-9 * max(omega, 1.0)
    pts = [k_lo, k_hi]
    for c in exact_real:
        pts += [c * (1 - 1e-7), c * (1 + 1e-7)]
    pts += list(cand)
    pts = np.unique(np.clip(np.array(pts), k_lo, k_hi))
    mids = 0.5 * (pts[1:] + pts[:-1])
    pts = np.unique(np.concatenate([pts, mids]))
    N = model.count(name, pts, omega, kappa_max=k_hi)
    simple = []   # (a, b, count at a, count at b): one root each
    todo = [(pts[i], pts[i + 1], int(N[i]), int(N[i + 1]), 0)
            for i in range(pts.size - 1) if N[i] != N[i + 1]]
    while todo:
        a, b, na, nb, depth = todo.pop()
        if abs(na - nb) == 1:
            simple.append((a, b, na, nb))
            continue
        if depth >= MAX_HALVINGS:
            failures.append((omega, name, f"{abs(na - nb)} roots closer than round-off "
                             f"near kappa={a:.6g}"))
            continue
        m = 0.5 * (a + b)
        nm = int(model.count(name, [m], omega, kappa_max=k_hi)[0])
        for lo, hi, n1, n2 in ((a, m, na, nm), (m, b, nm, nb)):
            if n1 != n2:
                todo.append((lo, hi, n1, n2, depth + 1))
    roots, labels, groups = [], [], []
    if not simple:
        return roots, labels, groups, failures
    simple.sort()
    found, still = model.close(name, omega, np.array([x[0] for x in simple]),
                               np.array([x[1] for x in simple]), kappa_max=k_hi)
    cells = np.array([[x[0], x[1]] for x in simple])
    certified, _, bad = model.certify(name, found, np.full(found.size, omega), cells,
                                      kappa_max=k_hi)
    slopes = model.slope(name, certified, np.full(found.size, omega), None, kappa_max=k_hi)
    for i, ((a, b, na, nb), k, open_) in enumerate(zip(simple, found, still)):
        k, kc, g = float(k), float(certified[i]), float(slopes[i])
        if open_:
            failures.append((omega, name, f"root refinement did not converge near "
                             f"kappa={k:.6g}"))
        if i in bad:
            failures.append((omega, name, f"root near kappa={k:.6g} not certified "
                             f"to {ROOT_RTOL:.0e} relative"))
        if not (np.isfinite(g) and np.sign(g) == np.sign(na - nb)):
            failures.append((omega, name, f"group velocity at kappa={kc:.6g} "
                             f"({g:.3g}) disagrees with the count ({na} -> {nb})"))
        roots.append(kc)
        labels.append(model.label(name, min(na, nb)))
        groups.append(g)
    return roots, labels, groups, failures


def chosen_classes(model, families) -> list:
    """The mode classes of ``model`` (a :class:`LayeredModel`) whose family is in
    ``families`` (all for None); a family the plate does not have is refused by name."""
    classes = [model.mode_class(n) for n in model.classes()]
    if families is not None:
        known = sorted({c.family for c in classes})
        unknown = [f for f in families if f not in known]
        if unknown or not families:
            raise InputError(f"families must be a non-empty subset of {', '.join(known)} for "
                             f"this plate; got {', '.join(map(str, families)) or 'none'}")
        classes = [c for c in classes if c.family in families]
    return classes


def checked_omega(omega) -> np.ndarray:
    """``omega`` as a non-empty 1-d float array inside :data:`OMEGA_RANGE`, else an
    :class:`~dispersion.errors.InputError` naming the first value outside."""
    try:
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
    except (TypeError, ValueError):
        raise InputError("Omega must be a number or a list of numbers") from None
    if omega.ndim != 1 or omega.size == 0 or not np.all(np.isfinite(omega)):
        raise InputError("Omega must be a non-empty 1-d list of finite numbers")
    lo, hi = OMEGA_RANGE
    bad = (omega < lo) | (omega > hi)
    if np.any(bad):
        raise InputError(f"Omega = omega h / c_ref must lie in [{lo:g}, {hi:g}], got "
                         f"{omega[bad][0]!r}")
    return omega


def layered_modes(plate, omega, *, families=None) -> LayeredRoots:
    """Every propagating mode of ``plate`` (a
    :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate`, undamped) at each
    dimensionless frequency in ``omega`` (:math:`\\Omega = \\omega h / c_{ref}`, see
    :meth:`~dispersion.continuum.layered.layered_plate.LayeredPlate.scaled`), each root certified or
    listed in ``failures``. ``families``: a subset of the plate's families (S, A, SH, L, M) to
    solve (default: all).
    """
    if not plate.lossless:
        raise InputError("layered_modes: the plate is damped; its wavenumbers are complex "
                         "(use the damped solver)")
    omega = checked_omega(omega)
    model = LayeredModel(plate)
    classes = chosen_classes(model, families)
    rows, failures = [], []
    for i, w in enumerate(omega):
        for cls in classes:
            roots, labels, groups, fails = _class_roots(model, cls.name, float(w))
            failures += fails
            rows += [(i, lab, cls.family, k, g) for k, lab, g in zip(roots, labels, groups)]
    fam_order = {"S": 0, "A": 1, "L": 0, "M": 0, "SH": 2}

    def number(label):
        digits = label.lstrip("SAHLM")
        return int(digits) if digits.isdigit() else 10**9

    rows.sort(key=lambda r: (r[0], number(r[1]), fam_order.get(r[2], 3), r[3]))
    cutoffs = {}
    top = float(omega.max())
    for family in dict.fromkeys(c.family for c in classes):
        # every cut-off up to the top frequency, and the family's next one
        found = sorted((w, lab) for c in classes if c.family == family
                       for lab, w in model.cutoff_table(c.name, top))
        above = [lab for w, lab in found if w > top][:1]
        cutoffs.update({lab: w for w, lab in found if w <= top or lab in above})
    return LayeredRoots(plate, omega, np.array([r[0] for r in rows], dtype=int),
                        tuple(r[1] for r in rows), tuple(r[2] for r in rows),
                        np.array([r[3] for r in rows]), np.array([r[4] for r in rows]),
                        cutoffs, tuple(dict.fromkeys(failures)),
                        tuple(c.name for c in classes))
