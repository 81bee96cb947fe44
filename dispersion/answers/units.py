"""Physical units: a material and a plate thickness turn (kappa, Omega) into Hz, m/s and mm.

The toolkit computes in :math:`\\kappa = kh` and :math:`\\Omega = \\omega h / c_T` for a plate of
thickness :math:`d = 2h`. Given the bulk speeds :math:`c_L, c_T` (or :math:`E, \\nu, \\rho`),

.. math::

    f = \\frac{\\Omega c_T}{2 \\pi h}, \\quad f d = \\frac{\\Omega c_T}{\\pi}, \\quad
    c_p = \\frac{\\Omega}{\\kappa} c_T, \\quad c_g = \\frac{d\\Omega}{d\\kappa} c_T, \\quad
    \\lambda = \\frac{2 \\pi h}{\\kappa},

the quantities the Dispersion Calculator, GEWtool or lambwaves print (frequency-thickness in
MHz mm, velocities in m/s). Plane strain ties the two: :math:`(c_T/c_L)^2 = (1-2\\nu)/(2(1-\\nu))`.

>>> al = ALUMINIUM
>>> round(al.nu, 4), round(al.plate_velocity, 1)      # S0 speed at f d -> 0, m/s
(0.3375, 5438.4)
>>> round(float(fd_mhz_mm(1.5707963267948966, al)), 4)  # A1 cut-off (Omega = pi/2): c_T / 2
1.565

References
----------
J. L. Rose, *Ultrasonic waves in solid media*, 2004, ch. 8; A. Huber, Dispersion Calculator
(DLR), user manual (units of its exports).
"""
from __future__ import annotations

import math
from dataclasses import dataclass


from dispersion.errors import InputError, check_positive
from dispersion.materials.materials import ALUMINIUM, MATERIALS, Material, material_from_moduli

import numpy as np

__all__ = [
    "ALUMINIUM",
    "MATERIALS",
    "Material",
    "NU_TOLERANCE",
    "PhysicalBranches",
    "check_same_nu",
    "fd_mhz_mm",
    "frequency_khz",
    "zgv_in_units",
    "material_from_moduli",
    "physical_branches",
    "rayleigh_speed",
]


def rayleigh_speed(material: Material) -> float:
    """Rayleigh wave speed (m/s), the root :math:`x = (c_R/c_T)^2 \\in (0, 1)` of the cubic

    .. math:: x^3 - 8 x^2 + 8 (3 - 2\\eta) x - 16 (1 - \\eta) = 0, \\quad \\eta = (c_T/c_L)^2

    (Viktorov 1967; Rahman and Barber 1995 give its root in closed form).

    >>> round(rayleigh_speed(ALUMINIUM), 1)
    2920.8
    """
    eta = (material.c_T / material.c_L) ** 2
    roots = np.roots([1.0, -8.0, 8.0 * (3 - 2 * eta), -16.0 * (1 - eta)])
    real = [r.real for r in roots if abs(r.imag) < 1e-12 and 0 < r.real < 1]
    return material.c_T * math.sqrt(min(real))


def fd_mhz_mm(Omega, material: Material):
    """Frequency-thickness :math:`f d = \\Omega c_T / \\pi` in MHz mm (Hz m is 1e-3 MHz mm)."""
    return np.asarray(Omega, dtype=float) * material.c_T / math.pi * 1e-3


#: Largest relative difference between two Poisson's ratios taken as the same nu. Rule: the
#: nu of a material is computed from its speeds in floating point (a few ulps); anything
#: above 1e-9 is a different material, not round-off.
NU_TOLERANCE = 1e-9


def check_same_nu(nu_branches, material: Material, what: str = "branches") -> float:
    """Return the material's nu if the branches were computed at it; raise naming both.

    >>> check_same_nu(0.3, ALUMINIUM)
    Traceback (most recent call last):
    ...
    dispersion.errors.InputError: branches computed at nu = 0.3 cannot be combined with aluminium (nu = 0.337506): compute them at the material's nu (e.g. exact_branches(kappa, nu=material.nu))
    """
    if nu_branches is None:
        raise InputError(f"{what} carry no nu: pass nu= (the Poisson ratio they were computed "
                         f"at) so it can be checked against {material.name} "
                         f"(nu = {material.nu:.6g})")
    nu_b = float(nu_branches)
    if not abs(nu_b - material.nu) <= NU_TOLERANCE * max(abs(material.nu), 1e-3):
        raise InputError(f"{what} computed at nu = {nu_b:.6g} cannot be combined with "
                         f"{material.name} (nu = {material.nu:.6g}): compute them at the "
                         f"material's nu (e.g. exact_branches(kappa, nu=material.nu))")
    return material.nu


