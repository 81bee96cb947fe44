"""What the dispersion analysis predicts for a simulated burst: the fully discrete branch.

The strip's interior is the Bloch plate patch with the same thickness mesh (p, n), aspect
ratio :math:`r = b/H`, mass rule and Poisson's ratio. Its semi-discrete branch
:math:`\\Omega_h(\\kappa)` (:func:`dispersion.discretization.discrete_branches.discrete_branches`, with
the group velocity :math:`c_h = d\\Omega_h/d\\kappa`) integrated by central differences with the
run's own step :math:`\\tau` travels with the fully discrete frequency
(:func:`dispersion.time_stepping.fully_discrete.time_frequency`)

.. math::

    \\sin \\frac{\\tilde\\Omega \\tau}{2} = \\frac{\\Omega_h \\tau}{2}, \\qquad
    \\tilde c_g = \\frac{d\\tilde\\Omega}{d\\kappa} = \\frac{c_h}{\\cos(\\tilde\\Omega\\tau/2)} .

A burst of carrier :math:`\\Omega_c` excites the discrete wavenumber :math:`\\tilde\\kappa`
with :math:`\\tilde\\Omega(\\tilde\\kappa) = \\Omega_c` (bracketed on samples of the branch
around the exact :math:`\\kappa`, refined on their cubic Hermite interpolant,
:func:`predict`). Over a distance :math:`\\Delta x` the analysis then predicts

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
    #: The branch as sampled: kappa, Omega_tilde and its slope (for :func:`band_arrival_error`).
    samples: tuple = ()


def _branch(patch, nu, label, tau):
    """``kappa -> (Omega_tilde, d Omega_tilde / d kappa)`` arrays of the fully discrete branch."""
    from dispersion.discretization.discrete_branches import discrete_branches
    from dispersion.time_stepping.fully_discrete import time_frequency

    def at(kappa):
        kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
        br = discrete_branches(patch, nu, kappa, group=True)
        if label not in br.omega:
            nan = np.full(kappa.shape, np.nan)
            return nan, nan
        w, cg = np.asarray(br.omega[label], float), np.asarray(br.group[label], float)
        wt = time_frequency(w, tau)
        with np.errstate(invalid="ignore"):
            return wt, cg / np.cos(wt * tau / 2)

    return at


#: Samples of the fully discrete branch over [KAPPA_SPAN[0], KAPPA_SPAN[1]] x kappa (clipped
#: to the Brillouin zone) that bracket the root, and of the bracket that refines it.
KAPPA_SPAN = (0.25, 2.5)
SAMPLES = 33


def _hermite_root(k0, k1, f0, f1, d0, d1, target):
    """Root of the cubic Hermite interpolant of (f, f') on [k0, k1] where it crosses target."""
    from scipy.optimize import brentq

    h = k1 - k0

    def cubic(k):
        t = (k - k0) / h
        h00, h10 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t
        h01, h11 = -2 * t**3 + 3 * t**2, t**3 - t**2
        return h00 * f0 + h10 * h * d0 + h01 * f1 + h11 * h * d1 - target

    return brentq(cubic, k0, k1, xtol=1e-15 * k1, rtol=4 * np.finfo(float).eps)


def predict(plan, tau: float) -> DispersionPrediction:
    """The prediction for the strip of ``plan`` run with step ``tau`` (module docstring).

    The root is bracketed on :data:`SAMPLES` samples of the branch over the span
    :data:`KAPPA_SPAN` times the exact wavenumber, refined on the cubic Hermite interpolant of
    the samples (values and slopes) between them and on a second, finer sampling of the
    bracket, and the group velocity taken at the root itself (three calls of the branch
    solver in all).
    """
    import sympy

    from dispersion.errors import InputError
    from dispersion.symbolic.plate import plate_patch

    s = plan.strip
    label = s.mode
    k_ex, cg_ex = float(s.kappa_c), float(plan.group_c)
    r = sympy.Rational(plan.r.numerator, plan.r.denominator)
    try:
        patch = plate_patch(s.p, plan.n, "bloch", r, s.mass, s.contact,
                            sympy.Rational(repr(s.gamma_s)))
    except InputError as exc:  # a rule the Bloch plate patch does not model
        return DispersionPrediction(plan.omega_c, tau, plan.distance, k_ex, cg_ex, None, None,
                                    None, None, None, f"no Bloch plate patch: {exc.reason}")
    at = _branch(patch, plan.nu, label, tau)
    edge = math.pi / float(r)
    target = plan.omega_c
    lo, hi = KAPPA_SPAN[0] * k_ex, min(KAPPA_SPAN[1] * k_ex, edge * (1 - 1e-9))
    failure = None
    root = None
    samples = ()
    for _ in range(2):  # a coarse sampling, then one of the bracket it finds
        k = np.linspace(lo, hi, SAMPLES)
        w, d = at(k)
        if not samples:
            samples = (tuple(k.tolist()), tuple(w.tolist()), tuple(d.tolist()))
        ok = np.isfinite(w) & np.isfinite(d)
        cross = np.flatnonzero(ok[:-1] & ok[1:] & ((w[:-1] - target) * (w[1:] - target) <= 0))
        if cross.size == 0:
            break
        i = int(cross[0])
        root = _hermite_root(k[i], k[i + 1], w[i], w[i + 1], d[i], d[i + 1], target)
        lo, hi = k[i], k[i + 1]
    if root is None:
        failure = (f"the fully discrete {label} branch does not reach Omega_c = {target:.6g} "
                   f"for kappa in [{KAPPA_SPAN[0]:g}, {KAPPA_SPAN[1]:g}] x {k_ex:.4g} inside "
                   f"the Brillouin zone (kappa < {edge:.6g})")
    else:
        w, d = at([root])
        w, cg = float(w[0]), float(d[0])
        if not (math.isfinite(w) and abs(w - target) <= 1e-9 * target and cg > 0):
            failure = f"no fully discrete {label} root at Omega_c = {target:.6g}"
    if failure is not None:
        return DispersionPrediction(plan.omega_c, tau, plan.distance, k_ex, cg_ex, None, None,
                                    None, None, None, failure, samples)
    k = root
    return DispersionPrediction(plan.omega_c, tau, plan.distance, k_ex, cg_ex, k, cg,
                                cg_ex / cg - 1, -(k - k_ex) * plan.distance, k_ex / k - 1,
                                None, samples)


#: Most of the burst's energy the band prediction may leave out (frequencies the sampled
#: branch does not reach) before it is a failure.
BAND_MISSING = 1e-2


def band_arrival_error(prediction: DispersionPrediction, omega, weights, group_exact
                       ) -> tuple[float | None, str | None]:
    """The energy arrival error the fully discrete branch predicts over the whole band.

    The centroid of :math:`|z|^2` of a single mode moves by the group delay averaged over its
    energy spectrum, :math:`\\Delta x \\sum_k w_k / c_g(\\Omega_k) / \\sum_k w_k`, exactly; so
    with the weights :math:`w_k = |U(x_0, \\Omega_k)|^2` of the received burst the branch
    predicts :math:`\\sum w / \\tilde c_g \\,/\\, \\sum w / c_g - 1` (the discrete group velocity at
    each frequency from the cubic Hermite interpolant of the branch's samples). Returns
    ``(error, failure)``: None and the reason where the samples miss more than
    :data:`BAND_MISSING` of the energy.
    """
    if not prediction.samples:
        return None, "no samples of the branch"
    k, w, d = (np.asarray(a, dtype=float) for a in prediction.samples)
    omega, weights = np.asarray(omega, float), np.asarray(weights, float)
    group_exact = np.asarray(group_exact, float)
    ok = np.isfinite(w) & np.isfinite(d)
    slow = np.full(omega.shape, np.nan)
    for j, target in enumerate(omega):
        cross = np.flatnonzero(ok[:-1] & ok[1:] & ((w[:-1] - target) * (w[1:] - target) <= 0))
        if cross.size == 0:
            continue
        i = int(cross[0])
        h = k[i + 1] - k[i]
        root = _hermite_root(k[i], k[i + 1], w[i], w[i + 1], d[i], d[i + 1], target)
        t = (root - k[i]) / h
        slope = ((6 * t**2 - 6 * t) * w[i] / h + (3 * t**2 - 4 * t + 1) * d[i]
                 + (-6 * t**2 + 6 * t) * w[i + 1] / h + (3 * t**2 - 2 * t) * d[i + 1])
        if slope > 0:
            slow[j] = 1.0 / slope
    have = np.isfinite(slow)
    missing = float(weights[~have].sum() / weights.sum()) if weights.sum() > 0 else 1.0
    if missing > BAND_MISSING:
        return None, (f"the sampled branch misses {100 * missing:.2g} % of the burst's energy "
                      "(frequencies it does not reach)")
    wk = weights[have]
    return float(np.sum(wk * slow[have]) / np.sum(wk / group_exact[have]) - 1), None
