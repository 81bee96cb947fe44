"""The evanescent modes of an undamped plate at a real frequency: imaginary and complex
wavenumbers, found by SAFE, polished on the exact relation, each certified and counted.

At a real :math:`\\Omega` an undamped plate has, besides its propagating modes (real
:math:`\\kappa`), infinitely many non-propagating ones: purely imaginary and complex
:math:`\\kappa = \\kappa' + i\\kappa''`, whose amplitude falls as :math:`e^{-\\kappa'' x/h}`
(:math:`20\\log_{10}(e)\\,\\kappa''/h` dB per metre). Those with
:math:`0 < \\kappa'' \\le` ``im_max`` are listed, one of each set of mirror images: the exact
relation of an undamped plate is real on the real axis up to a factor (:math:`K(\\bar\\kappa) =
K(\\kappa)^H`), so :math:`\\bar\\kappa` is a root with :math:`\\kappa`; a plate symmetric
under the half turn about its normal (every stack of in-plane rotated orthotropic or
monoclinic layers) has :math:`-\\kappa` too. The listed one decays towards +x
(:math:`\\kappa'' > 0`) and has :math:`\\kappa' \\ge 0`; :math:`-\\kappa' + i\\kappa''` is its
mirror image, the same mode travelling the other way.

For each :class:`~dispersion.continuum.layered.dynamic_stiffness.ModeClass`:

1. **Candidates.** Every eigenvalue of the B-spline SAFE pencil
   (:func:`~dispersion.continuum.layered.safe.wavenumbers`) with :math:`0 < \\kappa'' \\le
   1.25` ``im_max``, reflected to :math:`\\kappa' \\ge 0`; while the count (step 4) finds
   more roots than the list, again with twice and four times the elements
   (:data:`REFINEMENTS`).
2. **Polished** by the secant method on :math:`\\det K` in complex arithmetic (the damped
   solver's, :mod:`~dispersion.continuum.layered.damped_modes`), then a few secant steps on
   the 160-bit values of F below (the float determinant loses digits near
   :math:`\\kappa = 0`); one root of each set of candidates that meet.
3. **Certified** each: the entire function :math:`F = \\det K \\prod \\det P_{ut}`
   (:func:`~dispersion.continuum.layered.dynamic_stiffness.det_ball`, ``entire=True``) winds
   once around 0 along a 16-gon of circumradius :data:`ROOT_RTOL` :math:`|\\kappa|` around
   the root (:func:`~dispersion.continuum.layered.argument_principle.winding`: arguments
   certain in ball arithmetic at every sample, steps below an eighth of a turn). A root
   within that distance of the imaginary axis is centred on it: the polygon is then its own
   mirror image, so its one root is purely imaginary.
4. **Counted.** The winding of F along the rectangle :math:`|\\kappa'| \\le R`,
   :math:`|\\kappa''| \\le` ``im_max`` must equal the roots listed with their mirror images
   (4 of a complex root, 2 of an imaginary one) plus the propagating roots :math:`\\pm\\kappa`
   of the counted calculator (:func:`~dispersion.continuum.layered.layered_modes.layered_modes`).
   :math:`R` = 1.25 times the largest real part met (propagating roots and polished
   candidates) + 1. The first samples along the rectangle are at most :data:`SEGMENT`
   apart and at most half the distance to the nearest root known beforehand (the
   propagating roots and the SAFE candidates, with their mirror images:
   :func:`~dispersion.continuum.layered.argument_principle.graded_polygon`), so that
   known roots near the contour cannot alias a whole turn. A root on the rectangle, a segment not proven, or a count that differs
   goes to ``failures`` with both numbers: the class's list at that frequency is then not
   certified complete.

The roots are named by family and rank: ``S-e1``, ``S-e2``, ... in increasing
:math:`\\kappa''` (then :math:`\\kappa'`), as are ``A-e``, ``SH-e``, ``L-e``, ``M-e``.

References
----------
R. D. Mindlin, "Waves and vibrations in isotropic, elastic plates", in *Structural
Mechanics*, Pergamon (1960) 199 (the complex branches of the Rayleigh-Lamb spectrum);
J. D. Achenbach, *Wave Propagation in Elastic Solids*, North-Holland (1973), section 6.11;
I. Bartoli, A. Marzani, F. Lanza di Scalea, E. Viola, J. Sound Vib. 295 (2006) 685 (SAFE's
complex wavenumbers).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.continuum.layered.argument_principle import (graded_polygon,
                                                             regular_polygon, winding)
from dispersion.continuum.layered.damped_modes import DB_PER_NEPER, _secant, refined_on_balls
from dispersion.continuum.layered.dynamic_stiffness import det_ball, sublayers
from dispersion.errors import InputError

__all__ = ["EvanescentRoots", "evanescent_modes", "im_max_of", "DECAY_RANGE",
           "DEFAULT_DECAY", "ROOT_RTOL", "MAX_FREQUENCIES"]

#: Bound on the decay, dB per plate thickness: (0, 200] (a mode that decays faster than
#: 200 dB over one thickness is gone before it is measured; the rectangle's work grows with
#: it).
DECAY_RANGE = (0.0, 200.0)
#: Default bound on the decay: 60 dB per plate thickness (Im kappa <= 3.45).
DEFAULT_DECAY = 60.0
#: Relative radius of each root's certifying polygon.
ROOT_RTOL = 1e-10
#: Most frequencies of one request (each costs seconds of ball arithmetic per class).
MAX_FREQUENCIES = 20
#: First segment of the rectangle's edges (units of kappa).
SEGMENT = 0.25


def im_max_of(decay_db_per_thickness: float) -> float:
    """The bound on Im kappa (kappa = k h, h half the thickness) of a decay bound in dB per
    plate thickness d = 2h: :math:`\\kappa'' = D / (2 \\cdot 20 \\log_{10} e)`."""
    return float(decay_db_per_thickness) / (2 * DB_PER_NEPER)


@dataclass(frozen=True)
class EvanescentRoots:
    """Per root: ``index`` (into ``omega``), ``label``, ``family``, ``kind`` (imaginary or
    complex), complex ``kappa`` (Im > 0, Re >= 0). ``im_max`` the bound, ``region`` per
    ``(index, class)`` the half-width R of the counted rectangle, ``counts`` per
    ``(index, class)`` ``(counted, listed)`` (counted None: not proven); ``failures`` as in
    :class:`~dispersion.continuum.layered.layered_modes.LayeredRoots`."""

    plate: object
    omega: np.ndarray
    im_max: float
    index: np.ndarray
    label: tuple
    family: tuple
    kind: tuple
    kappa: np.ndarray
    failures: tuple
    classes: tuple
    region: dict
    counts: dict


def half_turn_symmetric(stack) -> bool:
    """Whether every layer's stiffness (wave frame) is unchanged by the half turn about
    the plate's normal: :math:`C_{IJ} = 0` for I in (1, 2, 3, 6) and J in (4, 5) (Voigt)."""
    C = np.asarray(stack.C)
    odd = C[:, [0, 1, 2, 5]][:, :, [3, 4]]
    return bool(np.all(np.abs(odd) <= 1e-12 * np.max(np.abs(C))))


