"""Bar hitting a rigid wall: exact solution (Graff, Wave Motion in Elastic Solids, sec. 1.2).

Exact: contact lasts 2L/c, contact stress rho c v0, rebound at v0, energy conserved.
"""
from __future__ import annotations

import numpy as np
import pytest

from dispersion.contact.bar import simulate_bar
from dispersion.errors import InputError


@pytest.fixture(scope="module")
def singular_runs():
    return {n: simulate_bar(n, mass="singular", courant=0.5) for n in (10, 20, 40)}


def test_singular_bar_matches_exact_solution(singular_runs):
    res = singular_runs[40]
    m = res.metrics
    step = m["dt"] / res.exact["duration"]
    assert abs(m["duration_error"]) <= 1.01 * step  # within one time step of 2L/c
    assert abs(m["stress_error"]) < 1e-3  # plateau rho c v0
    assert m["force_oscillation"] < 0.02
    assert abs(m["rebound_error"]) < 0.02
    assert abs(m["energy_change_percent"]) < 0.05
    assert not m["in_contact_at_end"]


def test_singular_bar_errors_fall_with_refinement(singular_runs):
    energy = [abs(singular_runs[n].metrics["energy_change_percent"]) for n in (10, 20, 40)]
    rebound = [abs(singular_runs[n].metrics["rebound_error"]) for n in (10, 20, 40)]
    assert energy[0] > energy[1] > energy[2]
    assert rebound[0] > rebound[1] > rebound[2]
    # measured energy errors fall at least linearly in h (dt = h / 2c)
    assert np.log2(energy[0] / energy[2]) / 2 > 1.0


@pytest.mark.parametrize("mass", ["lumped", "consistent"])
def test_regular_masses_oscillate_and_kane_dissipates(mass):
    m = simulate_bar(20, mass=mass, courant=0.5).metrics
    assert m["force_oscillation"] > 0.3  # lumped/consistent: contact-force oscillations
    assert m["energy_change_percent"] < 0  # Kane et al. 1999: dissipative for regular mass
    assert abs(m["stress_error"]) < 0.05  # but the mean stress is still rho c v0


def test_standard_newmark_gains_energy_with_regular_mass():
    # without the contact modification the impact pumps energy into the bar
    m = simulate_bar(20, mass="lumped", courant=0.5, scheme="standard").metrics
    assert m["energy_change_percent"] > 10


def test_singular_mass_makes_the_schemes_coincide():
    # contact DOFs without inertia: the predictor's contact term vanishes (paper eqs 11-12)
    a = simulate_bar(20, mass="singular", scheme="standard").history.arrays()
    b = simulate_bar(20, mass="singular", scheme="kane").history.arrays()
    assert np.allclose(a["contact_force"], b["contact_force"], rtol=1e-9, atol=1e-12)


def test_bad_mass_rejected():
    with pytest.raises(InputError, match="mass"):
        simulate_bar(10, mass="heavy")
