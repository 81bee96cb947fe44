"""Newmark stepping with contact: energy in free flight, non-convergence, input checks."""
from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from dataclasses import replace

from dispersion.contact.bar import Bar, assemble_bar, bar_problem
from dispersion.contact.contact_problem import ContactProblem
from dispersion.contact.newmark import critical_step, integrate
from dispersion.contact.newmark_scheme import Newmark
from dispersion.errors import ConvergenceError, InputError


def _oscillator(k=4.0, m=1.0, wall=None):
    K = sp.csr_matrix([[k]])
    G = sp.csr_matrix([[1.0]]) if wall is not None else sp.csr_matrix((0, 1))
    g0 = np.array([wall]) if wall is not None else np.zeros(0)
    return ContactProblem(sp.csr_matrix([[m]]), lambda u: (K @ u, K), G, g0,
                          lambda u: 0.5 * k * float(u @ u))


@pytest.mark.parametrize("scheme", ["kane", "standard"])
def test_trapezoidal_rule_conserves_energy_without_contact(scheme):
    # beta = 1/4, gamma = 1/2 conserves the energy of a linear system exactly (Newmark 1959)
    hist = integrate(_oscillator(), np.array([1.0]), np.zeros(1), 0.3, 200,
                     Newmark(scheme=scheme))
    assert np.allclose(hist.total, 2.0, rtol=1e-12)


def test_period_elongation_of_trapezoidal_rule():
    # trapezoidal rule: omega_h dt = 2 arctan(omega dt / 2) (Hughes, The FEM, sec. 9.3)
    dt, w = 0.1, 2.0
    hist = integrate(_oscillator(), np.array([1.0]), np.zeros(1), dt, 50)
    wh = 2 * np.arctan(w * dt / 2) / dt
    t = np.asarray(hist.t)
    k = np.asarray(hist.strain)  # 0.5 k u^2 with u = cos(wh t)
    assert np.allclose(k, 2.0 * np.cos(wh * t) ** 2, atol=1e-10)


def test_kane_contact_on_a_rigid_wall_is_dissipative():
    # Kane et al. 1999: the contact-modified scheme never creates energy (regular mass)
    hist = integrate(_oscillator(wall=0.5), np.zeros(1), np.array([-2.0]), 0.05, 200)
    assert hist.total.max() <= hist.total[0] * (1 + 1e-12)
    assert min(hist.gap_min) > -1e-12  # multipliers enforce the gap exactly


def _hardening(k=1.0):
    # nonlinear spring f = k (u + u^3): Newton needs several iterations from a large amplitude
    def internal(u):
        return k * (u + u**3), sp.csr_matrix([[k * (1 + 3 * u[0] ** 2)]])
    return ContactProblem(sp.csr_matrix([[1.0]]), internal, sp.csr_matrix((0, 1)), np.zeros(0),
                          lambda u: k * float(0.5 * u[0] ** 2 + 0.25 * u[0] ** 4))


def test_non_convergence_raises():
    with pytest.raises(ConvergenceError, match="Newton did not reach"):
        integrate(_hardening(), np.array([3.0]), np.zeros(1), 0.5, 3, Newmark(max_iter=1))


def test_bad_parameters_rejected():
    with pytest.raises(InputError, match="scheme"):
        Newmark(scheme="explicit")
    with pytest.raises(InputError, match="beta"):
        Newmark(beta=-0.1)
    with pytest.raises(InputError, match="beta = 0"):
        Newmark(beta=0.0, scheme="standard")
    with pytest.raises(InputError, match="dt"):
        integrate(_oscillator(), np.zeros(1), np.zeros(1), -1.0, 3)


def test_initial_penetration_refused():
    with pytest.raises(InputError, match="u0 penetrates"):
        integrate(_oscillator(wall=0.5), np.array([-1.0]), np.zeros(1), 0.1, 3)


@pytest.mark.parametrize("solver", ["sparse", "dense"])
def test_solvers_give_the_same_steps(solver):
    prob = replace(bar_problem(10, mass="singular"), K=None)  # through Newton
    args = (prob, np.zeros(prob.n), -np.ones(prob.n), 0.02, 40)
    a = integrate(*args, Newmark(solver="auto")).arrays()
    b = integrate(*args, Newmark(solver=solver)).arrays()
    assert np.allclose(a["contact_force"], b["contact_force"], rtol=1e-7, atol=1e-9)


def test_nonlinear_trapezoidal_energy_error_falls_like_dt_squared():
    # the trapezoidal rule does not conserve the energy of a nonlinear spring exactly; its
    # energy error is second order (Hughes, The FEM, sec. 9.3): check over 4 halvings
    errs = []
    for dt in (0.2, 0.1, 0.05, 0.025):
        h = integrate(_hardening(), np.array([1.0]), np.zeros(1), dt, round(4.0 / dt))
        errs.append(np.abs(h.total - h.total[0]).max())
    assert all(a > b for a, b in zip(errs, errs[1:]))
    rate = np.polyfit(np.log([0.2, 0.1, 0.05, 0.025]), np.log(errs), 1)[0]
    assert 1.7 < rate < 2.5


def test_central_difference_phase_is_exact_in_closed_form():
    # central differences on u'' = -w^2 u from (1, 0): u_n = cos(w_h n dt) exactly with
    # w_h dt = 2 arcsin(w dt / 2) (Hughes, The FEM, sec. 9.3)
    dt, w = 0.3, 2.0
    hist = integrate(_oscillator(), np.array([1.0]), np.zeros(1), dt, 60,
                     Newmark(beta=0.0), keep_states=True)
    wh = 2 * np.arcsin(w * dt / 2) / dt
    u = np.array([s.u[0] for s in hist.states])
    assert np.allclose(u, np.cos(wh * np.asarray(hist.t)), atol=1e-12)


def test_critical_step_is_two_over_omega_max():
    assert np.isclose(critical_step(_oscillator(k=4.0)), 1.0)
    with pytest.raises(InputError, match="stability limit"):
        integrate(_oscillator(k=4.0), np.ones(1), np.zeros(1), 1.01, 3, Newmark(beta=0.0))


def test_consistent_state_removes_the_first_element_strain_energy():
    # P1 bar, singular mass, u0 = (1 - x)/2: the massless end DOF relaxes to u_1, removing
    # the first element's strain energy h (1/2)^2 / 2 = h/8 (issue 12, GetFEM's 1D demo)
    model = assemble_bar(Bar(20, 1, mass="singular", clamped=("right",)))
    prob = model.problem
    u0 = model.coefficients(lambda x: 0.5 * (1 - x))
    hist = integrate(prob, u0, np.zeros(prob.n), 0.002, 5)
    assert np.isclose(hist.initial_energy_change, -0.05 / 8, rtol=1e-10)
    assert np.allclose(hist.total, hist.total[0], rtol=1e-12)  # no first-step loss
    raw = integrate(prob, u0, np.zeros(prob.n), 0.002, 5, consistent=False)
    assert raw.initial_energy_change == 0
    # without it the first step loses about the same (plus what the first step moves)
    assert np.isclose(raw.total[1] - raw.total[0], -0.05 / 8, rtol=1e-2)
