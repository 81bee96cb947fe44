"""Newmark stepping with contact: energy in free flight, non-convergence, input checks."""
from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from dispersion.contact.bar import bar_problem
from dispersion.contact.newmark import ContactProblem, Newmark, integrate
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


def test_non_convergence_raises():
    prob = bar_problem(10, mass="lumped")
    with pytest.raises(ConvergenceError, match="Newton did not reach"):
        integrate(prob, np.zeros(prob.n), -np.ones(prob.n), 0.05, 3, Newmark(max_iter=1))


def test_bad_parameters_rejected():
    with pytest.raises(InputError, match="scheme"):
        Newmark(scheme="explicit")
    with pytest.raises(InputError, match="beta"):
        Newmark(beta=0.0)
    with pytest.raises(InputError, match="dt"):
        integrate(_oscillator(), np.zeros(1), np.zeros(1), -1.0, 3)


def test_dense_baseline_gives_the_same_steps():
    prob = bar_problem(10, mass="singular")
    args = (prob, np.zeros(prob.n), -np.ones(prob.n), 0.02, 40)
    a = integrate(*args, Newmark(solver="sparse")).arrays()
    b = integrate(*args, Newmark(solver="dense")).arrays()
    assert np.allclose(a["contact_force"], b["contact_force"], rtol=1e-8, atol=1e-10)
