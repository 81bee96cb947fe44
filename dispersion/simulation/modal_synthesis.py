"""The exact reference: a received signal continued along the plate by the exact branch.

In the far field of a symmetric (antisymmetric) end load below the first cut-off only S0 (A0)
propagates; every other mode of its class is evanescent. A displacement recorded at
:math:`x_0` then determines the one at any :math:`x > x_0` by modal synthesis,

.. math::

    U(x, \\Omega) = U(x_0, \\Omega)\\, e^{-i \\kappa(\\Omega) (x - x_0)/H}, \\qquad
    U(x, \\Omega) = \\int u(x, t) e^{-i\\Omega t} dt ,

with :math:`\\kappa(\\Omega)` the exact wavenumber of the branch at each frequency of the band
(:func:`dispersion.continuum.frequency.modes_at_frequency`, certified roots): exact phase delay
:math:`\\kappa \\Delta x` and group delay :math:`\\Delta x\\, d\\kappa/d\\Omega` at every
frequency, no narrow-band approximation. Numerically: the record of :math:`N` samples is
zero-padded to a power of two of at least ``PAD`` N samples (the continuation delays it
by less than its own length, so nothing wraps round), transformed by the real FFT, cut to
the band (every other bin set to zero), multiplied by the phase factor and transformed back.

**The rule that fixes the reference** (stated before any result was looked at): the
reference at the far station is the signal the *same run* recorded at the reference station
:math:`x_0` (``reference_station`` wavelengths from the loaded end: in the far field),
band-limited to the burst's band (:data:`dispersion.simulation.strip.BAND_LEVEL`) and
continued by the exact branch over :math:`x_1 - x_0`. Its amplitude and time origin are
therefore those of the run at :math:`x_0`: nothing is fitted, and the source region (the
end load's excitability of the mode, the near field) cancels; what remains is the
propagation over :math:`x_1 - x_0`, which is what the dispersion analysis predicts.

>>> import numpy as np
>>> dt = 0.05
>>> t = np.arange(2000) * dt
>>> pulse = np.exp(-((t - 10.0) / 2.0) ** 2)
>>> moved = continue_signal(pulse, dt, 20.0, lambda w: w / 2.0, (0.0, np.pi / dt))
>>> bool(np.abs(moved - np.exp(-((t - 20.0) / 2.0) ** 2)).max() < 1e-10)  # delay 20 / 2
True

References
----------
K. F. Graff, *Wave Motion in Elastic Solids*, Dover 1991, sec. 1.5 and 8.1 (Fourier synthesis
of dispersive pulses). P. D. Wilcox, "A rapid signal processing technique to remove the effect
of dispersion from guided wave signals", IEEE TUFFC 50 (2003) 419-427.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from dispersion.errors import InputError, check_positive

__all__ = ["PAD", "continue_signal", "band_limit", "exact_branch", "exact_wavenumber",
           "fft_length"]

#: The FFT length is a power of two of at least PAD times the record.
PAD = 2


def fft_length(n: int) -> int:
    """Power of two of at least ``PAD * n``."""
    return 1 << int(np.ceil(np.log2(max(PAD * n, 2))))


def _bins(n: int, dt: float, band):
    nfft = fft_length(n)
    omega = 2 * np.pi * np.fft.rfftfreq(nfft, dt)
    lo, hi = band
    return nfft, omega, (omega >= lo) & (omega <= hi)


def band_limit(signal, dt: float, band) -> np.ndarray:
    """``signal`` with every FFT bin outside ``band`` (in rad per unit time) set to zero."""
    u = np.asarray(signal, dtype=float)
    nfft, _, keep = _bins(u.size, dt, band)
    U = np.fft.rfft(u, nfft)
    U[~keep] = 0.0
    return np.fft.irfft(U, nfft)[: u.size]


def continue_signal(signal, dt: float, distance, wavenumber: Callable,
                    band: tuple[float, float]) -> np.ndarray:
    """The record ``signal`` (step ``dt``) band-limited and continued over ``distance``.

    ``wavenumber(omega)`` gives :math:`\\kappa` (per unit length) at an array of angular
    frequencies; it is called once, on the bins inside ``band``. ``distance`` may be an
    array: the result then has one column per distance (one transform of the record).
    """
    dt = float(check_positive("dt", dt))
    u = np.asarray(signal, dtype=float)
    if u.ndim != 1 or u.size < 2 or not np.all(np.isfinite(u)):
        raise InputError("signal must be a 1-d record of at least 2 finite samples")
    nfft, omega, keep = _bins(u.size, dt, band)
    U = np.fft.rfft(u, nfft)
    U[~keep] = 0.0
    kappa = np.asarray(wavenumber(omega[keep]), dtype=float)
    if kappa.shape != (int(keep.sum()),) or not np.all(np.isfinite(kappa)):
        raise InputError("wavenumber must return one finite kappa per frequency")
    d = np.asarray(distance, dtype=float)
    if d.ndim == 0:
        U[keep] *= np.exp(-1j * kappa * float(d))
        return np.fft.irfft(U, nfft)[: u.size]
    V = np.zeros((U.size, d.size), complex)
    V[keep] = U[keep, None] * np.exp(-1j * np.outer(kappa, d))
    return np.fft.irfft(V, nfft, axis=0)[: u.size]


def exact_branch(kind: str, nu: float, omega) -> tuple[np.ndarray, np.ndarray]:
    """Exact wavenumber and group velocity of S0 (``kind="S"``) or A0 at each frequency."""
    from dispersion.errors import ConvergenceError
    from dispersion.continuum.frequency import FREQUENCY_OMEGA_MIN, modes_at_frequency

    omega = np.asarray(omega, dtype=float)
    kappa, group = np.full(omega.shape, np.nan), np.full(omega.shape, np.nan)
    ok = omega >= FREQUENCY_OMEGA_MIN
    if np.any(ok):
        roots = modes_at_frequency(nu, omega[ok], kinds=(kind,), zgv=False)
        if roots.failures:
            raise ConvergenceError(f"exact {kind}0 not certified: {roots.failures[0]}")
        rows = [i for i, lab in enumerate(roots.label) if lab == f"{kind}0"]
        idx = np.flatnonzero(ok)[roots.index[rows]]
        kappa[idx], group[idx] = roots.kappa[rows], roots.group[rows]
    if np.any(~np.isfinite(kappa)):
        raise ConvergenceError(f"exact {kind}0 has no root at some frequency of the band "
                               f"(below Omega = {FREQUENCY_OMEGA_MIN:g}?)")
    return kappa, group


def exact_wavenumber(kind: str, nu: float) -> Callable:
    """``omega -> kappa`` of the exact S0 (``kind="S"``) or A0 branch (certified roots).

    >>> k = exact_wavenumber("S", 0.3)(np.array([0.01]))
    >>> round(float(0.01 / k[0]) ** 2, 4)      # plate speed squared, 2 / (1 - nu)
    2.8571
    """
    def wavenumber(omega):
        return exact_branch(kind, nu, omega)[0]

    return wavenumber