def _check(plate, omega, im_max):
    from dispersion.continuum.layered.layered_modes import checked_omega

    if not plate.lossless:
        raise InputError("evanescent modes: the plate is damped (its modes are all complex: "
                         "use the damped solver); drop the damping")
    omega = checked_omega(omega)
    if omega.size > MAX_FREQUENCIES:
        raise InputError(f"evanescent modes: at most {MAX_FREQUENCIES} frequencies a request "
                         f"(seconds of ball arithmetic each), got {omega.size}")
    top = im_max_of(DECAY_RANGE[1])
    if not (isinstance(im_max, (int, float)) and 0 < im_max <= top):
        raise InputError(f"im_max (the bound on Im kappa) must lie in (0, {top:.6g}] "
                         f"({DECAY_RANGE[1]:g} dB per thickness), got {im_max!r}")
    _check_work(plate, omega, im_max)
    if not half_turn_symmetric(plate.scaled()):
        raise InputError("evanescent modes need a plate unchanged by the half turn about its "
                         "normal (C14, C15, C24, C25, C34, C35, C46, C56 zero in the waves' "
                         "frame); this plate's layers are not")
    return omega


def _check_work(plate, omega, im_max):
    """Refuse, before any work, a request beyond :data:`dispersion.budget.EVANESCENT_WORK_MAX`
    (the estimate of rule 7 there)."""
    from dispersion.budget import check_evanescent_work
    from dispersion.continuum.layered.dynamic_stiffness import _kelvin_min, mode_classes

    stack = plate.scaled()
    s_max = max(math.sqrt(2 * r / _kelvin_min(C)) for C, r in zip(stack.C, stack.rho))
    work = 0.0
    for w in omega:
        R = 1.25 * float(w) * s_max + 1.0
        for cls in mode_classes(plate):
            chain = sum(e.count for e in sublayers(stack, cls, float(w), math.hypot(R, im_max)))
            work += 8 * (R + im_max) / SEGMENT * (chain + 10)
    check_evanescent_work(work, int(omega.size))


