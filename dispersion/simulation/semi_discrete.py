"""The semi-discrete (space only) record of a run: central differences' own error taken out exactly.

Central differences with step :math:`\\tau` advance, from rest,

.. math::

    \\mathbf M (\\mathbf u_{k+1} - 2 \\mathbf u_k + \\mathbf u_{k-1})
    = \\tau^2 (\\mathbf g f_k - \\mathbf K \\mathbf u_k)

(a massless row of a singular rule reads :math:`0 = g_m f_k - (\\mathbf K \\mathbf u_k)_m`,
paper eq 12: the same equation with a zero row of M). Summed against
:math:`e^{-i\\tilde\\omega k\\tau}` over the whole response, with
:math:`\\tilde{\\mathbf U}(\\tilde\\omega) = \\sum_k \\mathbf u_k e^{-i\\tilde\\omega k\\tau}`
and :math:`F_d(\\tilde\\omega) = \\sum_k f_k e^{-i\\tilde\\omega k\\tau}`,

.. math::

    (\\mathbf K - \\hat\\Omega^2 \\mathbf M)\\, \\tilde{\\mathbf U}(\\tilde\\omega)
    = \\mathbf g F_d(\\tilde\\omega), \\qquad
    \\hat\\Omega = \\frac{2}{\\tau} \\sin\\frac{\\tilde\\omega\\tau}{2},

while the semi-discrete system :math:`\\mathbf M \\ddot{\\mathbf u} + \\mathbf K \\mathbf u =
\\mathbf g f(t)` has :math:`(\\mathbf K - \\omega^2 \\mathbf M) \\mathbf U(\\omega) = \\mathbf g
F(\\omega)`. Both are the one transfer function :math:`\\mathbf H` of the mesh, at frequencies
related by the map of central differences, so frequency by frequency

.. math::

    \\tau\\, \\tilde{\\mathbf U}(\\tilde\\omega) = \\mathbf H(\\omega)\\, \\tau F_d(\\tilde\\omega),
    \\qquad \\tilde\\omega = \\frac{2}{\\tau} \\arcsin \\frac{\\omega\\tau}{2}

(:func:`dispersion.time_stepping.fully_discrete.time_frequency`). The run's velocity records
:math:`\\mathbf w_{k+1/2} = (\\mathbf u_{k+1} - \\mathbf u_k)/\\tau` on the half steps have the
transform :math:`\\tilde{\\mathbf W}(\\tilde\\omega) = \\sum_k \\mathbf w_{k+1/2}
e^{-i\\tilde\\omega (k + 1/2)\\tau} = i\\hat\\Omega\\, \\tilde{\\mathbf U}(\\tilde\\omega)`, and
:math:`\\hat\\Omega(\\tilde\\omega(\\omega)) = \\omega`, so

.. math::

    \\tau\\, \\tilde{\\mathbf W}(\\tilde\\omega) = i\\omega\\, \\mathbf H(\\omega)\\, \\tau
    F_d(\\tilde\\omega) :

the run's velocity record read at :math:`\\tilde\\omega` *is* the semi-discrete velocity at
:math:`\\omega`, the response to the load whose spectrum is :math:`\\tau
F_d(\\tilde\\omega(\\omega))` (the burst as the run sampled it, :math:`\\approx
F(\\tilde\\omega)`: the same burst with its frequency axis stretched by
:math:`\\tilde\\omega/\\omega - 1 \\approx (\\omega\\tau)^2/24`, 0.2 % at 0.9 of the study's
critical steps). That is the exact time integration of the semi-discrete system, formed from
the run's own station records, with no eigen-decomposition of the strip and no second run.
Two choices, both measured: the velocity is read, not the displacement (the free strip keeps
a static offset after the burst, so a displacement record never ends and its cut leaks into
the band: 0.9 % in the transfer between two stations of a p = 1 lumped strip); and
:math:`F` itself is not restored by dividing by :math:`F_d` (at the nulls of the burst's
spectrum inside the band that amplifies the record's round-off into a tone through the whole
record: 0.6 % L2 at the far station of a 20-wavelength run). The load's spectrum cancels
from every error measured (each station is judged against the reference station's own record
continued by the exact branch), so what is compared is the mesh's propagation alone.
:func:`semi_discrete_records` evaluates it on the FFT bins of the burst's band (the only
frequencies the errors compare) and returns it on the half steps
:math:`(k + \\tfrac12)\\tau`, the times of the fully discrete velocity records; the errors of
:mod:`~.signal_error` are then measured on it exactly as on the run.

**Where it holds.** The sums run over the whole response; the record stops at
:math:`t_{end}`. At a station the direct wave has passed within the record (the strip's far
end reflects nothing back before :math:`t_{end}`, :func:`~.strip.plan_strip`) the rest is
what a semi-infinite strip would leave, nothing in the band: the identity holds to the
record's in-band tail. That is the condition under which the fully discrete errors are
measurable at all (:func:`~.signal_error.tail_fraction` below
:data:`~.signal_error.TAIL_LEVEL`); where the fully discrete record of a station or of the
reference station runs past its end the semi-discrete one is not formed (a failure, never
guessed). Measured on the study's scene (S0, 40 wavelengths: p = 2 consistent at N = 6,
nodal-greville at N = 12): the semi-discrete errors formed from a run at 0.9 of the critical
step and from one at 0.1 agree in the carrier phase to 1e-5 (it does not depend on the
load's spectrum) and in the arrival and L2 errors, which weigh the spectrum, to 1 %. The
tests check the records against an independent exact modal integration of the
semi-discrete system and the errors against a run at a small Courant number.

:func:`time_phase_error` is the leading-order closed form of what the map adds to the carrier
phase over a distance: :math:`\\hat\\Omega = \\Omega (1 - (\\Omega\\tau)^2/24 + \\dots)`, so the
fully discrete wave at :math:`\\Omega` travels with the semi-discrete wavenumber at
:math:`\\hat\\Omega`, :math:`\\Delta\\kappa \\approx -\\Omega (\\Omega\\tau)^2 / (24 c_g)`, and
the phase gains :math:`\\Omega (\\Omega\\tau)^2 \\Delta x / (24 c_g)`.

>>> import numpy as np
>>> from dispersion.simulation.tone_burst import ToneBurst
>>> burst, dt = ToneBurst(5, 1.0), 0.02
>>> t = (np.arange(8000) + 0.5) * dt             # a "system" whose velocity is its load
>>> v = semi_discrete_records(burst.signal(t)[:, None], dt, (0.0, 8.0))
>>> bool(np.abs(v[:, 0] - burst.signal(t)).max() < 1e-3)   # read at omega~, 2e-5 apart
True
>>> round(time_phase_error(1.0, 0.1, 24.0, 1.0), 6)     # 1 * 0.01 / 24 * 24
0.01

References
----------
T. J. R. Hughes, *The Finite Element Method*, Dover 2000, sec. 9.3 (central differences,
period error). A. V. Oppenheim, R. W. Schafer, *Discrete-Time Signal Processing*, 3rd ed.,
Pearson 2010, ch. 3 (the z-transform of a difference equation).
"""
from __future__ import annotations

