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

from dispersion.continuum.layered.dynamic_stiffness import (ModeClass, assemble, count_and_det,
                                                            det_ball, mode_classes, null_vector,
                                                            sublayers)
from dispersion.continuum.layered.safe import elements_per_layer, safe_pencil, wavenumbers
from dispersion.errors import InputError

__all__ = ["LayeredRoots", "layered_modes", "ROOT_RTOL", "OMEGA_RANGE", "KAPPA_LIMIT"]

#: Relative accuracy every root is certified to (or listed in ``failures``).
ROOT_RTOL = 1e-12
#: Dimensionless frequencies accepted (omega h / c_ref). Rule: the isotropic calculator's
#: range (:data:`dispersion.continuum.frequency.FREQUENCY_OMEGA_MIN`, ``_MAX``).
OMEGA_RANGE = (2e-3, 30.0)
#: Largest kappa_hi tried before a class is listed as a failure.
KAPPA_LIMIT = 1000.0
#: Depth of the halving of an interval whose counts differ by more than one.
MAX_HALVINGS = 45


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


def _close(stack, cls, elements, kappa_or_none, omega, a, b):
    """Roots of det K on the brackets ``[a, b]`` (arrays with a sign change each) by the
    Illinois method, all at once: in kappa at one ``omega`` (``kappa_or_none`` None), or in
    Omega at one kappa (``omega`` None, ``a, b`` frequencies). Returns (roots, still open)."""
    from dispersion.continuum.illinois import illinois

    def evaluate(x, idx=None):
        if omega is not None:
            return count_and_det(stack, cls, elements, x, omega)
        return count_and_det(stack, cls, elements, np.full(x.size, kappa_or_none), x)

    _, la, sa = evaluate(a)
    _, lb, sb = evaluate(b)
    ref = np.maximum(la, lb)
    ref = np.where(np.isfinite(ref), ref, 0.0)

    def f(idx, x):
        if omega is not None:
            _, ld, sg = count_and_det(stack, cls, elements, x, omega)
        else:
            _, ld, sg = count_and_det(stack, cls, elements, np.full(x.size, kappa_or_none), x)
        return sg * np.exp(np.clip(ld - ref[idx], -600, 600))

    fa = sa * np.exp(np.clip(la - ref, -600, 600))
    fb = sb * np.exp(np.clip(lb - ref, -600, 600))
    roots, _, _, still = illinois(f, a.copy(), b.copy(), fa, fb, 1e-16)
    return roots, still


def _certify(stack, cls, elements, omega, k):
    """``(kappa, ok)``: the root certified by certain opposite signs of det K (balls) at
    kappa (1 +- delta); else a certain bracket around it halved with certain signs."""
    def sign(x):
        d = det_ball(stack, cls, elements, x, omega).real
        return 1 if d > 0 else -1 if d < 0 else 0

    return _bracketed(sign, k)


def _group(stack, cls, elements, omega, k):
    K, Kk, Kw = assemble(stack, cls, elements, k, omega, derivatives=True, sparse=True)
    v = null_vector((K + K.conj().T) / 2)
    num = np.real(np.conj(v) @ (Kk @ v))
    den = np.real(np.conj(v) @ (Kw @ v))
    return -num / den


