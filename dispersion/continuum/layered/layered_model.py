"""The layered or anisotropic plate as a :class:`~dispersion.continuum.plate_model.PlateModel`:
what the calculators ask of it, answered from the exact dynamic stiffness of the stack.

Units of :meth:`~dispersion.continuum.layered.layered_plate.LayeredPlate.scaled`. The classes
are the plate's :func:`~dispersion.continuum.layered.dynamic_stiffness.mode_classes` (S, A,
SHS, SHA for a symmetric decoupled stack; L and SH, or M, otherwise). The model answers:

- **dispersion**: :math:`\\det K(\\kappa, \\Omega)` of the class, signed exactly by its
  Wittrick-Williams count (:math:`\\operatorname{sign} \\det K = (-1)^N`), scaled by its
  value at :math:`\\kappa = 1` of the same frequency so that it stays in range;
- **count**: :math:`N(\\kappa, \\Omega)`, the class's branches below Omega at kappa;
- **certify**: certain opposite signs of :math:`\\det K` in ball arithmetic
  (:func:`~dispersion.continuum.layered.dynamic_stiffness.det_ball`) at
  :math:`\\kappa (1 \\pm` :data:`ROOT_RTOL` / 4), else a certain bracket halved;
- **slope**: :math:`c_g = -\\bar v^T K_\\kappa v / \\bar v^T K_\\Omega v` (v the null vector);
- **cutoffs**: every branch at kappa = 0 (:func:`branches_at_kappa`: counted in Omega);
- **candidates**: the B-spline SAFE wavenumbers near the positive real axis.

>>> from dispersion.continuum.layered.layered_plate import layered_plate
>>> from dispersion.materials.materials import material
>>> m = LayeredModel(layered_plate([(material("steel"), 0.71), (material("aluminium"), 0.29)]))
>>> m.classes(), [m.label("L", j) for j in range(3)]
(('L', 'SH'), ['L0', 'L1', 'L2'])
>>> int(m.count("L", [0.5], 2.0)[0])     # L0 and L1 lie below Omega = 2 at kappa = 0.5
2
"""
from __future__ import annotations

from functools import cached_property

import numpy as np

from dispersion.continuum.layered.dynamic_stiffness import (ModeClass, assemble, count_and_det,
                                                            det_ball, mode_classes, null_vector,
                                                            sublayers)
from dispersion.continuum.layered.safe import elements_per_layer, safe_pencil, wavenumbers

__all__ = ["LayeredModel", "branches_at_kappa", "ROOT_RTOL", "OMEGA_RANGE", "KAPPA_LIMIT",
           "MAX_HALVINGS"]

#: Relative accuracy every root is certified to (or listed in ``failures``).
ROOT_RTOL = 1e-12
#: Dimensionless frequencies accepted (omega h / c_ref). Rule: the isotropic calculator's
#: range (:data:`dispersion.continuum.frequency.FREQUENCY_OMEGA_MIN`, ``_MAX``).
OMEGA_RANGE = (2e-3, 30.0)
#: Largest kappa_hi tried before a class is listed as a failure.
KAPPA_LIMIT = 1000.0
#: Depth of the halving of an interval whose counts differ by more than one.
MAX_HALVINGS = 45


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




