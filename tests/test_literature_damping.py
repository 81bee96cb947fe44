"""Damped plates against the published decay per wavelength of Cremer and Heckl.

A wave in a solid whose moduli carry one loss factor eta, C (1 - i eta) (the hysteretic law
of ``--damping``), loses per wavelength, for small eta, **27.3 eta dB** when it is
non-dispersive (longitudinal, quasi-longitudinal, shear and torsional waves) and **13.6 eta dB**
when it is a bending wave, whose wavenumber goes as the fourth root of the stiffness:
L. Cremer, M. Heckl, B. A. T. Petersson, *Structure-Borne Sound*, 3rd ed., Springer 2005,
ch. 3 (damping; the decay per wavelength D = 27.3 eta dB for quasi-longitudinal waves, 13.6
eta dB for bending waves). They are the values 20 log10(e) pi eta = 27.29 eta and half of it
= 13.64 eta, printed to three digits. A plate's S0 and SH0 modes are those waves and its A0 the
bending wave in the low-frequency limit, for one layer or a stack of any laws with the same
eta.

The window is fixed before looking (the rule of the developers' guide for a leading term):
the rule is the leading term in eta and in kh; the next terms are relative O(eta^2), and
O((kh)^2) with a coefficient below 1 for an isotropic plate's A0 (the shear and rotary
inertia term of Mindlin's plate: omega^2 = omega_K^2 (1 - beta (kh)^2), beta = (1 + 2 /
(kappa_s^2 (1 - nu))) / 12 with kappa_s^2 = pi^2/12, changes c_p/c_g, and so the decay per
wavelength, by beta (kh)^2 / 2, at most 0.23 (kh)^2 for nu <= 0.45) and far below it for S0
(and 0 for SH0, non-dispersive). So each measured decay per wavelength over eta must lie within
half a unit of the printed last digit (0.05) plus (kh)^2 times the printed value of the
published number. The laminate's A0 is left out: its low transverse shear modulus makes that
coefficient about 3 (E1 / G13 over 10), outside the stated window.
"""
from __future__ import annotations

import math

import pytest

from dispersion.api import layered_lamb_modes, layup

PUBLISHED = {"S0": 27.3, "SH0": 27.3, "A0": 13.6}
PRINTED_HALF_UNIT = 0.05


def _check(text: str, eta: float, f_khz: float, modes=("S0", "SH0", "A0"), **kw):
    plate = layup(text, damping=eta, **kw)
    table = layered_lamb_modes(plate, frequency_khz=f_khz)
    assert not table.failures, table.failures
    rows = {r["mode"]: r for r in table.rows()}
    h_mm = sum(layer.thickness_mm for layer in plate.layers)
    for mode in modes:
        r = rows[mode]
        wavelength_m = 2 * math.pi / r["k [rad/mm]"] / 1e3
        per_wavelength = r["attenuation [dB/m]"] * wavelength_m / eta
        kh = r["k [rad/mm]"] * h_mm
        tol = PRINTED_HALF_UNIT + kh**2 * PUBLISHED[mode]
        assert abs(per_wavelength - PUBLISHED[mode]) <= tol, (text, eta, f_khz, mode,
                                                              per_wavelength, tol)


def test_steel_plate_decays_as_cremer_and_heckl_print():
    _check("steel:1", 1e-3, 5.0)


@pytest.mark.slow
@pytest.mark.parametrize("material", ["aluminium", "steel", "copper", "titanium", "glass",
                                      "pmma", "magnesium", "epoxy"])
@pytest.mark.parametrize("eta", [1e-3, 1e-2])
def test_every_isotropic_material_decays_as_published(material, eta):
    _check(f"{material}:1", eta, 5.0)


@pytest.mark.slow
@pytest.mark.parametrize("eta", [1e-3, 1e-2])
def test_a_damped_laminate_and_a_bilayer_decay_as_published(eta):
    _check("[0/90]s", eta, 5.0, modes=("S0", "SH0"), ply="T800/913", ply_thickness_mm=0.125)