def _class_roots(stack, cls: ModeClass, omega: float):
    """Roots, labels, group velocities and failures of one class at one Omega."""
    failures = []
    # SAFE candidates (discretised for the largest wavenumber they may have)
    k_guess = 2.0 * omega + 2.0
    for _ in range(8):
        pencil = safe_pencil(stack, cls, elements_per_layer(stack, cls, omega, k_guess))
        kap = wavenumbers(pencil, omega)
        kap = kap[np.isfinite(kap)]
        near = kap[(kap.real > 0) & (np.abs(kap.imag) < 0.05 * np.abs(kap))]
        top = float(np.max(near.real, initial=0.0))
        if top < 0.8 * k_guess:
            break
        k_guess = 1.5 * top + 1.0
    cand = np.sort(near.real)
    exact_real = np.sort(kap[(kap.real > 0) & (np.abs(kap.imag) <= 1e-6 * np.abs(kap))].real)
    k_hi = 1.2 * max(float(cand.max(initial=0.0)), omega) + 0.5
    elements = None
    for _ in range(20):
        elements = sublayers(stack, cls, omega, k_hi)
        n_hi = count_and_det(stack, cls, elements, np.array([k_hi]), omega)[0][0]
        if n_hi == 0:
            break
        k_hi *= 1.5
        if k_hi > KAPPA_LIMIT:
            failures.append((omega, cls.name, f"no kappa_hi <= {KAPPA_LIMIT:g} with every "
                             "branch above Omega"))
            return [], [], [], failures, elements
    # test points: near zero, around and between candidates, the near-real parts, kappa_hi
    k_lo = 1e-9 * max(omega, 1.0)
    pts = [k_lo, k_hi]
    for c in exact_real:
        pts += [c * (1 - 1e-7), c * (1 + 1e-7)]
    pts += list(cand)
    pts = np.unique(np.clip(np.array(pts), k_lo, k_hi))
    mids = 0.5 * (pts[1:] + pts[:-1])
    pts = np.unique(np.concatenate([pts, mids]))
    N, _, _ = count_and_det(stack, cls, elements, pts, omega)
    simple = []   # (a, b, count at a, count at b): one root each
    todo = [(pts[i], pts[i + 1], int(N[i]), int(N[i + 1]), 0)
            for i in range(pts.size - 1) if N[i] != N[i + 1]]
    while todo:
        a, b, na, nb, depth = todo.pop()
        if abs(na - nb) == 1:
            simple.append((a, b, na, nb))
            continue
        if depth >= MAX_HALVINGS:
            failures.append((omega, cls.name, f"{abs(na - nb)} roots closer than round-off "
                             f"near kappa={a:.6g}"))
            continue
        m = 0.5 * (a + b)
        nm = int(count_and_det(stack, cls, elements, np.array([m]), omega)[0][0])
        for lo, hi, n1, n2 in ((a, m, na, nm), (m, b, nm, nb)):
            if n1 != n2:
                todo.append((lo, hi, n1, n2, depth + 1))
    roots, labels, groups = [], [], []
    if not simple:
        return roots, labels, groups, failures, elements
    simple.sort()
    found, still = _close(stack, cls, elements, None, omega, np.array([x[0] for x in simple]),
                          np.array([x[1] for x in simple]))
    for (a, b, na, nb), k, open_ in zip(simple, found, still):
        k = float(k)
        if open_:
            failures.append((omega, cls.name, f"root refinement did not converge near "
                             f"kappa={k:.6g}"))
        kc, ok = _certify(stack, cls, elements, omega, k)
        if not ok:
            failures.append((omega, cls.name, f"root near kappa={k:.6g} not certified "
                             f"to {ROOT_RTOL:.0e} relative"))
        g = _group(stack, cls, elements, omega, kc)
        if not (np.isfinite(g) and np.sign(g) == np.sign(na - nb)):
            failures.append((omega, cls.name, f"group velocity at kappa={kc:.6g} "
                             f"({g:.3g}) disagrees with the count ({na} -> {nb})"))
        roots.append(kc)
        labels.append(cls.label(min(na, nb)))
        groups.append(g)
    return roots, labels, groups, failures, elements


def _cutoffs(stack, cls: ModeClass, omega_top: float):
    """``[(label, Omega)]`` of the class's branches at kappa = 0 up to ``omega_top`` and
    the first above it (:func:`branches_at_kappa` at kappa = 0)."""
    return [(lab, w) for lab, w, _ in branches_at_kappa(stack, cls, 0.0, omega_top, True)]


def branches_at_kappa(stack, cls: ModeClass, kappa: float, omega_top: float,
                      next_above: bool = False):
    """``[(label, Omega, certified)]`` of every branch of the class at ``kappa`` with
    :math:`\\Omega \\le` omega_top (and the first above it with ``next_above``).

    At fixed kappa the count N(kappa, Omega) never decreases in Omega (Wittrick-Williams),
    so an interval whose ends have equal counts holds no branch: the intervals of a grid are
    halved until the counts at their ends differ by one, each such interval is closed on
    det K, and each root is certified by certain opposite signs of det K (balls) at
    Omega (1 +- ROOT_RTOL / 4). Every branch below omega_top is found: the count at
    omega_top says how many there are. At kappa = 0 the rigid translations the class allows
    are its branches at Omega = 0 (a count there is round-off: the static stiffness is
    singular).
    """
    zero = (len([d for d in cls.dofs if not (cls.half and d in cls.mid_fixed)])
            if kappa == 0 else 0)
    out = [(cls.label(j), 0.0, True) for j in range(zero)]
    kap = np.array([float(kappa)])
    top = omega_top
    elements = sublayers(stack, cls, top, max(abs(kappa), 1.0))
    for _ in range(30 if next_above else 0):   # the first branch above omega_top is below top
        n_top = int(count_and_det(stack, cls, elements, kap, np.array([top]))[0][0])
        n_req = int(count_and_det(stack, cls, elements, kap, np.array([omega_top]))[0][0])
        if n_top > n_req:
            break
        top = 1.25 * top + 0.5
        elements = sublayers(stack, cls, top, max(abs(kappa), 1.0))
    # the rigid translations are the branches with cut-off 0; the count at a tiny Omega is
    # round-off (the static stiffness is singular at kappa = 0), so the grid starts above
    grid = np.linspace(0, top, 33)[1:]
    counts = count_and_det(stack, cls, elements, np.full(grid.size, float(kappa)), grid)[0]
    lo = np.concatenate([[0.0], grid[:-1]])
    c_lo = np.concatenate([[zero], counts[:-1]])
    simple_a, simple_b, simple_n = [], [], []
    todo = [(a, b, na, nb) for a, b, na, nb in zip(lo, grid, c_lo, counts) if nb > na]
    for _ in range(60):
        if not todo:
            break
        split = [t for t in todo if t[3] - t[2] > 1 or t[0] == 0.0]
        for a, b, na, nb in todo:
            if not (nb - na > 1 or a == 0.0):
                simple_a.append(a)
                simple_b.append(b)
                simple_n.append(na)
        if not split:
            todo = []
            break
        mids = np.array([0.5 * (t[0] + t[1]) for t in split])
        cm = count_and_det(stack, cls, elements, np.full(mids.size, float(kappa)), mids)[0]
        todo = []
        for (a, b, na, nb), m, n in zip(split, mids, cm):
            if n > na:
                todo.append((a, m, na, int(n)))
            if nb > n:
                todo.append((m, b, int(n), nb))
    if todo:
        out += [(f"{cls.name}?", float("nan"), False)]
    if simple_a:
        w, _ = _close(stack, cls, elements, float(kappa), None, np.array(simple_a),
                      np.array(simple_b))
        for x, n in sorted(zip(w, simple_n)):
            ok = True
            if kappa != 0:
                x, ok = _certify_in_omega(stack, cls, elements, float(kappa), float(x))
            out.append((cls.label(int(n)), float(x), ok))
    return out