def _F(stack, cls, elements, omega):
    def F(z):
        return det_ball(stack, cls, elements, z, omega, entire=True)
    return F


def _anisotropy(stack) -> float:
    """How much faster the fields vary through the thickness than along the waves at an
    imaginary kappa: the largest sqrt(C_xx / C_zz) of each displacement (C11/C55, C66/C44,
    C55/C33) over the layers (about 1.8 for an isotropic layer, 6 for a CFRP ply)."""
    C = np.asarray(stack.C).real
    ratios = [C[:, 0, 0] / C[:, 4, 4], C[:, 5, 5] / C[:, 3, 3], C[:, 4, 4] / C[:, 2, 2]]
    return float(np.sqrt(np.max(ratios)))


def _candidates(stack, cls, omega, im_max, k_real, refine: int = 1):
    """SAFE eigenvalues with 0 < Im <= 1.25 im_max, reflected to Re >= 0; the elements
    resolve the through-thickness wavenumber of kappa up to the rectangle's corner
    (:func:`_anisotropy` times it), ``refine`` times more when a count asked for it."""
    from dispersion.continuum.layered.safe import elements_per_layer, safe_pencil, wavenumbers

    k_guess = math.hypot(max(k_real, omega) + 2.0, im_max) * _anisotropy(stack) * refine
    pencil = safe_pencil(stack, cls, elements_per_layer(stack, cls, omega, k_guess))
    kap = wavenumbers(pencil, omega)
    kap = kap[np.isfinite(kap)]
    kap = kap[(kap.imag > 1e-8 * np.abs(kap)) & (kap.imag <= 1.25 * im_max)]
    kap = np.abs(kap.real) + 1j * kap.imag
    return kap[np.argsort(kap.imag)]


#: SAFE refinements tried while the count finds more roots than the list (elements x 1, 2, 4).
REFINEMENTS = (1, 2, 4)


