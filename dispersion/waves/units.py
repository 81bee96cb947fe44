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
from typing import TYPE_CHECKING


from dispersion.errors import InputError, check_positive

if TYPE_CHECKING:  # numpy is imported where used: the CLI lists the materials without it
    import numpy as np

__all__ = [
    "ALUMINIUM",
    "MATERIALS",
    "Material",
    "PhysicalBranches",
    "fd_mhz_mm",
    "material_from_moduli",
    "physical_branches",
    "rayleigh_speed",
]


@dataclass(frozen=True)
class Material:
    """An isotropic material by its bulk wave speeds (m/s) and, optionally, density (kg/m^3)."""

    c_L: float
    c_T: float
    rho: float | None = None
    name: str = "custom"

    def __post_init__(self):
        check_positive("c_T", self.c_T)
        check_positive("c_L", self.c_L)
        if not self.c_L > self.c_T * math.sqrt(4 / 3):  # nu > -1
            raise InputError(f"c_L must exceed c_T sqrt(4/3) (nu > -1), got c_L={self.c_L}, "
                             f"c_T={self.c_T}")

    @property
    def nu(self) -> float:
        """Poisson's ratio :math:`(c_L^2 - 2 c_T^2) / (2 (c_L^2 - c_T^2))`."""
        L2, T2 = self.c_L**2, self.c_T**2
        return (L2 - 2 * T2) / (2 * (L2 - T2))

    @property
    def plate_velocity(self) -> float:
        """S0 speed at :math:`fd \\to 0`: :math:`c_{pl} = 2 c_T \\sqrt{1 - c_T^2/c_L^2}` (m/s)."""
        return 2 * self.c_T * math.sqrt(1 - (self.c_T / self.c_L) ** 2)

    def as_dict(self) -> dict:
        """Inputs as plain data (for CSV headers and JSON)."""
        return {"name": self.name, "c_L [m/s]": self.c_L, "c_T [m/s]": self.c_T,
                "rho [kg/m^3]": self.rho, "nu": self.nu}


def material_from_moduli(E: float, nu: float, rho: float, name: str = "custom") -> Material:
    """Material from Young's modulus E (Pa), Poisson's ratio and density (kg/m^3).

    :math:`c_T^2 = E / (2 \\rho (1+\\nu))`, :math:`c_L^2 = E (1-\\nu) / (\\rho (1+\\nu)(1-2\\nu))`.

    >>> m = material_from_moduli(70e9, 0.33, 2700.0)
    >>> round(m.c_T), round(m.nu, 12)
    (3122, 0.33)
    """
    check_positive("E", E)
    check_positive("rho", rho)
    if not -1 < nu < 0.5:
        raise InputError(f"nu must be in (-1, 0.5), got {nu}")
    c_T = math.sqrt(E / (2 * rho * (1 + nu)))
    c_L = math.sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)))
    return Material(c_L, c_T, rho, name)


#: The Dispersion Calculator's aluminium example (bulk speeds as issue 10 quotes them).
ALUMINIUM = Material(c_L=6320.0, c_T=3130.0, rho=2700.0, name="aluminium")
MATERIALS = {"aluminium": ALUMINIUM}


def rayleigh_speed(material: Material) -> float:
    """Rayleigh wave speed (m/s), the root :math:`x = (c_R/c_T)^2 \\in (0, 1)` of the cubic

    .. math:: x^3 - 8 x^2 + 8 (3 - 2\\eta) x - 16 (1 - \\eta) = 0, \\quad \\eta = (c_T/c_L)^2

    (Viktorov 1967; Rahman and Barber 1995 give its root in closed form).

    >>> round(rayleigh_speed(ALUMINIUM), 1)
    2920.8
    """
    import numpy as np

    eta = (material.c_T / material.c_L) ** 2
    roots = np.roots([1.0, -8.0, 8.0 * (3 - 2 * eta), -16.0 * (1 - eta)])
    real = [r.real for r in roots if abs(r.imag) < 1e-12 and 0 < r.real < 1]
    return material.c_T * math.sqrt(min(real))


def fd_mhz_mm(Omega, material: Material):
    """Frequency-thickness :math:`f d = \\Omega c_T / \\pi` in MHz mm (Hz m is 1e-3 MHz mm)."""
    import numpy as np

    return np.asarray(Omega, dtype=float) * material.c_T / math.pi * 1e-3


@dataclass(frozen=True)
class PhysicalBranches:
    """Branches in physical units on one kappa grid (arrays per label; NaN where absent).

    ``frequency`` in kHz, ``fd`` in MHz mm, ``phase``/``group`` in m/s, ``wavelength`` in mm.
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


def physical_branches(kappa, omega: dict, group: dict | None, material: Material,
                      thickness_mm: float) -> PhysicalBranches:
    """Dimensionless branches (``omega[label]``, ``group[label]`` = dOmega/dkappa) in units.

    >>> import numpy as np
    >>> import numpy as np
    >>> pb = physical_branches(np.array([1.0]), {"S0": np.array([1.6])}, None, ALUMINIUM, 1.0)
    >>> round(float(pb.fd["S0"][0]), 4), round(float(pb.wavelength[0]), 4)   # h = 0.5 mm
    (1.5941, 3.1416)
    """
    import numpy as np

    check_positive("thickness", thickness_mm)
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