import numpy as np

from dispersion.errors import InputError, check_positive
from dispersion.simulation.modal_synthesis import fft_length

__all__ = ["semi_discrete_records", "time_phase_error"]


def semi_discrete_records(velocities, dt: float, band) -> np.ndarray:
    """The semi-discrete velocity at every station, from a central-difference run's records.

    Parameters
    ----------
    velocities : array, shape (n_steps, stations)
        :math:`(u_{k+1} - u_k)/\\tau` at the stations, on the half steps (the run from rest).
    dt : float
        The run's step :math:`\\tau`.
    band : (float, float)
        Angular frequencies kept (every other FFT bin is zero); below the limit
        :math:`\\omega\\tau < 2` of the map.

    Returns
    -------
    array, shape (n_steps, stations)
        The semi-discrete velocity on the same half steps, band-limited (module docstring).
    """
    from dispersion.time_stepping.fully_discrete import time_frequency

    dt = float(check_positive("dt", dt))
    v = np.asarray(velocities, dtype=float)
    if v.ndim != 2 or v.shape[0] < 2 or not np.all(np.isfinite(v)):
        raise InputError("velocities must be (n_steps, stations) finite records")
    n = v.shape[0]
    nfft = fft_length(n)
    omega = 2 * np.pi * np.fft.rfftfreq(nfft, dt)
    keep = (omega >= band[0]) & (omega <= band[1])
    w = omega[keep]
    if np.any(w * dt >= 2):
        raise InputError("the band reaches the limit of central differences' map "
                         "(omega dt >= 2): no semi-discrete frequency maps there")
    shifted = time_frequency(w, dt)
    half = (np.arange(n) + 0.5) * dt
    X = np.zeros((omega.size, v.shape[1]), complex)
    X[keep] = np.exp(0.5j * w * dt)[:, None] * (np.exp(-1j * np.outer(shifted, half)) @ v)
    return np.fft.irfft(X, nfft, axis=0)[:n]


def time_phase_error(omega: float, tau: float, distance: float, group: float) -> float:
    """Leading-order carrier phase (rad) central differences add over ``distance`` at
    frequency ``omega``, step ``tau`` and group velocity ``group`` (module docstring)."""
    return float(omega * (omega * tau) ** 2 / 24 * distance / group)
