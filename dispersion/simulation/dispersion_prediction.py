"""What the dispersion analysis predicts for a simulated burst: the fully discrete branch.

The strip's interior is the Bloch plate patch with the same thickness mesh (p, n), aspect
ratio :math:`r = b/H`, mass rule and Poisson's ratio. Its semi-discrete branch
:math:`\\Omega_h(\\kappa)` (:func:`dispersion.waves.discrete_branches.discrete_branches`, with
the group velocity :math:`c_h = d\\Omega_h/d\\kappa`) integrated by central differences with the
run's own step :math:`\\tau` travels with the fully discrete frequency
(:func:`dispersion.waves.fully_discrete.time_frequency`)

.. math::

    \\sin \\frac{\\tilde\\Omega \\tau}{2} = \\frac{\\Omega_h \\tau}{2}, \\qquad
    \\tilde c_g = \\frac{d\\tilde\\Omega}{d\\kappa} = \\frac{c_h}{\\cos(\\tilde\\Omega\\tau/2)} .

A burst of carrier :math:`\\Omega_c` excites the discrete wavenumber :math:`\\tilde\\kappa`
with :math:`\\tilde\\Omega(\\tilde\\kappa) = \\Omega_c` (found by Newton's method from the
exact :math:`\\kappa`, safeguarded by bisection). Over a distance :math:`\\Delta x` the
analysis then predicts

* the arrival-time error :math:`c_g / \\tilde c_g - 1` (group delay, relative),
* the carrier phase error :math:`\\Delta\\varphi = -(\\tilde\\kappa - \\kappa)\\,\\Delta x`,
* the phase-velocity error :math:`\\kappa / \\tilde\\kappa - 1`,

all at the centre frequency: a narrow-band prediction. The measured errors
(:mod:`dispersion.simulation.signal_error`) are those of the whole band and of the strip's
ends; where the two differ the study says so.

>>> from dispersion.simulation.strip import Strip, plan_strip
>>> plan = plan_strip(Strip(p=2, mass="consistent", elements_per_wavelength=16, travel=1,
...                          stations=2))
>>> pred = predict(plan, 0.05)
>>> abs(pred.arrival_error) < 1e-3, pred.failure is None
(True, True)

References
----------
T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3 (period error of central
differences). J. L. Rose, *Ultrasonic Guided Waves in Solid Media*, 2014, sec. 6.5 (group
velocity and the travel of a burst). Paper section 2 (the patch).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["DispersionPrediction", "predict"]


@dataclass(frozen=True)
class DispersionPrediction:
    """The narrow-band prediction at the carrier (units of H and c_T; errors relative, phase
    in rad over ``distance``). ``failure`` says why a value is missing (None: all there)."""

    omega_c: float
    tau: float
    distance: float
    kappa_exact: float
    group_exact: float
    kappa_discrete: float | None
    group_discrete: float | None
    arrival_error: float | None
    phase_error: float | None
    phase_velocity_error: float | None
    failure: str | None = None


def _branch(patch, nu, label, tau):
    from dispersion.waves.discrete_branches import discrete_branches
    from dispersion.waves.fully_discrete import time_frequency

    def at(kappa):
        br = discrete_branches(patch, nu, [kappa], group=True)
        if label not in br.omega:
            return math.nan, math.nan
        w, cg = float(br.omega[label][0]), float(br.group[label][0])
        wt = float(time_frequency(np.array([w]), tau)[0])
        if not math.isfinite(wt):
            return math.nan, math.nan
        return wt, cg / math.cos(wt * tau / 2)

    return at


def predict(plan, tau: float, *, rtol: float = 1e-13, max_iter: int = 60) -> DispersionPrediction:
    """The prediction for the strip of ``plan`` run with step ``tau`` (module docstring)."""
    import sympy

    from dispersion.symbolic.plate import plate_patch
    from dispersion.waves.frequency import modes_at_frequency

    s = plan.strip
    label = s.mode
    roots = modes_at_frequency(plan.nu, [plan.omega_c], kinds=(s.kind,), zgv=False)
    row = roots.label.index(label)
    k_ex, cg_ex = float(roots.kappa[row]), float(roots.group[row])
    from dispersion.errors import InputError

    try:
        patch = plate_patch(s.p, plan.n, "bloch", plan.r, s.mass, s.contact,
                            sympy.Rational(repr(s.gamma_s)))
    except InputError as exc:  # a rule the Bloch plate patch does not model
        return DispersionPrediction(plan.omega_c, tau, plan.distance, k_ex, cg_ex, None, None,
                                    None, None, None, f"no Bloch plate patch: {exc}")
    at = _branch(patch, plan.nu, label, tau)
    edge = math.pi / plan.r
    lo, hi = 0.0, edge
    k = min(k_ex, 0.999 * edge)
    failure, f = None, math.inf
    for _ in range(max_iter):
        w, cg = at(k)
        if not math.isfinite(w):
            hi = k
            k = 0.5 * (lo + hi)
            continue
        f = w - plan.omega_c
        if abs(f) <= rtol * plan.omega_c:
            break
        if f < 0:
            lo = k
        else:
            hi = k
        k_new = k - f / cg if cg > 0 else math.inf
        k = k_new if lo < k_new < hi else 0.5 * (lo + hi)
    else:
        if abs(f) > 1e-9 * plan.omega_c:
            failure = (f"the fully discrete {label} branch does not reach Omega_c = "
                       f"{plan.omega_c:.6g} inside the Brillouin zone (kappa < {edge:.6g})"
                       if hi == edge else f"Newton's method found no fully discrete {label} "
                       f"root at Omega_c = {plan.omega_c:.6g}")
    w, cg = at(k)
    if failure is not None:
        return DispersionPrediction(plan.omega_c, tau, plan.distance, k_ex, cg_ex, None, None,
                                    None, None, None, failure)
    return DispersionPrediction(plan.omega_c, tau, plan.distance, k_ex, cg_ex, k, cg,
                                cg_ex / cg - 1, -(k - k_ex) * plan.distance, k_ex / k - 1)