def _class_evanescent(model, cls, omega, im_max):
    """``(roots, counted, listed, R, failures)`` of one class at one Omega."""
    from dispersion.continuum.layered.layered_modes import _class_roots

    stack = model.stack
    real, _, _, failures = _class_roots(model, cls.name, omega)
    k_real = max(real, default=0.0)
    cand = _candidates(stack, cls, omega, im_max, k_real)
    top = max(k_real, float(np.max(cand.real, initial=0.0)))
    R = 1.25 * top + 1.0
    elements = sublayers(stack, cls, omega, math.hypot(R, im_max))
    F = _F(stack, cls, elements, omega)
    rect = [complex(-R, -im_max), complex(R, -im_max), complex(R, im_max),
            complex(-R, im_max)]
    known = [s * k for k in real for s in (1, -1)] + \
        [complex(sr * c.real, si * c.imag) for c in cand for sr in (1, -1) for si in (1, -1)]
    counted, _ = winding(F, graded_polygon(rect, known, SEGMENT))
    roots, kept, fails = [], [], []
    for refine in REFINEMENTS:
        if refine > 1:
            cand = _candidates(stack, cls, omega, im_max, k_real, refine)
        for c in cand:
            k = complex(_secant(stack, cls, elements, omega, complex(c)))
            if not np.isfinite(k):
                continue
            k = complex(abs(k.real), abs(k.imag))    # its mirror image in the listed quadrant
            if k.imag <= 1e-9 * abs(k) or k.imag > im_max or k.real > R:
                continue
            k = refined_on_balls(F, k)
            r = ROOT_RTOL * abs(k)
            if abs(k.real) < r:
                k = complex(0.0, k.imag)
            if any(abs(k - q) <= 1e-7 * abs(k) for q in roots):
                continue
            roots.append(k)
            turns, _ = winding(F, regular_polygon(k, r))
            if turns != 1:
                fails.append((omega, cls.name, f"root near kappa={k:.6g}: not certified to "
                              f"{ROOT_RTOL:.0e} (winding {turns})"))
            kept.append(k)
        listed = 2 * len(real) + sum(2 if k.real == 0 else 4 for k in kept)
        if counted is None or counted <= listed:
            break
    failures += fails
    if counted is None:
        failures.append((omega, cls.name, f"count of the roots with |Re kappa| <= {R:.4g}, "
                         f"|Im kappa| <= {im_max:.4g} not proven (a root on or near the "
                         "rectangle?)"))
    elif counted != listed:
        failures.append((omega, cls.name, f"{counted} roots with |Re kappa| <= {R:.4g}, "
                         f"|Im kappa| <= {im_max:.4g} by the argument principle, {listed} "
                         "listed (with mirror images and propagating roots)"))
    return kept, counted, listed, R, failures


def evanescent_modes(plate, omega, *, im_max: float, families=None) -> EvanescentRoots:
    """The evanescent modes of an undamped ``plate`` (a
    :class:`~dispersion.continuum.layered.layered_plate.LayeredPlate`) at each ``omega``
    (units of :meth:`~dispersion.continuum.layered.layered_plate.LayeredPlate.scaled`) with
    :math:`0 < \\mathrm{Im}\\,\\kappa \\le` ``im_max``, each certified and their number
    counted, else listed in ``failures``.

    >>> from dispersion.continuum.layered.layered_plate import layered_plate
    >>> from dispersion.materials.materials import material
    >>> r = evanescent_modes(layered_plate([(material("steel"), 1.0)]), [1.0], im_max=1.0,
    ...                      families=("A",))
    >>> [(lab, kind, round(float(k.imag), 6))
    ...  for lab, kind, k in zip(r.label, r.kind, r.kappa)]
    [('A-e1', 'imaginary', 0.587881)]
    >>> r.failures
    ()
    """
    from dispersion.continuum.layered.layered_model import LayeredModel
    from dispersion.continuum.layered.layered_modes import chosen_classes

    omega = _check(plate, omega, im_max)
    model = LayeredModel(plate)
    classes = chosen_classes(model, families)
    rows, failures, region, counts = [], [], {}, {}
    for i, w in enumerate(omega):
        by_family = {}
        for cls in classes:
            kept, counted, listed, R, fails = _class_evanescent(model, cls, float(w), im_max)
            failures += fails
            region[(i, cls.name)] = R
            counts[(i, cls.name)] = (counted, listed)
            by_family.setdefault(cls.family, []).extend(kept)
        for family, ks in by_family.items():
            for n, k in enumerate(sorted(ks, key=lambda q: (q.imag, q.real)), 1):
                rows.append((i, f"{family}-e{n}", family,
                             "imaginary" if k.real == 0 else "complex", k))
    return EvanescentRoots(plate, omega, float(im_max),
                           np.array([r[0] for r in rows], dtype=int),
                           tuple(r[1] for r in rows), tuple(r[2] for r in rows),
                           tuple(r[3] for r in rows),
                           np.array([r[4] for r in rows], dtype=complex),
                           tuple(dict.fromkeys(failures)), tuple(c.name for c in classes),
                           region, counts)