@dataclass(frozen=True)
class PhysicalBranches:
    """Branches in physical units on one kappa grid (arrays per label; NaN where absent).

    ``frequency`` in kHz, ``fd`` in MHz mm, ``phase``/``group`` in m/s, ``wavelength`` in mm;
    ``nu`` is the material's, which the branches were checked to share.
    """

    material: Material
    thickness_mm: float
    frequency: dict[str, np.ndarray]
    fd: dict[str, np.ndarray]
    phase: dict[str, np.ndarray]
    group: dict[str, np.ndarray]
    wavelength: np.ndarray

    UNITS = {"frequency": "kHz", "fd": "MHz mm", "phase": "m/s", "group": "m/s",
             "wavelength": "mm"}

    @property
    def nu(self) -> float:
        return self.material.nu

    def title(self) -> str:
        """Material, thickness and nu, for captions."""
        return f"{self.material.name}, d = {self.thickness_mm:g} mm, nu = {self.nu:.4f}"

    def curves(self) -> dict[str, dict[str, np.ndarray]]:
        """Per label, arrays along the kappa grid: ``f`` (kHz), ``fd``, ``c_p``, ``c_g`` (m/s),
        ``k`` (rad/mm), for :func:`dispersion.plotting.lamb.figure_dispersion`."""
        with np.errstate(divide="ignore"):
            k = 2 * math.pi / self.wavelength
        return {lab: {"f": self.frequency[lab], "fd": self.fd[lab], "c_p": self.phase[lab],
                      "c_g": self.group.get(lab, np.full(k.shape, np.nan)), "k": k}
                for lab in self.frequency}


def physical_branches(kappa, omega: dict, group: dict | None, material: Material,
                      thickness_mm: float, *, nu: float | None = None) -> PhysicalBranches:
    """Dimensionless branches (``omega[label]``, ``group[label]`` = dOmega/dkappa) in units.

    One source of nu: the branches must have been computed at the material's Poisson ratio.
    ``omega`` as returned by the tracer (``ExactBranches.omega``) carries its ``nu``; a
    plain mapping needs ``nu=``. A mismatch raises :class:`~dispersion.errors.InputError`
    naming both values (:func:`check_same_nu`).

    >>> import numpy as np
    >>> pb = physical_branches(np.array([1.0]), {"S0": np.array([1.6])}, None, ALUMINIUM, 1.0,
    ...                        nu=ALUMINIUM.nu)
    >>> round(float(pb.fd["S0"][0]), 4), round(float(pb.wavelength[0]), 4)   # h = 0.5 mm
    (1.5941, 3.1416)
    """
    check_positive("thickness", thickness_mm)
    tagged = getattr(omega, "nu", None)
    if tagged is not None and nu is not None and float(tagged) != float(nu):
        raise InputError(f"nu = {nu:.6g} given, but the branches were computed at "
                         f"nu = {float(tagged):.6g}")
    check_same_nu(tagged if tagged is not None else nu, material)
    kappa = np.asarray(kappa, dtype=float)
    h_m = thickness_mm * 1e-3 / 2
    cT = material.c_T
    with np.errstate(divide="ignore", invalid="ignore"):
        wavelength = np.where(kappa > 0, 2 * math.pi * (h_m * 1e3) / kappa, np.inf)
        phase = {lab: np.where(kappa > 0, w / kappa, np.nan) * cT for lab, w in omega.items()}
    freq = {lab: w * cT / (2 * math.pi * h_m) * 1e-3 for lab, w in omega.items()}
    fd = {lab: fd_mhz_mm(w, material) for lab, w in omega.items()}
    grp = {lab: g * cT for lab, g in (group or {}).items()}
    return PhysicalBranches(material, float(thickness_mm), freq, fd, phase, grp, wavelength)



def frequency_khz(Omega, material: Material, thickness_mm: float):
    """:math:`f = \\Omega c_T / (2\\pi h)` in kHz for a plate of thickness d = 2h (mm)."""
    return np.asarray(Omega, dtype=float) * material.c_T / (math.pi * thickness_mm)


def zgv_in_units(points, material: Material, thickness_mm: float) -> list[dict]:
    """Zero-group-velocity points (label, kappa, Omega) as dicts in the practitioner's units:
    ``mode``, ``f [kHz]``, ``fd [MHz mm]``, ``c_p [m/s]``, ``wavelength [mm]``.

    >>> from dispersion.continuum.velocities import ZGVPoint
    >>> zgv_in_units([ZGVPoint("S1", 1.0, 2.0)], ALUMINIUM, 1.0)[0]["c_p [m/s]"]
    6260.0
    """
    out = []
    for p in points:
        f = float(frequency_khz(p.omega, material, thickness_mm))
        out.append({"mode": p.label, "f [kHz]": f, "fd [MHz mm]": f * thickness_mm * 1e-3,
                    "c_p [m/s]": p.omega / p.kappa * material.c_T,
                    "wavelength [mm]": math.pi * thickness_mm / p.kappa})
    return out
