"""Bar hitting a rigid wall: exact solution (Graff, Wave Motion in Elastic Solids, sec. 1.2).

Exact: contact lasts 2L/c, contact stress rho c v0, rebound at v0, energy conserved.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from dispersion.contact.bar import MAX_STEPS, Bar, assemble_bar, check_steps, simulate_bar
from dispersion.contact.newmark import critical_step, integrate
from dispersion.contact.newmark_scheme import Newmark
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


@pytest.mark.parametrize("kwargs, name", [
    ({"n_elements": 0}, "n_elements"),
    ({"clamped": ("left",), "contact": "left"}, "clamped"),
    ({"contact": "middle"}, "contact"),
    ({"gap": float("inf")}, "gap"),
    ({"E": -1.0}, "E"),
    ({"p": 0}, "p"),
])
def test_bad_bar_rejected_naming_the_parameter(kwargs, name):
    with pytest.raises(InputError, match=name):
        Bar(**kwargs)


def test_explicit_step_above_the_limit_is_refused():
    # P1 lumped bar: omega_max = 2 c / h (Hughes, The FEM, sec. 9.3), limit dt = h / c
    model = assemble_bar(Bar(10, 1, mass="lumped"))
    prob = model.problem
    assert np.isclose(critical_step(prob), 0.1, rtol=1e-12)
    with pytest.raises(InputError, match="dt"):
        integrate(prob, np.zeros(prob.n), -np.ones(prob.n), 0.11, 3, Newmark(beta=0.0))


def test_body_force_energy_is_conserved_in_free_flight():
    # clamped-free bar under a uniform body force, no contact reached (gap 1 m):
    # trapezoidal rule conserves kinetic + strain - f_ext . u of a linear system exactly
    model = assemble_bar(Bar(8, 2, mass="consistent", clamped=("right",), gap=1.0,
                          body_force=-0.5))
    prob = model.problem
    hist = integrate(prob, np.zeros(prob.n), np.zeros(prob.n), 0.01, 300)
    assert max(hist.strain) > 1e-3  # the load does work
    assert np.allclose(hist.total, hist.total[0], atol=1e-12)


def test_right_end_contact_mirrors_left_end_contact():
    # the bar moving right into a wall at x = L is the mirror image of the standard test
    left = assemble_bar(Bar(10, 2, mass="singular")).problem
    right = assemble_bar(Bar(10, 2, mass="singular", contact="right")).problem
    a = integrate(left, np.zeros(left.n), -np.ones(left.n), 0.02, 100)
    b = integrate(right, np.zeros(right.n), np.ones(right.n), 0.02, 100)
    assert np.allclose(a.contact_force, b.contact_force, rtol=1e-10, atol=1e-12)


def test_linear_fast_path_equals_the_newton_path():
    # the factorized linear step (Schur complement on the contact DOF) and the general
    # semismooth Newton solve the same step equations
    prob = assemble_bar(Bar(10, 2, mass="lumped")).problem
    slow = replace(prob, K=None)
    args = (np.zeros(prob.n), -np.ones(prob.n), 0.02, 60)
    a, b = integrate(prob, *args), integrate(slow, *args)
    assert np.allclose(a.contact_force, b.contact_force, rtol=1e-7, atol=1e-9)
    assert np.allclose(a.total, b.total, rtol=1e-9)


def test_courant_and_step_count_are_refused_up_front():
    with pytest.raises(InputError, match=r"courant must lie in \(0, inf\)"):
        simulate_bar(courant=0.0)
    with pytest.raises(InputError, match=r"/ dt must be <= 1000000 steps"):
        simulate_bar(dt=1e-12)
    assert check_steps(float(MAX_STEPS), 1.0) == MAX_STEPS
    with pytest.raises(InputError, match="t_end / dt"):
        check_steps(float(MAX_STEPS) * 1.01, 1.0)