class LayeredModel:
    """A :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate` (undamped) as a
    plate model; its scaled stack and classes are computed once."""

    kappa_limit = KAPPA_LIMIT

    def __init__(self, plate):
        self.plate = plate

    @cached_property
    def stack(self):
        return self.plate.scaled()

    @cached_property
    def _classes(self) -> dict:
        return {c.name: c for c in mode_classes(self.plate)}

    def mode_class(self, name: str) -> ModeClass:
        return self._classes[name]

    def classes(self) -> tuple[str, ...]:
        return tuple(self._classes)

    def closed_form(self, cls: str) -> bool:
        return False

    def closed_form_roots(self, cls: str, omega: float) -> list:
        raise NotImplementedError("a layered plate has no closed-form class")

    def label(self, cls: str, j: int) -> str:
        return self.mode_class(cls).label(j)

    def elements(self, cls: str, omega_max: float, kappa_max: float):
        """The sublayers valid up to ``omega_max`` and ``kappa_max``."""
        return sublayers(self.stack, self.mode_class(cls), float(omega_max),
                         max(float(kappa_max), 1.0))

    def count(self, cls: str, kappa, omega, *, kappa_max=None):
        """N at each kappa; ``kappa_max``: the largest kappa the sublayers must serve
        (default: the largest of the call)."""
        kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
        omega = np.broadcast_to(np.asarray(omega, dtype=float), kappa.shape)
        els = self.elements(cls, float(np.max(omega, initial=0.0)),
                            float(np.max(kappa, initial=0.0)) if kappa_max is None
                            else kappa_max)
        return count_and_det(self.stack, self.mode_class(cls), els, kappa, omega)[0]

    def candidates(self, cls: str, omega: float):
        """``(near, real)``: the real parts of the B-spline SAFE wavenumbers with
        :math:`|\\mathrm{Im}\\,\\kappa| < 0.05 |\\kappa|` and positive real part (the
        discretisation refined until it resolves the largest of them), sorted, and those
        real to 1e-6."""
        c = self.mode_class(cls)
        k_guess = 2.0 * omega + 2.0
        for _ in range(8):
            pencil = safe_pencil(self.stack, c, elements_per_layer(self.stack, c, omega,
                                                                   k_guess))
            kap = wavenumbers(pencil, omega)
            kap = kap[np.isfinite(kap)]
            near = kap[(kap.real > 0) & (np.abs(kap.imag) < 0.05 * np.abs(kap))]
            top = float(np.max(near.real, initial=0.0))
            if top < 0.8 * k_guess:
                break
            k_guess = 1.5 * top + 1.0
        real = kap[(kap.real > 0) & (np.abs(kap.imag) <= 1e-6 * np.abs(kap))].real
        return np.sort(near.real), np.sort(real)

    def close(self, cls: str, omega: float, a, b, *, kappa_max=None):
        """Roots in kappa of det K on the brackets ``[a, b]`` (Illinois, all at once):
        ``(roots, still open)``."""
        els = self.elements(cls, omega, float(np.max(b)) if kappa_max is None else kappa_max)
        return _close(self.stack, self.mode_class(cls), els, None, omega, a, b)

    def dispersion(self, cls: str, kappa, omega):
        """``(value, bound)``: :math:`\\det K` signed by the count, times
        :math:`1 / |\\det K(1, \\Omega)|` (a positive factor of the frequency alone); the
        sign is exact up to the float inertia of the pivots, so the bound is 0."""
        kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
        omega = np.broadcast_to(np.asarray(omega, dtype=float), kappa.shape)
        c = self.mode_class(cls)
        top = float(np.max(omega, initial=0.0))
        els = self.elements(cls, top, float(np.max(kappa, initial=0.0)))
        _, ld, sg = count_and_det(self.stack, c, els, kappa, omega)
        uw, inv = np.unique(omega, return_inverse=True)
        _, ref, _ = count_and_det(self.stack, c, els, np.ones(uw.size), uw)
        value = sg * np.exp(np.clip(ld - ref[inv.reshape(omega.shape)], -700, 700))
        return value, np.zeros_like(value)

    def decide(self, cls: str, kappa: float, omega: float) -> int:
        els = self.elements(cls, omega, kappa)
        d = det_ball(self.stack, self.mode_class(cls), els, kappa, omega).real
        return 1 if d > 0 else -1 if d < 0 else 0

    def kappa_start(self, omega: np.ndarray) -> np.ndarray:
        """Beyond the slowest bulk wave (every branch but the fundamental flexural one is
        faster) and beyond the flexural branch at low frequency (Omega ~ kappa^2)."""
        slow = min(layer.solid.slowest_speed() for layer in self.plate.layers)
        ratio = self.stack.c_ref / slow
        return 1.3 * np.maximum(2.0 * np.sqrt(omega), ratio * omega) + 0.2

    def cutoffs(self, cls: str, omega_top: float) -> np.ndarray:
        return np.array(sorted(w for _, w, _ in branches_at_kappa(
            self.stack, self.mode_class(cls), 0.0, omega_top)))

    def cutoff_table(self, cls: str, omega_top: float) -> list[tuple[str, float]]:
        found = [(lab, w) for lab, w, _ in branches_at_kappa(
            self.stack, self.mode_class(cls), 0.0, omega_top, True)]
        above = [lab for lab, w in found if w > omega_top][:1]
        return [(lab, w) for lab, w in found if w <= omega_top or lab in above]

    def polish(self, cls: str, kappa, omega):
        return kappa

    def certify(self, cls: str, roots, omega, cells, *, kappa_max=None):
        c = self.mode_class(cls)
        out, bad = np.array(roots, dtype=float), []
        for i, (k, w) in enumerate(zip(out, omega)):
            els = self.elements(cls, float(w), float(k) if kappa_max is None else kappa_max)
            kc, ok = _certify(self.stack, c, els, float(w), float(k))
            out[i] = kc
            if not ok:
                bad.append(i)
        return out, np.zeros(out.size, dtype=bool), bad

    def slope(self, cls: str, kappa, omega, redone, *, kappa_max=None) -> np.ndarray:
        c = self.mode_class(cls)
        return np.array([_group(self.stack, c, self.elements(
            cls, float(w), float(k) if kappa_max is None else kappa_max), float(w), float(k))
            for k, w in zip(kappa, omega)])

    def split_pair(self, cls: str, kappa: float, omega: float, sign: int):
        return None
