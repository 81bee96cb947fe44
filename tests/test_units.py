"""Physical units: aluminium read like the Dispersion Calculator, checked by closed forms."""
from __future__ import annotations

import math

import numpy as np
import pytest

from dispersion.errors import InputError
from dispersion.continuum.exact_branches import trace_branches
from dispersion.answers.units import (
    ALUMINIUM,
    Material,
    fd_mhz_mm,
    material_from_moduli,
    physical_branches,
    rayleigh_speed,
)
from dispersion.continuum.velocities import exact_velocities

AL = ALUMINIUM  # c_L = 6320, c_T = 3130 m/s (issue 10)


def _al_branches(kappa, omega_max):
    ex = trace_branches(AL.nu, kappa, omega_max)
    v = exact_velocities(ex)
    return physical_branches(ex.kappa, ex.omega, v.group, AL, thickness_mm=1.0)


def test_cutoffs_in_frequency_thickness():
    # kappa = 0: A1 thickness shear at f d = c_T / 2, S1 at c_T, S2 (thickness stretch) at
    # c_L / 2 (Rose 2004 ch. 8; the Dispersion Calculator's aluminium cut-offs)
    pb = _al_branches([0.0], 4.0)
    assert pb.fd["A1"][0] == pytest.approx(AL.c_T / 2 * 1e-3, rel=1e-14)
    assert pb.fd["S1"][0] == pytest.approx(AL.c_T * 1e-3, rel=1e-14)
    assert pb.fd["S2"][0] == pytest.approx(AL.c_L / 2 * 1e-3, rel=1e-14)


def test_low_and_high_frequency_speeds():
    # S0 at f d -> 0: plate speed 2 c_T sqrt(1 - c_T^2/c_L^2) = sqrt(E / (rho (1 - nu^2)));
    # A0 and S0 at large f d: Rayleigh speed from the cubic (Viktorov 1967)
    pb = _al_branches([1e-6], 1.0)
    assert pb.phase["S0"][0] == pytest.approx(AL.plate_velocity, rel=1e-12)
    assert pb.group["S0"][0] == pytest.approx(AL.plate_velocity, rel=1e-12)
    E = 2 * AL.rho * AL.c_T**2 * (1 + AL.nu)
    assert AL.plate_velocity == pytest.approx(math.sqrt(E / (AL.rho * (1 - AL.nu**2))), rel=1e-14)
    far = _al_branches([30.0], 28.5)
    for label in ("S0", "A0"):
        assert far.phase[label][0] == pytest.approx(rayleigh_speed(AL), rel=1e-7)
    # the textbook approximation c_R ~ c_T (0.862 + 1.14 nu) / (1 + nu) (Viktorov) to 0.5 %
    approx = AL.c_T * (0.862 + 1.14 * AL.nu) / (1 + AL.nu)
    assert rayleigh_speed(AL) == pytest.approx(approx, rel=5e-3)


def test_wavelength_and_frequency_agree():
    # c_p = f lambda for every branch point
    pb = _al_branches(np.array([0.5, 1.0, 2.0]), 6.0)
    for label, f_khz in pb.frequency.items():
        ok = np.isfinite(f_khz)
        lhs = pb.phase[label][ok]
        rhs = f_khz[ok] * 1e3 * pb.wavelength[ok] * 1e-3
        assert np.allclose(lhs, rhs, rtol=1e-13)
    assert fd_mhz_mm(math.pi, AL) == pytest.approx(AL.c_T * 1e-3)


def test_material_from_moduli_round_trip():
    m = material_from_moduli(70e9, 0.33, 2700.0)
    assert m.nu == pytest.approx(0.33, rel=1e-13)
    assert 2 * m.rho * m.c_T**2 * (1 + m.nu) == pytest.approx(70e9, rel=1e-13)


@pytest.mark.parametrize("kwargs", [{"c_L": 3000.0, "c_T": 3130.0}, {"c_L": 6320.0, "c_T": -1.0}])
def test_bad_material(kwargs):
    with pytest.raises(InputError):
        Material(**kwargs)


def test_bad_thickness():
    with pytest.raises(InputError):
        physical_branches([1.0], {"S0": np.array([1.0])}, None, AL, thickness_mm=0.0)