def _certify_in_omega(stack, cls, elements, kappa, w):
    """Certain opposite signs of det K (balls) at Omega (1 +- ROOT_RTOL / 4), else a certain
    bracket around the root halved with certain signs (:func:`_bracketed`)."""
    def sign(x):
        d = det_ball(stack, cls, elements, kappa, x).real
        return 1 if d > 0 else -1 if d < 0 else 0

    return _bracketed(sign, w)


def _bracketed(sign, x):
    """``(root, ok)``: ``x`` certified by certain opposite signs at x (1 +- ROOT_RTOL / 4),
    else the first bracket x (1 +- w), w = 1e-11, 1e-9, 1e-7, with certain opposite signs,
    halved with certain signs down to that width."""
    delta = ROOT_RTOL / 4
    if sign(x * (1 - delta)) * sign(x * (1 + delta)) < 0:
        return x, True
    for w in (1e-11, 1e-9, 1e-7):
        a, b = x * (1 - w), x * (1 + w)
        sa = sign(a)
        if sa * sign(b) < 0:
            for _ in range(60):
                if b - a <= 2 * delta * abs(a):
                    return 0.5 * (a + b), True
                m = 0.5 * (a + b)
                sm = sign(m)
                if sm == 0:
                    return x, False
                a, b = (m, b) if sm == sa else (a, m)
            return x, False
    return x, False


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
    stack = plate.scaled()
    classes = mode_classes(plate)
    if families is not None:
        known = sorted({c.family for c in classes})
        unknown = [f for f in families if f not in known]
        if unknown or not families:
            raise InputError(f"families must be a non-empty subset of {', '.join(known)} for "
                             f"this plate; got {', '.join(map(str, families)) or 'none'}")
        classes = tuple(c for c in classes if c.family in families)
    rows, failures = [], []
    for i, w in enumerate(omega):
        for cls in classes:
            roots, labels, groups, fails, _ = _class_roots(stack, cls, float(w))
            failures += fails
            rows += [(i, lab, cls.family, k, g) for k, lab, g in zip(roots, labels, groups)]
    order = {c.name: n for n, c in enumerate(classes)}
    fam_order = {"S": 0, "A": 1, "L": 0, "M": 0, "SH": 2}

    def number(label):
        digits = label.lstrip("SAHLM")
        return int(digits) if digits.isdigit() else 10**9

    rows.sort(key=lambda r: (r[0], number(r[1]), fam_order.get(r[2], 3), r[3]))
    del order
    cutoffs = {}
    top = float(omega.max())
    for family in dict.fromkeys(c.family for c in classes):
        # every cut-off up to the top frequency, and the family's next one
        found = sorted((w, lab) for c in classes if c.family == family
                       for lab, w in _cutoffs(stack, c, top))
        above = [lab for w, lab in found if w > top][:1]
        cutoffs.update({lab: w for w, lab in found if w <= top or lab in above})
    return LayeredRoots(plate, omega, np.array([r[0] for r in rows], dtype=int),
                        tuple(r[1] for r in rows), tuple(r[2] for r in rows),
                        np.array([r[3] for r in rows]), np.array([r[4] for r in rows]),
                        cutoffs, tuple(dict.fromkeys(failures)),
                        tuple(c.name for c in classes))
