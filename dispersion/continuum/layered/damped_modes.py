"""The modes of a damped layered plate at a real frequency: complex wavenumbers, attenuation.

With complex moduli (:meth:`dispersion.materials.stiffness.Stiffness.with_loss`) the
wavenumber of each mode at a real :math:`\\Omega` is complex, :math:`\\kappa = \\kappa' +
i\\kappa''`, and the wave decays as :math:`e^{-\\kappa'' x / h}`: an attenuation of
:math:`20 \\log_{10}(e)\\, \\kappa'' / h` dB per metre. The count of the undamped plate does
not apply (the stiffness is no longer Hermitian), so each mode is followed from the undamped
plate of the real parts of the moduli (:func:`~dispersion.continuum.layered.layered_modes.layered_modes`,
its names and its roots):

1. **Followed.** Each certified undamped root is continued as the imaginary parts of the
   moduli grow from 0 to their value in :data:`CONTINUATION_STEPS` steps, each closed by
   the secant method on :math:`\\det K(\\kappa, \\Omega)` in complex arithmetic
   (:func:`~dispersion.continuum.layered.dynamic_stiffness.count_and_det`): the damped root keeps the
   undamped mode's name; two modes that meet in one root are listed as failures.
2. **Refined** where the certificate below fails at the float root: a few secant steps on
   the 160-bit ball values of the entire function (:func:`refined_on_balls`; the float
   determinant loses digits near kappa = 0: S0 of 1 mm steel at 2.1 kHz, eta 1e-4, was
   left uncertified before), then certified again.
3. **Certified** by the argument principle: the entire function
   :math:`\\det K \\prod \\det P_{ut}` (:func:`~dispersion.continuum.layered.dynamic_stiffness.det_ball`,
   ``entire=True``) is evaluated in ball arithmetic at the :data:`CIRCLE_POINTS` vertices of
   the polygon inscribed in the circle :math:`|\\kappa - \\kappa_0| = ` :data:`ROOT_RTOL`
   :math:`|\\kappa_0|`, and between them wherever the argument moves by more than an eighth
   of a turn (:func:`~dispersion.continuum.layered.argument_principle.winding`, shared with
   the evanescent modes); it winds once around 0 (every argument certain) when one root
   lies within that distance. Else the root is listed in ``failures``; so is a damped root
   farther than :data:`MATCH` (relative) from its undamped one (the name would be a guess).

References
----------
I. Bartoli, A. Marzani, F. Lanza di Scalea, E. Viola, "Modeling wave propagation in
damped waveguides of arbitrary cross-section", J. Sound Vib. 295 (2006) 685 (SAFE with
hysteretic damping); M. J. S. Lowe, "Matrix techniques for modeling ultrasonic waves in
multilayered media", IEEE UFFC 42 (1995) 525 (complex roots of layered plates).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.continuum.layered.dynamic_stiffness import (count_and_det, det_ball, mode_classes,
                                                    sublayers)

__all__ = ["damped_modes", "lossless_twin", "DampedRoots", "ROOT_RTOL", "CIRCLE_POINTS",
           "MATCH", "DB_PER_NEPER"]

#: Relative radius of the certifying circle: every damped root to this accuracy.
ROOT_RTOL = 1e-10
#: Points of the certifying circle (consecutive points 22.5 degrees apart).
CIRCLE_POINTS = 16
#: Largest relative distance between a damped root and the undamped root it is named after.
MATCH = 0.25
#: Steps in which the loss is switched on while a root is followed from the undamped plate.
CONTINUATION_STEPS = 8
#: Decibels per neper.
DB_PER_NEPER = 20 / math.log(10)


@dataclass(frozen=True)
class DampedRoots:
    """Per root: ``index`` (into ``omega``), ``label``, ``family``, complex ``kappa``;
    ``failures`` as in :class:`~dispersion.continuum.layered.layered_modes.LayeredRoots`."""

    plate: object
    omega: np.ndarray
    index: np.ndarray
    label: tuple
    family: tuple
    kappa: np.ndarray
    failures: tuple
    classes: tuple
    cutoffs: dict


def lossless_twin(plate):
    """The plate with the real parts of its moduli (the undamped plate its modes come from)."""
    from dispersion.continuum.layered.layered_plate import Layer, LayeredPlate
    from dispersion.materials.solid import Solid
    from dispersion.materials.stiffness import Stiffness

    layers = tuple(Layer(Solid(Stiffness(tuple(map(tuple, layer.solid.stiffness.array().real)),
                                         layer.solid.stiffness.kind),
                               layer.solid.rho, layer.solid.name, layer.solid.source),
                         layer.thickness_mm, layer.angle) for layer in plate.layers)
    return LayeredPlate(layers, plate.interfaces, plate.direction)


def _det(stack, cls, elements, omega, k):
    _, ld, sg = count_and_det(stack, cls, elements, np.array([k], dtype=complex), omega)
    return complex(sg[0]) * math.exp(min(max(ld[0], -700.0), 700.0)) if np.isfinite(ld[0]) \
        else 0.0, ld[0]


def _secant(stack, cls, elements, omega, k0):
    """Root of det K near ``k0`` by the secant method (values scaled by the first one)."""
    a, b = k0, k0 * (1 + 1e-7)
    _, ref = _det(stack, cls, elements, omega, a)

    def f(x):
        _, ld, sg = count_and_det(stack, cls, elements, np.array([x], dtype=complex), omega)
        return complex(sg[0]) * np.exp(np.clip(ld[0] - ref, -600, 600))

    fa, fb = f(a), f(b)
    for _ in range(60):
        if fb == fa:
            break
        c = b - fb * (b - a) / (fb - fa)
        a, fa, b, fb = b, fb, c, f(c)
        if abs(b - a) <= 1e-15 * abs(b) or fb == 0:
            break
    return b


def _partly_damped(stack, s: float):
    """The stack with the imaginary parts of its moduli times ``s``."""
    from dataclasses import replace

    return replace(stack, C=stack.C.real + 1j * s * stack.C.imag)


def refined_on_balls(F, k, steps: int = 4):
    """A few secant steps on the midpoints of the ball values of F (160 bits): the float
    determinant loses digits near kappa = 0 and near other roots, the balls do not."""
    a, b = k, k * (1 + 1e-9)
    fa, fb = complex(F(a).mid()), complex(F(b).mid())
    for _ in range(steps):
        if fb == fa:
            break
        c = b - fb * (b - a) / (fb - fa)
        a, fa, b = b, fb, c
        fb = complex(F(b).mid())
        if abs(b - a) <= 1e-14 * abs(b):
            break
    return b if np.isfinite(b) and abs(b - k) <= 1e-6 * abs(k) else k


def _winding(stack, cls, elements, omega, k):
    """``(turns, k)``: turns of the entire function around 0 on the certifying polygon about
    ``k`` (None if a sample's ball meets 0 or its argument is uncertain, or the steps do not
    resolve: :func:`~dispersion.continuum.layered.argument_principle.winding`); where it is
    not 1, the root refined on the ball values (:func:`refined_on_balls`) and certified there
    if it can be, the refined root returned with it."""
    from dispersion.continuum.layered.argument_principle import regular_polygon, winding

    def F(z):
        return det_ball(stack, cls, elements, z, omega, entire=True)

    turns, _ = winding(F, regular_polygon(k, ROOT_RTOL * abs(k), CIRCLE_POINTS))
    if turns != 1:          # the float secant may stop short where det K loses digits
        better = refined_on_balls(F, k)
        if better != k:
            again, _ = winding(F, regular_polygon(better, ROOT_RTOL * abs(better),
                                                  CIRCLE_POINTS))
            if again == 1:
                return 1, better
    return turns, k


def damped_modes(plate, omega, *, families=None) -> DampedRoots:
    """The modes of a damped ``plate`` at each real ``omega`` (units of
    :meth:`~dispersion.continuum.layered.layered_plate.LayeredPlate.scaled`), named after the
    undamped plate's, each complex root certified to :data:`ROOT_RTOL` or listed."""
    from dispersion.continuum.layered.layered_modes import layered_modes

    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    twin = layered_modes(lossless_twin(plate), omega, families=families)
    stack = plate.scaled()
    classes = {c.name: c for c in mode_classes(plate)}
    by_family = {}
    for c in classes.values():
        by_family.setdefault(c.family, []).append(c)
    rows, failures = [], list(twin.failures)
    for i, W in enumerate(omega):
        mine = [n for n in range(twin.kappa.size) if twin.index[n] == i]
        if not mine:
            continue
        k_max = 2.0 * max(twin.kappa[n] for n in mine) + 2.0
        for cls in classes.values():
            names = [n for n in mine if twin.family[n] == cls.family
                     and _in_class(cls, twin.label[n])]
            if not names:
                continue
            elements = sublayers(stack, cls, W, k_max)
            found = {}
            for n in names:
                k0 = complex(twin.kappa[n])
                k = k0
                for j in range(1, CONTINUATION_STEPS + 1):   # the loss switched on in steps
                    k = _secant(_partly_damped(stack, j / CONTINUATION_STEPS), cls, elements,
                                float(W), k)
                if not np.isfinite(k) or abs(k - k0) > MATCH * abs(k0):
                    failures.append((float(W), cls.name, f"{twin.label[n]}: no damped root "
                                     f"within {MATCH:g} of the undamped one"))
                    continue
                found[n] = k
            for n, k in found.items():
                twins = [m for m, q in found.items() if m != n and abs(q - k) <= 1e-8 * abs(k)]
                if twins:
                    failures.append((float(W), cls.name, f"{twin.label[n]} and "
                                     f"{', '.join(twin.label[m] for m in twins)} lead to one "
                                     f"damped root near kappa={k:.6g}: names not certain"))
                    continue
                turns, k = _winding(stack, cls, elements, float(W), k)
                if turns != 1:
                    failures.append((float(W), cls.name, f"{twin.label[n]} near kappa={k:.6g}:"
                                     f" not certified to {ROOT_RTOL:.0e} (winding {turns})"))
                rows.append((i, twin.label[n], cls.family, k))
    return DampedRoots(plate, omega, np.array([r[0] for r in rows], dtype=int),
                       tuple(r[1] for r in rows), tuple(r[2] for r in rows),
                       np.array([r[3] for r in rows], dtype=complex),
                       tuple(dict.fromkeys(failures)), twin.classes, twin.cutoffs)


def _in_class(cls, label: str) -> bool:
    """Whether a mode name belongs to the class (SH_n of a symmetric stack: parity of n)."""
    if not label.startswith(cls.prefix):
        return False
    digits = label[len(cls.prefix):]
    if not digits.isdigit():
        return False
    return (int(digits) - cls.offset) % cls.step == 0
