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


def _exact(stack, cls, kappa, omega_top, j):
    """``(Omega, c_g)`` of branch j of the class at kappa (None if it is above omega_top)."""
    from dispersion.continuum.layered.layered_model import _group, branches_at_kappa

    found = [w for lab, w, _ in branches_at_kappa(stack, cls, kappa, omega_top)
             if lab == cls.label(j)]
    if not found:
        return None
    w = found[0]
    elements = sublayers(stack, cls, omega_top, max(kappa, 1.0))
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
        W = np.array([frequencies(pencil, float(k)) for k in kappas])   # (kappa, branch)
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
                ea, eb = _exact(stack, cls, a, omega_top * 1.2, j), _exact(stack, cls, b,
                                                                         omega_top * 1.2, j)
                if ea is None or eb is None or ea[1] * eb[1] > 0:
                    continue
                ga, gb = ea[1], eb[1]
                for _ in range(40):   # Illinois on c_g
                    c = (a * gb - b * ga) / (gb - ga)
                    ec = _exact(stack, cls, c, omega_top * 1.2, j)
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
