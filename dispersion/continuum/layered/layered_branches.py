"""Every mode of a layered plate at given wavenumbers: the branches below a frequency, counted.

At a fixed :math:`\\kappa` the number of the class's modes below :math:`\\Omega` is the
Wittrick-Williams count of the exact stiffness (:mod:`dispersion.continuum.layered.dynamic_stiffness`),
which never decreases in :math:`\\Omega`: every branch below ``omega_max`` is found and named
by the count (branch j is the j-th of its class), closed on :math:`\\det K` and certified by
certain opposite signs of it in ball arithmetic at :math:`\\Omega(1 \\pm 2.5\\cdot 10^{-13})`
(:func:`~dispersion.continuum.layered.layered_modes.branches_at_kappa`); group velocities from the null
vector of K. What cannot be certified is listed in ``failures``.

>>> from dispersion.continuum.layered.layered_plate import layered_plate
>>> from dispersion.materials.materials import material
>>> b = layered_branches(layered_plate([(material("steel"), 1.0)]), [1.0], 2.0)
>>> [(lab, round(float(w), 10)) for lab, w in zip(b.label, b.omega)]
[('S0', 1.6104401822), ('A0', 0.6478232112), ('SH0', 1.0), ('SH1', 1.8620958891)]
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dispersion.continuum.layered.dynamic_stiffness import mode_classes, sublayers
from dispersion.errors import InputError

__all__ = ["LayeredBranches", "layered_branches"]


@dataclass(frozen=True)
class LayeredBranches:
    """One row per branch and wavenumber: ``kappa``, ``omega`` (dimensionless), ``label``,
    ``family``, ``group`` (:math:`d\\Omega/d\\kappa`); ``failures`` as elsewhere."""

    plate: object
    omega_max: float
    kappa: np.ndarray
    omega: np.ndarray
    label: tuple
    family: tuple
    group: np.ndarray
    failures: tuple


def layered_branches(plate, kappa, omega_max: float, *, families=None) -> LayeredBranches:
    """Every branch of an undamped ``plate`` with :math:`\\Omega \\le` ``omega_max`` at each
    ``kappa`` (units of :meth:`~dispersion.continuum.layered.layered_plate.LayeredPlate.scaled`)."""
    from dispersion.continuum.layered.layered_model import OMEGA_RANGE, _group, branches_at_kappa

    if not plate.lossless:
        raise InputError("layered_branches: the plate is damped (complex frequencies at a "
                         "real wavenumber are not solved)")
    try:
        kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    except (TypeError, ValueError):
        raise InputError("kappa must be a number or a list of numbers") from None
    if kappa.ndim != 1 or not np.all(np.isfinite(kappa)) or np.any(kappa < 0) \
            or np.any(kappa > 300):
        raise InputError("kappa = k h must be a 1-d list of numbers in [0, 300]")
    if not 0 < omega_max <= OMEGA_RANGE[1]:
        raise InputError(f"omega_max must lie in (0, {OMEGA_RANGE[1]:g}], got {omega_max!r}")
    stack = plate.scaled()
    classes = [c for c in mode_classes(plate) if families is None or c.family in families]
    rows, failures = [], []
    for k in kappa:
        for cls in classes:
            elements = sublayers(stack, cls, omega_max, max(float(k), 1.0))
            for lab, w, ok in branches_at_kappa(stack, cls, float(k), omega_max):
                if not np.isfinite(w):
                    failures.append((float(k), cls.name, "branches closer than round-off"))
                    continue
                if not ok:
                    failures.append((float(k), cls.name, f"{lab} near Omega={w:.6g} not "
                                     "certified to 1e-12 relative"))
                g = _group(stack, cls, elements, w, float(k)) if (k > 0 and w > 0) else 0.0
                rows.append((float(k), w, lab, cls.family, g))
    return LayeredBranches(plate, float(omega_max), np.array([r[0] for r in rows]),
                           np.array([r[1] for r in rows]), tuple(r[2] for r in rows),
                           tuple(r[3] for r in rows), np.array([r[4] for r in rows]),
                           tuple(dict.fromkeys(failures)))
