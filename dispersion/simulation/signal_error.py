"""The error of a received signal against its reference: arrival time, carrier phase, L2.

Both signals are band-limited to the burst's band first (the same FFT bins), so the three
measures compare the burst and nothing else; what the simulation put outside the band is
reported apart (``out_of_band``, relative L2 norm).

* **Arrival time**: the time of the peak of the Hilbert envelope :math:`|z(t)|`, with
  :math:`z` the analytic signal (the band's positive-frequency bins, doubled). The sampled
  maximum is refined between its neighbours on the band-limited interpolant of :math:`z`
  (the sum over the bins, evaluated at any t), so the peak time carries no sampling error.
  The error is relative to the travel time of the reference from the reference station,
  :math:`(t_{sim} - t_{ref}) / (t_{ref} - t_0)`. Beside it, the *energy* arrival: the
  centroid :math:`\\int t |z|^2 dt / \\int |z|^2 dt` of the envelope, which a single mode
  carries exactly at its band-averaged group delay (the peak of a distorted envelope is not).
* **Carrier phase**: :math:`\\Delta\\varphi = \\arg U_{sim}(\\Omega_c) / U_{ref}(\\Omega_c)` (the
  transforms at exactly the carrier frequency, :func:`carrier_phase`), on the branch nearest
  to ``phase_guess`` (the caller follows the phase from zero at the reference station along
  stations a wavelength apart); with the propagation phase :math:`\\kappa\\Delta x` it gives
  the phase-velocity error :math:`\\kappa / (\\kappa - \\Delta\\varphi/\\Delta x) - 1`.
* **L2**: :math:`\\|u_{sim} - u_{ref}\\| / \\|u_{ref}\\|` over the record.

What cannot be measured (an envelope peak at an end of the record, a burst that runs past its
end) is reported in ``failure``, never guessed.

>>> import numpy as np
>>> dt, t = 0.05, np.arange(4000) * 0.05
>>> burst = lambda s: np.exp(-((t - s) / 6.0) ** 2) * np.cos(2.0 * (t - s))
>>> e = signal_error(burst(100.3), burst(100.0), 0.05, (0.5, 4.0), 2.0,
...                  origin=(10.0, 10.0), distance=90.0, kappa=1.0, phase_guess=0.0)
>>> round(e.arrival_error * 90, 6), round(e.energy_arrival_error * 90, 6)  # 0.3 late of 90
(0.3, 0.3)
>>> round(e.phase_error, 6)                                                # -2 * 0.3
-0.6

References
----------
D. Gabor, "Theory of communication", J. IEE 93 (1946) 429-457 (the analytic signal).
P. D. Wilcox, M. J. S. Lowe, P. Cawley, "The effect of dispersion on long-range inspection
using ultrasonic guided waves", NDT&E Int. 34 (2001) 1-9 (arrival and spreading of bursts).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dispersion.simulation.modal_synthesis import fft_length

__all__ = ["SignalError", "envelope_peak", "envelope_centroid", "carrier_phase", "signal_error",
           "TAIL_LEVEL", "tail_fraction"]

@dataclass(frozen=True)
class SignalError:
    """Errors of one received signal (times in H/c_T, phase in rad, the rest relative)."""

    arrival_simulated: float
    arrival_reference: float
    arrival_error: float
    phase_error: float
    phase_velocity_error: float
    l2_error: float
    out_of_band: float
    energy_arrival_error: float
    failure: str | None = None


def _spectrum(u, dt, band):
    nfft = fft_length(u.size)
    omega = 2 * np.pi * np.fft.rfftfreq(nfft, dt)
    U = np.fft.rfft(u, nfft)
    keep = (omega >= band[0]) & (omega <= band[1])
    return nfft, omega, U, keep


def envelope_peak(u, dt: float, band) -> tuple[float, float, bool]:
    """``(t, |z(t)|, inside)``: the refined peak of the band-limited Hilbert envelope;
    ``inside`` is False if the sampled maximum sits at an end of the record."""
    from scipy.optimize import minimize_scalar

    u = np.asarray(u, dtype=float)
    nfft, omega, U, keep = _spectrum(u, dt, band)
    Z = np.zeros(nfft, complex)
    k = np.flatnonzero(keep)
    Z[k] = 2 * U[k]
    z = np.fft.ifft(Z)[: u.size]
    i = int(np.argmax(np.abs(z)))
    inside = 0 < i < u.size - 1
    if not inside:
        return i * dt, float(abs(z[i])), False
    coef, w = Z[k] / nfft, omega[k]

    def minus_env2(t):
        v = np.sum(coef * np.exp(1j * w * t))
        return -(v.real ** 2 + v.imag ** 2)

    res = minimize_scalar(minus_env2, bounds=((i - 1) * dt, (i + 1) * dt), method="bounded",
                          options={"xatol": 1e-12 * max(1.0, i * dt)})
    return float(res.x), float(np.sqrt(-res.fun)), True


def _envelope2(u, dt: float, band) -> np.ndarray:
    nfft, _, U, keep = _spectrum(u, dt, band)
    Z = np.zeros(nfft, complex)
    k = np.flatnonzero(keep)
    Z[k] = 2 * U[k]
    return np.abs(np.fft.ifft(Z)[: u.size]) ** 2


def envelope_centroid(u, dt: float, band) -> float:
    """Centroid in time of the squared band-limited Hilbert envelope."""
    u = np.asarray(u, dtype=float)
    e2 = _envelope2(u, dt, band)
    t = np.arange(u.size) * dt
    return float(np.sum(t * e2) / np.sum(e2))


#: A record whose last 5 % hold more than this fraction of the envelope's energy has a burst
#: that runs past its end (its arrival and energy are not all in the record).
TAIL_LEVEL = 1e-2


def tail_fraction(u, dt: float, band) -> float:
    """Fraction of the band-limited envelope's energy in the last 5 % of the record (above
    :data:`TAIL_LEVEL`: the burst runs past the end of the record)."""
    e2 = _envelope2(np.asarray(u, dtype=float), dt, band)
    total = float(np.sum(e2))
    return float(np.sum(e2[int(0.95 * e2.size):])) / total if total > 0 else 0.0


def _dtft(u, dt, omega):
    t = np.arange(u.size) * dt
    return np.sum(u * np.exp(-1j * omega * t)) * dt


def carrier_phase(simulated, reference, dt: float, band, omega_c: float) -> float:
    """:math:`\\arg U_{sim}(\\Omega_c)/U_{ref}(\\Omega_c)` in :math:`(-\\pi, \\pi]`, of the
    band-limited signals."""
    from dispersion.simulation.modal_synthesis import band_limit

    ub = band_limit(simulated, dt, band)
    rb = band_limit(reference, dt, band)
    return float(np.angle(_dtft(ub, dt, omega_c) / _dtft(rb, dt, omega_c)))


def signal_error(simulated, reference, dt: float, band, omega_c: float, *, origin,
                 distance: float, kappa: float, phase_guess: float = 0.0) -> SignalError:
    """Errors of ``simulated`` against ``reference`` (same sampling ``dt``).

    ``origin`` is ``(peak, centroid)``: the arrival times of the envelope at the reference
    station (the travel starts there),
    ``distance`` the travel :math:`x - x_0`, ``kappa`` the exact wavenumber at ``omega_c``
    (for the phase-velocity error) and ``phase_guess`` the phase error the branch is chosen
    nearest to.
    """
    u = np.asarray(simulated, dtype=float)
    r = np.asarray(reference, dtype=float)
    nfft, omega, U, keep = _spectrum(u, dt, band)
    _, _, R, _ = _spectrum(r, dt, band)
    Ub = U.copy()
    Ub[~keep] = 0.0
    Rb = R.copy()
    Rb[~keep] = 0.0
    ub = np.fft.irfft(Ub, nfft)[: u.size]
    rb = np.fft.irfft(Rb, nfft)[: u.size]
    failures = []
    t_sim, _, in_sim = envelope_peak(u, dt, band)
    t_ref, _, in_ref = envelope_peak(r, dt, band)
    if not (in_sim and in_ref):
        failures.append("envelope peak at an end of the record (the burst is not inside it)")
    if tail_fraction(u, dt, band) > TAIL_LEVEL:
        failures.append("the simulated burst runs past the end of the record (slower than "
                        "the record's room for it)")
    travel = t_ref - origin[0]
    arrival = (t_sim - t_ref) / travel if travel > 0 else np.nan
    c_sim, c_ref = envelope_centroid(u, dt, band), envelope_centroid(r, dt, band)
    energy = (c_sim - c_ref) / (c_ref - origin[1]) if c_ref > origin[1] else np.nan
    wrapped = carrier_phase(u, r, dt, band, omega_c)
    phase = wrapped + 2 * np.pi * round((phase_guess - wrapped) / (2 * np.pi))
    pv = kappa / (kappa - phase / distance) - 1 if distance > 0 else np.nan
    norm = float(np.linalg.norm(rb))
    l2 = float(np.linalg.norm(ub - rb)) / norm if norm > 0 else np.nan
    total = float(np.linalg.norm(u))
    oob = float(np.linalg.norm(u - ub)) / total if total > 0 else np.nan
    return SignalError(float(t_sim), float(t_ref), float(arrival), float(phase), float(pv), l2,
                       oob, float(energy), "; ".join(failures) or None)
