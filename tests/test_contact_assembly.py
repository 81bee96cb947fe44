"""St.Venant-Kirchhoff internal force, tangent, energy and ring mass variants."""
from __future__ import annotations

import numpy as np
import pytest

from dispersion.contact.assembly import (
    discretize,
    internal_force,
    ring_mass,
    ring_redistribution,
    strain_energy,
)
from dispersion.contact.material import StVenantKirchhoff
from dispersion.splines.nurbs import quarter_ring
from dispersion.errors import InputError


@pytest.fixture(scope="module")
def setup():
    ring = quarter_ring(0.9, 1.0, 4, 2, theta0=0.4)
    return ring, discretize(ring), StVenantKirchhoff(1.0e5, 0.3)


def test_plane_stress_uniaxial_closed_form():
    # small uniaxial plane-stress strain E = diag(e, -nu e): S11 = E e, S22 = 0 (Hooke)
    mat = StVenantKirchhoff(2.0, 0.25)
    S = mat.stress(np.diag([1e-3, -0.25e-3]))
    assert np.allclose(S, np.diag([2e-3, 0.0]), atol=1e-15)


def test_tangent_matches_finite_differences(setup):
    _, disc, mat = setup
    rng = np.random.default_rng(0)
    u = 0.03 * rng.standard_normal(disc.n_dofs)
    _, K = internal_force(disc, mat, u)
    v = rng.standard_normal(disc.n_dofs)
    h = 1e-6
    fd = (internal_force(disc, mat, u + h * v, False)
          - internal_force(disc, mat, u - h * v, False)) / (2 * h)
    assert np.abs(fd - K @ v).max() < 1e-6 * np.abs(fd).max()
    assert abs(K - K.T).max() < 1e-9 * abs(K).max()


def test_internal_force_is_energy_gradient(setup):
    _, disc, mat = setup
    rng = np.random.default_rng(1)
    u, v = 0.03 * rng.standard_normal((2, disc.n_dofs))
    h = 1e-6
    dW = (strain_energy(disc, mat, u + h * v) - strain_energy(disc, mat, u - h * v)) / (2 * h)
    f = internal_force(disc, mat, u, tangent=False)
    assert abs(dW - f @ v) < 1e-6 * abs(dW)


def test_rigid_rotation_is_stress_free(setup):
    # SVK is frame invariant: a finite rigid rotation gives E = 0, so f_int = 0 and W = 0
    ring, disc, mat = setup
    th = 0.9
    Q = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    u = (ring.points @ Q.T - ring.points).ravel()
    f, _ = internal_force(disc, mat, u)
    assert np.abs(f).max() < 1e-8 * mat.E
    assert strain_energy(disc, mat, u) < 1e-20 * mat.E


@pytest.mark.parametrize("variant", ["consistent", "lumped", "singular", "singular-lumped"])
def test_mass_symmetric_psd_and_translational_mass(setup, variant):
    _, disc, _ = setup
    rho = 1000.0
    M = ring_mass(disc, rho, variant).toarray()
    assert np.allclose(M, M.T)
    assert np.linalg.eigvalsh(M).min() > -1e-10 * np.abs(M).max()
    ex = np.zeros(disc.n_dofs)
    ex[0::2] = 1.0  # rigid translation in x: kinetic mass = rho * area (paper sec. 1.1)
    assert np.isclose(ex @ M @ ex, rho * disc.wdet.sum(), rtol=1e-12)


def test_singular_mass_has_massless_outer_surface(setup):
    ring, disc, _ = setup
    M = ring_mass(disc, 1.0, "singular").toarray()
    outer = np.concatenate([2 * ring.outer_indices(), 2 * ring.outer_indices() + 1])
    assert np.abs(M[outer]).max() == 0 and np.abs(M[:, outer]).max() == 0
    # rank = 2 x number of non-contact control points
    assert np.linalg.matrix_rank(M) == 2 * (ring.n_points - ring.n_xi)


def test_redistribution_weight_outside_unit_interval_rejected(setup):
    ring, _, _ = setup
    with pytest.raises(InputError, match=r"gamma_s must lie in \[0, 1\]"):
        ring_redistribution(ring, gamma_s=1.5)
    with pytest.raises(InputError):
        ring_redistribution(ring, gamma_s=-0.2)
