"""The Hann-windowed tone burst: the excitation of a guided-wave simulation.

An :math:`N`-cycle tone burst of carrier frequency :math:`\\Omega_c` (units :math:`c_T/H`,
H the half-thickness of the plate) is the carrier under one Hann window of the same length,

.. math::

    f(t) = \\sin(\\Omega_c t) \\; \\tfrac12 \\bigl(1 - \\cos(\\Omega_c t / N)\\bigr), \\qquad
    0 \\le t \\le D = 2\\pi N / \\Omega_c ,

and 0 outside. It is three sinusoids switched on over :math:`[0, D]`, so its spectrum
:math:`F(\\Omega) = \\int_0^D f(t) e^{-i\\Omega t} dt` is a sum of closed forms
(:meth:`ToneBurst.spectrum`). Its main lobe spans :math:`\\Omega_c (1 \\pm 2/N)`; the side
lobes fall as :math:`|\\Omega - \\Omega_c|^{-3}`. :meth:`ToneBurst.band` is the interval
where :math:`|F| \\ge` ``rel`` :math:`\\max |F|` (the band a modal synthesis must cover).

>>> b = ToneBurst(5, 1.0)
>>> round(b.duration, 12), float(b.signal(0.0)), float(b.signal(b.duration + 1))
(31.415926535898, 0.0, 0.0)
>>> lo, hi = b.band(1e-3)
>>> bool(lo < 1.0 < hi)
True

References
----------
J. L. Rose, *Ultrasonic Guided Waves in Solid Media*, Cambridge University Press 2014,
sec. 8.8 (tone-burst excitation of Lamb waves). F. J. Harris, "On the use of windows for
harmonic analysis with the discrete Fourier transform", Proc. IEEE 66 (1978) 51-83 (Hann
window: main-lobe half width 2 bins, side lobes -31 dB falling 18 dB per octave).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from dispersion.errors import check_positive, check_positive_int

__all__ = ["ToneBurst", "MAX_CYCLES"]

#: Most cycles of a burst: a longer burst is a near-monochromatic wave whose envelope peak
#: is too flat to time (and needs a strip longer than its 40 wavelengths of travel).
MAX_CYCLES = 20


@dataclass(frozen=True)
class ToneBurst:
    """``cycles`` periods of :math:`\\sin \\Omega_c t` under a Hann window (``omega_c``:
    c_T/H)."""

    cycles: int
    omega_c: float

    def __post_init__(self):
        check_positive_int("cycles", self.cycles, maximum=MAX_CYCLES)
        object.__setattr__(self, "omega_c", float(check_positive("omega_c", self.omega_c)))

    @property
    def duration(self) -> float:
        """:math:`D = 2 \\pi N / \\Omega_c` (units H/c_T)."""
        return 2 * math.pi * self.cycles / self.omega_c

    def signal(self, t):
        """:math:`f(t)`, zero outside :math:`[0, D]`."""
        t = np.asarray(t, dtype=float)
        inside = (t >= 0) & (t <= self.duration)
        w = self.omega_c
        return np.where(inside, np.sin(w * t) * 0.5 * (1 - np.cos(w * t / self.cycles)), 0.0)

    def spectrum(self, omega):
        """:math:`F(\\Omega) = \\int_0^D f(t) e^{-i\\Omega t} dt` in closed form.

        :math:`f` is :math:`\\tfrac12 \\sin w t - \\tfrac14 \\sin (w \\pm w/N) t`, and
        :math:`\\int_0^D \\sin(a t) e^{-i\\Omega t} dt =
        \\tfrac{1}{2i}(E(a - \\Omega) - E(-a - \\Omega))` with
        :math:`E(s) = (e^{i s D} - 1)/(i s)` (:math:`= D` at :math:`s = 0`).
        """
        omega = np.asarray(omega, dtype=float)
        D, w, N = self.duration, self.omega_c, self.cycles

        def E(s):
            small = np.abs(s) * D < 1e-8
            safe = np.where(small, 1.0, s)
            return np.where(small, D + 0.5j * s * D * D, (np.exp(1j * safe * D) - 1) / (1j * safe))

        def sine(a):
            return (E(a - omega) - E(-a - omega)) / 2j

        return 0.5 * sine(w) - 0.25 * sine(w * (1 + 1 / N)) - 0.25 * sine(w * (1 - 1 / N))

    def band(self, rel: float = 1e-4) -> tuple[float, float]:
        """The interval around :math:`\\Omega_c` where :math:`|F| \\ge` ``rel`` :math:`\\max|F|`.

        Found on a grid of 1/200 of the main-lobe half width over :math:`(0, 4\\Omega_c]`:
        the outermost grid points that still reach the level (side lobes included).
        """
        check_positive("rel", rel)
        step = self.omega_c * 2 / self.cycles / 200
        grid = np.arange(step, 4 * self.omega_c + step, step)
        mag = np.abs(self.spectrum(grid))
        above = np.flatnonzero(mag >= rel * mag.max())
        return float(grid[above[0]]), float(grid[above[-1]])
