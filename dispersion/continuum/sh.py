"""Shear-horizontal (SH) modes of a free plate, in closed form.

A plate :math:`-h \\le y \\le h` carries SH waves :math:`u_z = U(y) e^{i(kx - \\omega t)}` with
traction-free faces when :math:`U = \\cos(n\\pi (y + h) / (2h))`, :math:`n = 0, 1, 2, \\dots`
(SH0, SH1, ...; n even symmetric, n odd antisymmetric). In the toolkit's units
(:math:`\\kappa = kh`, :math:`\\Omega = \\omega h / c_T`)

.. math::

    \\Omega^2 = \\kappa^2 + \\left(\\frac{n\\pi}{2}\\right)^2, \\qquad
    \\frac{c_g}{c_T} = \\frac{d\\Omega}{d\\kappa} = \\frac{\\kappa}{\\Omega}, \\qquad
    c_p c_g = c_T^2,

so the cut-offs are :math:`f_n = n c_T / (2d)` with :math:`d = 2h`, and SH0 is not dispersive.

>>> [(lab, round(k, 6)) for lab, k, _ in sh_roots(2.0)]
[('SH0', 2.0), ('SH1', 1.237982)]

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, Cambridge University Press 2004, sec. 9.2;
B. A. Auld, *Acoustic fields and waves in solids*, vol. II, 1973, ch. 10.
"""
from __future__ import annotations

import math

from dispersion.errors import check_real_in_range

__all__ = ["AT_CUTOFF_RTOL", "at_cutoff", "sh_cutoffs", "sh_roots", "sh_mode_shape"]

#: Largest Omega of an SH request (the list has about 2 Omega / pi entries).
SH_OMEGA_MAX = 1e6
#: A requested Omega within this relative distance of a cut-off *is* at the cut-off: the
#: mode has kappa = 0 and infinite phase velocity there, so it is not propagating and not
#: listed (:func:`at_cutoff` names it). Rule: Omega reaches the toolkit through about four
#: roundings of the user's frequency (2 pi f h / c_T) and a cut-off through two or three
#: (n pi / 2, or a square root for the Lamb families), so 8 eps covers both; a request
#: farther away gets its true, certified kappa (next to a cut-off kappa ~ sqrt of the
#: distance, the phase velocity large but finite).
AT_CUTOFF_RTOL = 8 * 2.0**-52


def sh_cutoffs(omega_max: float) -> list[tuple[str, float]]:
    """``(label, Omega_n)`` with :math:`\\Omega_n = n\\pi/2 \\le` ``omega_max``.

    >>> [(lab, round(w, 4)) for lab, w in sh_cutoffs(4.0)]
    [('SH0', 0.0), ('SH1', 1.5708), ('SH2', 3.1416)]
    """
    omega_max = float(check_real_in_range("omega_max", omega_max, 0, SH_OMEGA_MAX))
    return [(f"SH{n}", n * math.pi / 2) for n in range(int(2 * omega_max / math.pi) + 1)
            if n * math.pi / 2 <= omega_max]


def at_cutoff(Omega: float, cutoff: float) -> bool:
    """True if ``Omega`` is the cut-off ``cutoff`` to rounding (:data:`AT_CUTOFF_RTOL`).

    >>> at_cutoff(11 * math.pi / 2 * (1 + 2**-52), 11 * math.pi / 2), at_cutoff(1.0 + 1e-12, 1.0)
    (True, False)
    """
    return abs(Omega - cutoff) <= AT_CUTOFF_RTOL * abs(Omega)


def sh_roots(Omega: float) -> list[tuple[str, float, float]]:
    """Propagating SH modes at :math:`\\Omega > 0`: ``(label, kappa, dOmega/dkappa)``.

    :math:`\\kappa = \\sqrt{(\\Omega - n\\pi/2)(\\Omega + n\\pi/2)}`; within 1e-3 relative
    of a cut-off the difference is taken with pi to 40 digits (mpmath), so kappa keeps its
    relative accuracy there (with the float pi the rounding of :math:`n\\pi/2` alone moves
    kappa by :math:`\\epsilon / 2\\delta` at a relative distance delta). A mode at its cut-off (:func:`at_cutoff`) has
    kappa = 0 and is not propagating: it is not listed.
    """
    Omega = float(check_real_in_range("Omega", Omega, 0, SH_OMEGA_MAX, lo_open=True))
    out = []
    for label, wc in sh_cutoffs(min(Omega * (1 + 2 * AT_CUTOFF_RTOL), SH_OMEGA_MAX)):
        if at_cutoff(Omega, wc):
            continue
        n = int(label[2:])
        if abs(Omega - wc) > 1e-3 * Omega:
            # the float pi's rounding moves kappa by eps wc / (2 (Omega - wc)) < 1e-13
            if Omega <= wc:
                continue
            kappa = math.sqrt((Omega - wc) * (Omega + wc))
        else:   # next to the cut-off: the difference with pi to 40 digits
            import mpmath

            with mpmath.workdps(40):
                W = mpmath.mpf(Omega)
                d = W - n * mpmath.pi / 2
                if d <= 0:
                    continue
                kappa = float(mpmath.sqrt(d * (W + n * mpmath.pi / 2)))
        out.append((label, kappa, kappa / Omega))
    return out


def sh_mode_shape(label: str, y):
    """:math:`U(y) = \\cos(n\\pi(y+1)/2)` and :math:`dU/dy` at ``y`` (units of h), max |U| = 1.

    >>> [round(float(v), 12) for v in sh_mode_shape("SH1", [-1.0, 0.0, 1.0])[0]]
    [1.0, 0.0, -1.0]
    """
    import numpy as np

    n = int(label[2:])
    y = np.asarray(y, dtype=float)
    a = n * math.pi / 2
    return np.cos(a * (y + 1)), -a * np.sin(a * (y + 1))
