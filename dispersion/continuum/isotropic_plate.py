"""The isotropic plate as a :class:`~dispersion.continuum.plate_model.PlateModel`: the
Rayleigh-Lamb plate, the first member of the family.

Units: :math:`\\kappa = kh`, :math:`\\Omega = \\omega h / c_T` (h the half thickness). The
classes are ``"S"`` and ``"A"`` (Lamb, the deflated Rayleigh-Lamb function
:func:`~dispersion.continuum.deflated_frequency.deflated_with_noise` with its rounding bound)
and ``"SH"`` (closed form, :mod:`dispersion.continuum.sh`). Its roots are certified at the
*exact* Poisson ratio ``nu_q`` (a float's binary value, a material's rational of its speeds):
in floats with a proven rounding bound, else in ball arithmetic
(:mod:`dispersion.continuum.root_certificate`); its group velocities are the float slope of the
frequency function, or its 30-digit slope where floats lose digits.

>>> from fractions import Fraction
>>> p = IsotropicPlate(Fraction(3, 10))
>>> p.classes(), p.label("A", 2), [round(float(w), 6) for w in p.cutoffs("A", 5.0)]
(('S', 'A', 'SH'), 'A2', [0.0, 1.570796, 4.712389])
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from dispersion.continuum.deflated_frequency import (deflated_with_noise,
                                                     evanescent_frequency_function)
from dispersion.continuum.illinois import illinois
from dispersion.continuum.numeric_frequency import frequency_function_bound, frequency_slope
from dispersion.continuum.rayleigh_lamb import (arb_frequency_function, cutoff_frequencies,
                                                mpmath_frequency_function, speed_ratio_squared)
from dispersion.continuum.root_certificate import (arb_certified, arb_sign, exact_square,
                                                   extremum_in_squares, float_certified,
                                                   refine_in_squares)

__all__ = ["IsotropicPlate", "ROOT_RTOL", "ROOT_DELTA", "SLOPE_OMEGA", "KAPPA_LIMIT"]

#: Relative accuracy every root in kappa is certified to (or listed in ``failures``).
ROOT_RTOL = 1e-12
#: Half-width of the certificate's bracket: a root certified at kappa lies in
#: :math:`\\kappa (1 \\pm \\delta)` (:mod:`dispersion.continuum.root_certificate`).
ROOT_DELTA = ROOT_RTOL / 4
#: Below this Omega the float slope :func:`~dispersion.continuum.numeric_frequency.frequency_slope`
#: loses about eps / Omega^2 to the trivial root of F at Omega = 0 (measured against mpmath:
#: 2e-11 at Omega = 2e-3, 3e-12 at 1e-2, 4e-14 at 0.1); rule: where eps / Omega^2 > 1e-13
#: the slope is taken in 30-digit arithmetic instead.
SLOPE_OMEGA = 0.05
#: Largest kappa of a scan.
KAPPA_LIMIT = 300.0


def _mp_digits(kappa: float) -> int:
    """Digits for the frequency function at kappa: 40, plus the cosh-sized terms that cancel
    in the evanescent region (about kappa / ln 10 digits)."""
    return 40 + int(abs(kappa) / 2.3)


def _arb_prec(kappa: float) -> int:
    """Starting precision (bits) of the frequency function in ball arithmetic at kappa: S and
    A roots at large kappa differ by about :math:`e^{-2\\kappa}` relative (3 bits per unit),
    and next to a cut-off F is flat in :math:`x = \\kappa^2`, resolved to delta only with
    :math:`\\log_2(1/x)` more bits; :func:`~dispersion.continuum.root_certificate.arb_sign` raises
    it where a ball still holds 0."""
    tiny = min(-2 * math.log2(kappa), 128.0) if 0 < kappa < 1 else 0.0
    return 96 + int(3 * min(kappa, KAPPA_LIMIT)) + int(tiny)


@dataclass(frozen=True)
class IsotropicPlate:
    """One homogeneous isotropic layer of Poisson's ratio ``nu_q`` (exact)."""

    nu_q: Fraction
    kappa_limit: float = KAPPA_LIMIT

    @property
    def nu(self) -> float:
        """The float nearest to the exact Poisson ratio."""
        return float(self.nu_q)

    @property
    def ratio(self) -> Fraction:
        """:math:`s = (c_T / c_L)^2`, exact."""
        return speed_ratio_squared(self.nu_q)

    # ------------------------------------------------------------------ classes

    def classes(self) -> tuple[str, ...]:
        return ("S", "A", "SH")

    def closed_form(self, cls: str) -> bool:
        return cls == "SH"

    def closed_form_roots(self, cls: str, omega: float) -> list:
        from dispersion.continuum.sh import sh_roots

        return sh_roots(omega)

    def label(self, cls: str, j: int) -> str:
        return f"{cls}{j}"

    def count(self, cls: str, kappa, omega):
        return None

    def candidates(self, cls: str, omega: float):
        return None

    def close(self, cls: str, omega: float, a, b, rtol: float = 1e-15):
        """Illinois on the deflated function on every bracket (a sign change each)."""
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        w = np.full(a.size, float(omega))
        fa, fb = self.dispersion(cls, a, w)[0], self.dispersion(cls, b, w)[0]
        roots, _, _, still = illinois(lambda idx, x: self.dispersion(cls, x, w[idx])[0],
                                      a.copy(), b.copy(), fa, fb, rtol)
        return roots, still

    # ------------------------------------------------------------------ the function

    def dispersion(self, cls: str, kappa, omega):
        return deflated_with_noise(cls, kappa, omega, self.nu)

    def _arb_function(self, cls: str, omega: float):
        ratio = self.ratio

        def value(x, prec):
            return arb_frequency_function(cls, x, omega, ratio, prec)
        return value

    def decide(self, cls: str, kappa: float, omega: float) -> int:
        return arb_sign(self._arb_function(cls, omega), exact_square(kappa), _arb_prec(kappa))

    def kappa_start(self, omega: np.ndarray) -> np.ndarray:
        """Beyond A0 at low frequency (Kirchhoff, A0 lies below) and beyond the Rayleigh
        speed at high frequency (S0 and A0 tend to it)."""
        beta = math.sqrt(2 / (3 * (1 - self.nu)))  # Omega ~ beta kappa^2 (eq 15)
        return 1.3 * np.maximum(np.sqrt(omega / beta), omega) + 0.2

    def cutoffs(self, cls: str, omega_top: float) -> np.ndarray:
        if cls == "SH":
            from dispersion.continuum.sh import sh_cutoffs

            return np.array([w for _, w in sh_cutoffs(omega_top)])
        return np.array([w for w, _ in cutoff_frequencies(cls, self.nu, omega_top)])

    def cutoff_table(self, cls: str, omega_top: float) -> list[tuple[str, float]]:
        top = omega_top + math.pi  # the next cut-off of every family lies within pi
        if cls == "SH":
            from dispersion.continuum.sh import sh_cutoffs

            found = sh_cutoffs(top)
        else:
            found = [(f"{cls}{j}", w) for j, (w, _) in
                     enumerate(cutoff_frequencies(cls, self.nu, top))]
        above = [lab for lab, w in found if w > omega_top][:1]
        return [(lab, w) for lab, w in found if w <= omega_top or lab in above]

    # ------------------------------------------------------------------ roots

    def polish(self, cls: str, kappa, omega, width: float = 1e-9):
        """Roots with P < 0 closed again on the scaled evanescent form (no cosh-sized
        terms)."""
        nu = self.nu
        ev = kappa**2 - speed_ratio_squared(nu) * omega**2 > 9.0
        if not np.any(ev):
            return kappa
        k, w = kappa[ev], omega[ev]
        a, b = k * (1 - width), k * (1 + width)
        fa = evanescent_frequency_function(cls, a, w, nu)
        fb = evanescent_frequency_function(cls, b, w, nu)
        ok = np.isfinite(fa) & np.isfinite(fb) & (np.sign(fa) * np.sign(fb) < 0)
        if not np.any(ok):
            return kappa
        wo = w[ok]
        roots, _, _, active = illinois(
            lambda idx, x: evanescent_frequency_function(cls, x, wo[idx], nu),
            a[ok], b[ok], fa[ok], fb[ok], 1e-17)
        sub = k.copy()
        sub[ok] = np.where(active, sub[ok], roots)
        out = kappa.copy()
        out[ev] = sub
        return out

    def _float_bound(self, cls: str, omega):
        s = float(self.ratio)
        half_ulp = 0.5 * float(np.spacing(s))   # the float nearest to the rational s

        def bound(k):
            return frequency_function_bound(cls, k, omega, s, half_ulp)
        return bound

    def certify(self, cls: str, roots, omega, cells):
        """Each root certified to :data:`ROOT_RTOL` relative by a sign change of the exact
        frequency function at the floats :math:`\\kappa (1 \\pm \\delta)`,
        :data:`ROOT_DELTA` (:mod:`dispersion.continuum.root_certificate`), at the exact
        :math:`s = (c_T/c_L)^2`.

        First in floats with a proven rounding bound; where floats cannot decide, in ball
        arithmetic at the same float kappa; where that fails too (the float root is off: next
        to a cut-off the root in kappa is ill-conditioned in floats, next to a ZGV point two
        roots merge), the root is closed again in ball arithmetic from its scan cell
        ``cells`` (its ends' signs decided there) and certified. Returns the roots, a mask of
        those certified in ball arithmetic, and the indices that could not be certified.
        """
        ok = float_certified(self._float_bound(cls, omega), roots, ROOT_DELTA)
        out, redone, bad = roots.copy(), np.zeros(roots.size, dtype=bool), []
        for i in np.flatnonzero(~ok):
            F = self._arb_function(cls, float(omega[i]))
            k0 = float(roots[i])
            if math.isfinite(k0) and k0 > 0 and arb_certified(F, k0, ROOT_DELTA, _arb_prec(k0)):
                redone[i] = True
                continue
            a, b = (float(c) for c in cells[i])
            k = refine_in_squares(F, a, b, _arb_prec(max(min(abs(k0), b), 1e-300)))
            if k is not None and k > 0 and arb_certified(F, k, ROOT_DELTA, _arb_prec(k)):
                out[i], redone[i] = k, True
            else:
                bad.append(i)
        return out, redone, bad

    def _slope_mp(self, cls: str, kappa, omega) -> np.ndarray:
        """:math:`d\\Omega/d\\kappa = -F_\\kappa / F_\\Omega` of the frequency function in
        mpmath, at the exact Poisson ratio."""
        import mpmath

        out = np.empty(kappa.size)
        for i, (k, W) in enumerate(zip(kappa, omega)):
            with mpmath.workdps(_mp_digits(float(k))):
                m_nu = mpmath.mpf(self.nu_q.numerator) / self.nu_q.denominator

                def F(k, W):
                    return mpmath_frequency_function(cls, k, W, m_nu)

                k, W = mpmath.mpf(float(k)), mpmath.mpf(float(W))
                out[i] = float(-mpmath.diff(lambda x: F(x, W), k)
                               / mpmath.diff(lambda x: F(k, x), W))
        return out

    def slope(self, cls: str, kappa, omega, redone) -> np.ndarray:
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            group = np.asarray(frequency_slope(cls, kappa, omega, self.nu), dtype=float)
        # where the root needed ball arithmetic the float slope loses as much: redone in mpmath
        low = np.flatnonzero((omega < SLOPE_OMEGA) | redone)
        if low.size:
            group[low] = self._slope_mp(cls, kappa[low], omega[low])
        return group

    def split_pair(self, cls: str, kappa: float, omega: float, sign: int):
        F = self._arb_function(cls, omega)
        prec = _arb_prec(kappa) + 64
        x = extremum_in_squares(F, kappa, prec)
        if arb_sign(F, x, prec) == -sign:
            return float(x.sqrt().mid()) if x > 0 else kappa
        return None
