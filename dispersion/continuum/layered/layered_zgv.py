"""Zero-group-velocity points of a layered plate: where a branch's frequency is stationary.

A branch of a class keeps its place in the class at every kappa (branches of one class do not
cross), so branch j is the j-th frequency of the class. Its group velocity
:math:`c_g = d\\Omega/d\\kappa` changes sign at a ZGV point: brackets come from the SAFE
frequencies on a kappa grid (:func:`dispersion.continuum.layered.safe.frequencies`, their finite
differences), and each is closed on the exact branch (its frequency and group velocity from
:func:`~dispersion.continuum.layered.layered_modes.branches_at_kappa` and the null vector of K) by the
Illinois method on :math:`c_g`.

>>> from dispersion.continuum.layered.layered_plate import layered_plate
>>> from dispersion.materials.materials import material
>>> [(p[0], round(p[1], 6), round(p[2], 6))
...  for p in zgv_points(layered_plate([(material("steel"), 1.0)]), 3.0, step=0.1)]
[('S1', 0.846141, 2.699918)]
"""
from __future__ import annotations

import numpy as np

from dispersion.continuum.layered.dynamic_stiffness import mode_classes, sublayers
from dispersion.continuum.layered.safe import elements_per_layer, frequencies, safe_pencil

__all__ = ["zgv_points"]


def _exact(stack, cls, kappa, omega_top, j, guess=None):
    """``(Omega, c_g)`` of branch j of the class at kappa (None if it is above omega_top).

    Branch j lies where the count N(kappa, Omega) steps from j to j + 1 (the count never
    decreases in Omega): from a ``guess`` a bracket with those counts is widened, then closed
    on det K (Illinois in Omega); without a guess, every branch is solved
    (:func:`~dispersion.continuum.layered.layered_model.branches_at_kappa`)."""
    from dispersion.continuum.layered.dynamic_stiffness import count_and_det
    from dispersion.continuum.layered.layered_model import _close, _group, branches_at_kappa

    elements = sublayers(stack, cls, omega_top, max(kappa, 1.0))
    if guess is None or not 0 < guess < omega_top:
        found = [w for lab, w, _ in branches_at_kappa(stack, cls, kappa, omega_top)
                 if lab == cls.label(j)]
        if not found:
            return None
        w = found[0]
        return w, _group(stack, cls, elements, w, kappa)
    kap = np.array([float(kappa)])

    def count(w):
        return int(count_and_det(stack, cls, elements, kap, np.array([w]))[0][0])

    lo, hi, width = guess, guess, 1e-6 * guess
    for _ in range(60):
        lo, hi = max(guess - width, 1e-12), min(guess + width, omega_top)
        n_lo, n_hi = count(lo), count(hi)
        if n_lo <= j < n_hi:
            break
        width *= 4
    else:
        return None
    while n_lo < j or n_hi > j + 1:        # one branch in the bracket: halve by the count
        m = 0.5 * (lo + hi)
        n_m = count(m)
        if n_m <= j:
            lo, n_lo = m, n_m
        else:
            hi, n_hi = m, n_m
    w, _ = _close(stack, cls, elements, float(kappa), None, np.array([lo]), np.array([hi]))
    w = float(w[0])
    return w, _group(stack, cls, elements, w, kappa)


def zgv_points(plate, omega_top: float, step: float = 0.02):
    """``[(label, kappa, Omega)]`` of every ZGV point with :math:`\\Omega \\le` omega_top
    (units of :meth:`~dispersion.continuum.layered.layered_plate.LayeredPlate.scaled`) found on a
    kappa grid of spacing ``step`` up to omega_top (a ZGV point is a stationary frequency of
    a branch that is not a cut-off, so :math:`c_p = \\Omega / \\kappa` is finite there and,
    for the plates of the tests, kappa < Omega). A stationary point between grid points
    whose SAFE frequencies do not show it (two extrema in one cell) is not found."""
    stack = plate.scaled()
    out = []
    kappas = np.arange(step, omega_top + step, step)
    for cls in mode_classes(plate):
        pencil = safe_pencil(stack, cls, elements_per_layer(stack, cls, 1.5 * omega_top,
                                                            float(kappas[-1])))
        # the branches that reach below 1.5 omega_top anywhere on the grid: at most those
        # below it at kappa = 0 (branches rise from their cut-offs), and a margin
        first = frequencies(pencil, 0.0)
        count = int(np.count_nonzero(first < 1.5 * omega_top)) + 2
        W = np.array([frequencies(pencil, float(k), count) for k in kappas])  # (kappa, branch)
        n = W.shape[1]
        for j in range(n):
            w = W[:, j]
            if w.min() > omega_top:
                continue
            slope = np.diff(w)
            for i in np.flatnonzero((slope[:-1] < 0) & (slope[1:] > 0) | (slope[:-1] > 0)
                                    & (slope[1:] < 0)):
                a, b = float(kappas[i]), float(kappas[i + 2])
                if min(w[i:i + 3]) > omega_top:
                    continue
                ea = _exact(stack, cls, a, omega_top * 1.2, j, float(w[i]))
                eb = _exact(stack, cls, b, omega_top * 1.2, j, float(w[i + 2]))
                if ea is None or eb is None or ea[1] * eb[1] > 0:
                    continue
                ga, gb = ea[1], eb[1]
                for _ in range(40):   # Illinois on c_g
                    c = (a * gb - b * ga) / (gb - ga)
                    ec = _exact(stack, cls, c, omega_top * 1.2, j, ea[0])
                    if ec is None:
                        break
                    if ec[1] * ga > 0:
                        a, ga, gb = c, ec[1], gb / 2
                    else:
                        b, gb, ga = c, ec[1], ga / 2
                    if b - a <= 1e-12 * c or ec[1] == 0:
                        break
                if ec is not None and ec[0] <= omega_top:
                    out.append((cls.label(j), float(c), float(ec[0])))
    return sorted(out, key=lambda p: p[2])
